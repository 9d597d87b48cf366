!> Block-tridiagonal LU for the interleaved monolithic system: with nb unknowns per node
!> (the fields in the system, at most NB_MAX = 5), node i couples only to nodes i-1 and
!> i+1, so A is block tridiagonal with nb x nb blocks D_i (diagonal), E_i (row i, column
!> i+1) and F_i (row i+1, column i). The 5 x 5 kernel (all fields) is written out so that
!> it is fully unrolled; smaller blocks (fields left out, scheme_m's active_fields) use a loop.
!>
!> Why: the per-step solve with the band LU of dgbtrf is latency-bound (every unknown waits
!> for the previous one, one store/load/FMA chain per column). Block elimination makes the
!> chain one link per node instead of one per unknown, with independent work inside a node.
!>
!> Factorisation (once): S_0 = D_0, S_i = D_i - F_{i-1} S_{i-1}^{-1} E_{i-1}; we keep
!> G_i = S_i^{-1} (5 x 5 LU with partial pivoting, dgetrf/dgetri; or, with inline_inverse,
!> Gauss-Jordan elimination with partial pivoting written out here: an adaptive mesh
!> factors a new matrix at every remesh, where the ~8000 instructions per node of the two
!> LAPACK calls on a 5 x 5 block were half of the run time), L_i = F_{i-1} G_{i-1} and
!> H_i = G_i E_i.
!> Solve: y_0 = b_0, y_i = b_i - L_i y_{i-1}, c_i = G_i y_i; x_last = c_last,
!> x_i = c_i - H_i x_{i+1}. Only y_{i-1} -> y_i and x_{i+1} -> x_i are on the dependency
!> chain (one 5 x 5 product each, summed as a tree); c_i is computed off the chain.
!> There is no pivoting across nodes. The pivot blocks S_i are nonsingular because the
!> symmetric part of the scaled matrix of (6.1) is positive definite (Theorem 6.1 and the
!> scaling of scheme_m), and stepper_m checks the solver against the band LU once per run.
module block_tridiagonal_m
    use kinds_m, only: dp
    use ieee_arithmetic, only: ieee_is_nan
    use errors_m, only: check_allocation
    use reals_m, only: is_zero
    use banded_m, only: band_t
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
        procedure :: prepare => block_prepare
        procedure :: factor_blocks => block_factor_blocks
        procedure :: solve => block_solve
        procedure :: solve_last => block_solve_last
    end type block_tridiagonal_t

contains
    !> Factor the block-tridiagonal matrix held (unfactored) in band a, with nb unknowns per
    !> node. info = 0 on success; -1 if a is not block tridiagonal with nb x nb blocks; else
    !> the node (1-based) whose pivot block is singular.
    !> inline_inverse: invert the pivot blocks with invert_small instead of dgetrf/dgetri
    !> (default .false.: uniform meshes keep LAPACK, and their results bit for bit).
    subroutine block_factor(self, a, nb, info, inline_inverse)
        class(block_tridiagonal_t), intent(inout) :: self
        type(band_t), intent(in) :: a
        integer, intent(in) :: nb
        integer, intent(out) :: info
        logical, intent(in), optional :: inline_inverse
        integer :: stat
        character(len=256) :: message
        logical :: inline

        inline = .false.
        if (present(inline_inverse)) inline = inline_inverse
        info = -1
        if (nb < 1 .or. nb > NB_MAX) return
        if (mod(a%n, nb) /= 0 .or. a%kl > 2 * nb - 1 .or. a%ku > 2 * nb - 1) return
        self%nb = nb
        self%last = a%n / nb - 1
        if (allocated(self%g)) deallocate (self%g, self%l, self%h)
        allocate (self%g(nb, nb, 0:self%last), self%l(nb, nb, 1:self%last), self%h(nb, nb, 0:self%last - 1), &
                  stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the block LU factors')
        ! factor_full reads whole columns of a%ab: the band's fill-in rows must still be zero
        if (nb == NB_MAX .and. a%kl >= NB_MAX - 1 .and. a%ku >= NB_MAX - 1 .and. a%kl + a%ku >= 2 * NB_MAX - 1 &
            .and. .not. a%factored) then
            call factor_full(a, self%last, inline, self%g, self%l, self%h, info)
        else
            call factor_reduced(a, nb, self%last, inline, self%g, self%l, self%h, info)
        end if
    end subroutine block_factor

    !> The factorisation for nb < 5 unknowns per node (or a band factor_full does not take):
    !> S_i = D_i - L_i E_{i-1}, G_i = S_i^{-1}, H_i = G_i E_i, node by node. info as
    !> block_factor's.
    subroutine factor_reduced(a, nb, last, inline, g, l, h, info)
        type(band_t), intent(in) :: a
        integer, intent(in) :: nb, last
        logical, intent(in) :: inline
        real(dp), intent(out) :: g(nb, nb, 0:last), l(nb, nb, last), h(nb, nb, 0:last - 1)
        integer, intent(out) :: info
        real(dp) :: f(nb, nb), p(nb, nb), e_before(nb, nb), e_now(nb, nb)
        integer :: i

        info = 0
        ! blocks and products written into their places (no array-valued function results
        ! of run-time size, which gfortran allocates on the heap: ~8 per node)
        do i = 0, last
            call get_block(a, nb, i, i, g(:, :, i))
            if (i > 0) then
                call get_block(a, nb, i, i - 1, f)
                call multiply(f, g(:, :, i - 1), nb, l(:, :, i))
                call multiply(l(:, :, i), e_before, nb, p)
                g(:, :, i) = g(:, :, i) - p
            end if
            call invert(g(:, :, i), nb, inline, info)
            if (info /= 0) then
                info = i + 1
                return
            end if
            if (i < last) then
                call get_block(a, nb, i, i + 1, e_now)
                call multiply(g(:, :, i), e_now, nb, h(:, :, i))
                e_before = e_now
            end if
        end do
    end subroutine factor_reduced

    !> factor_reduced for every field in the system (nb = 5), on a band not yet factored with
    !> kl, ku >= 4 and kl + ku >= 9 (the system of (6.1): kl = ku = 7): the same operations in
    !> the same order, on blocks of fixed size, which the compiler unrolls (factor_node).
    subroutine factor_full(a, last, inline, g, l, h, info)
        type(band_t), intent(in) :: a
        integer, intent(in) :: last
        logical, intent(in) :: inline
        real(dp), intent(out) :: g(NB_MAX, NB_MAX, 0:last), l(NB_MAX, NB_MAX, last), h(NB_MAX, NB_MAX, 0:last - 1)
        integer, intent(out) :: info
        real(dp) :: f(NB_MAX, NB_MAX), e_before(NB_MAX, NB_MAX), e_now(NB_MAX, NB_MAX)
        integer :: i
        logical :: before_in_pattern   !< in_pattern(e_before)

        info = 0
        before_in_pattern = .false.
        f = 0.0_dp
        e_now = 0.0_dp
        e_before = 0.0_dp
        do i = 0, last
            call column_block5(a, i, i, g(:, :, i))
            if (i > 0) call coupling_block5(a, i, i - 1, f)
            if (i < last) call column_block5(a, i, i + 1, e_now)
            call factor_node(i, last, f, e_before, e_now, inline, g, l, h, before_in_pattern, info)
            if (info /= 0) return
            e_before = e_now
        end do
    end subroutine factor_full

    !> Storage for the factors of a matrix with every field in the system (nb = 5) and nodes
    !> 0..last, for factor_blocks: the caller puts D_i into g(:, :, i) (scheme_m's
    !> assemble_blocks writes there).
    subroutine block_prepare(self, last)
        class(block_tridiagonal_t), intent(inout) :: self
        integer, intent(in) :: last
        integer :: stat
        character(len=256) :: message

        self%nb = NB_MAX
        self%last = last
        if (allocated(self%g)) deallocate (self%g, self%l, self%h)
        allocate (self%g(NB_MAX, NB_MAX, 0:last), self%l(NB_MAX, NB_MAX, 1:last), self%h(NB_MAX, NB_MAX, 0:last - 1), &
                  stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the block LU factors')
    end subroutine block_prepare

    !> Factor the matrix given by its blocks, every field in the system (nb = 5), in place:
    !> g(:, :, i) = D_i on entry (block_prepare), G_i on return; e(:, :, i) = E_i (row node i,
    !> column node i+1), f(:, :, i) = F_i (row node i+1, column node i). factor_full's
    !> operations on them (factor_node): the factors of a band holding the same matrix, bit for
    !> bit, without the band (an adaptive-step run factors a system at every new step size;
    !> scheme_m's assemble_blocks). info as block_factor's; inline_inverse as block_factor's
    !> (default .false.).
    subroutine block_factor_blocks(self, e, f, info, inline_inverse)
        class(block_tridiagonal_t), intent(inout) :: self
        real(dp), intent(in), contiguous :: e(:, :, 0:), f(:, :, 0:)
        integer, intent(out) :: info
        logical, intent(in), optional :: inline_inverse
        integer :: i
        logical :: inline, before_in_pattern

        inline = .false.
        if (present(inline_inverse)) inline = inline_inverse
        info = -1
        if (self%nb /= NB_MAX .or. .not. allocated(self%g)) return
        if (size(e, 3) < self%last .or. size(f, 3) < self%last) return
        info = 0
        before_in_pattern = .false.
        associate (last => self%last)
            do i = 0, last
                call factor_node(i, last, f(:, :, max(i - 1, 0)), e(:, :, max(i - 1, 0)), &
                                 e(:, :, min(i, max(last - 1, 0))), inline, self%g, self%l, self%h, &
                                 before_in_pattern, info)
                if (info /= 0) return
            end do
        end associate
    end subroutine block_factor_blocks

    !> Node i of the block LU (factor_full, block_factor_blocks): on entry g(:, :, i) = D_i,
    !> f = F_{i-1} and e_before = E_{i-1} (read when i > 0), e_now = E_i (read when i < last),
    !> before_in_pattern = in_pattern(E_{i-1}) from node i - 1; on return G_i, L_i, H_i, and
    !> before_in_pattern of E_i for node i + 1. S_i = D_i - L_i E_{i-1} with L_i = F_{i-1} G_{i-1},
    !> G_i = S_i^{-1} (invert5 when inline, else LAPACK), H_i = G_i E_i. info: 0, or i + 1 for a
    !> singular pivot block.
    subroutine factor_node(i, last, f, e_before, e_now, inline, g, l, h, before_in_pattern, info)
        integer, intent(in) :: i, last
        real(dp), intent(in) :: f(NB_MAX, NB_MAX), e_before(NB_MAX, NB_MAX), e_now(NB_MAX, NB_MAX)
        logical, intent(in) :: inline
        real(dp), intent(inout) :: g(NB_MAX, NB_MAX, 0:last), l(NB_MAX, NB_MAX, last), h(NB_MAX, NB_MAX, 0:last - 1)
        logical, intent(inout) :: before_in_pattern
        integer, intent(out) :: info

        if (i > 0) then
            if (in_pattern(f) .and. before_in_pattern) then
                call product5_left_pattern(f, g(:, :, i - 1), l(:, :, i))
                call subtract_product5_pattern(l(:, :, i), e_before, g(:, :, i))
            else
                call product5(f, g(:, :, i - 1), l(:, :, i))
                call subtract_product5(l(:, :, i), e_before, g(:, :, i))
            end if
        end if
        if (inline) then
            call invert5(g(:, :, i), info)
        else
            call invert(g(:, :, i), NB_MAX, .false., info)
        end if
        if (info /= 0) then
            info = i + 1
            return
        end if
        if (i < last) then
            before_in_pattern = in_pattern(e_now)
            if (before_in_pattern) then
                call product5_right_pattern(g(:, :, i), e_now, h(:, :, i))
            else
                call product5(g(:, :, i), e_now, h(:, :, i))
            end if
        end if
    end subroutine factor_node

    !> a = a^{-1} for an n x n pivot block: invert_small (inline) or LAPACK's dgetrf and
    !> dgetri. info = 0, or nonzero for a singular block.
    subroutine invert(a, n, inline, info)
        integer, intent(in) :: n
        real(dp), intent(inout) :: a(n, n)
        logical, intent(in) :: inline
        integer, intent(out) :: info
        real(dp) :: work(n * n)
        integer :: ipiv(n)

        if (inline) then
            call invert_small(a, n, info)
        else
            call dgetrf(n, n, a, n, ipiv, info)
            if (info == 0) call dgetri(n, a, n, ipiv, work, size(work), info)
        end if
    end subroutine invert

    !> The nb x nb block (row_node, col_node) of a into blk: band_get's entries, read from the
    !> band storage here (the type-bound call per entry was half of a factorisation).
    pure subroutine get_block(a, nb, row_node, col_node, blk)
        type(band_t), intent(in) :: a
        integer, intent(in) :: nb, row_node, col_node
        real(dp), intent(out) :: blk(nb, nb)
        integer :: q, c, r0, p_first, p_last

        r0 = nb * row_node
        do q = 1, nb
            c = nb * col_node + q
            ! rows r = r0 + p in the band: c - ku <= r <= c + kl (a column of a%ab, contiguous)
            p_first = max(1, c - a%ku - r0)
            p_last = min(nb, c + a%kl - r0)
            blk(:, q) = 0.0_dp
            if (p_first <= p_last) blk(p_first:p_last, q) = &
                a%ab(a%kl + a%ku + 1 + r0 + p_first - c:a%kl + a%ku + 1 + r0 + p_last - c, c)
        end do
    end subroutine get_block
    !> a = a^{-1} for an n x n block by Gauss-Jordan elimination with partial pivoting, in
    !> place (Numerical Recipes' gaussj with row interchanges only): column k is eliminated
    !> above and below the largest pivot of rows k..n, the column of the inverse built in its
    !> place, and the row interchanges undone on the columns at the end, in reverse order.
    !> info = 0, or the column (1-based) without a nonzero pivot (a singular block).
    pure subroutine invert_small(a, n, info)
        integer, intent(in) :: n
        real(dp), intent(inout) :: a(n, n)
        integer, intent(out) :: info
        integer :: pivot_row(NB_MAX), k, p, r
        real(dp) :: inv_pivot, factor, swap(NB_MAX)   ! fixed size: no allocation per block

        info = 0
        do k = 1, n
            p = k - 1 + maxloc(abs(a(k:n, k)), dim=1)
            if (is_zero(a(p, k))) then
                info = k
                return
            end if
            pivot_row(k) = p
            if (p /= k) then
                swap(1:n) = a(k, :)
                a(k, :) = a(p, :)
                a(p, :) = swap(1:n)
            end if
            inv_pivot = 1.0_dp / a(k, k)
            a(k, k) = 1.0_dp
            a(k, :) = a(k, :) * inv_pivot
            do r = 1, n
                if (r == k) cycle
                factor = a(r, k)
                a(r, k) = 0.0_dp
                a(r, :) = a(r, :) - factor * a(k, :)
            end do
        end do
        do k = n, 1, -1
            p = pivot_row(k)
            if (p /= k) then
                swap(1:n) = a(:, k)
                a(:, k) = a(:, p)
                a(:, p) = swap(1:n)
            end if
        end do
    end subroutine invert_small

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

    !> block_solve for a right-hand side that is +0 outside the last node (z = A^{-1} e_s, the
    !> contact response): the same bits, without the forward sweep's products of zeros.
    subroutine block_solve_last(self, b)
        class(block_tridiagonal_t), intent(in) :: self
        real(dp), intent(inout), contiguous :: b(:)

        if (self%nb == NB_MAX) then
            call solve_full_last(self%g, self%l, self%h, self%last, b)
        else
            call solve_reduced(self%g, self%l, self%h, self%last, self%nb, b)
        end if
    end subroutine block_solve_last

    !> forward: y_i = b_i - L_i y_{i-1}; c_i = G_i y_i (off the dependency chain);
    !> back: x_last = c_last, x_i = c_i - H_i x_{i+1}, H_i = G_i E_i. b(:, i) is node i.
    subroutine solve_full(g, l, h, last, b)
        integer, intent(in) :: last
        real(dp), intent(in) :: g(NB_MAX, NB_MAX, 0:last), l(NB_MAX, NB_MAX, last), h(NB_MAX, NB_MAX, 0:last - 1)
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

    !> solve_full for b = +0 at the nodes before the last (the contact response): there the
    !> forward sweep's y_i = b_i - L_i y_{i-1} is +0 minus zeros, +0 = b_i, so the products
    !> L_i y_{i-1} are left out; the same bits. (A routine of its own: solve_full, every
    !> step's, stays as it is.)
    subroutine solve_full_last(g, l, h, last, b)
        integer, intent(in) :: last
        real(dp), intent(in) :: g(NB_MAX, NB_MAX, 0:last), l(NB_MAX, NB_MAX, last), h(NB_MAX, NB_MAX, 0:last - 1)
        real(dp), intent(inout) :: b(NB_MAX, 0:last)
        real(dp) :: y(NB_MAX), x(NB_MAX)
        integer :: i

        do i = 0, last - 1
            b(:, i) = matvec5(g(:, :, i), b(:, i))
        end do
        x = 0.0_dp   ! y_{last-1}
        y = b(:, last) - matvec5(l(:, :, last), x)
        b(:, last) = matvec5(g(:, :, last), y)
        x = b(:, last)
        do i = last - 1, 0, -1
            x = b(:, i) - matvec5(h(:, :, i), x)
            b(:, i) = x
        end do
    end subroutine solve_full_last

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

    !> c = a b for nb x nb blocks: matmul, with the loops of constant length for nb = 5 (every
    !> field in the system), which the compiler unrolls (matmul with a run-time size was a
    !> quarter of an adaptive-mesh run). The same sums in the same order as matmul's.
    pure subroutine multiply(a, b, nb, c)
        integer, intent(in) :: nb
        real(dp), intent(in) :: a(nb, nb), b(nb, nb)
        real(dp), intent(out) :: c(nb, nb)

        if (nb == NB_MAX) then
            call product5(a, b, c)
        else
            c = matmul(a, b)
        end if
    end subroutine multiply

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

    !> c = c - a b for b in_pattern (subtract_product5 with product5_right_pattern).
    pure subroutine subtract_product5_pattern(a, b, c)
        real(dp), intent(in) :: a(NB_MAX, NB_MAX), b(NB_MAX, NB_MAX)
        real(dp), intent(inout) :: c(NB_MAX, NB_MAX)
        real(dp) :: ab(NB_MAX, NB_MAX)

        call product5_right_pattern(a, b, ab)
        c = c - ab
    end subroutine subtract_product5_pattern

    !> c = c - a b for 5 x 5 blocks: a b summed first, as product5 sums it (S_i = D_i - L_i E_{i-1}).
    pure subroutine subtract_product5(a, b, c)
        real(dp), intent(in) :: a(NB_MAX, NB_MAX), b(NB_MAX, NB_MAX)
        real(dp), intent(inout) :: c(NB_MAX, NB_MAX)
        real(dp) :: ab(NB_MAX, NB_MAX)

        call product5(a, b, ab)
        c = c - ab
    end subroutine subtract_product5

    !> The block (row_node, col_node) of a for nb = 5 (get_block), col_node = row_node or
    !> row_node + 1: every column of it is 5 consecutive entries of a column of a%ab, those
    !> above the band in the fill-in rows, zero before the factorisation (kl + ku >= 9).
    pure subroutine column_block5(a, row_node, col_node, blk)
        type(band_t), intent(in) :: a
        integer, intent(in) :: row_node, col_node
        real(dp), intent(out) :: blk(NB_MAX, NB_MAX)
        integer :: q, c, first

        do q = 1, NB_MAX
            c = NB_MAX * col_node + q
            first = a%kl + a%ku + 1 + NB_MAX * row_node + 1 - c   ! row p = 1 of the block
            blk(:, q) = a%ab(first:first + NB_MAX - 1, c)
        end do
    end subroutine column_block5

    !> The block (row_node, col_node) of a for nb = 5 (get_block), its entries outside the
    !> band zero: F_i, below the diagonal (column_block5 reads the blocks on and above it).
    pure subroutine coupling_block5(a, row_node, col_node, blk)
        type(band_t), intent(in) :: a
        integer, intent(in) :: row_node, col_node
        real(dp), intent(out) :: blk(NB_MAX, NB_MAX)
        integer :: q, c, r0, p, p_first, p_last, shift

        r0 = NB_MAX * row_node
        do q = 1, NB_MAX
            c = NB_MAX * col_node + q
            p_first = max(1, c - a%ku - r0)
            p_last = min(NB_MAX, c + a%kl - r0)
            shift = a%kl + a%ku + 1 + r0 - c
            blk(:, q) = 0.0_dp
            do p = p_first, p_last
                blk(p, q) = a%ab(shift + p, c)
            end do
        end do
    end subroutine coupling_block5

    !> invert_small for a 5 x 5 block (factor_full): the same operations on every entry, the
    !> elimination done a column at a time (contiguous) instead of a row at a time. Row k,
    !> the scaled pivot row, is written after the elimination, which it takes no part in.
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

    !> k - 1 + maxloc(abs(column(k:NB_MAX)), dim=1) written out (the intrinsic's call was a fifth
    !> of invert5): the first row of the largest |column(r)|, r >= k, NaNs passed over (all NaN: k).
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
