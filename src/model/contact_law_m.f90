!> The contact law at x = 1 as the rest of the code sees it: what the stepper, the massless
!> end, the energy and the event logic ask of a law, and nothing of any one law. A law is a
!> type extending contact_law_t in its own module (contact_penalty_m, contact_signorini_m);
!> contact_laws_m maps the name of &contact law to one (docs/architecture.md, "A contact
!> law"). No caller tests which law it has: it asks the law.
!>
!> A law lambda = lambda(u(1)) with a potential phi, phi' = lambda (normal compliance), extends
!> compliance_law_t: it gives phi's discrete gradient and gets the midpoint rule's contact step.
module contact_law_m
    use kinds_m, only: dp
    use reals_m, only: is_zero
    implicit none
    private
    public :: contact_law_t, compliance_law_t

    type, abstract :: contact_law_t
        real(dp) :: g = 0.0_dp      !< gap between the free end and the obstacle (&contact g)
        real(dp) :: eps = 1.0_dp    !< &contact eps, for a law that has a compliance
    contains
        procedure, nopass :: is_constraint => law_is_constraint
        procedure :: penetration => law_penetration
        !> lambda at a given u(1) (0 for a constraint, whose lambda is known only from a step)
        procedure(law_of_end), deferred :: force
        !> the law's term of E^n at a given u(1)
        procedure(law_of_end), deferred :: energy
        !> dt lambda(u_lag), the Section 7 iteration's lagged contact term
        procedure(lagged_impulse_i), deferred :: lagged_impulse
        !> dt lambda of one implicit step (see implicit_impulse_i)
        procedure(implicit_impulse_i), deferred :: implicit_impulse
        !> dt lambda of the midpoint rule's half step (see midpoint_impulse_i)
        procedure(midpoint_impulse_i), deferred :: midpoint_impulse
        !> the massless contact node's u(1) (see equilibrium_i)
        procedure(equilibrium_i), deferred :: equilibrium
    end type contact_law_t

    type, abstract, extends(contact_law_t) :: compliance_law_t
    contains
        procedure :: midpoint_impulse => compliance_midpoint_impulse
        !> (phi(q) - phi(p)) / (q - p), phi'(p) when q = p
        procedure(discrete_gradient_i), deferred :: discrete_gradient
    end type compliance_law_t

    abstract interface
        pure real(dp) function law_of_end(self, u_end)
            import :: contact_law_t, dp
            class(contact_law_t), intent(in) :: self
            real(dp), intent(in) :: u_end
        end function law_of_end

        pure real(dp) function lagged_impulse_i(self, dt, u_lag)
            import :: contact_law_t, dp
            class(contact_law_t), intent(in) :: self
            real(dp), intent(in) :: dt, u_lag
        end function lagged_impulse_i

        !> The exact contact step of one implicit step of size dt. Without a contact force
        !> the end would reach u(1) = g + gap; a force lambda moves it to
        !> g + gap - dt^2 z_s lambda, where z_s = e_s^T A^{-1} e_s > 0 is the compliance of
        !> the step's matrix at the contact row (which carries dt lambda). Returns dt lambda,
        !> 0 if gap <= 0 (a piecewise-linear law's semismooth equation has a closed-form root).
        pure real(dp) function implicit_impulse_i(self, gap, dt, z_s)
            import :: contact_law_t, dp
            class(contact_law_t), intent(in) :: self
            real(dp), intent(in) :: gap, dt, z_s
        end function implicit_impulse_i

        !> The contact step of the midpoint rule (time_scheme_m), solved for the half level
        !> Y with step dt = dt_n / 2. Without a contact force the end would reach u_Y(1) = a,
        !> so u^n(1) = 2 u_Y(1) - u_old; a force lambda moves it to
        !> u^n(1) = 2 a - u_old - 2 dt^2 z_s lambda. Returns dt lambda.
        pure real(dp) function midpoint_impulse_i(self, a, u_old, dt, z_s)
            import :: contact_law_t, dp
            class(contact_law_t), intent(in) :: self
            real(dp), intent(in) :: a, u_old, dt, z_s
        end function midpoint_impulse_i

        !> The end position u that minimises k/2 (u - a)^2 + the law's energy: the
        !> equilibrium of a massless contact node tied by the stiffness k > 0 to its
        !> neighbour at a, k (u - a) + lambda(u) = 0.
        pure real(dp) function equilibrium_i(self, a, k)
            import :: contact_law_t, dp
            class(contact_law_t), intent(in) :: self
            real(dp), intent(in) :: a, k
        end function equilibrium_i

        pure real(dp) function discrete_gradient_i(self, p, q)
            import :: compliance_law_t, dp
            class(compliance_law_t), intent(in) :: self
            real(dp), intent(in) :: p, q
        end function discrete_gradient_i
    end interface

contains

    !> Whether u(1) <= g is a constraint (Signorini): the end stops on the obstacle, lambda
    !> is a multiplier known only from a step (no force(u), no energy, no lagged form), so
    !> the contact state is the multiplier's and a release is located on the contact node's
    !> force. A law extending contact_law_t is a compliance unless it says otherwise.
    pure logical function law_is_constraint()
        law_is_constraint = .false.
    end function law_is_constraint

    !> [u(1) - g]_+, the penetration into the obstacle.
    pure real(dp) function law_penetration(self, u_end)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: u_end

        law_penetration = max(u_end - self%g, 0.0_dp)
    end function law_penetration

    !> midpoint_impulse_i for lambda = phi': lambda is the discrete gradient
    !> (phi(u^n(1)) - phi(u_old)) / (u^n(1) - u_old), so that the contact work equals
    !> phi(u^n(1)) - phi(u_old) exactly: the energy identity holds through impacts.
    !> lambda - DG(lambda) is strictly increasing in lambda (phi convex), so the root in
    !> [0, DG(0)] is unique; it is found by bisection with the Illinois secant to round-off.
    pure real(dp) function compliance_midpoint_impulse(self, a, u_old, dt, z_s) result(impulse)
        class(compliance_law_t), intent(in) :: self
        real(dp), intent(in) :: a, u_old, dt, z_s
        real(dp) :: c, lo, hi, f_lo, f_hi, lambda, f, u_free
        integer :: k, side

        impulse = 0.0_dp
        c = 2.0_dp * dt**2 * z_s
        u_free = 2.0_dp * a - u_old
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
    end function compliance_midpoint_impulse

end module contact_law_m
