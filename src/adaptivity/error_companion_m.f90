!> The built-in error estimate of a run (&output error_estimate = .true.; docs/scheme.md,
!> "The error estimate of a run"): companion solutions integrated beside the run on coarser
!> meshes with longer steps, and Richardson extrapolation with observed orders.
!>
!> The run X computes on s elements (size h) with steps dt. Beside it:
!>   A at (2 dt, 2 h)   every other node;   C at (4 dt, 4 h)   every fourth node;
!>   D at (8 dt, 4 h)   C's mesh.
!> Total (time and space together), per field: X, A, C refine dt and h together by 2; with
!> d1 = |A - X| and d2 = |C - A| at their common nodes the observed order is
!> r = log2(d2 / d1) (clamped to [ORDER_MIN, ORDER_MAX]) and the error of X is
!> (A - X) / (2^r - 1) on A's nodes (Richardson; scaled up to the size d2 / (2^r (2^r - 1))
!> of the coarse pair's extrapolation when d1 is smaller than that, as it is when r is
!> clamped at ORDER_MAX: a fine difference that nearly vanishes by chance, e.g. at a kink
!> that moves). Observed, not nominal: at a usual
!> resolution several fields converge at order ~1 (initial layers of the stiff modes, the
!> coupling), where the nominal order 2 underestimates 3x.
!> Time part: C and D differ in dt alone; with p_t = min(p, r) (p the scheme's order: the
!> time error converges no faster than the scheme, nor than the whole) the time error of X
!> is (D - C) / (4^p_t (2^p_t - 1)) on C's nodes. Space part: what the total leaves beyond
!> the time part, sqrt(total^2 - time^2) (0 when the time part is larger).
!> The relative errors are L2 norms over the rod (trapezoidal rule on the companion's
!> nodes) over the field's L2 norm on the same nodes.
!> Steps: a companion of k (2, 4, 8) takes each step over k consecutive steps of the run
!> (their sum), and lands on every snapshot with a step over the run's last k steps: the
!> run's steps wait in a queue, and when 3k are queued the first k go into one step; at a
!> snapshot the L queued steps go into one step over the last k and, before it, the r = L - k
!> others in one step (r <= k) or two (k < r < 2k: r/2 and the rest). With the run's steps
!> of any count between snapshots (odd, adaptive landing steps) every companion's last step
!> is over the run's last k, and each of its steps over k/2 to k of the run's (fewer only
!> where the run takes fewer than 2k steps between two snapshots): the midpoint rule's
!> algebraic fields (v, whose value is that of the last half step: an error dt_last/2 v_t)
!> and BDF2's step ratios (within [1/2, 2]) scale as Richardson assumes.
!> Cost: A a quarter of the run's solves, C a sixteenth, D a thirty-second (docs/scheme.md
!> has the measurement); the companions' steps skip the stepper's per-step finiteness test
!> (a non-finite value stays non-finite: the estimate tests the companions' levels).
!> Uniform meshes of a multiple of 4 elements only (validate_m).
module error_companion_m
    use kinds_m, only: dp
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
    use config_m, only: config_t
    use fields_m, only: N_FIELDS, N_OUTPUT_FIELDS, OUTPUT_ORDER
    use state_m, only: state_t, initial_state, field_values, land_on
    use stepper_m, only: stepper_t, step_result_t
    use sources_m, only: source_t
    use checkpoint_m, only: checkpoint_t
    use errors_m, only: check_allocation, fatal, EXIT_INPUT
    implicit none
    private
    public :: error_companions_t, N_ESTIMATE_PARTS, PART_TOTAL, PART_TIME, PART_SPACE, &
              N_COMPANION_SCALARS

    integer, parameter :: N_COMPANIONS = 3
    integer, parameter :: COMP_A = 1, COMP_C = 2, COMP_D = 3
    !> steps of the run per step of companion A, C, D
    integer, parameter :: STEPS_PER_STEP(N_COMPANIONS) = [2, 4, 8]
    !> elements of the run per element of companion A, C, D
    integer, parameter :: ELEMENTS_PER_ELEMENT(N_COMPANIONS) = [2, 4, 4]
    !> observed orders are clamped to this range (below: not converging; above: cancellation)
    real(dp), parameter :: ORDER_MIN = 0.5_dp, ORDER_MAX = 2.0_dp
    !> the estimate's parts: total, time, space
    character(len=*), parameter :: NAMES = 'ACD'
    integer, parameter :: PART_TOTAL = 1, PART_TIME = 2, PART_SPACE = 3, N_ESTIMATE_PARTS = 3
    !> the run's steps a companion holds at most (3 k: the module's header)
    integer, parameter :: QUEUE_MAX = 3 * maxval(STEPS_PER_STEP)
    !> a companion's scalars in a checkpoint: step, t, dt_last, t_anchor, step_anchor,
    !> n_queued, n_solves, whether it holds a previous level, then the queue's step sizes
    !> and end times
    integer, parameter :: SCALARS_HEAD = 8
    integer, parameter :: SCALARS_PER_COMPANION = SCALARS_HEAD + 2 * QUEUE_MAX
    integer, parameter :: N_COMPANION_SCALARS = N_COMPANIONS * SCALARS_PER_COMPANION + 1

    !> One companion solution on its own mesh, with its own steps.
    type :: companion_t
        integer :: steps_per_step = 2      !< k: steps of the run per step of the companion
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        !> the run's steps since the companion's last step: their sizes and end times
        integer :: n_queued = 0
        real(dp) :: queue_dt(QUEUE_MAX) = 0.0_dp, queue_t(QUEUE_MAX) = 0.0_dp
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
        !> the last estimate (values(k, part): field OUTPUT_ORDER(k))
        real(dp) :: last(N_OUTPUT_FIELDS, N_ESTIMATE_PARTS) = 0.0_dp
    contains
        procedure :: init => companions_init
        procedure :: follow => companions_follow
        procedure :: estimate => companions_estimate
        procedure :: save_checkpoint => companions_save_checkpoint
        procedure :: restore_checkpoint => companions_restore_checkpoint
    end type error_companions_t

