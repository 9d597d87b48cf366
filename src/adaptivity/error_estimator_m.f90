!> The local error estimate of adaptive time steps (&time adaptive = .true.): the
!> predictor-corrector difference of the BDF codes, est_n = factor * |X^n - P^n|_E, P^n the
!> polynomial of degree p through the last p+1 accepted levels extrapolated to t_n, factor
!> time_scheme_m's error_factor, |X|_E = sqrt(2 E_lin(X)) (Corollary 6.2's energy) over all
!> fields at once: no solve. Why this one: docs/scheme.md, "Adaptive time steps".
!> The levels are a ring; callers reach the j-th most recent through slot(j), step(j) and
!> times(t, n), never through the ring's index.
module error_estimator_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fields_m, only: N_FIELDS
    use energy_m, only: discrete_energy
    use mesh_m, only: mesh_t
    use errors_m, only: check_allocation
    use time_scheme_m, only: time_scheme_t
    use checkpoint_m, only: checkpoint_t
    implicit none
    private
    public :: error_estimator_t, MAX_LEVELS, energy_norm

    integer, parameter :: MAX_LEVELS = 3       !< past levels kept (p + 1 for p <= 2)

    !> The last accepted levels, most recent first, with the steps that reached them.
    type :: error_estimator_t
        type(time_scheme_t) :: scheme
        integer :: order = 1               !< p: the scheme's order
        integer :: n_levels = 0            !< levels held (0..order+1)
        integer, private :: head = 1       !< slot of the most recent level (slot(1))
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
        procedure :: slot => estimator_slot
        procedure :: step => estimator_step
        procedure :: times => estimator_times
        procedure :: checkpoint => estimator_checkpoint
    end type error_estimator_t

