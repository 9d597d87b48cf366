!> The contact law at x = 1 (&contact law, g, eps): its force, its energy and the exact
!> contact step. Nowhere else in the code is the law written out.
!>
!>   penalty (normal compliance (3.4)): sigma(1,t) = -lambda, lambda = (1/eps) [u(1,t) - g]_+,
!>       energy 1/(2 eps) [u(1,t) - g]_+^2 (the last term of E^n, Corollary 6.2);
!>   signorini (the eps -> 0 limit): u(1,t) <= g, lambda >= 0, lambda (u(1,t) - g) = 0,
!>       no energy term.
module contact_law_m
    use kinds_m, only: dp
    use reals_m, only: is_zero
    implicit none
    private
    public :: contact_law_t, contact_law

    integer, parameter :: LAW_PENALTY = 1, LAW_SIGNORINI = 2

    type :: contact_law_t
        real(dp) :: g = 0.0_dp      !< gap between the free end and the obstacle
        real(dp) :: eps = 1.0_dp    !< penalty parameter (penalty law only)
        integer :: kind = LAW_PENALTY
    contains
        procedure :: is_signorini => law_is_signorini
        procedure :: penetration => law_penetration
        procedure :: force => law_force
        procedure :: lagged_impulse => law_lagged_impulse
        procedure :: energy => law_energy
        procedure :: implicit_impulse => law_implicit_impulse
        procedure :: midpoint_impulse => law_midpoint_impulse
        procedure :: discrete_gradient => law_discrete_gradient
        procedure :: equilibrium => law_equilibrium
    end type contact_law_t