contains

    !> Companions for the run cfg (validated: a uniform mesh of a multiple of 4 elements),
    !> from the run's initial level `initial` (its values at their nodes); source: the run's
    !> source terms (manufactured solutions).
    subroutine companions_init(self, cfg, initial, source)
        class(error_companions_t), intent(out) :: self
        type(config_t), intent(in) :: cfg
        type(state_t), intent(in) :: initial
        class(source_t), intent(in), optional :: source
        type(config_t) :: coarse
        integer :: j, k

        self%on = .true.
        if (.not. cfg%time%adaptive) self%dt_fixed = cfg%time%dt
        coarse = cfg
        do j = 1, N_COMPANIONS
            associate (c => self%pair(j))
                c%steps_per_step = STEPS_PER_STEP(j)
                k = ELEMENTS_PER_ELEMENT(j)
                coarse%mesh%n_elements = cfg%mesh%n_elements / k
                coarse%time%dt = real(c%steps_per_step, dp) * cfg%time%dt
                call initial_state(coarse, c%state)
                c%state%u = initial%u(0::k)
                c%state%w = initial%w(0::k, :)
                call c%stepper%init(coarse, c%result, source)
                ! a non-finite level stays so: companions_estimate tests it once per snapshot
                c%stepper%check_finite = .false.
                if (.not. c%result%ok) call stop_companions(self, 'setting up companion '//NAMES(j:j)// &
                                                            ': '//trim(c%result%message))
            end associate
        end do
        self%p = self%pair(COMP_A)%stepper%scheme%order()
    end subroutine companions_init

    !> The run has accepted a step (state: its new level): into each companion's queue; a
    !> companion with 3 k queued steps takes one step over the first k.
    subroutine companions_follow(self, state)
        class(error_companions_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        integer :: j

        do j = 1, N_COMPANIONS
            associate (c => self%pair(j))
                c%n_queued = c%n_queued + 1
                c%queue_dt(c%n_queued) = state%dt_last
                c%queue_t(c%n_queued) = state%t
                if (c%n_queued == 3 * c%steps_per_step) call step_over(self, j, c%steps_per_step)
            end associate
        end do
    end subroutine companions_follow

    !> The run is at a snapshot (its last step queued): every companion lands on it, with one
    !> step over the run's last k steps, and the r steps queued before them in one step (r <= k)
    !> or two of r/2 (k < r < 2k).
    subroutine companions_land(self)
        type(error_companions_t), intent(inout) :: self
        integer :: j, r

        do j = 1, N_COMPANIONS
            associate (c => self%pair(j))
                r = c%n_queued - c%steps_per_step
                if (r > c%steps_per_step) call step_over(self, j, r / 2)
                if (c%n_queued > c%steps_per_step) call step_over(self, j, c%n_queued - c%steps_per_step)
                if (c%n_queued > 0) call step_over(self, j, c%n_queued)
            end associate
        end do
    end subroutine companions_land

    !> Companion j takes one step over the first m steps of its queue (to the end time of the
    !> m-th), and drops them from the queue.
    subroutine step_over(self, j, m)
        type(error_companions_t), intent(inout) :: self
        integer, intent(in) :: j, m
        real(dp) :: dt
        integer :: n

        associate (c => self%pair(j))
            if (.not. self%failed) then
                ! fixed steps: exactly m dt, so that every step of m reuses one factored system
                if (self%dt_fixed > 0.0_dp) then
                    dt = real(m, dp) * self%dt_fixed
                else
                    dt = sum(c%queue_dt(1:m))
                end if
                call c%stepper%advance(c%state, c%result, dt)
                if (c%result%ok) then
                    call land_on(c%state, c%queue_t(m))
                else
                    call stop_companions(self, 'companion '//NAMES(j:j)//': '//trim(c%result%message))
                end if
            end if
            n = c%n_queued - m
            c%queue_dt(1:n) = c%queue_dt(m + 1:c%n_queued)
            c%queue_t(1:n) = c%queue_t(m + 1:c%n_queued)
            c%n_queued = n
        end associate
    end subroutine step_over

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
        real(dp) :: x(0:state%s), a(0:state%s / 2), total(0:state%s / 2)
        real(dp), dimension(0:state%s / 4) :: c, d, time
        real(dp) :: r, p_t, d1, d2
        integer :: k

        call companions_land(self)
        do k = 1, N_COMPANIONS
            associate (st => self%pair(k)%state)
                if (.not. (all(ieee_is_finite(st%u)) .and. all(ieee_is_finite(st%w)))) &
                    call stop_companions(self, 'companion '//NAMES(k:k)//': non-finite value in the solution')
            end associate
        end do
        if (self%failed) then
            values = ieee_value(1.0_dp, ieee_quiet_nan)
            self%last = values
            return
        end if
        do k = 1, N_OUTPUT_FIELDS
            x = field_values(state, OUTPUT_ORDER(k))
            a = field_values(self%pair(COMP_A)%state, OUTPUT_ORDER(k))
            c = field_values(self%pair(COMP_C)%state, OUTPUT_ORDER(k))
            d = field_values(self%pair(COMP_D)%state, OUTPUT_ORDER(k))
            d1 = l2_norm(a(0::2) - x(0::4))
            d2 = l2_norm(c - a(0::2))
            r = observed_order(d1, d2)
            ! a fine difference smaller than the coarse one allows (r clamped at ORDER_MAX):
            ! the coarse pair's extrapolation, d2 / 2^r, is the estimate's size
            total = (a - x(0::2)) / (2.0_dp**r - 1.0_dp)
            if (d2 / 2.0_dp**r > d1) total = total * (d2 / 2.0_dp**r / d1)
            p_t = min(real(self%p, dp), r)
            time = (d - c) / (4.0_dp**p_t * (2.0_dp**p_t - 1.0_dp))
            values(k, PART_TOTAL) = relative(l2_norm(total), l2_norm(x(0::2)))
            values(k, PART_TIME) = relative(l2_norm(time), l2_norm(x(0::4)))
            values(k, PART_SPACE) = sqrt(max(values(k, PART_TOTAL)**2 - values(k, PART_TIME)**2, 0.0_dp))
        end do
        self%last = values
    end subroutine companions_estimate

    !> log2(coarse / fine) of two successive differences of a ladder refined by 2, clamped to
    !> [ORDER_MIN, ORDER_MAX] (ORDER_MIN: also when they vanish).
    pure real(dp) function observed_order(fine, coarse) result(order)
        real(dp), intent(in) :: fine, coarse

        order = ORDER_MIN
        if (fine > 0.0_dp .and. coarse > 0.0_dp) &
            order = min(max(log(coarse / fine) / log(2.0_dp), ORDER_MIN), ORDER_MAX)
    end function observed_order

    !> The L2 norm over the rod of the P1 function with nodal values x on a uniform mesh,
    !> up to the factor sqrt(h) (the trapezoidal rule; the factor cancels in a ratio).
    pure real(dp) function l2_norm(x)
        real(dp), intent(in) :: x(0:)
        integer :: n

        n = ubound(x, 1)
        l2_norm = sqrt(max(sum(x**2) - 0.5_dp * (x(0)**2 + x(n)**2), 0.0_dp))
    end function l2_norm

    !> error / norm; 0 for a field that is zero at every node (a field left out of the
    !> system, or u at t = 0: the companions hold the same zeros).
    pure real(dp) function relative(error, norm)
        real(dp), intent(in) :: error, norm

        relative = 0.0_dp
        if (norm > 0.0_dp) relative = error / norm
    end function relative

    !> The companions' levels (and the levels before, for a multistep scheme) and scalars
    !> into a checkpoint: companion_levels (s/2+1, (1+N_FIELDS) x 2 per companion: level,
    !> previous level or zeros; a companion on fewer nodes in the leading rows),
    !> companion_scalars (SCALARS_PER_COMPANION per companion, then whether they failed).
    subroutine companions_save_checkpoint(self, ckpt)
        class(error_companions_t), intent(in) :: self
        type(checkpoint_t), intent(inout) :: ckpt
        integer :: j, col, width, n, stat
        character(len=256) :: message

        width = 1 + N_FIELDS
        if (allocated(ckpt%companion_levels)) deallocate (ckpt%companion_levels)
        if (allocated(ckpt%companion_scalars)) deallocate (ckpt%companion_scalars)
        allocate (ckpt%companion_levels(self%pair(1)%state%s + 1, 2 * width * N_COMPANIONS), &
                  ckpt%companion_scalars(N_COMPANION_SCALARS), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the checkpoint of the error estimate')
        ckpt%companion_levels = 0.0_dp
        do j = 1, N_COMPANIONS
            associate (c => self%pair(j), st => self%pair(j)%state)
                col = (j - 1) * 2 * width
                n = st%s + 1
                ckpt%companion_levels(1:n, col + 1) = st%u
                ckpt%companion_levels(1:n, col + 2:col + width) = st%w
                if (allocated(st%u_prev)) then
                    ckpt%companion_levels(1:n, col + width + 1) = st%u_prev
                    ckpt%companion_levels(1:n, col + width + 2:col + 2 * width) = st%w_prev
                end if
                ckpt%companion_scalars((j - 1) * SCALARS_PER_COMPANION + 1:j * SCALARS_PER_COMPANION) = &
                    [real(st%step, dp), st%t, st%dt_last, st%t_anchor, real(st%step_anchor, dp), &
                     real(c%n_queued, dp), real(c%stepper%n_solves, dp), &
                     merge(1.0_dp, 0.0_dp, allocated(st%u_prev)), c%queue_dt, c%queue_t]
            end associate
        end do
        ckpt%companion_scalars(N_COMPANION_SCALARS) = merge(1.0_dp, 0.0_dp, self%failed)
    end subroutine companions_save_checkpoint

    !> The inverse of save_checkpoint (on companions initialised for this run).
    subroutine companions_restore_checkpoint(self, ckpt)
        class(error_companions_t), intent(inout) :: self
        type(checkpoint_t), intent(in) :: ckpt
        integer :: j, col, width, n, stat
        character(len=256) :: message
        real(dp) :: scalars(SCALARS_PER_COMPANION)

        if (size(ckpt%companion_scalars) /= N_COMPANION_SCALARS) &
            call fatal(EXIT_INPUT, 'restart', 'the checkpoint''s error-estimate companions are of another '// &
                       'version of rodcontact (companion_scalars has the wrong length): restart without '// &
                       'output.error_estimate, or from a checkpoint of this version')
        width = 1 + N_FIELDS
        do j = 1, N_COMPANIONS
            associate (c => self%pair(j), st => self%pair(j)%state)
                col = (j - 1) * 2 * width
                scalars = ckpt%companion_scalars((j - 1) * SCALARS_PER_COMPANION + 1:j * SCALARS_PER_COMPANION)
                n = st%s + 1
                st%u = ckpt%companion_levels(1:n, col + 1)
                st%w = ckpt%companion_levels(1:n, col + 2:col + width)
                if (scalars(8) > 0.0_dp) then
                    if (.not. allocated(st%u_prev)) then
                        allocate (st%u_prev(0:n - 1), st%w_prev(0:n - 1, N_FIELDS), stat=stat, errmsg=message)
                        call check_allocation(stat, message, 'the error estimate''s previous level')
                    end if
                    st%u_prev = ckpt%companion_levels(1:n, col + width + 1)
                    st%w_prev = ckpt%companion_levels(1:n, col + width + 2:col + 2 * width)
                end if
                st%step = nint(scalars(1))
                st%t = scalars(2)
                st%dt_last = scalars(3)
                st%t_anchor = scalars(4)
                st%step_anchor = nint(scalars(5))
                c%n_queued = nint(scalars(6))
                c%stepper%n_solves = nint(scalars(7), kind(c%stepper%n_solves))
                c%queue_dt = scalars(SCALARS_HEAD + 1:SCALARS_HEAD + QUEUE_MAX)
                c%queue_t = scalars(SCALARS_HEAD + QUEUE_MAX + 1:)
            end associate
        end do
        if (ckpt%companion_scalars(N_COMPANION_SCALARS) > 0.0_dp) &
            call stop_companions(self, 'failed before the checkpoint')
    end subroutine companions_restore_checkpoint

end module error_companion_m
