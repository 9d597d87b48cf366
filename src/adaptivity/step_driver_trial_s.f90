!> Taking one step (step_driver_m's take_step): choose_step, try_step, judge (with landing:
!> where a contact event the step crossed lies, and whether the step is cut to end there),
!> accept, undo_step. A submodule of step_driver_m, so that it works on the driver's
!> private state; only take_step is seen outside it.
submodule (step_driver_m) step_driver_trial_s
    use reals_m, only: equal
    use iso_fortran_env, only: error_unit
    use ieee_arithmetic, only: ieee_is_finite
    use state_m, only: advance_time, land_on
    use events_m, only: EVENT_ONSET, EVENT_RELEASE, event_landing, MAX_LANDINGS, LANDING_FRACTION, LINEAR_CUT_MIN, &
                        crossing_time
    use dense_output_m, only: interpolant_root
    use adaptive_mesh_m, only: FRONT_CFL
    implicit none

    !> One tried step of take_step.
    type :: trial_t
        real(dp) :: dt = 0.0_dp             !< its size
        real(dp) :: target = 0.0_dp         !< t_stop or the next snapshot time
        logical :: lands = .false.          !< it ends on target
        logical :: at_snapshot = .false.    !< it ends on a snapshot time
        real(dp) :: t_before = 0.0_dp       !< the state's t before it
        real(dp) :: dt_last = 0.0_dp        !< the state's dt_last before it
        real(dp) :: gap_start = 0.0_dp      !< u(1) - g before it
        type(step_result_t) :: result       !< the stepper's (advance)
        real(dp) :: gap_end = 0.0_dp        !< the gap at its end (try_step)
        logical :: contact = .false.        !< the contact state at its end
        logical :: flipped = .false.        !< it changed the contact state
        real(dp) :: est = 0.0_dp            !< its error estimate
        real(dp) :: err = -1.0_dp           !< est / (tol S); negative: no estimate
        integer :: landings = 0             !< retries cut to end at a located event
        logical :: cut = .false.            !< it is retried so (landing)
        real(dp) :: dt_land = 0.0_dp        !< the next such retry's size
        real(dp) :: t_event = 0.0_dp        !< its contact event's time
        !> the end of the last step that changed the contact state (landing)
        real(dp) :: t_bound = 0.0_dp
    end type trial_t

