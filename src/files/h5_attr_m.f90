!> HDF5 attributes on any object (the root group or a dataset), split out of output_m: one
!> routine per stored type. Each replaces an attribute of the same name (HDF5 cannot
!> re-create one in place, and end-of-run values overwrite earlier ones) and returns in
!> `failed` the HDF5 call that failed ('' when all went well), so the caller decides how to
!> fail (output_m: abandon the file, exit 4).
module h5_attr_m
    use iso_c_binding, only: c_ptr, c_char, c_loc, c_null_char
    use kinds_m, only: dp
    use errors_m, only: check_allocation
    use hdf5, only: hid_t, hsize_t, h5screate_f, h5screate_simple_f, h5sclose_f, h5acreate_f, h5aclose_f, &
                    h5awrite_f, h5aexists_f, h5adelete_f, h5tcopy_f, h5tclose_f, h5tset_cset_f, &
                    H5S_SCALAR_F, H5S_NULL_F, H5T_STRING, H5T_CSET_UTF8_F, H5T_IEEE_F64LE, H5T_STD_I32LE, &
                    H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER
    implicit none
    private
    public :: put_attr_real, put_attr_int, put_attr_str, put_attr_real_array

contains

    !> Scalar float64 attribute.
    subroutine put_attr_real(obj_id, name, value, failed)
        integer(hid_t), intent(in) :: obj_id
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: value
        character(len=:), allocatable, intent(out) :: failed
        integer(hid_t) :: space_id, attr_id
        integer :: hdferr

        failed = ''
        call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
        if (hdferr < 0) failed = 'h5screate_f for attribute '//name
        if (failed == '') call new_attr(obj_id, name, H5T_IEEE_F64LE, space_id, attr_id, failed)
        if (failed /= '') return
        call h5awrite_f(attr_id, H5T_NATIVE_DOUBLE, value, [1_hsize_t], hdferr)
        if (hdferr < 0) failed = 'h5awrite_f attribute '//name
        call close_attr(name, space_id, attr_id, failed)
    end subroutine put_attr_real

    !> Scalar int32 attribute.
    subroutine put_attr_int(obj_id, name, value, failed)
        integer(hid_t), intent(in) :: obj_id
        character(len=*), intent(in) :: name
        integer, intent(in) :: value
        character(len=:), allocatable, intent(out) :: failed
        integer(hid_t) :: space_id, attr_id
        integer :: hdferr

        failed = ''
        call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
        if (hdferr < 0) failed = 'h5screate_f for attribute '//name
        if (failed == '') call new_attr(obj_id, name, H5T_STD_I32LE, space_id, attr_id, failed)
        if (failed /= '') return
        call h5awrite_f(attr_id, H5T_NATIVE_INTEGER, value, [1_hsize_t], hdferr)
        if (hdferr < 0) failed = 'h5awrite_f attribute '//name
        call close_attr(name, space_id, attr_id, failed)
    end subroutine put_attr_int

    !> Float64 array attribute (e.g. polynomial coefficients). An empty array is stored with
    !> a null dataspace (h5py: h5py.Empty).
    subroutine put_attr_real_array(obj_id, name, values, failed)
        integer(hid_t), intent(in) :: obj_id
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: values(:)
        character(len=:), allocatable, intent(out) :: failed
        integer(hid_t) :: space_id, attr_id
        integer(hsize_t) :: dims(1)
        integer :: hdferr

        failed = ''
        dims = int(size(values), hsize_t)
        if (size(values) > 0) then
            call h5screate_simple_f(1, dims, space_id, hdferr)
        else
            call h5screate_f(H5S_NULL_F, space_id, hdferr)
        end if
        if (hdferr < 0) failed = 'h5screate_f for attribute '//name
        if (failed == '') call new_attr(obj_id, name, H5T_IEEE_F64LE, space_id, attr_id, failed)
        if (failed /= '') return
        if (size(values) > 0) then
            call h5awrite_f(attr_id, H5T_NATIVE_DOUBLE, values, dims, hdferr)
            if (hdferr < 0) failed = 'h5awrite_f attribute '//name
        end if
        call close_attr(name, space_id, attr_id, failed)
    end subroutine put_attr_real_array

    !> String attribute, stored as a scalar variable-length UTF-8 string: h5py returns it as
    !> str (`f.attrs['status'] == 'complete'`), with no padding to strip.
    subroutine put_attr_str(obj_id, name, value, failed)
        integer(hid_t), intent(in) :: obj_id
        character(len=*), intent(in) :: name
        character(len=*), intent(in) :: value
        character(len=:), allocatable, intent(out) :: failed
        integer(hid_t) :: type_id, space_id, attr_id
        integer :: hdferr, i, stat
        character(len=256) :: message
        character(kind=c_char), allocatable, target :: chars(:)
        type(c_ptr), target :: str_ptr(1)
        type(c_ptr) :: buf_ptr

        failed = ''
        ! a variable-length string is written as a pointer to a NUL-terminated C string
        allocate (chars(len(value) + 1), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the attribute '''//name//'''')
        do i = 1, len(value)
            chars(i) = value(i:i)
        end do
        chars(len(value) + 1) = c_null_char
        str_ptr(1) = c_loc(chars)
        buf_ptr = c_loc(str_ptr)

        call h5tcopy_f(H5T_STRING, type_id, hdferr)
        if (hdferr < 0) then
            failed = 'h5tcopy_f (string type) for attribute '//name
            return
        end if
        call h5tset_cset_f(type_id, H5T_CSET_UTF8_F, hdferr)
        if (hdferr < 0) failed = 'h5tset_cset_f for attribute '//name
        if (failed == '') then
            call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
            if (hdferr < 0) failed = 'h5screate_f for attribute '//name
        end if
        if (failed == '') call new_attr(obj_id, name, type_id, space_id, attr_id, failed)
        if (failed == '') then
            call h5awrite_f(attr_id, type_id, buf_ptr, hdferr)
            if (hdferr < 0) failed = 'h5awrite_f attribute '//name
            call close_attr(name, space_id, attr_id, failed)
        end if
        call h5tclose_f(type_id, hdferr)
        if (hdferr < 0 .and. failed == '') failed = 'h5tclose_f (string type) for attribute '//name
    end subroutine put_attr_str

    !> Create attribute `name` on obj_id, deleting an older one of that name first.
    subroutine new_attr(obj_id, name, file_type, space_id, attr_id, failed)
        integer(hid_t), intent(in) :: obj_id, file_type, space_id
        character(len=*), intent(in) :: name
        integer(hid_t), intent(out) :: attr_id
        character(len=:), allocatable, intent(inout) :: failed
        logical :: exists
        integer :: hdferr

        attr_id = -1
        call h5aexists_f(obj_id, name, exists, hdferr)
        if (hdferr < 0) then
            failed = 'h5aexists_f attribute '//name
            return
        end if
        if (exists) then
            call h5adelete_f(obj_id, name, hdferr)
            if (hdferr < 0) then
                failed = 'h5adelete_f attribute '//name
                return
            end if
        end if
        call h5acreate_f(obj_id, name, file_type, space_id, attr_id, hdferr)
        if (hdferr < 0) failed = 'h5acreate_f attribute '//name
    end subroutine new_attr

    !> Close the attribute and its dataspace; the first failure is the one reported.
    subroutine close_attr(name, space_id, attr_id, failed)
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: space_id, attr_id
        character(len=:), allocatable, intent(inout) :: failed
        integer :: hdferr

        call h5aclose_f(attr_id, hdferr)
        if (hdferr < 0 .and. failed == '') failed = 'h5aclose_f attribute '//name
        call h5sclose_f(space_id, hdferr)
        if (hdferr < 0 .and. failed == '') failed = 'h5sclose_f for attribute '//name
    end subroutine close_attr

end module h5_attr_m
