!> One simulation run: initial state, time loop, diagnostics and output. The time loop
!> (stepper_m) knows nothing of HDF5; the writer (output_m) knows nothing of the scheme;
!> this module wires them together.
module run_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use ieee_arithmetic, only: ieee_is_finite
    use config_m, only: config_t, number_of_steps
    use input_vars_m, only: input_item_t, input_items, KIND_REAL, KIND_INTEGER, KIND_STRING, KIND_LOGICAL
    use iso_fortran_env, only: error_unit
    use errors_m, only: fatal, EXIT_NUMERIC, EXIT_INTERRUPTED
    use stop_signal_m, only: install_stop_handlers, stop_signal_name, ignore_file_size_signal
    use fe_m, only: mesh_nodes
    use fields_m, only: N_SERIES, S_T, S_ENERGY, S_U_END, S_PENETRATION, S_CONTACT_STRESS, S_ITERATIONS, &
                        N_OUTPUT_FIELDS, OUTPUT_ORDER
    use state_m, only: state_t, initial_state, field_values, advance_time
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: energy_monitor_t
    use restart_m, only: N_COUNTERS, COUNTER_SOLVES, COUNTER_CONTACT_STEPS, COUNTER_ENERGY, COUNTER_LAW_ENERGY, &
                         COUNTER_HAVE_LAW, COUNTER_MAX_RISE, COUNTER_STEP, COUNTER_T, COUNTER_DT_LAST, &
                         COUNTER_T_ANCHOR, COUNTER_STEP_ANCHOR, pack_state, read_checkpoint, copy_history
    use output_m, only: h5_writer_t
    use progress_m, only: progress_t
    use version_m, only: PROGRAM_VERSION, SOURCE_VERSION
    use provenance_m, only: utc_now, host_name, command_line, hdf5_version, fortran_compiler
    use material_m, only: nondim_t, nondim_groups, si_scale_t, si_scales
    implicit none
    private
    public :: run_simulation

