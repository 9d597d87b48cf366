!> One simulation run: initial state, time loop, diagnostics and output. The time loop
!> (stepper_m) knows nothing of HDF5; the writer (output_m) knows nothing of the scheme;
!> this module wires them together.
module run_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use config_m, only: config_t
    use errors_m, only: fatal, EXIT_NUMERIC
    use fe_m, only: mesh_nodes
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use scheme_m, only: F_Q, F_THETA, F_V, F_P, F_ETA
    use energy_m, only: discrete_energy, bdf2_energy, penetration
    use output_m, only: h5_writer_t
    use progress_m, only: progress_t
    use version_m, only: PROGRAM_VERSION
    implicit none
    private
    public :: run_simulation, number_of_steps

contains

    !> Number of time steps N: t_end/dt rounded to the nearest integer when t_end is a
    !> multiple of dt to round-off, else rounded up; the run ends at t_N = N dt.
    pure integer function number_of_steps(dt, t_end)
        real(dp), intent(in) :: dt, t_end
        real(dp) :: ratio

        ratio = t_end / dt
        if (abs(ratio - anint(ratio)) <= 1.0e-9_dp * ratio) then
            number_of_steps = nint(ratio)
        else
            number_of_steps = ceiling(ratio)
        end if
    end function number_of_steps

    !> Run the validated configuration cfg and write <prefix>.h5. A numerical failure
    !> finishes the file with status 'failed: ...' and stops with EXIT_NUMERIC.
    subroutine run_simulation(cfg)
        type(config_t), intent(in) :: cfg
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        type(h5_writer_t) :: writer
        type(progress_t) :: progress
        integer :: n, n_steps
        integer(int64) :: clock_start, clock_rate
        real(dp) :: energy, energy_old, law_energy, law_energy_old, max_rise
        real(dp), allocatable :: u_work(:), w_work(:, :)
        logical :: penalty, bdf2
        character(len=320) :: failure

        call system_clock(clock_start, clock_rate)
        n_steps = number_of_steps(cfg%time%dt, cfg%time%t_end)
        call initial_state(cfg, state)
        call writer%create(trim(cfg%output%prefix), mesh_nodes(cfg%mesh%n_elements))
        call record_inputs(writer, cfg)
        call writer%attr_str('version', PROGRAM_VERSION)
        call writer%attr_int('steps_planned', n_steps)

        penalty = trim(cfg%contact%law) /= 'signorini'
        bdf2 = trim(cfg%time%scheme) == 'bdf2'
        energy = discrete_energy(cfg%model, cfg%contact%eps, cfg%contact%g, state%u, state%w, penalty)
        law_energy = energy
        max_rise = 0.0_dp
        if (bdf2) allocate (u_work, mold=state%u)
        if (bdf2) allocate (w_work, mold=state%w)
        result%contact_force = 0.0_dp
        if (penalty) result%contact_force = penetration(state%u, cfg%contact%g) / cfg%contact%eps
        call write_series(writer, cfg, state, energy, result)
        call write_snapshot(writer, state)

        call stepper%init(cfg, result)
        failure = ''
        if (.not. result%ok) failure = 'setting up the solver: '//trim(result%message)
        call progress%start(n_steps, cfg%output%quiet)
        do n = 1, n_steps
            if (failure /= '') exit
            call stepper%advance(state, result)
            if (.not. result%ok) then
                write (failure, '(a,i0,a,es12.5,a)') 'step ', n, ' (t = ', real(n, dp) * cfg%time%dt, &
                    '): '//trim(result%message)
                exit
            end if
            energy_old = energy
            law_energy_old = law_energy
            energy = discrete_energy(cfg%model, cfg%contact%eps, cfg%contact%g, state%u, state%w, penalty)
            law_energy = energy
            if (bdf2 .and. n >= 2) call bdf2_energy(cfg%model, cfg%contact%eps, cfg%contact%g, state%u, state%w, &
                                                     state%u_prev, state%w_prev, u_work, w_work, penalty, law_energy)
            ! Corollary 6.2: E^n <= E^{n-1} (BDF2: its G-energy from the second step on, see
            ! energy_m); record the largest relative rise (round-off only for Euler)
            if (.not. bdf2 .or. n >= 3) &
                max_rise = max(max_rise, (law_energy - law_energy_old) / max(law_energy_old, tiny(1.0_dp)))
            if (mod(n, cfg%output%series_every) == 0 .or. n == n_steps) &
                call write_series(writer, cfg, state, energy, result)
            if (mod(n, cfg%output%snapshot_every) == 0 .or. n == n_steps) call write_snapshot(writer, state)
            call progress%update(n, state%t, result%in_contact)
        end do
        call progress%finish()

        call writer%attr_int('steps', state%step)
        call writer%attr_real('t_final', state%t)
        call writer%attr_real('wall_seconds', seconds_since(clock_start, clock_rate))
        call writer%attr_real('energy_max_relative_rise', max_rise)
        if (bdf2) then
            call writer%attr_str('energy_law', 'BDF2 G-energy (E_lin(X^n) + E_lin(2X^n - X^{n-1}))/2 + penalty(u^n)')
        else
            call writer%attr_str('energy_law', 'E^n of Corollary 6.2')
        end if
        call writer%attr_int('solver.linear_solves', int(stepper%n_solves))
        call writer%attr_int('solver.contact_steps', int(stepper%n_contact_steps))
        if (failure /= '') then
            call writer%finish('failed: '//trim(failure))
            call fatal(EXIT_NUMERIC, 'solver', trim(failure)//'; every step before it is in '// &
                       trim(cfg%output%prefix)//'.h5 (status attribute: failed)')
        end if
        call writer%finish('complete')
    end subroutine run_simulation

    !> One series entry; the contact stress is sigma(1,t) = -lambda (normal compliance (3.4),
    !> or the Signorini multiplier).
    subroutine write_series(writer, cfg, state, energy, result)
        type(h5_writer_t), intent(inout) :: writer
        type(config_t), intent(in) :: cfg
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: energy
        type(step_result_t), intent(in) :: result

        call writer%append_series(state%t, energy, state%u(state%s), penetration(state%u, cfg%contact%g), &
                                  -result%contact_force, result%iterations)
    end subroutine write_series

    subroutine write_snapshot(writer, state)
        type(h5_writer_t), intent(inout) :: writer
        type(state_t), intent(in) :: state

        call writer%append_snapshot(state%t, state%u, state%w(:, F_V), state%w(:, F_THETA), &
                                    state%w(:, F_P), state%w(:, F_Q), state%w(:, F_ETA))
    end subroutine write_snapshot

    !> Every input value as a root attribute named group.variable (SPEC section 4).
    subroutine record_inputs(writer, cfg)
        type(h5_writer_t), intent(inout) :: writer
        type(config_t), intent(in) :: cfg

        associate (m => cfg%model)
            call writer%attr_real('model.rho', m%rho)
            call writer%attr_real('model.alpha', m%alpha)
            call writer%attr_real('model.varpi', m%varpi)
            call writer%attr_real('model.gamma1', m%gamma1)
            call writer%attr_real('model.gamma2', m%gamma2)
            call writer%attr_real('model.c', m%c)
            call writer%attr_real('model.d', m%d)
            call writer%attr_real('model.r', m%r)
            call writer%attr_real('model.hbar', m%hbar)
            call writer%attr_real('model.tau0', m%tau0)
            call writer%attr_real('model.tau', m%tau)
        end associate
        call writer%attr_real('contact.g', cfg%contact%g)
        call writer%attr_real('contact.eps', cfg%contact%eps)
        call writer%attr_str('contact.law', trim(cfg%contact%law))
        call writer%attr_int('mesh.n_elements', cfg%mesh%n_elements)
        call writer%attr_real('time.dt', cfg%time%dt)
        call writer%attr_real('time.t_end', cfg%time%t_end)
        call writer%attr_str('time.scheme', trim(cfg%time%scheme))
        call writer%attr_str('time.restart_from', trim(cfg%time%restart_from))
        associate (i => cfg%initial)
            call writer%attr_real_array('initial.u0_poly', i%u0_poly)
            call writer%attr_real_array('initial.u1_poly', i%u1_poly)
            call writer%attr_real_array('initial.theta0_poly', i%theta0_poly)
            call writer%attr_real_array('initial.p0_poly', i%p0_poly)
            call writer%attr_real_array('initial.q0_poly', i%q0_poly)
            call writer%attr_real_array('initial.eta0_poly', i%eta0_poly)
            call writer%attr_real_array('initial.theta0_step', i%theta0_step)
            call writer%attr_real_array('initial.p0_step', i%p0_step)
        end associate
        call writer%attr_str('solver.method', trim(cfg%solver%method))
        call writer%attr_real('solver.tol', cfg%solver%tol)
        call writer%attr_int('solver.max_iter', cfg%solver%max_iter)
        call writer%attr_str('output.prefix', trim(cfg%output%prefix))
        call writer%attr_int('output.snapshot_every', cfg%output%snapshot_every)
        call writer%attr_int('output.series_every', cfg%output%series_every)
        call writer%attr_int('output.checkpoint_every', cfg%output%checkpoint_every)
        call writer%attr_logical('output.quiet', cfg%output%quiet)
        call writer%attr_str('input.source', trim(cfg%source))
    end subroutine record_inputs

    real(dp) function seconds_since(clock_start, clock_rate)
        integer(int64), intent(in) :: clock_start, clock_rate
        integer(int64) :: clock_now

        call system_clock(clock_now)
        seconds_since = real(clock_now - clock_start, dp) / real(clock_rate, dp)
    end function seconds_since

end module run_m
