!> Initial data (2.12) of &initial: a polynomial in x plus an optional step and table.
!> The one function both validation (boundary values, u0(1) <= g) and initialisation
!> (nodal interpolants) evaluate, so that they cannot disagree.
module initial_data_m
    use kinds_m, only: dp
    implicit none
    private
    public :: profile

    !> A point within STEP_TOL of the step's end x_end is on the jump, so that a node
    !> computed as i/s that should equal x_end is not lost to round-off.
    real(dp), parameter :: STEP_TOL = 1.0e-12_dp

contains

    !> y = sum_k poly(k) x**k (constant term first, Horner), plus the step (amplitude,
    !> x_end) if present: its amplitude on [0, x_end), half of it at x_end, the mean of the
    !> jump's two sides, which keeps the pulse's integral exact in the nodal interpolant
    !> when x_end is a node (docs/scheme.md, "Initial data"), plus the table (rows of
    !> position, value; increasing positions covering [0, 1]) if present, interpolated
    !> linearly between its rows.
    pure function profile(poly, x, step, table) result(y)
        real(dp), intent(in) :: poly(0:)
        real(dp), intent(in) :: x
        real(dp), intent(in), optional :: step(2), table(:, :)
        real(dp) :: y, w
        integer :: k

        y = 0.0_dp
        do k = ubound(poly, 1), 0, -1
            y = y * x + poly(k)
        end do
        if (present(step)) then
            if (x < step(2) - STEP_TOL) then
                y = y + step(1)
            else if (x <= step(2) + STEP_TOL) then
                y = y + 0.5_dp * step(1)
            end if
        end if
        if (present(table)) then
            ! rows k, k + 1 around x (the first or last two beyond the ends, by round-off)
            k = min(max(count(table(:, 1) <= x), 1), size(table, 1) - 1)
            w = (x - table(k, 1)) / (table(k + 1, 1) - table(k, 1))
            y = y + (1.0_dp - w) * table(k, 2) + w * table(k + 1, 2)
        end if
    end function profile

end module initial_data_m
