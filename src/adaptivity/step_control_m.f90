!> Adaptive time steps (&time adaptive = .true.): the local error estimate of every step
!> and the step-size controller. (Fixed steps compute no estimate; the error of a run is
!> error_companion_m's, with &output error_estimate.)
!>
!> Estimate (docs/scheme.md, "Adaptive time steps"): the predictor-corrector difference, as
!> in the BDF codes (DASSL, CVODE). P^n is the polynomial of degree p (the scheme's order)
!> through the last p+1 accepted levels, extrapolated to t_n; for smooth solutions
!>   X^n - P^n = X^(p+1) / (p+1)! * d_1 ... d_{p+1} + h.o.t.,  d_j = t_n - t_{n-j},
!> while the local error of the step is C X^(p+1) h_n^(p+1) (C, p and the exact factor
!> are the scheme's: time_scheme_m's order and error_factor), so
!>   est_n = factor * |X^n - P^n|_E,   |X|_E = sqrt(2 E_lin(X))   (Corollary 6.2's energy),
!> over all fields at once. It costs no solve: one extrapolation and one energy per step.
!> A step is accepted when est_n <= error_tol * S, S the largest |X^k|_E so far (k <= n);
!> error_tol is thus relative to the size the solution has had. The controller is the
!> standard one, dt_new = dt * safety * (error_tol S / est)^(1/(p+1)), limited to
!> [SHRINK_MIN, growth_max] (growth_max: the scheme's max_step_ratio, for BDF2 below the
!> step-ratio bound of its zero-stability) and to [dt_min, dt_max]; a growth below
!> GROWTH_MIN is not taken, because every new step size costs a factorisation. The steps the
!> controller proposes are rounded down to the ladder dt_first * LADDER_RATIO**k (k an
!> integer; on_ladder), so that a run moves between few step sizes whose factored systems
!> stay in the stepper's cache (system_cache_m): a new size is a new factorisation, a size
!> met before is not. (Steps shortened to land on an output time or to end before a contact
!> event are not on the ladder.)
module step_control_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fields_m, only: N_FIELDS
    use energy_m, only: linear_energy_by_nodes
    use mesh_m, only: mesh_t
    use errors_m, only: check_allocation
    use time_scheme_m, only: time_scheme_t
    use checkpoint_m, only: checkpoint_t
    implicit none
    private
    public :: error_estimator_t, step_controller_t, MAX_LEVELS
    public :: energy_norm

    integer, parameter :: MAX_LEVELS = 3       !< past levels kept (p + 1 for p <= 2)
    real(dp), parameter :: SAFETY = 0.9_dp
    real(dp), parameter :: GROWTH_MIN = 1.25_dp !< smaller growths are not taken
    real(dp), parameter :: SHRINK_MIN = 0.2_dp  !< smallest dt_new / dt after a rejection
    !> ratio of neighbouring step sizes on the ladder (2 is 3 rungs: BDF2's growth bound is one).
    !> 2^(1/3) against 2^(1/4): on exp1 to t = 60 (midpoint, error_tol 1e-5) 1.4 % more steps,
    !> a quarter fewer factorisations, fewer instructions in all (callgrind)
    real(dp), parameter :: LADDER_RATIO = 2.0_dp**(1.0_dp / 3.0_dp)

    !> The last accepted levels, most recent first, with the steps that reached them.
    type :: error_estimator_t
        type(time_scheme_t) :: scheme
        integer :: order = 1               !< p: the scheme's order
        integer :: n_levels = 0            !< levels held (0..order+1)
        integer :: head = 1                !< slot of the most recent level
        real(dp) :: steps(MAX_LEVELS) = 0.0_dp   !< steps(slot): the step that reached that level
        real(dp), allocatable :: levels(:, :, :)  !< (0:s, 0:N_FIELDS, slot): u, then fields_m's F_*
        real(dp), allocatable :: u_diff(:), w_diff(:, :)   !< work: X^n - P^n
        real(dp), allocatable :: work(:)                   !< work: linear_energy_by_nodes' terms
    contains
        procedure :: init => estimator_init
        procedure :: resize => estimator_resize
        procedure :: reset => estimator_reset
        procedure :: push => estimator_push
        procedure :: ready => estimator_ready
        procedure :: estimate => estimator_estimate
        procedure :: save_checkpoint => estimator_save_checkpoint
        procedure :: restore_checkpoint => estimator_restore_checkpoint
    end type error_estimator_t

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
        procedure :: add_estimate => controller_add_estimate
        procedure :: count_forced => controller_count_forced
        procedure :: observe_size => controller_observe_size
        procedure :: counts => controller_counts
        procedure :: save_checkpoint => controller_save_checkpoint
        procedure :: restore_checkpoint => controller_restore_checkpoint
    end type step_controller_t

contains

    ! ------------------------------------------------------------------ estimator

    !> An estimator for `scheme` on s elements.
    subroutine estimator_init(self, scheme, s)
        class(error_estimator_t), intent(out) :: self
        type(time_scheme_t), intent(in) :: scheme
        integer, intent(in) :: s

        self%scheme = scheme
        self%order = scheme%order()
        call self%resize(s)
    end subroutine estimator_init

    !> Arrays for a mesh of s elements (the levels held are lost: a remesh moves them
    !> first, remesh_m).
    subroutine estimator_resize(self, s)
        class(error_estimator_t), intent(inout) :: self
        integer, intent(in) :: s
        integer :: stat
        character(len=256) :: message

        if (allocated(self%levels)) deallocate (self%levels, self%u_diff, self%w_diff, self%work)
        allocate (self%levels(0:s, 0:N_FIELDS, MAX_LEVELS), self%u_diff(0:s), self%w_diff(0:s, N_FIELDS), &
                  self%work(s), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the error estimator''s levels')
        self%levels = 0.0_dp
    end subroutine estimator_resize

    !> Forget the levels (after a contact event: the solution is not smooth across it).
    subroutine estimator_reset(self)
        class(error_estimator_t), intent(inout) :: self

        self%n_levels = 0
    end subroutine estimator_reset

    !> Keep the accepted level (u, w) reached by a step of size dt.
    subroutine estimator_push(self, u, w, dt)
        class(error_estimator_t), intent(inout) :: self
        real(dp), intent(in) :: u(0:), w(0:, :)
        real(dp), intent(in) :: dt

        self%head = modulo(self%head, MAX_LEVELS) + 1
        self%levels(:, 0, self%head) = u
        self%levels(:, 1:, self%head) = w
        self%steps(self%head) = dt
        self%n_levels = min(self%n_levels + 1, MAX_LEVELS)
    end subroutine estimator_push

    !> Enough levels for an estimate of the next step (p + 1).
    pure logical function estimator_ready(self)
        class(error_estimator_t), intent(in) :: self

        estimator_ready = self%n_levels >= self%order + 1
    end function estimator_ready

    !> est_n = factor |X^n - P^n|_E for the new level (u, w) reached by a step of size dt
    !> on mesh (the module's header); needs ready().
    function estimator_estimate(self, model, u, w, dt, mesh) result(est)
        class(error_estimator_t), intent(inout) :: self
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: u(0:), w(0:, :)
        real(dp), intent(in) :: dt
        type(mesh_t), intent(in) :: mesh
        real(dp) :: est
        real(dp) :: d(MAX_LEVELS), weight(MAX_LEVELS), energy
        integer :: j, k, n

        n = self%order + 1
        ! d_j = t_n - t_{n-j}: the new step plus the steps that reached the newer levels
        d(1) = dt
        do j = 2, n
            d(j) = d(j - 1) + self%steps(level_slot(self%head, j - 1))
        end do
        ! Lagrange weights of the extrapolation to t_n from t_n - d_j
        do j = 1, n
            weight(j) = 1.0_dp
            do k = 1, n
                if (k /= j) weight(j) = weight(j) * d(k) / (d(k) - d(j))
            end do
        end do
        call extrapolation_difference(self, u, w, weight(1:n))
        call linear_energy_by_nodes(model, self%u_diff, self%w_diff, mesh, self%work, energy)
        est = self%scheme%error_factor(d(1:n), self%steps(level_slot(self%head, 1))) * energy_norm(energy)
    end function estimator_estimate

    !> u_diff, w_diff = X^n - P^n, P^n = sum_j weight(j) X^{n-j} over the levels held (the
    !> newest first): one pass over the nodes per field, the terms subtracted in the order
    !> j = 1, 2, ... (the same sums as one array operation per level, without reading and
    !> writing the difference once per level).
    subroutine extrapolation_difference(self, u, w, weight)
        type(error_estimator_t), intent(inout) :: self
        real(dp), intent(in) :: u(0:), w(0:, :)
        real(dp), intent(in) :: weight(:)
        integer :: f, i, s, slot(MAX_LEVELS)
        real(dp) :: c1, c2, c3

        s = ubound(u, 1)
        do i = 1, size(weight)
            slot(i) = level_slot(self%head, i)
        end do
        if (size(weight) == 3) then
            c1 = weight(1); c2 = weight(2); c3 = weight(3)
            ! unrolled 4 times (GCC's directive; a comment to other compilers): the vector loop's
            ! own instructions were 3 of 14 per two values
            associate (l => self%levels, k1 => slot(1), k2 => slot(2), k3 => slot(3))
                !GCC$ unroll 4
                do i = 0, s
                    self%u_diff(i) = ((u(i) - c1 * l(i, 0, k1)) - c2 * l(i, 0, k2)) - c3 * l(i, 0, k3)
                end do
                do f = 1, N_FIELDS
                    !GCC$ unroll 4
                    do i = 0, s
                        self%w_diff(i, f) = ((w(i, f) - c1 * l(i, f, k1)) - c2 * l(i, f, k2)) - c3 * l(i, f, k3)
                    end do
                end do
            end associate
            return
        end if
        if (size(weight) == 2) then   ! Euler (p = 1): the same sums, one pass
            c1 = weight(1); c2 = weight(2)
            associate (l => self%levels, k1 => slot(1), k2 => slot(2))
                !GCC$ unroll 8
                do i = 0, s
                    self%u_diff(i) = (u(i) - c1 * l(i, 0, k1)) - c2 * l(i, 0, k2)
                end do
                do f = 1, N_FIELDS
                    !GCC$ unroll 8
                    do i = 0, s
                        self%w_diff(i, f) = (w(i, f) - c1 * l(i, f, k1)) - c2 * l(i, f, k2)
                    end do
                end do
            end associate
            return
        end if
        self%u_diff = u
        self%w_diff = w
        do i = 1, size(weight)
            self%u_diff = self%u_diff - weight(i) * self%levels(:, 0, slot(i))
            self%w_diff = self%w_diff - weight(i) * self%levels(:, 1:, slot(i))
        end do
    end subroutine extrapolation_difference

    !> |X|_E = sqrt(2 E) of an energy E (Corollary 6.2).
    pure real(dp) function energy_norm(energy)
        real(dp), intent(in) :: energy

        energy_norm = sqrt(2.0_dp * max(energy, 0.0_dp))
    end function energy_norm

    !> The slot of the j-th most recent level (j = 1: the newest, in slot head).
    pure integer function level_slot(head, j)
        integer, intent(in) :: head, j

        level_slot = modulo(head - j, MAX_LEVELS) + 1
    end function level_slot

    ! ------------------------------------------------------------------ controller

    !> A controller for `scheme` (its order p and step-ratio bound) whose first proposal is
    !> dt_first; scale: S of the first level (default 0).
    subroutine controller_init(self, tol, dt_min, dt_max, scheme, dt_first, scale)
        class(step_controller_t), intent(out) :: self
        real(dp), intent(in) :: tol, dt_min, dt_max, dt_first
        type(time_scheme_t), intent(in) :: scheme
        real(dp), intent(in), optional :: scale

        self%tol = tol
        self%dt_min = dt_min
        self%dt_max = dt_max
        self%order = scheme%order()
        self%growth_max = scheme%max_step_ratio()
        self%dt_next = dt_first
        self%ladder_base = dt_first
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

    !> An accepted step had the estimate est: into the run's time error (error_sum).
    subroutine controller_add_estimate(self, est)
        class(step_controller_t), intent(inout) :: self
        real(dp), intent(in) :: est

        self%error_sum = self%error_sum + est
        self%n_estimated = self%n_estimated + 1
    end subroutine controller_add_estimate

    !> A step was accepted at dt_min although its estimate exceeded the tolerance.
    subroutine controller_count_forced(self)
        class(step_controller_t), intent(inout) :: self

        self%n_forced = self%n_forced + 1
    end subroutine controller_count_forced

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

    !> A step of size dt was accepted with error ratio err (negative: no estimate, the step
    !> size is kept): the next proposal. shortened: the step was shortened to land on an
    !> output time, which says nothing against the proposal it was shortened from.
    subroutine controller_accept(self, dt, err, shortened)
        class(step_controller_t), intent(inout) :: self
        real(dp), intent(in) :: dt, err
        logical, intent(in), optional :: shortened
        real(dp) :: factor, proposal

        proposal = self%dt_next
        self%dt_next = dt
        if (err >= 0.0_dp .and. .not. self%no_growth) then
            factor = self%growth_max
            if (err > 0.0_dp) factor = min(self%growth_max, SAFETY * err**(-1.0_dp / real(self%order + 1, dp)))
            if (factor >= GROWTH_MIN) self%dt_next = min(on_ladder(dt * factor, self%ladder_base), self%dt_max)
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

    !> The controller's scalars into a checkpoint (step_controller/...).
    subroutine controller_save_checkpoint(self, ckpt)
        class(step_controller_t), intent(in) :: self
        type(checkpoint_t), intent(inout) :: ckpt

        call ckpt%put('step_controller/dt_next', self%dt_next)
        call ckpt%put('step_controller/no_growth', self%no_growth)
        call ckpt%put('step_controller/scale', self%scale)
        call ckpt%put('step_controller/error_sum', self%error_sum)
        call ckpt%put('step_controller/n_estimated', self%n_estimated)
        call ckpt%put('step_controller/n_rejected', self%n_rejected)
        call ckpt%put('step_controller/n_forced', self%n_forced)
    end subroutine controller_save_checkpoint

    !> The inverse of save_checkpoint (on a controller initialised for this run).
    subroutine controller_restore_checkpoint(self, ckpt)
        class(step_controller_t), intent(inout) :: self
        type(checkpoint_t), intent(in) :: ckpt

        call ckpt%get('step_controller/dt_next', self%dt_next)
        call ckpt%get('step_controller/no_growth', self%no_growth)
        call ckpt%get('step_controller/scale', self%scale)
        call ckpt%get('step_controller/error_sum', self%error_sum)
        call ckpt%get('step_controller/n_estimated', self%n_estimated)
        call ckpt%get('step_controller/n_rejected', self%n_rejected)
        call ckpt%get('step_controller/n_forced', self%n_forced)
    end subroutine controller_restore_checkpoint

    !> The estimator's levels into a checkpoint, most recent first: error_estimator/levels
    !> (s+1, (1+N_FIELDS) MAX_LEVELS; unused ones zero) and steps (the step that reached each).
    subroutine estimator_save_checkpoint(self, ckpt)
        class(error_estimator_t), intent(in) :: self
        type(checkpoint_t), intent(inout) :: ckpt
        real(dp), allocatable :: levels(:, :)
        real(dp) :: steps(self%n_levels)
        integer :: j, slot, width, stat
        character(len=256) :: message

        width = 1 + N_FIELDS
        allocate (levels(size(self%levels, 1), width * MAX_LEVELS), source=0.0_dp, stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the checkpoint of the error estimator')
        do j = 1, self%n_levels
            slot = level_slot(self%head, j)
            steps(j) = self%steps(slot)
            levels(:, (j - 1) * width + 1:j * width) = self%levels(:, :, slot)
        end do
        call ckpt%put('error_estimator/levels', levels)
        call ckpt%put('error_estimator/steps', steps)
    end subroutine estimator_save_checkpoint

    !> The inverse of save_checkpoint (on an estimator initialised for this run, on the
    !> checkpoint's mesh).
    subroutine estimator_restore_checkpoint(self, ckpt)
        class(error_estimator_t), intent(inout) :: self
        type(checkpoint_t), intent(in) :: ckpt
        real(dp), allocatable :: levels(:, :), steps(:)
        integer :: j, width

        width = 1 + N_FIELDS
        call ckpt%get('error_estimator/levels', levels)
        call ckpt%get('error_estimator/steps', steps)
        call self%reset()
        do j = size(steps), 1, -1
            call self%push(levels(:, (j - 1) * width + 1), levels(:, (j - 1) * width + 2:j * width), steps(j))
        end do
    end subroutine estimator_restore_checkpoint

end module step_control_m
