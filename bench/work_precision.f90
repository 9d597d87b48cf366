!> Benchmark (not a test): error at the final time against the wall time of the stepping,
!> one run per (scheme, h, dt) point, for a work-precision diagram (scripts/work_precision.sh).
!>
!>   rodcontact_work_precision mms <t_end> <point> [<point> ...]
!>   rodcontact_work_precision exp2 <input.nml> <t_end> <reference point> <point> [<point> ...]
!>   rodcontact_work_precision exp2dt <input.nml> <t_end> <reference point> <point> [<point> ...]
!>
!> A point is scheme:s:dt, e.g. euler:400:2.5e-3 or bdf2:400:2.5e-3 (method 'monolithic').
!>
!> mms : the manufactured solution mms_no_contact (tests/lib/mms_m) with the O(1) model of
!>       tests/test_convergence.f90, source terms through sources_m, started from the nodal
!>       interpolants of the exact fields. Errors at t_end against the exact solution (5-point
!>       Gauss per element): L2 of theta, v, P and H1 of u, absolute (the fields are O(1)).
!> exp2: the input (input/exp2.nml) with mesh and time step of each point. Errors at t_end
!>       against the reference point (run first, kept in memory; its s must be a multiple of
!>       every point's s, so that a coarse P1 function is exactly a P1 function on the
!>       reference mesh and the norms below are exact integrals): L2 of theta, v, P and H1 of
!>       u, each relative to the same norm of the reference. The reference is checked
!>       against a run with s/2 and 2 dt ('reference_check' line).
!> exp2dt: as exp2, for the time error alone: points with the reference's s, and the check
!>       run has the same s and 2 dt.
!>
!> Only the time loop (stepper_t%advance, N = t_end / dt steps, sources included for mms) is
!> timed; set-up (assembly, factorisations) is reported apart, and the error is evaluated
!> once, after the clock has stopped. Runs shorter than 0.2 s are repeated (5 times below
!> 0.05 s, else 3) and the median is reported.
program work_precision
    use kinds_m, only: dp
    use config_m, only: config_t, model_t
    use config_reader_m, only: read_config
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use fields_m, only: N_FIELDS, F_THETA, F_V, F_P, is_dirichlet
    use mms_m, only: mms_t, mms_no_contact, U_FIELD, N_EXACT
    use convergence_m, only: level_errors
    use bench_timing_m, only: wall_seconds, median, num
    implicit none

    integer, parameter :: N_ERR = 4     !< theta (L2), v (L2), P (L2), u (H1)
    character(len=*), parameter :: ERR_NAMES(N_ERR) = [character(len=10) :: 'e_theta_L2', 'e_v_L2', 'e_P_L2', 'e_u_H1']
    type(config_t) :: cfg
    type(mms_t) :: mms
    type(state_t) :: state, reference, check
    character(len=1024) :: mode, arg, path
    character(len=16) :: scheme
    real(dp) :: t_end, dt, seconds, init_seconds, errors(N_ERR)
    integer :: s, s_check, k, i_err, first_point, repeats
    logical :: is_mms

    call get_command_argument(1, mode)
    is_mms = mode == 'mms'
    if (.not. (is_mms .or. mode == 'exp2' .or. mode == 'exp2dt') .or. &
        command_argument_count() < merge(3, 5, is_mms)) then
        write (*, '(a)') 'usage: rodcontact_work_precision mms <t_end> <scheme:s:dt> ...'
        write (*, '(a)') '       rodcontact_work_precision exp2|exp2dt <input.nml> <t_end> <reference scheme:s:dt> '// &
            '<scheme:s:dt> ...'
        stop 2
    end if
    if (is_mms) then
        call get_command_argument(2, arg)
        read (arg, *) t_end
        ! the O(1) model of tests/test_convergence.f90; u(1,t) <= 0.06 < g: no contact
        mms = mms_no_contact(model_t(rho=1.0_dp, alpha=1.0_dp, varpi=0.1_dp, gamma1=0.5_dp, gamma2=0.5_dp, &
                                     c=1.0_dp, d=0.2_dp, r=1.0_dp, hbar=1.0_dp, tau0=0.5_dp, tau=0.5_dp))
        cfg%model = mms%model
        cfg%contact%eps = mms%eps
        cfg%contact%g = mms%g
        first_point = 3
    else
        call get_command_argument(2, path)
        call get_command_argument(3, arg)
        read (arg, *) t_end
        call read_config(trim(path), cfg)
        cfg%output%quiet = .true.
        call get_command_argument(4, arg)
        call parse_point(arg, scheme, s, dt)
        call run_point(scheme, s, dt, reference, seconds, init_seconds, repeats, once=.true.)
        write (*, '(a,a,a,i0,a,a,a,i0,a,a)') 'reference scheme=', trim(scheme), ' s=', s, ' dt=', num(dt), &
            ' steps=', nint(t_end / dt), ' seconds=', num(seconds)
        if (mode == 'exp2') s_check = s / 2
        if (mode == 'exp2dt') s_check = s
        call run_point(scheme, s_check, 2.0_dp * dt, check, seconds, init_seconds, repeats, once=.true.)
        errors = errors_against_reference(check, reference)
        write (*, '(a,a,a,i0,a,a,*(a,a,a,a))') 'reference_check scheme=', trim(scheme), ' s=', s_check, &
            ' dt=', num(2.0_dp * dt), (' ', trim(ERR_NAMES(i_err)), '=', num(errors(i_err)), i_err = 1, N_ERR)
        first_point = 5
    end if

    do k = first_point, command_argument_count()
        call get_command_argument(k, arg)
        call parse_point(arg, scheme, s, dt)
        call run_point(scheme, s, dt, state, seconds, init_seconds, repeats, once=.false.)
        if (is_mms) then
            errors = errors_against_mms(state)
        else
            errors = errors_against_reference(state, reference)
        end if
        write (*, '(a,a,a,a,a,i0,a,a,a,i0,a,a,a,a,a,i0,*(a,a,a,a))') 'point problem=', trim(mode), &
            ' scheme=', trim(scheme), ' s=', s, ' dt=', num(dt), ' steps=', nint(t_end / dt), ' seconds=', num(seconds), &
            ' init_seconds=', num(init_seconds), ' repeats=', repeats, (' ', trim(ERR_NAMES(i_err)), '=', &
            num(errors(i_err)), i_err = 1, N_ERR)
    end do

