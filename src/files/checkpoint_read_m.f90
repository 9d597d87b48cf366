!> Reading a checkpoint slot of a file (restart_m): every dataset under a group, whatever
!> its owner, into a checkpoint_t record as entry '<path below the group>', integers as
!> integers. What the entries mean is their owners' business (checkpoint_m). A file that
!> cannot be read stops the run with exit 2 (EXIT_INPUT), as h5_read_m does.
module checkpoint_read_m
    use iso_c_binding, only: c_loc, c_ptr
    use iso_fortran_env, only: int64
    use kinds_m, only: dp
    use errors_m, only: fatal, check_allocation, EXIT_INPUT
    use checkpoint_m, only: checkpoint_t, entry_t
    use h5_read_m, only: h5_library_init
    use h5_swmr_m, only: open_swmr_read
    use hdf5, only: hid_t, hsize_t, h5fopen_f, h5fclose_f, H5F_ACC_RDONLY_F, h5gopen_f, h5gclose_f, &
                    h5gget_info_f, h5lget_name_by_idx_f, H5_INDEX_NAME_F, H5_ITER_INC_F, h5oopen_f, h5oclose_f, &
                    h5iget_type_f, H5I_GROUP_F, h5dopen_f, h5dclose_f, h5dread_f, h5dget_type_f, h5tget_class_f, &
                    h5tclose_f, H5T_INTEGER_F, h5dget_space_f, h5sget_simple_extent_ndims_f, &
                    h5sget_simple_extent_dims_f, h5sclose_f, H5T_NATIVE_DOUBLE, h5kind_to_type, H5_INTEGER_KIND, &
                    h5aexists_by_name_f, h5tget_nmembers_f, h5tget_member_class_f, h5tget_member_name_f, &
                    h5tcreate_f, h5tinsert_f, H5T_COMPOUND_F, size_t
    implicit none
    private
    public :: read_entries, has_group_attribute

