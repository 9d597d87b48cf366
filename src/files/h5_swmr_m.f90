!> What HDF5 1.10's Fortran API lacks, bound to its C API: the single-writer/multiple-reader
!> (SWMR) mode, in which the writer (output_m) runs between its structural changes so that a
!> killed run leaves its last flush readable (output_file_s), and H5free_memory for the
!> strings HDF5 allocates. The file of a killed SWMR writer is still marked as open for
!> writing: only a SWMR reader opens it (h5_read_m, and h5py.File(path, 'r', swmr=True)).
module h5_swmr_m
    use iso_c_binding, only: c_int, c_int64_t, c_char, c_null_char, c_ptr
    use hdf5, only: hid_t
    implicit none
    private
    public :: start_swmr_write, open_swmr_read, h5_free_memory

    !> H5F_ACC_RDONLY | H5F_ACC_SWMR_READ (H5Fpublic.h, 0x0000u | 0x0040u)
    integer(c_int), parameter :: SWMR_READ = 64_c_int

    interface   ! hid_t: int64_t in HDF5 1.10
        !> Switch the open file file_id (1.10 format, open for writing, only datasets open)
        !> to SWMR writing; negative on failure.
        function start_swmr_write(file_id) bind(C, name='H5Fstart_swmr_write') result(herr)
            import :: c_int64_t, c_int
            integer(c_int64_t), value, intent(in) :: file_id
            integer(c_int) :: herr
        end function start_swmr_write

        function c_h5fopen(path, flags, fapl_id) bind(C, name='H5Fopen') result(file_id)
            import :: c_int64_t, c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value, intent(in) :: flags
            integer(c_int64_t), value, intent(in) :: fapl_id
            integer(c_int64_t) :: file_id
        end function c_h5fopen

        !> Free `mem`, memory HDF5 allocated (the string of a variable-length string read; a
        !> null pointer is nothing to free); negative on failure.
        function h5_free_memory(mem) bind(C, name='H5free_memory') result(herr)
            import :: c_ptr, c_int
            type(c_ptr), value, intent(in) :: mem
            integer(c_int) :: herr
        end function h5_free_memory
    end interface

contains

    !> Open `path` read-only as a SWMR reader, writing nothing to it: file_id, negative on
    !> failure (not an HDF5 file, or one of an older format than 1.10, which a plain
    !> read-only open reads).
    function open_swmr_read(path) result(file_id)
        character(len=*), intent(in) :: path
        integer(hid_t) :: file_id

        file_id = c_h5fopen(trim(path)//c_null_char, SWMR_READ, 0_c_int64_t)   ! H5P_DEFAULT
    end function open_swmr_read

end module h5_swmr_m
