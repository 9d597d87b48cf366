!> The discrete state at one time level: (u, v, theta, P, q, eta) at the nodes 0..s, and
!> the mesh they live on (mesh_m: uniform, or graded with &mesh adaptive).
module state_m
    use kinds_m, only: dp
    use reals_m, only: equal
    use config_m, only: config_t
    use mesh_m, only: mesh_t, copy_mesh
    use initial_data_m, only: profile
    use errors_m, only: check_allocation, fatal, EXIT_INPUT
    use fields_m, only: N_FIELDS, F_U, F_Q, F_THETA, F_V, F_P, F_ETA, zero_dirichlet
    use checkpoint_m, only: checkpoint_t
    implicit none
    private
    public :: state_t, initial_state, set_mesh, field_values, advance_time, accept_step, land_on, &
              copy_state, keep_copy

    type :: state_t
        integer :: s = 0                !< number of elements (mesh%s())
        integer :: step = 0             !< n, the time level
        real(dp) :: t = 0.0_dp          !< t_n
        real(dp) :: dt_last = 0.0_dp    !< t_n - t_{n-1} (0 at t = 0)
        !> t_n = t_anchor + (n - step_anchor) dt while the step size dt stays the same, so
        !> that a constant-step run has t_n = n dt exactly (anchor 0, 0)
        real(dp) :: t_anchor = 0.0_dp
        integer :: step_anchor = 0
        real(dp), allocatable :: u(:)       !< u_h^n(x_i), i = 0..s
        real(dp), allocatable :: w(:, :)    !< w(i, f): field f (fields_m's F_*) at node i
        real(dp), allocatable :: u_prev(:), w_prev(:, :)  !< the level before (multistep schemes
                                                          !< only; allocated by the stepper)
        type(mesh_t) :: mesh            !< the nodes x_i and element sizes h_e (set_mesh)
    contains
        procedure :: checkpoint => state_checkpoint
    end type state_t

contains

    !> The state at t = 0: nodal interpolants of the initial data (2.12), with the boundary
    !> values of the spaces S_h, V_h imposed (validation has checked that the data satisfy
    !> them, so this only removes round-off). nodes: a graded mesh (absent: the uniform mesh
    !> of &mesh n_elements).
    subroutine initial_state(cfg, state, nodes)
        type(config_t), intent(in) :: cfg
        type(state_t), intent(out) :: state
        real(dp), intent(in), optional :: nodes(0:)
        integer :: s, i, stat
        character(len=256) :: message

        if (present(nodes)) then
            call set_mesh(state, nodes)
        else
            call state%mesh%set_uniform(cfg%mesh%n_elements)
            state%s = cfg%mesh%n_elements
        end if
        s = state%s
        allocate (state%u(0:s), state%w(0:s, N_FIELDS), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the state')
        associate (x => state%mesh%x, init => cfg%initial)
            do i = 0, s
                state%u(i) = profile(poly=init%u0_poly, x=x(i), table=init%u0_table)
                state%w(i, F_V) = profile(poly=init%u1_poly, x=x(i), table=init%u1_table)
                state%w(i, F_THETA) = profile(init%theta0_poly, x(i), init%theta0_step, init%theta0_table)
                state%w(i, F_P) = profile(init%p0_poly, x(i), init%p0_step, init%p0_table)
                state%w(i, F_Q) = profile(poly=init%q0_poly, x=x(i), table=init%q0_table)
                state%w(i, F_ETA) = profile(poly=init%eta0_poly, x=x(i), table=init%eta0_table)
            end do
        end associate
        state%u(0) = 0.0_dp
        call zero_dirichlet(state%w)
    end subroutine initial_state

    !> The state lives on the graded mesh with nodes x(0:s) (its arrays are not touched).
    subroutine set_mesh(state, x)
        type(state_t), intent(inout) :: state
        real(dp), intent(in) :: x(0:)

        call state%mesh%set_nodes(x)
        state%s = ubound(x, 1)
    end subroutine set_mesh

    !> The nodal values of field f (fields_m's F_*, F_U the displacement).
    pure function field_values(state, f) result(values)
        type(state_t), intent(in) :: state
        integer, intent(in) :: f
        real(dp) :: values(0:state%s)

        if (f == F_U) then
            values = state%u
        else
            values = state%w(:, f)
        end if
    end function field_values

    !> The time of the level after a step of size dt (see next_anchor).
    pure real(dp) function advance_time(state, dt) result(t_new)
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: dt
        real(dp) :: t_anchor
        integer :: step_anchor

        call next_anchor(state, dt, t_anchor, step_anchor)
        t_new = t_anchor + real(state%step + 1 - step_anchor, dp) * dt
    end function advance_time

    !> The state has taken a step of size dt to t_new: the level counter, the time, the last
    !> step size and the anchor move on.
    pure subroutine accept_step(state, dt, t_new)
        type(state_t), intent(inout) :: state
        real(dp), intent(in) :: dt, t_new

        call next_anchor(state, dt, state%t_anchor, state%step_anchor)
        state%step = state%step + 1
        state%t = t_new
        state%dt_last = dt
    end subroutine accept_step

    !> t_n = t_anchor + (n - step_anchor) dt while the step size stays dt; the anchor moves
    !> to the current level when a step of another size follows.
    pure subroutine next_anchor(state, dt, t_anchor, step_anchor)
        type(state_t), intent(in) :: state
        real(dp), intent(in) :: dt
        real(dp), intent(out) :: t_anchor
        integer, intent(out) :: step_anchor

        t_anchor = state%t_anchor
        step_anchor = state%step_anchor
        if (state%step > 0 .and. .not. equal(dt, state%dt_last)) then
            t_anchor = state%t
            step_anchor = state%step
        end if
    end subroutine next_anchor

    !> The step just accepted was sized to end at t_target (an output time or t_end):
    !> take t_n = t_target exactly, and count the following steps from there.
    pure subroutine land_on(state, t_target)
        type(state_t), intent(inout) :: state
        real(dp), intent(in) :: t_target

        state%t = t_target
        state%t_anchor = t_target
        state%step_anchor = state%step
    end subroutine land_on

    !> copy = state, reusing copy's arrays (a rejected adaptive step restores from it; the
    !> intrinsic assignment would allocate every step). level = .false.: all but the level
    !> (u, w), which the caller keeps elsewhere (default .true.).
    subroutine copy_state(state, copy, level)
        type(state_t), intent(in) :: state
        type(state_t), intent(inout) :: copy
        logical, intent(in), optional :: level
        logical :: with_level

        copy%s = state%s
        copy%step = state%step
        copy%t = state%t
        copy%dt_last = state%dt_last
        copy%t_anchor = state%t_anchor
        copy%step_anchor = state%step_anchor
        call copy_mesh(state%mesh, copy%mesh)
        with_level = .true.
        if (present(level)) with_level = level
        if (with_level) call keep_copy(state%u, state%w, copy%u, copy%w, 'the saved state')
        if (allocated(state%u_prev)) then
            call keep_copy(state%u_prev, state%w_prev, copy%u_prev, copy%w_prev, 'the saved state')
        else if (allocated(copy%u_prev)) then
            deallocate (copy%u_prev, copy%w_prev)
        end if
    end subroutine copy_state

    !> (u_copy, w_copy) = (u, w) with their bounds: the arrays are kept when u_copy has as many
    !> entries as u (the mesh is the same), else allocated anew (what: for the message if the
    !> allocation fails).
    subroutine keep_copy(u, w, u_copy, w_copy, what)
        real(dp), intent(in) :: u(0:), w(0:, :)
        real(dp), allocatable, intent(inout) :: u_copy(:), w_copy(:, :)
        character(len=*), intent(in) :: what
        integer :: stat
        character(len=256) :: message

        if (allocated(u_copy)) then
            if (size(u_copy) /= size(u)) deallocate (u_copy, w_copy)   ! the mesh has changed
        end if
        if (.not. allocated(u_copy)) then
            allocate (u_copy(0:ubound(u, 1)), w_copy(0:ubound(w, 1), size(w, 2)), &
                      stat=stat, errmsg=message)
            call check_allocation(stat, message, what)
        end if
        u_copy = u
        w_copy = w
    end subroutine keep_copy

    !> The level, the level before and the time counters in a checkpoint (checkpoint_m's sync)
    !> under owner (e.g. 'state'): owner/level and owner/previous (s+1, 1+N_FIELDS: the columns
    !> u, then w; previous with no rows before a multistep scheme's first step or for a
    !> single-step scheme, so that every checkpoint of a run has the same entries), owner/step,
    !> t, ... Restored, the arrays take the checkpoint's number of elements (a mesh of that many
    !> is set apart: set_mesh); a checkpoint of an earlier version may lack previous.
    subroutine state_checkpoint(self, ckpt, owner)
        class(state_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt
        character(len=*), intent(in) :: owner
        real(dp), allocatable :: level(:, :), prev(:, :)

        allocate (prev(0, 1 + N_FIELDS))
        if (.not. ckpt%reading) then
            level = reshape([self%u, self%w], [self%s + 1, 1 + N_FIELDS])
            if (allocated(self%u_prev)) prev = reshape([self%u_prev, self%w_prev], shape(level))
        end if
        call ckpt%sync(owner//'/level', level)
        if (.not. ckpt%reading .or. ckpt%has(owner//'/previous')) &
            call ckpt%sync(owner//'/previous', prev)
        if (ckpt%reading) then
            self%s = size(level, 1) - 1
            call keep_copy(level(:, 1), level(:, 2:), self%u, self%w, 'the state')
            if (all(size(prev, 1) /= [0, self%s + 1])) &
                call fatal(EXIT_INPUT, 'time.restart_from', &
                           'the checkpoint''s '//owner//' levels differ in size')
            if (size(prev, 1) > 0) &
                call keep_copy(prev(:, 1), prev(:, 2:), self%u_prev, self%w_prev, 'the previous level')
        end if
        call ckpt%sync(owner//'/step', self%step)
        call ckpt%sync(owner//'/t', self%t)
        call ckpt%sync(owner//'/dt_last', self%dt_last)
        call ckpt%sync(owner//'/t_anchor', self%t_anchor)
        call ckpt%sync(owner//'/step_anchor', self%step_anchor)
    end subroutine state_checkpoint

end module state_m
