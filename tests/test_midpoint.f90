!> The midpoint rule (&time scheme = 'midpoint') on the cases it is for:
!>  1. input/impact.nml (elastic bar, no dissipation, exact pre-contact solution
!>     u(1,t) = t - t^2/2): with the penalty law the energy E^n stays within 0.1 % of E^0
!>     over t in [0, 4] through every impact, and the first contact step is the one holding
!>     t = 1 - sqrt(1 - 2 g); with the Signorini law E^n never rises (the impacts dissipate:
!>     the loss is printed) and u(1,t) <= g.
!>  2. Experiment 1's u(1,t) before contact (t <= 0.15, s = 100): order 2 in dt against a
!>     run with dt 16 times smaller (same mesh, so only the time error is measured).
program test_midpoint
    use kinds_m, only: dp
    use config_m, only: config_t
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: discrete_energy
    use contact_laws_m, only: contact_law
    use shipped_inputs_m, only: load_input, command_arguments
    use testing_m, only: check_true, check_close, test_summary
    implicit none
    character(len=:), allocatable :: source_dir, scratch_dir

    call command_arguments(source_dir, scratch_dir)
    call impact('penalty')
    call impact('signorini')
    call exp1_order()
    call test_summary('test_midpoint')

contains

    subroutine impact(law)
        character(len=*), intent(in) :: law
        type(config_t) :: cfg
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        real(dp) :: e0, e, e_old, worst_drift, worst_rise, onset, exact_onset, max_u
        integer :: n, n_steps
        character(len=160) :: detail

        call load_input(source_dir, 'impact', scratch_dir, cfg)
        cfg%contact%law = law
        cfg%time%scheme = 'midpoint'
        call initial_state(cfg, state)
        call stepper%init(cfg, result)
        call check_true('impact '//law//': set-up', result%ok, result%message)
        call discrete_energy(cfg%model, state%u, state%w, state%mesh, e0, law=stepper%law)
        e = e0
        worst_drift = 0.0_dp
        worst_rise = -huge(1.0_dp)
        onset = -1.0_dp
        max_u = state%u(state%s)
        n_steps = nint(cfg%time%t_end / cfg%time%dt)
        do n = 1, n_steps
            call stepper%advance(state, result)
            if (.not. result%ok) exit
            e_old = e
            call discrete_energy(cfg%model, state%u, state%w, state%mesh, e, law=stepper%law)
            worst_drift = max(worst_drift, abs(e - e0) / e0)
            worst_rise = max(worst_rise, (e - e_old) / e0)
            if (result%in_contact .and. onset < 0.0_dp) onset = state%t
            max_u = max(max_u, state%u(state%s))
        end do
        call check_true('impact '//law//': steps succeed', result%ok, result%message)
        exact_onset = 1.0_dp - sqrt(1.0_dp - 2.0_dp * cfg%contact%g)
        write (detail, '(a,es12.5,a,es12.5,a,es10.3)') 'first contact step ends at ', onset, &
            ', exact onset ', exact_onset, ', dt ', cfg%time%dt
        call check_true('impact '//law//': contact onset within one step', &
                        onset >= exact_onset .and. onset - cfg%time%dt < exact_onset, detail)
        write (*, '(a,a,a,es10.3,a,es10.3,a,es10.3,a,es12.5)') 'impact ', law, ': max |E^n/E^0 - 1| = ', &
            worst_drift, ', largest rise (rel. to E^0) = ', worst_rise, ', E(4)/E(0) - 1 = ', e / e0 - 1.0_dp, &
            ', max u(1,t) - g = ', max_u - cfg%contact%g
        if (law == 'penalty') then
            write (detail, '(a,es10.3)') 'max |E^n/E^0 - 1| = ', worst_drift
            call check_true('impact penalty: energy conserved to 0.1 % over [0, 4]', worst_drift <= 1.0e-3_dp, detail)
        else
            write (detail, '(a,es10.3)') 'largest rise ', worst_rise
            call check_true('impact signorini: energy never rises', worst_rise <= 1.0e-12_dp, detail)
            call check_true('impact signorini: no penetration', max_u - cfg%contact%g <= 1.0e-12_dp)
        end if
    end subroutine impact

    !> u(1, t = 0.15) of exp1 (s = 100) for dt = 1e-3 / 2^k against dt = 1e-3 / 64.
    subroutine exp1_order()
        real(dp) :: reference, errors(3), order
        integer :: k
        character(len=120) :: detail

        reference = u_end_at(1.0e-3_dp / 64.0_dp)
        do k = 1, 3
            errors(k) = abs(u_end_at(1.0e-3_dp / 2**(k - 1)) - reference)
        end do
        order = log(errors(2) / errors(3)) / log(2.0_dp)
        write (detail, '(a,3es10.3,a,f6.3)') 'errors ', errors, ', order between the finest two ', order
        write (*, '(a)') 'exp1 u(1, 0.15), midpoint: '//trim(detail)
        call check_close('exp1 u(1,t) before contact: order 2 in dt', 2.0_dp, order, 0.15_dp)
    end subroutine exp1_order

    real(dp) function u_end_at(dt)
        real(dp), intent(in) :: dt
        type(config_t) :: cfg
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        integer :: n

        call load_input(source_dir, 'exp1', scratch_dir, cfg)
        cfg%mesh%n_elements = 100
        cfg%time%dt = dt
        cfg%time%scheme = 'midpoint'
        call initial_state(cfg, state)
        call stepper%init(cfg, result)
        do n = 1, nint(0.15_dp / dt)
            call stepper%advance(state, result)
            if (.not. result%ok) error stop 'exp1_order: step failed'
            if (result%in_contact) error stop 'exp1_order: contact before t = 0.15'
        end do
        u_end_at = state%u(state%s)
    end function u_end_at

end program test_midpoint
