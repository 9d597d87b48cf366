!> Exact comparisons of reals that the code makes on purpose: a coefficient that is exactly
!> zero (a field left out of the system), a pivot that is exactly zero, a step size equal to
!> the one a matrix was factored for. Written through these two functions, they say that
!> exactness is meant, and gfortran's -Wcompare-reals keeps flagging every other `==` or `/=`
!> on reals as the likely mistake it is. Same results as `==` and `/=` for every value,
!> NaN included (a NaN equals nothing, not even itself).
module reals_m
    use kinds_m, only: dp
    implicit none
    private

    public :: equal, is_zero

contains

    !> a == b, written so that the comparison is seen to be meant.
    elemental logical function equal(a, b)
        real(dp), intent(in) :: a
        real(dp), intent(in) :: b

        equal = a <= b .and. a >= b
    end function equal

    !> a == 0 (either sign of zero).
    elemental logical function is_zero(a)
        real(dp), intent(in) :: a

        is_zero = a <= 0.0_dp .and. a >= 0.0_dp
    end function is_zero
end module reals_m
