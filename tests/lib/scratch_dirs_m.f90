!> Removing scratch directories between test cases (the program itself never removes one).
module scratch_dirs_m
    use iso_c_binding, only: c_char, c_int, c_null_char
    implicit none
    private
    public :: remove_dir

    interface
        function c_rmdir(path) bind(C, name='rmdir') result(rc)
            import :: c_char, c_int
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: rc
        end function c_rmdir
    end interface

contains

    !> Remove an empty directory; a missing or non-empty one is left as it is.
    subroutine remove_dir(path)
        character(len=*), intent(in) :: path
        integer(c_int) :: rc

        rc = c_rmdir(trim(path)//c_null_char)
    end subroutine remove_dir

end module scratch_dirs_m
