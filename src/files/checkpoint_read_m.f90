!> Reading a checkpoint slot of a file, or the history (/series, /snapshots) restart_m
!> copies: every dataset under a group into a checkpoint_t record as entry '<path below the
!> group>', and each member of a compound (an owner's scalars) as '<its group's
!> path>/<member>'; integers as integers. What the entries mean is their owners' business
!> (checkpoint_m). A file that cannot be read stops the run with exit 2 (EXIT_INPUT).
module checkpoint_read_m
    use iso_c_binding, only: c_loc, c_ptr
    use iso_fortran_env, only: int64
    use errors_m, only: fatal, check_allocation, EXIT_INPUT
    use checkpoint_m, only: checkpoint_t, entry_t
    use h5_read_m, only: open_file
    use hdf5, only: hid_t, hsize_t, h5fclose_f, h5gopen_f, h5gclose_f, &
                    h5gget_info_f, h5lget_name_by_idx_f, H5_INDEX_NAME_F, H5_ITER_INC_F, h5oopen_f, h5oclose_f, &
                    h5iget_type_f, H5I_GROUP_F, h5dopen_f, h5dclose_f, h5dread_f, h5dget_type_f, h5tget_class_f, &
                    h5tclose_f, h5dget_space_f, h5sget_simple_extent_ndims_f, &
                    h5sget_simple_extent_dims_f, h5sclose_f, H5T_NATIVE_DOUBLE, h5kind_to_type, H5_INTEGER_KIND, &
                    h5tget_nmembers_f, h5tget_member_class_f, h5tget_member_name_f, h5tget_native_type_f, &
                    H5T_DIR_ASCEND_F, H5T_COMPOUND_F, H5T_INTEGER_F
    implicit none
    private
    public :: read_entries

