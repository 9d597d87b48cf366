!> Dense output: the solution between the time levels, from the scheme's own interpolant:
!> the polynomial of degree p (time_scheme_m's order) through the last p+1 accepted levels,
!> evaluated in [t_{n-1}, t_n] (Euler: the straight line; BDF2: its own quadratic; midpoint:
!> the same quadratic, not the rule's collocation line, of order 1). Across a contact event
!> the caller passes only the levels since the event (fewer points: a lower degree). The same
!> polynomial gives the time of a contact event: the root of the interpolated gap u(1,t) - g.
!> Its error and why: docs/scheme.md, "Dense output".
module dense_output_m
    use kinds_m, only: dp
    implicit none
    private
    public :: lagrange_weights, interpolant_root

    integer, parameter :: BISECTIONS = 60   !< halvings of the bracket of a root (below round-off)

contains

    !> weight(j) such that sum_j weight(j) X_j is the polynomial through (times(j), X_j),
    !> j = 1..size(times), evaluated at t.
    pure function lagrange_weights(times, t) result(weight)
        real(dp), intent(in) :: times(:), t
        real(dp) :: weight(size(times))
        integer :: j, k

        do j = 1, size(times)
            weight(j) = 1.0_dp
            do k = 1, size(times)
                if (k /= j) weight(j) = weight(j) * (t - times(k)) / (times(j) - times(k))
            end do
        end do
    end function lagrange_weights

    !> The time in [t_lo, t_hi] where the polynomial through (times(j), values(j)) is zero,
    !> found by bisection (found = .false.: it has the same sign at both ends, and root is
    !> undefined).
    pure subroutine interpolant_root(times, values, t_lo, t_hi, root, found)
        real(dp), intent(in) :: times(:), values(:), t_lo, t_hi
        real(dp), intent(out) :: root
        logical, intent(out) :: found
        real(dp) :: a, b, fa, fm
        integer :: k

        a = t_lo
        b = t_hi
        fa = sum(lagrange_weights(times, a) * values)
        root = t_hi
        found = fa * sum(lagrange_weights(times, b) * values) <= 0.0_dp
        if (.not. found) return
        do k = 1, BISECTIONS
            root = 0.5_dp * (a + b)
            fm = sum(lagrange_weights(times, root) * values)
            if (fa * fm <= 0.0_dp) then
                b = root
            else
                a = root
                fa = fm
            end if
        end do
        root = 0.5_dp * (a + b)
    end subroutine interpolant_root

end module dense_output_m
