!> Test and benchmark helpers for band_t that the program itself does not need: the dense
!> copy of a band matrix and LAPACK's own dgbtrs on band_t's factors (the reference for
!> band_t%solve, which does the same operations as plain loops).
module band_reference_m
    use kinds_m, only: dp
    use banded_m, only: band_t
    implicit none
    private
    public :: band_to_dense, solve_with_dgbtrs

    interface
        subroutine dgbtrs(trans, n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb, info)
            import :: dp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: n, kl, ku, nrhs, ldab, ldb
            real(dp), intent(in) :: ab(ldab, *)
            integer, intent(in) :: ipiv(*)
            real(dp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgbtrs
    end interface

contains

    !> The dense n x n matrix; only meaningful before factor().
    pure function band_to_dense(a) result(dense)
        type(band_t), intent(in) :: a
        real(dp) :: dense(a%n, a%n)
        integer :: i, j

        dense = 0.0_dp
        do j = 1, a%n
            do i = max(1, j - a%ku), min(a%n, j + a%kl)
                dense(i, j) = a%ab(a%kl + a%ku + 1 + i - j, j)
            end do
        end do
    end function band_to_dense

    !> Solve A x = b in place with LAPACK's dgbtrs on the factors of a%factor().
    subroutine solve_with_dgbtrs(a, b, info)
        type(band_t), intent(in) :: a
        real(dp), intent(inout) :: b(:)
        integer, intent(out) :: info

        if (.not. a%factored) error stop 'solve_with_dgbtrs: matrix not factored'
        call dgbtrs('N', a%n, a%kl, a%ku, 1, a%ab, size(a%ab, 1), a%ipiv, b, a%n, info)
    end subroutine solve_with_dgbtrs

end module band_reference_m
