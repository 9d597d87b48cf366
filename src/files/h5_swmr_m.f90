!> What HDF5 1.10's Fortran API lacks, bound to its C API: the single-writer/multiple-reader
!> (SWMR) mode, in which the writer (output_m) runs between its structural changes so that a
!> killed run leaves its last flush readable (output_file_s), the flags of a SWMR reader, and
!> H5free_memory for the strings HDF5 allocates. The file of a killed SWMR writer is still
!> marked as open for writing: only a SWMR reader opens it (h5_read_m, and h5py.File(path,
!> 'r', swmr=True)).
module h5_swmr_m
    use iso_c_binding, only: c_int, c_int64_t, c_ptr
    implicit none
    private
    public :: start_swmr_write, h5_free_memory, SWMR_READ

    !> h5fopen_f's flags (passed on to H5Fopen) for a SWMR reader, which writes nothing to the
    !> file: H5F_ACC_RDONLY | H5F_ACC_SWMR_READ (H5Fpublic.h, 0x0000u | 0x0040u)
    integer, parameter :: SWMR_READ = 64

    interface   ! hid_t: int64_t in HDF5 1.10
        !> Switch the open file file_id (1.10 format, open for writing, only datasets open)
        !> to SWMR writing; negative on failure.
        function start_swmr_write(file_id) bind(C, name='H5Fstart_swmr_write') result(herr)
            import :: c_int64_t, c_int
            integer(c_int64_t), value, intent(in) :: file_id
            integer(c_int) :: herr
        end function start_swmr_write

        !> Free `mem`, memory HDF5 allocated (the string of a variable-length string read; a
        !> null pointer is nothing to free); negative on failure.
        function h5_free_memory(mem) bind(C, name='H5free_memory') result(herr)
            import :: c_ptr, c_int
            type(c_ptr), value, intent(in) :: mem
            integer(c_int) :: herr
        end function h5_free_memory
    end interface

end module h5_swmr_m
