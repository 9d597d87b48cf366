!> Validation of &initial (docs/input.md): the coefficients, steps and tables finite and not
!> too large, steps inside [0, 1], tables covering the rod, and the boundary values of each
!> profile those of its finite element space, (2.13) and (2.15), and u0(1) <= g; evaluated by
!> initial_data_m's profile, the function that initialises the nodes. validate_m calls it in
!> its order of the groups; the first failure stops with EXIT_INPUT, naming the variable.
!> require_real is the one check of a real input's range, validate_m's too.
module validate_initial_m
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use kinds_m, only: dp
    use errors_m, only: fatal, EXIT_INPUT
    use config_m, only: initial_t
    use strings_m, only: format_real, int_str
    use initial_data_m, only: profile
    implicit none
    private
    public :: validate_initial, require_real

    !> Boundary values of the initial data must vanish to this tolerance times (1 + sum |coef|).
    real(dp), parameter :: BOUNDARY_TOL = 1.0e-12_dp
    !> Every real input has magnitude at most MAX_MAGNITUDE, and the coefficients that
    !> divide (rho, alpha, c, r, hbar weigh the energy; 1/eps; t_end/dt) are at least
    !> MIN_POSITIVE. Why: with every input in this range no intermediate quantity of the
    !> scheme can overflow. The initial energy is at most ~1e93, the matrix entries
    !> (largest dt**2 alpha / h) at most ~1e97, and the scheme never lets the energy grow
    !> (Corollary 6.2), so every field stays far below the double-precision limit ~1.8e308.
    !> Outside it a run would overflow (Inf energy, NaN fields) or trap in a Debug build.
    real(dp), parameter :: MAX_MAGNITUDE = 1.0e30_dp
    real(dp), parameter :: MIN_POSITIVE = 1.0e-30_dp
    !> The bounds of require_real
    integer, parameter, public :: DATUM = 0, NONNEGATIVE = 1, POSITIVE = 2, DIVISOR = 3

