!> &material: the physical quantities of Table 1 (SI units) and the nondimensional &model
!> coefficients computed from them by (2.10)-(2.11), their check, and the one conversion of
!> a run's SI inputs to the nondimensional variables the code runs in, echoed on stdout.
module material_m
    use, intrinsic :: iso_fortran_env, only: output_unit
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use kinds_m, only: dp
    use errors_m, only: fatal, EXIT_INPUT
    use config_m, only: config_t, material_t, model_t
    use strings_m, only: format_real, quoted
    use input_vars_m, only: INPUT_VARS, input_item_t, input_item, KIND_REAL
    implicit none
    private
    public :: nondim_groups, model_from_material, check_material, nondimensionalise
    public :: si_scale_t, si_scales, time_scale, NONDIM_NAMES
    public :: BETA1, BETA2, OMEGA, DELTA, VARSIGMA, ZETA, A_CHECK, ALPHA1, ALPHA2, ALPHA3

    !> The nondimensional groups of (2.10) computed from &material (nondim_groups, whose lines
    !> are their formulas; omega is the time scale), by index: the k-th is named NONDIM_NAMES(k),
    !> in units NONDIM_UNITS(k) ('': none).
    integer, parameter :: BETA1 = 1, BETA2 = 2, OMEGA = 3, DELTA = 4, VARSIGMA = 5, ZETA = 6, &
                          A_CHECK = 7, ALPHA1 = 8, ALPHA2 = 9, ALPHA3 = 10
    character(len=*), parameter :: NONDIM_NAMES(10) = [character(len=8) :: 'beta1', 'beta2', 'omega', &
        'delta', 'varsigma', 'zeta', 'a_check', 'alpha1', 'alpha2', 'alpha3']
    character(len=*), parameter :: NONDIM_UNITS(10) = [character(len=17) :: 'kg/(m s^2 K)', 'm^2/s^2', &
        's  (t = omega t*)', '', '', '', '', '', '', '']

    !> One scale of the nondimensional variables of (2.10): a quantity in SI units is
    !> `factor` times its nondimensional value (x = ell x*, t = omega t*, ...).
    type :: si_scale_t
        character(len=24) :: name = ''    !< as fields_m's scale column
        real(dp) :: factor = 0.0_dp
        character(len=16) :: units = ''   !< SI units of factor
    end type si_scale_t

