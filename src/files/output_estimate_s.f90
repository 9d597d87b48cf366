!> The per-snapshot error estimates of a run with &output error_estimate (/snapshots/
!> error_estimate*: docs/output.md; error_companion_m computes them): a submodule of output_m,
!> so that it reaches the writer's open file. Created by the first append and kept open until
!> finish(); the values are buffered between flushes, as the series are.
submodule (output_m) output_estimate_s
    implicit none

    character(len=*), parameter :: WHAT(3) = [character(len=40) :: '(time and space)', &
                                              '(time part)', '(space part)']
    integer(hsize_t), parameter :: CHUNK(1) = [int(SERIES_CHUNK, hsize_t)]

contains

    !> Append one snapshot's estimates: values(k, part) of field OUTPUT_ORDER(k), part 1 the
    !> total, 2 the time part, 3 the space part. Held in a buffer of SERIES_CHUNK snapshots
    !> and written when it is full and at every flush() (18 small writes per snapshot would
    !> cost more than the estimate).
    module procedure writer_append_estimate
        integer :: stat
        character(len=256) :: message

        call w%need_open('append_estimate()')
        if (size(values, 1) /= N_OUTPUT_FIELDS .or. size(values, 2) /= size(ESTIMATE_PARTS)) &
            call w%fail('internal error: append_estimate() given the wrong number of values')
        if (w%estimate_ids(1, 1) < 0) then
            call open_estimate(w)
            allocate (w%estimate_buf(SERIES_CHUNK, N_OUTPUT_FIELDS, size(ESTIMATE_PARTS)), stat=stat, errmsg=message)
            if (stat /= 0) call w%fail('no memory for the error estimates ('//trim(message)//')')
        end if
        w%n_estimate_buf = w%n_estimate_buf + 1
        w%estimate_buf(w%n_estimate_buf, :, :) = values
        if (w%n_estimate_buf == SERIES_CHUNK) call writer_flush_estimate(w)
    end procedure writer_append_estimate

    !> Write the buffered estimates (flush()).
    module procedure writer_flush_estimate
        integer(hsize_t) :: n
        integer :: k, part

        if (w%n_estimate_buf == 0) return
        n = int(w%n_estimate_buf, hsize_t)
        do part = 1, size(ESTIMATE_PARTS)
            do k = 1, N_OUTPUT_FIELDS
                call w%append_rows(w%estimate_ids(k, part), estimate_path(part, k), w%n_estimate_snap, [n], &
                                   w%estimate_buf(1:n, k, part))
            end do
        end do
        w%n_estimate_snap = w%n_estimate_snap + n
        w%n_estimate_buf = 0
    end procedure writer_flush_estimate

    !> The groups and their datasets: created by the first append of the file (a restart's
    !> copy of the history included), kept open.
    subroutine open_estimate(w)
        class(h5_writer_t), intent(inout) :: w
        integer :: k, part

        call w%leave_swmr()   ! new groups: not in SWMR writing (output_file_s)
        do part = 1, size(ESTIMATE_PARTS)
            call w%make_group('/snapshots/'//trim(ESTIMATE_PARTS(part)))
            do k = 1, N_OUTPUT_FIELDS
                call w%create_extendible(estimate_path(part, k), H5T_IEEE_F64LE, [0_hsize_t], CHUNK, &
                                         w%estimate_ids(k, part), 'estimated relative L2 error of '// &
                                         trim(FIELDS(OUTPUT_ORDER(k))%long_name)// &
                                         ' at each snapshot '//trim(WHAT(part)), '1')
            end do
        end do
    end subroutine open_estimate

end submodule output_estimate_s
