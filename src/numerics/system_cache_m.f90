!> The factored systems of (6.1) a run keeps, keyed by the effective step dt_eff of the
!> step's plan (time_scheme_m) and the mesh they were assembled on; when the cache is full
!> the least recently used entry is replaced.
!>
!> The matrix depends on nothing else (the step model is fixed at set-up, the contact term is
!> not in it, a remesh bumps the mesh key). An entry serves only exactly (bit for bit) the
!> dt_eff it was factored for, so a step gives the same bits whether its system was found
!> here or factored anew, and a restart (empty cache) repeats the run bit for bit: a change
!> must keep both. Why: docs/scheme.md, "Factorisations".
module system_cache_m
    use kinds_m, only: dp
    use reals_m, only: equal
    use banded_m, only: band_t
    use block_tridiagonal_m, only: block_tridiagonal_t
    use ieee_arithmetic, only: ieee_is_finite
    use errors_m, only: check_allocation
    implicit none
    private
    public :: monolithic_system_t, system_cache_t, CACHE_SIZE

    !> factored systems kept (distinct dt_eff; why 16: docs/performance.md, "The step-size ladder")
    integer, parameter :: CACHE_SIZE = 16

    !> The monolithic matrix of (6.1) for one step size, factored, with its contact response.
    type :: monolithic_system_t
        real(dp) :: dt_eff = 0.0_dp    !< the step of (6.1) it was assembled with (0: unused)
        integer :: mesh_key = 0        !< the mesh it was assembled on (system_cache_t's mesh_key)
        integer :: last_used = 0       !< lookup counter of its last use (to replace the oldest)
        type(band_t) :: a              !< factored with dgbtrf
        type(block_tridiagonal_t) :: blocks   !< the same matrix, block LU (fast per-step solve)
        logical :: use_blocks = .false.       !< block LU solves as well as dgbtrf (checked at set-up)
        real(dp), allocatable :: z(:)  !< A^{-1} e_s, the response to a unit contact force
        integer :: contact_dof = 0     !< row of the v equation at x = 1
    contains
        procedure :: solve => system_solve
        procedure :: blocks_agree => system_blocks_agree
    end type monolithic_system_t

    type :: system_cache_t
        type(monolithic_system_t) :: systems(CACHE_SIZE)
        integer :: mesh_key = 1        !< the current mesh (invalidate: a new one)
        integer :: uses = 0            !< lookups so far
    contains
        procedure :: lookup => cache_lookup
        procedure :: stored => cache_stored
        procedure :: invalidate => cache_invalidate
        procedure :: all_use_blocks => cache_all_use_blocks
    end type system_cache_t

contains

    !> The entry k of the system with step dt_eff on the current mesh (found), or the entry
    !> to assemble and factor it in (not found: an unused or the least recently used one;
    !> the caller factors into systems(k) and then calls stored(k, dt_eff)).
    subroutine cache_lookup(self, dt_eff, k, found)
        class(system_cache_t), intent(inout) :: self
        real(dp), intent(in) :: dt_eff
        integer, intent(out) :: k
        logical, intent(out) :: found

        self%uses = self%uses + 1
        found = .false.
        do k = 1, CACHE_SIZE
            if (self%systems(k)%mesh_key /= self%mesh_key) cycle
            if (equal(self%systems(k)%dt_eff, dt_eff)) then
                found = .true.
                self%systems(k)%last_used = self%uses
                return
            end if
        end do
        k = minloc(self%systems%last_used, dim=1)
        self%systems(k)%dt_eff = 0.0_dp
        self%systems(k)%mesh_key = 0
    end subroutine cache_lookup

    !> systems(k) now holds the factored system of dt_eff on the current mesh.
    subroutine cache_stored(self, k, dt_eff)
        class(system_cache_t), intent(inout) :: self
        integer, intent(in) :: k
        real(dp), intent(in) :: dt_eff

        self%systems(k)%dt_eff = dt_eff
        self%systems(k)%mesh_key = self%mesh_key
        self%systems(k)%last_used = self%uses
    end subroutine cache_stored

    !> The mesh changed (or anything else in the matrix): no entry is used again (lookup and
    !> all_use_blocks take only entries of the current mesh key; the old ones, used before any
    !> of the new mesh, are the first replaced).
    subroutine cache_invalidate(self)
        class(system_cache_t), intent(inout) :: self

        self%mesh_key = self%mesh_key + 1
    end subroutine cache_invalidate

    !> x = A^{-1} x, by the block LU if use_blocks, else by dgbtrf's factors.
    subroutine system_solve(self, x)
        class(monolithic_system_t), intent(in) :: self
        real(dp), intent(inout), contiguous :: x(:)

        if (self%use_blocks) then
            call self%blocks%solve(x)
        else
            call self%a%solve(x)
        end if
    end subroutine system_solve

    !> The block LU has no pivoting across nodes; use it only if it solves as well as the
    !> band LU with partial pivoting: on the unit contact force and on a smooth right-hand
    !> side, its residual |A x - b| must be at most 10 times dgbtrf's (or 1e-13 |b|). (The
    !> solutions themselves may differ by cond(A) times round-off, which grows with s.)
    logical function system_blocks_agree(sys, a, x) result(blocks_agree)
        class(monolithic_system_t), intent(in) :: sys
        type(band_t), intent(in) :: a                 !< the matrix, not factored
        real(dp), intent(inout), contiguous :: x(:)   !< work array of the system's size
        real(dp), allocatable :: b(:), reference(:)
        integer :: k, trial
        character(len=256) :: message

        blocks_agree = .true.
        allocate (b(size(x)), stat=trial, errmsg=message)
        call check_allocation(trial, message, 'the block solver check')
        do trial = 1, 2
            if (trial == 1) then
                b = 0.0_dp
                b(sys%contact_dof) = 1.0_dp
            else
                do k = 1, size(b)
                    b(k) = sin(0.1_dp * k)
                end do
            end if
            reference = b
            call sys%a%solve(reference)
            x = b
            call sys%blocks%solve(x)
            blocks_agree = blocks_agree .and. all(ieee_is_finite(x)) .and. &
                           maxval(abs(a%matvec(x) - b)) <= max(10.0_dp * maxval(abs(a%matvec(reference) - b)), &
                                                               1.0e-13_dp * maxval(abs(b)))
        end do
    end function system_blocks_agree

    !> Every system held solves with the block LU (none held: .true.).
    pure logical function cache_all_use_blocks(self)
        class(system_cache_t), intent(in) :: self
        integer :: k

        cache_all_use_blocks = .true.
        do k = 1, CACHE_SIZE
            if (self%systems(k)%mesh_key == self%mesh_key .and. self%systems(k)%dt_eff > 0.0_dp) &
                cache_all_use_blocks = cache_all_use_blocks .and. self%systems(k)%use_blocks
        end do
    end function cache_all_use_blocks

end module system_cache_m
