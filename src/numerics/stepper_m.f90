!> One time step of (6.1) by either solution method of docs/scheme.md, "Solution methods".
!>
!> 'monolithic': all five fields in one system (nodes interleaved), factored once by the
!>   block-tridiagonal LU (block_tridiagonal_m), which solves every step once it reproduces
!>   the band LU's (dgbtrf) solution at set-up (setup_monolithic). The contact term acts on
!>   one unknown (v at x=1): x = y - f z with y = A^{-1} b, z = A^{-1} e_s (kept with the
!>   factors) and the scalar force f in closed form from the law (contact_law_m): one solve.
!> 'paper': the Section 7 iteration (paper_method_m).
!>
!> &time scheme: every scheme is one Euler step (6.1) of size dt_eff from a combination of
!> past levels (time_scheme_m's plan), so the same assembly, contact step and sources serve all.
module stepper_m
    use kinds_m, only: dp
    use config_m, only: config_t, model_t, with_contact_mass
    use errors_m, only: check_allocation
    use banded_m, only: band_t, lapack_info_message
    use step_result_m, only: step_result_t, fail
    use paper_method_m, only: paper_method_t
    use system_cache_m, only: monolithic_system_t, system_cache_t
    use fields_m, only: N_FIELDS, F_V, zero_dirichlet
    use scheme_m, only: active_fields, assemble_matrix, assemble_blocks, old_state_rhs, &
                        initial_data_present
    use slots_m, only: MONOLITHIC_SLOTS, slots_of, scatter_fields, gather_fields
    use block_tridiagonal_m, only: NB_MAX
    use contact_laws_m, only: contact_law_t, contact_law
    use time_scheme_m, only: time_scheme_t, time_scheme, step_plan_t
    use state_m, only: state_t, advance_time, accept_step, keep_copy
    use mesh_m, only: mesh_t, copy_mesh
    use sources_m, only: source_t, add_source_terms
    use checkpoint_m, only: checkpoint_t
    use massless_end_m, only: settle_end
    implicit none
    private
    public :: stepper_t, step_result_t

    integer, parameter :: METHOD_MONOLITHIC = 1, METHOD_PAPER = 2

    type :: stepper_t
        type(model_t) :: model         !< the paper's coefficients (&model)
        type(model_t) :: step_model    !< what the steps use (time_scheme_m's stiff_limit)
        logical :: algebraic(N_FIELDS) = .false.   !< no time derivative in step_model
        class(contact_law_t), allocatable :: law
        type(time_scheme_t) :: scheme
        real(dp) :: dt = 0.0_dp        !< the step size when advance() is given none (&time dt)
        integer :: s = 0, method = METHOD_MONOLITHIC
        !> the mesh the factored systems belong to (s = mesh%s()): the uniform mesh of &mesh
        !> n_elements from init, a copy of the state's after remesh
        type(mesh_t) :: mesh
        !> adaptive mesh or steps: the block LU has passed blocks_agree on a system of this run
        logical :: blocks_trusted = .false.
        !> &time adaptive: systems are factored as on a graded mesh (setup_monolithic)
        logical :: adaptive_steps = .false.
        logical :: active(N_FIELDS) = .true.   !< fields in the system (others stay zero)
        !> a non-finite solution fails the step (error_companion_m's companions test their
        !> levels once per snapshot instead)
        logical :: check_finite = .true.
        integer :: slots(N_FIELDS) = MONOLITHIC_SLOTS
        class(source_t), allocatable :: source   !< optional source terms (manufactured solutions)
        !> the factored systems of (6.1), by dt_eff and mesh (system_cache_m)
        type(system_cache_t) :: cache
        type(paper_method_t) :: paper  !< the Section 7 iteration (method = 'paper')
        ! work arrays, allocated once
        real(dp), allocatable :: b(:, :), w_new(:, :), work(:), x(:)
        real(dp), allocatable :: u_star(:), w_star(:, :)   !< multistep: the level a step starts from
        ! counters for the output attributes
        integer(kind=8) :: n_solves = 0, n_contact_steps = 0
    contains
        procedure :: init => stepper_init
        procedure :: advance => stepper_advance
        procedure :: uses_block_solver => stepper_uses_block_solver
        procedure :: remesh => stepper_remesh
        procedure :: take_back => stepper_take_back
        procedure :: checkpoint => stepper_checkpoint
    end type stepper_t

contains

    !> Set up the chosen method for cfg (validated: validate_m has refused every combination
    !> the methods do not support). A singular matrix (impossible for valid input) is
    !> reported through result.
    subroutine stepper_init(self, cfg, result, source)
        class(stepper_t), intent(out) :: self
        type(config_t), intent(in) :: cfg
        type(step_result_t), intent(out) :: result
        class(source_t), intent(in), optional :: source   !< source terms of sources_m
        integer :: k, s_finest, stat
        character(len=256) :: message

        self%model = with_contact_mass(cfg%model, cfg%contact%mass)
        self%dt = cfg%time%dt
        self%adaptive_steps = cfg%time%adaptive
        self%law = contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps)
        self%scheme = time_scheme(cfg%time%scheme)
        ! an adaptive mesh: the stiff limit of its finest possible elements, for the whole run
        s_finest = cfg%mesh%n_elements
        if (cfg%mesh%adaptive) s_finest = cfg%mesh%n_elements * 2**cfg%mesh%max_level
        call self%scheme%stiff_limit(self%model, self%dt, s_finest, self%step_model, self%algebraic)
        self%paper%tol = cfg%solver%tol
        self%paper%max_iter = cfg%solver%max_iter
        call self%mesh%set_uniform(cfg%mesh%n_elements)
        self%s = cfg%mesh%n_elements
        stat = 0
        if (present(source)) allocate (self%source, source=source, stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the source terms')
        select case (trim(cfg%solver%method))
        case ('paper')
            self%method = METHOD_PAPER
            call allocate_work(self)
            call self%paper%setup(self%model, self%mesh, self%dt, result)
        case default
            self%method = METHOD_MONOLITHIC
            self%active = active_fields(self%step_model, initial_data_present(cfg) .or. present(source))
            self%slots = slots_of(self%active)
            call allocate_work(self)
            call find_system(self, self%dt, k, result)
        end select
    end subroutine stepper_init

    !> The work arrays for self%s elements (and the monolithic system vector).
    subroutine allocate_work(self)
        type(stepper_t), intent(inout) :: self
        integer :: s, stat
        character(len=256) :: message

        s = self%s
        if (allocated(self%b)) deallocate (self%b, self%w_new, self%work, self%u_star, self%w_star)
        allocate (self%b(0:s, N_FIELDS), self%w_new(0:s, N_FIELDS), self%work(0:s), self%u_star(0:s), &
                  self%w_star(0:s, N_FIELDS), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the work arrays')
        self%w_new = 0.0_dp
        if (allocated(self%x)) deallocate (self%x)
        allocate (self%x(count(self%active) * (s + 1)), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the system')
    end subroutine allocate_work

    !> The state has moved to another mesh (state%mesh; adaptive_mesh_m): the work arrays
    !> take its size and every factored system is dropped (the next step assembles and
    !> factors the matrix of (6.1) on the new mesh). Monolithic method only.
    subroutine stepper_remesh(self, state)
        class(stepper_t), intent(inout) :: self
        type(state_t), intent(in) :: state

        call copy_mesh(state%mesh, self%mesh)
        self%s = self%mesh%s()
        call allocate_work(self)
        call self%cache%invalidate()
    end subroutine stepper_remesh

    !> The factored system of (6.1) with step dt_eff: one the cache holds for exactly this
    !> dt_eff and mesh, or a new assembly and factorisation in the entry it frees.
    subroutine find_system(self, dt_eff, k, result)
        type(stepper_t), intent(inout) :: self
        real(dp), intent(in) :: dt_eff
        integer, intent(out) :: k
        type(step_result_t), intent(inout) :: result
        logical :: found

        call self%cache%lookup(dt_eff, k, found)
        if (found) return
        call setup_monolithic(self, dt_eff, self%cache%systems(k), result)
        if (result%ok) call self%cache%stored(k, dt_eff)
    end subroutine find_system

    !> Assemble (6.1) with step dt_eff, factor it by the block LU and compute the contact
    !> response z. The block LU does not pivot across nodes: until it has passed blocks_agree
    !> in a run, the band is factored too (dgbtrf), gives z, and solves if the check fails.
    !> Fixed steps on a uniform mesh (a system or two a run) check each system and invert
    !> the pivot blocks by LAPACK; adaptive steps and a graded mesh (a system per step size
    !> or remesh) trust the block LU once checked and invert by invert5 (docs/performance.md).
    !> Each inversion keeps its runs' bits.
    subroutine setup_monolithic(self, dt_eff, sys, result)
        type(stepper_t), intent(inout) :: self
        real(dp), intent(in) :: dt_eff
        type(monolithic_system_t), intent(out) :: sys
        type(step_result_t), intent(inout) :: result
        type(band_t) :: unfactored
        !> the node blocks D_i, E_i, F_i (D_i's storage becomes the block LU's factors)
        real(dp), allocatable :: d(:, :, :), e(:, :, :), f(:, :, :)
        integer :: info, stat
        logical :: fast, blocks_ok
        character(len=256) :: message

        fast = self%adaptive_steps .or. .not. self%mesh%is_uniform()
        sys%contact_dof = count(self%active) * self%s + self%slots(F_V)
        allocate (d(NB_MAX, NB_MAX, 0:self%s), e(NB_MAX, NB_MAX, 0:self%s - 1), f(NB_MAX, NB_MAX, 0:self%s - 1), &
                  stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the blocks of the system')
        ! the fields in the system (active): assemble_matrix's band, bit for bit
        call assemble_blocks(self%step_model, self%mesh, dt_eff, d, e, f)
        call sys%blocks%factor(d, e, f, info, fast, self%active)
        blocks_ok = info == 0
        sys%use_blocks = blocks_ok .and. self%blocks_trusted
        if (.not. sys%use_blocks) then
            call assemble_matrix(self%step_model, self%mesh, dt_eff, self%slots, sys%a)
            unfactored = sys%a
            call sys%a%factor(info)
            if (info /= 0) then
                call fail(result, lapack_info_message('dgbtrf', info))
                return
            end if
            call contact_response(self, sys)
            if (blocks_ok) sys%use_blocks = sys%blocks_agree(unfactored, self%x)
            self%blocks_trusted = sys%use_blocks .and. fast
        end if
        ! once trusted, z from the block LU for every system (a restart, which checks the
        ! block LU anew, then repeats the run bit for bit), and the band is not kept
        if (self%blocks_trusted) then
            call contact_response(self, sys)
            call sys%a%release()
        end if
        if (.not. (sys%z(sys%contact_dof) > 0.0_dp)) &
            call fail(result, 'contact compliance e_s^T A^{-1} e_s is not positive')
    end subroutine setup_monolithic

    !> z = A^{-1} e_s, the response to a unit contact force (block LU once trusted, else band).
    subroutine contact_response(self, sys)
        type(stepper_t), intent(in) :: self
        type(monolithic_system_t), intent(inout) :: sys
        integer :: stat
        character(len=256) :: message

        if (.not. allocated(sys%z)) then
            allocate (sys%z(count(self%active) * (self%s + 1)), stat=stat, errmsg=message)
            call check_allocation(stat, message, 'the contact response')
        end if
        sys%z = 0.0_dp
        sys%z(sys%contact_dof) = 1.0_dp
        call sys%solve(sys%z)
    end subroutine contact_response

    !> Does the monolithic method solve with the block-tridiagonal LU (else dgbtrf's factors)?
    logical function stepper_uses_block_solver(self)
        class(stepper_t), intent(in) :: self

        stepper_uses_block_solver = self%method == METHOD_MONOLITHIC .and. self%cache%all_use_blocks()
    end function stepper_uses_block_solver

    !> Advance state from t_{n-1} by one step of size dt (default: &time dt). On failure
    !> the state is left unchanged.
    subroutine stepper_advance(self, state, result, dt)
        class(stepper_t), intent(inout) :: self
        type(state_t), intent(inout) :: state
        type(step_result_t), intent(out) :: result
        real(dp), intent(in), optional :: dt
        type(step_plan_t) :: plan
        real(dp) :: step_size, t_new, t_source
        integer :: k

        step_size = self%dt
        if (present(dt)) step_size = dt
        t_new = advance_time(state, step_size)
        select case (self%method)
        case (METHOD_PAPER)
            call start_rhs(self, self%model, step_size, t_new, state%u, state%w)
            call self%paper%advance(self%model, self%mesh, self%law, self%b, state, step_size, result)
        case default
            plan = self%scheme%plan(step_size, state%dt_last, allocated(state%u_prev), state%step)
            t_source = t_new - plan%source_back * step_size
            call find_system(self, plan%dt_eff, k, result)
            if (.not. result%ok) return
            if (plan%from_history) then
                ! the level the step starts from, e.g. (4 X^{n-1} - X^{n-2}) / 3 (BDF2)
                self%u_star = (plan%a * state%u - plan%b * state%u_prev) / plan%d
                self%w_star = (plan%a * state%w - plan%b * state%w_prev) / plan%d
                call start_rhs(self, self%step_model, plan%dt_eff, t_source, self%u_star, self%w_star)
            else
                call start_rhs(self, self%step_model, plan%dt_eff, t_source, state%u, state%w)
            end if
            call advance_monolithic(self, self%cache%systems(k), state, plan, result)
        end select
        if (.not. result%ok) return
        call accept_step(state, step_size, t_new)
        result%in_contact = result%contact_force > 0.0_dp
        if (result%in_contact) self%n_contact_steps = self%n_contact_steps + 1
        self%n_solves = self%n_solves + result%iterations
    end subroutine stepper_advance

    !> Right-hand side of (6.1) for `model` with step dt_eff from the level (u_from, w_from),
    !> plus the sources at t_source, Dirichlet rows zero: by field in b, and node by node in
    !> the system vector x.
    subroutine start_rhs(self, model, dt_eff, t_source, u_from, w_from)
        type(stepper_t), intent(inout) :: self
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: dt_eff, t_source
        real(dp), intent(in) :: u_from(0:), w_from(0:, :)

        call old_state_rhs(model, dt_eff, u_from, w_from, self%slots, self%b, self%work, self%mesh)
        if (allocated(self%source)) &
            call add_source_terms(self%source, model, t_source, dt_eff, self%b, self%mesh)
        call zero_dirichlet(self%b)
        call scatter_fields(self%slots, self%b, self%x)
    end subroutine start_rhs

    !> One step of plan (time_scheme_m), its right-hand side in x. Euler (6.1): from the
    !> state, or from u_star, w_star (from_history: multistep schemes). Midpoint: the half
    !> level Y = X^{n-1/2} is the Euler step of size dt/2 from X^{n-1} with the
    !> discrete-gradient force (contact_law_m's midpoint_impulse); X^n = 2 Y - X^{n-1}, but
    !> X^n = Y for the algebraic fields, and u^n = u^{n-1} + dt v^{n-1/2}. Y stays in w_new
    !> (its columns of fields outside the system stay zero from set-up).
    subroutine advance_monolithic(self, sys, state, plan, result)
        type(stepper_t), intent(inout) :: self
        type(monolithic_system_t), intent(in) :: sys
        type(state_t), intent(inout) :: state
        type(step_plan_t), intent(in) :: plan
        type(step_result_t), intent(inout) :: result
        real(dp) :: impulse, u_end_from
        integer :: f

        call sys%solve(self%x)   ! the solution without contact force
        result%iterations = 1
        u_end_from = state%u(self%s)
        if (plan%from_history) u_end_from = self%u_star(self%s)
        ! The trial gap without contact force decides the contact state; the contact row
        ! carries dt*lambda, so x = y - dt*lambda*z (contact_law_m's implicit_impulse).
        associate (dt => sys%dt_eff, z_s => sys%z(sys%contact_dof), y_s => self%x(sys%contact_dof))
            if (plan%midpoint) then
                impulse = self%law%midpoint_impulse(u_end_from + dt * y_s, u_end_from, dt, z_s)
                result%trial_gap = u_end_from + 2.0_dp * dt * y_s - self%law%g
            else
                result%trial_gap = u_end_from + dt * y_s - self%law%g
                impulse = self%law%implicit_impulse(result%trial_gap, dt, z_s)
            end if
        end associate
        call apply_contact(self, sys, impulse, result)
        if (.not. result%ok) return
        if (plan%midpoint) then
            call gather_fields(self%slots, self%x, self%w_new)
            do f = 1, N_FIELDS
                if (self%algebraic(f)) then
                    state%w(:, f) = self%w_new(:, f)
                else
                    state%w(:, f) = 2.0_dp * self%w_new(:, f) - state%w(:, f)
                end if
            end do
            state%u = state%u + 2.0_dp * sys%dt_eff * self%w_new(:, F_V)
            call settle_end(self%step_model, self%law, self%mesh%h(self%s), result%contact_force > 0.0_dp, &
                            state%u, state%w(:, F_V), self%w_new(self%s, F_V))
            return
        end if
        ! multistep schemes: X^{n-1} is kept before the step overwrites it
        if (self%scheme%row%keeps_previous_level) &
            call keep_copy(state%u, state%w, state%u_prev, state%w_prev, 'the previous level')
        call gather_fields(self%slots, self%x, state%w)
        if (plan%from_history) then
            state%u = self%u_star + sys%dt_eff * state%w(:, F_V)
        else
            state%u = state%u + sys%dt_eff * state%w(:, F_V)
        end if
        call settle_end(self%step_model, self%law, self%mesh%h(self%s), result%contact_force > 0.0_dp, &
                        state%u)
    end subroutine advance_monolithic

    !> x = y - (dt lambda) z: the contact row carries dt lambda (impulse); lambda is reported.
    !> A non-finite solution fails the step (unless check_finite is off).
    subroutine apply_contact(self, sys, impulse, result)
        type(stepper_t), intent(inout) :: self
        type(monolithic_system_t), intent(in) :: sys
        real(dp), intent(in) :: impulse
        type(step_result_t), intent(inout) :: result

        result%contact_force = 0.0_dp
        if (impulse > 0.0_dp) then
            self%x = self%x - impulse * sys%z
            result%contact_force = impulse / sys%dt_eff
        end if
        if (.not. self%check_finite) return
        if (.not. all_finite(self%x)) call fail(result, 'non-finite value in the solution')
    end subroutine apply_contact

    !> all(ieee_is_finite(x)) as a loop the compiler vectorises (docs/performance.md):
    !> abs(x) <= huge is false for a NaN and for an infinity.
    pure logical function all_finite(x)
        real(dp), intent(in), contiguous :: x(:)
        integer :: i, n_bad

        n_bad = 0
        do i = 1, size(x)
            if (.not. (abs(x(i)) <= huge(1.0_dp))) n_bad = n_bad + 1
        end do
        all_finite = n_bad == 0
    end function all_finite

    !> The step of result was rejected (the caller restores the state): its contact count is taken back.
    subroutine stepper_take_back(self, result)
        class(stepper_t), intent(inout) :: self
        type(step_result_t), intent(in) :: result

        if (result%in_contact) self%n_contact_steps = self%n_contact_steps - 1
    end subroutine stepper_take_back

    !> The counters of the output attributes solver.* in a checkpoint (checkpoint_m's sync).
    subroutine stepper_checkpoint(self, ckpt)
        class(stepper_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt

        call ckpt%sync('stepper/n_solves', self%n_solves)
        call ckpt%sync('stepper/n_contact_steps', self%n_contact_steps)
    end subroutine stepper_checkpoint

end module stepper_m
