!> band_t: storage, factor/solve with dgbtrf/dgbtrs against a dense solve (dgesv) of the
!> same matrix, and a singular matrix reported through info; the block
!> LU of block_tridiagonal_m with LAPACK's and with its own (inline) 5 x 5 inversion against
!> the dense solve, on blocks that need pivoting, and a singular pivot block reported; the
!> products with a block in the coupling pattern of (6.1) (in_pattern) equal product5's bit for bit.
program test_banded_m
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use kinds_m, only: dp
    use banded_m, only: band_t, lapack_info_message
    use band_reference_m, only: band_entry, band_to_dense, solve_with_dgbtrs, factor_band_blocks
    use block_tridiagonal_m, only: block_tridiagonal_t, product5, product5_left_pattern, product5_right_pattern, &
                                   in_pattern
    use testing_m, only: check_close, check_true, test_summary
    implicit none
    interface
        subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: dp
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgesv
    end interface
    integer, parameter :: n = 23, kl = 3, ku = 5
    type(band_t) :: a
    real(dp) :: dense(n, n), b(n), x(n), y(n), r
    integer :: i, j, info, ipiv(n), seed_size
    integer, allocatable :: seed(:)
    character(len=64) :: name

    ! a fixed seed: the random matrices (and the test's outcome) the same in every run (the
    ! compiler's own seed changes from run to run, and about 1 run in 100 drew a matrix too
    ! ill-conditioned for the tolerances below)
    call random_seed(size=seed_size)
    allocate (seed(seed_size))
    seed = [(104729 + 7919 * i, i = 1, seed_size)]
    call random_seed(put=seed)
    call a%init(n, kl, ku)
    ! a nonsymmetric band matrix needing pivoting (small diagonal)
    do j = 1, n
        do i = max(1, j - ku), min(n, j + kl)
            call random_number(r)
            call a%add(i, j, r - 0.5_dp)
        end do
        call a%add(j, j, 1.0e-3_dp)
    end do
    dense = band_to_dense(a)
    call check_close('band_entry = dense', dense(5, 8), band_entry(a, 5, 8), 0.0_dp)
    call check_close('outside band is zero', 0.0_dp, band_entry(a, 1, n), 0.0_dp)
    do i = 1, n
        b(i) = sin(real(i, dp))
    end do
    x = a%matvec(b)
    call check_close('matvec = dense product', maxval(abs(matmul(dense, b))), maxval(abs(x)), 1e-14_dp)

    x = b
    call dgesv(n, 1, dense, n, ipiv, x, n, info)
    call check_true('dgesv succeeded', info == 0)
    call a%factor(info)
    call check_true('dgbtrf succeeded', info == 0, lapack_info_message('dgbtrf', info))
    y = b
    call solve_with_dgbtrs(a, y, info)
    call check_true('dgbtrs succeeded', info == 0)
    call a%solve(b)
    call check_true('band solve succeeded', info == 0)
    do i = 1, n
        write (name, '(a,i0)') 'banded solve = dense solve, entry ', i
        call check_close(trim(name), x(i), b(i), 1e-10_dp * max(1.0_dp, abs(x(i))))
        write (name, '(a,i0)') 'dgbtrs = dense solve, entry ', i
        call check_close(trim(name), x(i), y(i), 1e-10_dp * max(1.0_dp, abs(x(i))))
        write (name, '(a,i0)') 'banded solve = dgbtrs to round-off, entry ', i
        call check_close(trim(name), y(i), b(i), 1e-13_dp * max(1.0_dp, abs(x(i))))
    end do

    ! a singular matrix (zero column) must be reported, not solved
    call a%init(4, 1, 1)
    call a%add(1, 1, 1.0_dp)
    call a%add(2, 1, 1.0_dp)
    call a%add(3, 3, 1.0_dp)
    call a%add(4, 4, 1.0_dp)
    call a%factor(info)
    call check_true('singular matrix: info > 0', info > 0)
    call check_true('singular matrix message', index(lapack_info_message('dgbtrf', info), 'singular') > 0)

    call check_block_lu(5, 9)
    call check_block_lu(5, 7)   ! the band of (6.1) with every field: blocks partly outside the band
    call check_block_lu(3, 5)
    call check_pattern_products()
    call test_summary('test_banded_m')
