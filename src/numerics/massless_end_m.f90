!> The contact node without mass (&contact mass = 'redistributed'): what a step does to its
!> displacement after the solve (the consistent mass's results stay bit for bit).
!>  - Signorini: an active multiplier puts the end on the obstacle, u^n(1) = g, exactly.
!>  - Midpoint: v^n(1) is the step's mean velocity Y_v(1) (no velocity of its own to extrapolate);
!>    with varpi = gamma1 = gamma2 = 0 the algebraic u(1), whose extrapolation carries an
!>    undamped alternating mode, is set to the node's equilibrium with its neighbour
!>    (contact_law_m's equilibrium), which only lowers E^n; with viscosity or coupling the
!>    extrapolated value is kept. Why: docs/scheme.md, "Mass redistribution at the contact node".
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
