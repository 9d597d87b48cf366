!> Restart (&time restart_from): the last checkpoint of a file (complete, failed, or the
!> .h5.part of a killed run; its layout: docs/output.md, "Checkpoints") read into
!> checkpoint_m's record once this run may continue it, and the series and snapshots up to
!> it copied into the new file, so that the continued run is bit-for-bit an uninterrupted
!> one. A restart from the run's own <prefix>.h5.part resumes it in place (output_m's
!> RESUMED_SUFFIX); the positional layout of earlier versions is refused with what to do
!> (docs/robustness.md).
module restart_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use config_m, only: config_t, number_of_steps
    use input_vars_m, only: INPUT_VARS, input_item_t, input_item, changes_history, table_items, KIND_INTEGER, &
                            KIND_STRING, KIND_LOGICAL
    use strings_m, only: format_real, int_str
    use errors_m, only: fatal, EXIT_INPUT, EXIT_OUTPUT, check_allocation
    use reals_m, only: equal
    use checkpoint_m, only: checkpoint_t, entry_t
    use checkpoint_read_m, only: read_entries
    use fields_m, only: N_FIELDS, N_OUTPUT_FIELDS, N_SNAPSHOT_FIELDS, SNAPSHOTS, SERIES, N_SERIES
    use fsys_m, only: file_exists, same_file, rename_file, remove_file
    use h5_read_m, only: read_real_1d, read_attr_real, &
                         read_attr_str, read_attr_real_1d, dataset_exists, attr_exists, is_hdf5_file
    use output_m, only: h5_writer_t, CHECKPOINT_LAYOUT, RESUMED_SUFFIX, ESTIMATE_PARTS
    implicit none
    private
    public :: read_checkpoint, copy_history

    character(len=*), parameter :: WHERE = 'time.restart_from'