contains

    !> The law named by &contact law ('penalty' or 'signorini'; validate_m has checked it).
    pure function contact_law(name, g, eps) result(law)
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: g, eps
        type(contact_law_t) :: law

        law%g = g
        law%eps = eps
        law%kind = LAW_PENALTY
        if (trim(name) == 'signorini') law%kind = LAW_SIGNORINI
    end function contact_law

    pure logical function law_is_signorini(self)
        class(contact_law_t), intent(in) :: self

        law_is_signorini = self%kind == LAW_SIGNORINI
    end function law_is_signorini

    !> [u(1) - g]_+, the penetration into the obstacle.
    pure real(dp) function law_penetration(self, u_end)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: u_end

        law_penetration = max(u_end - self%g, 0.0_dp)
    end function law_penetration

    !> lambda = (1/eps) [u(1) - g]_+ of the penalty law at a given u(1) (the Signorini
    !> multiplier is known only from a step: implicit_impulse).
    pure real(dp) function law_force(self, u_end)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: u_end

        law_force = 0.0_dp
        if (self%kind == LAW_PENALTY) law_force = max(u_end - self%g, 0.0_dp) / self%eps
    end function law_force

    !> dt lambda(u_lag), the penalty term of the paper's Section 7 iteration with a lagged u(1).
    pure real(dp) function law_lagged_impulse(self, dt, u_lag)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: dt, u_lag

        law_lagged_impulse = dt / self%eps * max(u_lag - self%g, 0.0_dp)
    end function law_lagged_impulse

    !> The law's term of E^n: 1/(2 eps) [u(1) - g]_+^2 (penalty), 0 (Signorini).
    pure real(dp) function law_energy(self, u_end)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: u_end

        law_energy = 0.0_dp
        if (self%kind == LAW_PENALTY) law_energy = 0.5_dp / self%eps * max(u_end - self%g, 0.0_dp)**2
    end function law_energy

    !> The exact contact step of one implicit step of size dt. Without a contact force the
    !> end would reach u(1) = g + gap; a force lambda moves it to g + gap - dt^2 z_s lambda,
    !> where z_s = e_s^T A^{-1} e_s > 0 is the compliance of the step's matrix at the contact
    !> row (which carries dt lambda). Returns dt lambda: 0 if gap <= 0, else
    !>   penalty:   lambda = (1/eps)(gap - dt^2 z_s lambda)  ->  dt lambda = dt gap / (eps + dt^2 z_s)
    !>   Signorini: u(1) = g                              ->  dt lambda = gap / (dt z_s)
    !> (the semismooth equation of a piecewise-linear law has this closed-form root).
    pure real(dp) function law_implicit_impulse(self, gap, dt, z_s)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: gap, dt, z_s

        law_implicit_impulse = 0.0_dp
        if (.not. (gap > 0.0_dp)) return
        if (self%kind == LAW_SIGNORINI) then
            law_implicit_impulse = gap / (dt * z_s)
        else
            law_implicit_impulse = dt * gap / (self%eps + dt**2 * z_s)
        end if
    end function law_implicit_impulse

    !> The contact step of the midpoint rule (time_scheme_m), solved for the half level Y
    !> with step dt = dt_n / 2. Without a contact force the end would reach u_Y(1) = a, so
    !> u^n(1) = 2 u_Y(1) - u_old; a force lambda moves it to u^n(1) = 2 a - u_old - 2 dt^2 z_s lambda.
    !> Returns dt lambda with
    !>   penalty: lambda = the discrete gradient (phi(u^n(1)) - phi(u_old)) / (u^n(1) - u_old)
    !>            of phi(u) = 1/(2 eps)[u - g]_+^2, so that the contact work equals
    !>            phi(u^n(1)) - phi(u_old) exactly: the energy identity holds through impacts.
    !>            lambda - DG(lambda) is strictly increasing in lambda, so the root in
    !>            [0, DG(0)] is unique; it is found by bisection with the Illinois secant
    !>            to round-off.
    !>   Signorini: u^n(1) <= g, lambda >= 0, lambda (u^n(1) - g) = 0 at the end of the step;
    !>            the closed form lambda = (2 a - u_old - g) / (2 dt^2 z_s) when positive.
    function law_midpoint_impulse(self, a, u_old, dt, z_s) result(impulse)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: a, u_old, dt, z_s
        real(dp) :: impulse
        real(dp) :: c, lo, hi, f_lo, f_hi, lambda, f, u_free
        integer :: k, side

        impulse = 0.0_dp
        c = 2.0_dp * dt**2 * z_s
        u_free = 2.0_dp * a - u_old
        if (self%kind == LAW_SIGNORINI) then
            if (u_free > self%g) impulse = dt * (u_free - self%g) / c
            return
        end if
        hi = self%discrete_gradient(u_old, u_free)
        if (.not. (hi > 0.0_dp)) return
        lo = 0.0_dp
        f_lo = -hi                                        ! lambda - DG at lambda = 0
        f_hi = hi - self%discrete_gradient(u_old, u_free - c * hi)
        side = 0
        lambda = hi
        do k = 1, 200
            if (is_zero(f_hi)) then
                lambda = hi
                exit
            end if
            lambda = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
            if (.not. (lambda > lo .and. lambda < hi)) lambda = 0.5_dp * (lo + hi)
            f = lambda - self%discrete_gradient(u_old, u_free - c * lambda)
            if (f > 0.0_dp) then
                hi = lambda
                f_hi = f
                if (side == 1) f_lo = 0.5_dp * f_lo       ! Illinois: halve the stale end
                side = 1
            else
                lo = lambda
                f_lo = f
                if (side == -1) f_hi = 0.5_dp * f_hi
                side = -1
            end if
            if (is_zero(f) .or. hi - lo <= 4.0_dp * epsilon(1.0_dp) * hi) exit
        end do
        impulse = dt * lambda
    end function law_midpoint_impulse

    !> (phi(q) - phi(p)) / (q - p) for phi(u) = 1/(2 eps)[u - g]_+^2, written per case so
    !> that no difference of nearly equal values is divided (phi'(p) when q = p).
    pure real(dp) function law_discrete_gradient(self, p, q) result(dg)
        class(contact_law_t), intent(in) :: self
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
    end function law_discrete_gradient

    !> The end position u that minimises k/2 (u - a)^2 + the law's energy (Signorini: over
    !> u <= g): the equilibrium of a massless contact node tied by the stiffness k > 0 to its
    !> neighbour at a, i.e. k (u - a) + lambda(u) = 0 (penalty), or u = min(a, g) (Signorini).
    pure real(dp) function law_equilibrium(self, a, k) result(u)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: a, k

        if (self%kind == LAW_SIGNORINI) then
            u = min(a, self%g)
        else if (a <= self%g) then
            u = a
        else
            u = (k * a + self%g / self%eps) / (k + 1.0_dp / self%eps)
        end if
    end function law_equilibrium

end module contact_law_m
