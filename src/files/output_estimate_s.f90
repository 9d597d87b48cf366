!> The per-snapshot error estimates of a run with &output error_estimate (docs/output.md):
!> a submodule of output_m, so that it reaches the writer's open file.
!>
!>     /snapshots/error_estimate/<field>         (n_snap,)  float64   time and space together
!>     /snapshots/error_estimate_time/<field>    (n_snap,)  float64   its time part
!>     /snapshots/error_estimate_space/<field>   (n_snap,)  float64   its space part
!>
!> One value per snapshot: the estimated relative L2 error |f_h - f| / |f_h| of the field
!> (error_companion_m computes it). Created by the first append and kept open until
!> finish(); the values are buffered between flushes, as the series are.
submodule (output_m) output_estimate_s
    implicit none

    !> the groups, in the order of the parts given to append_estimate: total, time, space
    character(len=*), parameter :: GROUPS(3) = [character(len=32) :: '/snapshots/error_estimate', &
                                                '/snapshots/error_estimate_time', '/snapshots/error_estimate_space']
    character(len=*), parameter :: WHAT(3) = [character(len=40) :: '(time and space)', &
                                              '(time part)', '(space part)']

contains

    !> Append one snapshot's estimates: values(k, part) of field OUTPUT_ORDER(k), part 1 the
    !> total, 2 the time part, 3 the space part. Held in a buffer of SERIES_CHUNK snapshots
    !> and written when it is full and at every flush() (18 small writes per snapshot would
    !> cost more than the estimate).
    module subroutine writer_append_estimate(w, values)
        class(h5_writer_t), intent(inout) :: w
        real(dp), intent(in) :: values(:, :)
        integer :: stat
        character(len=256) :: message

        if (.not. w%opened) call fatal(EXIT_OUTPUT, 'output', 'internal error: append_estimate() on a closed writer')
        if (size(values, 1) /= N_OUTPUT_FIELDS .or. size(values, 2) /= size(GROUPS)) &
            call w%fail('internal error: append_estimate() given the wrong number of values')
        if (w%estimate_ids(1, 1) < 0) then
            call open_estimate(w)
            allocate (w%estimate_buf(N_OUTPUT_FIELDS, size(GROUPS), SERIES_CHUNK), stat=stat, errmsg=message)
            if (stat /= 0) call w%fail('no memory for the error estimates ('//trim(message)//')')
        end if
        w%n_estimate_buf = w%n_estimate_buf + 1
        w%estimate_buf(:, :, w%n_estimate_buf) = values
        if (w%n_estimate_buf == SERIES_CHUNK) call writer_flush_estimate(w)
    end subroutine writer_append_estimate

    !> Write the buffered estimates (flush()).
    module subroutine writer_flush_estimate(w)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t) :: file_space, mem_space
        integer(hsize_t) :: n
        integer :: hdferr, k, part
        character(len=:), allocatable :: path
        real(dp) :: column(SERIES_CHUNK)

        if (w%n_estimate_buf == 0) return
        n = int(w%n_estimate_buf, hsize_t)
        do part = 1, size(GROUPS)
            do k = 1, N_OUTPUT_FIELDS
                path = trim(GROUPS(part))//'/'//trim(FIELDS(OUTPUT_ORDER(k))%name)
                column(1:n) = w%estimate_buf(k, part, 1:n)
                call w%select_append(w%estimate_ids(k, part), path, [n], w%n_estimate_snap, file_space, mem_space)
                call h5dwrite_f(w%estimate_ids(k, part), H5T_NATIVE_DOUBLE, column(1:n), [n], hdferr, &
                                mem_space_id=mem_space, file_space_id=file_space)
                call w%check(hdferr, 'h5dwrite_f '//path)
                call w%close_spaces(path, file_space, mem_space)
            end do
        end do
        w%n_estimate_snap = w%n_estimate_snap + n
        w%n_estimate_buf = 0
    end subroutine writer_flush_estimate

    !> Close the datasets (finish(), after its flush()).
    module subroutine writer_close_estimate(w)
        class(h5_writer_t), intent(inout) :: w
        integer :: hdferr, k, part

        if (allocated(w%estimate_buf)) deallocate (w%estimate_buf)
        do part = 1, size(GROUPS)
            do k = 1, N_OUTPUT_FIELDS
                if (w%estimate_ids(k, part) < 0) cycle
                call h5dclose_f(w%estimate_ids(k, part), hdferr)
                call w%check(hdferr, 'h5dclose_f '//trim(GROUPS(part))//'/'//trim(FIELDS(OUTPUT_ORDER(k))%name))
                w%estimate_ids(k, part) = -1
            end do
        end do
    end subroutine writer_close_estimate

    !> The groups and their datasets: created by the first append of the file (a restart's
    !> copy of the history included), kept open.
    subroutine open_estimate(w)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t) :: group_id
        integer(hsize_t) :: dims(1)
        integer :: hdferr, k, part
        character(len=:), allocatable :: group

        call w%leave_swmr()   ! new groups: not in SWMR writing (output_file_s)
        dims = 0
        do part = 1, size(GROUPS)
            group = trim(GROUPS(part))
            call h5gcreate_f(w%file_id, group, group_id, hdferr)
            call w%check(hdferr, 'h5gcreate_f '//group)
            do k = 1, N_OUTPUT_FIELDS
                associate (field => FIELDS(OUTPUT_ORDER(k)))
                    call w%create_extendible(group_id, group//'/', trim(field%name), H5T_IEEE_F64LE, dims, &
                                             [int(SERIES_CHUNK, hsize_t)], w%estimate_ids(k, part))
                    call w%describe(w%estimate_ids(k, part), group//'/'//trim(field%name), &
                                    'estimated relative L2 error of '//trim(field%long_name)//' at each snapshot '// &
                                    trim(WHAT(part)), '1')
                end associate
            end do
            call h5gclose_f(group_id, hdferr)
            call w%check(hdferr, 'h5gclose_f '//group)
        end do
    end subroutine open_estimate

end submodule output_estimate_s
