!> The step driver: takes one accepted step of the time loop, trying and rejecting steps
!> as the step control asks.
!>
!> The step is &time dt (fixed) or the size step_control_m's controller proposes
!> (adaptive). Adaptive steps are tried: a step whose local error estimate exceeds the
!> tolerance is rejected (the state restored) and retried smaller. A contact event is
!> located and stepped over (events_m's event_landing): a step that changes the contact
!> state in its interior is taken back and retried to end at the located event, and the
!> step after it, which starts there, changes the contact state at its start and is
!> accepted; the controller's proposal is kept across the event (no shrinking of dt
!> towards the event). Steps are shortened to land on the snapshot times (&output snapshot_dt)
!> and on the end of the run. An accepted step adds its contact event to the event log,
!> (adaptive steps) its level to the error estimator and its estimate to the controller's
!> error sum, and its energy to the energy monitor. Fixed steps compute no estimate.
module step_driver_m
    use kinds_m, only: dp
    use reals_m, only: equal
    use iso_fortran_env, only: error_unit
    use ieee_arithmetic, only: ieee_is_finite
    use config_m, only: config_t, model_t, with_contact_mass
    use state_m, only: state_t, advance_time, land_on, copy_state, keep_copy
    use contact_law_m, only: contact_law_t
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: energy_monitor_t, energy_and_parts
    use fields_m, only: N_ENERGY_PARTS
    use checkpoint_m, only: checkpoint_t
    use events_m, only: event_log_t, EVENT_ONSET, EVENT_RELEASE, crossing_time, event_landing, MAX_LANDINGS, LANDING_FRACTION, &
                        LINEAR_CUT_MIN
    use step_control_m, only: error_estimator_t, step_controller_t, energy_norm, MAX_LEVELS
    use dense_output_m, only: lagrange_weights, interpolant_root
    use adaptive_mesh_m, only: adaptive_mesh_t, FRONT_CFL, front_speed
    use remesh_m, only: remesh
    implicit none
    private
    public :: step_driver_t, step_failure

    type :: step_driver_t
        private
        logical :: adaptive = .false.          !< &time adaptive
        logical :: mesh_adaptive = .false.     !< &mesh adaptive
        !> dense output (&output series_dt, snapshot_land = .false.): fixed steps keep their
        !> levels in the estimator too (dense_level, dense_series)
        logical :: dense = .false.
        real(dp) :: dt = 0.0_dp, dt_min = 0.0_dp, dt_max = 0.0_dp   !< &time dt, dt_min, dt_max
        real(dp) :: v_front = 0.0_dp           !< adaptive_mesh_m's front_speed
        type(model_t) :: model                 !< for the error estimate's energy norm
        type(error_estimator_t) :: estimator
        type(step_controller_t) :: control
        type(event_log_t) :: events
        type(state_t) :: saved                 !< the state before a tried step (adaptive)
        !> the state's level (u, w) is the estimator's newest level, bit for bit (pushed at the
        !> end of the step that reached it, unchanged since): a step tried from it saves the
        !> rest of the state only, and a step taken back restores the level from the estimator
        logical :: level_kept = .false.
        !> the state saved before the last tried step has no level of its own (level_kept):
        !> the level before that step is the estimator's newest (before the step's push)
        logical :: saved_without_level = .false.
        logical :: in_contact = .false.        !< the contact state after the last accepted step
        logical :: warned_forced = .false.
        !> dense output: E of the j-th most recent level (dense_series), for the step energies_step
        real(dp) :: level_energy(MAX_LEVELS) = 0.0_dp
        real(dp) :: level_parts(N_ENERGY_PARTS, MAX_LEVELS) = 0.0_dp   !< their parts (energy_parts)
        integer :: energies_step = -1
    contains
        procedure :: init => driver_init
        procedure :: take_step => driver_take_step
        procedure :: remesh => driver_remesh
        procedure :: events_log => driver_events_log
        procedure :: controller => driver_controller
        procedure :: save_checkpoint => driver_save_checkpoint
        procedure :: restore_checkpoint => driver_restore_checkpoint
        procedure :: dense_level => driver_dense_level
        procedure :: dense_series => driver_dense_series
        procedure, private :: event_time => driver_event_time
        procedure, private :: release_time => driver_release_time
        procedure, private :: landing => driver_landing
        procedure, private :: choose_step => driver_choose_step
        procedure, private :: undo_step => driver_undo_step
    end type step_driver_t

