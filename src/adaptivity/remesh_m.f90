!> Remeshing a run (&mesh adaptive = .true.): the first mesh, fitted to the initial data,
!> and a state moved onto a new mesh with transfer_m (move_state), for the remesh between
!> two steps (step_driver_m's remesh) and the error companions'.
module remesh_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use config_m, only: config_t, model_t
    use fields_m, only: N_FIELDS
    use state_m, only: state_t, initial_state, set_mesh
    use stepper_m, only: stepper_t
    use adaptive_mesh_m, only: adaptive_mesh_t, FRONT_CFL, front_speed, nodes_of_keys
    use transfer_m, only: transfer_level
    use errors_m, only: check_allocation
    implicit none
    private
    public :: initial_mesh, front_buffer, move_state

contains

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

    !> How many elements around a large indicator are kept fine (adaptive_mesh_t's buffer):
    !> the finest elements the fastest front (front_speed) can cross in remesh_every steps,
    !> plus one. A step moves it v dt, so v dt n_fine of the finest elements with fixed
    !> steps (&time dt; the buffer is 1 when there is no front: Fourier's and Fick's laws), and
    !> FRONT_CFL elements with adaptive steps (step_driver_m limits them so), whatever the laws.
    integer function front_buffer(cfg) result(buffer)
        type(config_t), intent(in) :: cfg
        real(dp) :: v, cfl, n_fine

        v = front_speed(cfg%model)
        n_fine = real(cfg%mesh%n_elements, dp) * 2.0_dp**cfg%mesh%max_level
        cfl = merge(FRONT_CFL, v * cfg%time%dt * n_fine, cfg%time%adaptive)
        buffer = 1 + ceiling(min(real(cfg%mesh%remesh_every, dp) * cfl, n_fine))
    end function front_buffer

    !> The state on the mesh of keys k_old (its level, and the level before of a multistep
    !> scheme) moved onto the mesh of keys k_new (move_level), and the stepper onto it.
    subroutine move_state(k_old, k_new, n_fine, stepper, state)
        integer(int64), intent(in) :: k_old(0:), k_new(0:), n_fine
        type(stepper_t), intent(inout) :: stepper
        type(state_t), intent(inout) :: state

        call move_level(k_old, k_new, n_fine, stepper%model, state%u, state%w)
        if (allocated(state%u_prev)) &
            call move_level(k_old, k_new, n_fine, stepper%model, state%u_prev, state%w_prev)
        call set_mesh(state, nodes_of_keys(k_new, n_fine))
        call stepper%remesh(state)
    end subroutine move_state

    !> One level (u, w) on the mesh of keys k_old onto the mesh of keys k_new (u and w
    !> reallocated with its size), by transfer_m (model: the run's, whose velocity mass v is
    !> moved in).
    subroutine move_level(k_old, k_new, n_fine, model, u, w)
        integer(int64), intent(in) :: k_old(0:), k_new(0:), n_fine
        type(model_t), intent(in) :: model
        real(dp), allocatable, intent(inout) :: u(:), w(:, :)
        real(dp) :: old(0:ubound(u, 1), 0:N_FIELDS), new(0:ubound(k_new, 1), 0:N_FIELDS)
        integer :: s, stat
        character(len=256) :: message

        s = ubound(k_new, 1)
        old(:, 0) = u
        old(:, 1:) = w
        call transfer_level(k_old, k_new, n_fine, old, new, model)
        deallocate (u, w)
        allocate (u(0:s), w(0:s, N_FIELDS), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the remeshed state')
        u = new(:, 0)
        w = new(:, 1:)
    end subroutine move_level

end module remesh_m
