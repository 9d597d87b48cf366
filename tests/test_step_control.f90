!> Adaptive time steps (step_control_m):
!>  1. the controller rejects a step whose estimate exceeds the tolerance (smaller retry, no
!>     growth right after), grows the step (by at most 2) when the estimate is small, keeps
!>     it inside the deadband and inside [dt_min, dt_max], grows it again after a
!>     rejection (regrowth_check); the ratio is est / (tol S) at a
!>     scale S /= 1 (at S = 1, est / tol would pass too);
!>  1b. save_checkpoint / restore_checkpoint (into checkpoint_m's checkpoint_t) give back
!>     every counter and sum of the controller, its proposal and no-growth flag, and the
!>     estimator's levels and steps;
!>  1c. the estimate is exact on levels X(t) = t^(p+1) Z with unequal past steps: the local
!>     error of the step, h^2 |Z|_E (Euler), h^2 (h + h_prev) (1+w)/(1+2w) |Z|_E (BDF2, w =
!>     h/h_prev), h^3/2 |Z|_E (midpoint) (a factor right for constant steps only fails), for
!>     every scheme of time_scheme_m (a new scheme needs its local error written here);
!>  2. the local error estimate tracks the true local error within a factor of 3, for all
!>     fields at once in the energy norm, on the manufactured solution of tests/lib/mms_m
!>     (no contact), for every scheme of time_scheme_m (Euler, BDF2, the midpoint rule; a new
!>     scheme is tested without a change here), over step sizes 0.04 ... 0.005
!>     with constant and with varying past steps. The true local error of a step is its
!>     difference from the same mesh's solution computed with 64 times smaller midpoint
!>     steps from the same past levels (the time error alone).
program test_step_control
    use kinds_m, only: dp
    use config_m, only: config_t, model_t, time_t
    use state_m, only: state_t
    use stepper_m, only: stepper_t, step_result_t
    use error_estimator_m, only: error_estimator_t, energy_norm
    use step_control_m, only: step_controller_t
    use time_scheme_m, only: time_scheme_t, time_scheme, scheme_rules
    use validate_m, only: scheme_rule_t
    use checkpoint_m, only: checkpoint_t
    use mesh_m, only: mesh_t
    use meshes_m, only: uniform_mesh
    use fields_m, only: N_FIELDS
    use energy_m, only: discrete_energy
    use mms_m, only: mms_t, mms_no_contact
    use convergence_m, only: mms_config, mms_initial_state
    use testing_m, only: check => check_true, test_summary
    implicit none

    integer, parameter :: S = 16, FINE = 64
    real(dp), parameter :: T_STEP_END = 0.3_dp   !< the tested step ends here
    real(dp), parameter :: DTS(4) = [0.04_dp, 0.02_dp, 0.01_dp, 0.005_dp]
    type(mms_t) :: mms
    integer :: k, j
    real(dp) :: ratio
    type(scheme_rule_t), allocatable :: schemes(:)
    character(len=160) :: detail

    call controller_checks()
    call checkpoint_checks()
    call estimator_checks()
    mms = mms_no_contact(model_t(rho=1.0_dp, alpha=1.0_dp, varpi=0.1_dp, gamma1=0.5_dp, gamma2=0.5_dp, c=1.0_dp, &
                                 d=0.1_dp, r=1.0_dp, hbar=1.0_dp, tau0=0.5_dp, tau=0.5_dp))
    schemes = scheme_rules()
    do k = 1, size(schemes)
        do j = 1, size(DTS)
            ratio = estimate_over_true(trim(schemes(k)%name), DTS(j), [1.0_dp, 1.0_dp, 1.0_dp])
            write (detail, '(a,a,a,es9.2,a,f7.3)') 'estimate/true, ', trim(schemes(k)%name), ', dt = ', DTS(j), &
                ', constant steps: ', ratio
            write (*, '(a)') trim(detail)
            call check(trim(detail), ratio >= 1.0_dp / 3.0_dp .and. ratio <= 3.0_dp)
            ratio = estimate_over_true(trim(schemes(k)%name), DTS(j), [1.0_dp, 0.6_dp, 1.5_dp])
            write (detail, '(a,a,a,es9.2,a,f7.3)') 'estimate/true, ', trim(schemes(k)%name), ', dt = ', DTS(j), &
                ', past steps 0.6 dt, 1.5 dt (new step / last = 1/0.6): ', ratio
            write (*, '(a)') trim(detail)
            call check(trim(detail), ratio >= 1.0_dp / 3.0_dp .and. ratio <= 3.0_dp)
        end do
    end do
    call test_summary('test_step_control')

contains

    subroutine controller_checks()
        type(step_controller_t) :: c
        real(dp) :: error_sum, scale
        integer :: n_estimated, n_rejected, n_forced

        call c%init(time_t(dt=0.01_dp, error_tol=1.0e-3_dp, dt_min=1.0e-6_dp, dt_max=0.1_dp), time_scheme('bdf2'), &
                    scale=1.0_dp)
        call check('ratio est / (tol S) = 8 for est = 8e-3', abs(c%ratio(8.0e-3_dp) - 8.0_dp) < 1.0e-12_dp)
        call c%reject(0.01_dp, 8.0_dp)
        call c%counts(error_sum, scale, n_estimated, n_rejected, n_forced)
        ! proposals are rounded down to the ladder dt_first 2^(k/3) (step_control_m's on_ladder)
        call check('a rejected step is retried smaller (0.45 dt for err = 8, order 2, down to the ladder: ' // &
                   '2^(-4/3) dt)', abs(c%proposal() - 0.01_dp * 2.0_dp**(-4.0_dp / 3.0_dp)) < 1.0e-15_dp .and. &
                   n_rejected == 1)
        call c%accept(c%proposal(), 0.0_dp, 1.0e-6_dp)
        call check('no growth on the step right after a rejection', &
                   abs(c%proposal() - 0.01_dp * 2.0_dp**(-4.0_dp / 3.0_dp)) < 1.0e-15_dp)
        call c%accept(0.0045_dp, 0.0_dp, 1.0e-6_dp)
        call check('a quiet step grows dt by the largest factor, 2 (0.009, down to the ladder: 2^(-1/3) 0.01)', &
                   abs(c%proposal() - 0.01_dp * 2.0_dp**(-1.0_dp / 3.0_dp)) < 1.0e-15_dp)
        call c%accept(0.01_dp, 0.0_dp, 1.0e-6_dp)
        call check('a step on the ladder that doubles stays on it (0.02)', abs(c%proposal() - 0.02_dp) < 1.0e-15_dp)
        call c%accept(0.009_dp, 0.0_dp, 0.5_dp)
        call check('err = 0.5 (growth 1.13 < 1.25): dt is kept', abs(c%proposal() - 0.009_dp) < 1.0e-15_dp)
        call c%accept(0.09_dp, 0.0_dp, 0.0_dp)
        call check('growth stops at dt_max', abs(c%proposal() - 0.1_dp) < 1.0e-15_dp)
        call c%reject(2.0e-6_dp, 1.0e6_dp)
        call check('shrinking stops at dt_min', abs(c%proposal() - 1.0e-6_dp) < 1.0e-18_dp)
        ! S = max |X^k|_E so far: 2.5 after levels of norm 2.5 and 0.5
        call c%observe_size(2.5_dp)
        call c%observe_size(0.5_dp)
        write (detail, '(a,es24.16)') 'got ', c%ratio(8.0e-3_dp)
        call check('ratio est / (tol S) = 3.2 for est = 8e-3, S = 2.5', abs(c%ratio(8.0e-3_dp) - 3.2_dp) < 1.0e-12_dp, &
                   trim(detail))
        call regrowth_check()
    end subroutine controller_checks

    !> After a rejection the step grows again: one step at the retried size (no growth),
    !> then three quiet steps double it each, past the step that was rejected.
    subroutine regrowth_check()
        type(step_controller_t) :: c
        real(dp) :: dt_retry, expected
        integer :: k

        call c%init(time_t(dt=0.01_dp, error_tol=1.0e-3_dp, dt_min=1.0e-6_dp, dt_max=0.1_dp), time_scheme('bdf2'), &
                    scale=1.0_dp)
        call c%reject(0.01_dp, 8.0_dp)
        dt_retry = c%proposal()
        call c%accept(dt_retry, 0.0_dp, 1.0e-6_dp)
        do k = 1, 3
            call c%accept(c%proposal(), 0.0_dp, 1.0e-6_dp)
        end do
        expected = 8.0_dp * dt_retry
        write (detail, '(a,es24.16,a,es24.16)') 'got ', c%proposal(), ', expected ', expected
        call check('after a rejection quiet steps grow again (8 times the retry, past the rejected 0.01)', &
                   abs(c%proposal() - expected) < 1.0e-12_dp * expected .and. c%proposal() > 0.01_dp, trim(detail))
    end subroutine regrowth_check

    !> A controller and an estimator in the middle of a run, through a checkpoint.
    subroutine checkpoint_checks()
        integer, parameter :: SC = 4
        type(step_controller_t) :: c, c2
        type(error_estimator_t) :: e, e2
        type(checkpoint_t) :: ckpt, ckpt2
        real(dp) :: u(0:SC), w(0:SC, N_FIELDS)
        real(dp) :: error_sum, scale, error_sum2, scale2
        integer :: n_estimated, n_rejected, n_forced, n_estimated2, n_rejected2, n_forced2
        real(dp) :: dt_held
        integer :: i, j

        ! counters and sums none of which is the default or equal to another
        call c%init(time_t(dt=0.01_dp, error_tol=1.0e-4_dp, dt_min=1.0e-8_dp, dt_max=0.5_dp), time_scheme('bdf2'))
        call c%observe_size(3.75_dp)
        do j = 1, 17   ! the first two forced (err > 1, accepted at dt_min)
            call c%accept(0.01_dp, 0.001_dp * real(j, dp), merge(1.5_dp, 0.5_dp, j <= 2))
        end do
        do j = 1, 5
            call c%reject(0.01_dp, 1.5_dp)
        end do
        ! the last reject leaves a proposal below 0.01 and no growth on the next step
        dt_held = c%proposal()
        call e%init(time_scheme('bdf2'), SC)
        do j = 1, 4
            u = real(j, dp) * [(0.1_dp * real(i, dp), i = 0, SC)]
            w = real(j, dp) + spread([(real(i, dp), i = 0, SC)], 2, N_FIELDS)
            call e%push(u, w, 0.001_dp * real(j, dp))
        end do
        call c%checkpoint(ckpt)
        call e%checkpoint(ckpt)
        call c2%init(time_t(dt=0.01_dp, error_tol=1.0e-4_dp, dt_min=1.0e-8_dp, dt_max=0.5_dp), time_scheme('bdf2'))
        call e2%init(time_scheme('bdf2'), SC)
        ckpt%reading = .true.
        call c2%checkpoint(ckpt)
        call e2%checkpoint(ckpt)
        call c%counts(error_sum, scale, n_estimated, n_rejected, n_forced)
        call c2%counts(error_sum2, scale2, n_estimated2, n_rejected2, n_forced2)
        ! exact: a checkpoint keeps every bit (<= 0 rather than ==: no real equality warning)
        call check('checkpoint: the proposal, scale, error_sum restored', &
                   abs(c2%proposal() - c%proposal()) <= 0.0_dp .and. dt_held < 0.01_dp .and. &
                   abs(scale2 - scale) <= 0.0_dp .and. abs(error_sum2 - error_sum) <= 0.0_dp)
        call check('checkpoint: n_estimated, n_rejected, n_forced restored', n_estimated2 == n_estimated .and. &
                   n_rejected2 == n_rejected .and. n_forced2 == n_forced .and. n_estimated == 17 .and. &
                   n_rejected == 5 .and. n_forced == 2)
        call c2%checkpoint(ckpt2)
        call e2%checkpoint(ckpt2)
        call check('checkpoint: the estimator''s levels and steps restored (saved again: the same arrays)', &
                   same_entries(ckpt2, ckpt) .and. e2%n_levels == e%n_levels)
        ! no_growth: a quiet step right after the restart keeps dt, as it would have without one
        call c%accept(dt_held, 0.0_dp, 1.0e-6_dp)
        call c2%accept(dt_held, 0.0_dp, 1.0e-6_dp)
        call check('checkpoint: no growth after a rejection restored', &
                   abs(c2%proposal() - c%proposal()) <= 0.0_dp .and. abs(c2%proposal() - dt_held) <= 0.0_dp)
    end subroutine checkpoint_checks

    !> Levels X(t_j) = t_j^(p+1) Z at t = 0.7, 0.82, 0.9 and the new one at 1 (steps 0.12, 0.08,
    !> 0.1): the estimate against the local error of the step for a solution with that X^(p+1).
    subroutine estimator_checks()
        integer, parameter :: SE = 6
        real(dp), parameter :: T_LEVELS(3) = [0.7_dp, 0.82_dp, 0.9_dp], T_NEW = 1.0_dp
        type(model_t), parameter :: MODEL = model_t(rho=1.5_dp, alpha=0.7_dp, varpi=0.1_dp, gamma1=0.3_dp, &
                                                    gamma2=0.2_dp, c=1.1_dp, d=0.2_dp, r=0.9_dp, hbar=0.8_dp, &
                                                    tau0=0.6_dp, tau=0.4_dp)
        type(error_estimator_t) :: e
        type(time_scheme_t) :: scheme
        type(mesh_t) :: mesh
        type(scheme_rule_t), allocatable :: rules(:)
        character(len=:), allocatable :: name
        real(dp) :: zu(0:SE), zw(0:SE, N_FIELDS), norm, h, h_prev, w, expected, est, energy
        integer :: i, j, k, p

        do i = 0, SE
            zu(i) = sin(real(i, dp))
            zw(i, :) = [(cos(real(i + j, dp)), j = 1, N_FIELDS)]
        end do
        mesh = uniform_mesh(SE)
        call discrete_energy(MODEL, zu, zw, mesh, energy)
        norm = energy_norm(energy)
        h = T_NEW - T_LEVELS(3)
        h_prev = T_LEVELS(3) - T_LEVELS(2)
        rules = scheme_rules()
        do k = 1, size(rules)
            name = trim(rules(k)%name)
            scheme = time_scheme(name)
            p = scheme%row%order
            call e%init(scheme, SE)
            do j = 1, 3
                call e%push(T_LEVELS(j)**(p + 1) * zu, T_LEVELS(j)**(p + 1) * zw, T_LEVELS(j) - T_LEVELS(max(j - 1, 1)))
            end do
            est = e%estimate(MODEL, T_NEW**(p + 1) * zu, T_NEW**(p + 1) * zw, h, mesh)
            select case (name)
            case ('euler')
                expected = h**2 * norm
            case ('bdf2')
                w = h / h_prev
                expected = h**2 * (h + h_prev) * (1.0_dp + w) / (1.0_dp + 2.0_dp * w) * norm
            case ('midpoint')
                expected = 0.5_dp * h**3 * norm
            case default
                call check('the local error of scheme '//name//' is written in estimator_checks', .false.)
                cycle
            end select
            write (detail, '(a,es24.16,a,es24.16)') 'expected ', expected, ', got ', est
            call check('estimate = local error on X = t^(p+1) Z, unequal steps, '//name, &
                       abs(est - expected) <= 1.0e-9_dp * expected, trim(detail))
        end do
    end subroutine estimator_checks

    !> est / |X^n - X_true|_E for one step of `scheme` of size dt ending at T_STEP_END, the
    !> past levels at T_STEP_END - dt - (0, h2, h2 + h3) with h2 = dt past(2), h3 = dt past(3)
    !> taken from a fine midpoint run (past(1) = 1: the new step).
    real(dp) function estimate_over_true(scheme, dt, past) result(ratio)
        character(len=*), intent(in) :: scheme
        real(dp), intent(in) :: dt, past(3)
        type(state_t) :: levels(3), coarse, fine_end
        type(error_estimator_t) :: estimator
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        type(config_t) :: cfg
        real(dp) :: t(3), est, energy
        integer :: j

        ! past levels, oldest first: t(1) = t_{n-3}, t(2) = t_{n-2}, t(3) = t_{n-1}
        t(3) = T_STEP_END - dt
        t(2) = t(3) - dt * past(2)
        t(1) = t(2) - dt * past(3)
        do j = 1, 3
            call fine_solution(t(j), dt / FINE, levels(j))
        end do
        call fine_solution(T_STEP_END, dt / FINE, fine_end)
        ! the step of the scheme from the last past level (and the one before, BDF2)
        cfg = mms_config(mms, S, dt, 1.0_dp, scheme)
        call stepper%init(cfg, result, mms)
        coarse = levels(3)
        coarse%step = 10                    ! past the midpoint rule's damped start
        coarse%t_anchor = t(3)
        coarse%step_anchor = coarse%step
        coarse%dt_last = t(3) - t(2)
        if (stepper%scheme%row%keeps_previous_level) then
            coarse%u_prev = levels(2)%u
            coarse%w_prev = levels(2)%w
        end if
        call stepper%advance(coarse, result, dt)
        if (.not. result%ok) error stop 'test_step_control: coarse step failed'
        call estimator%init(time_scheme(scheme), S)
        do j = 1, 3
            call estimator%push(levels(j)%u, levels(j)%w, t(j) - t(max(j - 1, 1)))
        end do
        est = estimator%estimate(mms%model, coarse%u, coarse%w, dt, coarse%mesh)
        call discrete_energy(mms%model, coarse%u - fine_end%u, coarse%w - fine_end%w, coarse%mesh, energy)
        ratio = est / sqrt(2.0_dp * energy)
    end function estimate_over_true

    !> The mesh solution at time t_want from the exact data at t = 0 with midpoint steps of
    !> about delta (landing exactly on t_want).
    subroutine fine_solution(t_want, delta, state)
        real(dp), intent(in) :: t_want, delta
        type(state_t), intent(out) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        type(config_t) :: cfg
        integer :: n, n_steps
        real(dp) :: dt

        n_steps = max(1, ceiling(t_want / delta))
        dt = t_want / n_steps
        cfg = mms_config(mms, S, dt, 1.0_dp, 'midpoint')
        call mms_initial_state(mms, S, state)
        call stepper%init(cfg, result, mms)
        do n = 1, n_steps
            call stepper%advance(state, result)
            if (.not. result%ok) error stop 'test_step_control: fine step failed'
        end do
    end subroutine fine_solution

    !> Two checkpoints with the same entries, bit for bit.
    logical function same_entries(a, b)
        type(checkpoint_t), intent(in) :: a, b
        integer :: k

        same_entries = a%n == b%n .and. a%n > 0
        do k = 1, min(a%n, b%n)
            associate (x => a%entries(k), y => b%entries(k))
                if (x%name /= y%name .or. (x%is_integer .neqv. y%is_integer) .or. any(x%dims /= y%dims)) then
                    same_entries = .false.
                else
                    same_entries = same_entries .and. all(x%values == y%values)
                end if
            end associate
        end do
    end function same_entries

end program test_step_control
