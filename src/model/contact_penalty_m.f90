!> Normal compliance (3.4), the paper's penalized contact: sigma(1,t) = -lambda with
!> lambda = (1/eps) [u(1,t) - g]_+ (the term (1/eps)[u_h^n(1) - g]_+ w_h(1) of (6.1)_1), and
!> its energy phi(u) = 1/(2 eps) [u(1,t) - g]_+^2 (the last term of E^n, Corollary 6.2).
module contact_penalty_m
    use kinds_m, only: dp
    use contact_law_m, only: compliance_law_t
    implicit none
    private
    public :: penalty_law_t

    type, extends(compliance_law_t) :: penalty_law_t
    contains
        procedure :: force => penalty_force
        procedure :: energy => penalty_energy
        procedure :: lagged_impulse => penalty_lagged_impulse
        procedure :: implicit_impulse => penalty_implicit_impulse
        procedure :: equilibrium => penalty_equilibrium
        procedure :: discrete_gradient => penalty_discrete_gradient
    end type penalty_law_t

contains

    pure real(dp) function penalty_force(self, u_end)
        class(penalty_law_t), intent(in) :: self
        real(dp), intent(in) :: u_end

        penalty_force = max(u_end - self%g, 0.0_dp) / self%eps
    end function penalty_force

    pure real(dp) function penalty_energy(self, u_end)
        class(penalty_law_t), intent(in) :: self
        real(dp), intent(in) :: u_end

        penalty_energy = 0.5_dp / self%eps * max(u_end - self%g, 0.0_dp)**2
    end function penalty_energy

    !> dt lambda(u_lag), the penalty term of the paper's Section 7 iteration.
    pure real(dp) function penalty_lagged_impulse(self, dt, u_lag)
        class(penalty_law_t), intent(in) :: self
        real(dp), intent(in) :: dt, u_lag

        penalty_lagged_impulse = dt / self%eps * max(u_lag - self%g, 0.0_dp)
    end function penalty_lagged_impulse

    !> lambda = (1/eps)(gap - dt^2 z_s lambda)  ->  dt lambda = dt gap / (eps + dt^2 z_s).
    pure real(dp) function penalty_implicit_impulse(self, gap, dt, z_s)
        class(penalty_law_t), intent(in) :: self
        real(dp), intent(in) :: gap, dt, z_s

        penalty_implicit_impulse = 0.0_dp
        if (gap > 0.0_dp) penalty_implicit_impulse = dt * gap / (self%eps + dt**2 * z_s)
    end function penalty_implicit_impulse

    !> k (u - a) + (1/eps)[u - g]_+ = 0.
    pure real(dp) function penalty_equilibrium(self, a, k) result(u)
        class(penalty_law_t), intent(in) :: self
        real(dp), intent(in) :: a, k

        if (a <= self%g) then
            u = a
        else
            u = (k * a + self%g / self%eps) / (k + 1.0_dp / self%eps)
        end if
    end function penalty_equilibrium

    !> (phi(q) - phi(p)) / (q - p), written per case so that no difference of nearly equal
    !> values is divided (phi'(p) when q = p).
    pure real(dp) function penalty_discrete_gradient(self, p, q) result(dg)
        class(penalty_law_t), intent(in) :: self
        real(dp), intent(in) :: p, q
        real(dp) :: low, high

        low = min(p, q)
        high = max(p, q)
        if (high <= self%g) then
            dg = 0.0_dp
        else if (low >= self%g) then
            dg = 0.5_dp * ((p - self%g) + (q - self%g)) / self%eps
        else
            dg = 0.5_dp * (high - self%g)**2 / (self%eps * (high - low))
        end if
    end function penalty_discrete_gradient

end module contact_penalty_m
