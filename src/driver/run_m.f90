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
    use fe_m, only: mesh_nodes, evaluate_p1
    use fields_m, only: N_SERIES, S_T, S_ENERGY, S_U_END, S_PENETRATION, S_CONTACT_STRESS, S_ITERATIONS, S_DT, &
                        S_N_ELEMENTS, N_OUTPUT_FIELDS, OUTPUT_ORDER, N_FIELDS
    use state_m, only: state_t, initial_state, field_values, advance_time, land_on, copy_state, set_mesh
    use adaptive_mesh_m, only: adaptive_mesh_t, FRONT_CFL, front_speed
    use mesh_m, only: mesh_t
    use remesh_m, only: initial_mesh, remesh
    use step_control_m, only: error_estimator_t, step_controller_t, N_CONTROL_VALUES, MAX_LEVELS, &
                              pack_control, unpack_control, energy_norm
    use contact_law_m, only: contact_law_t
    use events_m, only: event_log_t, EVENT_ONSET, EVENT_RELEASE, crossing_time
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: energy_monitor_t
    use restart_m, only: N_COUNTERS, COUNTER_SOLVES, COUNTER_CONTACT_STEPS, COUNTER_ENERGY, COUNTER_LAW_ENERGY, &
                         COUNTER_HAVE_LAW, COUNTER_MAX_RISE, COUNTER_STEP, COUNTER_T, COUNTER_DT_LAST, &
                         COUNTER_T_ANCHOR, COUNTER_STEP_ANCHOR, MESH_HEADER, pack_state, read_checkpoint, copy_history
    use output_m, only: h5_writer_t
    use progress_m, only: progress_t
    use version_m, only: PROGRAM_VERSION, SOURCE_VERSION
    use provenance_m, only: utc_now, host_name, command_line, hdf5_version, fortran_compiler
    use material_m, only: nondim_t, nondim_groups, si_scale_t, si_scales
    implicit none
    private
    public :: run_simulation

    !> The progress report of an adaptive run counts t / t_end in these units.
    integer, parameter :: PROGRESS_UNITS = 1000

