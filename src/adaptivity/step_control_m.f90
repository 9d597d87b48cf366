!> The step-size controller of adaptive time steps (&time adaptive = .true.), on the local
!> error estimate of error_estimator_m: a step is accepted when est_n <= error_tol * S, S the
!> largest |X^k|_E so far; dt_new = dt * safety * (error_tol S / est)^(1/(p+1)), limited to
!> [SHRINK_MIN, growth_max] (the scheme's max_step_ratio) and [dt_min, dt_max], a growth below
!> GROWTH_MIN not taken, and rounded down to the ladder dt_first * LADDER_RATIO**k (on_ladder;
!> each new size costs a factorisation). Steps shortened to land on an output time or to end
!> at a contact event are not on the ladder. Why: docs/scheme.md, "Adaptive time steps".
module step_control_m
    use kinds_m, only: dp
    use config_m, only: time_t
    use time_scheme_m, only: time_scheme_t
    use checkpoint_m, only: checkpoint_t
    implicit none
    private
    public :: step_controller_t

    real(dp), parameter :: SAFETY = 0.9_dp
    real(dp), parameter :: GROWTH_MIN = 1.25_dp !< smaller growths are not taken
    real(dp), parameter :: SHRINK_MIN = 0.2_dp  !< smallest dt_new / dt after a rejection
    !> ratio of neighbouring step sizes on the ladder (three rungs to BDF2's growth bound 2;
    !> the choice against 2^(1/4): docs/performance.md, "The step-size ladder")
    real(dp), parameter :: LADDER_RATIO = 2.0_dp**(1.0_dp / 3.0_dp)

    !> The controller's state between steps.
    type :: step_controller_t
        private
        real(dp) :: tol = 1.0e-5_dp, dt_min = 0.0_dp, dt_max = huge(1.0_dp)
        integer :: order = 1               !< p: the scheme's order
        real(dp) :: growth_max = 2.0_dp    !< largest dt_n / dt_{n-1}: the scheme's max_step_ratio
        real(dp) :: dt_next = 0.0_dp       !< the step the controller proposes next
        real(dp) :: ladder_base = 0.0_dp   !< dt_first: the ladder's rung k = 0 (on_ladder)
        logical :: no_growth = .false.     !< after a rejection: no growth on the next step
        real(dp) :: scale = 0.0_dp         !< S: the largest |X^k|_E so far
        real(dp) :: error_sum = 0.0_dp     !< sum of est_n over the accepted steps
        integer :: n_estimated = 0         !< accepted steps that had an estimate
        integer :: n_rejected = 0          !< steps rejected by the estimate
        integer :: n_forced = 0            !< steps accepted at dt_min although est > tol S
    contains
        procedure :: init => controller_init
        procedure :: ratio => controller_ratio
        procedure :: accept => controller_accept
        procedure :: reject => controller_reject
        procedure :: proposal => controller_proposal
        procedure :: observe_size => controller_observe_size
        procedure :: counts => controller_counts
        procedure :: checkpoint => controller_checkpoint
    end type step_controller_t

contains

    ! ------------------------------------------------------------------ controller

    !> A controller for the run's &time (error_tol, dt_min, dt_max; the first proposal dt)
    !> and `scheme` (its order p and step-ratio bound); scale: S of the first level (default 0).
    subroutine controller_init(self, time, scheme, scale)
        class(step_controller_t), intent(out) :: self
        type(time_t), intent(in) :: time
        type(time_scheme_t), intent(in) :: scheme
        real(dp), intent(in), optional :: scale

        self%tol = time%error_tol
        self%dt_min = time%dt_min
        self%dt_max = time%dt_max
        self%order = scheme%row%order
        self%growth_max = scheme%row%max_step_ratio
        self%dt_next = time%dt
        self%ladder_base = time%dt
        if (present(scale)) self%scale = scale
    end subroutine controller_init

    !> The step the controller proposes next; after a last step of size dt_last > 0, at most
    !> growth_max dt_last (the scheme's step-ratio bound).
    pure real(dp) function controller_proposal(self, dt_last) result(dt)
        class(step_controller_t), intent(in) :: self
        real(dp), intent(in), optional :: dt_last

        dt = self%dt_next
        if (present(dt_last)) then
            if (dt_last > 0.0_dp .and. self%growth_max * dt_last < dt) &
                dt = on_ladder(self%growth_max * dt_last, self%ladder_base)
        end if
    end function controller_proposal

    !> The accepted level has the energy norm |X^n|_E: S = max(S, |X^n|_E).
    subroutine controller_observe_size(self, norm)
        class(step_controller_t), intent(inout) :: self
        real(dp), intent(in) :: norm

        self%scale = max(self%scale, norm)
    end subroutine controller_observe_size

    !> The controller's error sum and counts (the root attributes step_control_error_sum*,
    !> time_steps_* of adaptive runs).
    pure subroutine controller_counts(self, error_sum, scale, n_estimated, n_rejected, n_forced)
        class(step_controller_t), intent(in) :: self
        real(dp), intent(out) :: error_sum, scale
        integer, intent(out) :: n_estimated, n_rejected, n_forced

        error_sum = self%error_sum
        scale = self%scale
        n_estimated = self%n_estimated
        n_rejected = self%n_rejected
        n_forced = self%n_forced
    end subroutine controller_counts

    !> est / (error_tol S): a step is accepted when this is <= 1.
    pure real(dp) function controller_ratio(self, est) result(ratio)
        class(step_controller_t), intent(in) :: self
        real(dp), intent(in) :: est

        ratio = est / max(self%tol * self%scale, tiny(1.0_dp))
    end function controller_ratio

    !> A step of size dt was accepted with estimate est and error ratio err (negative: no
    !> estimate, the step size is kept): est into the run's time error (error_sum), counted
    !> as forced if err > 1 (accepted at dt_min), and the next proposal. shortened: the step
    !> was shortened to land on an output time, which says nothing against the proposal it
    !> was shortened from.
    subroutine controller_accept(self, dt, est, err, shortened)
        class(step_controller_t), intent(inout) :: self
        real(dp), intent(in) :: dt, est, err
        logical, intent(in), optional :: shortened
        real(dp) :: factor, proposal

        if (err >= 0.0_dp) then
            self%error_sum = self%error_sum + est
            self%n_estimated = self%n_estimated + 1
        end if
        if (err > 1.0_dp) self%n_forced = self%n_forced + 1
        proposal = self%dt_next
        self%dt_next = dt
        if (err >= 0.0_dp .and. .not. self%no_growth) then
            factor = self%growth_max
            if (err > 0.0_dp) factor = min(self%growth_max, SAFETY * err**(-1.0_dp / real(self%order + 1, dp)))
            if (factor >= GROWTH_MIN) &
                self%dt_next = min(on_ladder(dt * factor, self%ladder_base), self%dt_max)
        end if
        self%dt_next = max(self%dt_next, self%dt_min)
        self%no_growth = .false.
        if (present(shortened)) then
            if (shortened) self%dt_next = max(self%dt_next, min(proposal, self%dt_max))
        end if
    end subroutine controller_accept

    !> A step of size dt was rejected with error ratio err > 1: the retry.
    subroutine controller_reject(self, dt, err)
        class(step_controller_t), intent(inout) :: self
        real(dp), intent(in) :: dt, err
        real(dp) :: shrink

        self%n_rejected = self%n_rejected + 1
        shrink = max(SHRINK_MIN, min(SAFETY, SAFETY * err**(-1.0_dp / real(self%order + 1, dp))))
        self%dt_next = max(on_ladder(dt * shrink, self%ladder_base), self%dt_min)
        self%no_growth = .true.
    end subroutine controller_reject

    !> The largest step base * LADDER_RATIO**k (k an integer) that is at most dt (to a relative
    !> 1e-12: a dt on the ladder stays where it is). A function of k alone, so that a size met
    !> twice is the same number bit for bit.
    pure real(dp) function on_ladder(dt, base) result(rung)
        real(dp), intent(in) :: dt, base
        integer :: k

        rung = dt
        if (.not. (dt > 0.0_dp .and. base > 0.0_dp)) return
        k = floor(log(dt / base) / log(LADDER_RATIO) + 1.0e-12_dp)
        rung = base * LADDER_RATIO**k
    end function on_ladder

    ! ------------------------------------------------------------------ checkpoint

    !> The controller's scalars into a checkpoint (step_controller/...), or back from one
    !> (checkpoint_m's sync; on a controller initialised for this run).
    subroutine controller_checkpoint(self, ckpt)
        class(step_controller_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt

        call ckpt%sync('step_controller/dt_next', self%dt_next)
        call ckpt%sync('step_controller/no_growth', self%no_growth)
        call ckpt%sync('step_controller/scale', self%scale)
        call ckpt%sync('step_controller/error_sum', self%error_sum)
        call ckpt%sync('step_controller/n_estimated', self%n_estimated)
        call ckpt%sync('step_controller/n_rejected', self%n_rejected)
        call ckpt%sync('step_controller/n_forced', self%n_forced)
    end subroutine controller_checkpoint

end module step_control_m
