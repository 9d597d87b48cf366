!> The step driver: takes one accepted step of the time loop, trying and rejecting steps
!> as the step control asks: &time dt (fixed) or step_control_m's proposal (adaptive), a
!> rejected step restored and retried smaller, a contact event located and stepped over
!> (events_m's event_landing), steps shortened to land on the snapshot times and the end.
!> The whole sequence: docs/architecture.md, "One adaptive step"; choosing, trying, judging
!> and accepting one step (take_step): the submodule step_driver_trial_s.
module step_driver_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use config_m, only: config_t
    use material_m, only: time_scale
    use state_m, only: state_t, copy_state, keep_copy
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: energy_monitor_t
    use checkpoint_m, only: checkpoint_t
    use events_m, only: event_log_t
    use error_estimator_m, only: error_estimator_t, energy_norm, MAX_LEVELS
    use step_control_m, only: step_controller_t
    use dense_output_m, only: lagrange_weights
    use adaptive_mesh_m, only: adaptive_mesh_t, front_speed
    use transfer_m, only: transfer_level, move_state
    use errors_m, only: check_allocation
    implicit none
    private
    public :: step_driver_t

    type :: step_driver_t
        private
        logical :: adaptive = .false.          !< &time adaptive
        !> dense output (&output series_dt, snapshot_land = .false.): fixed steps keep their
        !> levels in the estimator too (dense_weights, dense_level, past_level)
        logical :: dense = .false.
        real(dp) :: dt = 0.0_dp, dt_min = 0.0_dp, dt_max = 0.0_dp   !< &time dt, dt_min, dt_max
        real(dp) :: v_front = 0.0_dp           !< &mesh adaptive: adaptive_mesh_m's front_speed
        type(error_estimator_t) :: estimator
        type(step_controller_t) :: control
        type(event_log_t) :: events
        !> the state before a tried step (adaptive) without its level (u, w): an adaptive run's
        !> level is the estimator's newest, bit for bit (pushed by init and by each accepted
        !> step, moved with it by a remesh, read with it from a checkpoint), and a step taken
        !> back gets it from there
        type(state_t) :: saved
        logical :: in_contact = .false.        !< the contact state after the last accepted step
        logical :: warned_forced = .false.
        !> a step's t in the input's units (step_label): with &material in s (the time
        !> scale omega of (2.10)), else nondimensional
        real(dp) :: t_scale = 1.0_dp
        character(len=2) :: t_unit = ''
    contains
        procedure :: init => driver_init
        procedure :: take_step => driver_take_step
        procedure :: remesh => driver_remesh
        procedure :: events_log => driver_events_log
        procedure :: controller => driver_controller
        procedure :: checkpoint => driver_checkpoint
        procedure :: dense_level => driver_dense_level
        procedure :: dense_weights => driver_dense_weights
        procedure :: past_level => driver_past_level
        procedure :: step_label => driver_step_label
    end type step_driver_t

    interface   ! in the submodule step_driver_trial_s
        !> Take one accepted step from state towards t_stop (landing on it, or on t_snapshot
        !> when that comes first; at_snapshot: the step ended there): choose a step, try it,
        !> judge it (locate a contact event it crossed, reject it on its estimate) until one
        !> is accepted. On a numerical failure, failure says which step and why ('' otherwise);
        !> the state is then that of the failed step (a failed solve) or of the accepted step
        !> (a non-finite energy).
        module subroutine driver_take_step(self, state, stepper, monitor, result, t_stop, at_snapshot, failure, &
                                           t_snapshot)
            class(step_driver_t), intent(inout) :: self
            type(state_t), intent(inout) :: state
            type(stepper_t), intent(inout) :: stepper
            type(energy_monitor_t), intent(inout) :: monitor
            type(step_result_t), intent(inout) :: result
            real(dp), intent(in) :: t_stop
            logical, intent(out) :: at_snapshot
            character(len=*), intent(out) :: failure
            real(dp), intent(in), optional :: t_snapshot   !< the next snapshot time (absent: none)
        end subroutine driver_take_step
    end interface

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
        self%dense = cfg%output%series_dt > 0.0_dp .or. (cfg%output%snapshot_dt > 0.0_dp .and. &
                                                         .not. cfg%output%snapshot_land)
        self%dt = cfg%time%dt
        self%dt_min = cfg%time%dt_min
        self%dt_max = cfg%time%dt_max
        if (cfg%mesh%adaptive) self%v_front = front_speed(cfg%model)
        call self%estimator%init(stepper%scheme, state%s)
        call self%control%init(cfg%time, stepper%scheme, &
                               scale=energy_norm(monitor%current_energy()))
        call self%estimator%push(state%u, state%w, 0.0_dp)
        self%in_contact = stepper%law%penetration(state%u(state%s)) > 0.0_dp
        self%t_scale = time_scale(cfg%material)
        if (cfg%material%present) self%t_unit = ' s'
    end subroutine driver_init

    !> The step control, the estimator's levels, the contact state and the events into a
    !> checkpoint, or back from one (checkpoint_m's reading; on a driver initialised for this
    !> run, to continue from it).
    subroutine driver_checkpoint(self, ckpt)
        class(step_driver_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt

        call self%control%checkpoint(ckpt)
        call self%estimator%checkpoint(ckpt)
        call ckpt%sync('step_driver/in_contact', self%in_contact)
        call self%events%checkpoint(ckpt)
    end subroutine driver_checkpoint

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

    !> The interpolant at time t of the last accepted step [t_{n-1}, t_n] (state holds X^n;
    !> dense_output_m): the polynomial through the levels since the last contact event, p+1
    !> of them (p the scheme's order) when held, else fewer. n points, weight(j) of the j-th
    !> most recent level (j = 1: X^n); with one level since the event, the straight line
    !> from the level before the step (n = 2: the estimator's second level, which its reset
    !> keeps, at the saved state's t).
    subroutine driver_dense_weights(self, state, t, n, weight)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: t
        integer, intent(out) :: n
        real(dp), intent(out) :: weight(MAX_LEVELS)

        weight = 0.0_dp
        associate (e => self%estimator)
            n = min(e%order + 1, e%n_levels)
            if (n < 2) then
                ! a programming error (fixed steps keep their levels when dense output is on)
                if (.not. self%adaptive) &
                    error stop 'step_driver_m: dense output without the level before the step'
                n = 2
                weight(1:2) = lagrange_weights([state%t, self%saved%t], t)
                return
            end if
            weight(1:n) = lagrange_weights(e%times(state%t, n), t)
        end associate
    end subroutine driver_dense_weights

    !> The level (u, w) at time t of the last accepted step, from the scheme's interpolant
    !> (dense_weights): a snapshot between the steps.
    subroutine driver_dense_level(self, state, t, u, w)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: t
        real(dp), intent(out) :: u(0:), w(0:, :)
        real(dp) :: weight(MAX_LEVELS)
        integer :: j, n, slot

        call self%dense_weights(state, t, n, weight)
        u = weight(1) * state%u
        w = weight(1) * state%w
        do j = 2, n
            slot = self%estimator%slot(j)
            u = u + weight(j) * self%estimator%levels(:, 0, slot)
            w = w + weight(j) * self%estimator%levels(:, 1:, slot)
        end do
    end subroutine driver_dense_level

    !> The j-th most recent level (j >= 2) of the last accepted step's interpolant
    !> (dense_weights) into level, on state's mesh: the estimator's.
    subroutine driver_past_level(self, state, j, level)
        class(step_driver_t), intent(in) :: self
        type(state_t), intent(in) :: state
        integer, intent(in) :: j
        type(state_t), intent(inout) :: level

        call copy_state(state, level, level=.false.)
        associate (e => self%estimator, slot => self%estimator%slot(j))
            call keep_copy(e%levels(:, 0, slot), e%levels(:, 1:, slot), level%u, level%w, &
                           'a past level')
        end associate
    end subroutine driver_past_level

    !> Adapt the mesh to the level in state and, if it changed, move every time level the
    !> run holds and the stepper onto it (transfer_m), and let the monitor measure the law
    !> energy across the move and count the remesh (energy_m).
    subroutine driver_remesh(self, mesh, state, stepper, monitor, changed)
        class(step_driver_t), intent(inout) :: self
        type(adaptive_mesh_t), intent(inout) :: mesh
        type(state_t), intent(inout) :: state
        type(stepper_t), intent(inout) :: stepper
        type(energy_monitor_t), intent(inout) :: monitor
        logical, intent(out) :: changed
        integer(int64), allocatable :: k_old(:)
        real(dp), allocatable :: levels_old(:, :, :)
        integer :: j, stat
        character(len=256) :: message

        allocate (k_old, source=mesh%k, stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the remesh')
        call mesh%adapt(state%mesh, state%u, state%w, changed)
        if (.not. changed) return
        call move_state(k_old, mesh%k, mesh%n_fine, stepper, state)
        allocate (levels_old, source=self%estimator%levels, stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the remesh')
        call self%estimator%resize(mesh%s())
        do j = 1, MAX_LEVELS
            call transfer_level(k_old, mesh%k, mesh%n_fine, levels_old(:, 0, j), levels_old(:, 1:, j), &
                                self%estimator%levels(:, 0, j), self%estimator%levels(:, 1:, j), &
                                stepper%model)
        end do
        call monitor%remeshed(state)
    end subroutine driver_remesh

    !> 'step n (t = ...): reason' for a failure message, the status attribute and a
    !> checkpoint's description, t with &material in seconds ('t = 1.2345E-03 s'); with
    !> reason = '' just 'step n (t = ...)'.
    function driver_step_label(self, n, t, reason) result(text)
        class(step_driver_t), intent(in) :: self
        integer, intent(in) :: n
        real(dp), intent(in) :: t
        character(len=*), intent(in) :: reason
        character(len=:), allocatable :: text
        character(len=48) :: buf

        write (buf, '(a,i0,a,es11.4,a)') 'step ', n, ' (t = ', self%t_scale * t, trim(self%t_unit)//')'
        text = trim(buf)
        if (reason /= '') text = text//': '//reason
    end function driver_step_label

end module step_driver_m
