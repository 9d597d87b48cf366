!> The snapshots of an adaptive mesh on their own meshes (/snapshots/native, docs/output.md):
!> a submodule of output_m, so that it reaches the writer's open file.
!>
!>     /snapshots/native/x, /snapshots/native/<field>   (sum of counts,)  float64
!>     /snapshots/native/offset, /snapshots/native/count (n_snap,)        int64
!>
!> Snapshot j holds the nodes x[offset[j] : offset[j] + count[j]] and the exact nodal
!> values of every field there (the P1 solution the run computed); /snapshots/<field>
!> hold the same P1 functions evaluated on the fixed grid /mesh/x. Every append opens,
!> extends, writes and closes the datasets.
submodule (output_m) output_native_s
    use hdf5, only: h5dopen_f, H5T_STD_I64LE
    implicit none

    character(len=*), parameter :: GROUP = '/snapshots/native'
    integer, parameter :: VALUES_CHUNK = 4096   !< float64 entries per chunk (32 KiB)

contains

    !> Append one snapshot on its own mesh: nodes x(0:s), values(0:s, k) of the field
    !> fields_m's SNAPSHOTS(k).
    module subroutine writer_append_native(w, x, values)
        class(h5_writer_t), intent(inout) :: w
        real(dp), intent(in) :: x(:)
        real(dp), intent(in) :: values(:, :)
        integer(hsize_t) :: n
        integer :: k

        if (.not. w%opened) call fatal(EXIT_OUTPUT, 'output', 'internal error: append_native() on a closed writer')
        if (size(values, 1) /= size(x) .or. size(values, 2) /= N_SNAPSHOT_FIELDS) &
            call w%fail('internal error: append_native() given fields that do not match the nodes')
        if (.not. w%native_created) call writer_create_native(w)
        n = int(size(x), hsize_t)
        call append_real(w, 'x', x, n)
        do k = 1, N_SNAPSHOT_FIELDS
            call append_real(w, trim(SNAPSHOTS(k)%name), values(:, k), n)
        end do
        call append_int(w, 'offset', w%n_native_values)
        call append_int(w, 'count', int(n, int64))
        w%n_native_values = w%n_native_values + int(n, int64)
        w%n_native_snap = w%n_native_snap + 1
    end subroutine writer_append_native

    !> The group and its empty datasets. Dimension scales (docs/output.md, "netCDF"): native/x
    !> is the coordinate of the fields (dimension x of this group: every snapshot's nodes one
    !> after the other), /snapshots/t that of offset and count. Created by the first append,
    !> or by the first checkpoint of an adaptive mesh (write_checkpoint), so that SWMR
    !> writing need not end for it later (output_file_s).
    module subroutine writer_create_native(w)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t) :: group_id, dset_id, x_id
        integer(hsize_t) :: dims(1)
        integer :: hdferr, k

        call w%leave_swmr()
        call h5gcreate_f(w%file_id, GROUP, group_id, hdferr)
        call w%check(hdferr, 'h5gcreate_f '//GROUP)
        w%native_created = .true.
        dims = 0
        call w%create_extendible(group_id, GROUP//'/', 'x', H5T_IEEE_F64LE, dims, [int(VALUES_CHUNK, hsize_t)], x_id)
        call w%describe(x_id, GROUP//'/x', 'nodes of the mesh of each snapshot, concatenated (see offset, count)', '1')
        call w%describe_si_of(x_id, 'position')
        call w%make_scale(x_id, 'x', GROUP//'/x')
        do k = 1, N_SNAPSHOT_FIELDS
            associate (field => SNAPSHOTS(k))
                call w%create_extendible(group_id, GROUP//'/', trim(field%name), H5T_IEEE_F64LE, dims, &
                                         [int(VALUES_CHUNK, hsize_t)], dset_id)
                call w%describe(dset_id, GROUP//'/'//trim(field%name), described(trim(field%long_name)// &
                                ' at the nodes of its own mesh (native/x)', field%scale), field%units)
                call w%describe_si_of(dset_id, field%scale)
                call w%attach_scale(dset_id, x_id, 0, GROUP//'/'//trim(field%name))
                call close_dataset(w, dset_id, trim(field%name))
            end associate
        end do
        call close_dataset(w, x_id, 'x')
        call w%create_extendible(group_id, GROUP//'/', 'offset', H5T_STD_I64LE, dims, [int(SERIES_CHUNK, hsize_t)], &
                                 dset_id)
        call w%describe(dset_id, GROUP//'/offset', 'first entry of each snapshot in native/x and the fields', '1')
        call w%describe_si_of(dset_id, '')
        call w%attach_scale(dset_id, w%snap_t_id, 0, GROUP//'/offset')
        call close_dataset(w, dset_id, 'offset')
        call w%create_extendible(group_id, GROUP//'/', 'count', H5T_STD_I64LE, dims, [int(SERIES_CHUNK, hsize_t)], &
                                 dset_id)
        call w%describe(dset_id, GROUP//'/count', 'number of nodes of each snapshot''s mesh', '1')
        call w%describe_si_of(dset_id, '')
        call w%attach_scale(dset_id, w%snap_t_id, 0, GROUP//'/count')
        call close_dataset(w, dset_id, 'count')
        call h5gclose_f(group_id, hdferr)
        call w%check(hdferr, 'h5gclose_f '//GROUP)
    end subroutine writer_create_native

    subroutine close_dataset(w, dset_id, name)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: dset_id
        character(len=*), intent(in) :: name
        integer :: hdferr

        call h5dclose_f(dset_id, hdferr)
        call w%check(hdferr, 'h5dclose_f '//GROUP//'/'//name)
    end subroutine close_dataset

    !> Append n float64 values to GROUP/name (which holds w%n_native_values).
    subroutine append_real(w, name, values, n)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: values(:)
        integer(hsize_t), intent(in) :: n
        integer(hid_t) :: dset_id, file_space, mem_space
        integer :: hdferr

        call h5dopen_f(w%file_id, GROUP//'/'//name, dset_id, hdferr)
        call w%check(hdferr, 'h5dopen_f '//GROUP//'/'//name)
        call w%select_append(dset_id, GROUP//'/'//name, [n], int(w%n_native_values, hsize_t), file_space, mem_space)
        call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, values, [n], hdferr, mem_space_id=mem_space, &
                        file_space_id=file_space)
        call w%check(hdferr, 'h5dwrite_f '//GROUP//'/'//name)
        call w%close_spaces(GROUP//'/'//name, file_space, mem_space)
        call close_dataset(w, dset_id, name)
    end subroutine append_real

    !> Append one int64 value to GROUP/name (which holds w%n_native_snap).
    subroutine append_int(w, name, value)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        integer(int64), intent(in) :: value
        integer(hid_t) :: dset_id, file_space, mem_space
        integer :: hdferr
        real(dp) :: as_real(1)

        call h5dopen_f(w%file_id, GROUP//'/'//name, dset_id, hdferr)
        call w%check(hdferr, 'h5dopen_f '//GROUP//'/'//name)
        call w%select_append(dset_id, GROUP//'/'//name, [1_hsize_t], w%n_native_snap, file_space, mem_space)
        ! written from a double (exact below 2^53): the HDF5 Fortran API converts to int64
        as_real = real(value, dp)
        call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, as_real, [1_hsize_t], hdferr, mem_space_id=mem_space, &
                        file_space_id=file_space)
        call w%check(hdferr, 'h5dwrite_f '//GROUP//'/'//name)
        call w%close_spaces(GROUP//'/'//name, file_space, mem_space)
        call close_dataset(w, dset_id, name)
    end subroutine append_int

end submodule output_native_s
