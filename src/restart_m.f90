!> Checkpoint contents and restart (&output checkpoint_every, &time restart_from).
!>
!> A checkpoint lives in the group /checkpoint of the output file, in one of two slots
!> (slot0, slot1; /checkpoint/current says which is complete, see output_m): `state`
!> (s+1, 1+N_FIELDS) with the columns of fields_m (F_U+1.., i.e. u, q, theta, v, P, eta);
!> `previous`, the same for the level before (multistep schemes only); `counters`, the
!> scalars the run needs to continue exactly (COUNTER_*). A restart
!> reads the last checkpoint of a file (complete, failed, or the .h5.part of a killed run),
!> copies the series and snapshots up to it into the new file and continues the time loop
!> from there, so the result is bit-for-bit that of an uninterrupted run.
module restart_m
    use kinds_m, only: dp
    use config_m, only: config_t
    use errors_m, only: fatal, EXIT_INPUT
    use state_m, only: state_t
    use fields_m, only: N_FIELDS, FIELDS, N_OUTPUT_FIELDS, OUTPUT_ORDER, SERIES, N_SERIES, S_T
    use fsys_m, only: file_exists
    use h5_read_m, only: read_real_1d, read_real_2d, read_int_1d, read_attr_int, read_attr_real, &
                         read_attr_str, dataset_exists
    use output_m, only: h5_writer_t
    implicit none
    private
    public :: N_COUNTERS, COUNTER_STEP, COUNTER_T, COUNTER_SOLVES, COUNTER_CONTACT_STEPS, COUNTER_ENERGY, &
              COUNTER_LAW_ENERGY, COUNTER_HAVE_LAW, COUNTER_MAX_RISE, COUNTER_DT_LAST, COUNTER_T_ANCHOR, &
              COUNTER_STEP_ANCHOR
    public :: pack_state, read_checkpoint, copy_history

    integer, parameter :: COUNTER_STEP = 1, COUNTER_T = 2, COUNTER_SOLVES = 3, COUNTER_CONTACT_STEPS = 4, &
                          COUNTER_ENERGY = 5, COUNTER_LAW_ENERGY = 6, COUNTER_HAVE_LAW = 7, COUNTER_MAX_RISE = 8, &
                          COUNTER_DT_LAST = 9, COUNTER_T_ANCHOR = 10, COUNTER_STEP_ANCHOR = 11
    integer, parameter :: N_COUNTERS = 11
    character(len=*), parameter :: WHERE = 'time.restart_from'

