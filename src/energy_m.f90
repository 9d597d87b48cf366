!> The discrete energy of Corollary 6.2 and the contact diagnostics of SPEC section 4.
module energy_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use scheme_m, only: F_Q, F_THETA, F_V, F_P, F_ETA
    implicit none
    private
    public :: discrete_energy, bdf2_energy, penetration, mass_product, stiffness_product

contains

    !> E^n = 1/2 int (rho v^2 + alpha u_x^2 + c theta^2 + r P^2 + 2 d P theta + tau0 q^2
    !>       + tau hbar eta^2) dx + 1/(2 eps) [u(1) - g]_+^2, integrals exact for P1 functions.
    !> With the Signorini law (penalty = .false.) the last term is absent: u(1) <= g.
    pure function discrete_energy(model, eps, g, u, w, penalty) result(energy)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: eps, g
        real(dp), intent(in) :: u(0:)
        real(dp), intent(in) :: w(0:, :)
        logical, intent(in), optional :: penalty   !< .false.: Signorini law, no penalty energy
        real(dp) :: energy
        real(dp) :: mass_terms, strain_terms
        integer :: e, s

        ! One pass over the elements (this runs every time step): on element e the mass
        ! product of P1 functions a, b is h/6 (2 a0 b0 + a0 b1 + a1 b0 + 2 a1 b1), written
        ! here as h/6 ((a0 + a1)(b0 + b1) + a0 b0 + a1 b1) for every pair of fields.
        s = ubound(u, 1)
        mass_terms = 0.0_dp
        strain_terms = 0.0_dp
        do e = 1, s
            mass_terms = mass_terms &
                + model%rho * element_mass_product(w(e - 1, F_V), w(e, F_V), w(e - 1, F_V), w(e, F_V)) &
                + model%c * element_mass_product(w(e - 1, F_THETA), w(e, F_THETA), w(e - 1, F_THETA), w(e, F_THETA)) &
                + model%r * element_mass_product(w(e - 1, F_P), w(e, F_P), w(e - 1, F_P), w(e, F_P)) &
                + 2.0_dp * model%d * element_mass_product(w(e - 1, F_P), w(e, F_P), w(e - 1, F_THETA), w(e, F_THETA)) &
                + model%tau0 * element_mass_product(w(e - 1, F_Q), w(e, F_Q), w(e - 1, F_Q), w(e, F_Q)) &
                + model%tau * model%hbar * element_mass_product(w(e - 1, F_ETA), w(e, F_ETA), w(e - 1, F_ETA), w(e, F_ETA))
            strain_terms = strain_terms + (u(e) - u(e - 1))**2
        end do
        energy = 0.5_dp * (mass_terms / (6.0_dp * real(s, dp)) + model%alpha * strain_terms * real(s, dp))
        if (present(penalty)) then
            if (.not. penalty) return
        end if
        energy = energy + 0.5_dp / eps * penetration(u, g)**2
    end function discrete_energy

    !> The energy of the BDF2 scheme's law: G-stability of BDF2 gives, for the linear part
    !> of (2.11) tested with the new level,
    !>   (3a - 4b + c)/2 . a = [|a|^2 + |2a - b|^2]/4 - [|b|^2 + |2b - c|^2]/4 + |a - 2b + c|^2/4,
    !> so E_G^n = (E_lin(X^n) + E_lin(2 X^n - X^{n-1})) / 2 never rises while the contact
    !> node is inactive (E_lin: E^n without the penalty term). The penalty term is added at
    !> the current level, 1/(2 eps)[u^n(1) - g]_+^2. With an active penalty BDF2 has no such
    !> law (the nonlinear term is not G-stable); see docs/performance.md for what we measured.
    !> u_work, w_work: arrays shaped as u, w (no allocation here; called every step).
    !> lin_now: E_lin(X^n) when the caller has it already (it is not computed again).
    subroutine bdf2_energy(model, eps, g, u, w, u_prev, w_prev, u_work, w_work, penalty, energy, lin_now)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: eps, g
        real(dp), intent(in) :: u(0:), w(0:, :), u_prev(0:), w_prev(0:, :)
        real(dp), intent(inout) :: u_work(0:), w_work(0:, :)
        logical, intent(in) :: penalty
        real(dp), intent(out) :: energy
        real(dp), intent(in), optional :: lin_now
        real(dp) :: lin

        if (present(lin_now)) then
            lin = lin_now
        else
            lin = discrete_energy(model, eps, g, u, w, .false.)
        end if
        u_work = 2.0_dp * u - u_prev
        w_work = 2.0_dp * w - w_prev
        energy = 0.5_dp * (lin + discrete_energy(model, eps, g, u_work, w_work, .false.))
        if (penalty) energy = energy + 0.5_dp / eps * penetration(u, g)**2
    end subroutine bdf2_energy

    !> 6/h times the mass product of two P1 functions on one element (nodal values a0, a1
    !> and b0, b1).
    pure real(dp) function element_mass_product(a0, a1, b0, b1)
        real(dp), intent(in) :: a0, a1, b0, b1

        element_mass_product = (a0 + a1) * (b0 + b1) + a0 * b0 + a1 * b1
    end function element_mass_product

    !> [u(1) - g]_+, the penetration into the obstacle.
    pure real(dp) function penetration(u, g)
        real(dp), intent(in) :: u(0:)
        real(dp), intent(in) :: g

        penetration = max(u(ubound(u, 1)) - g, 0.0_dp)
    end function penetration

    !> int a b dx for P1 functions a, b given by nodal values 0..s on the uniform mesh.
    pure real(dp) function mass_product(a, b)
        real(dp), intent(in) :: a(0:), b(0:)
        integer :: e, s

        s = ubound(a, 1)
        mass_product = 0.0_dp
        do e = 1, s
            mass_product = mass_product + 2.0_dp * a(e - 1) * b(e - 1) + a(e - 1) * b(e) &
                           + a(e) * b(e - 1) + 2.0_dp * a(e) * b(e)
        end do
        mass_product = mass_product / (6.0_dp * real(s, dp))
    end function mass_product

    !> int a_x b_x dx for P1 functions a, b given by nodal values 0..s on the uniform mesh.
    pure real(dp) function stiffness_product(a, b)
        real(dp), intent(in) :: a(0:), b(0:)
        integer :: e, s

        s = ubound(a, 1)
        stiffness_product = 0.0_dp
        do e = 1, s
            stiffness_product = stiffness_product + (a(e) - a(e - 1)) * (b(e) - b(e - 1))
        end do
        stiffness_product = stiffness_product * real(s, dp)
    end function stiffness_product

end module energy_m
