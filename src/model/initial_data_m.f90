!> Initial data (2.12) of &initial: a polynomial in x plus an optional step.
!> The one function both validation (boundary values, u0(1) <= g) and initialisation
!> (nodal interpolants) evaluate, so that they cannot disagree.
module initial_data_m
    use kinds_m, only: dp
    implicit none
    private
    public :: profile, STEP_TOL

    !> A point within STEP_TOL of the step's end x_end counts as inside [0, x_end], so a
    !> node computed as i/s that should equal x_end is not lost to round-off.
    real(dp), parameter :: STEP_TOL = 1.0e-12_dp

contains

    !> y = sum_k poly(k) x**k (constant term first, Horner), plus step(1) if step is
    !> present and x <= step(2): the step (amplitude, x_end) adds its amplitude on [0, x_end].
    pure function profile(poly, x, step) result(y)
        real(dp), intent(in) :: poly(0:)
        real(dp), intent(in) :: x
        real(dp), intent(in), optional :: step(2)
        real(dp) :: y
        integer :: k

        y = 0.0_dp
        do k = ubound(poly, 1), 0, -1
            y = y * x + poly(k)
        end do
        if (present(step)) then
            if (x <= step(2) + STEP_TOL) y = y + step(1)
        end if
    end function profile

end module initial_data_m
