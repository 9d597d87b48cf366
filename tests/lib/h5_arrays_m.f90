!> What the tests read from an output file besides h5_read_m's routines: an integer series
!> as integers, a snapshot field as a 2D array, an integer root attribute.
module h5_arrays_m
    use kinds_m, only: dp
    use hdf5, only: hsize_t
    use h5_read_m, only: read_real_1d, read_attr_real_1d
    implicit none
    private
    public :: read_int_1d, read_real_2d, read_attr_int

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

    !> Whole 2D float dataset: values(s+1, n_snap) for what h5py shows as (n_snap, s+1).
    subroutine read_real_2d(file, dset, values)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: dset
        real(dp), allocatable, intent(out) :: values(:, :)
        real(dp), allocatable :: flat(:)
        integer(hsize_t) :: dims(2)

        call read_real_1d(file, dset, flat, dims)
        values = reshape(flat, dims)
    end subroutine read_real_2d

    !> Scalar integer root attribute `name` (also the 0/1 of a logical attribute), read as
    !> float64, which holds every int32 exactly.
    subroutine read_attr_int(file, name, value)
        character(len=*), intent(in) :: file
        character(len=*), intent(in) :: name
        integer, intent(out) :: value
        real(dp), allocatable :: values(:)

        call read_attr_real_1d(file, name, values, scalar=.true.)
        value = nint(values(1))
    end subroutine read_attr_int

end module h5_arrays_m