contains

    !> take_step: choose a step, try it and judge it until one is accepted (step_driver_m).
    module procedure driver_take_step
        type(trial_t) :: trial
        logical :: retry

        failure = ''
        do
            call choose_step(self, state, t_stop, trial, t_snapshot)
            call try_step(self, state, stepper, trial)
            at_snapshot = trial%at_snapshot
            if (.not. trial%result%ok) then
                failure = self%step_label(state%step + 1, advance_time(state, trial%dt), &
                                          trim(trial%result%message))
                exit
            end if
            ! fixed steps compute no estimate (the run's error: &output error_estimate)
            if (.not. self%adaptive) exit
            call judge(self, state, stepper, trial, retry)
            if (.not. retry) exit
        end do
        result = trial%result
        if (result%ok) call accept(self, state, monitor, trial, failure)
    end procedure driver_take_step

    !> The next step (trial%dt): &time dt or the controller's proposal (at most the scheme's
    !> step-ratio bound times the last step; on an adaptive mesh at most FRONT_CFL of its
    !> smallest elements for the fastest front), shortened to end on the next snapshot time
    !> or t_stop (target; lands). Adaptive steps that would leave less than a step to the
    !> target take half the distance instead, so no tiny step follows. The retry of a step
    !> that changed the contact state (landings > 0) ends at the located event (dt_land).
    subroutine choose_step(self, state, t_stop, trial, t_snapshot)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: t_stop
        type(trial_t), intent(inout) :: trial
        real(dp), intent(in), optional :: t_snapshot
        real(dp) :: remaining, slack, dt

        if (self%adaptive) then
            dt = self%control%proposal(state%dt_last)
            dt = min(max(dt, self%dt_min), self%dt_max)
            if (self%v_front > 0.0_dp) &
                dt = max(min(dt, FRONT_CFL * minval(state%mesh%h) / self%v_front), self%dt_min)
        else
            dt = self%dt
        end if
        slack = 1.0e-9_dp * dt
        trial%target = t_stop
        trial%at_snapshot = .false.
        if (present(t_snapshot)) then
            ! a snapshot time that is t_stop to round-off is the target (not t_stop): so
            ! a run to t_stop takes the steps a longer run takes up to there
            trial%at_snapshot = t_snapshot <= t_stop + slack
            if (trial%at_snapshot) trial%target = t_snapshot
        end if
        remaining = trial%target - state%t
        trial%lands = dt >= remaining - slack
        if (trial%lands) then
            if (self%adaptive .or. dt > remaining + slack) dt = remaining
        else if (self%adaptive .and. dt > 0.5_dp * remaining) then
            dt = 0.5_dp * remaining
        end if
        trial%dt = dt
        trial%at_snapshot = trial%at_snapshot .and. trial%lands
        if (trial%landings > 0) then
            trial%dt = trial%dt_land
            trial%lands = .false.
            trial%at_snapshot = .false.
        end if
    end subroutine choose_step

    !> Try the step of trial%dt from state (adaptive steps: the state saved before it):
    !> where it started, the contact state it reached and (flipped) the time of its event;
    !> trial%result: whether the solve failed.
    subroutine try_step(self, state, stepper, trial)
        class(step_driver_t), intent(inout) :: self
        type(state_t), intent(inout) :: state
        type(stepper_t), intent(inout) :: stepper
        type(trial_t), intent(inout) :: trial

        trial%t_before = state%t
        trial%dt_last = state%dt_last
        trial%gap_start = state%u(state%s) - stepper%law%g
        ! without its level (undo_step takes it from the estimator)
        if (self%adaptive) call copy_state(state, self%saved, level=.false.)
        call stepper%advance(state, trial%result, trial%dt)
        if (.not. trial%result%ok) return
        ! the contact state as events count it: penalty, u^n(1) > g (the end position; the
        ! midpoint rule's force may act a step longer); Signorini, an active multiplier. The
        ! gap the crossing time is interpolated to: u^n(1) - g, or Signorini's trial gap (its
        ! u^n(1) stops at g)
        if (stepper%law%is_constraint()) then
            trial%contact = trial%result%in_contact
            trial%gap_end = trial%result%trial_gap
        else
            trial%gap_end = state%u(state%s) - stepper%law%g
            trial%contact = trial%gap_end > 0.0_dp
        end if
        trial%flipped = trial%contact .neqv. self%in_contact
        if (trial%flipped) &   ! the straight line's (adaptive steps: landing)
            trial%t_event = crossing_time(trial%t_before, trial%dt, trial%gap_start, trial%gap_end)
        trial%est = 0.0_dp
        trial%err = -1.0_dp
    end subroutine try_step

    !> Judge a tried adaptive step: its estimate (none across a contact event); a contact
    !> event it crossed located (landing), the step taken back to end there (retry, at most
    !> MAX_LANDINGS times); a step whose estimate exceeds the tolerance taken back to be
    !> retried smaller (retry), unless at dt_min (then accepted, counted as forced).
    subroutine judge(self, state, stepper, trial, retry)
        class(step_driver_t), intent(inout) :: self
        type(state_t), intent(inout) :: state
        type(stepper_t), intent(inout) :: stepper
        type(trial_t), intent(inout) :: trial
        logical, intent(out) :: retry

        retry = .true.
        if (self%estimator%ready() .and. .not. trial%flipped) then
            trial%est = self%estimator%estimate(stepper%model, state%u, state%w, trial%dt, state%mesh)
            trial%err = self%control%ratio(trial%est)
        end if
        if (trial%flipped .or. (trial%landings > 0 .and. trial%landings < MAX_LANDINGS)) then
            call landing(self, state, stepper, trial)
            if (trial%cut .and. trial%landings < MAX_LANDINGS) then
                call undo_step(self, stepper, trial%result, state)
                trial%landings = trial%landings + 1
                return
            end if
        end if
        if (trial%err > 1.0_dp .and. trial%dt > self%dt_min) then
            call undo_step(self, stepper, trial%result, state)
            call self%control%reject(trial%dt, trial%err)
            trial%landings = 0
            return
        end if
        retry = .false.
        if (trial%err > 1.0_dp .and. .not. self%warned_forced) then   ! once per run
            write (error_unit, '(a,es11.4,a,es10.3,a)') 'rodcontact: warning: at t = ', state%t, &
                ' a step of dt_min = ', self%dt_min, &
                ' exceeds time.error_tol and is accepted; lower time.dt_min ' // &
                '(the count is in the root attribute time_steps_at_dt_min)'
            flush (error_unit)
            self%warned_forced = .true.
        end if
    end subroutine judge

    !> A tried adaptive step that changed the contact state (flipped), or a step cut to end at
    !> an event that did not (the event is later): locate the event (t_event; a Signorini
    !> release: release_time, else gap_event_time) and say whether the step is retried to end
    !> there (cut, of size dt_land; events_m's event_landing). t_bound: the end of the last
    !> flipped step, beyond which the event is not sought.
    subroutine landing(self, state, stepper, trial)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        type(stepper_t), intent(in) :: stepper
        type(trial_t), intent(inout) :: trial
        real(dp) :: t_lo
        logical :: found

        associate (t_before => trial%t_before, dt => trial%dt, flipped => trial%flipped, &
                   cut => trial%cut, t_bound => trial%t_bound, dt_land => trial%dt_land, &
                   t_event => trial%t_event)
            if (flipped) then
                t_bound = t_before + dt
                t_lo = t_before
            else
                t_lo = t_before + dt
            end if
            if (self%in_contact .and. stepper%law%is_constraint()) then
                t_event = release_time(self, state, stepper%model%alpha, trial, t_lo, found)
            else
                t_event = gap_event_time(self, trial, stepper%law%g, t_lo, found)
            end if
            if (flipped) then
                call event_landing(t_before, dt, t_event, self%dt_min, cut, dt_land)
                ! located by the straight line only (Euler, or right after an event)
                if (.not. found) cut = cut .and. dt_land >= LINEAR_CUT_MIN * dt
            else
                ! the cut step ended short of the event: cut again at the event its end locates
                call event_landing(t_before, t_bound - t_before, t_event, self%dt_min, cut, dt_land)
                cut = cut .and. found .and. &
                      t_event - (t_before + dt) > max(LANDING_FRACTION * dt, self%dt_min)
            end if
        end associate
    end subroutine landing

    !> The time of the contact event in the tried step, whose gap went from gap_start to
    !> gap_end: with a scheme of order 2 and a level before the step since the last event,
    !> the root in [t_lo, t_bound] (found) of the gap's quadratic interpolant (dense_output_m)
    !> through the two levels before the step and its end: for an onset the trial gap (the
    !> free motion, which the solution follows up to the onset; the stiff penalty bends u^n(1)
    !> away from it), for a release u^n(1) - g (gap_end). Otherwise (or with no root there)
    !> the straight line's (crossing_time).
    real(dp) function gap_event_time(self, trial, g, t_lo, found) result(t_event)
        class(step_driver_t), intent(in) :: self
        type(trial_t), intent(in) :: trial
        real(dp), intent(in) :: g, t_lo
        logical, intent(out) :: found
        real(dp) :: times(3), gaps(3)

        found = .false.
        associate (e => self%estimator, t_before => trial%t_before)
            if (e%order >= 2 .and. e%n_levels >= 2) then
                times = [t_before + trial%dt, t_before, t_before - e%step(1)]
                gaps = [merge(trial%result%trial_gap, trial%gap_end, .not. self%in_contact), trial%gap_start, &
                        e%levels(ubound(e%levels, 1), 0, e%slot(2)) - g]
                call interpolant_root(times, gaps, t_lo, trial%t_bound, t_event, found)
            end if
            if (.not. found) t_event = crossing_time(t_before, trial%dt, trial%gap_start, trial%gap_end)
        end associate
    end function gap_event_time

    !> The time of a Signorini release in the tried step: the root in [t_lo, t_bound] (found;
    !> else t_event = t_bound) of the polynomial (dense_output_m) through the contact force
    !> lambda = -sigma = alpha (u_{s-1} - u_s) / h_s (the massless contact node's equilibrium
    !> with its neighbour under &contact mass = 'redistributed', the last element's stress
    !> otherwise) at the levels since the last event, at most p+1 (p the scheme's order), with
    !> the step's end unless it flipped; not found with fewer than two levels.
    real(dp) function release_time(self, state, alpha, trial, t_lo, found) result(t_event)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: alpha, t_lo
        type(trial_t), intent(in) :: trial
        logical, intent(out) :: found
        real(dp) :: times(MAX_LEVELS + 1), force(MAX_LEVELS + 1), to_node
        integer :: j, k, n, slot, s

        t_event = trial%t_bound
        found = .false.
        s = state%s
        to_node = alpha / state%mesh%h(s)
        k = 0
        if (.not. trial%flipped) then
            k = 1
            times(1) = trial%t_before + trial%dt
            force(1) = to_node * (state%u(s - 1) - state%u(s))
        end if
        associate (e => self%estimator)
            n = min(e%n_levels, e%order + 1 - k)
            if (k + n < 2) return
            times(k + 1:k + n) = e%times(trial%t_before, n)
            do j = 1, n
                slot = e%slot(j)
                force(k + j) = to_node * (e%levels(s - 1, 0, slot) - e%levels(s, 0, slot))
            end do
        end associate
        call interpolant_root(times(1:k + n), force(1:k + n), t_lo, trial%t_bound, t_event, found)
    end function release_time

    !> The tried step is accepted: its contact event into the log; its level into the
    !> estimator (adaptive steps; fixed steps with dense output), its estimate and size to
    !> the controller (adaptive steps); its energy to the monitor.
    subroutine accept(self, state, monitor, trial, failure)
        class(step_driver_t), intent(inout) :: self
        type(state_t), intent(inout) :: state
        type(energy_monitor_t), intent(inout) :: monitor
        type(trial_t), intent(in) :: trial
        character(len=*), intent(inout) :: failure

        if (trial%flipped) &
            call self%events%add(trial%t_event, merge(EVENT_ONSET, EVENT_RELEASE, trial%contact))
        self%in_contact = trial%contact
        if (self%adaptive) then
            if (trial%lands) call land_on(state, trial%target)
            if (trial%flipped) call self%estimator%reset()
            call self%estimator%push(state%u, state%w, trial%dt)
            ! a step cut to end at an event, and the event's step, keep the proposal from before
            call self%control%accept(trial%dt, trial%est, trial%err, &
                                     shortened=trial%lands .or. trial%landings > 0 .or. trial%flipped)
        else if (self%dense) then
            call self%estimator%push(state%u, state%w, trial%dt)
        end if
        call monitor%observe(state, step_changed=.not. equal(trial%dt, trial%dt_last))
        if (.not. ieee_is_finite(monitor%current_energy())) then
            failure = self%step_label(state%step, state%t, 'the discrete energy is not finite')
            return
        end if
        if (self%adaptive) call self%control%observe_size(energy_norm(monitor%current_energy()))
    end subroutine accept

    !> A rejected step: the state as before it, and the step's contact count taken back.
    subroutine undo_step(self, stepper, result, state)
        class(step_driver_t), intent(in) :: self
        type(stepper_t), intent(inout) :: stepper
        type(step_result_t), intent(in) :: result
        type(state_t), intent(inout) :: state

        call stepper%take_back(result)
        call copy_state(self%saved, state, level=.false.)
        associate (e => self%estimator, newest => self%estimator%slot(1))   ! the level it started from
            state%u = e%levels(:, 0, newest)
            state%w = e%levels(:, 1:, newest)
        end associate
    end subroutine undo_step

end submodule step_driver_trial_s
