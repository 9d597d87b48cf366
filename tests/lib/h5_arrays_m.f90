!> What the tests read from an output file besides h5_read_m's routines: an integer series
!> as integers.
module h5_arrays_m
    use kinds_m, only: dp
    use h5_read_m, only: read_real_1d
    implicit none
    private
    public :: read_int_1d

contains

    !> Whole 1D integer dataset (e.g. '/series/iterations'), read as float64, which holds
    !> every int32 exactly.
    subroutine read_int_1d(file, dset, values)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: dset
        integer, allocatable, intent(out) :: values(:)
        real(dp), allocatable :: flat(:)

        call read_real_1d(file, dset, flat)
        values = nint(flat)
    end subroutine read_int_1d

end module h5_arrays_m
