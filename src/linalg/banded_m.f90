!> Banded matrices in LAPACK general-band storage, factored with dgbtrf and solved by
!> band_solve, a plain-loop substitution on dgbtrf's factors: the paper method's blocks, and
!> the monolithic method's check of its block LU and fallback (stepper_m). Every LAPACK info
!> is decoded into a readable message.
module banded_m
    use kinds_m, only: dp
    use errors_m, only: check_allocation
    implicit none
    private
    public :: band_t, lapack_info_message

    interface
        subroutine dgbtrf(m, n, kl, ku, ab, ldab, ipiv, info)
            import :: dp
            integer, intent(in) :: m, n, kl, ku, ldab
            real(dp), intent(inout) :: ab(ldab, *)
            integer, intent(out) :: ipiv(*)
            integer, intent(out) :: info
        end subroutine dgbtrf
    end interface

    !> A general band matrix: entry (i,j), |i-j| within the band, lives at ab(kl+ku+1+i-j, j);
    !> the first kl rows of ab are room for the fill-in of the LU factorisation.
    type :: band_t
        integer :: n = 0
        integer :: kl = 0
        integer :: ku = 0
        real(dp), allocatable :: ab(:, :)
        integer, allocatable :: ipiv(:)
        real(dp), allocatable :: inv_diag(:)   !< 1 / U(j,j), so that the solve multiplies
        logical :: factored = .false.
    contains
        procedure :: init => band_init
        procedure :: add => band_add
        procedure :: release => band_release
        procedure :: matvec => band_matvec
        procedure :: factor => band_factor
        procedure :: solve => band_solve
    end type band_t

contains

    !> Allocate an n x n band matrix with kl sub- and ku super-diagonals, all zero.
    subroutine band_init(self, n, kl, ku)
        class(band_t), intent(inout) :: self
        integer, intent(in) :: n, kl, ku
        integer :: stat
        character(len=256) :: message

        self%n = n
        self%kl = kl
        self%ku = ku
        if (allocated(self%ab)) deallocate (self%ab)
        if (allocated(self%ipiv)) deallocate (self%ipiv)
        allocate (self%ab(2 * kl + ku + 1, n), self%ipiv(n), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'a band matrix')
        self%ab = 0.0_dp
        self%ipiv = 0
        self%factored = .false.
    end subroutine band_init

    !> Free the storage of a matrix no longer used (e.g. one whose block LU solves instead):
    !> n, kl and ku are kept; init allocates it again.
    subroutine band_release(self)
        class(band_t), intent(inout) :: self

        if (allocated(self%ab)) deallocate (self%ab)
        if (allocated(self%ipiv)) deallocate (self%ipiv)
        self%factored = .false.
    end subroutine band_release

    !> A(i,j) += value. An entry outside the band is a programming error.
    subroutine band_add(self, i, j, value)
        class(band_t), intent(inout) :: self
        integer, intent(in) :: i, j
        real(dp), intent(in) :: value

        if (j - i > self%ku .or. i - j > self%kl) error stop 'band_add: entry outside the band'
        self%ab(self%kl + self%ku + 1 + i - j, j) = self%ab(self%kl + self%ku + 1 + i - j, j) + value
    end subroutine band_add

    !> y = A x; only meaningful before factor().
    pure function band_matvec(self, x) result(y)
        class(band_t), intent(in) :: self
        real(dp), intent(in) :: x(:)
        real(dp) :: y(self%n)
        integer :: i, j

        y = 0.0_dp
        do j = 1, self%n
            do i = max(1, j - self%ku), min(self%n, j + self%kl)
                y(i) = y(i) + self%ab(self%kl + self%ku + 1 + i - j, j) * x(j)
            end do
        end do
    end function band_matvec

    !> LU factorisation in place (dgbtrf); info as LAPACK's, decoded by lapack_info_message.
    subroutine band_factor(self, info)
        class(band_t), intent(inout) :: self
        integer, intent(out) :: info

        call dgbtrf(self%n, self%n, self%kl, self%ku, self%ab, size(self%ab, 1), self%ipiv, info)
        self%factored = info == 0
        if (self%factored) self%inv_diag = 1.0_dp / self%ab(self%kl + self%ku + 1, :)
    end subroutine band_factor

    !> Solve A x = b in place with the factors of factor(): forward substitution with L and the
    !> row interchanges, back substitution with the band of U: the order of LAPACK's dgbtrs
    !> ('N', one right-hand side) in plain loops (docs/performance.md), but U's diagonal
    !> divides as a product with its reciprocal, so the bits differ from dgbtrs's.
    !> No allocation: called every time step. It cannot fail once factor() succeeded
    !> (calling it before is a bug in rodcontact and stops the program).
    subroutine band_solve(self, b)
        class(band_t), intent(in) :: self
        real(dp), intent(inout) :: b(:)
        integer :: j, i, jp, lm, kd, ku_u
        real(dp) :: temp

        if (.not. self%factored) error stop 'band_solve: matrix not factored'
        kd = self%kl + self%ku + 1         ! row of the diagonal in ab
        ku_u = self%kl + self%ku           ! super-diagonals of U after pivoting
        ! L y = P b: column j of L (unit diagonal) holds the multipliers in rows kd+1..kd+lm
        do j = 1, self%n - 1
            lm = min(self%kl, self%n - j)
            jp = self%ipiv(j)
            temp = b(jp)
            if (jp /= j) then
                b(jp) = b(j)
                b(j) = temp
            end if
            do i = 1, lm
                b(j + i) = b(j + i) - self%ab(kd + i, j) * temp
            end do
        end do
        ! U x = y, U upper triangular with ku_u super-diagonals: ab(kd + i - j, j) = U(i, j).
        ! Multiplying by the stored reciprocal keeps a division off the critical path: each
        ! column waits for the previous one, so the solve is latency-bound, not flop-bound.
        do j = self%n, 1, -1
            b(j) = b(j) * self%inv_diag(j)
            temp = b(j)
            do i = max(1, j - ku_u), j - 1
                b(i) = b(i) - self%ab(kd + i - j, j) * temp
            end do
        end do
    end subroutine band_solve

    !> A readable message for a LAPACK info value of routine (e.g. 'dgbtrf').
    function lapack_info_message(routine, info) result(message)
        character(len=*), intent(in) :: routine
        integer, intent(in) :: info
        character(len=:), allocatable :: message
        character(len=32) :: buf

        write (buf, '(i0)') abs(info)
        if (info == 0) then
            message = routine//': success'
        else if (info < 0) then
            message = routine//': argument '//trim(buf)//' had an illegal value (a bug in rodcontact)'
        else
            message = routine//': the matrix is singular: U('//trim(buf)//','//trim(buf)// &
                      ') is exactly zero in the LU factorisation'
        end if
    end function lapack_info_message

end module banded_m