contains

    !> Run the validated configuration cfg and write <prefix>.h5. A numerical failure
    !> finishes the file with status 'failed: ...' and stops with EXIT_NUMERIC.
    subroutine run_simulation(cfg)
        type(config_t), intent(in) :: cfg
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        type(h5_writer_t) :: writer
        type(progress_t) :: progress
        type(energy_monitor_t) :: monitor
        integer :: n, n_steps, first_step, last_written
        integer(int64) :: clock_start, clock_rate
        real(dp) :: counters(N_COUNTERS)
        character(len=320) :: failure
        character(len=:), allocatable :: interrupted

        call system_clock(clock_start, clock_rate)
        n_steps = number_of_steps(cfg%time%dt, cfg%time%t_end)
        call initial_state(cfg, state)
        call stepper%init(cfg, result)
        if (stepper%scheme%is_midpoint()) then
            call monitor%init(cfg%model, stepper%law, stepper%scheme, state, law_model=stepper%step_model)
        else
            call monitor%init(cfg%model, stepper%law, stepper%scheme, state)
        end if
        if (cfg%time%restart_from /= '') then
            ! everything the restart needs is read and checked before the new file exists
            call read_checkpoint(trim(cfg%time%restart_from), cfg, state, counters)
            monitor%energy = counters(COUNTER_ENERGY)
            monitor%law_energy = counters(COUNTER_LAW_ENERGY)
            monitor%have_law = counters(COUNTER_HAVE_LAW) > 0.0_dp
            monitor%max_rise = counters(COUNTER_MAX_RISE)
            stepper%n_solves = nint(counters(COUNTER_SOLVES), int64)
            stepper%n_contact_steps = nint(counters(COUNTER_CONTACT_STEPS), int64)
        end if
        ! a file size limit (ulimit -f) makes a write fail (exit 4), as a full disk does
        call ignore_file_size_signal()
        call writer%create(trim(cfg%output%prefix), mesh_nodes(cfg%mesh%n_elements), cfg%output%compression)
        call record_inputs(writer, cfg)
        call writer%attr_str('version', PROGRAM_VERSION)
        call record_provenance(writer)
        if (cfg%material%present) call record_scales(writer, cfg)
        call writer%attr_int('steps_planned', n_steps)
        if (cfg%time%restart_from /= '') then
            call copy_history(writer, trim(cfg%time%restart_from), state%t)
            call writer%attr_int('restart_step', state%step)
        else
            result%contact_force = stepper%law%force(state%u(state%s))
            call write_series(writer, stepper, state, monitor%energy, result)
            call write_snapshot(writer, state)
        end if

        ! from here on the .part is a valid file (inputs, provenance, the initial state), also
        ! if the run is killed or the disk fills up before its first checkpoint
        call writer%flush()
        failure = ''
        if (.not. result%ok) failure = 'setting up the solver: '//trim(result%message)
        first_step = state%step + 1
        last_written = 0
        interrupted = ''
        call install_stop_handlers()
        call progress%start(n_steps, cfg%output%quiet)
        do n = first_step, n_steps
            if (failure /= '') exit
            if (interrupted /= '') exit
            call stepper%advance(state, result)
            if (.not. result%ok) then
                failure = step_failure(n, advance_time(state, cfg%time%dt), trim(result%message))
                exit
            end if
            call monitor%observe(state)
            if (.not. ieee_is_finite(monitor%energy)) then
                failure = step_failure(n, state%t, 'the discrete energy is not finite')
                exit
            end if
            if (mod(n, cfg%output%series_every) == 0 .or. n == n_steps) &
                call write_series(writer, stepper, state, monitor%energy, result)
            if (mod(n, cfg%output%snapshot_every) == 0 .or. n == n_steps) call write_snapshot(writer, state)
            last_written = n
            if (cfg%output%checkpoint_every > 0) then
                if (mod(n, cfg%output%checkpoint_every) == 0) call write_checkpoint(writer, state, stepper, monitor)
            end if
            call progress%update(n, state%t, result%in_contact)
            ! a signal stops the run after this step, with a checkpoint of it (below)
            if (n < n_steps) interrupted = stop_signal_name()
        end do
        call progress%finish()
        if (interrupted /= '') then
            ! not the series/snapshot rows a failure adds: a restart copies the rows up to the
            ! checkpoint, so the file must hold exactly those an uninterrupted run has
            if (cfg%output%checkpoint_every == 0) then
                call write_checkpoint(writer, state, stepper, monitor)
            else if (mod(state%step, cfg%output%checkpoint_every) /= 0) then
                call write_checkpoint(writer, state, stepper, monitor)
            end if
        end if
        if (failure /= '' .and. last_written > 0 .and. last_written == state%step .and. &
            mod(last_written, cfg%output%series_every) /= 0) then
            ! the last good step was skipped by series_every: keep it in the failed file
            call write_series(writer, stepper, state, monitor%energy, result)
        end if
        if (failure /= '' .and. last_written > 0 .and. last_written == state%step .and. &
            mod(last_written, cfg%output%snapshot_every) /= 0) call write_snapshot(writer, state)

        call writer%attr_int('steps', state%step)
        call writer%attr_real('t_final', state%t)
        call writer%attr_real('wall_seconds', seconds_since(clock_start, clock_rate))
        call writer%attr_real('energy_max_relative_rise', monitor%max_rise)
        call writer%attr_str('energy_law', stepper%scheme%law())
        call writer%attr_int('solver.linear_solves', int(stepper%n_solves))
        call writer%attr_int('solver.contact_steps', int(stepper%n_contact_steps))
        call writer%attr_logical('solver.block_solver', stepper%uses_block_solver())
        if (interrupted /= '') then
            call writer%finish('interrupted: '//interrupted, keep_part=.true.)
            write (error_unit, '(a)') 'rodcontact: stopped by '//interrupted//' after '// &
                trim(step_failure(state%step, state%t, 'checkpoint written'))//"; continue with "// &
                "--set time.restart_from='"//trim(cfg%output%prefix)//".h5.part' and another output.prefix"
            flush (error_unit)
            stop EXIT_INTERRUPTED, quiet=.true.
        end if
        if (failure /= '') then
            call writer%finish('failed: '//trim(failure))
            call fatal(EXIT_NUMERIC, 'solver', trim(failure)//'; every step before it is in '// &
                       trim(cfg%output%prefix)//'.h5 (status attribute: failed)')
        end if
        call writer%finish('complete')
    end subroutine run_simulation

    !> 'step n (t = ...): reason' for the failure message and the status attribute.
    function step_failure(n, t, reason) result(text)
        integer, intent(in) :: n
        real(dp), intent(in) :: t
        character(len=*), intent(in) :: reason
        character(len=:), allocatable :: text
        character(len=40) :: buf

        write (buf, '(a,i0,a,es11.4,a)') 'step ', n, ' (t = ', t, ')'
        text = trim(buf)//': '//reason
    end function step_failure

    !> /checkpoint: the state, the level before (BDF2) and the counters to continue exactly.
    subroutine write_checkpoint(writer, state, stepper, monitor)
        type(h5_writer_t), intent(inout) :: writer
        type(state_t), intent(in) :: state
        type(stepper_t), intent(in) :: stepper
        type(energy_monitor_t), intent(in) :: monitor
        real(dp) :: counters(N_COUNTERS)
        character(len=:), allocatable :: note

        counters(COUNTER_STEP) = real(state%step, dp)
        counters(COUNTER_T) = state%t
        counters(COUNTER_SOLVES) = real(stepper%n_solves, dp)
        counters(COUNTER_CONTACT_STEPS) = real(stepper%n_contact_steps, dp)
        counters(COUNTER_ENERGY) = monitor%energy
        counters(COUNTER_LAW_ENERGY) = monitor%law_energy
        counters(COUNTER_HAVE_LAW) = merge(1.0_dp, 0.0_dp, monitor%have_law)
        counters(COUNTER_MAX_RISE) = monitor%max_rise
        counters(COUNTER_DT_LAST) = state%dt_last
        counters(COUNTER_T_ANCHOR) = state%t_anchor
        counters(COUNTER_STEP_ANCHOR) = real(state%step_anchor, dp)
        note = step_failure(state%step, state%t, '')
        note = note(1:len(note) - 2)   ! 'step n (t = ...)'
        if (allocated(state%u_prev)) then
            call writer%write_checkpoint(pack_state(state%u, state%w), counters, note, &
                                         pack_state(state%u_prev, state%w_prev))
        else
            call writer%write_checkpoint(pack_state(state%u, state%w), counters, note)
        end if
    end subroutine write_checkpoint

    !> One series entry (fields_m's SERIES); the contact stress is sigma(1,t) = -lambda
    !> (normal compliance (3.4), or the Signorini multiplier).
    subroutine write_series(writer, stepper, state, energy, result)
        type(h5_writer_t), intent(inout) :: writer
        type(stepper_t), intent(in) :: stepper
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: energy
        type(step_result_t), intent(in) :: result
        real(dp) :: values(N_SERIES)

        values(S_T) = state%t
        values(S_ENERGY) = energy
        values(S_U_END) = state%u(state%s)
        values(S_PENETRATION) = stepper%law%penetration(state%u(state%s))
        values(S_CONTACT_STRESS) = -result%contact_force
        values(S_ITERATIONS) = real(result%iterations, dp)
        call writer%append_series(values)
    end subroutine write_series

    !> One snapshot: every field of fields_m's OUTPUT_ORDER.
    subroutine write_snapshot(writer, state)
        type(h5_writer_t), intent(inout) :: writer
        type(state_t), intent(in) :: state
        real(dp) :: values(0:state%s, N_OUTPUT_FIELDS)
        integer :: k

        do k = 1, N_OUTPUT_FIELDS
            values(:, k) = field_values(state, OUTPUT_ORDER(k))
        end do
        call writer%append_snapshot(state%t, values)
    end subroutine write_snapshot

    !> Every input value as a root attribute named group.variable (SPEC section 4).
    subroutine record_inputs(writer, cfg)
        type(h5_writer_t), intent(inout) :: writer
        type(config_t), intent(in) :: cfg
        type(input_item_t), allocatable :: items(:)
        integer :: k

        items = input_items(cfg)
        do k = 1, size(items)
            associate (item => items(k))
                select case (item%kind)
                case (KIND_REAL)
                    call writer%attr_real(item%name, item%reals(1))
                case (KIND_INTEGER)
                    call writer%attr_int(item%name, item%int)
                case (KIND_STRING)
                    call writer%attr_str(item%name, item%text)
                case (KIND_LOGICAL)
                    call writer%attr_logical(item%name, item%flag)
                case default   ! polynomial coefficients, (amplitude, x_end)
                    call writer%attr_real_array(item%name, item%reals)
                end select
            end associate
        end do
    end subroutine record_inputs

    !> Where the file came from (SPEC section 4): provenance_m's root attributes.
    subroutine record_provenance(writer)
        type(h5_writer_t), intent(inout) :: writer

        call writer%attr_str('created', utc_now())
        call writer%attr_str('source_version', SOURCE_VERSION)
        call writer%attr_str('host', host_name())
        call writer%attr_str('command_line', command_line())
        call writer%attr_str('hdf5_version', hdf5_version())
        call writer%attr_str('compiler_version', fortran_compiler())
    end subroutine record_provenance

    !> With &material: the groups of (2.10) (root attributes derived.*), each scale of the
    !> nondimensional variables (scale.<name>, its SI units in scale.<name>.units) and, on
    !> every dataset measured in one, si_factor and si_units.
    subroutine record_scales(writer, cfg)
        type(h5_writer_t), intent(inout) :: writer
        type(config_t), intent(in) :: cfg
        type(nondim_t) :: nd
        type(si_scale_t), allocatable :: scales(:)
        integer :: k

        nd = nondim_groups(cfg%material)
        call writer%attr_real('derived.beta1', nd%beta1)
        call writer%attr_real('derived.beta2', nd%beta2)
        call writer%attr_real('derived.omega', nd%omega)
        call writer%attr_real('derived.delta', nd%delta)
        call writer%attr_real('derived.varsigma', nd%varsigma)
        call writer%attr_real('derived.zeta', nd%zeta)
        call writer%attr_real('derived.a_check', nd%a_check)
        call writer%attr_real('derived.alpha1', nd%alpha1)
        call writer%attr_real('derived.alpha2', nd%alpha2)
        call writer%attr_real('derived.alpha3', nd%alpha3)
        scales = si_scales(cfg%material)
        do k = 1, size(scales)
            call writer%attr_real('scale.'//trim(scales(k)%name), scales(k)%factor)
            call writer%attr_str('scale.'//trim(scales(k)%name)//'.units', trim(scales(k)%units))
            call writer%describe_si(trim(scales(k)%name), scales(k)%factor, trim(scales(k)%units))
        end do
    end subroutine record_scales

    real(dp) function seconds_since(clock_start, clock_rate)
        integer(int64), intent(in) :: clock_start, clock_rate
        integer(int64) :: clock_now

        call system_clock(clock_now)
        seconds_since = real(clock_now - clock_start, dp) / real(clock_rate, dp)
    end function seconds_since

end module run_m
