!> Dense output: the solution between the time levels, from the scheme's own interpolant.
!>
!> A scheme of order p (time_scheme_m) is interpolated by the polynomial of degree p through
!> its last p+1 accepted levels X^n, X^{n-1}, ..., X^{n-p}, evaluated in [t_{n-1}, t_n]:
!>   Euler (p = 1): the straight line between X^{n-1} and X^n;
!>   BDF2 (p = 2): the quadratic through X^{n-2}, X^{n-1}, X^n, which is BDF2's own
!>     interpolating polynomial (its derivative at t_n is the one the scheme imposes);
!>   midpoint (p = 2): the same quadratic (the rule's own collocation polynomial is the
!>     straight line, of order 1 between the levels).
!> For a solution with p+1 bounded time derivatives the interpolant's own error is
!> |X^(p+1)| / (p+1)! * |(t - t_n)(t - t_{n-1})...(t - t_{n-p})| = O(dt^(p+1)), below the
!> scheme's global error O(dt^p): the error between the steps falls at the scheme's order,
!> with a constant close to the one at the steps (a straight line's O(dt^2/8 X'') is not
!> below it for p = 2). Across a contact event the solution is not smooth: the caller passes
!> only the levels since the event (fewer points: a lower degree).
!> The same polynomial gives the time of a contact event: the root of the interpolated gap
!> u(1,t) - g in the step that changed the contact state.
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
