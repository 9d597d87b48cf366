!> The built-in error estimate of a run (&output error_estimate = .true.): companion solutions
!> integrated beside the run X (s elements of size h, steps dt) on coarser meshes with longer
!> steps, A at (2 dt, 2 h) on every other node, C at (4 dt, 4 h) on every fourth, D at
!> (8 dt, 4 h) on C's mesh, and Richardson extrapolation with observed orders (clamped to
!> [ORDER_MIN, ORDER_MAX]): the total from X, A, C, the time part from C, D, the space part
!> what the total leaves. The formulas, the reasons and the measurements: docs/scheme.md,
!> "The error estimate of a run". A companion of k (2, 4, 8) steps over k of the run's
!> (companions_follow, companions_land); on an adaptive mesh (&mesh adaptive) each has its own
!> bisection mesh, nested in the run's (companion_mesh_m).
module error_companion_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
    use config_m, only: config_t
    use fields_m, only: N_OUTPUT_FIELDS, OUTPUT_ORDER
    use state_m, only: state_t, initial_state, field_values, land_on, copy_state
    use stepper_m, only: stepper_t, step_result_t
    use sources_m, only: source_t
    use checkpoint_m, only: checkpoint_t
    use errors_m, only: fatal, EXIT_INPUT
    use adaptive_mesh_m, only: nodes_of_keys
    use companion_mesh_m, only: companion_keys, key_positions, trapezoid_weights
    use transfer_m, only: move_state
    implicit none
    private
    public :: error_companions_t, N_ESTIMATE_PARTS, PART_TOTAL, PART_TIME, PART_SPACE

    integer, parameter :: N_COMPANIONS = 3
    integer, parameter :: COMP_A = 1, COMP_C = 2, COMP_D = 3
    !> steps of the run per step of companion A, C, D
    integer, parameter :: STEPS_PER_STEP(N_COMPANIONS) = [2, 4, 8]
    !> elements of the run per element of companion A, C, D
    integer, parameter :: ELEMENTS_PER_ELEMENT(N_COMPANIONS) = [2, 4, 4]
    !> observed orders are clamped to this range (below: not converging; above: cancellation)
    real(dp), parameter :: ORDER_MIN = 0.5_dp, ORDER_MAX = 2.0_dp
    character(len=*), parameter :: NAMES = 'ACD'
    !> the estimate's parts: total, time, space
    integer, parameter :: PART_TOTAL = 1, PART_TIME = 2, PART_SPACE = 3, N_ESTIMATE_PARTS = 3
    !> a companion lands itself on a snapshot LAND_SPAN k or more run steps after the last
    integer, parameter :: LAND_SPAN = 8
    !> the run's steps a companion holds at most (3 k: companions_follow)
    integer, parameter :: QUEUE_MAX = 3 * maxval(STEPS_PER_STEP)
    !> One companion solution on its own mesh, with its own steps.
    type :: companion_t
        type(state_t) :: state
        !> the level landed on the last snapshot (companions_land)
        type(state_t) :: ahead
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        !> the run's steps since the companion's last step: their sizes and end times
        integer :: n_queued = 0
        real(dp), allocatable :: queue_dt(:), queue_t(:)
        !> an adaptive mesh: the companion's node keys (companion_mesh_m)
        integer(int64), allocatable :: k(:)
    end type companion_t

    !> The companions of a run and its last estimate.
    type :: error_companions_t
        logical :: on = .false.
        integer :: p = 1                   !< the scheme's order
        real(dp) :: dt_fixed = 0.0_dp      !< &time dt of fixed steps (0: adaptive steps)
        type(companion_t) :: pair(N_COMPANIONS)
        !> a companion has stopped (failure says why): the estimates are NaN from then on
        logical :: failed = .false.
        character(len=320) :: failure = ''
        integer :: n_since = 0             !< the run's steps since the last snapshot
        !> the last estimate (values(k, part): field OUTPUT_ORDER(k))
        real(dp) :: last(N_OUTPUT_FIELDS, N_ESTIMATE_PARTS) = 0.0_dp
        !> an adaptive mesh (k_run allocated only then): the run's coarse and finest elements, keys
        integer :: n_coarse = 0
        integer(int64) :: n_fine = 0
        integer(int64), allocatable :: k_run(:)
    contains
        procedure :: init => companions_init
        procedure :: remesh => companions_remesh
        procedure :: follow => companions_follow
        procedure :: estimate => companions_estimate
        procedure :: checkpoint => companions_checkpoint
    end type error_companions_t

