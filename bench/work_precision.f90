!> Benchmark (not a test): error at the final time against the wall time of the stepping,
!> one run per (scheme, h, dt) point, for a work-precision diagram (bench/work_precision.sh).
!>
!>   rodcontact_work_precision mms <t_end> <point> [<point> ...]
!>   rodcontact_work_precision exp2 <input.nml> <t_end> <reference point> <point> [<point> ...]
!>   rodcontact_work_precision exp2dt <input.nml> <t_end> <reference point> <point> [<point> ...]
!>   rodcontact_work_precision uend <input.nml> <t_end> <reference point> <point> [<point> ...]
!>   rodcontact_work_precision impact <input.nml> <t_end> <law> <point> [<point> ...]
!>
!> A point is scheme:s:dt, e.g. euler:400:2.5e-3, bdf2:400:2.5e-3 or midpoint:400:2.5e-3
!> (method 'monolithic').
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
!> uend: the time error of u(1,t) alone (exp1; bench/work_precision_schemes.sh): points with
!>       the reference's s and dt a multiple of the reference's dt; e_uend_max = max over the
!>       steps t_n <= t_end of |u(1,t_n) - u_ref(1,t_n)|, e_uend_pre the same over the steps
!>       before the reference's first contact (t_contact on the 'reference' line), both
!>       absolute; and the errors at t_end of exp2dt. The check run: same s, 2 dt.
!> impact: input/impact.nml (rho = alpha = 1, u0 = 0, u1 = x: u(1,t) = t - t^2/2 exactly
!>       until the end reaches g at t_onset = 1 - sqrt(1 - 2 g)) with the contact law <law>
!>       ('penalty' or 'signorini'): e_uend_pre = max over t_n < t_onset of
!>       |u(1,t_n) - (t_n - t_n^2/2)| (space and time error), the energy E^n of Corollary 6.2:
!>       drift = E(t_end)/E(0) - 1 and max_rise = max_n (E^n - E^{n-1}) / E(0).
!>
!> Only the time loop (stepper_t%advance, N = t_end / dt steps, sources included for mms) is
!> timed; set-up (assembly, factorisations) is reported apart, and the error is evaluated
!> once, after the clock has stopped. Runs shorter than 0.2 s are repeated (5 times below
!> 0.05 s, else 3) and the median is reported. uend and impact record u(1,t_n) (and E^n)
!> after every step: there each step is timed alone (the clock stops before the recording),
!> and the points are run round robin, 5 rounds, the median reported (the reference and its
!> check once).
program work_precision
    use kinds_m, only: dp
    use reals_m, only: equal
    use config_m, only: config_t, model_t
    use config_reader_m, only: read_config
    use energy_m, only: discrete_energy
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use fields_m, only: F_THETA, F_V, F_P
    use mms_m, only: mms_t, mms_no_contact, U_FIELD, N_EXACT
    use convergence_m, only: level_errors, mms_initial_state
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
    real(dp), allocatable :: u_end(:), u_end_ref(:), energy(:)
    character(len=1024), allocatable :: stashed(:)   !< series_mode: a line per point, until its time is known
    real(dp) :: t_contact, dt_ref      !< uend: the reference's first contact and its step
    integer :: s_ref

    call get_command_argument(1, mode)
    is_mms = mode == 'mms'
    if (mode == 'uend' .or. mode == 'impact') then
        call series_mode()
        stop
    end if
    if (.not. (is_mms .or. mode == 'exp2' .or. mode == 'exp2dt') .or. &
        command_argument_count() < merge(3, 5, is_mms)) then
        write (*, '(a)') 'usage: rodcontact_work_precision mms <t_end> <scheme:s:dt> ...'
        write (*, '(a)') '       rodcontact_work_precision exp2|exp2dt|uend <input.nml> <t_end> <reference scheme:s:dt> '// &
            '<scheme:s:dt> ...'
        write (*, '(a)') '       rodcontact_work_precision impact <input.nml> <t_end> penalty|signorini <scheme:s:dt> ...'
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

    !> The modes uend and impact (see the header): u(1,t_n) (and E^n) recorded every step. The
    !> points are timed round robin, SERIES_ROUNDS times (a burst of load on the shared machine
    !> then hits one run of several points, not all runs of one), and the median is reported;
    !> the errors are evaluated on the first round.
    subroutine series_mode()
        integer, parameter :: SERIES_ROUNDS = 5
        character(len=16) :: law
        character(len=16), allocatable :: schemes(:)
        integer, allocatable :: sizes(:)
        real(dp), allocatable :: dts(:), times(:, :), metrics(:, :)
        real(dp) :: t_onset, t_n, e_pre
        integer :: n, m, n_steps, n_points, r

        if (command_argument_count() < 5) then
            write (*, '(a)') 'usage: rodcontact_work_precision uend <input.nml> <t_end> <reference scheme:s:dt> '// &
                '<scheme:s:dt> ...'
            write (*, '(a)') '       rodcontact_work_precision impact <input.nml> <t_end> penalty|signorini <scheme:s:dt> ...'
            stop 2
        end if
        call get_command_argument(2, path)
        call get_command_argument(3, arg)
        read (arg, *) t_end
        call read_config(trim(path), cfg)
        cfg%output%quiet = .true.
        if (mode == 'uend') then
            call get_command_argument(4, arg)
            call parse_point(arg, scheme, s_ref, dt_ref)
            call run_series(scheme, s_ref, dt_ref, reference, u_end_ref, seconds, .false.)
            t_contact = t_end          ! the reference's first step in contact
            do n = 0, ubound(u_end_ref, 1)
                if (u_end_ref(n) > cfg%contact%g) then
                    t_contact = n * dt_ref
                    exit
                end if
            end do
            write (*, '(*(g0))') 'reference scheme=', trim(scheme), ' s=', s_ref, ' dt=', num(dt_ref), &
                ' steps=', nint(t_end / dt_ref), ' seconds=', num(seconds), ' t_contact=', num(t_contact)
            call run_series(scheme, s_ref, 2.0_dp * dt_ref, check, u_end, seconds, .false.)
            write (*, '(*(g0))') 'reference_check problem=uend scheme=', trim(scheme), ' s=', s_ref, ' dt=', &
                num(2.0_dp * dt_ref), ' steps=', ubound(u_end, 1), ' seconds=', num(seconds), ' repeats=1', &
                trim(uend_errors(2.0_dp * dt_ref, check))
        else
            call get_command_argument(4, law)
            if (law /= 'penalty' .and. law /= 'signorini') then
                write (*, '(a)') "work_precision: impact: law '"//trim(law)//"' (penalty|signorini)"
                stop 2
            end if
            cfg%contact%law = law
            ! u(1,t) = t - t^2/2 holds for rho = alpha = 1, u0 = 0, u1 = x (input/impact.nml)
            if (.not. (equal(cfg%model%rho, 1.0_dp) .and. equal(cfg%model%alpha, 1.0_dp))) then
                write (*, '(a)') 'work_precision: impact: the exact solution needs rho = alpha = 1 (input/impact.nml)'
                stop 2
            end if
            t_onset = 1.0_dp - sqrt(1.0_dp - 2.0_dp * cfg%contact%g)
        end if

        n_points = command_argument_count() - 4
        allocate (schemes(n_points), sizes(n_points), dts(n_points), times(SERIES_ROUNDS, n_points), &
                  metrics(3, n_points), stashed(n_points))
        do k = 1, n_points
            call get_command_argument(k + 4, arg)
            call parse_point(arg, schemes(k), sizes(k), dts(k))
            if (mode /= 'uend') cycle
            m = nint(dts(k) / dt_ref)
            if (sizes(k) /= s_ref .or. abs(m * dt_ref - dts(k)) > 1.0e-9_dp * dts(k)) then
                write (*, '(a)') 'work_precision: uend: a point needs the reference''s s and a multiple of its dt: '// &
                    trim(arg)
                stop 2
            end if
        end do
        do r = 1, SERIES_ROUNDS
            do k = 1, n_points
                scheme = schemes(k)
                call run_series(scheme, sizes(k), dts(k), state, u_end, times(r, k), &
                                mode == 'impact' .and. r == 1, energy)
                if (r > 1) cycle
                if (mode == 'uend') then
                    ! the line without its time, completed after the last round
                    write (stashed(k), '(*(g0))') ' problem=uend scheme=', trim(scheme), ' s=', s_ref, ' dt=', &
                        num(dts(k)), ' steps=', ubound(u_end, 1), trim(uend_errors(dts(k), state))
                else
                    n_steps = ubound(u_end, 1)
                    e_pre = 0.0_dp
                    do n = 0, n_steps
                        t_n = n * dts(k)
                        if (t_n >= t_onset) exit
                        e_pre = max(e_pre, abs(u_end(n) - (t_n - 0.5_dp * t_n**2)))
                    end do
                    metrics(:, k) = [e_pre, energy(n_steps) / energy(0) - 1.0_dp, &
                                     maxval(energy(1:) - energy(:n_steps - 1)) / energy(0)]
                    write (stashed(k), '(*(g0))') ' problem=impact law=', trim(law), ' scheme=', trim(scheme), &
                        ' s=', sizes(k), ' dt=', num(dts(k)), ' steps=', n_steps, ' t_onset=', num(t_onset), &
                        ' e_uend_pre=', num(metrics(1, k)), ' drift=', num(metrics(2, k)), ' max_rise=', num(metrics(3, k))
                end if
            end do
        end do
        do k = 1, n_points
            write (*, '(*(g0))') 'point', trim(stashed(k)), ' seconds=', num(median(times(:, k))), &
                ' repeats=', SERIES_ROUNDS
        end do
    end subroutine series_mode

    !> ' e_uend_max=... e_uend_pre=... e_theta_L2=...': the errors of u_end (step dt) and of the
    !> state at t_end against the reference (mode uend).
    function uend_errors(dt, final) result(text)
        real(dp), intent(in) :: dt
        type(state_t), intent(in) :: final
        character(len=512) :: text
        real(dp) :: e_max, e_pre
        integer :: n, m

        m = nint(dt / dt_ref)
        e_max = 0.0_dp
        e_pre = 0.0_dp
        do n = 0, ubound(u_end, 1)
            e_max = max(e_max, abs(u_end(n) - u_end_ref(n * m)))
            if (n * dt < t_contact) e_pre = max(e_pre, abs(u_end(n) - u_end_ref(n * m)))
        end do
        errors = errors_against_reference(final, reference)
        write (text, '(*(g0))') ' e_uend_max=', num(e_max), ' e_uend_pre=', num(e_pre), &
            (' ', trim(ERR_NAMES(i_err)), '=', num(errors(i_err)), i_err = 1, N_ERR)
    end function uend_errors

    !> Run one point from t = 0 to t_end recording u(1,t_n) after every step (and E^n, if
    !> with_energy); seconds: the summed wall time of the steps (the recording is not timed).
    subroutine run_series(scheme, s, dt, state, u_end, seconds, with_energy, energy)
        character(len=*), intent(in) :: scheme
        integer, intent(in) :: s
        real(dp), intent(in) :: dt
        type(state_t), intent(out) :: state
        real(dp), allocatable, intent(inout) :: u_end(:)
        real(dp), intent(out) :: seconds
        logical, intent(in) :: with_energy
        real(dp), allocatable, intent(inout), optional :: energy(:)
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        real(dp) :: t0
        integer :: n, n_steps

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
        if (allocated(u_end)) deallocate (u_end)
        allocate (u_end(0:n_steps))
        if (with_energy) then
            if (allocated(energy)) deallocate (energy)
            allocate (energy(0:n_steps))
        end if
        call initial_state(cfg, state)
        call stepper%init(cfg, result)
        if (.not. result%ok) then
            write (*, '(a)') 'work_precision: stepper init failed: '//trim(result%message)
            stop 1
        end if
        u_end(0) = state%u(s)
        if (with_energy) call discrete_energy(cfg%model, state%u, state%w, state%mesh, energy(0), law=stepper%law)
        seconds = 0.0_dp
        do n = 1, n_steps
            t0 = wall_seconds()
            call stepper%advance(state, result)
            seconds = seconds + (wall_seconds() - t0)
            if (.not. result%ok) then
                write (*, '(a)') 'work_precision: step failed: '//trim(result%message)
                stop 1
            end if
            u_end(n) = state%u(s)
            if (with_energy) call discrete_energy(cfg%model, state%u, state%w, state%mesh, energy(n), law=stepper%law)
        end do
    end subroutine run_series

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
        if (ios /= 0 .or. (scheme /= 'euler' .and. scheme /= 'bdf2' .and. scheme /= 'midpoint')) then
            write (*, '(a)') "work_precision: bad point '"//trim(text)//"' (scheme euler|bdf2|midpoint, s integer, dt real)"
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

        if (.not. is_mms) then
            call initial_state(cfg, state)
            return
        end if
        call mms_initial_state(mms, cfg%mesh%n_elements, state)
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