contains

    !> Every dataset under `group` of `file` (e.g. '/checkpoint/slot1'), into ckpt.
    subroutine read_entries(file, group, ckpt)
        character(len=*), intent(in) :: file, group
        type(checkpoint_t), intent(inout) :: ckpt
        integer(hid_t) :: file_id
        integer :: hdferr

        ckpt%source = file
        file_id = open_file(file)
        call read_below(file, file_id, group, '', ckpt)
        call h5fclose_f(file_id, hdferr)
        call require(hdferr, file, group, 'h5fclose_f')
    end subroutine read_entries

    !> Has `group` of `file` the attribute `name` (/checkpoint's layout)?
    logical function has_group_attribute(file, group, name) result(yes)
        character(len=*), intent(in) :: file, group, name
        integer(hid_t) :: file_id
        integer :: hdferr

        file_id = open_file(file)
        call h5aexists_by_name_f(file_id, group, name, yes, hdferr)
        call require(hdferr, file, group, 'h5aexists_by_name_f '//name)
        call h5fclose_f(file_id, hdferr)
    end function has_group_attribute

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
            else if (trim(name) == 'scalars') then
                call read_scalars(file, group_id, here//'/scalars', path(2:)//'/', ckpt)
            else
                call ckpt%add(read_entry(file, group_id, here//'/'//trim(name), path(2:)//'/'//trim(name)))
            end if
        end do
        call h5gclose_f(group_id, hdferr)
    end subroutine read_below

    !> The dataset `where` (name in its group: the last part) as entry `name`.
    function read_entry(file, group_id, where, name) result(entry)
        character(len=*), intent(in) :: file, where, name
        integer(hid_t), intent(in) :: group_id
        type(entry_t), target :: entry
        integer(hid_t) :: dset_id, type_id, space_id
        integer(hsize_t) :: dims(2), maxdims(2)
        integer :: hdferr, type_class, stat
        character(len=256) :: message
        type(c_ptr) :: buf

        call h5dopen_f(group_id, where(index(where, '/', back=.true.) + 1:), dset_id, hdferr)
        call require(hdferr, file, where, 'h5dopen_f')
        call h5dget_type_f(dset_id, type_id, hdferr)
        call h5tget_class_f(type_id, type_class, hdferr)
        call h5tclose_f(type_id, hdferr)
        call h5dget_space_f(dset_id, space_id, hdferr)
        call h5sget_simple_extent_ndims_f(space_id, entry%rank, hdferr)
        dims = 1
        if (entry%rank > 2) call require(-1, file, where, 'a rank above 2')
        if (entry%rank > 0) call h5sget_simple_extent_dims_f(space_id, dims(:entry%rank), maxdims(:entry%rank), hdferr)
        call require(hdferr, file, where, 'h5sget_simple_extent_dims_f')
        call h5sclose_f(space_id, hdferr)
        entry%name = name
        entry%dims = int(dims)
        entry%is_integer = type_class == H5T_INTEGER_F
        if (entry%is_integer) then
            allocate (entry%ints(product(entry%dims)), stat=stat, errmsg=message)
            call check_allocation(stat, message, 'a checkpoint entry')
            buf = c_loc(entry%ints)
            if (size(entry%ints) > 0) call h5dread_f(dset_id, h5kind_to_type(int64, H5_INTEGER_KIND), buf, hdferr)
        else
            allocate (entry%reals(product(entry%dims)), stat=stat, errmsg=message)
            call check_allocation(stat, message, 'a checkpoint entry')
            buf = c_loc(entry%reals)
            if (size(entry%reals) > 0) call h5dread_f(dset_id, H5T_NATIVE_DOUBLE, buf, hdferr)
        end if
        call require(hdferr, file, where, 'h5dread_f')
        call h5dclose_f(dset_id, hdferr)
    end function read_entry

    !> An owner's scalars, the compound dataset `where`: each member as entry prefix//member
    !> (every member 8 bytes: int64 or float64).
    subroutine read_scalars(file, group_id, where, prefix, ckpt)
        character(len=*), intent(in) :: file, where, prefix
        integer(hid_t), intent(in) :: group_id
        type(checkpoint_t), intent(inout) :: ckpt
        integer(hid_t) :: dset_id, type_id, mem_type
        integer(int64), allocatable, target :: values(:)
        integer :: hdferr, n, m, member_class, stat
        character(len=64) :: member
        character(len=256) :: message
        type(c_ptr) :: buf
        logical, allocatable :: is_integer(:)

        call h5dopen_f(group_id, 'scalars', dset_id, hdferr)
        call require(hdferr, file, where, 'h5dopen_f')
        call h5dget_type_f(dset_id, type_id, hdferr)
        call h5tget_nmembers_f(type_id, n, hdferr)
        call require(hdferr, file, where, 'h5tget_nmembers_f')
        allocate (values(n), is_integer(n), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'a checkpoint entry')
        call h5tcreate_f(H5T_COMPOUND_F, int(8 * n, size_t), mem_type, hdferr)
        do m = 1, n
            call h5tget_member_class_f(type_id, m - 1, member_class, hdferr)
            is_integer(m) = member_class == H5T_INTEGER_F
            call h5tinsert_f(mem_type, member_name(type_id, m - 1), int(8 * (m - 1), size_t), &
                             merge(h5kind_to_type(int64, H5_INTEGER_KIND), H5T_NATIVE_DOUBLE, is_integer(m)), hdferr)
            call require(hdferr, file, where, 'h5tinsert_f')
        end do
        buf = c_loc(values)
        call h5dread_f(dset_id, mem_type, buf, hdferr)
        call require(hdferr, file, where, 'h5dread_f')
        do m = 1, n
            member = member_name(type_id, m - 1)
            if (is_integer(m)) then
                call ckpt%add(entry_t(prefix//trim(member), .true., 0, [1, 1], null(), [values(m)]))
            else
                call ckpt%add(entry_t(prefix//trim(member), .false., 0, [1, 1], [transfer(values(m), 1.0_dp)], null()))
            end if
        end do
        call h5tclose_f(mem_type, hdferr)
        call h5tclose_f(type_id, hdferr)
        call h5dclose_f(dset_id, hdferr)
    end subroutine read_scalars

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

    !> `file` opened for reading; the .h5.part of a killed run as a SWMR reader (h5_swmr_m).
    function open_file(file) result(file_id)
        character(len=*), intent(in) :: file
        integer(hid_t) :: file_id
        integer :: hdferr

        call h5_library_init()
        call h5fopen_f(file, H5F_ACC_RDONLY_F, file_id, hdferr)
        if (hdferr < 0) then
            file_id = open_swmr_read(file)
            hdferr = merge(0, -1, file_id >= 0)
        end if
        call require(hdferr, file, '/', 'h5fopen_f')
    end function open_file

    subroutine require(hdferr, file, what, call_name)
        integer, intent(in) :: hdferr
        character(len=*), intent(in) :: file, what, call_name

        if (hdferr < 0) call fatal(EXIT_INPUT, 'time.restart_from', "cannot read '"//what//"' from '"//file// &
                                   "': "//call_name//' failed')
    end subroutine require

end module checkpoint_read_m