contains

    !> Every dataset under `group` of `file` (e.g. '/checkpoint/slot1'), into ckpt.
    subroutine read_entries(file, group, ckpt)
        character(len=*), intent(in) :: file, group
        type(checkpoint_t), intent(inout) :: ckpt
        integer(hid_t) :: file_id
        integer :: hdferr

        ckpt%source = file
        ckpt%reading = .true.
        file_id = open_file(file, group)
        call read_below(file, file_id, group, '', ckpt)
        call h5fclose_f(file_id, hdferr)
        call require(hdferr, file, group, 'h5fclose_f')
    end subroutine read_entries

    !> The datasets of group//'/'//path and of its subgroups, as entries path/...
    recursive subroutine read_below(file, file_id, group, path, ckpt)
        character(len=*), intent(in) :: file, group, path
        integer(hid_t), intent(in) :: file_id
        type(checkpoint_t), intent(inout) :: ckpt
        integer(hid_t) :: group_id, obj_id
        integer :: hdferr, storage, n_links, max_order, k, obj_type
        integer(hsize_t) :: k_link
        character(len=64) :: name
        character(len=:), allocatable :: here

        here = group//path
        call h5gopen_f(file_id, here, group_id, hdferr)
        call require(hdferr, file, here, 'h5gopen_f')
        call h5gget_info_f(group_id, storage, n_links, max_order, hdferr)
        call require(hdferr, file, here, 'h5gget_info_f')
        do k = 0, n_links - 1
            k_link = int(k, hsize_t)
            call h5lget_name_by_idx_f(group_id, '.', H5_INDEX_NAME_F, H5_ITER_INC_F, k_link, name, hdferr)
            call require(hdferr, file, here, 'h5lget_name_by_idx_f')
            call h5oopen_f(group_id, trim(name), obj_id, hdferr)
            call require(hdferr, file, here//'/'//trim(name), 'h5oopen_f')
            call h5iget_type_f(obj_id, obj_type, hdferr)
            call h5oclose_f(obj_id, hdferr)
            if (obj_type == H5I_GROUP_F) then
                call read_below(file, file_id, group, path//'/'//trim(name), ckpt)
            else
                call read_dataset(file, group_id, here//'/'//trim(name), path//'/', ckpt)
            end if
        end do
        call h5gclose_f(group_id, hdferr)
    end subroutine read_below

    !> The dataset `where` (in group_id: its last part) as entry prefix(2:)//<its name>; a
    !> compound (an owner's scalars: every member 8 bytes, int64 or float64) read whole, as
    !> output_checkpoint_s writes it, into the scalar entries prefix(2:)//<member>, one a member.
    subroutine read_dataset(file, group_id, where, prefix, ckpt)
        character(len=*), intent(in) :: file, where, prefix
        integer(hid_t), intent(in) :: group_id
        type(checkpoint_t), intent(inout) :: ckpt
        type(entry_t), target :: entry
        integer(hid_t) :: dset_id, type_id, space_id, mem_type
        integer(hsize_t) :: dims(2), maxdims(2)
        integer :: hdferr, type_class, m, n, stat
        character(len=256) :: message
        type(c_ptr) :: buf

        call h5dopen_f(group_id, where(index(where, '/', back=.true.) + 1:), dset_id, hdferr)
        call require(hdferr, file, where, 'h5dopen_f')
        call h5dget_type_f(dset_id, type_id, hdferr)
        call h5tget_class_f(type_id, type_class, hdferr)
        call require(hdferr, file, where, 'h5tget_class_f')
        call h5dget_space_f(dset_id, space_id, hdferr)
        call h5sget_simple_extent_ndims_f(space_id, entry%rank, hdferr)
        if (entry%rank > 2) call require(-1, file, where, 'a rank above 2')
        dims = 1
        if (entry%rank > 0) call h5sget_simple_extent_dims_f(space_id, dims, maxdims, hdferr)
        call require(hdferr, file, where, 'h5sget_simple_extent_dims_f')
        call h5sclose_f(space_id, hdferr)
        n = 1
        mem_type = merge(h5kind_to_type(int64, H5_INTEGER_KIND), H5T_NATIVE_DOUBLE, type_class == H5T_INTEGER_F)
        if (type_class == H5T_COMPOUND_F) then
            call h5tget_nmembers_f(type_id, n, hdferr)
            call require(hdferr, file, where, 'h5tget_nmembers_f')
            call h5tget_native_type_f(type_id, H5T_DIR_ASCEND_F, mem_type, hdferr)
            call require(hdferr, file, where, 'h5tget_native_type_f')
        end if
        allocate (entry%values(n * product(dims)), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'a checkpoint entry')
        buf = c_loc(entry%values)
        if (size(entry%values) > 0) call h5dread_f(dset_id, mem_type, buf, hdferr)
        call require(hdferr, file, where, 'h5dread_f')
        if (type_class == H5T_COMPOUND_F) then
            do m = 0, n - 1
                call h5tget_member_class_f(type_id, m, type_class, hdferr)
                call ckpt%add(entry_t(prefix(2:)//member_name(type_id, m), type_class == H5T_INTEGER_F, 0, [1, 1], &
                                      entry%values(m + 1:m + 1)))
            end do
            call h5tclose_f(mem_type, hdferr)
        else
            entry%name = prefix(2:)//where(index(where, '/', back=.true.) + 1:)
            entry%dims = int(dims)
            entry%is_integer = type_class == H5T_INTEGER_F
            call ckpt%add(entry)
        end if
        call h5tclose_f(type_id, hdferr)
        call h5dclose_f(dset_id, hdferr)
    end subroutine read_dataset

    !> Member m (from 0) of compound type type_id.
    function member_name(type_id, m) result(name)
        integer(hid_t), intent(in) :: type_id
        integer, intent(in) :: m
        character(len=:), allocatable :: name
        character(len=64) :: buffer
        integer :: length, hdferr

        call h5tget_member_name_f(type_id, m, buffer, length, hdferr)
        name = buffer(:min(length, len(buffer)))
    end function member_name

    subroutine require(hdferr, file, what, call_name)
        integer, intent(in) :: hdferr
        character(len=*), intent(in) :: file, what, call_name

        if (hdferr < 0) call fatal(EXIT_INPUT, 'time.restart_from', "cannot read '"//what//"' from '"//file// &
                                   "': "//call_name//' failed')
    end subroutine require

end module checkpoint_read_m