contains

    !> (s+1, 1+N_FIELDS) array with the columns u and fields_m's F_* (the layout of /checkpoint/state).
    pure function pack_state(u, w) result(packed)
        real(dp), intent(in) :: u(0:), w(0:, :)
        real(dp) :: packed(size(u), 1 + N_FIELDS)

        packed(:, 1) = u
        packed(:, 2:) = w
    end function pack_state

    !> Read the checkpoint of `file` into state and counters. The run being restarted must
    !> have the same mesh, time step, scheme, method and contact law as cfg.
    subroutine read_checkpoint(file, cfg, state, counters)
        character(len=*), intent(in) :: file
        type(config_t), intent(in) :: cfg
        type(state_t), intent(inout) :: state
        real(dp), intent(out) :: counters(N_COUNTERS)
        real(dp), allocatable :: packed(:, :), values(:)
        character(len=:), allocatable :: slot
        integer :: s

        if (.not. file_exists(file)) call fatal(EXIT_INPUT, WHERE, "got '"//file// &
                                                "': no such file; must be the output (.h5 or .h5.part) of a run with checkpoints")
        if (.not. dataset_exists(file, '/checkpoint/current')) call fatal(EXIT_INPUT, WHERE, "'"//file// &
            "' holds no checkpoint; the run must have &output checkpoint_every > 0 and reached a checkpoint")
        call require_same_int(file, 'mesh.n_elements', cfg%mesh%n_elements)
        call require_same_real(file, 'time.dt', cfg%time%dt)
        call require_same_str(file, 'time.scheme', trim(cfg%time%scheme))
        call require_same_str(file, 'solver.method', trim(cfg%solver%method))
        call require_same_str(file, 'contact.law', trim(cfg%contact%law))
        s = cfg%mesh%n_elements
        call read_real_1d(file, '/checkpoint/current', values)
        slot = '/checkpoint/slot0'
        if (nint(values(1)) == 1) slot = '/checkpoint/slot1'
        call read_real_2d(file, slot//'/state', packed)
        if (any(shape(packed) /= [s + 1, 1 + N_FIELDS])) &
            call fatal(EXIT_INPUT, WHERE, "'"//file//"': "//slot//"/state has the wrong shape")
        state%u = packed(:, 1)
        state%w = packed(:, 2:)
        if (dataset_exists(file, slot//'/previous')) then
            call read_real_2d(file, slot//'/previous', packed)
            allocate (state%u_prev(0:s), state%w_prev(0:s, N_FIELDS))
            state%u_prev = packed(:, 1)
            state%w_prev = packed(:, 2:)
        end if
        call read_real_1d(file, slot//'/counters', values)
        if (size(values) /= N_COUNTERS) call fatal(EXIT_INPUT, WHERE, "'"//file//"': /checkpoint/counters is not "// &
                                                   "from this version of rodcontact")
        counters = values
        state%step = nint(counters(COUNTER_STEP))
        state%t = counters(COUNTER_T)
        state%dt_last = counters(COUNTER_DT_LAST)
        state%t_anchor = counters(COUNTER_T_ANCHOR)
        state%step_anchor = nint(counters(COUNTER_STEP_ANCHOR))
    end subroutine read_checkpoint

    !> Append to writer the series entries and snapshots of `file` up to time t_checkpoint
    !> (see rows_to_copy): every dataset of fields_m's SERIES and FIELDS tables.
    subroutine copy_history(writer, file, t_checkpoint)
        type(h5_writer_t), intent(inout) :: writer
        character(len=*), intent(in) :: file
        real(dp), intent(in) :: t_checkpoint
        real(dp), allocatable :: column(:), rows(:, :), snap_t(:), snap(:, :), snaps(:, :, :)
        integer, allocatable :: whole(:)
        real(dp) :: t_last
        integer :: k, n

        t_last = t_checkpoint * (1.0_dp + 1.0e-12_dp)
        call read_real_1d(file, '/series/'//trim(SERIES(S_T)%name), column)
        n = rows_to_copy(column, t_last)
        allocate (rows(n, N_SERIES))
        do k = 1, N_SERIES
            if (SERIES(k)%is_integer) then
                call read_int_1d(file, '/series/'//trim(SERIES(k)%name), whole)
                column = real(whole, dp)
            else
                call read_real_1d(file, '/series/'//trim(SERIES(k)%name), column)
            end if
            call require_rows(file, '/series/'//trim(SERIES(k)%name), size(column), n)
            rows(:, k) = column(1:n)
        end do
        do k = 1, n
            call writer%append_series(rows(k, :))
        end do
        call read_real_1d(file, '/snapshots/t', snap_t)
        n = rows_to_copy(snap_t, t_last)
        do k = 1, N_OUTPUT_FIELDS
            call read_real_2d(file, '/snapshots/'//trim(FIELDS(OUTPUT_ORDER(k))%name), snap)
            call require_rows(file, '/snapshots/'//trim(FIELDS(OUTPUT_ORDER(k))%name), size(snap, 2), n)
            if (.not. allocated(snaps)) allocate (snaps(size(snap, 1), N_OUTPUT_FIELDS, n))
            snaps(:, k, :) = snap(:, 1:n)
        end do
        do k = 1, n
            call writer%append_snapshot(snap_t(k), snaps(:, :, k))
        end do
    end subroutine copy_history

    !> A dataset of the copied history has fewer rows than its time column: not a file this
    !> version of rodcontact wrote.
    subroutine require_rows(file, dset, have, need)
        character(len=*), intent(in) :: file, dset
        integer, intent(in) :: have, need

        if (have < need) call fatal(EXIT_INPUT, WHERE, "'"//file//"': "//dset//' has fewer rows than its time column')
    end subroutine require_rows

    !> How many leading rows to copy: times up to t_last and strictly increasing (a file left
    !> by a killed run can hold rows past its last flush whose values were never written).
    pure integer function rows_to_copy(times, t_last)
        real(dp), intent(in) :: times(:), t_last
        integer :: k

        rows_to_copy = 0
        do k = 1, size(times)
            if (times(k) > t_last) exit
            if (k > 1) then
                if (times(k) <= times(k - 1)) exit
            end if
            rows_to_copy = k
        end do
    end function rows_to_copy

    subroutine require_same_int(file, name, expected)
        character(len=*), intent(in) :: file, name
        integer, intent(in) :: expected
        integer :: value
        character(len=32) :: was, now

        call read_attr_int(file, name, value)
        write (was, '(i0)') value
        write (now, '(i0)') expected
        if (value /= expected) call refuse(file, name, trim(was), trim(now))
    end subroutine require_same_int

    subroutine require_same_real(file, name, expected)
        character(len=*), intent(in) :: file, name
        real(dp), intent(in) :: expected
        real(dp) :: value
        character(len=32) :: was, now

        call read_attr_real(file, name, value)
        write (was, '(es12.5)') value
        write (now, '(es12.5)') expected
        if (value /= expected) call refuse(file, name, trim(adjustl(was)), trim(adjustl(now)))
    end subroutine require_same_real

    subroutine require_same_str(file, name, expected)
        character(len=*), intent(in) :: file, name, expected
        character(len=:), allocatable :: value

        call read_attr_str(file, name, value)
        if (value /= expected) call refuse(file, name, "'"//value//"'", "'"//expected//"'")
    end subroutine require_same_str

    !> The checkpointed run and this one differ in `name`: stop with an input error.
    subroutine refuse(file, name, was, now)
        character(len=*), intent(in) :: file, name, was, now

        call fatal(EXIT_INPUT, WHERE, "'"//file//"': "//name//' was '//was//', this run has '//now// &
                   '; a restart must keep the mesh, dt, scheme, method and contact law')
    end subroutine refuse

end module restart_m
