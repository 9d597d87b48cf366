!> What HDF5 1.10's Fortran API lacks: its single-writer/multiple-reader (SWMR) mode
!> (h5_swmr_c.c), and H5free_memory for the strings HDF5 allocates (h5_free).
!> The writer (output_m) runs in SWMR write mode between its structural changes: HDF5 then writes a flush's metadata children before their parents (chunk index
!> nodes before the nodes and object headers pointing to them), so a run killed at any
!> moment leaves its last flush readable. Without it a kill inside a flush can leave an index
!> node pointing past the space the superblock records, or at a child not yet written,
!> and the whole dataset (with its checkpointed history) unreadable. The file left by a
!> killed SWMR writer is still marked as open for writing: only a SWMR reader opens it
!> (h5_read_m, and h5py.File(path, 'r', swmr=True)).
module h5_swmr_m
    use iso_c_binding, only: c_int, c_char, c_null_char, c_int64_t, c_ptr, c_associated
    use hdf5, only: hid_t
    implicit none
    private
    public :: start_swmr_write, open_swmr_read, h5_free

    interface
        function c_start_swmr_write(file_id) bind(C, name='rc_h5_start_swmr_write') result(rc)
            import :: c_int64_t, c_int
            integer(c_int64_t), value, intent(in) :: file_id   ! hid_t: int64_t in HDF5 1.10
            integer(c_int) :: rc
        end function c_start_swmr_write

        function c_open_swmr_read(path) bind(C, name='rc_h5_open_swmr_read') result(file_id)
            import :: c_int64_t, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int64_t) :: file_id
        end function c_open_swmr_read

        function c_h5free_memory(mem) bind(C, name='H5free_memory') result(rc)
            import :: c_ptr, c_int
            type(c_ptr), value, intent(in) :: mem
            integer(c_int) :: rc
        end function c_h5free_memory
    end interface

contains

    !> Switch the open file file_id to SWMR writing (H5Fstart_swmr_write). hdferr: 0, or -1
    !> on failure (the file must have the 1.10 format, be open for writing, and have only
    !> datasets open).
    subroutine start_swmr_write(file_id, hdferr)
        integer(hid_t), intent(in) :: file_id
        integer, intent(out) :: hdferr

        hdferr = int(c_start_swmr_write(int(file_id, c_int64_t)))
    end subroutine start_swmr_write

    !> Open `path` read-only as a SWMR reader: file_id, negative on failure (not an HDF5
    !> file, or one of an older format than 1.10, which a plain read-only open reads).
    function open_swmr_read(path) result(file_id)
        character(len=*), intent(in) :: path
        integer(hid_t) :: file_id

        file_id = int(c_open_swmr_read(trim(path)//c_null_char), hid_t)
    end function open_swmr_read

    !> Free `mem`, memory HDF5 allocated (the string of a variable-length string read):
    !> false when H5free_memory fails. A null pointer is nothing to free.
    logical function h5_free(mem)
        type(c_ptr), intent(in) :: mem

        h5_free = .true.
        if (c_associated(mem)) h5_free = c_h5free_memory(mem) >= 0
    end function h5_free

end module h5_swmr_m