contains

    !> The scales of (2.10) for &material `mat`: x* = x/ell, t* = t/omega,
    !> theta = beta1 (T - T0)/((lambda + 2 mu) delta), P* = P/(beta2 delta),
    !> q* = omega beta1 q/(rho0 cE delta ell (lambda + 2 mu)), eta* = ell eta/(D beta2 delta);
    !> u = delta ell u* (not the paper's printed u* = delta u/ell: (2.10) needs it), the stress
    !> (lambda + 2 mu) delta / a-check, the energy ell (lambda + 2 mu) delta^2 / a-check. Why
    !> each: docs/output.md, "Scales (with `&material` only)".
    pure function si_scales(mat) result(scales)
        type(material_t), intent(in) :: mat
        type(si_scale_t) :: scales(10)
        real(dp) :: nd(size(NONDIM_NAMES))
        real(dp) :: stiffness

        nd = nondim_groups(mat)
        stiffness = mat%lambda + 2.0_dp * mat%mu
        scales(1) = si_scale_t('time', nd(OMEGA), 's')
        scales(2) = si_scale_t('position', mat%ell, 'm')
        scales(3) = si_scale_t('displacement', mat%ell * nd(DELTA), 'm')
        scales(4) = si_scale_t('velocity', mat%ell * nd(DELTA) / nd(OMEGA), 'm/s')
        scales(5) = si_scale_t('temperature', stiffness * nd(DELTA) / nd(BETA1), 'K')   ! of T - T0
        scales(6) = si_scale_t('chemical_potential', nd(BETA2) * nd(DELTA), 'J/kg')
        scales(7) = si_scale_t('stress', stiffness * nd(DELTA) / nd(A_CHECK), 'Pa')
        scales(8) = si_scale_t('heat_flux', &
                               mat%rho0 * mat%cE * nd(DELTA) * mat%ell * stiffness / (nd(OMEGA) * nd(BETA1)), 'W/m^2')
        scales(9) = si_scale_t('diffusion_flux', mat%D * nd(BETA2) * nd(DELTA) / mat%ell, 'kg/(m^2 s)')
        scales(10) = si_scale_t('energy', mat%ell * stiffness * nd(DELTA)**2 / nd(A_CHECK), 'J/m^2')
    end function si_scales

    !> The factor from a run's times to those of its input: with &material the time scale
    !> omega of (2.10), in s; else 1.
    pure real(dp) function time_scale(mat)
        type(material_t), intent(in) :: mat
        real(dp) :: nd(size(NONDIM_NAMES))

        time_scale = 1.0_dp
        if (.not. mat%present) return
        nd = nondim_groups(mat)
        time_scale = nd(OMEGA)
    end function time_scale

    !> The nondimensional groups of (2.10) for the physical quantities `mat`, by index (BETA1, ...).
    pure function nondim_groups(mat) result(nd)
        type(material_t), intent(in) :: mat
        real(dp) :: nd(size(NONDIM_NAMES))
        real(dp) :: stiffness   ! lambda + 2 mu

        stiffness = mat%lambda + 2.0_dp * mat%mu
        nd(BETA1) = (3.0_dp * mat%lambda + 2.0_dp * mat%mu) * mat%alpha_t
        nd(BETA2) = (3.0_dp * mat%lambda + 2.0_dp * mat%mu) * mat%alpha_c
        nd(OMEGA) = mat%rho0 * mat%cE * mat%ell**2 / mat%kappa
        nd(DELTA) = sqrt(stiffness / (mat%rho0 * mat%cE * mat%T0))
        nd(VARSIGMA) = mat%rho0 * mat%ell**2 / (nd(OMEGA)**2 * stiffness)
        nd(ZETA) = (mat%lambda_v + 2.0_dp * mat%mu_v) / (nd(OMEGA) * stiffness)
        nd(A_CHECK) = mat%T0 * nd(BETA1)**2 / (mat%rho0 * mat%cE * stiffness)
        nd(ALPHA1) = stiffness * mat%nu / (nd(BETA1) * nd(BETA2))
        nd(ALPHA2) = stiffness * mat%ell**2 / (mat%D * nd(BETA2)**2 * nd(OMEGA))
        nd(ALPHA3) = stiffness * mat%varrho / nd(BETA2)**2
    end function nondim_groups

    !> The coefficients of (2.11) for the physical quantities `mat`; relaxation times are
    !> scaled as tau0* = tau0/omega, tau* = tau/omega.
    pure function model_from_material(mat) result(m)
        type(material_t), intent(in) :: mat
        type(model_t) :: m
        real(dp) :: nd(size(NONDIM_NAMES))

        nd = nondim_groups(mat)
        associate (a => nd(A_CHECK), a1 => nd(ALPHA1), a2 => nd(ALPHA2), a3 => nd(ALPHA3))
            m%rho = a * nd(VARSIGMA)
            m%alpha = a * (1.0_dp - 1.0_dp / a3)
            m%varpi = nd(ZETA) * a
            m%gamma1 = a * (1.0_dp + a1 / a3)
            m%gamma2 = a / a3
            m%c = 1.0_dp + a * a1**2 / a3
            m%d = a1 * a / a3
            m%r = a / a3
            m%hbar = a / a2
        end associate
        m%tau0 = mat%tau0 / nd(OMEGA)
        m%tau = mat%tau / nd(OMEGA)
    end function model_from_material

    !> &material must be such that (2.10)-(2.11) can be evaluated: checked here, since the
    !> reader computes &model from it (validate_m then checks the &model values).
    subroutine check_material(mat)
        type(material_t), intent(in) :: mat
        character(len=*), parameter :: names(16) = [character(len=8) :: 'T0', 'rho0', 'cE', 'kappa', &
            'mu', 'alpha_t', 'alpha_c', 'D', 'varrho', 'ell', 'nu', 'tau0', 'tau', 'lambda_v', 'mu_v', 'lambda']
        !  > 0 for the first 10, >= 0 for the next 5, any finite value for lambda
        real(dp) :: values(16)
        integer :: k

        ! with &material the other inputs are SI too: an input written for the nondimensional
        ! system (g, dt, t_end, &initial) must not be read so unnoticed
        if (mat%units /= 'si') call fatal(EXIT_INPUT, 'material.units', 'got ' // quoted(trim(mat%units)) // &
            "; must be 'SI': with &material every input that has a unit is in SI units " // &
            "(g and positions in m, times in s, &initial in K, m, m/s, ...: docs/input.md); " // &
            "say so with units = 'SI' after converting " // &
            'any nondimensional values, or leave &material out (then every input is nondimensional)')
        values = [mat%T0, mat%rho0, mat%cE, mat%kappa, mat%mu, mat%alpha_t, mat%alpha_c, mat%D, mat%varrho, &
                  mat%ell, mat%nu, mat%tau0, mat%tau, mat%lambda_v, mat%mu_v, mat%lambda]
        do k = 1, size(values)
            associate (x => values(k), where => 'material.' // trim(names(k)))
                if (.not. ieee_is_finite(x)) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be a finite real number')
                if (k <= 10 .and. .not. x > 0.0_dp) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be > 0')
                if (k > 10 .and. k <= 15 .and. .not. x >= 0.0_dp) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be >= 0')
            end associate
        end do
        if (.not. 3.0_dp * mat%lambda + 2.0_dp * mat%mu > 0.0_dp) call fatal(EXIT_INPUT, 'material.lambda', &
            'got ' // format_real(mat%lambda) // ' with mu = ' // format_real(mat%mu) // &
            '; 3 lambda + 2 mu must be > 0 (beta1, beta2 of (2.2))')
    end subroutine check_material

    !> With &material (validated), the one place where a run's SI inputs become the
    !> nondimensional variables of (2.10) the code runs in: &model by (2.10)-(2.11), the
    !> gap, compliance, times and initial data divided by their scales (si_scales; the
    !> polynomials' variable is x/ell in both systems). Echoed on stdout with what is off.
    subroutine nondimensionalise(cfg)
        type(config_t), intent(inout) :: cfg
        type(si_scale_t) :: s(10)

        if (.not. cfg%material%present) return
        s = si_scales(cfg%material)
        cfg%model = model_from_material(cfg%material)
        call echo_material(cfg, nondim_groups(cfg%material))
        write (output_unit, '(2x, a)') 'SI inputs / scale = the nondimensional values run'
        associate (c => cfg%contact, t => cfg%time, o => cfg%output, i => cfg%initial)
            call scale_down('contact.g', c%g, s(3))
            ! (3.4): u - g = -eps sigma in contact, so eps [m/Pa] scales as displacement / stress
            call scale_down('contact.eps', c%eps, si_scale_t('compliance', s(3)%factor / s(7)%factor, 'm/Pa'))
            call scale_down('time.dt', t%dt, s(1))
            call scale_down('time.t_end', t%t_end, s(1))
            call scale_down('time.dt_min', t%dt_min, s(1))
            call scale_down('time.dt_max', t%dt_max, s(1))
            call scale_down('output.snapshot_dt', o%snapshot_dt, s(1))
            call scale_down('output.series_dt', o%series_dt, s(1))
            ! each profile: its coefficients, and its table's rows (position in m, value)
            call scale_field('u0', i%u0_poly, i%u0_table, s(3), s(2))
            call scale_field('u1', i%u1_poly, i%u1_table, s(4), s(2))
            call scale_field('theta0', i%theta0_poly, i%theta0_table, s(5), s(2))
            call scale_field('p0', i%p0_poly, i%p0_table, s(6), s(2))
            call scale_field('q0', i%q0_poly, i%q0_table, s(8), s(2))
            call scale_field('eta0', i%eta0_poly, i%eta0_table, s(9), s(2))
            ! the steps (amplitude, x_end): x_end in m
            call scale_down('initial.theta0_step(1)', i%theta0_step(1), s(5))
            call scale_down('initial.theta0_step(2)', i%theta0_step(2), s(2))
            call scale_down('initial.p0_step(1)', i%p0_step(1), s(6))
            call scale_down('initial.p0_step(2)', i%p0_step(2), s(2))
        end associate
        call echo_effects(cfg%material)
        flush (output_unit)
    end subroutine nondimensionalise

    !> x (SI, in scale's units) becomes x / factor; an echo row gives both.
    subroutine scale_down(name, x, scale)
        character(len=*), intent(in) :: name
        real(dp), intent(inout) :: x
        type(si_scale_t), intent(in) :: scale
        real(dp) :: values(1)

        values = [x]
        call scale_profile(name, values, scale)
        x = values(1)
    end subroutine scale_down

    !> The profile `name` of &initial: its coefficients over value%factor (echoed, scale_profile)
    !> and its table's rows (if any), positions over position%factor, values over value%factor.
    subroutine scale_field(name, poly, table, value, position)
        character(len=*), intent(in) :: name
        real(dp), intent(inout) :: poly(:)
        real(dp), allocatable, intent(inout) :: table(:, :)
        type(si_scale_t), intent(in) :: value, position

        call scale_profile('initial.' // name // '_poly', poly, value)
        if (.not. allocated(table)) return
        table(:, 1) = table(:, 1) / position%factor
        table(:, 2) = table(:, 2) / value%factor
    end subroutine scale_field

    !> Coefficients (SI, in scale's units) divided by factor; echoed unless all are zero.
    subroutine scale_profile(name, values, scale)
        character(len=*), intent(in) :: name
        real(dp), intent(inout) :: values(:)
        type(si_scale_t), intent(in) :: scale
        character(len=240) :: row
        integer :: n

        values = values / scale%factor
        n = findloc(abs(values) > 0.0_dp, .true., dim=1, back=.true.)
        if (n == 0 .and. size(values) > 1) return
        write (row, '(4x, a, t28, a, t40, "/ ", es12.5, " =", *(1x, es13.6))') &
            name, '[' // trim(scale%units) // ']', scale%factor, values(:max(n, 1))
        write (output_unit, '(a)') trim(row)
    end subroutine scale_profile

    !> The effects the physical input leaves out (zero by default), each with the value that
    !> gives the paper's (7.1) one (the &model defaults): varpi = zeta a-check, tau0* = tau0/omega.
    subroutine echo_effects(mat)
        type(material_t), intent(in) :: mat
        real(dp) :: nd(size(NONDIM_NAMES))
        type(model_t) :: paper

        nd = nondim_groups(mat)
        if (.not. mat%lambda_v + 2.0_dp * mat%mu_v > 0.0_dp) write (output_unit, '(2x, a)') &
            'off: viscosity (lambda_v + 2 mu_v = 0; varpi = ' // format_real(paper%varpi) // &
            ' of (7.1) is lambda_v + 2 mu_v = ' // &
            format_real(paper%varpi * nd(OMEGA) * (mat%lambda + 2.0_dp * mat%mu) / nd(A_CHECK)) // ' Pa s)'
        if (.not. mat%tau0 > 0.0_dp) write (output_unit, '(2x, a)') &
            'off: second sound (tau0 = 0: Fourier''s law; tau0* = ' // format_real(paper%tau0) // &
            ' of (7.1) is tau0 = ' // format_real(paper%tau0 * nd(OMEGA)) // ' s)'
        if (.not. mat%tau > 0.0_dp) write (output_unit, '(2x, a)') &
            'off: diffusion relaxation (tau = 0: Fick''s law; tau* = ' // format_real(paper%tau) // &
            ' of (7.1) is tau = ' // format_real(paper%tau * nd(OMEGA)) // ' s)'
    end subroutine echo_effects

    !> Echo the physical values of cfg%material, the nondimensional groups nd computed from
    !> them and the &model values cfg%model (stdout).
    subroutine echo_material(cfg, nd)
        type(config_t), intent(in) :: cfg
        real(dp), intent(in) :: nd(:)
        integer :: k

        write (output_unit, '(a)') 'rodcontact: &material (SI units) -> &model by (2.10)-(2.11)'
        write (output_unit, '(2x, a)') 'physical'
        call echo_group(cfg, 'material')
        write (output_unit, '(2x, a)') 'derived (2.10)'
        do k = 1, size(NONDIM_NAMES)
            call echo_row(trim(NONDIM_NAMES(k)), nd(k), trim(NONDIM_UNITS(k)))
        end do
        write (output_unit, '(2x, a)') '&model (2.11)'
        call echo_group(cfg, 'model')
    end subroutine echo_material

    !> One row per variable of `group` (all real), with its unit or note from INPUT_VARS.
    subroutine echo_group(cfg, group)
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in) :: group
        type(input_item_t) :: item
        integer :: k

        do k = 1, size(INPUT_VARS)
            if (INPUT_VARS(k)%group /= group .or. INPUT_VARS(k)%kind /= KIND_REAL) cycle
            item = input_item(cfg, k)
            call echo_row(trim(INPUT_VARS(k)%name), item%reals(1), trim(INPUT_VARS(k)%unit))
        end do
    end subroutine echo_group

    subroutine echo_row(name, value, unit)
        character(len=*), intent(in) :: name, unit
        real(dp), intent(in) :: value
        character(len=120) :: row

        write (row, '(4x, a, t17, "= ", es13.6, 2x, a)') name, value, unit
        write (output_unit, '(a)') trim(row)
    end subroutine echo_row

end module material_m
