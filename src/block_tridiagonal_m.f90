!> Block-tridiagonal LU for the interleaved monolithic system: with NB = 5 unknowns per
!> node, node i couples only to nodes i-1 and i+1, so A is block tridiagonal with 5 x 5
!> blocks D_i (diagonal), E_i (row i, column i+1) and F_i (row i+1, column i). The block
!> size is a compile-time constant so that the 5 x 5 kernels are fully unrolled.
!>
!> Why: the per-step solve with the band LU of dgbtrf is latency-bound (every unknown waits
!> for the previous one, one store/load/FMA chain per column). Block elimination makes the
!> chain one link per node instead of one per unknown, with independent work inside a node.
!>
!> Factorisation (once): S_0 = D_0, S_i = D_i - F_{i-1} S_{i-1}^{-1} E_{i-1}; we keep
!> G_i = S_i^{-1} (5 x 5 LU with partial pivoting, dgetrf/dgetri), L_i = F_{i-1} G_{i-1} and
!> H_i = G_i E_i.
!> Solve: y_0 = b_0, y_i = b_i - L_i y_{i-1}, c_i = G_i y_i; x_last = c_last,
!> x_i = c_i - H_i x_{i+1}. Only y_{i-1} -> y_i and x_{i+1} -> x_i are on the dependency
!> chain (one 5 x 5 product each, summed as a tree); c_i is computed off the chain.
!> There is no pivoting across nodes. The pivot blocks S_i are nonsingular because the
!> symmetric part of the scaled matrix of (6.1) is positive definite (Theorem 6.1 and the
!> scaling of scheme_m), and stepper_m checks the solver against the band LU once per run.
module block_tridiagonal_m
    use kinds_m, only: dp
    use banded_m, only: band_t
    implicit none
    private
    public :: block_tridiagonal_t
    interface
        subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: dp
            integer, intent(in) :: m, n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgetrf
        subroutine dgetri(n, a, lda, ipiv, work, lwork, info)
            import :: dp
            integer, intent(in) :: n, lda, lwork
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(dp), intent(out) :: work(*)
            integer, intent(out) :: info
        end subroutine dgetri
    end interface
    integer, parameter, public :: NB = 5      !< unknowns per node

    type :: block_tridiagonal_t
        integer :: last = -1                 !< nodes are 0..last
        real(dp), allocatable :: g(:, :, :)  !< g(:,:,i) = S_i^{-1}
        real(dp), allocatable :: l(:, :, :)  !< l(:,:,i) = F_{i-1} S_{i-1}^{-1}, i >= 1
        real(dp), allocatable :: e(:, :, :)  !< e(:,:,i) = E_i, i <= last-1
        real(dp), allocatable :: h(:, :, :)  !< h(:,:,i) = G_i E_i, i <= last-1
    contains
        procedure :: factor => block_factor
        procedure :: solve => block_solve
    end type block_tridiagonal_t

contains
    !> Factor the block-tridiagonal matrix held (unfactored) in band a. info = 0 on success,
    !> else the node (1-based) whose pivot block is singular.
    subroutine block_factor(self, a, info)
        class(block_tridiagonal_t), intent(inout) :: self
        type(band_t), intent(in) :: a
        integer, intent(out) :: info
        real(dp) :: f(NB, NB), work(NB * NB)
        integer :: i, ipiv(NB), lapack_info

        if (mod(a%n, NB) /= 0 .or. a%kl > 2 * NB - 1 .or. a%ku > 2 * NB - 1) &
            error stop 'block_factor: matrix is not block tridiagonal with 5 x 5 blocks'
        self%last = a%n / NB - 1
        if (allocated(self%g)) deallocate (self%g, self%l, self%e, self%h)
        allocate (self%g(NB, NB, 0:self%last), self%l(NB, NB, 1:self%last), self%e(NB, NB, 0:self%last - 1))
        info = 0
        do i = 0, self%last
            self%g(:, :, i) = block(a, i, i)
            if (i > 0) then
                f = block(a, i, i - 1)
                self%l(:, :, i) = matmul(f, self%g(:, :, i - 1))
                self%g(:, :, i) = self%g(:, :, i) - matmul(self%l(:, :, i), self%e(:, :, i - 1))
            end if
            if (i < self%last) self%e(:, :, i) = block(a, i, i + 1)
            call dgetrf(NB, NB, self%g(:, :, i), NB, ipiv, lapack_info)
            if (lapack_info == 0) call dgetri(NB, self%g(:, :, i), NB, ipiv, work, size(work), lapack_info)
            if (lapack_info /= 0) then
                info = i + 1
                return
            end if
        end do
        allocate (self%h(NB, NB, 0:self%last - 1))
        do i = 0, self%last - 1
            self%h(:, :, i) = matmul(self%g(:, :, i), self%e(:, :, i))
        end do
    contains
        pure function block(a, row_node, col_node) result(blk)
            type(band_t), intent(in) :: a
            integer, intent(in) :: row_node, col_node
            real(dp) :: blk(NB, NB)
            integer :: p, q
            do q = 1, NB
                do p = 1, NB
                    blk(p, q) = a%get(NB * row_node + p, NB * col_node + q)
                end do
            end do
        end function block
    end subroutine block_factor
    !> Solve A x = b in place with the block factors. No allocation: called every step.
    subroutine block_solve(self, b)
        class(block_tridiagonal_t), intent(in) :: self
        real(dp), intent(inout) :: b(:)
        real(dp) :: y(NB), x(NB)
        integer :: i, lo

        ! forward: y_i = b_i - L_i y_{i-1}; c_i = G_i y_i (off the dependency chain)
        x = b(1:NB)
        b(1:NB) = matvec5(self%g(:, :, 0), x)
        do i = 1, self%last
            lo = NB * i
            y = b(lo + 1:lo + NB) - matvec5(self%l(:, :, i), x)
            b(lo + 1:lo + NB) = matvec5(self%g(:, :, i), y)
            x = y
        end do
        ! back: x_last = c_last, x_i = c_i - H_i x_{i+1}, H_i = G_i E_i
        x = b(NB * self%last + 1:NB * self%last + NB)
        do i = self%last - 1, 0, -1
            lo = NB * i
            x = b(lo + 1:lo + NB) - matvec5(self%h(:, :, i), x)
            b(lo + 1:lo + NB) = x
        end do
    end subroutine block_solve

    !> a x for a 5 x 5 block, summed as a tree (depth 3) to shorten the dependency chain.
    pure function matvec5(a, x) result(y)
        real(dp), intent(in) :: a(NB, NB), x(NB)
        real(dp) :: y(NB)

        y = (a(:, 1) * x(1) + a(:, 2) * x(2)) + (a(:, 3) * x(3) + a(:, 4) * x(4)) + a(:, 5) * x(5)
    end function matvec5

end module block_tridiagonal_m
