!> Small reader for rodcontact HDF5 files (docs/output.md): whole datasets and root
!> attributes, one call each (the file is opened and closed every time). Used by the tests,
!> and by restart and summary tools. Also owns the once-only HDF5 library start-up shared
!> with the writer (output_m). Every file it reads is an input of the run (a checkpoint to
!> restart from, a file to summarise): a file it cannot read stops the run with exit 2
!> (EXIT_INPUT), naming the file and what is missing.
!>
!> Shapes are Fortran's: a snapshot field that h5py shows as (n_snap, s+1) has dims
!> (s+1, n_snap); reshaped to them, values(:, k) is snapshot k.
module h5_read_m
    use iso_c_binding, only: c_ptr, c_char, c_loc
    use kinds_m, only: dp
    use errors_m, only: fatal, check_allocation, EXIT_INPUT, EXIT_OUTPUT
    use fsys_m, only: file_exists, from_c_string
    use strings_m, only: from_c_chars, int_str
    use h5_swmr_m, only: SWMR_READ, h5_free_memory
    use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5fis_hdf5_f, h5eset_auto_f, h5fopen_f, h5fclose_f, &
                    H5F_ACC_RDONLY_F, h5sclose_f, h5sget_simple_extent_npoints_f, h5aopen_f, h5aclose_f, &
                    h5aread_f, h5aexists_by_name_f, h5aget_space_f, h5aget_type_f, h5tclose_f, h5tget_class_f, &
                    h5tget_size_f, h5tis_variable_str_f, H5T_STRING_F, H5T_NATIVE_DOUBLE, &
                    h5oopen_f, h5oclose_f, h5iget_type_f, H5I_DATASET_F
    use h5lt, only: h5ltget_dataset_ndims_f, h5ltget_dataset_info_f, h5ltread_dataset_double_f, h5ltpath_valid_f
    implicit none
    private
    public :: h5_library_init
    public :: read_real_1d
    public :: read_attr_str, read_attr_real, read_attr_real_1d
    public :: dataset_exists, attr_exists, is_hdf5_file, open_file

    !> The HDF5 library is started once per process; this flag is the only module state.
    logical, save :: library_open = .false.