contains

    !> A driver for the run cfg starting from state; the stepper and the energy monitor are
    !> set up on that state.
    subroutine driver_init(self, cfg, state, stepper, monitor)
        class(step_driver_t), intent(out) :: self
        type(config_t), intent(in) :: cfg
        type(state_t), intent(in) :: state
        type(stepper_t), intent(in) :: stepper
        type(energy_monitor_t), intent(in) :: monitor

        self%adaptive = cfg%time%adaptive
        self%mesh_adaptive = cfg%mesh%adaptive
        self%dense = cfg%output%series_dt > 0.0_dp .or. (cfg%output%snapshot_dt > 0.0_dp .and. &
                                                         .not. cfg%output%snapshot_land)
        self%dt = cfg%time%dt
        self%dt_min = cfg%time%dt_min
        self%dt_max = cfg%time%dt_max
        self%v_front = front_speed(cfg%model)
        self%model = with_contact_mass(cfg%model, cfg%contact%mass)
        call self%estimator%init(stepper%scheme, state%s)
        call self%control%init(cfg%time%error_tol, cfg%time%dt_min, cfg%time%dt_max, stepper%scheme, &
                               cfg%time%dt, scale=energy_norm(monitor%current_energy()))
        call self%estimator%push(state%u, state%w, 0.0_dp)
        self%in_contact = stepper%law%penetration(state%u(state%s)) > 0.0_dp
    end subroutine driver_init

    !> Continue from a checkpoint: state (restored, on its mesh) is the level the run
    !> continues from; the step control and the events are the checkpoint's.
    subroutine driver_restore_checkpoint(self, ckpt, state, stepper)
        class(step_driver_t), intent(inout) :: self
        type(checkpoint_t), intent(in) :: ckpt
        type(state_t), intent(in) :: state
        type(stepper_t), intent(in) :: stepper

        if (self%mesh_adaptive) call self%estimator%resize(state%s)
        call self%estimator%reset()
        call self%estimator%push(state%u, state%w, state%dt_last)
        self%level_kept = .false.
        self%in_contact = stepper%law%penetration(state%u(state%s)) > 0.0_dp
        call self%control%restore_checkpoint(ckpt)
        call self%estimator%restore_checkpoint(ckpt)
        call ckpt%get('step_driver/in_contact', self%in_contact)
        call self%events%restore_checkpoint(ckpt)
    end subroutine driver_restore_checkpoint

    !> The step control, the contact state and the events into a checkpoint.
    subroutine driver_save_checkpoint(self, ckpt)
        class(step_driver_t), intent(in) :: self
        type(checkpoint_t), intent(inout) :: ckpt

        call self%control%save_checkpoint(ckpt)
        call self%estimator%save_checkpoint(ckpt)
        call ckpt%put('step_driver/in_contact', self%in_contact)
        call self%events%save_checkpoint(ckpt)
    end subroutine driver_save_checkpoint

    !> The contact events so far.
    function driver_events_log(self) result(events)
        class(step_driver_t), intent(in) :: self
        type(event_log_t) :: events

        events = self%events
    end function driver_events_log

    !> The step controller (its counts and the run's time error).
    function driver_controller(self) result(control)
        class(step_driver_t), intent(in) :: self
        type(step_controller_t) :: control

        control = self%control
    end function driver_controller

    !> Take one accepted step from state towards t_stop (landing on it, or on t_snapshot
    !> when that comes first; at_snapshot: the step ended there). On a numerical failure,
    !> failure says which step and why ('' otherwise); the state is then that of the
    !> failed step (a failed solve) or of the accepted step (a non-finite energy).
    subroutine driver_take_step(self, state, stepper, monitor, result, t_stop, at_snapshot, failure, t_snapshot)
        class(step_driver_t), intent(inout) :: self
        type(state_t), intent(inout) :: state
        type(stepper_t), intent(inout) :: stepper
        type(energy_monitor_t), intent(inout) :: monitor
        type(step_result_t), intent(inout) :: result
        real(dp), intent(in) :: t_stop
        logical, intent(out) :: at_snapshot
        character(len=*), intent(out) :: failure
        real(dp), intent(in), optional :: t_snapshot   !< the next snapshot time (absent: none)
        real(dp) :: dt_try, target, t_before, gap_start, gap_end, est, err, saved_dt_last, dt_land, t_event, t_bound
        logical :: lands, contact_now, flipped, landed, cut
        integer :: landings

        failure = ''
        landings = 0
        landed = .false.
        do
            call self%choose_step(state, t_stop, dt_try, target, lands, at_snapshot, t_snapshot)
            if (landings > 0) then
                ! the retry of a step that changed the contact state: end at the located event
                dt_try = dt_land
                lands = .false.
                at_snapshot = .false.
            end if
            t_before = state%t
            saved_dt_last = state%dt_last
            gap_start = state%u(state%s) - stepper%law%g
            if (self%adaptive) then
                self%saved_without_level = self%level_kept
                call copy_state(state, self%saved, level=.not. self%saved_without_level)
            end if
            call stepper%advance(state, result, dt_try)
            if (.not. result%ok) then
                failure = step_failure(state%step + 1, advance_time(state, dt_try), trim(result%message))
                return
            end if
            call contact_state(stepper%law, state, result, contact_now, gap_end)
            flipped = contact_now .neqv. self%in_contact
            est = 0.0_dp
            err = -1.0_dp
            ! fixed steps compute no estimate (the run's error: &output error_estimate)
            if (.not. self%adaptive) exit
            if (self%estimator%ready() .and. .not. flipped) then
                est = self%estimator%estimate(self%model, state%u, state%w, dt_try, state%mesh)
                err = self%control%ratio(est)
            end if
            if ((flipped .or. landings > 0) .and. landings < MAX_LANDINGS) then
                ! locate the event; in the step's interior, or beyond a cut step's end: retry to end there
                call self%landing(state, result, stepper%law, t_before, dt_try, gap_start, gap_end, flipped, t_bound, &
                                  cut, dt_land)
                if (cut) then
                    call self%undo_step(stepper, result, state)
                    landings = landings + 1
                    cycle
                end if
            end if
            if (err > 1.0_dp .and. dt_try > self%dt_min) then
                call self%undo_step(stepper, result, state)
                call self%control%reject(dt_try, err)
                landings = 0
                cycle
            end if
            if (err > 1.0_dp) then
                call self%control%count_forced()
                if (.not. self%warned_forced) call warn_forced(state%t, self%dt_min)
                self%warned_forced = .true.
            end if
            exit
        end do
        ! the step is accepted
        landed = landings > 0
        if (lands .and. self%adaptive) call land_on(state, target)
        if (flipped) then
            if (self%adaptive .and. self%in_contact .and. stepper%law%is_signorini()) then
                call self%release_time(state, t_before, dt_try, .false., t_before, t_before + dt_try, t_event, cut)
            else
                t_event = self%event_time(t_before, dt_try, gap_start, gap_end, result%trial_gap, contact_now, &
                                          stepper%law%g)
            end if
            call self%events%add(t_event, merge(EVENT_ONSET, EVENT_RELEASE, contact_now))
            if (self%adaptive) call self%estimator%reset()
        end if
        self%in_contact = contact_now
        if (self%dense .and. .not. self%adaptive) call self%estimator%push(state%u, state%w, dt_try)
        if (self%adaptive) then
            call self%estimator%push(state%u, state%w, dt_try)
            self%level_kept = .true.
            if (self%saved_without_level .and. self%estimator%n_levels < 2) then
                ! after an event the levels are forgotten: dense output takes the level before
                ! the step from the saved state (dense_weights), so it gets its level now
                associate (e => self%estimator, before => modulo(self%estimator%head - 2, MAX_LEVELS) + 1)
                    call keep_copy(e%levels(:, 0, before), e%levels(:, 1:, before), self%saved%u, self%saved%w, &
                                   'the saved state')
                end associate
                self%saved_without_level = .false.
            end if
            if (err >= 0.0_dp) call self%control%add_estimate(est)
            ! a step cut to end at an event, and the event's step, keep the proposal made before it
            call self%control%accept(dt_try, err, shortened=lands .or. landed .or. flipped)
        end if
        call monitor%observe(state, step_changed=.not. equal(dt_try, saved_dt_last))
        if (.not. ieee_is_finite(monitor%current_energy())) then
            failure = step_failure(state%step, state%t, 'the discrete energy is not finite')
            return
        end if
        if (self%adaptive) call self%control%observe_size(energy_norm(monitor%current_energy()))
    end subroutine driver_take_step

    !> The next step: &time dt or the controller's proposal (at most the scheme's step-ratio
    !> bound times the last step; on an adaptive mesh at most FRONT_CFL of its smallest elements for the
    !> fastest front), shortened to end on the next snapshot time or t_stop (target; lands).
    !> Adaptive steps that would leave less than a step to the target take half the
    !> distance instead, so no tiny step follows.
    subroutine driver_choose_step(self, state, t_stop, dt_try, target, lands, at_snapshot, t_snapshot)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: t_stop
        real(dp), intent(out) :: dt_try, target
        logical, intent(out) :: lands, at_snapshot
        real(dp), intent(in), optional :: t_snapshot
        real(dp) :: remaining, slack

        if (self%adaptive) then
            dt_try = self%control%proposal(state%dt_last)
            dt_try = min(max(dt_try, self%dt_min), self%dt_max)
            if (self%mesh_adaptive .and. self%v_front > 0.0_dp) &
                dt_try = max(min(dt_try, FRONT_CFL * minval(state%mesh%h) / self%v_front), self%dt_min)
            slack = 1.0e-9_dp * dt_try
        else
            dt_try = self%dt
            slack = 1.0e-9_dp * self%dt
        end if
        target = t_stop
        at_snapshot = .false.
        if (present(t_snapshot)) then
            ! a snapshot time that is t_stop to round-off is the target (not t_stop): so
            ! a run to t_stop takes the steps a longer run takes up to there
            if (t_snapshot <= target + slack) then
                target = t_snapshot
                at_snapshot = .true.
            end if
        end if
        remaining = target - state%t
        lands = dt_try >= remaining - slack
        if (lands) then
            if (self%adaptive .or. dt_try > remaining + slack) dt_try = remaining
        else if (self%adaptive .and. dt_try > 0.5_dp * remaining) then
            dt_try = 0.5_dp * remaining
        end if
        at_snapshot = at_snapshot .and. lands
    end subroutine driver_choose_step

    !> The time of the contact event in the step from t_before of size dt whose gap went from
    !> gap_start to gap_end: adaptive steps of a scheme of order 2, with a level before
    !> t_before since the last event, take the root of the quadratic interpolant of the gap
    !> (dense_output_m) through the two levels before the step and its end: for an onset
    !> (onset = .true.) the end's trial gap (no contact force in the step: the free motion,
    !> which the solution follows up to the onset; the stiff penalty bends u^n(1) away from
    !> it within the step), for a release u^n(1) - g (gap_end). Otherwise (and if that has no
    !> root in the step) the straight line's (events_m's crossing_time). Fixed steps keep the
    !> straight line (and their results).
    !> With t_lo, t_hi: the interpolant's root in [t_lo, t_hi] instead (found: there is one).
    real(dp) function driver_event_time(self, t_before, dt, gap_start, gap_end, trial_gap, onset, g, t_lo, t_hi, &
                                        found) result(t_event)
        class(step_driver_t), intent(in) :: self
        real(dp), intent(in) :: t_before, dt, gap_start, gap_end, trial_gap, g
        logical, intent(in) :: onset
        real(dp), intent(in), optional :: t_lo, t_hi
        logical, intent(out), optional :: found
        real(dp) :: times(3), gaps(3), lo, hi
        integer :: slot
        logical :: has_root

        t_event = crossing_time(t_before, dt, gap_start, gap_end)
        lo = t_before
        hi = t_before + dt
        if (present(t_lo)) lo = t_lo
        if (present(t_hi)) hi = t_hi
        if (present(found)) found = .false.
        if (.not. self%adaptive .or. self%estimator%order < 2 .or. self%estimator%n_levels < 2) return
        associate (e => self%estimator)
            slot = modulo(e%head - 2, MAX_LEVELS) + 1     ! the level before t_before
            times = [t_before + dt, t_before, t_before - e%steps(e%head)]
            gaps = [merge(trial_gap, gap_end, onset), gap_start, e%levels(ubound(e%levels, 1), 0, slot) - g]
        end associate
        call interpolant_root(times, gaps, lo, hi, t_event, has_root)
        if (.not. has_root) t_event = crossing_time(t_before, dt, gap_start, gap_end)
        if (present(found)) found = has_root
    end function driver_event_time

    !> The time of a Signorini release (adaptive steps): the contact force lambda = -sigma at the
    !> contact node from the node's equilibrium with its neighbour, alpha (u_{s-1} - u_s) / h_s
    !> (exact for the massless contact node of &contact mass = 'redistributed', the last
    !> element's stress otherwise), at the levels since the last event (t_before the latest)
    !> and, with_end, at the state's level at t_before + dt too; the root in [t_lo, t_hi] of the
    !> polynomial through them (dense_output_m), at most p+1 of them (p the scheme's order).
    !> found = .false. (t_event = t_hi): no root there, or fewer than two levels.
    subroutine driver_release_time(self, state, t_before, dt, with_end, t_lo, t_hi, t_event, found)
        class(step_driver_t), intent(in) :: self
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
        to_node = self%model%alpha / state%mesh%h(s)
        k = 0
        if (with_end) then
            k = 1
            times(1) = t_before + dt
            force(1) = to_node * (state%u(s - 1) - state%u(s))
        end if
        associate (e => self%estimator)
            n = min(e%n_levels, e%order + 1 - k)
            if (k + n < 2) return
            do j = 1, n
                slot = modulo(e%head - j, MAX_LEVELS) + 1
                times(k + j) = t_before
                if (j > 1) times(k + j) = times(k + j - 1) - e%steps(modulo(e%head - j + 1, MAX_LEVELS) + 1)
                force(k + j) = to_node * (e%levels(s - 1, 0, slot) - e%levels(s, 0, slot))
            end do
        end associate
        call interpolant_root(times(1:k + n), force(1:k + n), t_lo, t_hi, t_event, found)
        if (.not. found) t_event = t_hi
    end subroutine driver_release_time

    !> A tried adaptive step from t_before of size dt that changed the contact state (flipped),
    !> or a step cut to end at an event that did not (the event is later): locate the event
    !> (a Signorini release: release_time; otherwise event_time's interpolated gap) and say
    !> whether the step is retried to end there (cut, of size dt_land; events_m's event_landing;
    !> an event located by the straight line only is not cut closer than LINEAR_CUT_MIN of the
    !> step to its start).
    !> t_bound: the end of the last step that changed the contact state (set on a flipped
    !> step), beyond which the event is not sought.
    subroutine driver_landing(self, state, result, law, t_before, dt, gap_start, gap_end, flipped, t_bound, cut, &
                              dt_land)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        type(step_result_t), intent(in) :: result
        type(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: t_before, dt, gap_start, gap_end
        logical, intent(in) :: flipped
        real(dp), intent(inout) :: t_bound
        logical, intent(out) :: cut
        real(dp), intent(out) :: dt_land
        real(dp) :: t_lo, t_event
        logical :: found

        if (flipped) then
            t_bound = t_before + dt
            t_lo = t_before
        else
            t_lo = t_before + dt
        end if
        if (self%in_contact .and. law%is_signorini()) then
            call self%release_time(state, t_before, dt, .not. flipped, t_lo, t_bound, t_event, found)
        else
            t_event = self%event_time(t_before, dt, gap_start, gap_end, result%trial_gap, .not. self%in_contact, &
                                      law%g, t_lo, t_bound, found)
        end if
        if (flipped) then
            call event_landing(t_before, dt, t_event, self%dt_min, cut, dt_land)
            ! located by the straight line only (no interpolant: Euler, or right after an event): no
            ! cut of less than LINEAR_CUT_MIN of the step, which a slow (tangential) crossing would
            ! repeat step after step
            if (.not. found) cut = cut .and. dt_land >= LINEAR_CUT_MIN * dt
        else
            ! the cut step ended short of the event: cut again at the event located with its end
            call event_landing(t_before, t_bound - t_before, t_event, self%dt_min, cut, dt_land)
            cut = cut .and. found .and. t_event - (t_before + dt) > max(LANDING_FRACTION * dt, self%dt_min)
        end if
    end subroutine driver_landing

    !> The interpolant at time t of the last accepted step [t_{n-1}, t_n] (state holds X^n;
    !> dense_output_m): the polynomial through the levels since the last contact event, p+1
    !> of them (p the scheme's order) when held, else fewer. n points, weight(j) of the j-th
    !> most recent level (j = 1: X^n); n = 1: one level since the event, and the straight
    !> line from the state saved before the step is taken instead (weight(2) is the saved
    !> state's).
    subroutine dense_weights(self, state, t, n, weight)
        type(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: t
        integer, intent(out) :: n
        real(dp), intent(out) :: weight(MAX_LEVELS)
        real(dp) :: times(MAX_LEVELS)
        integer :: j

        weight = 0.0_dp
        associate (e => self%estimator)
            n = min(e%order + 1, e%n_levels)
            if (n < 2) then
                ! a programming error (fixed steps keep their levels when dense output is on)
                if (.not. allocated(self%saved%u)) &
                    error stop 'step_driver_m: dense output without the level before the step'
                weight(1:2) = lagrange_weights([state%t, self%saved%t], t)
                return
            end if
            times(1) = state%t
            do j = 2, n
                times(j) = times(j - 1) - e%steps(modulo(e%head - j + 1, MAX_LEVELS) + 1)
            end do
            weight(1:n) = lagrange_weights(times(1:n), t)
        end associate
    end subroutine dense_weights

    !> The level (u, w) at time t of the last accepted step, from the scheme's interpolant
    !> (dense_weights): a snapshot between the steps.
    subroutine driver_dense_level(self, state, t, u, w)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: t
        real(dp), intent(out) :: u(0:), w(0:, :)
        real(dp) :: weight(MAX_LEVELS)
        integer :: j, n, slot

        call dense_weights(self, state, t, n, weight)
        u = weight(1) * state%u
        w = weight(1) * state%w
        if (n < 2) then
            u = u + weight(2) * self%saved%u
            w = w + weight(2) * self%saved%w
        end if
        do j = 2, n
            slot = modulo(self%estimator%head - j, MAX_LEVELS) + 1
            u = u + weight(j) * self%estimator%levels(:, 0, slot)
            w = w + weight(j) * self%estimator%levels(:, 1:, slot)
        end do
    end subroutine driver_dense_level

    !> u(1,t), E(t) and E's parts (energy_m's energy_parts) at time t of the last accepted
    !> step for a series entry: the scheme's interpolant (dense_weights) of the levels' u(1),
    !> E^k (Corollary 6.2) and parts (energy_now, parts_now: those of the state, from the
    !> energy monitor). The energies and parts of the earlier levels are computed once per
    !> step, from the levels the estimator holds (so a restart gives the same bits).
    subroutine driver_dense_series(self, state, law, energy_now, parts_now, t, u_end, energy, parts)
        class(step_driver_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        type(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: energy_now, parts_now(N_ENERGY_PARTS), t
        real(dp), intent(out) :: u_end, energy, parts(N_ENERGY_PARTS)
        real(dp) :: weight(MAX_LEVELS)
        integer :: j, n, slot

        call dense_weights(self, state, t, n, weight)
        if (self%energies_step /= state%step) then
            self%energies_step = state%step
            if (n < 2) then
                call energy_and_parts(self%model, law, self%saved%u, self%saved%w, self%saved%mesh, &
                                      self%level_energy(2), self%level_parts(:, 2))
            else
                do j = 2, n
                    slot = modulo(self%estimator%head - j, MAX_LEVELS) + 1
                    associate (u => self%estimator%levels(:, 0, slot), w => self%estimator%levels(:, 1:, slot))
                        call energy_and_parts(self%model, law, u, w, state%mesh, self%level_energy(j), &
                                              self%level_parts(:, j))
                    end associate
                end do
            end if
        end if
        u_end = weight(1) * state%u(state%s)
        energy = weight(1) * energy_now
        parts = weight(1) * parts_now
        do j = 2, max(n, 2)
            if (n < 2) then
                u_end = u_end + weight(2) * self%saved%u(self%saved%s)
            else
                slot = modulo(self%estimator%head - j, MAX_LEVELS) + 1
                u_end = u_end + weight(j) * self%estimator%levels(state%s, 0, slot)
            end if
            energy = energy + weight(j) * self%level_energy(j)
            parts = parts + weight(j) * self%level_parts(:, j)
        end do
    end subroutine driver_dense_series

    !> A rejected step: the state as before it, and the step's contact count taken back.
    subroutine driver_undo_step(self, stepper, result, state)
        class(step_driver_t), intent(in) :: self
        type(stepper_t), intent(inout) :: stepper
        type(step_result_t), intent(in) :: result
        type(state_t), intent(inout) :: state

        call stepper%take_back(result)
        call copy_state(self%saved, state, level=.not. self%saved_without_level)
        if (self%saved_without_level) then   ! the level the step started from: the estimator's newest
            associate (e => self%estimator)
                state%u = e%levels(:, 0, e%head)
                state%w = e%levels(:, 1:, e%head)
            end associate
        end if
    end subroutine driver_undo_step

    !> Adapt the mesh to the level in state and, if it changed, move the state, the
    !> estimator's levels, the stepper and the monitor onto it (remesh_m).
    subroutine driver_remesh(self, mesh, state, stepper, monitor, changed)
        class(step_driver_t), intent(inout) :: self
        type(adaptive_mesh_t), intent(inout) :: mesh
        type(state_t), intent(inout) :: state
        type(stepper_t), intent(inout) :: stepper
        type(energy_monitor_t), intent(inout) :: monitor
        logical, intent(out) :: changed

        call remesh(mesh, state, stepper, self%estimator, monitor, changed)
        if (changed) self%level_kept = .false.
    end subroutine driver_remesh

    !> The contact state after a step, as events are counted: penalty, u^n(1) > g (the end
    !> position; the midpoint rule's force may act a step longer); Signorini, an active
    !> multiplier. gap: the gap at the step's end the crossing time is interpolated to,
    !> u^n(1) - g (penalty) or the trial gap (Signorini, whose u^n(1) stops at g).
    subroutine contact_state(law, state, result, in_contact, gap)
        type(contact_law_t), intent(in) :: law
        type(state_t), intent(in) :: state
        type(step_result_t), intent(in) :: result
        logical, intent(out) :: in_contact
        real(dp), intent(out) :: gap

        if (law%is_signorini()) then
            in_contact = result%in_contact
            gap = result%trial_gap
        else
            gap = state%u(state%s) - law%g
            in_contact = gap > 0.0_dp
        end if
    end subroutine contact_state

    !> Once per run: the error estimate exceeded the tolerance at the smallest step allowed.
    subroutine warn_forced(t, dt_min)
        real(dp), intent(in) :: t, dt_min

        write (error_unit, '(a,es11.4,a,es10.3,a)') 'rodcontact: warning: at t = ', t, &
            ' a step of dt_min = ', dt_min, ' exceeds time.error_tol and is accepted; lower time.dt_min ' // &
            '(the count is in the root attribute time_steps_at_dt_min)'
        flush (error_unit)
    end subroutine warn_forced

    !> 'step n (t = ...): reason' for a failure message and the status attribute; with
    !> reason = '' just 'step n (t = ...)'.
    function step_failure(n, t, reason) result(text)
        integer, intent(in) :: n
        real(dp), intent(in) :: t
        character(len=*), intent(in) :: reason
        character(len=:), allocatable :: text
        character(len=40) :: buf

        write (buf, '(a,i0,a,es11.4,a)') 'step ', n, ' (t = ', t, ')'
        text = trim(buf)
        if (reason /= '') text = text//': '//reason
    end function step_failure

end module step_driver_m
