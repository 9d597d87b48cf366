!> The meshes of the error estimate's companions on an adaptive mesh (&output error_estimate
!> with &mesh adaptive): the companion coarser by `ratio` (2: A, 4: C and D) is the coarse mesh
!> of n_coarse / ratio elements bisected top-down, an element of length H kept when every run
!> element inside it is at least H / ratio long; its nodes are the run's, the mesh of ratio 4
!> nested in that of ratio 2, rebuilt whenever the run's mesh changes. Why (and why ratio 2
!> everywhere is impossible): docs/scheme.md, "The error estimate of a run", "On an adaptive mesh".
module companion_mesh_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use errors_m, only: check_allocation
    implicit none
    private
    public :: companion_keys, key_positions, trapezoid_weights

contains

    !> k_comp = the keys of the companion coarser by `ratio` of the run's mesh with keys
    !> k_run (module header); n_coarse: the run's coarse elements (a multiple of ratio),
    !> n_fine: the finest elements.
    subroutine companion_keys(k_run, n_coarse, n_fine, ratio, k_comp)
        integer(int64), intent(in) :: k_run(0:), n_fine
        integer, intent(in) :: n_coarse, ratio
        integer(int64), allocatable, intent(out) :: k_comp(:)
        integer(int64) :: work(0:ubound(k_run, 1)), length
        integer :: n, i, e, stat
        character(len=256) :: message

        length = int(ratio, int64) * (n_fine / int(n_coarse, int64))
        n = 0
        work(0) = 0_int64
        i = 0
        do e = 1, n_coarse / ratio
            call keep_or_bisect(int(e - 1, int64) * length, length, i)
        end do
        allocate (k_comp(0:n), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'a companion''s mesh')
        k_comp = work(0:n)

    contains

        !> The element [a, a + h] of the companion, whose left end is the run's node i: kept
        !> (its right end appended) or bisected; i is then the run's node at its right end.
        recursive subroutine keep_or_bisect(a, h, i)
            integer(int64), intent(in) :: a, h
            integer, intent(inout) :: i
            integer :: j
            integer(int64) :: shortest

            j = i
            shortest = h
            do while (k_run(j) < a + h)
                j = j + 1
                shortest = min(shortest, k_run(j) - k_run(j - 1))
            end do
            if (int(ratio, int64) * shortest >= h) then
                n = n + 1
                work(n) = a + h
                i = j
            else
                call keep_or_bisect(a, h / 2, i)
                call keep_or_bisect(a + h / 2, h / 2, i)
            end if
        end subroutine keep_or_bisect
    end subroutine companion_keys

    !> pos(i) = the index of key sub(i) in keys (sub: increasing keys, all of them in keys).
    pure function key_positions(sub, keys) result(pos)
        integer(int64), intent(in) :: sub(0:), keys(0:)
        integer :: pos(0:ubound(sub, 1))
        integer :: i, j

        j = 0
        do i = 0, ubound(sub, 1)
            do while (keys(j) < sub(i))
                j = j + 1
            end do
            pos(i) = j
        end do
    end function key_positions

    !> The trapezoidal rule's weights on the nodes with keys k (in units of the finest
    !> element: the factor 1 / n_fine cancels in a ratio of norms).
    pure function trapezoid_weights(k) result(weights)
        integer(int64), intent(in) :: k(0:)
        real(dp) :: weights(0:ubound(k, 1))
        real(dp) :: h
        integer :: e

        weights = 0.0_dp
        do e = 1, ubound(k, 1)
            h = 0.5_dp * real(k(e) - k(e - 1), dp)
            weights(e - 1) = weights(e - 1) + h
            weights(e) = weights(e) + h
        end do
    end function trapezoid_weights

end module companion_mesh_m
