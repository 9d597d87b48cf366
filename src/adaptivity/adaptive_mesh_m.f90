!> The adaptive mesh of &mesh adaptive = .true.: bisection of the n_elements coarse elements
!> up to max_level times, refined where the error indicator is large and coarsened back where
!> the solution is smooth, neighbouring elements at most one level apart (2:1 grading). It
!> holds the refinement's own data (the node keys, the field scales); the solver's geometry is
!> the state's mesh_t, which adapt reads and the remesh (step_driver_m, with transfer_m) sets.
!>
!> Nodes are integers k_i in units of the finest possible element: x_i = k_i / n_fine, n_fine =
!> n_elements 2^max_level, is the same number whenever it is computed (a restart rebuilds the
!> mesh bit for bit), an element's level is max_level - log2(k_e - k_{e-1}), and x = 0 and x = 1
!> (the contact node) are nodes of every mesh.
!>
!> Indicators: the hierarchical details d_e (refine e above error_tol) and d_m (coarsen the
!> node m at or below error_tol / COARSEN_MARGIN), per unit length and relative to each field's
!> scale_f; the elements within `buffer` of one above error_tol are refined and kept. Formulas
!> and why: docs/scheme.md, "Adaptive mesh" ("Indicator: hierarchical").
module adaptive_mesh_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use fields_m, only: N_FIELDS
    use config_m, only: config_t, model_t
    use state_m, only: state_t, initial_state
    use errors_m, only: check_allocation
    use mesh_m, only: mesh_t
    use checkpoint_m, only: checkpoint_t
    implicit none
    private
    public :: adaptive_mesh_t, FRONT_CFL, front_speed, nodes_of_keys, initial_mesh

    !> Coarsen where the indicator is this many times below error_tol (hysteresis: a
    !> bisection halves the detail only about 4-fold, so the new node is not removed again).
    real(dp), parameter :: COARSEN_MARGIN = 4.0_dp
    !> With adaptive time steps a step moves a front at most this many of the smallest
    !> elements (step_driver_m), so that it stays on the fine elements kept around it.
    real(dp), parameter :: FRONT_CFL = 1.0_dp
    !> Fields are measured relative to their present L2 norm, but at least this fraction
    !> of the largest they have had.
    real(dp), parameter :: NORM_FLOOR = 1.0e-3_dp

    type :: adaptive_mesh_t
        integer :: n_coarse = 0                 !< &mesh n_elements
        integer :: max_level = 0                !< &mesh max_level
        integer :: buffer = 1                   !< elements kept fine around a large indicator
        real(dp) :: tol = 1.0e-3_dp             !< &mesh error_tol
        integer(int64) :: n_fine = 0            !< n_coarse 2^max_level
        integer(int64), allocatable :: k(:)     !< k(0:s): node i at x = k(i) / n_fine
        real(dp) :: scale(0:N_FIELDS) = 0.0_dp  !< largest L2 norm of each field so far
    contains
        procedure :: init => mesh_init
        procedure :: s => mesh_s
        procedure :: nodes => mesh_nodes_of
        procedure :: level => mesh_level
        procedure :: adapt => mesh_adapt
        procedure :: set_keys => mesh_set_keys
        procedure :: checkpoint => mesh_checkpoint
    end type adaptive_mesh_t