contains

    !> 'scheme:s:dt' -> scheme, s, dt
    subroutine parse_point(text, scheme, s, dt)
        character(len=*), intent(in) :: text
        character(len=*), intent(out) :: scheme
        integer, intent(out) :: s
        real(dp), intent(out) :: dt
        integer :: c1, c2, ios

        c1 = index(text, ':')
        c2 = index(text, ':', back=.true.)
        if (c1 == 0 .or. c2 == c1) then
            write (*, '(a)') "work_precision: a point is scheme:s:dt, got '"//trim(text)//"'"
            stop 2
        end if
        scheme = text(:c1 - 1)
        read (text(c1 + 1:c2 - 1), *, iostat=ios) s
        if (ios == 0) read (text(c2 + 1:), *, iostat=ios) dt
        if (ios /= 0 .or. (scheme /= 'euler' .and. scheme /= 'bdf2')) then
            write (*, '(a)') "work_precision: bad point '"//trim(text)//"' (scheme euler|bdf2, s integer, dt real)"
            stop 2
        end if
    end subroutine parse_point

    !> Run one point from t = 0 to t_end; state: the final state. seconds: median wall time of
    !> the time loop over the repeats (once: a single run).
    subroutine run_point(scheme, s, dt, state, seconds, init_seconds, repeats, once)
        character(len=*), intent(in) :: scheme
        integer, intent(in) :: s
        real(dp), intent(in) :: dt
        type(state_t), intent(out) :: state
        real(dp), intent(out) :: seconds, init_seconds
        integer, intent(out) :: repeats
        logical, intent(in) :: once
        real(dp) :: times(5), t0
        integer :: r, n, n_steps

        n_steps = nint(t_end / dt)
        if (abs(n_steps * dt - t_end) > 1.0e-9_dp * t_end) then
            write (*, '(a,es10.3,a,es10.3)') 'work_precision: t_end ', t_end, ' is not a multiple of dt ', dt
            stop 2
        end if
        cfg%mesh%n_elements = s
        cfg%time%dt = dt
        cfg%time%t_end = t_end
        cfg%time%scheme = scheme
        cfg%solver%method = 'monolithic'
        repeats = 1
        r = 0
        do
            r = r + 1
            block
                type(stepper_t) :: stepper
                type(step_result_t) :: result

                call start_state(state)
                t0 = wall_seconds()
                if (is_mms) then
                    call stepper%init(cfg, result, mms)
                else
                    call stepper%init(cfg, result)
                end if
                init_seconds = wall_seconds() - t0
                if (.not. result%ok) then
                    write (*, '(a)') 'work_precision: stepper init failed: '//trim(result%message)
                    stop 1
                end if
                t0 = wall_seconds()
                do n = 1, n_steps
                    call stepper%advance(state, result)
                    if (.not. result%ok) then
                        write (*, '(a)') 'work_precision: step failed: '//trim(result%message)
                        stop 1
                    end if
                end do
                times(r) = wall_seconds() - t0
            end block
            if (r == 1 .and. .not. once) then
                if (times(1) < 0.05_dp) then
                    repeats = 5
                else if (times(1) < 0.2_dp) then
                    repeats = 3
                end if
            end if
            if (r >= repeats) exit
        end do
        seconds = median(times(:repeats))
    end subroutine run_point

    !> t = 0: nodal interpolants of the exact fields (mms) or of the input's data (exp2).
    subroutine start_state(state)
        type(state_t), intent(out) :: state
        integer :: i, f, s

        if (.not. is_mms) then
            call initial_state(cfg, state)
            return
        end if
        s = cfg%mesh%n_elements
        state%s = s
        allocate (state%u(0:s), state%w(0:s, N_FIELDS))
        do i = 0, s
            state%u(i) = mms%exact(U_FIELD, 0.0_dp, real(i, dp) / s, 0)
            do f = 1, N_FIELDS
                state%w(i, f) = mms%exact(f, 0.0_dp, real(i, dp) / s, 0)
                if (is_dirichlet(f, i, s)) state%w(i, f) = 0.0_dp
            end do
        end do
    end subroutine start_state

    !> L2 of theta, v, P and H1 of u at state%t against the exact solution (convergence_m).
    function errors_against_mms(state) result(e)
        type(state_t), intent(in) :: state
        real(dp) :: e(N_ERR)
        real(dp) :: all_errors(N_EXACT)

        all_errors = level_errors(mms, state)
        e = all_errors([F_THETA, F_V, F_P, U_FIELD])
    end function errors_against_mms

    !> L2 of theta, v, P and H1 of u of (state - ref), relative to the same norms of ref. The
    !> coarse P1 functions are evaluated at the reference nodes (ref%s a multiple of state%s),
    !> so the differences are P1 on the reference mesh and the integrals are exact.
    function errors_against_reference(state, ref) result(e)
        type(state_t), intent(in) :: state, ref
        real(dp) :: e(N_ERR)
        integer, parameter :: FIELDS(3) = [F_THETA, F_V, F_P]
        real(dp), allocatable :: d(:, :), r(:, :)
        real(dp) :: hr, num(N_ERR), den(N_ERR)
        integer :: m, j, k

        if (mod(ref%s, state%s) /= 0) then
            write (*, '(a,i0,a,i0)') 'work_precision: reference s = ', ref%s, ' is not a multiple of s = ', state%s
            stop 2
        end if
        m = ref%s / state%s
        allocate (d(0:ref%s, N_ERR), r(0:ref%s, N_ERR))
        do j = 0, ref%s
            do k = 1, 3
                r(j, k) = ref%w(j, FIELDS(k))
                d(j, k) = coarse_at(state%w(:, FIELDS(k)), j, m) - r(j, k)
            end do
            r(j, 4) = ref%u(j)
            d(j, 4) = coarse_at(state%u, j, m) - r(j, 4)
        end do
        hr = 1.0_dp / ref%s
        do k = 1, N_ERR
            num(k) = l2_squared(d(:, k), hr)
            den(k) = l2_squared(r(:, k), hr)
        end do
        ! H1 of u: add the squared L2 norm of the (piecewise constant) derivative
        num(4) = num(4) + sum((d(1:, 4) - d(:ref%s - 1, 4))**2) / hr
        den(4) = den(4) + sum((r(1:, 4) - r(:ref%s - 1, 4))**2) / hr
        e = sqrt(num / den)
    end function errors_against_reference

    !> value at reference node j of the coarse P1 function with nodal values c(0:), m
    !> reference elements per coarse element
    pure real(dp) function coarse_at(c, j, m)
        real(dp), intent(in) :: c(0:)
        integer, intent(in) :: j, m
        integer :: e
        real(dp) :: w

        e = j / m
        if (e == ubound(c, 1)) then
            coarse_at = c(e)
        else
            w = real(j - e * m, dp) / m
            coarse_at = (1.0_dp - w) * c(e) + w * c(e + 1)
        end if
    end function coarse_at

    !> int f^2 dx for a P1 function with nodal values f(0:), uniform step h (exact)
    pure real(dp) function l2_squared(f, h)
        real(dp), intent(in) :: f(0:)
        real(dp), intent(in) :: h
        integer :: n

        n = ubound(f, 1)
        l2_squared = h / 3.0_dp * sum(f(:n - 1)**2 + f(:n - 1) * f(1:) + f(1:)**2)
    end function l2_squared

end program work_precision
