!> Block-tridiagonal LU of the monolithic system of (6.1): with nb unknowns per node (the
!> fields in the system, at most NB_MAX = 5), node i couples only to nodes i-1 and i+1,
!> so A is block tridiagonal: nb x nb blocks D_i (diagonal), E_i (row i, column i+1) and
!> F_i (row i+1, column i) (scheme_m's assemble_blocks). The 5 x 5 kernel is written out
!> to be unrolled (docs/performance.md); fewer fields (scheme_m's active_fields) use loops.
!>
!> Factorisation: S_0 = D_0, S_i = D_i - F_{i-1} S_{i-1}^{-1} E_{i-1}; we keep G_i =
!> S_i^{-1}, L_i = F_{i-1} G_{i-1} and H_i = G_i E_i. S_i is inverted with partial
!> pivoting by LAPACK (dgetrf, dgetri) or, with inline_inverse, by invert5 (Gauss-Jordan):
!> their round-off differs, and each keeps its runs' results (stepper_m says which).
!> Solve: y_0 = b_0, y_i = b_i - L_i y_{i-1}, c_i = G_i y_i; x_last = c_last,
!> x_i = c_i - H_i x_{i+1}. Only y_{i-1} -> y_i and x_{i+1} -> x_i are on the dependency
!> chain (one 5 x 5 product each, summed as a tree); c_i is computed off the chain.
!> There is no pivoting across nodes. The pivot blocks S_i are nonsingular because the
!> symmetric part of the scaled matrix of (6.1) is positive definite (Theorem 6.1 and the
!> scaling of scheme_m), and stepper_m checks the solver against the band LU.
module block_tridiagonal_m
    use kinds_m, only: dp
    use ieee_arithmetic, only: ieee_is_nan
    use errors_m, only: check_allocation
    implicit none
    private
    public :: block_tridiagonal_t
    public :: product5, product5_left_pattern, product5_right_pattern, in_pattern   ! (for test_banded_m)
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
    integer, parameter, public :: NB_MAX = 5   !< the most unknowns per node (N_FIELDS)

    type :: block_tridiagonal_t
        integer :: nb = 0                    !< unknowns per node
        integer :: last = -1                 !< nodes are 0..last
        real(dp), allocatable :: g(:, :, :)  !< g(:,:,i) = S_i^{-1}
        real(dp), allocatable :: l(:, :, :)  !< l(:,:,i) = F_{i-1} S_{i-1}^{-1}, i >= 1
        real(dp), allocatable :: h(:, :, :)  !< h(:,:,i) = G_i E_i, i <= last-1
    contains
        procedure :: factor => block_factor
        procedure :: solve => block_solve
    end type block_tridiagonal_t

contains

    !> Factor the matrix of blocks d(:, :, i) = D_i (node i, 0..last), e(:, :, i) = E_i and
    !> f(:, :, i) = F_i, of the rows and columns keep (default: all; the fields in the system).
    !> With all kept, d's storage becomes the factors' (d is then deallocated: no copy).
    !> inline_inverse: invert the pivot blocks by invert5, not LAPACK (default .false.).
    !> info = 0; -1 for blocks of a wrong size; else the node (1-based) of a singular pivot.
    subroutine block_factor(self, d, e, f, info, inline_inverse, keep)
        class(block_tridiagonal_t), intent(inout) :: self
        real(dp), allocatable, intent(inout) :: d(:, :, :)
        real(dp), intent(in), contiguous :: e(:, :, 0:), f(:, :, 0:)
        integer, intent(out) :: info
        logical, intent(in), optional :: inline_inverse, keep(:)
        integer :: rc(size(d, 1)), nb, k, stat
        character(len=256) :: message

        rc = [(k, k = 1, size(d, 1))]
        nb = size(rc)
        if (present(keep)) nb = count(keep)
        if (present(keep)) rc(:nb) = pack(rc, keep)
        info = -1
        if (nb < 1 .or. nb > NB_MAX .or. size(d, 3) < 2) return
        if (min(size(e, 3), size(f, 3)) < size(d, 3) - 1) return
        self%nb = nb
        self%last = size(d, 3) - 1
        if (allocated(self%g)) deallocate (self%g, self%l, self%h)
        allocate (self%l(nb, nb, self%last), self%h(nb, nb, 0:self%last - 1), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the block LU factors')
        if (nb == size(d, 1)) then
            call move_alloc(d, self%g)
            call factor_nodes(self, e, f, info, inline_inverse)
        else
            allocate (self%g(nb, nb, 0:self%last), stat=stat, errmsg=message)
            call check_allocation(stat, message, 'the block LU factors')
            self%g(:, :, :) = d(rc(:nb), rc(:nb), :)
            call factor_nodes(self, e(rc(:nb), rc(:nb), :), f(rc(:nb), rc(:nb), :), info, inline_inverse)
        end if
    end subroutine block_factor

    !> block_factor's elimination, node by node.
    subroutine factor_nodes(self, e, f, info, inline_inverse)
        type(block_tridiagonal_t), intent(inout) :: self
        real(dp), intent(in), contiguous :: e(:, :, 0:), f(:, :, 0:)
        integer, intent(out) :: info
        logical, intent(in), optional :: inline_inverse
        integer :: i, before, now
        logical :: inline, before_in_pattern

        inline = .false.
        if (present(inline_inverse)) inline = inline_inverse
        info = 0
        before_in_pattern = .false.
        do i = 0, self%last
            before = max(i - 1, 0)
            now = min(i, self%last - 1)
            if (self%nb == NB_MAX) then
                call factor_node5(i, self%last, f(:, :, before), e(:, :, before), e(:, :, now), inline, &
                                  self%g, self%l, self%h, before_in_pattern, info)
            else
                call factor_node(i, self%last, self%nb, f(:, :, before), e(:, :, before), e(:, :, now), &
                                 inline, self%g, self%l, self%h, info)
            end if
            if (info /= 0) then   ! a singular pivot block
                info = i + 1
                return
            end if
        end do
    end subroutine factor_nodes

    !> Node i of the block LU, nb = 5: g(:, :, i) = D_i becomes G_i = S_i^{-1}, S_i = D_i -
    !> L_i E_{i-1} with L_i = F_{i-1} G_{i-1}, and H_i = G_i E_i (f = F_{i-1}, e_before = E_{i-1},
    !> e_now = E_i). before_in_pattern: in_pattern(E_{i-1}) on entry, of E_i on return.
    !> info: the inversion's.
    subroutine factor_node5(i, last, f, e_before, e_now, inline, g, l, h, before_in_pattern, info)
        integer, intent(in) :: i, last
        real(dp), intent(in) :: f(NB_MAX, NB_MAX), e_before(NB_MAX, NB_MAX), e_now(NB_MAX, NB_MAX)
        logical, intent(in) :: inline
        real(dp), intent(inout) :: g(NB_MAX, NB_MAX, 0:last), l(NB_MAX, NB_MAX, last), &
                                   h(NB_MAX, NB_MAX, 0:last - 1)
        logical, intent(inout) :: before_in_pattern
        integer, intent(out) :: info
        real(dp) :: le(NB_MAX, NB_MAX)

        if (i > 0) then
            if (in_pattern(f) .and. before_in_pattern) then
                call product5_left_pattern(f, g(:, :, i - 1), l(:, :, i))
                call product5_right_pattern(l(:, :, i), e_before, le)
            else
                call product5(f, g(:, :, i - 1), l(:, :, i))
                call product5(l(:, :, i), e_before, le)
            end if
            g(:, :, i) = g(:, :, i) - le   ! L_i E_{i-1} summed first
        end if
        if (inline) then
            call invert5(g(:, :, i), info)   ! not through invert (docs/performance.md)
        else
            call invert(g(:, :, i), NB_MAX, .false., info)
        end if
        if (info /= 0 .or. i == last) return
        before_in_pattern = in_pattern(e_now)
        if (before_in_pattern) then
            call product5_right_pattern(g(:, :, i), e_now, h(:, :, i))
        else
            call product5(g(:, :, i), e_now, h(:, :, i))
        end if
    end subroutine factor_node5

    !> factor_node5 for nb < 5 unknowns per node: the same steps with matmul's products.
    subroutine factor_node(i, last, nb, f, e_before, e_now, inline, g, l, h, info)
        integer, intent(in) :: i, last, nb
        real(dp), intent(in) :: f(nb, nb), e_before(nb, nb), e_now(nb, nb)
        logical, intent(in) :: inline
        real(dp), intent(inout) :: g(nb, nb, 0:last), l(nb, nb, last), h(nb, nb, 0:last - 1)
        integer, intent(out) :: info

        if (i > 0) then
            l(:, :, i) = matmul(f, g(:, :, i - 1))
            g(:, :, i) = g(:, :, i) - matmul(l(:, :, i), e_before)
        end if
        call invert(g(:, :, i), nb, inline, info)
        if (info == 0 .and. i < last) h(:, :, i) = matmul(g(:, :, i), e_now)
    end subroutine factor_node

    !> a = a^{-1} for an n x n pivot block: invert5 (inline; n < 5: a inside an identity
    !> block, whose other rows its elimination leaves alone) or LAPACK's dgetrf and dgetri.
    !> info = 0, or nonzero for a singular block.
    subroutine invert(a, n, inline, info)
        integer, intent(in) :: n
        real(dp), intent(inout) :: a(n, n)
        logical, intent(in) :: inline
        integer, intent(out) :: info
        real(dp) :: work(n * n), padded(NB_MAX, NB_MAX)
        integer :: ipiv(n), k

        if (inline .and. n == NB_MAX) then
            call invert5(a, info)
        else if (inline) then
            padded = 0.0_dp
            do k = 1, NB_MAX
                padded(k, k) = 1.0_dp
            end do
            padded(1:n, 1:n) = a
            call invert5(padded, info)
            a = padded(1:n, 1:n)
        else
            call dgetrf(n, n, a, n, ipiv, info)
            if (info == 0) call dgetri(n, a, n, ipiv, work, size(work), info)
        end if
    end subroutine invert

    !> Solve A x = b in place with the block factors. No allocation: called every step.
    !> Every field in the system (nb = 5): products written out for the fixed block size,
    !> so that they are fully unrolled. Fewer fields (scheme_m's active_fields): a loop.
    subroutine block_solve(self, b)
        class(block_tridiagonal_t), intent(in) :: self
        real(dp), intent(inout), contiguous :: b(:)

        if (self%nb == NB_MAX) then
            call solve_full(self%g, self%l, self%h, self%last, b)
        else
            call solve_reduced(self%g, self%l, self%h, self%last, self%nb, b)
        end if
    end subroutine block_solve

    !> forward: y_i = b_i - L_i y_{i-1}; c_i = G_i y_i (off the dependency chain);
    !> back: x_last = c_last, x_i = c_i - H_i x_{i+1}, H_i = G_i E_i. b(:, i) is node i.
    subroutine solve_full(g, l, h, last, b)
        integer, intent(in) :: last
        real(dp), intent(in) :: g(NB_MAX, NB_MAX, 0:last), l(NB_MAX, NB_MAX, last), &
                                h(NB_MAX, NB_MAX, 0:last - 1)
        real(dp), intent(inout) :: b(NB_MAX, 0:last)
        real(dp) :: y(NB_MAX), x(NB_MAX)
        integer :: i

        x = b(:, 0)
        b(:, 0) = matvec5(g(:, :, 0), x)
        do i = 1, last
            y = b(:, i) - matvec5(l(:, :, i), x)
            b(:, i) = matvec5(g(:, :, i), y)
            x = y
        end do
        x = b(:, last)
        do i = last - 1, 0, -1
            x = b(:, i) - matvec5(h(:, :, i), x)
            b(:, i) = x
        end do
    end subroutine solve_full

    !> The same sweeps for nb < 5 unknowns per node, one row at a time.
    subroutine solve_reduced(g, l, h, last, nb, b)
        integer, intent(in) :: last, nb
        real(dp), intent(in) :: g(nb, nb, 0:last), l(nb, nb, last), h(nb, nb, 0:last - 1)
        real(dp), intent(inout) :: b(nb, 0:last)
        real(dp) :: before(NB_MAX), now(NB_MAX), acc
        integer :: i, r, k

        before(1:nb) = b(:, 0)
        call apply_pivot(0)
        do i = 1, last
            do r = 1, nb
                acc = b(r, i)
                do k = 1, nb
                    acc = acc - l(r, k, i) * before(k)
                end do
                now(r) = acc
            end do
            before(1:nb) = now(1:nb)
            call apply_pivot(i)
        end do
        do i = last - 1, 0, -1
            do r = 1, nb
                acc = b(r, i)
                do k = 1, nb
                    acc = acc - h(r, k, i) * b(k, i + 1)
                end do
                b(r, i) = acc
            end do
        end do

    contains

        !> b(:, j) = g_j before: the inverted pivot block of node j applied.
        subroutine apply_pivot(j)
            integer, intent(in) :: j

            do r = 1, nb
                acc = 0.0_dp
                do k = 1, nb
                    acc = acc + g(r, k, j) * before(k)
                end do
                b(r, j) = acc
            end do
        end subroutine apply_pivot
    end subroutine solve_reduced

    !> c = a b for 5 x 5 blocks (multiply).
    pure subroutine product5(a, b, c)
        real(dp), intent(in) :: a(NB_MAX, NB_MAX), b(NB_MAX, NB_MAX)
        real(dp), intent(out) :: c(NB_MAX, NB_MAX)
        real(dp) :: column(NB_MAX)
        integer :: j, k

        do j = 1, NB_MAX
            column = 0.0_dp
            do k = 1, NB_MAX
                column = column + a(:, k) * b(k, j)
            end do
            c(:, j) = column
        end do
    end subroutine product5

    !> The pattern: the entries of the coupling blocks E_i, F_i of the system of (6.1) with every
    !> field (scheme_m's order q, theta, v, P, eta) that can be nonzero, |r - c| <= 1 and
    !> theta-P: column (and row) j has them in rows (columns) 1-2, 1-4, 2-4, 2-5, 4-5.
    !> Are the entries of a 5 x 5 block outside the pattern all zero (then product5's terms
    !> with them add zeros, which the *_pattern products skip)? A NaN or infinity there: .false.
    pure logical function in_pattern(b)
        real(dp), intent(in) :: b(NB_MAX, NB_MAX)
        real(dp) :: outside

        outside = abs(b(3, 1)) + abs(b(4, 1)) + abs(b(5, 1)) + abs(b(5, 2)) + abs(b(5, 3)) &
                  + abs(b(1, 3)) + abs(b(1, 4)) + abs(b(1, 5)) + abs(b(2, 5)) + abs(b(3, 5))
        ! a NaN is tested first: an ordered comparison with it would raise IEEE invalid
        ! (a trap in the Debug build)
        in_pattern = .false.
        if (.not. ieee_is_nan(outside)) in_pattern = outside <= 0.0_dp
    end function in_pattern

    !> c = a b (product5) for b in_pattern: the sums of product5 without the terms a(:, k) b(k, j)
    !> of the zeros of b. Bit for bit product5's: a partial sum starts at +0 and so is never -0, and
    !> adding a zero (+0 or -0) to a sum that is not -0 leaves it unchanged.
    pure subroutine product5_right_pattern(a, b, c)
        real(dp), intent(in) :: a(NB_MAX, NB_MAX), b(NB_MAX, NB_MAX)
        real(dp), intent(out) :: c(NB_MAX, NB_MAX)
        real(dp), parameter :: ZERO(NB_MAX) = 0.0_dp

        ! column j: the rows of the pattern's column j of b (in_pattern), from a zero sum (as product5)
        c(:, 1) = (ZERO + a(:, 1) * b(1, 1)) + a(:, 2) * b(2, 1)
        c(:, 2) = (((ZERO + a(:, 1) * b(1, 2)) + a(:, 2) * b(2, 2)) + a(:, 3) * b(3, 2)) + a(:, 4) * b(4, 2)
        c(:, 3) = ((ZERO + a(:, 2) * b(2, 3)) + a(:, 3) * b(3, 3)) + a(:, 4) * b(4, 3)
        c(:, 4) = (((ZERO + a(:, 2) * b(2, 4)) + a(:, 3) * b(3, 4)) + a(:, 4) * b(4, 4)) + a(:, 5) * b(5, 4)
        c(:, 5) = (ZERO + a(:, 4) * b(4, 5)) + a(:, 5) * b(5, 5)
    end subroutine product5_right_pattern

    !> c = a b (product5) for a in_pattern: product5's sums without the terms of the zeros of a
    !> (product5_right_pattern says why they are the same bits).
    pure subroutine product5_left_pattern(a, b, c)
        real(dp), intent(in) :: a(NB_MAX, NB_MAX), b(NB_MAX, NB_MAX)
        real(dp), intent(out) :: c(NB_MAX, NB_MAX)
        real(dp) :: column(NB_MAX)
        integer :: j

        do j = 1, NB_MAX
            column = 0.0_dp
            column(1:2) = column(1:2) + a(1:2, 1) * b(1, j)
            column(1:4) = column(1:4) + a(1:4, 2) * b(2, j)
            column(2:4) = column(2:4) + a(2:4, 3) * b(3, j)
            column(2:5) = column(2:5) + a(2:5, 4) * b(4, j)
            column(4:5) = column(4:5) + a(4:5, 5) * b(5, j)
            c(:, j) = column
        end do
    end subroutine product5_left_pattern

    !> a = a^{-1} for a 5 x 5 block by Gauss-Jordan elimination with partial pivoting, in
    !> place: column k is eliminated above and below the largest pivot of rows k..5 (a column
    !> at a time), the column of the inverse built in its place, and the row interchanges
    !> undone on the columns at the end. Row k, the scaled pivot row, is written after the
    !> elimination. info = 0, or the column without a nonzero pivot (a singular block).
    pure subroutine invert5(a, info)
        real(dp), intent(inout) :: a(NB_MAX, NB_MAX)
        integer, intent(out) :: info
        integer :: pivot_row(NB_MAX), j, k, p
        real(dp) :: inv_pivot, factor(NB_MAX), pivot(NB_MAX), swap(NB_MAX)

        info = 0
        !GCC$ unroll 5
        do k = 1, NB_MAX
            p = pivot_index(a(:, k), k)
            if (a(p, k) <= 0.0_dp .and. a(p, k) >= 0.0_dp) then   ! is_zero, inline
                info = k
                return
            end if
            pivot_row(k) = p
            if (p /= k) then
                swap = a(k, :)
                a(k, :) = a(p, :)
                a(p, :) = swap
            end if
            inv_pivot = 1.0_dp / a(k, k)
            a(k, k) = 1.0_dp
            pivot = a(k, :) * inv_pivot
            factor = a(:, k)
            a(:, k) = 0.0_dp
            do j = 1, NB_MAX
                a(:, j) = a(:, j) - factor * pivot(j)
            end do
            a(k, :) = pivot
        end do
        do k = NB_MAX, 1, -1
            p = pivot_row(k)
            if (p /= k) then
                swap = a(:, k)
                a(:, k) = a(:, p)
                a(:, p) = swap
            end if
        end do
    end subroutine invert5

    !> k - 1 + maxloc(abs(column(k:NB_MAX)), dim=1) written out (docs/performance.md): the
    !> first row of the largest |column(r)|, r >= k, NaNs passed over (all NaN: k).
    pure integer function pivot_index(column, k) result(p)
        real(dp), intent(in) :: column(NB_MAX)
        integer, intent(in) :: k
        real(dp) :: largest
        integer :: r

        p = k
        largest = -1.0_dp
        do r = k, NB_MAX
            if (abs(column(r)) > largest) then
                largest = abs(column(r))
                p = r
            end if
        end do
    end function pivot_index

    !> a x for a 5 x 5 block, summed as a tree (depth 3) to shorten the dependency chain.
    pure function matvec5(a, x) result(y)
        real(dp), intent(in) :: a(NB_MAX, NB_MAX), x(NB_MAX)
        real(dp) :: y(NB_MAX)

        y = (a(:, 1) * x(1) + a(:, 2) * x(2)) + (a(:, 3) * x(3) + a(:, 4) * x(4)) + a(:, 5) * x(5)
    end function matvec5

end module block_tridiagonal_m