contains

    !> Read the checkpoint of `file` into ckpt, after checking that this run may continue
    !> it: `file` is not the <prefix>.h5 this run writes, its checkpoint is in this version's
    !> layout, every input that changes the computed history equals the one recorded in
    !> `file`, and t_end is not before the checkpoint. Any of these failing is an input error
    !> (exit 2) that leaves no output. in_place: `file` is this run's own <prefix>.h5.part.
    subroutine read_checkpoint(file, cfg, ckpt, in_place)
        character(len=*), intent(in) :: file
        type(config_t), intent(in) :: cfg
        type(checkpoint_t), intent(out) :: ckpt
        logical, intent(out) :: in_place
        real(dp) :: t
        integer :: step, slot
        character(len=:), allocatable :: prefix

        prefix = trim(cfg%output%prefix)
        if (.not. file_exists(file) .and. file == prefix//'.h5.part') call fatal(EXIT_INPUT, WHERE, "got '"//file// &
            "': no such file, nothing to resume (a run stopped by a signal leaves it); without --resume the run "// &
            'starts at t = 0')
        if (.not. file_exists(file)) call fatal(EXIT_INPUT, WHERE, "got '"//file// &
            "': no such file; must be the output (.h5 or .h5.part) of a run with checkpoints")
        if (any([same_file(file, prefix//'.h5'), same_file(file, prefix//RESUMED_SUFFIX)])) call fatal(EXIT_INPUT, &
            WHERE, "'"//file//"' is a file this run writes (output.prefix = '"//prefix//"' writes '"//prefix// &
            ".h5' at the end, and replaces '"//prefix//RESUMED_SUFFIX//"'): it would overwrite the checkpoint it "// &
            'restarts from; choose another output.prefix, or continue the run with --resume')
        in_place = same_file(file, prefix//'.h5.part')
        if (in_place) call take_over_resumed(prefix//RESUMED_SUFFIX, file)
        slot = current_slot(file)
        if (slot < 0) call fatal(EXIT_INPUT, WHERE, "'"//file//"' holds no complete checkpoint; the run must "// &
            'have &output checkpoint_every > 0 and reach a checkpoint')
        if (.not. attr_exists(file, 'layout', '/checkpoint')) call fatal(EXIT_INPUT, WHERE, "'"//file// &
            "': its checkpoint is in the positional layout of earlier versions of rodcontact (/checkpoint/slotN/"// &
            'counters, control, mesh, ...: arrays of reals); this version reads only its own layout ('// &
            CHECKPOINT_LAYOUT//') and cannot continue it: run again from the start, or restart with the '// &
            'version that wrote the file')
        call require_same_history_inputs(file, cfg)
        call require_history_datasets(file)
        call read_entries(file, '/checkpoint/slot'//int_str(slot), ckpt)
        call require_fit(file, cfg, ckpt)
        call ckpt%sync('state/t', t)
        call ckpt%sync('state/step', step)
        if (ends_before(cfg, t, step)) &
            call fatal(EXIT_INPUT, 'time.t_end', 'got '//format_real(cfg%time%t_end)//"; the checkpoint in '"//file// &
                       "' is at t = "//format_real(t)//' (step '//int_str(step)//'): a restart continues a run '// &
                       'up to t_end, so t_end must be >= '//format_real(t))
    end subroutine read_checkpoint

    !> The checkpoint's level fits this run's mesh (&mesh n_elements, or on an adaptive mesh
    !> the checkpoint's node keys) and it holds the error estimate's companions if this run
    !> continues them (&output error_estimate may change across a restart).
    subroutine require_fit(file, cfg, ckpt)
        character(len=*), intent(in) :: file
        type(config_t), intent(in) :: cfg
        type(checkpoint_t), intent(inout) :: ckpt
        real(dp), allocatable :: level(:, :)
        integer(int64), allocatable :: keys(:)
        integer :: s

        s = cfg%mesh%n_elements
        if (cfg%mesh%adaptive) then
            call ckpt%sync('adaptive_mesh/keys', keys)
            s = size(keys) - 1
        end if
        call ckpt%sync('state/level', level)
        if (any(shape(level) /= [s + 1, 1 + N_FIELDS])) call fatal(EXIT_INPUT, WHERE, "'"//file// &
            "': its checkpoint's state/level does not fit the mesh")
        if (cfg%output%error_estimate .and. .not. ckpt%has('error_companions/failed_flag')) &
            call fatal(EXIT_INPUT, WHERE, "'"//file//"': its checkpoint has no error-estimate companions")
    end subroutine require_fit

    !> Does the run cfg end before the checkpoint's level (time t, step n)? Fixed steps: its
    !> last step comes before the checkpoint's; adaptive steps: t_end < t.
    pure logical function ends_before(cfg, t, n)
        type(config_t), intent(in) :: cfg
        real(dp), intent(in) :: t
        integer, intent(in) :: n

        if (cfg%time%adaptive) then
            ends_before = cfg%time%t_end < t
        else
            ends_before = number_of_steps(cfg%time%dt, cfg%time%t_end) < n
        end if
    end function ends_before

    !> Before resuming `part` in place: a resumed run that was killed (or failed to write)
    !> left its own file `resumed`. With a complete checkpoint, which is later than part's
    !> (it continued part's history), it takes part's place; without one it is dropped.
    subroutine take_over_resumed(resumed, part)
        character(len=*), intent(in) :: resumed, part
        character(len=:), allocatable :: message
        logical :: ok

        if (.not. file_exists(resumed)) return
        ok = is_hdf5_file(resumed)
        if (ok) ok = current_slot(resumed) >= 0
        if (.not. ok) then
            call remove_file(resumed)
            return
        end if
        call rename_file(resumed, part, ok, message)
        if (.not. ok) &
            call fatal(EXIT_OUTPUT, 'output', message//' (taking over the later checkpoint of a resumed run)')
    end subroutine take_over_resumed

    !> The slot of the last complete checkpoint of `file` (/checkpoint/current), -1 if none
    !> (also after a kill while the first was written: output_checkpoint_s).
    integer function current_slot(file) result(slot)
        character(len=*), intent(in) :: file
        real(dp), allocatable :: current(:)

        slot = -1
        if (.not. dataset_exists(file, '/checkpoint/current')) return
        call read_real_1d(file, '/checkpoint/current', current)
        slot = nint(current(1))
    end function current_slot

    !> Every input variable that changes the computed history (input_vars_m's
    !> changes_history) must have the value recorded in `file` as root attribute
    !> group.variable; &material counts when either run has it; the tables of &initial's
    !> files (their names are input variables too) the rows recorded.
    subroutine require_same_history_inputs(file, cfg)
        character(len=*), intent(in) :: file
        type(config_t), intent(in) :: cfg
        type(config_t) :: defaults
        type(input_item_t) :: item, was
        integer :: k
        logical :: recorded

        do k = 1, size(INPUT_VARS)
            if (.not. changes_history(INPUT_VARS(k))) cycle
            item = input_item(cfg, k)
            recorded = attr_exists(file, item%name)
            if (INPUT_VARS(k)%group == 'material') then
                if (recorded .and. .not. cfg%material%present) &
                    call refuse(file, item%name, 'given (&material)', 'not given (no &material)')
                if (.not. recorded .and. cfg%material%present) &
                    call refuse(file, item%name, 'not given (no &material)', 'given (&material)')
                if (.not. recorded) cycle
            end if
            if (.not. recorded) then
                ! an input added after the version that wrote the file: its default is what that run computed
                if (same(item, input_item(defaults, k))) cycle
                call refuse(file, item%name, 'not recorded', 'a value other than its default')
            end if
            was = recorded_item(file, item)
            if (.not. same(was, item)) call refuse(file, item%name, value_text(was), value_text(item))
        end do
        associate (tables => table_items(cfg%initial))
            do k = 1, size(tables)
                if (.not. attr_exists(file, tables(k)%name)) &
                    call refuse(file, tables(k)%name, 'not recorded', 'a table')
                was = recorded_item(file, tables(k))
                if (.not. same(was, tables(k))) call refuse(file, tables(k)%name, int_str(size(was%reals) / 2)// &
                    ' rows (those recorded there)', int_str(size(tables(k)%reals) / 2)//' rows of other values')
            end do
        end associate
    end subroutine require_same_history_inputs

    !> Input `item` as `file` records it (root attribute item%name).
    function recorded_item(file, item) result(was)
        character(len=*), intent(in) :: file
        type(input_item_t), intent(in) :: item
        type(input_item_t) :: was
        real(dp) :: x

        was = item
        select case (item%kind)
        case (KIND_STRING)
            call read_attr_str(file, item%name, was%text)
        case (KIND_INTEGER, KIND_LOGICAL)   ! (a logical as 1 or 0)
            call read_attr_real(file, item%name, x)
            was%int = nint(x)
            was%flag = nint(x) /= 0
        case default   ! a real, polynomial coefficients, (amplitude, x_end), a table's rows
            call read_attr_real_1d(file, item%name, was%reals)
        end select
    end function recorded_item

    !> Two values of one input agree (reals: reals_m's equal).
    logical function same(a, b)
        type(input_item_t), intent(in) :: a, b

        select case (a%kind)
        case (KIND_INTEGER)
            same = a%int == b%int
        case (KIND_STRING)
            same = a%text == b%text
        case (KIND_LOGICAL)
            same = a%flag .eqv. b%flag
        case default
            same = size(a%reals) == size(b%reals)
            if (same) same = all(equal(a%reals, b%reals))
        end select
    end function same

    !> An input's value for messages: 100, 'euler', .true., 0, 40, -80, 40.
    function value_text(item) result(text)
        type(input_item_t), intent(in) :: item
        character(len=:), allocatable :: text
        integer :: k

        select case (item%kind)
        case (KIND_INTEGER)
            text = int_str(item%int)
        case (KIND_STRING)
            text = "'"//item%text//"'"
        case (KIND_LOGICAL)
            text = trim(merge('.true. ', '.false.', item%flag))
        case default   ! (a polynomial's coefficients count from 0)
            text = ''
            do k = lbound(item%reals, 1), ubound(item%reals, 1)
                text = text//', '//format_real(item%reals(k))
            end do
            text = text(3:)
        end select
    end function value_text

    !> Append to writer the series entries and snapshots of `file` up to time t_checkpoint
    !> (see rows_to_copy): every dataset of fields_m's SERIES and SNAPSHOTS tables, the
    !> native snapshots and the estimates; /series and /snapshots each read in one pass.
    subroutine copy_history(writer, file, t_checkpoint)
        type(h5_writer_t), intent(inout) :: writer
        character(len=*), intent(in) :: file
        real(dp), intent(in) :: t_checkpoint
        character(len=*), parameter :: NATIVE = '/snapshots/native/'
        type(checkpoint_t) :: ser, snaps
        real(dp), allocatable :: t(:, :, :), values(:, :, :), x(:, :, :), at(:, :, :), parts(:, :, :)
        real(dp) :: t_last
        integer :: j, k, n, stat
        character(len=256) :: message

        t_last = t_checkpoint * (1.0_dp + 1.0e-12_dp)
        call read_entries(file, '/series', ser)
        call read_rows(ser, '/series/', ['t'], -1, t)
        n = rows_to_copy(t(1, 1, :), t_last)
        call read_rows(ser, '/series/', [SERIES%name], n, values)   ! ([ ]: no array temporary)
        do k = 1, n
            call writer%append_series(values(1, :, k))
        end do
        call read_entries(file, '/snapshots', snaps)
        call read_rows(snaps, '/snapshots/', ['t'], -1, t)
        n = rows_to_copy(t(1, 1, :), t_last)
        call read_rows(snaps, '/snapshots/', [SNAPSHOTS%name], n, values)
        do k = 1, n
            call writer%append_snapshot(t(1, 1, k), values(:, :, k))
        end do
        if (snaps%has('native/offset')) then
            ! snapshot k: x and the fields from entry offset + 1 to offset + count
            call read_rows(snaps, NATIVE, ['offset', 'count '], n, at)
            call read_rows(snaps, NATIVE, ['x'], nint(sum(at(1, :, max(n, 1):n))), x)
            call read_rows(snaps, NATIVE, [SNAPSHOTS%name], size(x, 3), values)
            do k = 1, n
                associate (first => nint(at(1, 1, k)) + 1, last => nint(at(1, 1, k) + at(1, 2, k)))
                    call writer%append_native(x(1, 1, first:last), transpose(values(1, :, first:last)))
                end associate
            end do
        end if
        if (.not. snaps%has(trim(ESTIMATE_PARTS(1))//'/'//SNAPSHOTS(1)%name)) return
        allocate (parts(N_OUTPUT_FIELDS, size(ESTIMATE_PARTS), n), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the copied history')
        do j = 1, size(ESTIMATE_PARTS)
            ! /snapshots/<part>/<field>: the fields of SNAPSHOTS(:N_OUTPUT_FIELDS)
            call read_rows(snaps, '/snapshots/'//trim(ESTIMATE_PARTS(j))//'/', [SNAPSHOTS(:N_OUTPUT_FIELDS)%name], &
                           n, values)
            parts(:, j, :) = values(1, :, :)
        end do
        do k = 1, n
            call writer%append_estimate(parts(:, :, k))
        end do
    end subroutine copy_history

    !> Every dataset copy_history copies is in `file` (a file of an older version lacks the
    !> energy parts and sigma): checked before the new file is created.
    subroutine require_history_datasets(file)
        character(len=*), intent(in) :: file
        character(len=64) :: paths(N_SERIES + N_SNAPSHOT_FIELDS)
        integer :: k

        paths = [character(len=64) :: ('/series/'//SERIES(k)%name, k = 1, N_SERIES), &
                 ('/snapshots/'//SNAPSHOTS(k)%name, k = 1, N_SNAPSHOT_FIELDS)]
        do k = size(paths), 1, -1
            if (dataset_exists(file, trim(paths(k)))) cycle
            call fatal(EXIT_INPUT, WHERE, "'"//file//"' has no "//trim(paths(k))//': it was written by an '// &
                       'older version of rodcontact, whose checkpoints this version cannot continue')
        end do
    end subroutine require_history_datasets

    !> values(:, k, j): row j (j <= n, or every row with n < 0) of the dataset group//names(k),
    !> read into set; a row is the dataset's values at one time (its last Fortran index),
    !> float64 (an integer dataset's too, which it holds exactly).
    subroutine read_rows(set, group, names, n, values)
        type(checkpoint_t), intent(inout) :: set
        character(len=*), intent(in) :: group, names(:)
        integer, intent(in) :: n
        real(dp), allocatable, intent(out) :: values(:, :, :)
        type(entry_t) :: e
        character(len=:), allocatable :: path
        integer :: i, k, width, m, stat
        character(len=256) :: message

        do k = 1, size(names)
            path = group//trim(names(k))
            e = set%find(path(index(path(2:), '/') + 2:))   ! (its path below the group read)
            width = merge(e%dims(1), 1, e%rank == 2)
            m = merge(e%dims(e%rank), n, n < 0)
            if (e%dims(e%rank) < m) call fatal(EXIT_INPUT, WHERE, "'"//set%source//"': "//path// &
                ' has fewer rows than its time column')
            if (k == 1) then
                allocate (values(width, size(names), m), stat=stat, errmsg=message)
                call check_allocation(stat, message, 'the copied history')
            end if
            if (e%is_integer) then
                values(:, k, :) = reshape(real(e%values(:width * m), dp), [width, m])
            else
                values(:, k, :) = reshape(transfer(e%values(:width * m), 1.0_dp, width * m), [width, m])
            end if
            if (n < 0) cycle   ! (a time column, read again with the other datasets)
            do i = 1, set%n   ! its words, copied, dropped: a large history is not held twice
                if (set%entries(i)%name == e%name) deallocate (set%entries(i)%values)
            end do
        end do
    end subroutine read_rows

    !> How many leading rows to copy: times up to t_last and strictly increasing (a file left
    !> by a killed run can hold rows past its last flush whose values were never written).
    pure integer function rows_to_copy(times, t_last)
        real(dp), intent(in) :: times(:), t_last
        integer :: k
        real(dp) :: t_before

        rows_to_copy = 0
        t_before = -huge(1.0_dp)
        do k = 1, size(times)
            if (times(k) > t_last .or. times(k) <= t_before) exit
            t_before = times(k)
            rows_to_copy = k
        end do
    end function rows_to_copy

    !> The checkpointed run and this one differ in input `name`: stop with an input error
    !> that names both values and what a restart may change (from input_vars_m's table).
    subroutine refuse(file, name, was, now)
        character(len=*), intent(in) :: file, name, was, now
        character(len=:), allocatable :: may_change
        integer :: k

        may_change = ''
        do k = 1, size(INPUT_VARS)
            if (changes_history(INPUT_VARS(k))) cycle
            if (INPUT_VARS(k)%name == 'restart_from') cycle
            if (may_change /= '') may_change = may_change//', '
            may_change = may_change//trim(INPUT_VARS(k)%group)//'.'//trim(INPUT_VARS(k)%name)
        end do
        call fatal(EXIT_INPUT, WHERE, "'"//file//"': "//name//' was '//was//' in the run that wrote the checkpoint, '// &
                   'this run has '//now//'; a restart must keep every input that changes the computed history '// &
                   '(&model, &material, &contact, &mesh, &initial, &solver, &time except t_end); it may change '// &
                   may_change)
    end subroutine refuse

end module restart_m
