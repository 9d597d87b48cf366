!> Source terms in every equation of (2.11), for manufactured solutions and forced runs:
!>
!>   rho u_tt - alpha u_xx - varpi u_xxt + gamma1 theta_x + gamma2 P_x = f_v     (momentum)
!>   c theta_t + d P_t + q_x + gamma1 u_xt                              = f_theta (heat supply)
!>   tau0 q_t + q + theta_x                                             = f_q     (Cattaneo, q)
!>   d theta_t + r P_t + hbar eta_x + gamma2 u_xt                        = f_P     (mass supply)
!>   tau eta_t + eta + P_x                                              = f_eta   (Cattaneo, eta)
!>
!> and a traction b(t) added to the contact condition at x = 1:
!>   sigma(1,t) = -(1/eps) [u(1,t) - g]_+ + b(t).
!> In (6.1) they add dt int f phi dx (at t_n) to each equation's right-hand side (times hbar
!> for the eta law, as the equation itself; see scheme_m) and dt b(t_n) to the momentum row
!> of x = 1. Integrals by 3-point Gauss quadrature per element.
module sources_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fields_m, only: N_FIELDS, F_ETA, F_V
    use mesh_m, only: mesh_t
    implicit none
    private
    public :: source_t, add_source_terms

    !> A source: evaluate(t, x) returns the right-hand sides indexed by scheme_m's field
    !> constants (F_V: momentum, F_THETA: heat supply, F_Q, F_P, F_ETA); traction(t) is b(t).
    type, abstract :: source_t
    contains
        procedure(evaluate_interface), deferred :: evaluate
        procedure :: traction => no_traction
    end type source_t

    abstract interface
        pure function evaluate_interface(self, t, x) result(f)
            import :: source_t, dp, N_FIELDS
            class(source_t), intent(in) :: self
            real(dp), intent(in) :: t, x
            real(dp) :: f(N_FIELDS)
        end function evaluate_interface
    end interface

contains

    pure real(dp) function no_traction(self, t)
        class(source_t), intent(in) :: self
        real(dp), intent(in) :: t

        no_traction = 0.0_dp
    end function no_traction

    !> b(i, f) += dt int f_f(t, x) phi_i dx (times hbar for the eta law) and the traction on
    !> the momentum row of x = 1: b, the right-hand side of every field's equation (a run with
    !> sources has all of them: scheme_m's active_fields) on mesh, by field as scheme_m's
    !> old_state_rhs gives it (the caller zeroes the Dirichlet rows after: fields_m's
    !> zero_dirichlet).
    subroutine add_source_terms(source, model, t, dt, b, mesh)
        class(source_t), intent(in) :: source
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: t, dt
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(inout) :: b(0:ubound(mesh%x, 1), N_FIELDS)
        real(dp), parameter :: gauss_x(3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)]
        real(dp), parameter :: gauss_w(3) = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
        real(dp) :: h, x, weight, phi_left, f(N_FIELDS), scale(N_FIELDS)
        integer :: s, e, k

        s = mesh%s()
        scale = dt
        scale(F_ETA) = dt * model%hbar
        do e = 1, s
            h = mesh%h(e)
            do k = 1, 3
                x = 0.5_dp * (mesh%x(e - 1) + mesh%x(e)) + 0.5_dp * gauss_x(k) * h
                weight = 0.5_dp * h * gauss_w(k)
                phi_left = 0.5_dp * (1.0_dp - gauss_x(k))      ! hat of node e-1 at x
                f = scale * weight * source%evaluate(t, x)
                b(e - 1, :) = b(e - 1, :) + f * phi_left
                b(e, :) = b(e, :) + f * (1.0_dp - phi_left)
            end do
        end do
        b(s, F_V) = b(s, F_V) + dt * source%traction(t)
    end subroutine add_source_terms

end module sources_m
