!> Independent reference integrals for the tests: P1 hat functions evaluated from their
!> definition and integrated element by element with 3-point Gauss quadrature (exact for
!> the polynomials of degree <= 5 that occur). Shares no code with src/numerics/fe_m.f90.
module quadrature_m
    use kinds_m, only: dp
    implicit none
    private
    public :: hat, hat_dx, integrate_product

contains

    !> The hat function of node i on the uniform mesh of s elements, at x.
    pure real(dp) function hat(i, s, x)
        integer, intent(in) :: i, s
        real(dp), intent(in) :: x
        real(dp) :: xi, h

        h = 1.0_dp / s
        xi = i * h
        hat = max(0.0_dp, 1.0_dp - abs(x - xi) / h)
    end function hat

    !> Its derivative (one-sided at the kinks is irrelevant: quadrature points are interior).
    pure real(dp) function hat_dx(i, s, x)
        integer, intent(in) :: i, s
        real(dp), intent(in) :: x
        real(dp) :: xi, h

        h = 1.0_dp / s
        xi = i * h
        hat_dx = 0.0_dp
        if (x > xi - h .and. x < xi) hat_dx = 1.0_dp / h
        if (x > xi .and. x < xi + h) hat_dx = -1.0_dp / h
    end function hat_dx

    !> int_0^1 f(i,x) g(j,x) dx, with f, g each the hat (derivative = .false.) or its
    !> derivative (.true.).
    pure real(dp) function integrate_product(i, di, j, dj, s)
        integer, intent(in) :: i, j, s
        logical, intent(in) :: di, dj
        real(dp), parameter :: nodes(3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)]
        real(dp), parameter :: weights(3) = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
        real(dp) :: h, xm, x
        integer :: e, k

        h = 1.0_dp / s
        integrate_product = 0.0_dp
        do e = 1, s
            xm = (e - 0.5_dp) * h
            do k = 1, 3
                x = xm + 0.5_dp * h * nodes(k)
                integrate_product = integrate_product + 0.5_dp * h * weights(k) * f(i, di, x) * f(j, dj, x)
            end do
        end do
    contains
        pure real(dp) function f(node, derivative, x)
            integer, intent(in) :: node
            logical, intent(in) :: derivative
            real(dp), intent(in) :: x
            if (derivative) then
                f = hat_dx(node, s, x)
            else
                f = hat(node, s, x)
            end if
        end function f
    end function integrate_product

end module quadrature_m
