!> Taking one step (step_driver_m's take_step): choose_step, try_step, judge (with
!> landing: where a contact event the step crossed lies, and whether the step is cut to
!> end there), accept and keep_level, undo_step. A submodule of step_driver_m, so that it
!> works on the driver's private state; only take_step is seen outside it.
submodule (step_driver_m) step_driver_trial_s
    use reals_m, only: equal
    use iso_fortran_env, only: error_unit
    use ieee_arithmetic, only: ieee_is_finite
    use state_m, only: advance_time, land_on
    use events_m, only: EVENT_ONSET, EVENT_RELEASE, event_landing, MAX_LANDINGS, LANDING_FRACTION, LINEAR_CUT_MIN, &
                        crossing_time
    use event_location_m, only: contact_state, gap_event_time, release_time
    use contact_law_m, only: contact_law_t
    use adaptive_mesh_m, only: FRONT_CFL
    implicit none

    !> One tried step of take_step: its size, where it started and ends, the stepper's result,
    !> the contact state it reached, its estimate and the contact event it crossed.
    type :: trial_t
        real(dp) :: dt = 0.0_dp             !< its size
        real(dp) :: target = 0.0_dp         !< t_stop or the next snapshot time
        logical :: lands = .false.          !< it ends on target
        logical :: at_snapshot = .false.    !< it ends on a snapshot time
        real(dp) :: t_before = 0.0_dp       !< the state's t before it
        real(dp) :: dt_last = 0.0_dp        !< the state's dt_last before it
        real(dp) :: gap_start = 0.0_dp      !< u(1) - g before it
        type(step_result_t) :: result       !< the stepper's (advance)
        real(dp) :: gap_end = 0.0_dp        !< the gap at its end (contact_state)
        logical :: contact = .false.        !< the contact state at its end
        logical :: flipped = .false.        !< it changed the contact state
        real(dp) :: est = 0.0_dp            !< its error estimate
        real(dp) :: err = -1.0_dp           !< est / (tol S); negative: no estimate
        integer :: landings = 0             !< retries cut to end at a located event
        real(dp) :: dt_land = 0.0_dp        !< the next such retry's size
        real(dp) :: t_event = 0.0_dp        !< its contact event's time
        !> the end of the last step that changed the contact state (landing)
        real(dp) :: t_bound = 0.0_dp
    end type trial_t

