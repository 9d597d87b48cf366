!> The root attributes of a run: every input value at the start, the SI scales of
!> &material, where the file came from (docs/output.md, "Root attributes": when, on which
!> host, by which command, from which source, with which HDF5 library and compiler; the time
!> and host name from src/files/provenance_c.c), and at the end what the run did (steps,
!> energy law, solver, step control and mesh counts, the error estimate) with its contact
!> events.
module run_attributes_m
    use kinds_m, only: dp
    use config_m, only: config_t
    use input_vars_m, only: input_item_t, input_items, KIND_REAL, KIND_INTEGER, KIND_STRING, KIND_LOGICAL
    use material_m, only: nondim_groups, NONDIM_NAMES, si_scale_t, si_scales
    use state_m, only: state_t
    use stepper_m, only: stepper_t
    use time_scheme_m, only: energy_law_t
    use energy_m, only: energy_monitor_t
    use events_m, only: event_log_t
    use step_control_m, only: step_controller_t
    use step_driver_m, only: step_driver_t
    use error_companion_m, only: error_companions_t
    use fields_m, only: FIELDS, N_OUTPUT_FIELDS, OUTPUT_ORDER
    use output_m, only: h5_writer_t, ESTIMATE_PARTS
    use iso_c_binding, only: c_char, c_int
    use iso_fortran_env, only: compiler_version
    use hdf5, only: h5get_libversion_f
    use strings_m, only: int_str, from_c_chars
    implicit none
    private
    public :: record_inputs, dataset_scales, record_scales, record_results, record_provenance, ERROR_ESTIMATE_NONE

    !> The root attribute error_estimate of a run without &output error_estimate.
    character(len=*), parameter :: ERROR_ESTIMATE_NONE = &
        'none: set &output error_estimate=.true. or run scripts/converge.sh'

    abstract interface
        !> A helper of provenance_c.c: writes a NUL-terminated string of at most n characters
        !> into buf, returns 0 (non-zero: it failed).
        function c_helper(buf, n) bind(C) result(rc)
            import :: c_char, c_int
            character(kind=c_char), intent(out) :: buf(*)
            integer(c_int), value :: n
            integer(c_int) :: rc
        end function c_helper
    end interface

    procedure(c_helper), bind(C, name='rc_utc_now') :: c_utc_now
    procedure(c_helper), bind(C, name='rc_hostname') :: c_hostname