contains

    !> An estimator for `scheme` on s elements.
    subroutine estimator_init(self, scheme, s)
        class(error_estimator_t), intent(out) :: self
        type(time_scheme_t), intent(in) :: scheme
        integer, intent(in) :: s

        self%scheme = scheme
        self%order = scheme%row%order
        call self%resize(s)
    end subroutine estimator_init

    !> Arrays for a mesh of s elements (the levels held are lost: a remesh moves them
    !> first, step_driver_m's remesh).
    subroutine estimator_resize(self, s)
        class(error_estimator_t), intent(inout) :: self
        integer, intent(in) :: s
        integer :: stat
        character(len=256) :: message

        if (allocated(self%levels)) deallocate (self%levels, self%u_diff, self%w_diff)
        allocate (self%levels(0:s, 0:N_FIELDS, MAX_LEVELS), self%u_diff(0:s), self%w_diff(0:s, N_FIELDS), stat=stat, &
                  errmsg=message)
        call check_allocation(stat, message, 'the error estimator''s levels')
        self%levels = 0.0_dp
    end subroutine estimator_resize

    !> Forget the levels for the estimate (after a contact event: the solution is not smooth
    !> across it). The stored levels stay: the step driver takes a rejected step's state back
    !> from the newest (always the run's level) and dense output's line after an event from the
    !> second (step_driver_m's dense_level).
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
            d(j) = d(j - 1) + self%step(j - 1)
        end do
        ! Lagrange weights of the extrapolation to t_n from t_n - d_j
        do j = 1, n
            weight(j) = 1.0_dp
            do k = 1, n
                if (k /= j) weight(j) = weight(j) * d(k) / (d(k) - d(j))
            end do
        end do
        call extrapolation_difference(self, u, w, weight(1:n))
        call discrete_energy(model, self%u_diff, self%w_diff, mesh, energy)
        est = self%scheme%error_factor(d(1:n), self%step(1)) * energy_norm(energy)
    end function estimator_estimate

    !> u_diff, w_diff = X^n - P^n, P^n = sum_j weight(j) X^{n-j} over the p + 1 <= 3 levels
    !> held (the newest first), the terms subtracted in the order j = 1, 2, ...: one pass over
    !> the nodes per field (why, and Euler's own loop: docs/performance.md).
    subroutine extrapolation_difference(self, u, w, weight)
        type(error_estimator_t), intent(inout) :: self
        real(dp), intent(in) :: u(0:), w(0:, :)
        real(dp), intent(in) :: weight(:)
        integer :: f, j, slot(MAX_LEVELS)

        slot = [(self%slot(j), j = 1, MAX_LEVELS)]
        call subtract(u, 0, self%u_diff)
        do f = 1, N_FIELDS
            call subtract(w(:, f), f, self%w_diff(:, f))
        end do

    contains

        !> diff = x - P^n's field f (0: u), unrolled (GCC's directive; a comment to other
        !> compilers; docs/performance.md).
        subroutine subtract(x, f, diff)
            real(dp), intent(in) :: x(0:)
            integer, intent(in) :: f
            real(dp), intent(out) :: diff(0:)
            integer :: i

            associate (l => self%levels, c => weight, k1 => slot(1), k2 => slot(2), k3 => slot(3))
                if (size(weight) == 3) then
                    !GCC$ unroll 4
                    do i = 0, ubound(x, 1)
                        diff(i) = ((x(i) - c(1) * l(i, f, k1)) - c(2) * l(i, f, k2)) - c(3) * l(i, f, k3)
                    end do
                else   ! Euler (p = 1): the same sums over two levels
                    !GCC$ unroll 8
                    do i = 0, ubound(x, 1)
                        diff(i) = (x(i) - c(1) * l(i, f, k1)) - c(2) * l(i, f, k2)
                    end do
                end if
            end associate
        end subroutine subtract
    end subroutine extrapolation_difference

    !> |X|_E = sqrt(2 E) of an energy E (Corollary 6.2).
    pure real(dp) function energy_norm(energy)
        real(dp), intent(in) :: energy

        energy_norm = sqrt(2.0_dp * max(energy, 0.0_dp))
    end function energy_norm

    !> The slot of levels(:, :, slot) holding the j-th most recent level (j = 1: the newest).
    pure integer function estimator_slot(self, j) result(slot)
        class(error_estimator_t), intent(in) :: self
        integer, intent(in) :: j

        slot = modulo(self%head - j, MAX_LEVELS) + 1
    end function estimator_slot

    !> The step that reached the j-th most recent level.
    pure real(dp) function estimator_step(self, j) result(dt)
        class(error_estimator_t), intent(in) :: self
        integer, intent(in) :: j

        dt = self%steps(self%slot(j))
    end function estimator_step

    !> The times of the n >= 1 most recent levels, the newest at t_newest.
    pure function estimator_times(self, t_newest, n) result(times)
        class(error_estimator_t), intent(in) :: self
        real(dp), intent(in) :: t_newest
        integer, intent(in) :: n
        real(dp) :: times(n)
        integer :: j

        times(1) = t_newest
        do j = 2, n
            times(j) = times(j - 1) - self%step(j - 1)
        end do
    end function estimator_times

    ! ------------------------------------------------------------------ checkpoint

    !> The estimator's levels into a checkpoint, most recent first: error_estimator/levels
    !> (s+1, (1+N_FIELDS) MAX_LEVELS; unused ones zero) and steps (the step that reached each);
    !> or back from one (checkpoint_m's reading; the arrays take the checkpoint's mesh).
    subroutine estimator_checkpoint(self, ckpt)
        class(error_estimator_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt
        real(dp), allocatable :: levels(:, :), steps(:)
        integer :: j, width, stat
        character(len=256) :: message

        width = 1 + N_FIELDS
        if (.not. ckpt%reading) then
            allocate (levels(size(self%levels, 1), width * MAX_LEVELS), steps(self%n_levels), source=0.0_dp, &
                      stat=stat, errmsg=message)
            call check_allocation(stat, message, 'the checkpoint of the error estimator')
            do j = 1, self%n_levels
                steps(j) = self%step(j)
                levels(:, (j - 1) * width + 1:j * width) = self%levels(:, :, self%slot(j))
            end do
        end if
        call ckpt%sync('error_estimator/levels', levels)
        call ckpt%sync('error_estimator/steps', steps)
        if (.not. ckpt%reading) return
        call self%resize(size(levels, 1) - 1)
        call self%reset()
        do j = size(steps), 1, -1
            call self%push(levels(:, (j - 1) * width + 1), levels(:, (j - 1) * width + 2:j * width), &
                           steps(j))
        end do
    end subroutine estimator_checkpoint

end module error_estimator_m
