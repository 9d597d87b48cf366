!> The paper's Section 7 method (&solver method = 'paper') for one Euler step (6.1): the
!> thermal block (q, theta, P, eta) with the velocity of the previous iterate, then the
!> mechanical block (v) with the new theta, P and the lagged penalty, until the largest
!> change of any nodal value is <= tol * max(1, max |value|). Both blocks are factored
!> (dgbtrf) once per step size. A uniform mesh and the Euler scheme only (validate_m).
module paper_method_m
    use kinds_m, only: dp
    use reals_m, only: equal
    use ieee_arithmetic, only: ieee_is_finite
    use config_m, only: model_t
    use errors_m, only: check_allocation
    use banded_m, only: band_t, lapack_info_message
    use fields_m, only: N_FIELDS, F_V
    use scheme_m, only: assemble_matrix, add_lagged_coupling
    use slots_m, only: THERMAL_SLOTS, MECHANICAL_SLOTS, scatter_fields, gather_fields
    use contact_laws_m, only: contact_law_t
    use mesh_m, only: mesh_t
    use state_m, only: state_t
    use step_result_m, only: step_result_t, fail
    implicit none
    private
    public :: paper_method_t

    type :: paper_method_t
        real(dp) :: dt = 0.0_dp        !< the step the blocks are factored for
        real(dp) :: tol = 0.0_dp       !< &solver tol, max_iter
        integer :: max_iter = 0
        type(band_t) :: thermal        !< (q, theta, P, eta) block, factored
        type(band_t) :: mechanical     !< v block, factored
        ! work arrays, allocated once
        real(dp), allocatable :: b(:, :), w_lag(:, :), w_new(:, :), u_lag(:), work(:), xt(:)
    contains
        procedure :: setup => paper_setup
        procedure :: advance => paper_advance
    end type paper_method_t

contains

    !> Both blocks for step dt on mesh, factored (a singular one is reported in result).
    subroutine paper_setup(self, model, mesh, dt, result)
        class(paper_method_t), intent(inout) :: self
        type(model_t), intent(in) :: model
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(in) :: dt
        type(step_result_t), intent(inout) :: result
        integer :: info, stat, s
        character(len=256) :: message

        self%dt = dt
        call assemble_matrix(model, mesh, dt, THERMAL_SLOTS, self%thermal)
        call self%thermal%factor(info)
        if (info /= 0) call fail(result, 'thermal block: '//lapack_info_message('dgbtrf', info))
        call assemble_matrix(model, mesh, dt, MECHANICAL_SLOTS, self%mechanical)
        call self%mechanical%factor(info)
        if (info /= 0) call fail(result, 'mechanical block: '//lapack_info_message('dgbtrf', info))
        if (allocated(self%xt)) return
        s = mesh%s()
        allocate (self%b(0:s, N_FIELDS), self%w_lag(0:s, N_FIELDS), &
                  self%w_new(0:s, N_FIELDS), self%u_lag(0:s), self%work(0:s), self%xt(self%thermal%n), &
                  stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the paper iteration''s work arrays')
    end subroutine paper_setup

    !> The iteration for one Euler step of size dt of state, from rhs(0:s, f), the right-hand
    !> side of (6.1) of every field (stepper_m's start_rhs). On failure the state is left
    !> unchanged.
    subroutine paper_advance(self, model, mesh, law, rhs, state, dt, result)
        class(paper_method_t), intent(inout) :: self
        type(model_t), intent(in) :: model
        type(mesh_t), intent(in) :: mesh
        class(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: rhs(0:, :)
        type(state_t), intent(inout) :: state
        real(dp), intent(in) :: dt
        type(step_result_t), intent(inout) :: result
        integer :: l, s
        real(dp) :: change, scale

        if (.not. equal(dt, self%dt)) call paper_setup(self, model, mesh, dt, result)
        if (.not. result%ok) return
        s = state%s
        self%w_lag = state%w                 ! iterate l-1 (l = 0: the previous time level)
        self%u_lag = state%u
        scale = 1.0_dp
        do l = 1, self%max_iter
            ! thermal block with the lagged velocity
            self%b = rhs
            call add_lagged_coupling(model, dt, THERMAL_SLOTS, self%w_lag, self%b, self%work)
            call scatter_fields(THERMAL_SLOTS, self%b, self%xt)
            call self%thermal%solve(self%xt)
            call gather_fields(THERMAL_SLOTS, self%xt, self%w_new)
            ! mechanical block with the new theta, P and the lagged penalty
            self%b(:, F_V) = rhs(:, F_V)
            call add_lagged_coupling(model, dt, MECHANICAL_SLOTS, self%w_new, self%b, self%work)
            self%b(s, F_V) = self%b(s, F_V) - law%lagged_impulse(dt, self%u_lag(s))
            call self%mechanical%solve(self%b(:, F_V))
            self%w_new(:, F_V) = self%b(:, F_V)
            result%iterations = l
            if (.not. all(ieee_is_finite(self%w_new))) then
                call fail(result, 'non-finite value in the solution')
                return
            end if
            change = maxval(abs(self%w_new - self%w_lag))
            scale = max(1.0_dp, maxval(abs(self%w_new)))
            if (change > 1.0e100_dp * max(1.0_dp, maxval(abs(state%w)))) then
                ! stop before the iterates overflow: the lagged coupling is not a contraction
                write (result%message, '(a,i0,a)') 'paper iteration diverged (iteration ', l, &
                    '): the lagged penalty/velocity coupling does not contract here; use method = ''monolithic'''
                result%ok = .false.
                return
            end if
            self%w_lag = self%w_new
            self%u_lag = state%u + dt * self%w_new(:, F_V)
            if (change <= self%tol * scale) then
                state%w = self%w_lag
                state%u = self%u_lag
                result%contact_force = law%force(state%u(s))
                return
            end if
        end do
        write (result%message, '(a,i0,a,es10.3,a,es10.3)') 'paper iteration did not converge in ', &
            self%max_iter, ' iterations: last change ', change, ' > tol*scale = ', self%tol * scale
        result%ok = .false.
    end subroutine paper_advance

end module paper_method_m