contains
    !> Start the HDF5 library (once). HDF5's automatic error-stack printing is switched off:
    !> every call's error flag is checked here and in output_m and reported with the file and
    !> operation, so the stack dump would only be noise on stderr. Set RODCONTACT_HDF5_ERRORS=1
    !> to keep it on when debugging. The library is never closed explicitly: HDF5 shuts
    !> itself down at exit, and an h5close_f while another reader or writer is open would
    !> invalidate its identifiers.
    subroutine h5_library_init()
        integer :: hdferr, env_len, env_status
        character(len=8) :: env_value

        if (library_open) return
        call h5open_f(hdferr)
        if (hdferr < 0) call fatal(EXIT_OUTPUT, 'hdf5', 'cannot initialise the HDF5 library (h5open_f)')
        call get_environment_variable('RODCONTACT_HDF5_ERRORS', env_value, env_len, env_status)
        if (env_status /= 0 .or. env_value /= '1') then
            call h5eset_auto_f(0, hdferr)
            if (hdferr < 0) &
                call fatal(EXIT_OUTPUT, 'hdf5', 'cannot configure HDF5 error printing (h5eset_auto_f)')
        end if
        library_open = .true.
    end subroutine h5_library_init

    !> Whole 1D float dataset `dset` (e.g. '/series/t') of `file`; with dims, a dataset of
    !> rank size(dims), its elements in Fortran order and dims its Fortran shape. Read as
    !> float64: HDF5 converts the stored type.
    subroutine read_real_1d(file, dset, values, dims)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: dset
        real(dp), allocatable, intent(out) :: values(:)
        integer(hsize_t), intent(out), optional :: dims(:)
        integer(hsize_t) :: extent(7)
        integer(hid_t) :: file_id
        integer(size_t) :: type_size
        integer :: hdferr, rank, wanted, type_class, stat
        character(len=256) :: message

        file_id = open_file(file, dset)
        call h5ltget_dataset_ndims_f(file_id, trim(dset), rank, hdferr)
        if (hdferr < 0) call fail(file, dset, 'no such dataset (h5ltget_dataset_ndims_f failed)')
        wanted = 1
        if (present(dims)) wanted = size(dims)
        if (rank /= wanted) &
            call fail(file, dset, 'dataset has rank '//int_str(rank)//', expected '//int_str(wanted))
        call h5ltget_dataset_info_f(file_id, trim(dset), extent(:rank), type_class, type_size, hdferr)
        if (hdferr < 0) call fail(file, dset, 'h5ltget_dataset_info_f failed')
        if (present(dims)) dims = extent(:rank)
        allocate (values(product(extent(:rank))), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'what is read from '''//trim(file)//'''')
        if (size(values) > 0) &
            call h5ltread_dataset_double_f(file_id, trim(dset), values, extent(:rank), hdferr)
        if (hdferr < 0) call fail(file, dset, 'h5ltread_dataset_double_f failed')
        call close_file(file, dset, file_id)
    end subroutine read_real_1d

    !> True when `file` exists, can be read and is an HDF5 file (h5fis_hdf5_f): the test to
    !> make before any other routine here, which stop with exit 2 on a file they cannot open.
    function is_hdf5_file(file) result(yes)
        character(len=*), intent(in) :: file
        logical :: yes
        integer :: hdferr

        call h5_library_init()
        yes = .false.
        if (.not. file_exists(file)) return
        call h5fis_hdf5_f(trim(file), yes, hdferr)
        if (hdferr < 0) yes = .false.
    end function is_hdf5_file

    !> True when `dset` exists in `file` and is a dataset (not a group).
    function dataset_exists(file, dset) result(yes)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: dset
        logical :: yes
        integer(hid_t) :: file_id, obj_id
        integer :: hdferr, obj_type

        file_id = open_file(file, dset)
        ! each group on the path, then the object (h5lexists_f fails on a missing group)
        call h5ltpath_valid_f(file_id, trim(dset), .true., yes, hdferr)
        if (hdferr < 0) call fail(file, dset, 'h5ltpath_valid_f failed')
        if (yes) then
            call h5oopen_f(file_id, trim(dset), obj_id, hdferr)
            if (hdferr < 0) call fail(file, dset, 'h5oopen_f failed')
            call h5iget_type_f(obj_id, obj_type, hdferr)
            if (hdferr < 0) call fail(file, dset, 'h5iget_type_f failed')
            yes = (obj_type == H5I_DATASET_F)
            call h5oclose_f(obj_id, hdferr)
            if (hdferr < 0) call fail(file, dset, 'h5oclose_f failed')
        end if
        call close_file(file, dset, file_id)
    end function dataset_exists

    !> True when the root group of `file` (or the group `group`) has attribute `name`.
    function attr_exists(file, name, group) result(yes)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: name
        character(len=*), intent(in), optional :: group
        logical :: yes
        integer(hid_t) :: file_id
        integer :: hdferr
        character(len=:), allocatable :: object

        object = '/'
        if (present(group)) object = group
        file_id = open_file(file, 'attribute '//name)
        call h5aexists_by_name_f(file_id, object, name, yes, hdferr)
        if (hdferr < 0) call fail(file, 'attribute '//name, 'h5aexists_by_name_f failed')
        call close_file(file, 'attribute '//name, file_id)
    end function attr_exists

    !> Root attribute `name` as a string; fixed-length and variable-length strings both work.
    subroutine read_attr_str(file, name, value)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: name
        character(len=:), allocatable, intent(out) :: value
        character(len=:), allocatable :: what
        integer(hid_t) :: file_id, attr_id, str_type
        integer(hsize_t) :: npoints
        integer(size_t) :: type_size
        integer :: hdferr, type_class, stat
        character(len=256) :: message
        logical :: is_variable
        type(c_ptr), target :: vl_ptr(1)
        type(c_ptr) :: buf   ! h5aread_f wants a variable, not an expression
        character(kind=c_char), allocatable, target :: fixed(:)

        what = 'attribute '//name
        call open_attr(file, name, file_id, attr_id, npoints, scalar=.true.)
        ! the type h5aget_type_f returns is a copy, usable as the memory type: the string is
        ! read as stored, with no character-set conversion (which HDF5 does not do)
        call h5aget_type_f(attr_id, str_type, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5aget_type_f failed')
        call h5tget_class_f(str_type, type_class, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5tget_class_f failed')
        if (type_class /= H5T_STRING_F) call fail(file, what, 'not a string attribute')
        call h5tis_variable_str_f(str_type, is_variable, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5tis_variable_str_f failed')
        if (is_variable) then
            buf = c_loc(vl_ptr)
        else
            call h5tget_size_f(str_type, type_size, hdferr)
            if (hdferr < 0) call fail(file, what, 'h5tget_size_f failed')
            allocate (fixed(max(1_size_t, type_size)), stat=stat, errmsg=message)
            call check_allocation(stat, message, 'what is read from '''//trim(file)//'''')
            fixed = c_char_' '
            buf = c_loc(fixed)
        end if
        call h5aread_f(attr_id, str_type, buf, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5aread_f failed')
        if (is_variable) then
            value = from_c_string(vl_ptr(1), '')
            if (h5_free_memory(vl_ptr(1)) < 0) call fail(file, what, 'H5free_memory failed')
        else
            ! null-terminated, null-padded or space-padded: stop at the first NUL, drop
            ! trailing blanks
            value = trim(from_c_chars(fixed))
        end if
        call h5tclose_f(str_type, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5tclose_f failed')
        call close_attr(file, name, file_id, attr_id)
    end subroutine read_attr_str

    !> Scalar float root attribute `name` (an int32 one too: float64 holds it exactly).
    subroutine read_attr_real(file, name, value)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: name
        real(dp), intent(out) :: value
        real(dp), allocatable :: values(:)

        call read_attr_real_1d(file, name, values, scalar=.true.)
        value = values(1)
    end subroutine read_attr_real

    !> Root attribute `name` as float64 values: any number, with scalar = .true. one.
    subroutine read_attr_real_1d(file, name, values, scalar)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: name
        real(dp), allocatable, intent(out) :: values(:)
        logical, intent(in), optional :: scalar
        integer(hid_t) :: file_id, attr_id
        integer(hsize_t) :: npoints
        integer :: hdferr, stat
        character(len=256) :: message

        call open_attr(file, name, file_id, attr_id, npoints, scalar)
        allocate (values(npoints), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'what is read from '''//trim(file)//'''')
        hdferr = 0
        if (npoints > 0) call h5aread_f(attr_id, H5T_NATIVE_DOUBLE, values, [npoints], hdferr)
        if (hdferr < 0) call fail(file, 'attribute '//name, 'h5aread_f failed')
        call close_attr(file, name, file_id, attr_id)
    end subroutine read_attr_real_1d

    ! ---------------------------------------------------------------- private helpers

    !> Stop with a message naming the file, the dataset or attribute, and what failed.
    subroutine fail(file, what, reason)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: what
        character(len=*), intent(in) :: reason

        call fatal(EXIT_INPUT, 'h5_read', "cannot read '"//trim(what)//"' from '"//trim(file)//"': "//reason)
    end subroutine fail

    !> `file` opened read-only; the .h5.part of a killed run, still marked as open by its
    !> (SWMR) writer, by a SWMR reader, which opens it without changing it (h5_swmr_m).
    function open_file(file, what) result(file_id)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: what
        integer(hid_t) :: file_id
        integer :: hdferr

        call h5_library_init()
        if (.not. file_exists(file)) call fail(file, what, 'no such file')
        call h5fopen_f(trim(file), H5F_ACC_RDONLY_F, file_id, hdferr)
        if (hdferr < 0) call h5fopen_f(trim(file), SWMR_READ, file_id, hdferr)
        if (hdferr < 0) call fail(file, what, 'not an HDF5 file or not readable (h5fopen_f failed)')
    end function open_file

    subroutine close_file(file, what, file_id)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: what
        integer(hid_t), intent(in) :: file_id
        integer :: hdferr

        call h5fclose_f(file_id, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5fclose_f failed')
    end subroutine close_file

    !> Open `file` and root attribute `name`, with its number of elements (one with scalar).
    subroutine open_attr(file, name, file_id, attr_id, npoints, scalar)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: name
        logical, intent(in), optional :: scalar
        integer(hid_t), intent(out) :: file_id, attr_id
        integer(hsize_t), intent(out) :: npoints
        integer(hid_t) :: space_id
        integer :: hdferr
        character(len=:), allocatable :: what

        what = 'attribute '//name
        file_id = open_file(file, what)
        call h5aopen_f(file_id, name, attr_id, hdferr)
        if (hdferr < 0) call fail(file, what, 'no such root attribute (h5aopen_f failed)')
        call h5aget_space_f(attr_id, space_id, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5aget_space_f failed')
        call h5sget_simple_extent_npoints_f(space_id, npoints, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5sget_simple_extent_npoints_f failed')
        call h5sclose_f(space_id, hdferr)
        if (hdferr < 0) call fail(file, what, 'h5sclose_f failed')
        if (present(scalar)) then
            if (scalar .and. npoints /= 1) call fail(file, what, 'attribute is not a scalar')
        end if
    end subroutine open_attr

    subroutine close_attr(file, name, file_id, attr_id)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: file_id
        integer(hid_t), intent(in) :: attr_id
        integer :: hdferr

        call h5aclose_f(attr_id, hdferr)
        if (hdferr < 0) call fail(file, 'attribute '//name, 'h5aclose_f failed')
        call close_file(file, 'attribute '//name, file_id)
    end subroutine close_attr

end module h5_read_m