contains

    !> take_step (step_driver_m's interface names its arguments): choose a step, try it and
    !> judge it until one is accepted.
    module procedure driver_take_step
        type(trial_t) :: trial
        logical :: retry

        failure = ''
        do
            call choose_step(self, state, t_stop, trial, t_snapshot)
            call try_step(self, state, stepper, trial, failure)
            at_snapshot = trial%at_snapshot
            if (.not. trial%result%ok) exit   ! failure says why
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
    !> failure: the solve failed.
    subroutine try_step(self, state, stepper, trial, failure)
        class(step_driver_t), intent(inout) :: self
        type(state_t), intent(inout) :: state
        type(stepper_t), intent(inout) :: stepper
        type(trial_t), intent(inout) :: trial
        character(len=*), intent(inout) :: failure

        trial%t_before = state%t
        trial%dt_last = state%dt_last
        trial%gap_start = state%u(state%s) - stepper%law%g
        ! without its level (undo_step takes it from the estimator)
        if (self%adaptive) call copy_state(state, self%saved, level=.false.)
        call stepper%advance(state, trial%result, trial%dt)
        if (.not. trial%result%ok) then
            failure = self%step_label(state%step + 1, advance_time(state, trial%dt), &
                                      trim(trial%result%message))
            return
        end if
        call contact_state(stepper%law, state, trial%result, trial%contact, trial%gap_end)
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
        logical :: cut

        retry = .true.
        if (self%estimator%ready() .and. .not. trial%flipped) then
            trial%est = self%estimator%estimate(self%model, state%u, state%w, trial%dt, state%mesh)
            trial%err = self%control%ratio(trial%est)
        end if
        if (trial%flipped .or. (trial%landings > 0 .and. trial%landings < MAX_LANDINGS)) then
            call landing(self, state, stepper%law, trial, cut)
            if (cut .and. trial%landings < MAX_LANDINGS) then
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
        if (trial%err > 1.0_dp .and. .not. self%warned_forced) then
            call warn_forced(state%t, self%dt_min)
            self%warned_forced = .true.
        end if
    end subroutine judge

    !> A tried adaptive step that changed the contact state (flipped), or a step cut to end at
    !> an event that did not (the event is later): locate the event (t_event; a Signorini
    !> release: release_time, else gap_event_time) and say whether the step is retried to end
    !> there (cut, of size dt_land; events_m's event_landing). t_bound: the end of the last
    !> flipped step, beyond which the event is not sought.
    subroutine landing(self, state, law, trial, cut)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        class(contact_law_t), intent(in) :: law
        type(trial_t), intent(inout) :: trial
        logical, intent(out) :: cut
        real(dp) :: t_lo
        logical :: found

        associate (t_before => trial%t_before, dt => trial%dt, flipped => trial%flipped, &
                   t_bound => trial%t_bound, dt_land => trial%dt_land, t_event => trial%t_event)
            if (flipped) then
                t_bound = t_before + dt
                t_lo = t_before
            else
                t_lo = t_before + dt
            end if
            if (self%in_contact .and. law%is_constraint()) then
                call release_time(self%estimator, self%model%alpha, state, t_before, dt, .not. flipped, t_lo, &
                                  t_bound, t_event, found)
            else
                t_event = gap_event_time(self%estimator, t_before, dt, trial%gap_start, trial%gap_end, &
                                         trial%result%trial_gap, .not. self%in_contact, law%g, t_lo, t_bound, found)
            end if
            if (flipped) then
                call event_landing(t_before, dt, t_event, self%dt_min, cut, dt_land)
                ! located by the straight line only (Euler, or right after an event): no cut of
                ! less than LINEAR_CUT_MIN of the step, which a slow (tangential) crossing would
                ! repeat step after step
                if (.not. found) cut = cut .and. dt_land >= LINEAR_CUT_MIN * dt
            else
                ! the cut step ended short of the event: cut again at the event its end locates
                call event_landing(t_before, t_bound - t_before, t_event, self%dt_min, cut, dt_land)
                cut = cut .and. found .and. &
                      t_event - (t_before + dt) > max(LANDING_FRACTION * dt, self%dt_min)
            end if
        end associate
    end subroutine landing

    !> The tried step is accepted: its contact event into the log, its level into the
    !> estimator and its estimate to the controller (keep_level), its energy to the monitor.
    subroutine accept(self, state, monitor, trial, failure)
        class(step_driver_t), intent(inout) :: self
        type(state_t), intent(inout) :: state
        type(energy_monitor_t), intent(inout) :: monitor
        type(trial_t), intent(in) :: trial
        character(len=*), intent(inout) :: failure

        if (trial%lands .and. self%adaptive) call land_on(state, trial%target)
        if (trial%flipped) then
            call self%events%add(trial%t_event, merge(EVENT_ONSET, EVENT_RELEASE, trial%contact))
            if (self%adaptive) call self%estimator%reset()
        end if
        self%in_contact = trial%contact
        call keep_level(self, state, trial)
        call monitor%observe(state, step_changed=.not. equal(trial%dt, trial%dt_last))
        if (.not. ieee_is_finite(monitor%current_energy())) then
            failure = self%step_label(state%step, state%t, 'the discrete energy is not finite')
            return
        end if
        if (self%adaptive) call self%control%observe_size(energy_norm(monitor%current_energy()))
    end subroutine accept

    !> The accepted level into the estimator (adaptive steps; fixed steps with dense output)
    !> and the step's estimate and size to the controller (adaptive steps).
    subroutine keep_level(self, state, trial)
        class(step_driver_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        type(trial_t), intent(in) :: trial

        if (.not. self%adaptive) then
            if (self%dense) call self%estimator%push(state%u, state%w, trial%dt)
            return
        end if
        call self%estimator%push(state%u, state%w, trial%dt)
        ! a step cut to end at an event, and the event's step, keep the proposal from before
        call self%control%accept(trial%dt, trial%est, trial%err, &
                                 shortened=trial%lands .or. trial%landings > 0 .or. trial%flipped)
    end subroutine keep_level

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

    !> Once per run: the error estimate exceeded the tolerance at the smallest step allowed.
    subroutine warn_forced(t, dt_min)
        real(dp), intent(in) :: t, dt_min

        write (error_unit, '(a,es11.4,a,es10.3,a)') 'rodcontact: warning: at t = ', t, &
            ' a step of dt_min = ', dt_min, ' exceeds time.error_tol and is accepted; lower time.dt_min ' // &
            '(the count is in the root attribute time_steps_at_dt_min)'
        flush (error_unit)
    end subroutine warn_forced

end submodule step_driver_trial_s
