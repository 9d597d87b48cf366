!> The contact node without mass (&contact mass = 'redistributed'; docs/scheme.md, "Mass
!> redistribution at the contact node"): what a step does to its displacement after the solve.
!>  - Signorini: an active multiplier puts the end on the obstacle, u^n(1) = g, exactly (not to
!>    round-off); the consistent mass keeps its results bit for bit.
!>  - The midpoint rule: the node has no velocity of its own to extrapolate, so v^n(1) is the step's
!>    mean velocity Y_v(1) = (u^n(1) - u^{n-1}(1))/dt; and when no viscosity and no coupling act on
!>    the node (varpi = gamma1 = gamma2 = 0) its algebraic u(1), whose extrapolation
!>    2 u^{n-1/2}(1) - u^{n-1}(1) carries an undamped alternating mode, is set to the node's
!>    equilibrium at t_n with its neighbour, alpha (u(1) - u_{s-1})/h_s + lambda(u(1)) = 0
!>    (contact_law_m's equilibrium). That value minimises the part of E^n that depends on u(1)
!>    (the last element's strain energy and the penalty term), so E^n only falls. With
!>    viscosity or coupling the node's equilibrium has other terms, and the extrapolated value is kept.
module massless_end_m
    use kinds_m, only: dp
    use reals_m, only: is_zero
    use config_m, only: model_t
    use contact_law_m, only: contact_law_t
    implicit none
    private
    public :: settle_end

contains

    !> After a step with the step's model: u(0:s) the new displacement; in_contact: the step's
    !> contact force is positive; h_last: the size of the element at x = 1. The midpoint rule also
    !> passes v(0:s), the new velocity, and y_end, its half level's velocity at x = 1.
    pure subroutine settle_end(model, law, h_last, in_contact, u, v, y_end)
        type(model_t), intent(in) :: model
        class(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: h_last
        logical, intent(in) :: in_contact
        real(dp), intent(inout) :: u(0:)
        real(dp), intent(inout), optional :: v(0:)
        real(dp), intent(in), optional :: y_end
        integer :: s

        if (.not. model%mass_end_moved) return
        s = ubound(u, 1)
        if (law%is_constraint() .and. in_contact) u(s) = law%g
        if (.not. (present(v) .and. present(y_end))) return
        v(s) = y_end
        if (.not. (model%rho > 0.0_dp .and. is_zero(model%varpi) .and. is_zero(model%gamma1) .and. &
                   is_zero(model%gamma2))) return
        u(s) = law%equilibrium(u(s - 1), model%alpha / h_last)
    end subroutine settle_end

end module massless_end_m
