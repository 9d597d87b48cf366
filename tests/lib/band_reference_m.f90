!> Test and benchmark helpers for band_t that the program itself does not need: an entry and
!> the dense copy of a band matrix, LAPACK's own dgbtrs on band_t's factors (the reference for
!> band_t%solve, a plain-loop substitution), and the block LU of a band's node blocks.
module band_reference_m
    use kinds_m, only: dp
    use banded_m, only: band_t
    use block_tridiagonal_m, only: block_tridiagonal_t
    implicit none
    private
    public :: band_entry, band_to_dense, solve_with_dgbtrs, factor_band_blocks

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

    !> A(i,j) (zero outside the band); only meaningful before factor().
    pure function band_entry(a, i, j) result(value)
        type(band_t), intent(in) :: a
        integer, intent(in) :: i, j
        real(dp) :: value

        value = 0.0_dp
        if (j - i <= a%ku .and. i - j <= a%kl) value = a%ab(a%kl + a%ku + 1 + i - j, j)
    end function band_entry

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

    !> The block LU (block_tridiagonal_m) of the unfactored band a with nb unknowns per node:
    !> its node blocks D_i, E_i, F_i read with band_entry and factored (info, inline as factor's).
    subroutine factor_band_blocks(blocks, a, nb, info, inline)
        type(block_tridiagonal_t), intent(inout) :: blocks
        type(band_t), intent(in) :: a
        integer, intent(in) :: nb
        integer, intent(out) :: info
        logical, intent(in) :: inline
        real(dp), allocatable :: d(:, :, :), e(:, :, :), f(:, :, :)
        integer :: last, i, r, c

        last = a%n / nb - 1
        allocate (d(nb, nb, 0:last), e(nb, nb, 0:last - 1), f(nb, nb, 0:last - 1))
        do i = 0, last
            do c = 1, nb
                do r = 1, nb
                    d(r, c, i) = band_entry(a, nb * i + r, nb * i + c)
                    if (i == last) cycle
                    e(r, c, i) = band_entry(a, nb * i + r, nb * (i + 1) + c)
                    f(r, c, i) = band_entry(a, nb * (i + 1) + r, nb * i + c)
                end do
            end do
        end do
        call blocks%factor(d, e, f, info, inline_inverse=inline)
    end subroutine factor_band_blocks

    !> Solve A x = b in place with LAPACK's dgbtrs on the factors of a%factor().
    subroutine solve_with_dgbtrs(a, b, info)
        type(band_t), intent(in) :: a
        real(dp), intent(inout) :: b(:)
        integer, intent(out) :: info

        if (.not. a%factored) error stop 'solve_with_dgbtrs: matrix not factored'
        call dgbtrs('N', a%n, a%kl, a%ku, 1, a%ab, size(a%ab, 1), a%ipiv, b, a%n, info)
    end subroutine solve_with_dgbtrs

end module band_reference_m
