!> The built-in error estimate (error_companion_m, &output error_estimate) against the true
!> error on a manufactured solution (tests/lib/mms_m's mms_no_contact: smooth in x and t, all
!> five fields and u nonzero, the O(1) model of test_convergence), for Euler, BDF2 and the
!> midpoint rule: the run on s = 64 elements with dt = 1/128 to t = 1/2, its companions fed
!> the same source terms, the estimate at t = 1/4 and 1/2 against the relative L2 error of
!> the nodal values (trapezoidal rule on the run's nodes), and its time part against the
!> run's difference from the same mesh with steps dt/16. Target: every field's ratio
!> estimate / true error within [1/3, 3] (measured: total 0.82-1.61, time part 0.82-2.85).
!> The same with varying steps (as adaptive steps vary: sizes dt 2^(-k/3), k = 0, 1, 2 in
!> turn, five steps each; the estimate after 63 steps, an odd number: the companions step on
!> the run's queued steps and land on the estimate's time. After 31 steps, when companion D
!> has taken 4 steps, Euler's time part of eta is 3.5x the truth).
!> Checked that it can fail: the Richardson factor 2^(r+1) - 1 instead of 2^r - 1 fails
!> 5 checks with fixed steps and 3 with varying ones; the scheme's order p - 1 instead of p
!> in the time part fails 36 and 18.
program test_error_estimate_mms
    use kinds_m, only: dp
    use config_m, only: config_t, model_t
    use fields_m, only: N_OUTPUT_FIELDS, OUTPUT_ORDER, FIELDS, F_U
    use state_m, only: state_t, field_values
    use stepper_m, only: stepper_t, step_result_t
    use error_companion_m, only: error_companions_t, N_ESTIMATE_PARTS, PART_TOTAL, PART_TIME
    use mms_m, only: mms_t, mms_no_contact, U_FIELD
    use convergence_m, only: mms_initial_state
    use testing_m, only: check_true, test_summary
    implicit none
    character(len=*), parameter :: SCHEMES(3) = [character(len=8) :: 'euler', 'bdf2', 'midpoint']
    integer, parameter :: S = 64, N_STEPS = 64, FINE_STEPS = 16
    real(dp), parameter :: DT = 1.0_dp / 128.0_dp, RATIO_MAX = 3.0_dp
    type(model_t) :: unit_model
    integer :: k

    unit_model = model_t(rho=1.0_dp, alpha=1.0_dp, varpi=0.1_dp, gamma1=0.5_dp, gamma2=0.5_dp, c=1.0_dp, &
                         d=0.2_dp, r=1.0_dp, hbar=1.0_dp, tau0=0.5_dp, tau=0.5_dp)
    do k = 1, size(SCHEMES)
        call check_scheme(trim(SCHEMES(k)), mms_no_contact(unit_model), .false.)
        call check_scheme(trim(SCHEMES(k)), mms_no_contact(unit_model), .true.)
    end do
    call test_summary('test_error_estimate_mms')

contains

    !> One scheme with fixed steps (varying = .false.: N_STEPS of DT, estimates after
    !> N_STEPS/2 and N_STEPS) or varying ones (the program's header).
    subroutine check_scheme(scheme, mms, varying)
        character(len=*), intent(in) :: scheme
        type(mms_t), intent(in) :: mms
        logical, intent(in) :: varying
        type(config_t) :: cfg
        type(state_t) :: state, fine
        type(stepper_t) :: stepper, fine_stepper
        type(step_result_t) :: result
        type(error_companions_t) :: companions
        real(dp) :: values(N_OUTPUT_FIELDS, N_ESTIMATE_PARTS)
        real(dp) :: truth(N_OUTPUT_FIELDS), truth_time(N_OUTPUT_FIELDS)
        integer :: n, f, j, n_run
        real(dp) :: dt_n
        character(len=:), allocatable :: name

        cfg%model = mms%model
        cfg%mesh%n_elements = S
        cfg%time%dt = DT
        cfg%time%t_end = N_STEPS * DT
        cfg%time%scheme = scheme
        cfg%time%adaptive = varying
        cfg%output%error_estimate = .true.
        name = scheme
        n_run = N_STEPS
        if (varying) then
            name = scheme//' (varying steps)'
            n_run = N_STEPS - 1
        end if
        call mms_initial_state(mms, S, state)
        call stepper%init(cfg, result, mms)
        call companions%init(cfg, state, mms)
        ! the same mesh with steps dt / 16: the time error of the run is state - fine
        call mms_initial_state(mms, S, fine)
        cfg%time%dt = DT / FINE_STEPS
        call fine_stepper%init(cfg, result, mms)
        call check_true(name//': set up', result%ok .and. companions%failure == '')
        do n = 1, n_run
            dt_n = DT
            if (varying) dt_n = DT * 2.0_dp**(-real(mod((n - 1) / 5, 3), dp) / 3.0_dp)
            call stepper%advance(state, result, dt_n)
            if (.not. result%ok) error stop 'test_error_estimate_mms: a step failed'
            call companions%follow(state)
            do j = 1, FINE_STEPS
                call fine_stepper%advance(fine, result, dt_n / FINE_STEPS)
            end do
            if (varying .and. n < n_run) cycle
            if (mod(n, N_STEPS / 2) /= 0 .and. n < n_run) cycle
            call companions%estimate(state, values)
            truth = true_errors(mms, state)
            truth_time = time_errors(state, fine)
            do f = 1, N_OUTPUT_FIELDS
                call check_ratio(name, f, state%t, ': estimate ', values(f, PART_TOTAL), truth(f))
                call check_ratio(name, f, state%t, ': time part ', values(f, PART_TIME), truth_time(f))
            end do
        end do

    end subroutine check_scheme

    !> An estimate of field f at time t (what: ': estimate ' or ': time part ') within
    !> [1/RATIO_MAX, RATIO_MAX] of the truth.
    subroutine check_ratio(scheme, f, t, what, estimate, truth)
        character(len=*), intent(in) :: scheme, what
        integer, intent(in) :: f
        real(dp), intent(in) :: t, estimate, truth
        real(dp) :: ratio
        character(len=160) :: label

        ratio = estimate / truth
        write (label, '(a,a,a,a,f5.3,a,es9.2,a,es9.2,a,f6.2)') scheme, ': ', trim(FIELDS(OUTPUT_ORDER(f))%name), &
            ' at t = ', t, what, estimate, ', true ', truth, ', ratio ', ratio
        write (*, '(a)') trim(label)
        call check_true(trim(label)//' within [1/3, 3]', ratio >= 1.0_dp / RATIO_MAX .and. ratio <= RATIO_MAX)
    end subroutine check_ratio

    !> The relative L2 difference of each field's nodal values (OUTPUT_ORDER) from fine's.
    function time_errors(state, fine) result(e)
        type(state_t), intent(in) :: state, fine
        real(dp) :: e(N_OUTPUT_FIELDS)
        real(dp) :: values(0:state%s), w(0:state%s)
        integer :: k

        w = 1.0_dp
        w(0) = 0.5_dp
        w(state%s) = 0.5_dp
        do k = 1, N_OUTPUT_FIELDS
            values = field_values(state, OUTPUT_ORDER(k))
            e(k) = sqrt(sum(w * (values - field_values(fine, OUTPUT_ORDER(k)))**2) / sum(w * values**2))
        end do
    end function time_errors

    !> The relative L2 error of each field's nodal values (OUTPUT_ORDER), trapezoidal rule.
    function true_errors(mms, state) result(e)
        type(mms_t), intent(in) :: mms
        type(state_t), intent(in) :: state
        real(dp) :: e(N_OUTPUT_FIELDS)
        real(dp) :: values(0:state%s), exact(0:state%s), w(0:state%s)
        integer :: k, i, field

        w = 1.0_dp
        w(0) = 0.5_dp
        w(state%s) = 0.5_dp
        do k = 1, N_OUTPUT_FIELDS
            values = field_values(state, OUTPUT_ORDER(k))
            field = OUTPUT_ORDER(k)
            if (field == F_U) field = U_FIELD
            do i = 0, state%s
                exact(i) = mms%exact(field, state%t, state%mesh%x(i), 0)
            end do
            e(k) = sqrt(sum(w * (values - exact)**2) / sum(w * values**2))
        end do
    end function true_errors

end program test_error_estimate_mms
