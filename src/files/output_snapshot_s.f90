!> What a snapshot adds beyond the output grid (docs/output.md), a submodule of output_m, so
!> that it reaches the writer's open file: on an adaptive mesh the snapshot on its own mesh
!> (/snapshots/native; every append opens, extends, writes and closes its datasets), and with
!> &output error_estimate the estimates (/snapshots/error_estimate*; error_companion_m computes
!> them), created by the first append, kept open until finish() and buffered as the series are.
submodule (output_m) output_snapshot_s
    use hdf5, only: h5dopen_f, H5T_STD_I64LE
    implicit none

    character(len=*), parameter :: GROUP = '/snapshots/native'
    integer(hsize_t), parameter :: VALUES_CHUNK(1) = [4096_hsize_t]   !< float64 entries (32 KiB)
    integer(hsize_t), parameter :: CHUNK(1) = [int(SERIES_CHUNK, hsize_t)]
    character(len=*), parameter :: WHAT(3) = [character(len=40) :: '(time and space)', &
                                              '(time part)', '(space part)']

contains

    !> Append one snapshot on its own mesh: nodes x(0:s), values(0:s, k) of the field
    !> fields_m's SNAPSHOTS(k).
    module procedure writer_append_native
        integer(hsize_t) :: n, at
        integer :: k

        call w%need_open('append_native()')
        if (size(values, 1) /= size(x) .or. size(values, 2) /= N_SNAPSHOT_FIELDS) &
            call w%fail('internal error: append_native() given fields that do not match the nodes')
        if (.not. w%native_created) call writer_create_native(w)
        n = int(size(x), hsize_t)
        at = int(w%n_native_values, hsize_t)
        call append(w, 'x', at, x)
        do k = 1, N_SNAPSHOT_FIELDS
            call append(w, trim(SNAPSHOTS(k)%name), at, values(:, k))
        end do
        ! int64, written from a double (exact below 2^53)
        call append(w, 'offset', w%n_native_snap, [real(w%n_native_values, dp)])
        call append(w, 'count', w%n_native_snap, [real(n, dp)])
        w%n_native_values = w%n_native_values + int(n, int64)
        w%n_native_snap = w%n_native_snap + 1
    end procedure writer_append_native

    !> The group and its empty datasets with their dimension scales (docs/output.md, "netCDF").
    !> Created by the first append, or by the first checkpoint of an adaptive mesh
    !> (write_checkpoint), so that SWMR writing need not end for it later (output_file_s).
    module procedure writer_create_native
        integer(hid_t) :: dset_id, x_id
        integer :: k

        call w%leave_swmr()
        call w%make_group(GROUP)
        w%native_created = .true.
        call w%create_dataset(GROUP//'/x', H5T_IEEE_F64LE, VALUES_CHUNK, x_id, &
                              'nodes of the mesh of each snapshot, concatenated (see offset, count)', &
                              '1', si='position', scale='x')
        do k = 1, N_SNAPSHOT_FIELDS
            associate (f => SNAPSHOTS(k), path => GROUP//'/'//trim(SNAPSHOTS(k)%name))
                call w%create_dataset(path, H5T_IEEE_F64LE, VALUES_CHUNK, dset_id, &
                                      described(trim(f%long_name)//' at the nodes of its own '// &
                                                'mesh (native/x)', f%scale), &
                                      f%units, si=f%scale, coords=[x_id])
                call w%close_dataset(dset_id, path)
            end associate
        end do
        call w%close_dataset(x_id, GROUP//'/x')
        call create_index(w, 'offset', 'first entry of each snapshot in native/x and the fields')
        call create_index(w, 'count', 'number of nodes of each snapshot''s mesh')
    end procedure writer_create_native

    !> GROUP/name, int64, one entry per snapshot: its coordinate is /snapshots/t.
    subroutine create_index(w, name, long_name)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name, long_name
        integer(hid_t) :: dset_id

        call w%create_dataset(GROUP//'/'//name, H5T_STD_I64LE, CHUNK, dset_id, &
                              long_name, '1', si='', coords=[w%snap_t_id])
        call w%close_dataset(dset_id, GROUP//'/'//name)
    end subroutine create_index

    !> Append values to GROUP/name from entry `at` (every append opens and closes it).
    subroutine append(w, name, at, values)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        integer(hsize_t), intent(in) :: at
        real(dp), intent(in) :: values(:)
        integer(hid_t) :: dset_id
        integer :: hdferr

        call h5dopen_f(w%file_id, GROUP//'/'//name, dset_id, hdferr)
        call w%check(hdferr, 'h5dopen_f '//GROUP//'/'//name)
        call w%append_rows(dset_id, GROUP//'/'//name, at, [int(size(values), hsize_t)], values)
        call w%close_dataset(dset_id, GROUP//'/'//name)
    end subroutine append

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
                call w%create_dataset(trim(paths(k, part)), H5T_IEEE_F64LE, CHUNK, &
                                      w%estimates%ids(k + N_OUTPUT_FIELDS * (part - 1)), &
                                      'estimated relative L2 error of '// &
                                      trim(FIELDS(OUTPUT_ORDER(k))%long_name)// &
                                      ' at each snapshot '//trim(WHAT(part)), '1')
            end do
        end do
    end subroutine open_estimate

end submodule output_snapshot_s
