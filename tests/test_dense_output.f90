!> Dense output (dense_output_m through step_driver_t%dense_level and run_output_m's
!> dense_series): on a
!> manufactured solution whose fields are linear in x (tests/lib/mms_m: no spatial error, u(1,t)
!> = 0.03 + 0.02 sin 2t), fixed steps dt = 0.04, 0.02, 0.01, 0.005 to t = 1. Per scheme:
!>  - the error of u(1,t) at the middle of every step (the interpolant) falls at the scheme's
!>    order p (observed order within 0.2 of p on the last halvings);
!>  - it stays close to the error at the steps (at most 1.5 times it on the finest step);
!>  - the interpolant's own error (the error between the steps less the interpolated errors
!>    of the levels it is built from) falls at order p+1: a straight line between the levels
!>    of a second-order scheme (order 2, dt^2 |u''| / 8) fails this;
!>  - dense_series's u(1,t) is dense_level's u at x = 1 (the same interpolant), and its
!>    energy parts add up to its energy.
program test_dense_output
    use kinds_m, only: dp
    use config_m, only: config_t, model_t
    use state_m, only: state_t
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: energy_monitor_t
    use step_driver_m, only: step_driver_t
    use mms_m, only: mms_t, mms_linear_in_x, U_FIELD
    use convergence_m, only: mms_config, mms_initial_state
    use fields_m, only: N_FIELDS, N_SERIES, S_U_END, S_ENERGY, S_ENERGY_PARTS
    use error_estimator_m, only: MAX_LEVELS
    use run_output_m, only: dense_series
    use testing_m, only: check_true, test_summary
    use dense_output_m, only: lagrange_weights
    implicit none
    integer, parameter :: N_DT = 4, S = 4
    type(model_t) :: unit_model
    type(mms_t) :: mms
    character(len=8), parameter :: SCHEMES(3) = [character(len=8) :: 'euler', 'bdf2', 'midpoint']
    integer, parameter :: ORDERS(3) = [1, 2, 2]
    integer :: k, i
    real(dp) :: at_steps(N_DT), between(N_DT), series_gap(N_DT), own(N_DT), order
    character(len=200) :: detail

    unit_model = model_t(rho=1.0_dp, alpha=1.0_dp, varpi=0.1_dp, gamma1=0.5_dp, gamma2=0.5_dp, c=1.0_dp, &
                         d=0.1_dp, r=1.0_dp, hbar=1.0_dp, tau0=0.5_dp, tau=0.5_dp)
    mms = mms_linear_in_x(unit_model, 0.01_dp, 0.1_dp, .false.)
    do k = 1, size(SCHEMES)
        do i = 1, N_DT
            call run(trim(SCHEMES(k)), ORDERS(k), 0.04_dp / 2**(i - 1), at_steps(i), between(i), series_gap(i), own(i))
        end do
        order = log(between(N_DT - 1) / between(N_DT)) / log(2.0_dp)
        write (detail, '(a,4es10.2,a,f6.2)') 'between the steps ', between, '; order ', order
        call check_true(trim(SCHEMES(k))//': the error between the steps falls at the scheme''s order', &
                        abs(order - ORDERS(k)) <= 0.2_dp, trim(detail))
        write (detail, '(a,es10.2,a,es10.2)') 'between ', between(N_DT), ', at the steps ', at_steps(N_DT)
        call check_true(trim(SCHEMES(k))//': the error between the steps is at most 1.5 times that at the steps', &
                        between(N_DT) <= 1.5_dp * at_steps(N_DT), trim(detail))
        order = log(own(N_DT - 1) / own(N_DT)) / log(2.0_dp)
        write (detail, '(a,4es10.2,a,f6.2)') 'own error ', own, '; order ', order
        call check_true(trim(SCHEMES(k))//': the interpolant''s own error falls at order p+1', &
                        order >= ORDERS(k) + 1 - 0.2_dp, trim(detail))
        write (detail, '(a,es10.2)') 'largest difference ', maxval(series_gap)
        call check_true(trim(SCHEMES(k))//': dense_series''s u(1,t) is dense_level''s, its parts add up to E', &
                        maxval(series_gap) <= 1.0e-14_dp, trim(detail))
    end do
    call test_summary('test_dense_output')

contains

    !> One fixed-step run of `scheme` with step dt to t = 1: the largest error of u(1,t) at the
    !> steps and at the middle of the steps (dense_level), and the largest difference between
    !> dense_series's u(1,t) and dense_level's.
    subroutine run(scheme, p, dt, at_steps, between, series_gap, own)
        character(len=*), intent(in) :: scheme
        integer, intent(in) :: p         !< the scheme's order
        real(dp), intent(in) :: dt
        real(dp), intent(out) :: at_steps, between, series_gap, own
        type(config_t) :: cfg
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        type(energy_monitor_t) :: monitor
        type(step_driver_t) :: driver
        real(dp) :: u(0:S), w(0:S, N_FIELDS), t_mid, e_mid, rows(N_SERIES, MAX_LEVELS), values(N_SERIES)
        real(dp) :: t_level(3), e_level(3)   !< the last levels' times and errors, newest first
        logical :: at_snapshot
        character(len=200) :: failure
        integer :: n, n_rows

        cfg = mms_config(mms, S, dt, 1.0_dp, scheme)
        cfg%output%series_dt = dt      ! dense output: fixed steps keep their levels (step_driver_m)
        call mms_initial_state(mms, S, state)
        call stepper%init(cfg, result, mms)
        call monitor%init(cfg%model, stepper%step_model, stepper%law, stepper%scheme, state)
        call driver%init(cfg, state, stepper, monitor)
        at_steps = 0.0_dp
        between = 0.0_dp
        series_gap = 0.0_dp
        own = 0.0_dp
        t_level = 0.0_dp
        e_level = 0.0_dp
        do n = 1, nint(1.0_dp / dt)
            call driver%take_step(state, stepper, monitor, result, real(n, dp) * dt, at_snapshot, failure)
            if (failure /= '') error stop 'test_dense_output: a step failed'
            t_level = [state%t, t_level(1:2)]
            e_level = [state%u(S) - mms%exact(U_FIELD, state%t, 1.0_dp, 0), e_level(1:2)]
            at_steps = max(at_steps, abs(e_level(1)))
            t_mid = state%t - 0.5_dp * dt
            call driver%dense_level(state, t_mid, u, w)
            e_mid = u(S) - mms%exact(U_FIELD, t_mid, 1.0_dp, 0)
            between = max(between, abs(e_mid))
            if (n > p) own = max(own, abs(e_mid - sum(lagrange_weights(t_level(1:p + 1), t_mid) * e_level(1:p + 1))))
            n_rows = 0
            call dense_series(driver, stepper, state, monitor, t_mid, rows, n_rows, values)
            series_gap = max(series_gap, abs(values(S_U_END) - u(S)), &
                             abs(sum(values(S_ENERGY_PARTS)) - values(S_ENERGY)) / max(abs(values(S_ENERGY)), 1.0_dp))
        end do
    end subroutine run

end program test_dense_output
