!> Conditioning of the monolithic banded matrix of (6.1) (scheme_m%assemble_matrix, scaled as
!> in docs/scheme.md) at the paper's parameters and at extreme ones: LAPACK's estimate of the
!> reciprocal 1-norm condition number, rcond = 1 / (||A||_1 ||A^{-1}||_1) (dgbcon on the
!> dgbtrf factors), the same after row and column equilibration (dgbequ), the relative
!> residual of a solve, and how far the block-tridiagonal LU (block_tridiagonal_m, the
!> per-step solver) is from the dgbtrf solution (cond(A) x round-off; stepper_m accepts the
!> block LU by its residual, see stepper_m's blocks_agree).
!> Prints the table of docs/robustness.md; checks only sane things: every rcond in (0, 1],
!> a backward-stable solve (relative residual <= 1e-12), and the paper's case far from
!> singular (rcond > 1e-14).
!> Meshes stay at s <= 2000: on these badly scaled factors dgbcon's triangular solves
!> (dlatbs) take their careful, overflow-guarded path, which costs O(n**2).
program test_conditioning
    use kinds_m, only: dp
    use config_m, only: model_t
    use banded_m, only: band_t, lapack_info_message
    use block_tridiagonal_m, only: block_tridiagonal_t
    use band_reference_m, only: factor_band_blocks
    use scheme_m, only: assemble_matrix
    use slots_m, only: MONOLITHIC_SLOTS
    use meshes_m, only: uniform_mesh
    use fields_m, only: N_FIELDS, F_V
    use testing_m, only: check_true, test_summary
    use iso_fortran_env, only: output_unit
    implicit none
    interface
        subroutine dgbcon(norm, n, kl, ku, ab, ldab, ipiv, anorm, rcond, work, iwork, info)
            import :: dp
            character(len=1), intent(in) :: norm
            integer, intent(in) :: n, kl, ku, ldab
            real(dp), intent(in) :: ab(ldab, *)
            integer, intent(in) :: ipiv(*)
            real(dp), intent(in) :: anorm
            real(dp), intent(out) :: rcond
            real(dp), intent(out) :: work(*)
            integer, intent(out) :: iwork(*)
            integer, intent(out) :: info
        end subroutine dgbcon
        subroutine dgbequ(m, n, kl, ku, ab, ldab, r, c, rowcnd, colcnd, amax, info)
            import :: dp
            integer, intent(in) :: m, n, kl, ku, ldab
            real(dp), intent(in) :: ab(ldab, *)
            real(dp), intent(out) :: r(*), c(*)
            real(dp), intent(out) :: rowcnd, colcnd, amax
            integer, intent(out) :: info
        end subroutine dgbequ
    end interface

    type :: case_t
        character(len=24) :: label
        real(dp) :: rho, varpi, tau0, tau, dt
        integer :: s
    end type case_t

    type(case_t), parameter :: CASES(*) = [ &
        case_t('paper (7.1)', 1.2298e-17_dp, 0.1_dp, 0.02_dp, 0.2_dp, 1.0e-4_dp, 500), &
        case_t('varpi=0', 1.2298e-17_dp, 0.0_dp, 0.02_dp, 0.2_dp, 1.0e-4_dp, 500), &
        case_t('varpi=0 dt=1e-7', 1.2298e-17_dp, 0.0_dp, 0.02_dp, 0.2_dp, 1.0e-7_dp, 500), &
        case_t('varpi=0 dt=1e-7 s=2000', 1.0e-17_dp, 0.0_dp, 0.02_dp, 0.2_dp, 1.0e-7_dp, 2000), &
        case_t('varpi=1e-6 dt=1e-7', 1.0e-17_dp, 1.0e-6_dp, 0.02_dp, 0.2_dp, 1.0e-7_dp, 500), &
        case_t('dt=0.5', 1.2298e-17_dp, 0.1_dp, 0.02_dp, 0.2_dp, 0.5_dp, 500), &
        case_t('varpi=10 dt=0.5', 1.2298e-17_dp, 10.0_dp, 0.02_dp, 0.2_dp, 0.5_dp, 500), &
        case_t('rho=1', 1.0_dp, 0.1_dp, 0.02_dp, 0.2_dp, 1.0e-4_dp, 500), &
        case_t('rho=1 varpi=0 dt=1e-7', 1.0_dp, 0.0_dp, 0.02_dp, 0.2_dp, 1.0e-7_dp, 500), &
        case_t('tau0=tau=0 dt=1e-7', 1.2298e-17_dp, 0.1_dp, 0.0_dp, 0.0_dp, 1.0e-7_dp, 500), &
        case_t('tau0=tau=10 dt=1e-7', 1.2298e-17_dp, 0.1_dp, 10.0_dp, 10.0_dp, 1.0e-7_dp, 500), &
        case_t('s=2', 1.2298e-17_dp, 0.1_dp, 0.02_dp, 0.2_dp, 1.0e-4_dp, 2), &
        case_t('s=2000', 1.2298e-17_dp, 0.1_dp, 0.02_dp, 0.2_dp, 1.0e-4_dp, 2000) ]

    type(case_t) :: c
    integer :: k
    real(dp) :: rcond, rcond_eq, residual, block_diff

    write (output_unit, '(a)') '| case | rho | varpi | tau0, tau | dt | s | rcond (1-norm) | rcond equilibrated | ' // &
        'residual | block LU vs dgbtrf |'
    write (output_unit, '(a)') '|---|---|---|---|---|---|---|---|---|---|'
    do k = 1, size(CASES)
        c = CASES(k)
        call measure(c, rcond, rcond_eq, residual, block_diff)
        write (output_unit, '(a,4(es9.2,a),es8.1,a,i0,4(a,es9.2),a)') '| '//trim(c%label)//' | ', c%rho, ' | ', &
            c%varpi, ' | ', c%tau0, ', ', c%tau, ' | ', c%dt, ' | ', c%s, ' | ', rcond, ' | ', rcond_eq, ' | ', &
            residual, ' | ', block_diff, ' |'
        call check_true(trim(c%label)//': 0 < rcond <= 1', rcond > 0.0_dp .and. rcond <= 1.0_dp)
        call check_true(trim(c%label)//': 0 < rcond (equilibrated) <= 1', rcond_eq > 0.0_dp .and. rcond_eq <= 1.0_dp)
        call check_true(trim(c%label)//': backward-stable solve', residual <= 1.0e-12_dp)
        if (k == 1) call check_true('paper case far from singular', rcond > 1.0e-14_dp)
    end do
    call test_summary('test_conditioning')

contains

    !> rcond of the assembled matrix and of its equilibrated form, the relative residual
    !> ||A x - b||_inf / (||A||_inf ||x||_inf) of a dgbtrf solve, and the largest relative
    !> difference between the block-tridiagonal and the dgbtrf solutions (contact response
    !> e_s and a smooth right-hand side, as stepper_m checks at set-up).
    subroutine measure(c, rcond, rcond_eq, residual, block_diff)
        type(case_t), intent(in) :: c
        real(dp), intent(out) :: rcond, rcond_eq, residual, block_diff
        type(model_t) :: model
        type(band_t) :: a, a_eq
        type(block_tridiagonal_t) :: blocks
        real(dp), allocatable :: work(:), r(:), col(:), b(:), x(:), y(:), ax(:), band_only(:, :)
        integer, allocatable :: iwork(:)
        real(dp) :: anorm, rowcnd, colcnd, amax, inf_norm
        integer :: n, info, i, j, kd, contact_dof

        model = model_t()
        model%rho = c%rho
        model%varpi = c%varpi
        model%tau0 = c%tau0
        model%tau = c%tau
        call assemble_matrix(model, uniform_mesh(c%s), c%dt, MONOLITHIC_SLOTS, a)
        n = a%n
        kd = a%kl + a%ku + 1
        allocate (work(3 * n), iwork(n), r(n), col(n), b(n), x(n), y(n), ax(n))
        ! 1-norm and inf-norm before factoring (the kl fill rows are zero)
        anorm = maxval(sum(abs(a%ab), dim=1))
        ax = 0.0_dp
        do j = 1, n
            do i = max(1, j - a%ku), min(n, j + a%kl)
                ax(i) = ax(i) + abs(a%ab(kd + i - j, j))
            end do
        end do
        inf_norm = maxval(ax)
        do i = 1, n
            b(i) = sin(0.1_dp * i) + 0.5_dp
        end do
        ax = a%matvec(b)   ! keep A for the residual: A b with the unfactored matrix
        a_eq = a
        call factor_band_blocks(blocks, a, N_FIELDS, info, .false.)
        call check_true(trim(c%label)//': block LU factors', info == 0)

        ! equilibrated copy: A_eq = diag(r) A diag(col)
        allocate (band_only(a%kl + a%ku + 1, n))
        band_only = a%ab(a%kl + 1:, :)
        call dgbequ(n, n, a%kl, a%ku, band_only, size(band_only, 1), r, col, rowcnd, colcnd, amax, info)
        call check_true(trim(c%label)//': dgbequ', info == 0, 'info /= 0')
        do j = 1, n
            do i = max(1, j - a%ku), min(n, j + a%kl)
                a_eq%ab(kd + i - j, j) = r(i) * a%ab(kd + i - j, j) * col(j)
            end do
        end do

        call a%factor(info)
        call check_true(trim(c%label)//': dgbtrf', info == 0, lapack_info_message('dgbtrf', info))
        call dgbcon('1', n, a%kl, a%ku, a%ab, size(a%ab, 1), a%ipiv, anorm, rcond, work, iwork, info)
        call check_true(trim(c%label)//': dgbcon', info == 0)

        anorm = maxval(sum(abs(a_eq%ab), dim=1))
        call a_eq%factor(info)
        call check_true(trim(c%label)//': dgbtrf (equilibrated)', info == 0, lapack_info_message('dgbtrf', info))
        call dgbcon('1', n, a_eq%kl, a_eq%ku, a_eq%ab, size(a_eq%ab, 1), a_eq%ipiv, anorm, rcond_eq, work, iwork, info)
        call check_true(trim(c%label)//': dgbcon (equilibrated)', info == 0)

        ! solve A x = (A b) and compare: residual relative to ||A|| ||x||
        x = ax
        call a%solve(x)
        ! A x with the unfactored matrix: rebuild it
        call assemble_matrix(model, uniform_mesh(c%s), c%dt, MONOLITHIC_SLOTS, a_eq)
        residual = maxval(abs(a_eq%matvec(x) - ax)) / (inf_norm * maxval(abs(x)))

        ! block LU against dgbtrf: contact response and the smooth right-hand side
        contact_dof = N_FIELDS * c%s + MONOLITHIC_SLOTS(F_V)
        x = 0.0_dp
        x(contact_dof) = 1.0_dp
        y = x
        call a%solve(y)
        call blocks%solve(x)
        block_diff = maxval(abs(x - y)) / maxval(abs(y))
        x = ax
        y = ax
        call a%solve(y)
        call blocks%solve(x)
        block_diff = max(block_diff, maxval(abs(x - y)) / maxval(abs(y)))
    end subroutine measure

end program test_conditioning