contains

    !> Each profile of init (validate_profile) in turn, and u0(1) <= g: u0, u1, q0, eta0 in S_h
    !> vanish at x = 0, theta0, P0 in V_h at x = 1 (the rod's end, of length 1, or ell in m
    !> with &material).
    subroutine validate_initial(init, g, length)
        type(initial_t), intent(in) :: init
        real(dp), intent(in) :: g, length

        call validate_profile('u0', init%u0_poly, init%u0_file, length, 0.0_dp, 'u(0,t) = 0, (2.13)', &
                              table=init%u0_table, g=g)
        call validate_profile('u1', init%u1_poly, init%u1_file, length, 0.0_dp, &
                              'v = u_t vanishes where u(0,t) = 0, (2.13)', table=init%u1_table)
        call validate_profile('theta0', init%theta0_poly, init%theta0_file, length, 1.0_dp, &
                              'theta(1,t) = 0, (2.15)', init%theta0_step, init%theta0_table)
        call validate_profile('p0', init%p0_poly, init%p0_file, length, 1.0_dp, 'P(1,t) = 0, (2.15)', &
                              init%p0_step, init%p0_table)
        call validate_profile('q0', init%q0_poly, init%q0_file, length, 0.0_dp, 'q(0,t) = 0, (2.15)', &
                              table=init%q0_table)
        call validate_profile('eta0', init%eta0_poly, init%eta0_file, length, 0.0_dp, 'eta(0,t) = 0, (2.15)', &
                              table=init%eta0_table)
    end subroutine validate_initial

    !> The initial profile `name`: coefficients finite, its step and its table (of `file`)
    !> inside the rod [0, length], and its value at the boundary point x of its space 0 (the
    !> condition `why`); with g (u0), its value at the contact end at most g. The step's end
    !> and the table's positions are taken over length, as fractions of the rod, as the
    !> profiles take them (material_m's nondimensionalise divides them so for a run).
    subroutine validate_profile(name, poly, file, length, x, why, step, table, g)
        character(len=*), intent(in) :: name, file, why
        real(dp), intent(in) :: poly(0:), length, x
        real(dp), intent(in), optional :: step(2), table(:, :), g
        real(dp), allocatable :: rod_step(:), rod_table(:, :)
        real(dp) :: end_value
        integer :: k

        do k = 0, ubound(poly, 1)
            call require_real(poly(k), 'initial.' // name // '_poly', DATUM, what=format_real(poly(k)) // &
                              ' as coefficient of x**' // int_str(k) // '; every coefficient')
        end do
        if (present(step)) then
            call require_step(step, 'initial.' // name // '_step', length)
            allocate (rod_step, source=[step(1), step(2) / length])
        end if
        if (present(table)) then
            call require_table(table, 'initial.' // name // '_file', file, length)
            allocate (rod_table, source=table)
            rod_table(:, 1) = table(:, 1) / length
        end if
        call require_boundary_zero(name, poly, x, why, rod_step, rod_table)
        if (.not. present(g)) return
        end_value = profile(poly=poly, x=1.0_dp, table=rod_table)
        if (end_value > g + BOUNDARY_TOL * (1.0_dp + sum(abs(poly)))) call fatal(EXIT_INPUT, &
            'initial.' // name // trim(merge('_file', '_poly', present(table))), 'got ' // name // '(1) = ' // &
            format_real(end_value) // ' > g = ' // format_real(g) // &
            '; the initial displacement must satisfy the contact constraint u0(1) <= g')
    end subroutine validate_profile

    !> A step (amplitude, x_end): finite amplitude, 0 <= x_end <= length (1, or ell in m).
    subroutine require_step(step, where, length)
        real(dp), intent(in) :: step(2), length
        character(len=*), intent(in) :: where

        call require_real(step(1), where, DATUM, what='amplitude ' // format_real(step(1)) // ';')
        if (.not. ieee_is_finite(step(2))) call fatal(EXIT_INPUT, where, &
            'got x_end ' // format_real(step(2)) // '; must be a finite real number')
        if (.not. (step(2) >= 0.0_dp .and. step(2) <= length)) call fatal(EXIT_INPUT, where, 'got x_end ' // &
            format_real(step(2)) // '; the step (amplitude, x_end) adds amplitude on [0, x_end]: ' // &
            'need 0 <= x_end <= ' // format_real(length) // ' (the rod''s length: 1, or material.ell in m)')
    end subroutine require_step

    !> x finite, at most MAX_MAGNITUDE in magnitude and within bound: DATUM (no other), NONNEGATIVE
    !> (>= 0), POSITIVE (> 0), DIVISOR (>= MIN_POSITIVE: the energy or the scheme divides by it).
    !> The message: 'got <what> must be ...<note>' (what: 'x;' if not given).
    subroutine require_real(x, where, bound, note, what)
        real(dp), intent(in) :: x
        character(len=*), intent(in) :: where
        integer, intent(in) :: bound
        character(len=*), intent(in), optional :: note, what
        character(len=:), allocatable :: limit, got

        ! no comparison of a NaN: it raises the invalid exception that a Debug build traps
        if (.not. ieee_is_finite(x)) then
            limit = 'a finite real number'
        else if (abs(x) > MAX_MAGNITUDE .and. bound == DATUM) then
            limit = 'at most ' // format_real(MAX_MAGNITUDE) // &
                    ' in magnitude (larger initial data overflow double precision in the energy)'
        else if (abs(x) > MAX_MAGNITUDE) then
            limit = 'at most ' // format_real(MAX_MAGNITUDE) // &
                    ' in magnitude (larger values overflow double precision inside the scheme)'
        else if (bound == NONNEGATIVE .and. .not. x >= 0.0_dp) then
            limit = '>= 0'
        else if (bound >= POSITIVE .and. .not. x > 0.0_dp) then
            limit = '> 0'
        else if (bound == DIVISOR .and. x < MIN_POSITIVE) then
            limit = '>= ' // format_real(MIN_POSITIVE) // ' (the energy or the scheme divides by it; ' // &
                    'smaller values can make the fields overflow double precision)'
        else
            return
        end if
        got = format_real(x) // ';'
        if (present(what)) got = what
        if (present(note)) limit = limit // note
        call fatal(EXIT_INPUT, where, 'got ' // got // ' must be ' // limit)
    end subroutine require_real

    !> A table (if given) covers the rod [0, length] (to round-off), its values finite and at
    !> most MAX_MAGNITUDE in magnitude.
    subroutine require_table(table, where, file, length)
        real(dp), intent(in), optional :: table(:, :)
        character(len=*), intent(in) :: where, file
        real(dp), intent(in) :: length
        integer :: k, n

        if (.not. present(table)) return
        n = size(table, 1)
        if (table(1, 1) > BOUNDARY_TOL * length .or. table(n, 1) < (1.0_dp - BOUNDARY_TOL) * length) &
            call fatal(EXIT_INPUT, where, "got positions from " // format_real(table(1, 1)) // ' to ' // &
            format_real(table(n, 1)) // " in '" // trim(file) // "'; the table must cover the rod: first " // &
            'position <= 0, last >= ' // format_real(length) // ' (1, or material.ell in m)')
        do k = 1, n
            call require_real(table(k, 2), where, DATUM, what=format_real(table(k, 2)) // ' at position ' // &
                              format_real(table(k, 1)) // " in '" // trim(file) // "'; every value")
        end do
    end subroutine require_table

    !> The initial profile `name` (polynomial plus optional step and table) must vanish at
    !> the boundary point x of its finite element space; evaluated by the same profile()
    !> that initialises the nodes.
    subroutine require_boundary_zero(name, poly, x, why, step, table)
        character(len=*), intent(in) :: name, why
        real(dp), intent(in) :: poly(0:)
        real(dp), intent(in) :: x
        real(dp), intent(in), optional :: step(2), table(:, :)
        real(dp) :: value, scale
        character(len=:), allocatable :: where, what

        value = profile(poly=poly, x=x, step=step, table=table)
        scale = 1.0_dp + sum(abs(poly))
        if (present(step)) scale = scale + abs(step(1))
        if (present(table)) scale = scale + maxval(abs(table(:, 2)))
        if (abs(value) <= BOUNDARY_TOL * scale) return
        where = 'initial.' // name // '_poly'
        what = ''
        if (abs(value - profile(poly=poly, x=x)) > 0.0_dp) what = ' (polynomial plus step or table)'
        ! the polynomial alone is right: it is the step or the table that reaches x
        if (abs(profile(poly=poly, x=x)) <= BOUNDARY_TOL * scale) then
            where = 'initial.' // name // '_file'
            if (abs(profile(poly=poly, x=x, step=step) - profile(poly=poly, x=x)) > 0.0_dp) &
                where = 'initial.' // name // '_step'
        end if
        call fatal(EXIT_INPUT, where, 'got ' // name // '(' // format_real(x) // ') = ' // &
                   format_real(value) // what // '; must be 0 at x = ' // format_real(x) // &
                   ' (boundary condition ' // why // ')')
    end subroutine require_boundary_zero

end module validate_initial_m
