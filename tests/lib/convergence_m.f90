!> Runs a manufactured solution (mms_m) through the library's time stepping (stepper_m
!> with sources_m) and measures the errors in the norms of Corollary 6.4: L2 of q, theta,
!> v, P, eta and H1 of u, each the maximum over the time levels.
module convergence_m
    use kinds_m, only: dp
    use config_m, only: config_t
    use state_m, only: state_t, set_mesh
    use stepper_m, only: stepper_t, step_result_t
    use fields_m, only: N_FIELDS, is_dirichlet
    use mms_m, only: mms_t, U_FIELD, N_EXACT
    implicit none
    private
    public :: mms_errors, mms_config, mms_initial_state, level_errors, observed_orders, ERROR_NAMES

    character(len=*), parameter :: ERROR_NAMES(N_EXACT) = [character(len=8) :: &
        'L2 q', 'L2 theta', 'L2 v', 'L2 P', 'L2 eta', 'H1 u']

contains

    !> errors(f) = max_n ||field_h^n - field(t_n)|| for the run of `mms` with s elements,
    !> step dt up to t_end, `method` and (optional) `scheme`; nodes(0:s): a graded mesh (absent:
    !> uniform).
    subroutine mms_errors(mms, s, dt, t_end, method, errors, scheme, nodes)
        type(mms_t), intent(in) :: mms
        integer, intent(in) :: s
        real(dp), intent(in) :: dt, t_end
        character(len=*), intent(in) :: method
        real(dp), intent(out) :: errors(N_EXACT)
        character(len=*), intent(in), optional :: scheme
        real(dp), intent(in), optional :: nodes(0:)
        type(config_t) :: cfg
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        integer :: n

        cfg = mms_config(mms, s, dt, t_end)
        cfg%solver%method = method
        cfg%solver%tol = 1.0e-12_dp
        cfg%solver%max_iter = 200
        if (present(scheme)) cfg%time%scheme = scheme
        call mms_initial_state(mms, s, state, nodes)
        call stepper%init(cfg, result, mms)
        if (.not. result%ok) error stop 'mms_errors: stepper init failed'
        if (present(nodes)) call stepper%remesh(state)
        errors = level_errors(mms, state)
        do n = 1, nint(t_end / dt)
            call stepper%advance(state, result)
            if (.not. result%ok) then
                write (*, '(a)') 'mms_errors: step failed: '//trim(result%message)
                error stop 1
            end if
            errors = max(errors, level_errors(mms, state))
        end do
    end subroutine mms_errors

    !> The input of a run of `mms` (its model and contact law) on s elements with step dt up
    !> to t_end; scheme: the time scheme (absent: the default).
    function mms_config(mms, s, dt, t_end, scheme) result(cfg)
        type(mms_t), intent(in) :: mms
        integer, intent(in) :: s
        real(dp), intent(in) :: dt, t_end
        character(len=*), intent(in), optional :: scheme
        type(config_t) :: cfg

        cfg%model = mms%model
        cfg%contact%eps = mms%eps
        cfg%contact%g = mms%g
        cfg%mesh%n_elements = s
        cfg%time%dt = dt
        cfg%time%t_end = t_end
        if (present(scheme)) cfg%time%scheme = scheme
    end function mms_config

    !> The state at t = 0 on s elements: nodal values of the exact solution, with the
    !> boundary values of the spaces imposed; nodes(0:s): a graded mesh (absent: uniform).
    subroutine mms_initial_state(mms, s, state, nodes)
        type(mms_t), intent(in) :: mms
        integer, intent(in) :: s
        type(state_t), intent(out) :: state
        real(dp), intent(in), optional :: nodes(0:)
        real(dp) :: x(0:s)
        integer :: i, f

        state%s = s
        allocate (state%u(0:s), state%w(0:s, N_FIELDS))
        if (present(nodes)) then
            call set_mesh(state, nodes)
        else
            call state%mesh%set_uniform(s)
        end if
        x = state%mesh%x
        do i = 0, s
            state%u(i) = mms%exact(U_FIELD, 0.0_dp, x(i), 0)
            do f = 1, N_FIELDS
                state%w(i, f) = mms%exact(f, 0.0_dp, x(i), 0)
                if (is_dirichlet(f, i, s)) state%w(i, f) = 0.0_dp
            end do
        end do
    end subroutine mms_initial_state

    !> Errors of one time level: L2 norms by 5-point Gauss quadrature per element.
    function level_errors(mms, state) result(e)
        type(mms_t), intent(in) :: mms
        type(state_t), intent(in) :: state
        real(dp) :: e(N_EXACT)
        real(dp), parameter :: gx(5) = [-0.9061798459386640_dp, -0.5384693101056831_dp, 0.0_dp, &
                                        0.5384693101056831_dp, 0.9061798459386640_dp]
        real(dp), parameter :: gw(5) = [0.2369268850561891_dp, 0.4786286704993665_dp, 0.5688888888888889_dp, &
                                        0.4786286704993665_dp, 0.2369268850561891_dp]
        real(dp) :: h, x, wq, left, uh, uh_x, sq(N_EXACT), nodes(0:state%s)
        integer :: s, el, k, f

        s = state%s
        nodes = state%mesh%x
        sq = 0.0_dp
        do el = 1, s
            h = nodes(el) - nodes(el - 1)
            do k = 1, 5
                left = 0.5_dp * (1.0_dp - gx(k))
                x = nodes(el - 1) + 0.5_dp * (1.0_dp + gx(k)) * h
                wq = 0.5_dp * h * gw(k)
                do f = 1, N_FIELDS
                    sq(f) = sq(f) + wq * (left * state%w(el - 1, f) + (1.0_dp - left) * state%w(el, f) &
                                          - mms%exact(f, state%t, x, 0))**2
                end do
                uh = left * state%u(el - 1) + (1.0_dp - left) * state%u(el)
                uh_x = (state%u(el) - state%u(el - 1)) / h
                sq(U_FIELD) = sq(U_FIELD) + wq * ((uh - mms%exact(U_FIELD, state%t, x, 0))**2 &
                                                  + (uh_x - mms%exact(U_FIELD, state%t, x, 1))**2)
            end do
        end do
        e = sqrt(sq)
    end function level_errors

    !> Observed orders log(e_k / e_{k+1}) / log(ratio) between successive refinements.
    pure function observed_orders(errors, ratio) result(orders)
        real(dp), intent(in) :: errors(:, :)     !< (field, refinement level)
        real(dp), intent(in) :: ratio            !< refinement factor between levels
        real(dp) :: orders(size(errors, 1), size(errors, 2) - 1)
        integer :: k

        do k = 1, size(errors, 2) - 1
            orders(:, k) = log(errors(:, k) / errors(:, k + 1)) / log(ratio)
        end do
    end function observed_orders

end module convergence_m
