!> One simulation run, from the initial state (or a checkpoint) to the end, with its output:
!> the parts do the work (docs/architecture.md, 'One adaptive step'), this module says when.
module run_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64, error_unit
    use config_m, only: config_t, number_of_steps
    use errors_m, only: fatal, check_allocation, EXIT_NUMERIC, EXIT_INTERRUPTED
    use stop_signal_m, only: install_stop_handlers, stop_signal_arrived, stop_signal_name
    use state_m, only: state_t, initial_state, set_mesh
    use adaptive_mesh_m, only: adaptive_mesh_t, initial_mesh
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: energy_monitor_t
    use checkpoint_m, only: checkpoint_t
    use step_driver_m, only: step_driver_t
    use events_m, only: event_log_t, EVENT_ONSET, EVENT_RELEASE
    use strings_m, only: int_str, format_real, short_real
    use material_m, only: time_scale
    use output_m, only: h5_writer_t
    use restart_m, only: read_checkpoint, copy_history
    use run_output_m, only: output_grid, write_series, write_dense_series, write_snapshot, write_dense_snapshots, &
                            write_error_estimate
    use error_companion_m, only: error_companions_t
    use run_attributes_m, only: record_inputs, dataset_scales, record_scales, record_results, &
                                record_provenance
    use progress_m, only: progress_t
    use version_m, only: PROGRAM_VERSION, SOURCE_VERSION
    implicit none
    private
    public :: run_simulation

    !> The progress report of an adaptive run counts t / t_end in these units.
    integer, parameter :: PROGRESS_UNITS = 1000

    !> Everything one run holds.
    type :: run_t
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        type(energy_monitor_t) :: monitor
        type(step_driver_t) :: driver
        type(adaptive_mesh_t) :: mesh          !< &mesh adaptive only
        type(error_companions_t) :: companions !< &output error_estimate only
        type(h5_writer_t) :: writer
        real(dp), allocatable :: x_out(:)      !< the fixed output grid
        integer :: n_steps = 0                 !< fixed steps: number_of_steps
        integer :: n_snapshot_next = 0         !< with snapshot_dt: the next snapshot is at n snapshot_dt
        integer :: n_series_next = 0           !< with series_dt: the next series entry is at n series_dt
        integer :: n_elements_max = 0
        integer :: last_written = 0            !< the last step whose output was written
        integer :: checkpointed = -1           !< step of the file's last checkpoint
        integer(int64) :: clock_start = 0, clock_rate = 1
        real(dp) :: wall_before = 0.0_dp       !< a restart's: the wall seconds up to its checkpoint
        logical :: in_place = .false.          !< resuming its own <prefix>.h5.part (restart_m)
        character(len=:), allocatable :: resume_command   !< how to continue it, for the stop message
    end type run_t