contains

    !> Companions for the run cfg (validated: a mesh of a multiple of 4 elements), from the
    !> run's initial level `initial` (its values at their nodes); source: the run's source
    !> terms (manufactured solutions); keys: the node keys of the run's adaptive mesh
    !> (adaptive_mesh_m; absent: a uniform mesh).
    subroutine companions_init(self, cfg, initial, source, keys)
        class(error_companions_t), intent(out) :: self
        type(config_t), intent(in) :: cfg
        type(state_t), intent(in) :: initial
        class(source_t), intent(in), optional :: source
        integer(int64), intent(in), optional :: keys(0:)
        type(config_t) :: coarse
        integer, allocatable :: on_run(:)
        integer :: i, j, k

        self%on = .true.
        if (.not. cfg%time%adaptive) self%dt_fixed = cfg%time%dt
        if (present(keys)) then
            self%n_coarse = cfg%mesh%n_elements
            self%n_fine = int(cfg%mesh%n_elements, int64) * 2_int64**cfg%mesh%max_level
            self%k_run = keys
        end if
        coarse = cfg
        do j = 1, N_COMPANIONS
            associate (c => self%pair(j))
                k = ELEMENTS_PER_ELEMENT(j)
                coarse%mesh%n_elements = cfg%mesh%n_elements / k
                coarse%time%dt = real(STEPS_PER_STEP(j), dp) * cfg%time%dt
                if (present(keys)) then   ! its own mesh, nested in the run's (companion_mesh_m)
                    call companion_keys(keys, self%n_coarse, self%n_fine, k, c%k)
                    call initial_state(coarse, c%state, nodes_of_keys(c%k, self%n_fine))
                    on_run = key_positions(c%k, keys)
                else
                    call initial_state(coarse, c%state)
                    on_run = [(k * i, i = 0, c%state%s)]
                end if
                c%state%u = initial%u(on_run)
                c%state%w = initial%w(on_run, :)
                c%queue_dt = spread(0.0_dp, 1, QUEUE_MAX)
                c%queue_t = c%queue_dt
                call c%stepper%init(coarse, c%result, source)
                if (present(keys)) call c%stepper%remesh(c%state)
                ! a non-finite level stays so: companions_estimate tests it once per snapshot
                c%stepper%check_finite = .false.
                if (.not. c%result%ok) call stop_companions(self, 'setting up companion '//NAMES(j:j)// &
                                                            ': '//trim(c%result%message))
            end associate
        end do
        self%p = self%pair(COMP_A)%stepper%scheme%row%order
    end subroutine companions_init

    !> The run has accepted a step (state: its new level): into each companion's queue; a
    !> companion with 3 k queued steps takes one step over the first k.
    subroutine companions_follow(self, state)
        class(error_companions_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        integer :: j

        self%n_since = self%n_since + 1
        do j = 1, N_COMPANIONS
            associate (c => self%pair(j))
                c%n_queued = c%n_queued + 1
                c%queue_dt(c%n_queued) = state%dt_last
                c%queue_t(c%n_queued) = state%t
                if (c%n_queued == 3 * STEPS_PER_STEP(j)) then
                    call step_over(self, j, c%state, 1, STEPS_PER_STEP(j))
                    call drop(c, STEPS_PER_STEP(j))
                end if
            end associate
        end do
    end subroutine companions_follow

    !> The run is at a snapshot (its last step queued): every companion lands on it, with one
    !> step over the run's last k steps, and the r steps queued before them in one step (r <= k)
    !> or two (k < r < 2k: r/2 and the rest). A companion lands itself (its queue empties) when
    !> the run has taken LAND_SPAN k steps or more since the last snapshot; otherwise a copy
    !> lands (the r steps in one step) and the companion goes on with its queue, so that its
    !> own steps stay over k of the run's. Either way the landed level is then in ahead.
    subroutine companions_land(self)
        type(error_companions_t), intent(inout) :: self
        integer :: j, k, r
        logical :: on_copy

        do j = 1, N_COMPANIONS
            associate (c => self%pair(j))
                k = STEPS_PER_STEP(j)
                on_copy = .not. (c%n_queued >= 2 * k .and. self%n_since >= LAND_SPAN * k)
                if (.not. on_copy) then
                    call land_level(c%state)
                    call drop(c, c%n_queued)
                end if
                call copy_state(c%state, c%ahead)
                call land_level(c%ahead)   ! (no step if the companion has landed itself)
            end associate
        end do
        self%n_since = 0

    contains

        !> Companion j's level (its state or the copy) over its whole queue.
        subroutine land_level(level)
            type(state_t), intent(inout) :: level

            integer :: first

            associate (c => self%pair(j))
                r = c%n_queued - k
                first = 1
                if (r > k .and. .not. on_copy) then
                    call step_over(self, j, level, 1, r / 2)
                    first = r / 2 + 1
                end if
                if (r > 0) call step_over(self, j, level, first, r)
                if (c%n_queued > 0) call step_over(self, j, level, max(r, 0) + 1, c%n_queued)
            end associate
        end subroutine land_level
    end subroutine companions_land

    !> One step of companion j's stepper on level (its state or a copy) over the steps first
    !> to last of its queue (to the end time of the last).
    subroutine step_over(self, j, level, first, last)
        type(error_companions_t), intent(inout) :: self
        integer, intent(in) :: j, first, last
        type(state_t), intent(inout) :: level
        real(dp) :: dt

        if (self%failed) return
        associate (c => self%pair(j))
            ! fixed steps: exactly m dt, so that every step over m reuses one factored system
            if (self%dt_fixed > 0.0_dp) then
                dt = real(last - first + 1, dp) * self%dt_fixed
            else
                dt = sum(c%queue_dt(first:last))
            end if
            call c%stepper%advance(level, c%result, dt)
            if (c%result%ok) then
                call land_on(level, c%queue_t(last))
            else
                call stop_companions(self, 'companion '//NAMES(j:j)//': '//trim(c%result%message))
            end if
        end associate
    end subroutine step_over

    !> The first m steps of companion c's queue are done: out of the queue.
    pure subroutine drop(c, m)
        type(companion_t), intent(inout) :: c
        integer, intent(in) :: m
        integer :: n

        n = c%n_queued - m
        c%queue_dt(1:n) = c%queue_dt(m + 1:c%n_queued)
        c%queue_t(1:n) = c%queue_t(m + 1:c%n_queued)
        c%n_queued = n
    end subroutine drop

    !> A companion failed (message: why): the estimates are NaN from here on.
    subroutine stop_companions(self, message)
        type(error_companions_t), intent(inout) :: self
        character(len=*), intent(in) :: message

        if (self%failed) return
        self%failed = .true.
        self%failure = message
    end subroutine stop_companions

    !> The estimate for the run's level in state (a snapshot): values(k, part), the relative
    !> L2 error of field OUTPUT_ORDER(k), total, time and space part (the module's header);
    !> kept in self%last.
    subroutine companions_estimate(self, state, values)
        class(error_companions_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(out) :: values(N_OUTPUT_FIELDS, N_ESTIMATE_PARTS)
        integer :: k, i

        call companions_land(self)
        do k = 1, N_COMPANIONS
            associate (level => self%pair(k)%ahead)
                if (.not. (all(ieee_is_finite(level%u)) .and. all(ieee_is_finite(level%w)))) &
                    call stop_companions(self, 'companion '//NAMES(k:k)// &
                                         ': non-finite value in the solution')
            end associate
        end do
        if (self%failed) then
            values = ieee_value(1.0_dp, ieee_quiet_nan)
            self%last = values
            return
        end if
        if (allocated(self%k_run)) then   ! C's nodes are A's, A's are the run's (companion_mesh_m)
            associate (k_a => self%pair(COMP_A)%k, k_c => self%pair(COMP_C)%k)
                call extrapolate(self, state, key_positions(k_a, self%k_run), key_positions(k_c, self%k_run), &
                                 key_positions(k_c, k_a), values, trapezoid_weights(k_a), trapezoid_weights(k_c))
            end associate
        else   ! A's nodes are every other of the run's, C's every other of A's
            associate (s_a => self%pair(COMP_A)%state%s, s_c => self%pair(COMP_C)%state%s)
                call extrapolate(self, state, [(2 * i, i = 0, s_a)], [(4 * i, i = 0, s_c)], [(2 * i, i = 0, s_c)], &
                                 values)
            end associate
        end if
        self%last = values
    end subroutine companions_estimate

    !> The L2 norm over the rod of the P1 function with nodal values x by the trapezoidal rule:
    !> with weights (companion_mesh_m's trapezoid_weights), or on a uniform mesh (weights
    !> absent) up to the factor sqrt(h), which cancels in a ratio.
    pure real(dp) function norm(x, weights)
        real(dp), intent(in) :: x(0:)
        real(dp), intent(in), optional :: weights(0:)
        integer :: n

        if (present(weights)) then
            norm = sqrt(sum(weights * x**2))
        else
            n = ubound(x, 1)
            norm = sqrt(max(sum(x**2) - 0.5_dp * (x(0)**2 + x(n)**2), 0.0_dp))
        end if
    end function norm

    !> error / norm; 0 for a field that is zero at every node (a field left out of the
    !> system, or u at t = 0: the companions hold the same zeros).
    pure real(dp) function relative(error, norm)
        real(dp), intent(in) :: error, norm

        relative = 0.0_dp
        if (norm > 0.0_dp) relative = error / norm
    end function relative

    !> The companions into a checkpoint, or back from one (checkpoint_m's reading; on
    !> companions initialised for this run, an adaptive mesh's companion meshes first rebuilt
    !> from the run's), each under error_companions/<A|C|D>.
    subroutine companions_checkpoint(self, ckpt)
        class(error_companions_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt
        character(len=:), allocatable :: p
        integer(int64), allocatable :: keys(:)
        integer :: j

        if (allocated(self%k_run) .and. ckpt%reading) then   ! the companions' meshes for the run's
            call ckpt%sync('adaptive_mesh/keys', keys)
            call companions_remesh(self, keys)
        end if
        do j = 1, N_COMPANIONS
            associate (c => self%pair(j))
                p = 'error_companions/'//NAMES(j:j)
                call c%state%checkpoint(ckpt, p)
                if (c%state%s /= c%stepper%s) call fatal(EXIT_INPUT, 'restart', &
                    'the checkpoint''s error-estimate companion '//NAMES(j:j)//' does not fit its mesh')
                call ckpt%sync(p//'/n_solves', c%stepper%n_solves)
                call ckpt%sync(p//'/n_queued', c%n_queued)
                call ckpt%sync(p//'/queue_dt', c%queue_dt)
                call ckpt%sync(p//'/queue_t', c%queue_t)
                ! fewer than 3 k steps queued (companions_follow steps at 3 k), in QUEUE_MAX slots
                if (any([size(c%queue_dt), size(c%queue_t)] /= QUEUE_MAX) .or. c%n_queued < 0 &
                    .or. c%n_queued >= 3 * STEPS_PER_STEP(j)) call fatal(EXIT_INPUT, 'restart', &
                    'the checkpoint''s error-estimate companion '//NAMES(j:j)//' has a queue of another size')
            end associate
        end do
        call ckpt%sync('error_companions/failed', self%failed)
        call ckpt%sync('error_companions/n_since', self%n_since)
        if (self%failed .and. self%failure == '') self%failure = 'failed before the checkpoint'
    end subroutine companions_checkpoint

    !> The run's adaptive mesh has changed (keys: its new node keys): each companion onto its
    !> mesh for the new one (companion_mesh_m), its levels moved as the run's are (transfer_m's
    !> move_state); a companion whose mesh stays keeps its levels untouched. (A restart: before
    !> the checkpoint's levels are read.)
    subroutine companions_remesh(self, keys)
        class(error_companions_t), intent(inout) :: self
        integer(int64), intent(in) :: keys(0:)
        integer(int64), allocatable :: k_new(:)
        integer :: j

        self%k_run = keys
        do j = 1, N_COMPANIONS
            associate (c => self%pair(j))
                call companion_keys(keys, self%n_coarse, self%n_fine, ELEMENTS_PER_ELEMENT(j), &
                                    k_new)
                if (size(k_new) == size(c%k)) then
                    if (all(k_new == c%k)) cycle
                end if
                call move_state(c%k, k_new, self%n_fine, c%stepper, c%state)
                call move_alloc(k_new, c%k)
            end associate
        end do
    end subroutine companions_remesh

    !> The estimate (module header) of every field from the run's level (state) and the
    !> companions' landed levels: x_on_a, x_on_c the run's nodes at A's and C's, a_on_c A's
    !> at C's; weights_a, weights_c the trapezoidal rule's on A's and C's nodes (adaptive
    !> mesh; absent: a uniform mesh).
    subroutine extrapolate(self, state, x_on_a, x_on_c, a_on_c, values, weights_a, weights_c)
        type(error_companions_t), intent(in) :: self
        type(state_t), intent(in) :: state
        integer, intent(in) :: x_on_a(0:), x_on_c(0:), a_on_c(0:)
        real(dp), intent(out) :: values(N_OUTPUT_FIELDS, N_ESTIMATE_PARTS)
        real(dp), intent(in), optional :: weights_a(0:), weights_c(0:)
        real(dp), dimension(0:ubound(x_on_a, 1)) :: a, total
        real(dp), dimension(0:ubound(x_on_c, 1)) :: c, d, time
        real(dp) :: x(0:state%s)
        real(dp) :: r, p_t, d1, d2
        integer :: k

        do k = 1, N_OUTPUT_FIELDS
            x = field_values(state, OUTPUT_ORDER(k))
            a = field_values(self%pair(COMP_A)%ahead, OUTPUT_ORDER(k))
            c = field_values(self%pair(COMP_C)%ahead, OUTPUT_ORDER(k))
            d = field_values(self%pair(COMP_D)%ahead, OUTPUT_ORDER(k))
            d1 = norm(a(a_on_c) - x(x_on_c), weights_c)
            d2 = norm(c - a(a_on_c), weights_c)
            ! the observed order log2(d2 / d1), ORDER_MIN also when a difference vanishes
            r = ORDER_MIN
            if (d1 > 0.0_dp .and. d2 > 0.0_dp) &
                r = min(max(log(d2 / d1) / log(2.0_dp), ORDER_MIN), ORDER_MAX)
            ! a fine difference smaller than the coarse one allows (r clamped at ORDER_MAX):
            ! the coarse pair's extrapolation, d2 / 2^r, is the estimate's size
            total = (a - x(x_on_a)) / (2.0_dp**r - 1.0_dp)
            if (d2 / 2.0_dp**r > d1) total = total * (d2 / 2.0_dp**r / d1)
            p_t = min(real(self%p, dp), r)
            time = (d - c) / (4.0_dp**p_t * (2.0_dp**p_t - 1.0_dp))
            values(k, PART_TOTAL) = relative(norm(total, weights_a), norm(x(x_on_a), weights_a))
            values(k, PART_TIME) = relative(norm(time, weights_c), norm(x(x_on_c), weights_c))
            values(k, PART_SPACE) = sqrt(max(values(k, PART_TOTAL)**2 - values(k, PART_TIME)**2, &
                                             0.0_dp))
        end do
    end subroutine extrapolate

end module error_companion_m