contains

    !> The coarsest mesh: n_coarse uniform elements at level 0.
    subroutine mesh_init(self, n_coarse, max_level, tol, buffer)
        class(adaptive_mesh_t), intent(out) :: self
        integer, intent(in) :: n_coarse, max_level, buffer
        real(dp), intent(in) :: tol
        integer :: i

        self%n_coarse = n_coarse
        self%max_level = max_level
        self%tol = tol
        self%buffer = buffer
        self%n_fine = int(n_coarse, int64) * 2_int64**max_level
        call self%set_keys([(int(i, int64) * 2_int64**max_level, i = 0, n_coarse)])
    end subroutine mesh_init

    !> The first mesh: the coarsest one adapted to the initial data (2.12), interpolated
    !> afresh on every mesh, until it no longer changes (at most max_level + 2 passes); the
    !> state holds the initial data on it.
    subroutine initial_mesh(cfg, mesh, state)
        type(config_t), intent(in) :: cfg
        type(adaptive_mesh_t), intent(out) :: mesh
        type(state_t), intent(out) :: state
        integer :: pass
        logical :: changed

        call mesh%init(cfg%mesh%n_elements, cfg%mesh%max_level, cfg%mesh%error_tol, &
                       front_buffer(cfg))
        changed = .false.
        do pass = 1, cfg%mesh%max_level + 2
            call initial_state(cfg, state, mesh%nodes())
            call mesh%adapt(state%mesh, state%u, state%w, changed)
            if (.not. changed) exit
        end do
        if (changed) call initial_state(cfg, state, mesh%nodes())
    end subroutine initial_mesh

    !> How many elements around a large indicator are kept fine (the buffer): the finest
    !> elements the fastest front (front_speed) can cross in remesh_every steps, plus one. A
    !> step moves it v dt, so v dt n_fine of the finest elements with fixed steps (&time dt;
    !> the buffer is 1 when there is no front: Fourier's and Fick's laws), and FRONT_CFL
    !> elements with adaptive steps (step_driver_m limits them so), whatever the laws.
    integer function front_buffer(cfg) result(buffer)
        type(config_t), intent(in) :: cfg
        real(dp) :: v, cfl, n_fine

        v = front_speed(cfg%model)
        n_fine = real(cfg%mesh%n_elements, dp) * 2.0_dp**cfg%mesh%max_level
        cfl = merge(FRONT_CFL, v * cfg%time%dt * n_fine, cfg%time%adaptive)
        buffer = 1 + ceiling(min(real(cfg%mesh%remesh_every, dp) * cfl, n_fine))
    end function front_buffer

    !> The mesh with node keys k(0:s) (a checkpoint's, or adapt's).
    subroutine mesh_set_keys(self, k)
        class(adaptive_mesh_t), intent(inout) :: self
        integer(int64), intent(in) :: k(0:)
        integer :: stat
        character(len=256) :: message

        if (allocated(self%k)) deallocate (self%k)
        allocate (self%k(0:ubound(k, 1)), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the adaptive mesh')
        self%k = k
    end subroutine mesh_set_keys

    !> The node keys and the field scales into a checkpoint, or back from one (checkpoint_m's
    !> reading; on a mesh initialised for this run).
    subroutine mesh_checkpoint(self, ckpt)
        class(adaptive_mesh_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt
        real(dp), allocatable :: scale(:)
        integer(int64), allocatable :: keys(:)

        allocate (scale, source=self%scale)
        keys = self%k
        call ckpt%sync('adaptive_mesh/scale', scale)
        call ckpt%sync('adaptive_mesh/keys', keys)
        self%scale = scale
        if (ckpt%reading) call self%set_keys(keys)
    end subroutine mesh_checkpoint

    !> Number of elements.
    pure integer function mesh_s(self)
        class(adaptive_mesh_t), intent(in) :: self

        mesh_s = ubound(self%k, 1)
    end function mesh_s

    !> The nodes x_i = k_i / n_fine.
    pure function mesh_nodes_of(self) result(x)
        class(adaptive_mesh_t), intent(in) :: self
        real(dp) :: x(0:ubound(self%k, 1))

        x = nodes_of_keys(self%k, self%n_fine)
    end function mesh_nodes_of

    !> The nodes k / n_fine of keys k (x = 1 exactly at the end).
    pure function nodes_of_keys(k, n_fine) result(x)
        integer(int64), intent(in) :: k(0:)
        integer(int64), intent(in) :: n_fine
        real(dp) :: x(0:ubound(k, 1))

        x = real(k, dp) / real(n_fine, dp)
        x(ubound(x, 1)) = 1.0_dp
    end function nodes_of_keys

    !> Level of element e (0: a coarse element).
    pure integer function mesh_level(self, e)
        class(adaptive_mesh_t), intent(in) :: self
        integer, intent(in) :: e

        mesh_level = self%max_level - trailz(self%k(e) - self%k(e - 1))
    end function mesh_level

    !> The next mesh for the level (u, w) on the current mesh (the nodes of self%k; module
    !> header); changed: it differs from the current one (then self%k holds it).
    subroutine mesh_adapt(self, mesh, u, w, changed)
        class(adaptive_mesh_t), intent(inout) :: self
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(in) :: u(0:), w(0:, :)
        logical, intent(out) :: changed
        real(dp) :: refine_ind(ubound(self%k, 1)), coarsen_ind(0:ubound(self%k, 1)), norm(0:N_FIELDS)
        logical, dimension(ubound(self%k, 1)) :: hot, keep, bisect
        logical :: remove(0:ubound(self%k, 1))
        integer(int64), allocatable :: k_new(:)
        integer :: s, e, m, f
        integer(int64) :: length

        s = self%s()
        ! each field's L2 norm, scale_f = max(scale_f, |f|_L2), and the norm the indicators
        ! are relative to (NORM_FLOOR: a field decaying to zero is not resolved to round-off)
        norm(0) = l2_norm(mesh%x, u)
        do f = 1, N_FIELDS
            norm(f) = l2_norm(mesh%x, w(:, f))
        end do
        self%scale = max(self%scale, norm)
        norm = max(norm, NORM_FLOOR * self%scale)
        refine_ind = 0.0_dp
        coarsen_ind = 0.0_dp
        if (norm(0) > 0.0_dp) call add_field(mesh%x, u, norm(0), refine_ind, coarsen_ind)
        do f = 1, N_FIELDS
            if (norm(f) > 0.0_dp) call add_field(mesh%x, w(:, f), norm(f), refine_ind, coarsen_ind)
        end do
        hot = refine_ind > self%tol
        ! keep: within `buffer` elements of a hot one (refined up to max_level, never coarsened)
        keep = hot
        do e = 1, s
            if (hot(e)) keep(max(1, e - self%buffer):min(s, e + self%buffer)) = .true.
        end do
        do e = 1, s
            bisect(e) = keep(e) .and. self%level(e) < self%max_level
        end do
        remove = .false.
        do m = 1, s - 1
            if (keep(m) .or. keep(m + 1)) cycle
            length = self%k(m) - self%k(m - 1)
            if (length /= self%k(m + 1) - self%k(m) .or. self%level(m) == 0) cycle
            if (modulo(self%k(m - 1), 2_int64 * length) /= 0) cycle     ! not siblings
            remove(m) = coarsen_ind(m) <= self%tol / COARSEN_MARGIN
        end do
        call bisected(self%k, bisect, remove, k_new)
        call balance(k_new)
        changed = size(self%k) /= size(k_new)
        if (.not. changed) changed = any(self%k /= k_new)
        if (changed) call self%set_keys(k_new)
    end subroutine mesh_adapt

    !> k_new = the nodes of keys k but those m where remove(m) (remove(s) = .false.), with the
    !> midpoint of each element e where bisect(e).
    subroutine bisected(k, bisect, remove, k_new)
        integer(int64), intent(in) :: k(0:)
        logical, intent(in) :: bisect(:), remove(0:)
        integer(int64), allocatable, intent(out) :: k_new(:)
        integer(int64) :: work(0:2 * ubound(k, 1))
        integer :: e, n, stat
        character(len=256) :: message

        n = 0
        work(0) = k(0)
        do e = 1, ubound(k, 1)
            if (bisect(e)) then
                n = n + 1
                work(n) = (k(e - 1) + k(e)) / 2
            end if
            if (remove(e)) cycle
            n = n + 1
            work(n) = k(e)
        end do
        allocate (k_new(0:n), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the new mesh')
        k_new = work(0:n)
    end subroutine bisected

    !> The mesh of keys k bisected until neighbouring elements differ by at most one level
    !> (2:1 grading).
    subroutine balance(k)
        integer(int64), allocatable, intent(inout) :: k(:)
        integer(int64), allocatable :: k_next(:)
        logical, allocatable :: split(:)
        integer :: e

        do
            split = [(too_coarse(k, e), e = 1, ubound(k, 1))]
            if (.not. any(split)) exit
            call bisected(k, split, spread(.false., 1, size(k)), k_next)
            call move_alloc(k_next, k)
        end do

    contains

        !> Is element e more than twice as long as a neighbour?
        pure logical function too_coarse(k, e)
            integer(int64), intent(in) :: k(0:)
            integer, intent(in) :: e
            integer(int64) :: length

            length = k(e) - k(e - 1)
            too_coarse = .false.
            if (e > 1) too_coarse = length > 2 * (k(e - 1) - k(e - 2))
            if (e < ubound(k, 1)) too_coarse = too_coarse .or. length > 2 * (k(e + 1) - k(e))
        end function too_coarse
    end subroutine balance

    !> refine_ind = max(refine_ind, this field's indicators), likewise coarsen_ind (module
    !> header), f measured relative to scale.
    pure subroutine add_field(x, f, scale, refine_ind, coarsen_ind)
        real(dp), intent(in) :: x(0:), f(0:), scale
        real(dp), intent(inout) :: refine_ind(:), coarsen_ind(0:)
        real(dp) :: curvature(0:ubound(x, 1)), slope_left, slope_right, h
        integer :: s, i, e

        s = ubound(x, 1)
        ! |f''| at the interior nodes from the jump of the slope; 0 at the ends
        curvature = 0.0_dp
        do i = 1, s - 1
            slope_left = (f(i) - f(i - 1)) / (x(i) - x(i - 1))
            slope_right = (f(i + 1) - f(i)) / (x(i + 1) - x(i))
            curvature(i) = abs(slope_right - slope_left) / (0.5_dp * (x(i + 1) - x(i - 1)))
            ! the detail of node i if it bisects its parent, per unit length
            coarsen_ind(i) = max(coarsen_ind(i), abs(f(i) - 0.5_dp * (f(i - 1) + f(i + 1))) &
                                 / (sqrt(3.0_dp) * scale))
        end do
        do e = 1, s
            h = x(e) - x(e - 1)
            ! predicted detail h^2 |f''| / 8 times sqrt(h/3), per sqrt(h)
            refine_ind(e) = max(refine_ind(e), h**2 * max(curvature(e - 1), curvature(e)) &
                                / (8.0_dp * sqrt(3.0_dp) * scale))
        end do
    end subroutine add_field

    !> The fastest front of (2.11): the second-sound speeds of the Cattaneo laws for q and
    !> eta. Their principal part [c d; d r] (theta, P)_tt = diag(1/tau0, hbar/tau) (theta, P)_xx
    !> gives speeds^2 = the eigenvalues of [c d; d r]^{-1} diag(1/tau0, hbar/tau) (with d = 0:
    !> v_theta = 1/sqrt(tau0 c), v_P = sqrt(hbar/(r tau)), (7.4)); a law without relaxation
    !> time (Fourier, Fick: parabolic) has no front. 0: no front.
    pure real(dp) function front_speed(model) result(v)
        type(model_t), intent(in) :: model
        real(dp) :: a, b, det, tr, disc

        a = 0.0_dp
        b = 0.0_dp
        if (model%tau0 > 0.0_dp) a = 1.0_dp / model%tau0
        if (model%tau > 0.0_dp) b = model%hbar / model%tau
        det = model%c * model%r - model%d**2
        ! [c d; d r]^{-1} diag(a, b) = [r a, -d b; -d a, c b] / det
        tr = (model%r * a + model%c * b) / det
        disc = max(tr**2 - 4.0_dp * a * b / det, 0.0_dp)
        v = sqrt(max(0.5_dp * (tr + sqrt(disc)), 0.0_dp))
    end function front_speed

    !> |f|_L2 of the P1 function with nodal values f on nodes x.
    pure real(dp) function l2_norm(x, f)
        real(dp), intent(in) :: x(0:), f(0:)
        integer :: e
        real(dp) :: total

        total = 0.0_dp
        do e = 1, ubound(x, 1)
            total = total + (x(e) - x(e - 1)) * (f(e - 1)**2 + f(e - 1) * f(e) + f(e)**2) / 3.0_dp
        end do
        l2_norm = sqrt(total)
    end function l2_norm

end module adaptive_mesh_m