contains

    !> Run the validated configuration cfg and write <prefix>.h5. A numerical failure
    !> finishes the file with status 'failed: ...' and stops with EXIT_NUMERIC.
    !>
    !> The time loop takes steps of &time dt (fixed) or of the size step_control_m's
    !> controller proposes (adaptive). Adaptive steps are tried: a step whose local error
    !> estimate exceeds the tolerance is rejected (the state restored) and retried smaller,
    !> and so is a step that changes the contact state while longer than the event tolerance
    !> (max(error_tol, dt_min)), retried to end just before the crossing, so that the step
    !> across a contact event is at most that long. Steps are shortened to land on the
    !> snapshot times (&output snapshot_dt) and on t_end.
    subroutine run_simulation(cfg)
        type(config_t), intent(in) :: cfg
        type(state_t) :: state, saved
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        type(h5_writer_t) :: writer
        type(progress_t) :: progress
        type(energy_monitor_t) :: monitor
        type(error_estimator_t) :: estimator
        type(step_controller_t) :: control
        type(event_log_t) :: events
        type(adaptive_mesh_t) :: mesh
        integer :: n_steps, last_written, n_snapshot_next, n_elements_max
        integer(int64) :: clock_start, clock_rate
        real(dp) :: v_front
        real(dp) :: counters(N_COUNTERS), dt_try, target, t_before, gap_start, gap_end, est, err, proposal, event_tol, &
                    saved_dt_last
        logical :: adaptive, lands, at_snapshot, in_contact, contact_now, flipped, last, warned_forced, remeshed
        real(dp), allocatable :: control_values(:), history(:, :), event_table(:, :), mesh_data(:), x_out(:)
        character(len=320) :: failure
        character(len=:), allocatable :: interrupted

        call system_clock(clock_start, clock_rate)
        adaptive = cfg%time%adaptive
        n_steps = number_of_steps(cfg%time%dt, cfg%time%t_end)
        v_front = front_speed(cfg%model)
        if (cfg%mesh%adaptive) then
            call initial_mesh(cfg, mesh, state)
        else
            call initial_state(cfg, state)
        end if
        call stepper%init(cfg, result)
        if (cfg%mesh%adaptive) call stepper%remesh(state)
        call monitor%init(cfg%model, stepper%step_model, stepper%law, stepper%scheme, state)
        call estimator%init(stepper%scheme, state%s)
        call control%init(cfg%time%error_tol, cfg%time%dt_min, cfg%time%dt_max, stepper%scheme, cfg%time%dt)
        event_tol = max(cfg%time%error_tol, cfg%time%dt_min)
        control%scale = energy_norm(monitor%energy)
        call estimator%push(state%u, state%w, 0.0_dp)
        in_contact = stepper%law%penetration(state%u(state%s)) > 0.0_dp
        if (cfg%time%restart_from /= '') then
            ! everything the restart needs is read and checked before the new file exists
            call read_checkpoint(trim(cfg%time%restart_from), cfg, state, counters, control_values, history, &
                                 event_table, mesh_data)
            if (cfg%mesh%adaptive) then
                call restore_mesh(mesh, mesh_data, state%mesh)
                call set_mesh(state, mesh%nodes())
                call stepper%remesh(state)
                call estimator%resize(state%s)
                call monitor%resize(state)
            end if
            monitor%energy = counters(COUNTER_ENERGY)
            monitor%law_energy = counters(COUNTER_LAW_ENERGY)
            monitor%have_law = counters(COUNTER_HAVE_LAW) > 0.0_dp
            monitor%max_rise = counters(COUNTER_MAX_RISE)
            stepper%n_solves = nint(counters(COUNTER_SOLVES), int64)
            stepper%n_contact_steps = nint(counters(COUNTER_CONTACT_STEPS), int64)
            call estimator%reset()
            call estimator%push(state%u, state%w, state%dt_last)
            in_contact = stepper%law%penetration(state%u(state%s)) > 0.0_dp
            if (allocated(control_values) .and. allocated(history)) then
                call unpack_control(control_values(:N_CONTROL_VALUES), history, control, estimator)
                in_contact = control_values(N_CONTROL_VALUES + 1) > 0.0_dp
                monitor%max_rise_step_change = control_values(N_CONTROL_VALUES + 2)
            end if
            call events%restore(event_table)
        end if
        n_snapshot_next = 0
        if (cfg%output%snapshot_dt > 0.0_dp) n_snapshot_next = floor(state%t / cfg%output%snapshot_dt * (1.0_dp + 1.0e-12_dp)) + 1
        ! a file size limit (ulimit -f) makes a write fail (exit 4), as a full disk does
        call ignore_file_size_signal()
        x_out = output_grid(cfg)
        call writer%create(trim(cfg%output%prefix), x_out, cfg%output%compression)
        call record_inputs(writer, cfg)
        call writer%attr_str('version', PROGRAM_VERSION)
        call record_provenance(writer)
        if (cfg%material%present) call record_scales(writer, cfg)
        if (.not. adaptive) call writer%attr_int('steps_planned', n_steps)
        if (cfg%time%restart_from /= '') then
            call copy_history(writer, trim(cfg%time%restart_from), state%t)
            call writer%attr_int('restart_step', state%step)
        else
            result%contact_force = stepper%law%force(state%u(state%s))
            call write_series(writer, stepper, state, monitor%energy, result)
            call write_snapshot(writer, state, x_out)
        end if
        n_elements_max = state%s

        ! from here on the .part is a valid file (inputs, provenance, the initial state), also
        ! if the run is killed or the disk fills up before its first checkpoint
        call writer%flush()
        failure = ''
        if (.not. result%ok) failure = 'setting up the solver: '//trim(result%message)
        last_written = 0
        interrupted = ''
        warned_forced = .false.
        call install_stop_handlers()
        if (adaptive) then
            call progress%start(PROGRESS_UNITS, cfg%output%quiet)
        else
            call progress%start(n_steps, cfg%output%quiet)
        end if
        do
            if (failure /= '' .or. interrupted /= '') exit
            if (finished(state)) exit
            call choose_step(state, dt_try, target, lands, at_snapshot)
            t_before = state%t
            saved_dt_last = state%dt_last
            gap_start = state%u(state%s) - stepper%law%g
            if (adaptive) call copy_state(state, saved)
            call stepper%advance(state, result, dt_try)
            if (.not. result%ok) then
                failure = step_failure(state%step + 1, advance_time(state, dt_try), trim(result%message))
                exit
            end if
            call contact_state(stepper%law, state, result, contact_now, gap_end)
            flipped = contact_now .neqv. in_contact
            est = 0.0_dp
            err = -1.0_dp
            if (estimator%ready() .and. .not. flipped) then
                est = estimator%estimate(cfg%model, state%u, state%w, dt_try, state%mesh)
                err = control%ratio(est)
            end if
            if (adaptive) then
                if (flipped .and. dt_try > event_tol) then
                    ! retry to end just before the crossing (or, close to it, across it
                    ! within event_tol)
                    call undo_step(stepper, result, saved, state)
                    control%dt_next = retry_before_event(dt_try, gap_start, gap_end, event_tol)
                    control%no_growth = .true.
                    cycle
                end if
                if (err > 1.0_dp .and. dt_try > cfg%time%dt_min) then
                    call undo_step(stepper, result, saved, state)
                    call control%reject(dt_try, err)
                    cycle
                end if
                if (err > 1.0_dp) then
                    control%n_forced = control%n_forced + 1
                    if (.not. warned_forced) call warn_forced(state%t, cfg%time%dt_min)
                    warned_forced = .true.
                end if
            end if
            ! the step is accepted
            if (lands .and. adaptive) call land_on(state, target)
            if (flipped) then
                call events%add(crossing_time(t_before, dt_try, gap_start, gap_end), &
                                merge(EVENT_ONSET, EVENT_RELEASE, contact_now))
                if (adaptive) call estimator%reset()
            end if
            in_contact = contact_now
            call estimator%push(state%u, state%w, dt_try)
            if (err >= 0.0_dp) then
                control%error_sum = control%error_sum + est
                control%n_estimated = control%n_estimated + 1
            end if
            if (adaptive) then
                proposal = control%dt_next
                call control%accept(dt_try, err)
                ! a step shortened to land on an output time says nothing against the proposal
                if (lands) control%dt_next = max(control%dt_next, min(proposal, cfg%time%dt_max))
            end if
            call monitor%observe(state, step_changed=dt_try /= saved_dt_last)
            if (.not. ieee_is_finite(monitor%energy)) then
                failure = step_failure(state%step, state%t, 'the discrete energy is not finite')
                exit
            end if
            control%scale = max(control%scale, energy_norm(monitor%energy))
            if (at_snapshot) n_snapshot_next = n_snapshot_next + 1
            last = finished(state)
            if (mod(state%step, cfg%output%series_every) == 0 .or. last) &
                call write_series(writer, stepper, state, monitor%energy, result)
            if (snapshot_due(state%step, at_snapshot) .or. last) call write_snapshot(writer, state, x_out)
            last_written = state%step
            if (cfg%mesh%adaptive .and. .not. last .and. mod(state%step, cfg%mesh%remesh_every) == 0) then
                call remesh(mesh, state, stepper, estimator, monitor, remeshed)
                n_elements_max = max(n_elements_max, state%s)
            end if
            if (cfg%output%checkpoint_every > 0) then
                if (mod(state%step, cfg%output%checkpoint_every) == 0) call write_checkpoint(writer, state, stepper, &
                    monitor, control, estimator, events, in_contact, mesh)
            end if
            if (adaptive) then
                call progress%update(progress_position(state%t), state%t, result%in_contact)
            else
                call progress%update(state%step, state%t, result%in_contact)
            end if
            ! a signal stops the run after this step, with a checkpoint of it (below)
            if (.not. last) interrupted = stop_signal_name()
        end do
        call progress%finish()
        if (interrupted /= '') then
            ! not the series/snapshot rows a failure adds: a restart copies the rows up to the
            ! checkpoint, so the file must hold exactly those an uninterrupted run has
            if (cfg%output%checkpoint_every == 0) then
                call write_checkpoint(writer, state, stepper, monitor, control, estimator, events, in_contact, mesh)
            else if (mod(state%step, cfg%output%checkpoint_every) /= 0) then
                call write_checkpoint(writer, state, stepper, monitor, control, estimator, events, in_contact, mesh)
            end if
        end if
        if (failure /= '' .and. last_written > 0 .and. last_written == state%step .and. &
            mod(last_written, cfg%output%series_every) /= 0) then
            ! the last good step was skipped by series_every: keep it in the failed file
            call write_series(writer, stepper, state, monitor%energy, result)
        end if
        if (failure /= '' .and. last_written > 0 .and. last_written == state%step .and. &
            .not. snapshot_due(last_written, .false.)) call write_snapshot(writer, state, x_out)

        call writer%write_events(events%times(), events%kinds())
        call writer%attr_int('steps', state%step)
        call writer%attr_real('t_final', state%t)
        call writer%attr_real('wall_seconds', seconds_since(clock_start, clock_rate))
        call writer%attr_real('energy_max_relative_rise', monitor%max_rise)
        if (monitor%scheme_law%constant_steps .and. (adaptive .or. cfg%output%snapshot_dt > 0.0_dp)) &
            call writer%attr_real('energy_max_relative_rise_step_change', monitor%max_rise_step_change)
        call writer%attr_str('energy_law', trim(monitor%scheme_law%text))
        call writer%attr_int('solver.linear_solves', int(stepper%n_solves))
        call writer%attr_int('solver.contact_steps', int(stepper%n_contact_steps))
        call writer%attr_logical('solver.block_solver', stepper%uses_block_solver())
        call record_time_error(writer, control, adaptive)
        if (cfg%mesh%adaptive) then
            call writer%attr_int('mesh.remeshes', state%mesh%n_remeshes())
            call writer%attr_int('mesh.n_elements_max', n_elements_max)
            call writer%attr_real('energy_max_relative_rise_remesh', state%mesh%max_rise_remesh())
        end if
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

    contains

        !> Has the run reached its end? Fixed steps without snapshot_dt: n_steps steps (as
        !> always, t_N = N dt); otherwise t_end (adaptive) or N dt (fixed), to round-off.
        logical function finished(state)
            type(state_t), intent(in) :: state

            if (.not. adaptive .and. cfg%output%snapshot_dt <= 0.0_dp) then
                finished = state%step >= n_steps
            else
                finished = state%t >= t_stop() - 1.0e-9_dp * merge(cfg%time%dt_min, cfg%time%dt, adaptive)
            end if
        end function finished

        !> The end time: t_end (adaptive), N dt (fixed: number_of_steps).
        real(dp) function t_stop()
            if (adaptive) then
                t_stop = cfg%time%t_end
            else
                t_stop = real(n_steps, dp) * cfg%time%dt
            end if
        end function t_stop

        !> The next step: &time dt or the controller's proposal (at most growth_max times the
        !> last step), shortened to end on the next snapshot time or the end (target; lands).
        !> Adaptive steps that would leave less than a step to the target take half the
        !> distance instead, so no tiny step follows.
        subroutine choose_step(state, dt_try, target, lands, at_snapshot)
            type(state_t), intent(in) :: state
            real(dp), intent(out) :: dt_try, target
            logical, intent(out) :: lands, at_snapshot
            real(dp) :: remaining, slack

            if (adaptive) then
                dt_try = control%dt_next
                if (state%dt_last > 0.0_dp) dt_try = min(dt_try, control%growth_max * state%dt_last)
                dt_try = min(max(dt_try, cfg%time%dt_min), cfg%time%dt_max)
                if (cfg%mesh%adaptive .and. v_front > 0.0_dp) &
                    dt_try = max(min(dt_try, FRONT_CFL * minval(state%mesh%h) / v_front), cfg%time%dt_min)
                slack = 1.0e-9_dp * dt_try
            else
                dt_try = cfg%time%dt
                slack = 1.0e-9_dp * cfg%time%dt
            end if
            target = t_stop()
            at_snapshot = .false.
            if (cfg%output%snapshot_dt > 0.0_dp) then
                ! a snapshot time that is t_end to round-off is the target (not t_end): so
                ! a run to t_end takes the steps a longer run takes up to there
                if (real(n_snapshot_next, dp) * cfg%output%snapshot_dt <= target + slack) then
                    target = real(n_snapshot_next, dp) * cfg%output%snapshot_dt
                    at_snapshot = .true.
                end if
            end if
            remaining = target - state%t
            lands = dt_try >= remaining - slack
            if (lands) then
                if (adaptive .or. dt_try > remaining + slack) dt_try = remaining
            else if (adaptive .and. dt_try > 0.5_dp * remaining) then
                dt_try = 0.5_dp * remaining
            end if
            at_snapshot = at_snapshot .and. lands
        end subroutine choose_step

        !> Snapshot after step n: at the snapshot times (snapshot_dt), else every snapshot_every steps.
        logical function snapshot_due(n, at_snapshot)
            integer, intent(in) :: n
            logical, intent(in) :: at_snapshot

            if (cfg%output%snapshot_dt > 0.0_dp) then
                snapshot_due = at_snapshot
            else
                snapshot_due = mod(n, cfg%output%snapshot_every) == 0
            end if
        end function snapshot_due

        !> Where the progress report stands in an adaptive run: t / t_end in PROGRESS_UNITS.
        integer function progress_position(t)
            real(dp), intent(in) :: t

            progress_position = max(1, min(PROGRESS_UNITS, nint(real(PROGRESS_UNITS, dp) * t / cfg%time%t_end)))
        end function progress_position

    end subroutine run_simulation

    !> The contact state after a step, as events are counted: penalty, u^n(1) > g (the end
    !> position; the midpoint rule's force may act a step longer); Signorini, an active
    !> multiplier. gap: the gap at the step's end the crossing time is interpolated to,
    !> u^n(1) - g (penalty) or the trial gap (Signorini, whose u^n(1) stops at g).
    subroutine contact_state(law, state, result, in_contact, gap)
        type(contact_law_t), intent(in) :: law
        type(state_t), intent(in) :: state
        type(step_result_t), intent(in) :: result
        logical, intent(out) :: in_contact
        real(dp), intent(out) :: gap

        if (law%is_signorini()) then
            in_contact = result%in_contact
            gap = result%trial_gap
        else
            gap = state%u(state%s) - law%g
            in_contact = gap > 0.0_dp
        end if
    end subroutine contact_state

    !> A rejected step: the state as before it, and the step's contact count taken back.
    subroutine undo_step(stepper, result, saved, state)
        type(stepper_t), intent(inout) :: stepper
        type(step_result_t), intent(in) :: result
        type(state_t), intent(in) :: saved
        type(state_t), intent(inout) :: state

        if (result%in_contact) stepper%n_contact_steps = stepper%n_contact_steps - 1
        call copy_state(saved, state)
    end subroutine undo_step

    !> The retry of a step of size dt that changed the contact state: the trial gap went
    !> from gap_start to gap_end; end event_tol/2 before the interpolated crossing, or take
    !> a step of event_tol across it when the crossing is that close (events_m's crossing_time;
    !> a release from a zero gap (Signorini) halves the step).
    pure real(dp) function retry_before_event(dt, gap_start, gap_end, event_tol) result(dt_new)
        real(dp), intent(in) :: dt, gap_start, gap_end, event_tol
        real(dp) :: to_crossing

        to_crossing = crossing_time(0.0_dp, dt, gap_start, gap_end)
        if (to_crossing >= dt) to_crossing = 0.5_dp * dt
        dt_new = to_crossing - 0.5_dp * event_tol
        if (to_crossing <= event_tol) dt_new = event_tol
        dt_new = min(dt_new, dt - 0.5_dp * event_tol)
    end function retry_before_event

    !> Once per run: the error estimate exceeded the tolerance at the smallest step allowed.
    subroutine warn_forced(t, dt_min)
        real(dp), intent(in) :: t, dt_min

        write (error_unit, '(a,es11.4,a,es10.3,a)') 'rodcontact: warning: at t = ', t, &
            ' a step of dt_min = ', dt_min, ' exceeds time.error_tol and is accepted; lower time.dt_min ' // &
            '(the count is in the root attribute time_steps_at_dt_min)'
        flush (error_unit)
    end subroutine warn_forced

    !> The time error of the run (root attributes): the sum of the local error estimates of
    !> the accepted steps (step_control_m), absolute (energy norm) and relative to the largest
    !> energy norm of the solution; with it the counts of the step control.
    subroutine record_time_error(writer, control, adaptive)
        type(h5_writer_t), intent(inout) :: writer
        type(step_controller_t), intent(in) :: control
        logical, intent(in) :: adaptive

        call writer%attr_real('time_error_estimate', control%error_sum)
        call writer%attr_real('time_error_estimate_relative', control%error_sum / max(control%scale, tiny(1.0_dp)))
        call writer%attr_int('time_steps_estimated', control%n_estimated)
        if (.not. adaptive) return
        call writer%attr_int('time_steps_rejected', control%n_rejected)
        call writer%attr_int('time_steps_at_dt_min', control%n_forced)
    end subroutine record_time_error


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

    !> /checkpoint: the state, the level before (BDF2), the counters, the step control
    !> (step_control_m, with the contact state in_contact appended) and the events, so that
    !> the run continues exactly.
    subroutine write_checkpoint(writer, state, stepper, monitor, control, estimator, events, in_contact, mesh)
        type(h5_writer_t), intent(inout) :: writer
        type(state_t), intent(in) :: state
        type(stepper_t), intent(in) :: stepper
        type(energy_monitor_t), intent(in) :: monitor
        type(step_controller_t), intent(in) :: control
        type(error_estimator_t), intent(in) :: estimator
        type(event_log_t), intent(in) :: events
        logical, intent(in) :: in_contact
        type(adaptive_mesh_t), intent(in) :: mesh    !< (used when allocated: &mesh adaptive)
        real(dp) :: counters(N_COUNTERS), values(N_CONTROL_VALUES + 2)
        real(dp) :: history(0:state%s, (1 + N_FIELDS) * MAX_LEVELS)
        real(dp), allocatable :: previous(:, :), mesh_values(:)   !< left unallocated (absent) when not held
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
        call pack_control(control, estimator, values(:N_CONTROL_VALUES), history)
        values(N_CONTROL_VALUES + 1) = merge(1.0_dp, 0.0_dp, in_contact)
        values(N_CONTROL_VALUES + 2) = monitor%max_rise_step_change
        note = step_failure(state%step, state%t, '')
        note = note(1:len(note) - 2)   ! 'step n (t = ...)'
        ! an unallocated actual argument is an absent optional one (the level before: multistep
        ! schemes; the mesh: &mesh adaptive)
        if (allocated(state%u_prev)) previous = pack_state(state%u_prev, state%w_prev)
        if (allocated(mesh%k)) mesh_values = pack_mesh(mesh, state%mesh)
        call writer%write_checkpoint(pack_state(state%u, state%w), counters, note, previous, control=values, &
                                     history=history, events=events%packed(), mesh=mesh_values)
    end subroutine write_checkpoint

    !> The adaptive mesh in a checkpoint: the field scales (1 + N_FIELDS), the remesh
    !> counters of the state's mesh (2), then the node keys (restore_mesh is the inverse).
    function pack_mesh(mesh, state_mesh) result(values)
        type(adaptive_mesh_t), intent(in) :: mesh
        type(mesh_t), intent(in) :: state_mesh
        real(dp), allocatable :: values(:)

        values = [mesh%scale, state_mesh%max_rise_remesh(), real(state_mesh%n_remeshes(), dp), real(mesh%k, dp)]
    end function pack_mesh

    !> The adaptive mesh of a checkpoint (pack_mesh), on mesh initialised for this run; the
    !> remesh counters go to the state's mesh.
    subroutine restore_mesh(mesh, values, state_mesh)
        type(adaptive_mesh_t), intent(inout) :: mesh
        real(dp), intent(in) :: values(:)
        type(mesh_t), intent(inout) :: state_mesh
        integer :: n

        n = 1 + N_FIELDS
        mesh%scale = values(1:n)
        call state_mesh%restore_remesh_counters(nint(values(n + 2)), values(n + 1))
        call mesh%set_keys(nint(values(MESH_HEADER + 1:), int64))
    end subroutine restore_mesh

    !> The fixed grid of the snapshots (/mesh/x): &output n_points uniform points, by
    !> default the nodes of the coarsest mesh.
    function output_grid(cfg) result(x)
        type(config_t), intent(in) :: cfg
        real(dp), allocatable :: x(:)

        if (cfg%output%n_points > 0) then
            x = mesh_nodes(cfg%output%n_points - 1)
        else
            x = mesh_nodes(cfg%mesh%n_elements)
        end if
    end function output_grid

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
        values(S_DT) = state%dt_last
        values(S_N_ELEMENTS) = real(state%s, dp)
        call writer%append_series(values)
    end subroutine write_series

    !> One snapshot: every field of fields_m's OUTPUT_ORDER on the output grid x_out (the
    !> P1 solution evaluated there, unless x_out are the nodes), and on a graded mesh its
    !> nodal values in /snapshots/native.
    subroutine write_snapshot(writer, state, x_out)
        type(h5_writer_t), intent(inout) :: writer
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: x_out(:)
        real(dp) :: values(0:state%s, N_OUTPUT_FIELDS), on_grid(size(x_out), N_OUTPUT_FIELDS), x(0:state%s)
        integer :: k

        do k = 1, N_OUTPUT_FIELDS
            values(:, k) = field_values(state, OUTPUT_ORDER(k))
        end do
        if (size(x_out) == state%s + 1 .and. state%mesh%is_uniform()) then
            call writer%append_snapshot(state%t, values)
            return
        end if
        x = state%mesh%x
        do k = 1, N_OUTPUT_FIELDS
            on_grid(:, k) = evaluate_p1(x, values(:, k), x_out)
        end do
        call writer%append_snapshot(state%t, on_grid)
        if (.not. state%mesh%is_uniform()) call writer%append_native(x, values)
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
