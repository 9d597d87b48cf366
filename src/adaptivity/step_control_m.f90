!> Adaptive time steps (&time adaptive = .true.): the local error estimate of every step,
!> the step-size controller, and the a-posteriori estimate of fixed-step runs.
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
!> GROWTH_MIN is not taken, because every new step size costs a factorisation.
module step_control_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fields_m, only: N_FIELDS
    use energy_m, only: linear_energy
    use mesh_m, only: mesh_t
    use errors_m, only: check_allocation
    use time_scheme_m, only: time_scheme_t
    implicit none
    private
    public :: error_estimator_t, step_controller_t, N_CONTROL_VALUES, MAX_LEVELS
    public :: pack_control, unpack_control, energy_norm

    integer, parameter :: MAX_LEVELS = 3       !< past levels kept (p + 1 for p <= 2)
    real(dp), parameter :: SAFETY = 0.9_dp
    real(dp), parameter :: GROWTH_MIN = 1.25_dp !< smaller growths are not taken
    real(dp), parameter :: SHRINK_MIN = 0.2_dp  !< smallest dt_new / dt after a rejection

    !> The last accepted levels, most recent first, with the steps that reached them.
    type :: error_estimator_t
        type(time_scheme_t) :: scheme
        integer :: order = 1               !< p: the scheme's order
        integer :: n_levels = 0            !< levels held (0..order+1)
        integer :: head = 1                !< slot of the most recent level
        real(dp) :: steps(MAX_LEVELS) = 0.0_dp   !< steps(slot): the step that reached that level
        real(dp), allocatable :: levels(:, :, :)  !< (0:s, 0:N_FIELDS, slot): u, then fields_m's F_*
        real(dp), allocatable :: u_diff(:), w_diff(:, :)   !< work: X^n - P^n
    contains
        procedure :: init => estimator_init
        procedure :: resize => estimator_resize
        procedure :: reset => estimator_reset
        procedure :: push => estimator_push
        procedure :: ready => estimator_ready
        procedure :: estimate => estimator_estimate
    end type error_estimator_t

    !> The controller's state between steps.
    type :: step_controller_t
        real(dp) :: tol = 1.0e-5_dp, dt_min = 0.0_dp, dt_max = huge(1.0_dp)
        integer :: order = 1               !< p: the scheme's order
        real(dp) :: growth_max = 2.0_dp    !< largest dt_n / dt_{n-1}: the scheme's max_step_ratio
        real(dp) :: dt_next = 0.0_dp       !< the step the controller proposes next
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
    end type step_controller_t

    !> Scalars of a controller and an estimator in a checkpoint (pack_control).
    integer, parameter :: N_CONTROL_VALUES = 8 + MAX_LEVELS

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
    !> first, run_m).
    subroutine estimator_resize(self, s)
        class(error_estimator_t), intent(inout) :: self
        integer, intent(in) :: s
        integer :: stat
        character(len=256) :: message

        if (allocated(self%levels)) deallocate (self%levels, self%u_diff, self%w_diff)
        allocate (self%levels(0:s, 0:N_FIELDS, MAX_LEVELS), self%u_diff(0:s), self%w_diff(0:s, N_FIELDS), &
                  stat=stat, errmsg=message)
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
        real(dp) :: d(MAX_LEVELS), weight(MAX_LEVELS)
        integer :: j, k, n, slot

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
        self%u_diff = u
        self%w_diff = w
        do j = 1, n
            slot = level_slot(self%head, j)
            self%u_diff = self%u_diff - weight(j) * self%levels(:, 0, slot)
            self%w_diff = self%w_diff - weight(j) * self%levels(:, 1:, slot)
        end do
        est = self%scheme%error_factor(d(1:n), self%steps(level_slot(self%head, 1))) * &
              energy_norm(linear_energy(model, self%u_diff, self%w_diff, mesh))
    end function estimator_estimate

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

    !> A controller for `scheme` (its order and step-ratio bound) with error_tol tol.
    subroutine controller_init(self, tol, dt_min, dt_max, scheme, dt_first)
        class(step_controller_t), intent(out) :: self
        real(dp), intent(in) :: tol, dt_min, dt_max, dt_first
        type(time_scheme_t), intent(in) :: scheme

        self%tol = tol
        self%dt_min = dt_min
        self%dt_max = dt_max
        self%order = scheme%order()
        self%growth_max = scheme%max_step_ratio()
        self%dt_next = dt_first
    end subroutine controller_init

    !> est / (error_tol S): a step is accepted when this is <= 1.
    pure real(dp) function controller_ratio(self, est) result(ratio)
        class(step_controller_t), intent(in) :: self
        real(dp), intent(in) :: est

        ratio = est / max(self%tol * self%scale, tiny(1.0_dp))
    end function controller_ratio

    !> A step of size dt was accepted with error ratio err (negative: no estimate, the step
    !> size is kept): the next proposal.
    subroutine controller_accept(self, dt, err)
        class(step_controller_t), intent(inout) :: self
        real(dp), intent(in) :: dt, err
        real(dp) :: factor

        self%dt_next = dt
        if (err >= 0.0_dp .and. .not. self%no_growth) then
            factor = self%growth_max
            if (err > 0.0_dp) factor = min(self%growth_max, SAFETY * err**(-1.0_dp / real(self%order + 1, dp)))
            if (factor >= GROWTH_MIN) self%dt_next = min(dt * factor, self%dt_max)
        end if
        self%dt_next = max(self%dt_next, self%dt_min)
        self%no_growth = .false.
    end subroutine controller_accept

    !> A step of size dt was rejected with error ratio err > 1: the retry.
    subroutine controller_reject(self, dt, err)
        class(step_controller_t), intent(inout) :: self
        real(dp), intent(in) :: dt, err

        self%n_rejected = self%n_rejected + 1
        self%dt_next = max(dt * max(SHRINK_MIN, min(SAFETY, SAFETY * err**(-1.0_dp / real(self%order + 1, dp)))), &
                           self%dt_min)
        self%no_growth = .true.
    end subroutine controller_reject

    ! ------------------------------------------------------------------ checkpoint

    !> Everything controller and estimator need to continue exactly: scalars into values
    !> (N_CONTROL_VALUES) and the estimator's levels, most recent first, into history
    !> (s+1, (1+N_FIELDS) MAX_LEVELS).
    subroutine pack_control(control, estimator, values, history)
        type(step_controller_t), intent(in) :: control
        type(error_estimator_t), intent(in) :: estimator
        real(dp), intent(out) :: values(N_CONTROL_VALUES)
        real(dp), intent(out) :: history(:, :)
        integer :: j, slot, width

        values = 0.0_dp
        values(1:7) = [control%dt_next, merge(1.0_dp, 0.0_dp, control%no_growth), control%scale, &
                       control%error_sum, real(control%n_estimated, dp), real(control%n_rejected, dp), &
                       real(control%n_forced, dp)]
        values(8) = real(estimator%n_levels, dp)
        width = 1 + N_FIELDS
        history = 0.0_dp
        do j = 1, estimator%n_levels
            slot = level_slot(estimator%head, j)
            values(8 + j) = estimator%steps(slot)
            history(:, (j - 1) * width + 1:j * width) = estimator%levels(:, :, slot)
        end do
    end subroutine pack_control

    !> The inverse of pack_control (control and estimator initialised for this run).
    subroutine unpack_control(values, history, control, estimator)
        real(dp), intent(in) :: values(N_CONTROL_VALUES)
        real(dp), intent(in) :: history(:, :)
        type(step_controller_t), intent(inout) :: control
        type(error_estimator_t), intent(inout) :: estimator
        integer :: j, width

        control%dt_next = values(1)
        control%no_growth = values(2) > 0.0_dp
        control%scale = values(3)
        control%error_sum = values(4)
        control%n_estimated = nint(values(5))
        control%n_rejected = nint(values(6))
        control%n_forced = nint(values(7))
        width = 1 + N_FIELDS
        call estimator%reset()
        do j = nint(values(8)), 1, -1
            call estimator%push(history(:, (j - 1) * width + 1), history(:, (j - 1) * width + 2:j * width), &
                                values(8 + j))
        end do
    end subroutine unpack_control

end module step_control_m
