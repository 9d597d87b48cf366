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
    !> total, 2 the time part, 3 the space part. Buffered for SERIES_CHUNK snapshots and
    !> written when the buffer is full and at every flush() (18 small writes per snapshot
    !> would cost more than the estimate).
    module procedure writer_append_estimate

        call w%need_open('append_estimate()')
        if (.not. allocated(w%estimates%ids)) call open_estimate(w)
        call w%push(w%estimates, reshape(values, [size(values)]))
    end procedure writer_append_estimate

    !> The groups and their datasets: created by the first append of the file (a restart's
    !> copy of the history included), kept open.
    subroutine open_estimate(w)
        class(h5_writer_t), intent(inout) :: w
        character(len=64) :: paths(N_OUTPUT_FIELDS, size(ESTIMATE_PARTS))
        integer :: k, part

        call w%leave_swmr()   ! new groups: not in SWMR writing (output_file_s)
        do part = 1, size(ESTIMATE_PARTS)
            do k = 1, N_OUTPUT_FIELDS
                paths(k, part) = estimate_path(part, k)
            end do
        end do
        call w%start_buffered(w%estimates, size(paths), SERIES_CHUNK)
        w%estimates%paths = [paths]
        do part = 1, size(ESTIMATE_PARTS)
            call w%make_group('/snapshots/'//trim(ESTIMATE_PARTS(part)))
            do k = 1, N_OUTPUT_FIELDS
                call w%create_extendible(trim(paths(k, part)), H5T_IEEE_F64LE, [0_hsize_t], CHUNK, &
                                         w%estimates%ids(k + N_OUTPUT_FIELDS * (part - 1)), &
                                         'estimated relative L2 error of '// &
                                         trim(FIELDS(OUTPUT_ORDER(k))%long_name)// &
                                         ' at each snapshot '//trim(WHAT(part)), '1')
            end do
        end do
    end subroutine open_estimate

end submodule output_estimate_s