contains

    !> Run the validated configuration cfg and write <prefix>.h5. A numerical failure
    !> finishes the file with status 'failed: ...' and stops with EXIT_NUMERIC; a stop
    !> signal writes a checkpoint, leaves <prefix>.h5.part and stops with EXIT_INTERRUPTED,
    !> saying how to continue it: resume_command (the program's own command line with --resume).
    subroutine run_simulation(cfg, resume_command)
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in), optional :: resume_command
        type(run_t), allocatable :: run   ! on the heap: larger than the stack variable limit
        character(len=320) :: failure
        character(len=:), allocatable :: interrupted
        integer :: stat
        character(len=256) :: message

        allocate (run, stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the run')
        call system_clock(run%clock_start, run%clock_rate)
        run%resume_command = 'the same command and --resume'
        if (present(resume_command)) run%resume_command = resume_command
        ! before anything is written: a stop signal from here on (also one that arrived while
        ! the process was starting, pending and blocked) stops the run with a checkpoint,
        ! at the latest before its first step
        call install_stop_handlers()
        call set_up(run, cfg)
        call open_output(run, cfg)
        failure = ''
        if (.not. run%result%ok) failure = 'setting up the solver: '//trim(run%result%message)
        call time_loop(run, cfg, failure, interrupted)
        call close_output(run, cfg, failure, interrupted)
    end subroutine run_simulation

    !> The initial state (on the first adaptive mesh, with &mesh adaptive), the stepper, the
    !> energy monitor and the step driver on it; with &time restart_from, all of them as the
    !> checkpoint left them (read and checked before the new file exists).
    subroutine set_up(run, cfg)
        type(run_t), intent(inout) :: run
        type(config_t), intent(in) :: cfg
        type(checkpoint_t) :: ckpt

        run%n_steps = number_of_steps(cfg%time%dt, cfg%time%t_end)
        if (cfg%mesh%adaptive) then
            call initial_mesh(cfg, run%mesh, run%state)
        else
            call initial_state(cfg, run%state)
        end if
        call run%stepper%init(cfg, run%result)
        if (cfg%mesh%adaptive) call run%stepper%remesh(run%state)
        call run%monitor%init(run%stepper%model, run%stepper%step_model, run%stepper%law, run%stepper%scheme, &
                              run%state)
        call run%driver%init(cfg, run%state, run%stepper, run%monitor)
        ! keys: allocated, and so present, on an adaptive mesh only
        if (cfg%output%error_estimate) call run%companions%init(cfg, run%state, keys=run%mesh%k)
        if (cfg%time%restart_from /= '') then
            call read_checkpoint(trim(cfg%time%restart_from), cfg, ckpt, run%in_place)
            call checkpoint(run, cfg, ckpt)
        end if
        if (cfg%output%snapshot_dt > 0.0_dp) &
            run%n_snapshot_next = floor(run%state%t / cfg%output%snapshot_dt * (1.0_dp + 1.0e-12_dp)) + 1
        if (cfg%output%series_dt > 0.0_dp) &
            run%n_series_next = floor(run%state%t / cfg%output%series_dt * (1.0_dp + 1.0e-12_dp)) + 1
        run%n_elements_max = max(run%state%s, run%n_elements_max)   ! a restart's: those held before
    end subroutine set_up

    !> Create <prefix>.h5.part with the inputs, the provenance and the initial state (or the
    !> history up to the checkpoint restarted from), and flush it: from here on the .part
    !> is a valid file, also if the run is killed or the disk fills up before its first
    !> checkpoint.
    subroutine open_output(run, cfg)
        type(run_t), intent(inout) :: run
        type(config_t), intent(in) :: cfg

        call output_grid(cfg, run%x_out)
        call run%writer%create(trim(cfg%output%prefix), run%x_out, cfg%output%compression, run%in_place, &
                               dataset_scales(cfg))
        call record_inputs(run%writer, cfg)
        call record_provenance(run%writer, PROGRAM_VERSION, SOURCE_VERSION)
        if (cfg%material%present) call record_scales(run%writer, cfg)
        if (.not. cfg%time%adaptive) call run%writer%attr('steps_planned', run%n_steps)
        if (cfg%time%restart_from /= '') then
            call copy_history(run%writer, trim(cfg%time%restart_from), run%state%t)
            call run%writer%attr('restart_step', run%state%step)
        else
            call write_series(run%writer, run%stepper, run%state, run%monitor, run%result, initial=.true.)
            call snapshot(run, cfg)
        end if
        call run%writer%flush()
    end subroutine open_output

    !> The time loop: accepted steps with their output, remeshes and checkpoints, until the
    !> end, a numerical failure or a stop signal (interrupted: its name; after the step in
    !> progress, or before the first step when the signal came during the set-up).
    subroutine time_loop(run, cfg, failure, interrupted)
        type(run_t), intent(inout) :: run
        type(config_t), intent(in) :: cfg
        character(len=*), intent(inout) :: failure
        character(len=:), allocatable, intent(out) :: interrupted
        type(progress_t) :: progress
        logical :: at_snapshot, last, remeshed, dense_at_end
        real(dp) :: t_before, scale
        real(dp), allocatable :: t_land   !< the snapshot time the steps land on (none: not allocated)

        interrupted = stop_signal_name()
        scale = time_scale(cfg%material)
        call progress%start(merge(PROGRESS_UNITS, run%n_steps, cfg%time%adaptive), cfg%output%quiet, &
                            merge(' s', '  ', cfg%material%present))
        do
            if (failure /= '' .or. interrupted /= '') exit
            if (finished(run, cfg)) exit
            associate (state => run%state)
                t_before = state%t
                if (cfg%output%snapshot_dt > 0.0_dp .and. cfg%output%snapshot_land) &
                    t_land = real(run%n_snapshot_next, dp) * cfg%output%snapshot_dt
                call run%driver%take_step(state, run%stepper, run%monitor, run%result, t_stop(run, cfg), &
                                          at_snapshot, failure, t_land)
                if (failure /= '') exit
                if (cfg%output%error_estimate) call run%companions%follow(state)
                if (at_snapshot) run%n_snapshot_next = run%n_snapshot_next + 1
                last = finished(run, cfg)
                call write_dense_output(run, cfg, t_before, dense_at_end)
                if (cfg%output%series_dt > 0.0_dp) then
                    if (last .and. .not. dense_at_end) &
                        call write_series(run%writer, run%stepper, state, run%monitor, run%result)
                else if (mod(state%step, cfg%output%series_every) == 0 .or. last) then
                    call write_series(run%writer, run%stepper, state, run%monitor, run%result)
                end if
                if (snapshot_due(cfg, state%step, at_snapshot) .or. (last .and. .not. dense_at_end)) &
                    call snapshot(run, cfg)
                run%last_written = state%step
                if (cfg%mesh%adaptive .and. .not. last .and. mod(state%step, cfg%mesh%remesh_every) == 0) then
                    call run%driver%remesh(run%mesh, state, run%stepper, run%monitor, remeshed)
                    if (remeshed .and. cfg%output%error_estimate) call run%companions%remesh(run%mesh%k)
                    run%n_elements_max = max(run%n_elements_max, state%s)
                end if
                if (cfg%output%checkpoint_every > 0) then
                    if (mod(state%step, cfg%output%checkpoint_every) == 0) call checkpoint(run, cfg)
                end if
                call progress%update(merge(progress_position(cfg, state%t), state%step, cfg%time%adaptive), &
                                     scale * state%t, run%result%in_contact)
                ! a signal stops the run after this step, with a checkpoint of it (close_output)
                if (.not. last) then
                    if (stop_signal_arrived()) interrupted = stop_signal_name()
                end if
            end associate
        end do
        call progress%finish()
    end subroutine time_loop

    !> Finish the file: after a stop signal a checkpoint of the last step (status
    !> 'interrupted'), after a failure the last good step if series_every or the snapshots
    !> skipped it (status 'failed'); then the results and the status.
    subroutine close_output(run, cfg, failure, interrupted)
        type(run_t), intent(inout) :: run
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in) :: failure, interrupted
        real(dp) :: wall

        if (interrupted /= '') then
            ! not the series/snapshot rows a failure adds: a restart copies the rows up to the
            ! checkpoint, so the file must hold exactly those an uninterrupted run has; the
            ! checkpoint unless the file has one of the step (none before a restart's first)
            if (run%checkpointed /= run%state%step) call checkpoint(run, cfg)
        end if
        if (failure /= '' .and. run%last_written > 0 .and. run%last_written == run%state%step) then
            ! the last good step was skipped by series_every or the snapshots: keep it in the failed file
            if (mod(run%last_written, cfg%output%series_every) /= 0) &
                call write_series(run%writer, run%stepper, run%state, run%monitor, run%result)
            if (.not. snapshot_due(cfg, run%last_written, .false.)) call snapshot(run, cfg)
        end if
        wall = wall_seconds(run)
        call record_results(run%writer, cfg, run%state, run%stepper, run%monitor, run%driver, run%companions, &
                            wall, run%n_elements_max)
        if (interrupted /= '') then
            call run%writer%finish('interrupted: '//interrupted, keep_part=.true.)
            call report_end(run, cfg, '.h5.part', 'interrupted: '//interrupted, wall)
            write (error_unit, '(a)') 'rodcontact: stopped by '//interrupted//' after '// &
                run%driver%step_label(run%state%step, run%state%t, 'checkpoint written')//'; continue it with: '// &
                run%resume_command
            flush (error_unit)
            stop EXIT_INTERRUPTED, quiet=.true.
        end if
        if (failure /= '') then
            call run%writer%finish('failed: '//trim(failure))
            call report_end(run, cfg, '.h5', 'failed', wall)
            call fatal(EXIT_NUMERIC, 'solver', trim(failure)//'; every step before it is in '// &
                       trim(cfg%output%prefix)//'.h5 (status attribute: failed)')
        end if
        call run%writer%finish('complete')
        call report_end(run, cfg, '.h5', 'complete', wall)
    end subroutine close_output

    !> The run's last line on stderr (unless &output quiet; README, 'Usage'): where its
    !> file is, its status, the contact onsets and releases (how many, the first of each, to
    !> 15 digits as --summary prints it) and the wall time, with &material in seconds.
    !> suffix: '.h5', or '.h5.part' for a file left to be continued.
    subroutine report_end(run, cfg, suffix, status, wall)
        type(run_t), intent(in) :: run
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in) :: suffix, status
        real(dp), intent(in) :: wall
        type(event_log_t) :: events
        real(dp) :: scale
        character(len=:), allocatable :: unit, system

        if (cfg%output%quiet) return
        scale = time_scale(cfg%material)
        unit = ''
        system = '; times nondimensional'
        if (cfg%material%present) then
            unit = ' s'
            system = ''
        end if
        events = run%driver%events_log()
        write (error_unit, '(a)') 'rodcontact: '//trim(cfg%output%prefix)//suffix//' '//status//'; contact: '// &
            event_summary(scale * events%times(), events%kinds(), EVENT_ONSET, 'onset', unit)//', '// &
            event_summary(scale * events%times(), events%kinds(), EVENT_RELEASE, 'release', unit)//'; '// &
            int_str(run%state%step)//' steps, t = '//short_real(scale * run%state%t)//unit// &
            ', wall '//short_real(wall)//' s'//system
        flush (error_unit)
    end subroutine report_end

    !> '<n> <name>s (first t = <t><unit>)' of the events of kind `kind` ('no <name>s' when none).
    pure function event_summary(times, kinds, kind, name, unit) result(text)
        real(dp), intent(in) :: times(:)
        integer, intent(in) :: kinds(:), kind
        character(len=*), intent(in) :: name, unit
        character(len=:), allocatable :: text
        integer :: n, first

        n = count(kinds == kind)
        if (n == 0) then
            text = 'no '//name//'s'
            return
        end if
        first = findloc(kinds, kind, dim=1)
        text = int_str(n)//' '//name//merge('s', ' ', n > 1)
        text = trim(text)//' (first t = '//format_real(times(first))//unit//')'
    end function event_summary

    !> /checkpoint: every type that the run continues from saves itself (checkpoint_m's sync)
    !> and the checkpoint is written; or, given `from` (read from a file: restart_m), each gets
    !> itself back from it, the state first, then the adaptive mesh (which resizes
    !> the stepper and the monitor to the state's mesh) before the others. So a restart
    !> continues exactly, and the save and the restore name the same entries.
    subroutine checkpoint(run, cfg, from)
        type(run_t), intent(inout) :: run
        type(config_t), intent(in) :: cfg
        type(checkpoint_t), intent(in), optional :: from
        type(checkpoint_t) :: ckpt
        real(dp) :: wall

        if (present(from)) ckpt = from
        call run%state%checkpoint(ckpt, 'state')
        if (cfg%mesh%adaptive) then
            call run%mesh%checkpoint(ckpt)
            call ckpt%sync('run/n_elements_max', run%n_elements_max)
            if (ckpt%reading) then
                call set_mesh(run%state, run%mesh%nodes())
                call run%stepper%remesh(run%state)
                call run%monitor%resize(run%state)
            end if
        end if
        call run%monitor%checkpoint(ckpt)
        call run%stepper%checkpoint(ckpt)
        call run%driver%checkpoint(ckpt)
        if (cfg%output%error_estimate) call run%companions%checkpoint(ckpt)
        if (ckpt%reading) then
            if (ckpt%has('run/wall_seconds')) call ckpt%sync('run/wall_seconds', run%wall_before)
            return
        end if
        wall = wall_seconds(run)
        call ckpt%sync('run/wall_seconds', wall)
        call run%writer%write_checkpoint(ckpt, run%driver%step_label(run%state%step, run%state%t, ''))
        run%checkpointed = run%state%step
    end subroutine checkpoint

    !> The run's wall seconds so far, with those before the checkpoint it restarted from.
    real(dp) function wall_seconds(run)
        type(run_t), intent(in) :: run
        integer(int64) :: clock_now

        call system_clock(clock_now)
        wall_seconds = run%wall_before + real(clock_now - run%clock_start, dp) / real(run%clock_rate, dp)
    end function wall_seconds

    !> A snapshot of the level in run%state, with its error estimate (&output error_estimate).
    subroutine snapshot(run, cfg)
        type(run_t), intent(inout) :: run
        type(config_t), intent(in) :: cfg

        call write_snapshot(run%writer, run%state, cfg%model, run%x_out)
        if (cfg%output%error_estimate) call write_error_estimate(run%writer, run%companions, run%state)
    end subroutine snapshot

    !> Dense output of the step just taken from t_before (run_output_m's series entries and,
    !> with snapshot_land = .false., snapshots, which validate_m allows only without an error
    !> estimate). at_end: one so written is at t_n, so the last step's own would repeat it.
    subroutine write_dense_output(run, cfg, t_before, at_end)
        type(run_t), intent(inout) :: run
        type(config_t), intent(in) :: cfg
        real(dp), intent(in) :: t_before
        logical, intent(out) :: at_end

        at_end = .false.
        if (cfg%output%series_dt > 0.0_dp) &
            call write_dense_series(run%writer, run%driver, run%stepper, run%state, run%monitor, run%result, &
                                    t_before, cfg%output%series_dt, run%n_series_next, at_end)
        if (cfg%output%snapshot_dt > 0.0_dp .and. .not. cfg%output%snapshot_land) &
            call write_dense_snapshots(run%writer, run%driver, run%state, cfg%model, run%x_out, t_before, &
                                       cfg%output%snapshot_dt, run%n_snapshot_next, at_end)
    end subroutine write_dense_output

    !> Has the run reached its end? Fixed steps without snapshot_dt: n_steps steps (as
    !> always, t_N = N dt); otherwise t_end (adaptive) or N dt (fixed), to round-off.
    logical function finished(run, cfg)
        type(run_t), intent(in) :: run
        type(config_t), intent(in) :: cfg

        if (.not. cfg%time%adaptive .and. cfg%output%snapshot_dt <= 0.0_dp) then
            finished = run%state%step >= run%n_steps
        else
            finished = run%state%t >= t_stop(run, cfg) - &
                       1.0e-9_dp * merge(cfg%time%dt_min, cfg%time%dt, cfg%time%adaptive)
        end if
    end function finished

    !> The end time: t_end (adaptive), N dt (fixed: number_of_steps).
    real(dp) function t_stop(run, cfg)
        type(run_t), intent(in) :: run
        type(config_t), intent(in) :: cfg

        if (cfg%time%adaptive) then
            t_stop = cfg%time%t_end
        else
            t_stop = real(run%n_steps, dp) * cfg%time%dt
        end if
    end function t_stop

    !> Snapshot after step n: at the snapshot times (snapshot_dt), else every snapshot_every steps.
    logical function snapshot_due(cfg, n, at_snapshot)
        type(config_t), intent(in) :: cfg
        integer, intent(in) :: n
        logical, intent(in) :: at_snapshot

        if (cfg%output%snapshot_dt > 0.0_dp) then
            snapshot_due = at_snapshot
        else
            snapshot_due = mod(n, cfg%output%snapshot_every) == 0
        end if
    end function snapshot_due

    !> Where the progress report stands in an adaptive run: t / t_end in PROGRESS_UNITS.
    integer function progress_position(cfg, t)
        type(config_t), intent(in) :: cfg
        real(dp), intent(in) :: t

        progress_position = max(1, min(PROGRESS_UNITS, nint(real(PROGRESS_UNITS, dp) * t / cfg%time%t_end)))
    end function progress_position

end module run_m