contains

    !> Every input value as a root attribute named group.variable (docs/output.md).
    subroutine record_inputs(writer, cfg)
        type(h5_writer_t), intent(inout) :: writer
        type(config_t), intent(in) :: cfg

        call record_items(writer, input_items(cfg))
        ! the input's unit system (the values recorded are those run, nondimensional)
        if (cfg%material%present) then
            call writer%attr('units', 'SI')
        else
            call writer%attr('units', 'nondimensional')
        end if
    end subroutine record_inputs

    !> Each item as a root attribute of its kind.
    subroutine record_items(writer, items)
        type(h5_writer_t), intent(inout) :: writer
        type(input_item_t), intent(in) :: items(:)
        integer :: k

        do k = 1, size(items)
            associate (item => items(k))
                select case (item%kind)
                case (KIND_REAL)
                    call writer%attr(item%name, item%reals(1))
                case (KIND_INTEGER)
                    call writer%attr(item%name, item%int)
                case (KIND_STRING)
                    call writer%attr(item%name, item%text)
                case (KIND_LOGICAL)
                    call writer%attr(item%name, item%flag)
                case default   ! polynomial coefficients, (amplitude, x_end)
                    call writer%attr(item%name, item%reals)
                end select
            end associate
        end do
    end subroutine record_items

    !> The SI scales of the datasets (output_m's create): with &material those of (2.10) and
    !> '' for the counts (factor 1, so that every dataset converts), without it none.
    function dataset_scales(cfg) result(scales)
        type(config_t), intent(in) :: cfg
        type(si_scale_t), allocatable :: scales(:)

        allocate (scales(0))
        if (cfg%material%present) scales = [si_scales(cfg%material), si_scale_t('', 1.0_dp, '1')]
    end function dataset_scales

    !> With &material: the groups of (2.10) (root attributes derived.*) and each scale of the
    !> nondimensional variables (scale.<name>, its SI units in scale.<name>.units).
    subroutine record_scales(writer, cfg)
        type(h5_writer_t), intent(inout) :: writer
        type(config_t), intent(in) :: cfg
        real(dp) :: nd(size(NONDIM_NAMES))
        type(si_scale_t), allocatable :: scales(:)
        integer :: k

        nd = nondim_groups(cfg%material)
        do k = 1, size(NONDIM_NAMES)
            call writer%attr('derived.'//trim(NONDIM_NAMES(k)), nd(k))
        end do
        scales = si_scales(cfg%material)
        do k = 1, size(scales)
            call writer%attr('scale.'//trim(scales(k)%name), scales(k)%factor)
            call writer%attr('scale.'//trim(scales(k)%name)//'.units', trim(scales(k)%units))
        end do
    end subroutine record_scales

    !> At the end of the run cfg: the contact events (/events) and the root attributes of
    !> what the run did (docs/output.md): its steps and end time, wall_seconds, the energy
    !> law's largest rises, the solver's counts, the step control's error sum and counts
    !> (adaptive steps), the error estimate (or that there is none), and on an adaptive mesh
    !> its counts (n_elements_max: the most elements held).
    subroutine record_results(writer, cfg, state, stepper, monitor, driver, companions, wall_seconds, n_elements_max)
        type(h5_writer_t), intent(inout) :: writer
        type(config_t), intent(in) :: cfg
        type(state_t), intent(in) :: state
        type(stepper_t), intent(in) :: stepper
        type(energy_monitor_t), intent(in) :: monitor
        type(step_driver_t), intent(in) :: driver
        type(error_companions_t), intent(in) :: companions
        real(dp), intent(in) :: wall_seconds
        integer, intent(in) :: n_elements_max
        type(event_log_t) :: events
        type(energy_law_t) :: scheme_law
        real(dp) :: max_rise, max_rise_step_change, max_rise_remesh
        integer :: n_remeshes

        events = driver%events_log()
        call writer%write_events(events%times(), events%kinds())
        call writer%attr('steps', state%step)
        call writer%attr('t_final', state%t)
        call writer%attr('wall_seconds', wall_seconds)
        call monitor%rises(max_rise, max_rise_step_change, max_rise_remesh, n_remeshes)
        call writer%attr('energy_max_relative_rise', max_rise)
        scheme_law = stepper%scheme%row%law
        if (scheme_law%constant_steps .and. (cfg%time%adaptive .or. cfg%output%snapshot_dt > 0.0_dp)) &
            call writer%attr('energy_max_relative_rise_step_change', max_rise_step_change)
        call writer%attr('energy_law', trim(scheme_law%text))
        call writer%attr('solver.linear_solves', int(stepper%n_solves))
        call writer%attr('solver.contact_steps', int(stepper%n_contact_steps))
        call writer%attr('solver.block_solver', stepper%uses_block_solver())
        if (cfg%time%adaptive) call record_step_control(writer, driver%controller())
        call record_error_estimate(writer, companions)
        if (cfg%mesh%adaptive) then
            call writer%attr('mesh.remeshes', n_remeshes)
            call writer%attr('mesh.n_elements_max', n_elements_max)
            call writer%attr('energy_max_relative_rise_remesh', max_rise_remesh)
        end if
    end subroutine record_results

    !> What the step controller of an adaptive run used (root attributes): the sum of the
    !> local error estimates of the accepted steps (step_control_m), absolute (energy norm)
    !> and relative to the largest energy norm of the solution, and its counts. Not the error
    !> of the run (that is error_estimate*, &output error_estimate); fixed steps have none.
    subroutine record_step_control(writer, control)
        type(h5_writer_t), intent(inout) :: writer
        type(step_controller_t), intent(in) :: control
        real(dp) :: error_sum, scale
        integer :: n_estimated, n_rejected, n_forced

        call control%counts(error_sum, scale, n_estimated, n_rejected, n_forced)
        call writer%attr('step_control_error_sum', error_sum)
        call writer%attr('step_control_error_sum_relative', error_sum / max(scale, tiny(1.0_dp)))
        call writer%attr('time_steps_estimated', n_estimated)
        call writer%attr('time_steps_rejected', n_rejected)
        call writer%attr('time_steps_at_dt_min', n_forced)
    end subroutine record_step_control

    !> The run's error estimate (root attributes): without &output error_estimate, the
    !> attribute error_estimate says that there is none and how to get one; with it,
    !> error_estimate names the method and error_estimate.<field>, error_estimate_time.<field>,
    !> error_estimate_space.<field> hold the estimate of the final state (error_companion_m).
    subroutine record_error_estimate(writer, companions)
        type(h5_writer_t), intent(inout) :: writer
        type(error_companions_t), intent(in) :: companions
        integer :: k, part

        if (.not. companions%on) then
            call writer%attr('error_estimate', ERROR_ESTIMATE_NONE)
            return
        end if
        call writer%attr('error_estimate', 'companion solutions at (2 dt, 2 h), (4 dt, 4 h), (8 dt, 4 h); '// &
                             'Richardson with observed orders (docs/scheme.md)')
        if (companions%failure /= '') &
            call writer%attr('error_estimate_failure', trim(companions%failure))
        do part = 1, size(ESTIMATE_PARTS)
            do k = 1, N_OUTPUT_FIELDS
                call writer%attr(trim(ESTIMATE_PARTS(part))//'.'//trim(FIELDS(OUTPUT_ORDER(k))%name), &
                                      companions%last(k, part))
            end do
        end do
    end subroutine record_error_estimate

    !> The root attributes version (program_version) and the provenance: created (the UTC
    !> time, ISO 8601: '2026-11-23T07:30:00Z'), source_version, host (gethostname(2)),
    !> command_line, hdf5_version, compiler_version; 'unknown' for any it cannot get.
    subroutine record_provenance(writer, program_version, source_version)
        type(h5_writer_t), intent(inout) :: writer
        character(len=*), intent(in) :: program_version, source_version

        call writer%attr('version', program_version)
        call writer%attr('created', c_text(c_utc_now))
        call writer%attr('source_version', source_version)
        call writer%attr('host', c_text(c_hostname))
        call writer%attr('command_line', command_line())
        call writer%attr('hdf5_version', hdf5_version())
        call writer%attr('compiler_version', compiler_version())
    end subroutine record_provenance

    !> What the C helper `helper` writes, or 'unknown' when it fails.
    function c_text(helper) result(text)
        procedure(c_helper) :: helper
        character(len=:), allocatable :: text
        character(kind=c_char) :: buf(256)

        text = 'unknown'
        if (helper(buf, size(buf, kind=c_int)) == 0) text = from_c_chars(buf)
    end function c_text

    !> The command that started this run, as the shell passed it (arguments joined by ' ').
    function command_line() result(text)
        character(len=:), allocatable :: text
        integer :: length, stat

        text = 'unknown'
        call get_command(length=length, status=stat)
        if (stat > 0 .or. length == 0) return
        text = repeat(' ', length)
        call get_command(text)
    end function command_line

    !> 'major.minor.release' of the HDF5 library this program runs with.
    function hdf5_version() result(text)
        character(len=:), allocatable :: text
        integer :: major, minor, release, hdferr

        call h5get_libversion_f(major, minor, release, hdferr)
        text = 'unknown'
        if (hdferr >= 0) text = int_str(major)//'.'//int_str(minor)//'.'//int_str(release)
    end function hdf5_version

end module run_attributes_m
