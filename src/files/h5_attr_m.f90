!> HDF5 attributes on any object (the root group or a dataset): put_attr writes one of every
!> stored type (float64, int32, a UTF-8 string) and rank (a scalar, or a float64 array). It
!> replaces an attribute of the same name (HDF5 cannot re-create one in place, and end-of-run
!> values overwrite earlier ones) and returns in `failed` the HDF5 call that failed ('' when
!> all went well), so the caller decides how to fail (output_m: abandon the file, exit 4).
module h5_attr_m
    use iso_c_binding, only: c_ptr, c_char, c_loc, c_null_char
    use kinds_m, only: dp
    use hdf5, only: hid_t, hsize_t, h5screate_f, h5screate_simple_f, h5sclose_f, h5acreate_f, h5aclose_f, &
                    h5awrite_f, h5aexists_f, h5adelete_f, h5tcopy_f, h5tclose_f, h5tset_cset_f, &
                    H5S_SCALAR_F, H5S_NULL_F, H5T_STRING, H5T_CSET_UTF8_F, H5T_IEEE_F64LE, H5T_STD_I32LE, &
                    H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER
    implicit none
    private
    public :: put_attr

    !> put_attr(obj_id, name, value, failed): value a real(dp), an integer or a string
    !> (scalars), or a real(dp) array (an empty one is stored with a null dataspace, h5py:
    !> h5py.Empty).
    interface put_attr
        module procedure put_attr_scalar, put_attr_array
    end interface put_attr

contains

    !> A scalar attribute: float64, int32, or a variable-length UTF-8 string (h5py returns it
    !> as str, `f.attrs['status'] == 'complete'`, with no padding to strip).
    subroutine put_attr_scalar(obj_id, name, value, failed)
        integer(hid_t), intent(in) :: obj_id
        character(len=*), intent(in) :: name
        class(*), intent(in), target :: value
        character(len=:), allocatable, intent(out) :: failed

        failed = ''
        select type (value)
        type is (real(dp))
            call put_values(obj_id, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, -1, c_loc(value), failed)
        type is (integer)
            call put_values(obj_id, name, H5T_STD_I32LE, H5T_NATIVE_INTEGER, -1, c_loc(value), failed)
        type is (character(len=*))
            call put_str(obj_id, name, value, failed)
        class default
            failed = 'internal error: an attribute of an unknown type, '//name
        end select
    end subroutine put_attr_scalar

    !> A float64 array attribute (e.g. polynomial coefficients).
    subroutine put_attr_array(obj_id, name, values, failed)
        integer(hid_t), intent(in) :: obj_id
        character(len=*), intent(in) :: name
        real(dp), intent(in), target, contiguous :: values(:)
        character(len=:), allocatable, intent(out) :: failed

        failed = ''
        call put_values(obj_id, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, size(values), &
                        c_loc(values), failed)
    end subroutine put_attr_array

    !> A string: a variable-length string is written as a pointer to a NUL-terminated C string.
    subroutine put_str(obj_id, name, value, failed)
        integer(hid_t), intent(in) :: obj_id
        character(len=*), intent(in) :: name
        character(len=*), intent(in) :: value
        character(len=:), allocatable, intent(inout) :: failed
        character(kind=c_char, len=len(value) + 1), target :: chars
        type(c_ptr), target :: str_ptr(1)
        integer(hid_t) :: type_id
        integer :: hdferr

        chars = value//c_null_char
        str_ptr(1) = c_loc(chars)
        call h5tcopy_f(H5T_STRING, type_id, hdferr)
        if (hdferr < 0) failed = 'h5tcopy_f (string type) for attribute '//name
        if (failed /= '') return
        call h5tset_cset_f(type_id, H5T_CSET_UTF8_F, hdferr)
        if (hdferr < 0) failed = 'h5tset_cset_f for attribute '//name
        if (failed == '') call put_values(obj_id, name, type_id, type_id, -1, c_loc(str_ptr), failed)
        call h5tclose_f(type_id, hdferr)
        if (hdferr < 0 .and. failed == '') failed = 'h5tclose_f (string type) for attribute '//name
    end subroutine put_str

    !> Attribute `name` of type file_type on obj_id, replacing an older one of that name, from
    !> buf in mem_type: a scalar (n < 0), empty (n = 0: a null dataspace) or n values.
    subroutine put_values(obj_id, name, file_type, mem_type, n, buf, failed)
        integer(hid_t), intent(in) :: obj_id, file_type, mem_type
        character(len=*), intent(in) :: name
        integer, intent(in) :: n
        type(c_ptr), intent(in) :: buf
        character(len=:), allocatable, intent(inout) :: failed
        integer(hid_t) :: space_id, attr_id
        logical :: exists
        integer :: hdferr

        if (n < 0) call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
        if (n == 0) call h5screate_f(H5S_NULL_F, space_id, hdferr)
        if (n > 0) call h5screate_simple_f(1, [int(n, hsize_t)], space_id, hdferr)
        if (hdferr < 0) failed = 'h5screate_f for attribute '//name
        if (failed == '') call h5aexists_f(obj_id, name, exists, hdferr)
        if (failed == '' .and. hdferr < 0) failed = 'h5aexists_f attribute '//name
        if (failed == '' .and. exists) call h5adelete_f(obj_id, name, hdferr)
        if (failed == '' .and. hdferr < 0) failed = 'h5adelete_f attribute '//name
        if (failed == '') call h5acreate_f(obj_id, name, file_type, space_id, attr_id, hdferr)
        if (failed == '' .and. hdferr < 0) failed = 'h5acreate_f attribute '//name
        if (failed /= '') return
        if (n /= 0) call h5awrite_f(attr_id, mem_type, buf, hdferr)
        if (hdferr < 0) failed = 'h5awrite_f attribute '//name
        call h5aclose_f(attr_id, hdferr)
        if (hdferr < 0 .and. failed == '') failed = 'h5aclose_f attribute '//name
        call h5sclose_f(space_id, hdferr)
        if (hdferr < 0 .and. failed == '') failed = 'h5sclose_f for attribute '//name
    end subroutine put_values

end module h5_attr_m