contains

    !> Block LU (nb unknowns per node, 6 nodes, kw sub- and super-diagonals, kw <= 2 nb - 1)
    !> with both inversions of the pivot blocks against dgesv; the diagonal blocks have zero
    !> diagonals (pivoting needed). Then a zero pivot block must give info = its node.
    subroutine check_block_lu(nb, kw)
        integer, intent(in) :: nb, kw
        integer, parameter :: nodes = 6
        type(band_t) :: m
        type(block_tridiagonal_t) :: blocks
        real(dp), allocatable :: full(:, :), rhs(:), exact(:), got(:)
        integer :: n, i, j, k, piv(nb * nodes), stat
        logical :: inline
        character(len=80) :: label

        n = nb * nodes
        call m%init(n, kw, kw)
        do j = 1, n
            do i = max(1, j - kw), min(n, j + kw)
                if (abs((i - 1) / nb - (j - 1) / nb) > 1) cycle   ! block tridiagonal
                call random_number(r)
                if (i /= j) call m%add(i, j, r + 0.5_dp)          ! zero diagonal: rows must be swapped
            end do
        end do
        full = band_to_dense(m)
        allocate (rhs(n), exact(n), got(n))
        rhs = [(cos(real(i, dp)), i = 1, n)]
        exact = rhs
        call dgesv(n, 1, full, n, piv, exact, n, stat)
        call check_true('block test matrix: dgesv', stat == 0)
        do k = 1, 2
            inline = k == 2
            write (label, '(a,i0,a,i0,a,l1)') 'block LU, nb = ', nb, ', band ', kw, ', inline inverse = ', inline
            call factor_band_blocks(blocks, m, nb, stat, inline)
            call check_true(trim(label)//': factors', stat == 0)
            got = rhs
            call blocks%solve(got)
            call check_true(trim(label)//': = dense solve', maxval(abs(got - exact)) <= 1e-10_dp * maxval(abs(exact)))
        end do
        ! node 3's diagonal block zero: its Schur complement is singular only if the
        ! coupling is zero too, so clear both
        do j = 2 * nb + 1, 3 * nb
            do i = max(1, j - kw), min(n, j + kw)
                call m%add(i, j, -band_entry(m, i, j))
            end do
        end do
        call factor_band_blocks(blocks, m, nb, stat, .true.)
        write (label, '(a,i0,a,i0,a)') 'block LU, nb = ', nb, ', band ', kw, ', inline inverse: zero column reported'
        call check_true(trim(label), stat == 3, 'info /= 3')
    end subroutine check_block_lu

    !> product5_left_pattern and product5_right_pattern against product5, bit for bit, on random
    !> blocks with the pattern's entries (some of them zero, of either sign) and a full block
    !> (random signs, so that terms cancel); a block with an entry outside the pattern, a NaN
    !> outside it, are not in_pattern.
    subroutine check_pattern_products()
        real(dp) :: a(5, 5), b(5, 5), c_dense(5, 5), c_pattern(5, 5), r(5, 5)
        logical :: inside(5, 5)
        integer :: trial, i, j, n_diff

        inside = .false.
        do j = 1, 5
            do i = 1, 5
                inside(i, j) = abs(i - j) <= 1
            end do
        end do
        inside(2, 4) = .true.
        inside(4, 2) = .true.
        n_diff = 0
        do trial = 1, 200
            call random_number(a)
            a = a - 0.5_dp
            call random_number(r)
            b = merge(r - 0.5_dp, 0.0_dp, inside)
            if (mod(trial, 3) == 0) b(2, 3) = 0.0_dp
            if (mod(trial, 5) == 0) b(4, 4) = -0.0_dp
            if (mod(trial, 7) == 0) a(:, 2) = 0.0_dp
            call check_true('pattern products: the block is in_pattern', in_pattern(b))
            call product5(a, b, c_dense)
            call product5_right_pattern(a, b, c_pattern)
            n_diff = n_diff + count(transfer(c_dense, 0_int64, 25) /= transfer(c_pattern, 0_int64, 25))
            call product5(b, a, c_dense)
            call product5_left_pattern(b, a, c_pattern)
            n_diff = n_diff + count(transfer(c_dense, 0_int64, 25) /= transfer(c_pattern, 0_int64, 25))
        end do
        call check_true('pattern products = product5 bit for bit', n_diff == 0)
        b(1, 4) = 1.0e-300_dp
        call check_true('an entry outside the pattern: not in_pattern', .not. in_pattern(b))
        b(1, 4) = ieee_value(1.0_dp, ieee_quiet_nan)
        call check_true('a NaN outside the pattern: not in_pattern', .not. in_pattern(b))
    end subroutine check_pattern_products

end program test_banded_m
