!> The Signorini condition (2.14), the eps -> 0 limit of normal compliance (3.4):
!> u(1,t) <= g, lambda >= 0, lambda (u(1,t) - g) = 0. A constraint (is_constraint): lambda is
!> a multiplier known only from a step, with no energy term and no lagged form (validate_m
!> refuses solver.method = 'paper' for a constraint).
module contact_signorini_m
    use kinds_m, only: dp
    use contact_law_m, only: contact_law_t
    implicit none
    private
    public :: signorini_law_t

    type, extends(contact_law_t) :: signorini_law_t
    contains
        procedure, nopass :: is_constraint => signorini_is_constraint
        procedure :: force => signorini_zero
        procedure :: energy => signorini_zero
        procedure :: lagged_impulse => signorini_lagged_impulse
        procedure :: implicit_impulse => signorini_implicit_impulse
        procedure :: midpoint_impulse => signorini_midpoint_impulse
        procedure :: equilibrium => signorini_equilibrium
    end type signorini_law_t

contains

    pure logical function signorini_is_constraint()
        signorini_is_constraint = .true.
    end function signorini_is_constraint

    !> No force at a given u(1) (the multiplier comes from a step) and no energy term.
    pure real(dp) function signorini_zero(self, u_end)
        class(signorini_law_t), intent(in) :: self
        real(dp), intent(in) :: u_end

        signorini_zero = 0.0_dp
    end function signorini_zero

    pure real(dp) function signorini_lagged_impulse(self, dt, u_lag)
        class(signorini_law_t), intent(in) :: self
        real(dp), intent(in) :: dt, u_lag

        signorini_lagged_impulse = 0.0_dp
    end function signorini_lagged_impulse

    !> u(1) = g after the step  ->  dt lambda = gap / (dt z_s).
    pure real(dp) function signorini_implicit_impulse(self, gap, dt, z_s)
        class(signorini_law_t), intent(in) :: self
        real(dp), intent(in) :: gap, dt, z_s

        signorini_implicit_impulse = 0.0_dp
        if (gap > 0.0_dp) signorini_implicit_impulse = gap / (dt * z_s)
    end function signorini_implicit_impulse

    !> u^n(1) <= g, lambda >= 0, lambda (u^n(1) - g) = 0 at the end of the step: the closed
    !> form lambda = (2 a - u_old - g) / (2 dt^2 z_s) when positive.
    pure real(dp) function signorini_midpoint_impulse(self, a, u_old, dt, z_s) result(impulse)
        class(signorini_law_t), intent(in) :: self
        real(dp), intent(in) :: a, u_old, dt, z_s
        real(dp) :: c, u_free

        impulse = 0.0_dp
        c = 2.0_dp * dt**2 * z_s
        u_free = 2.0_dp * a - u_old
        if (u_free > self%g) impulse = dt * (u_free - self%g) / c
    end function signorini_midpoint_impulse

    !> The minimiser of k/2 (u - a)^2 over u <= g.
    pure real(dp) function signorini_equilibrium(self, a, k) result(u)
        class(signorini_law_t), intent(in) :: self
        real(dp), intent(in) :: a, k

        u = min(a, self%g)
    end function signorini_equilibrium

end module contact_signorini_m
