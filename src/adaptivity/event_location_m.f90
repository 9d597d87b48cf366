!> Where in a step a contact event lies: the contact state a step reached, the time its
!> gap crosses zero and the time a Signorini release happens, from the scheme's
!> interpolant through the levels since the last event (dense_output_m) where there are
!> enough of them, else from the straight line (events_m's crossing_time). The step driver
!> (step_driver_m) cuts steps at these times.
module event_location_m
    use kinds_m, only: dp
    use state_m, only: state_t
    use contact_law_m, only: contact_law_t
    use stepper_m, only: step_result_t
    use events_m, only: crossing_time
    use error_estimator_m, only: error_estimator_t, MAX_LEVELS
    use dense_output_m, only: interpolant_root
    implicit none
    private
    public :: contact_state, gap_event_time, release_time

contains

    !> The contact state after a step, as events are counted: penalty, u^n(1) > g (the end
    !> position; the midpoint rule's force may act a step longer); Signorini, an active
    !> multiplier. gap: the gap at the step's end the crossing time is interpolated to,
    !> u^n(1) - g (penalty) or the trial gap (Signorini, whose u^n(1) stops at g).
    subroutine contact_state(law, state, result, in_contact, gap)
        class(contact_law_t), intent(in) :: law
        type(state_t), intent(in) :: state
        type(step_result_t), intent(in) :: result
        logical, intent(out) :: in_contact
        real(dp), intent(out) :: gap

        if (law%is_constraint()) then
            in_contact = result%in_contact
            gap = result%trial_gap
        else
            gap = state%u(state%s) - law%g
            in_contact = gap > 0.0_dp
        end if
    end subroutine contact_state

    !> The time of the contact event in the adaptive step from t_before of size dt whose gap
    !> went from gap_start to gap_end: with a scheme of order 2 and a level before t_before
    !> since the last event, the root in [t_lo, t_hi] (found) of the gap's quadratic
    !> interpolant (dense_output_m) through the two levels before the step and its end: for an
    !> onset the trial gap (the free motion, which the solution follows up to the onset; the
    !> stiff penalty bends u^n(1) away from it), for a release u^n(1) - g (gap_end). Otherwise
    !> (or with no root there) the straight line's (events_m's crossing_time).
    real(dp) function gap_event_time(estimator, t_before, dt, gap_start, gap_end, trial_gap, onset, g, &
                                     t_lo, t_hi, found) result(t_event)
        type(error_estimator_t), intent(in) :: estimator
        real(dp), intent(in) :: t_before, dt, gap_start, gap_end, trial_gap, g, t_lo, t_hi
        logical, intent(in) :: onset
        logical, intent(out) :: found
        real(dp) :: times(3), gaps(3)

        found = .false.
        if (estimator%order >= 2 .and. estimator%n_levels >= 2) then
            associate (e => estimator, before => estimator%slot(2))   ! the level before t_before
                times = [t_before + dt, t_before, t_before - e%step(1)]
                gaps = [merge(trial_gap, gap_end, onset), gap_start, &
                        e%levels(ubound(e%levels, 1), 0, before) - g]
            end associate
            call interpolant_root(times, gaps, t_lo, t_hi, t_event, found)
        end if
        if (.not. found) t_event = crossing_time(t_before, dt, gap_start, gap_end)
    end function gap_event_time

    !> The time of a Signorini release (adaptive steps): the contact force lambda = -sigma at the
    !> contact node from the node's equilibrium with its neighbour, alpha (u_{s-1} - u_s) / h_s
    !> (exact for the massless contact node of &contact mass = 'redistributed', the last
    !> element's stress otherwise), at the levels since the last event (t_before the latest)
    !> and, with_end, at the state's level at t_before + dt too; the root in [t_lo, t_hi] of the
    !> polynomial through them (dense_output_m), at most p+1 of them (p the scheme's order).
    !> found = .false. (t_event = t_hi): no root there, or fewer than two levels.
    subroutine release_time(estimator, alpha, state, t_before, dt, with_end, t_lo, t_hi, t_event, &
                            found)
        type(error_estimator_t), intent(in) :: estimator
        real(dp), intent(in) :: alpha    !< the model's alpha
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: t_before, dt, t_lo, t_hi
        logical, intent(in) :: with_end
        real(dp), intent(out) :: t_event
        logical, intent(out) :: found
        real(dp) :: times(MAX_LEVELS + 1), force(MAX_LEVELS + 1), to_node
        integer :: j, k, n, slot, s

        t_event = t_hi
        found = .false.
        s = state%s
        to_node = alpha / state%mesh%h(s)
        k = 0
        if (with_end) then
            k = 1
            times(1) = t_before + dt
            force(1) = to_node * (state%u(s - 1) - state%u(s))
        end if
        associate (e => estimator)
            n = min(e%n_levels, e%order + 1 - k)
            if (k + n < 2) return
            times(k + 1:k + n) = e%times(t_before, n)
            do j = 1, n
                slot = e%slot(j)
                force(k + j) = to_node * (e%levels(s - 1, 0, slot) - e%levels(s, 0, slot))
            end do
        end associate
        call interpolant_root(times(1:k + n), force(1:k + n), t_lo, t_hi, t_event, found)
    end subroutine release_time

end module event_location_m
