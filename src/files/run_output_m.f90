!> What a run writes while it runs: the fixed output grid, one series entry, one snapshot
!> (the solution interpolated to the output grid, and on a graded mesh its nodal values).
!> The time loop (run_m) says when; this module says what, from the state and the step.
module run_output_m
    use kinds_m, only: dp
    use config_m, only: config_t
    use fe_m, only: mesh_nodes, evaluate_p1
    use config_m, only: model_t
    use fields_m, only: N_SERIES, S_T, S_ENERGY, S_U_END, S_PENETRATION, S_CONTACT_STRESS, S_ITERATIONS, S_DT, &
                        S_N_ELEMENTS, S_ENERGY_PARTS, N_ENERGY_PARTS, N_OUTPUT_FIELDS, OUTPUT_ORDER, N_SNAPSHOT_FIELDS, &
                        K_SIGMA
    use state_m, only: state_t, field_values
    use stress_m, only: nodal_stress
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: energy_monitor_t
    use output_m, only: h5_writer_t
    use errors_m, only: check_allocation
    use error_companion_m, only: error_companions_t, N_ESTIMATE_PARTS
    implicit none
    private
    public :: output_grid, write_series, write_snapshot, write_error_estimate

contains

    !> The fixed grid of the snapshots (/mesh/x): &output n_points uniform points, by
    !> default the nodes of the coarsest mesh.
    subroutine output_grid(cfg, x)
        type(config_t), intent(in) :: cfg
        real(dp), allocatable, intent(out) :: x(:)
        integer :: n, stat
        character(len=256) :: message

        n = cfg%mesh%n_elements
        if (cfg%output%n_points > 0) n = cfg%output%n_points - 1
        ! allocated before the assignment, whose reallocation test would read the bounds of
        ! the unallocated x (valgrind: uninitialised values, gfortran -O0)
        allocate (x(0:n), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the output grid')
        x = mesh_nodes(n)
    end subroutine output_grid

    !> One series entry (fields_m's SERIES); the contact stress is sigma(1,t) = -lambda
    !> (normal compliance (3.4), or the Signorini multiplier). initial: the level is the
    !> initial data, reached without a step (its lambda is the law's force at its u(1)).
    !> dense = [t, u(1,t), E(t), E's parts]: the entry is at t between the steps, from the scheme's
    !> interpolant (dense output, run_m; state: the step's end); lambda is the penalty law's
    !> force at that u(1) (Signorini: the step's multiplier).
    subroutine write_series(writer, stepper, state, monitor, result, initial, dense)
        type(h5_writer_t), intent(inout) :: writer
        type(stepper_t), intent(in) :: stepper
        type(state_t), intent(in) :: state
        type(energy_monitor_t), intent(in) :: monitor   !< has observed the level in state
        type(step_result_t), intent(in) :: result
        logical, intent(in), optional :: initial
        real(dp), intent(in), optional :: dense(3 + N_ENERGY_PARTS)
        real(dp) :: values(N_SERIES)

        values(S_T) = state%t
        values(S_ENERGY) = monitor%current_energy()
        values(S_U_END) = state%u(state%s)
        values(S_PENETRATION) = stepper%law%penetration(state%u(state%s))
        values(S_CONTACT_STRESS) = -result%contact_force
        if (present(initial)) then
            if (initial) values(S_CONTACT_STRESS) = -stepper%law%force(state%u(state%s))
        end if
        if (present(dense)) then
            values(S_T) = dense(1)
            values(S_U_END) = dense(2)
            values(S_ENERGY) = dense(3)
            values(S_PENETRATION) = stepper%law%penetration(dense(2))
            if (.not. stepper%law%is_signorini()) values(S_CONTACT_STRESS) = -stepper%law%force(dense(2))
        end if
        values(S_ITERATIONS) = real(result%iterations, dp)
        values(S_DT) = state%dt_last
        values(S_N_ELEMENTS) = real(state%s, dp)
        if (present(dense)) then
            values(S_ENERGY_PARTS) = dense(4:)
        else
            values(S_ENERGY_PARTS) = monitor%parts(state)
        end if
        call writer%append_series(values)
    end subroutine write_series

    !> One snapshot: every dataset of fields_m's SNAPSHOTS (the fields of OUTPUT_ORDER and
    !> the stress sigma of stress_m, with the coefficients of `model`) on the output grid
    !> x_out (the P1 function of the nodal values evaluated there, unless x_out are the
    !> nodes), and on a graded mesh the nodal values in /snapshots/native.
    subroutine write_snapshot(writer, state, model, x_out)
        type(h5_writer_t), intent(inout) :: writer
        type(state_t), intent(in) :: state
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: x_out(:)
        real(dp) :: values(0:state%s, N_SNAPSHOT_FIELDS), on_grid(size(x_out), N_SNAPSHOT_FIELDS), x(0:state%s)
        integer :: k

        do k = 1, N_OUTPUT_FIELDS
            values(:, k) = field_values(state, OUTPUT_ORDER(k))
        end do
        values(:, K_SIGMA) = nodal_stress(model, state%u, state%w, state%mesh)
        if (size(x_out) == state%s + 1 .and. state%mesh%is_uniform()) then
            call writer%append_snapshot(state%t, values)
            return
        end if
        x = state%mesh%x
        do k = 1, N_SNAPSHOT_FIELDS
            on_grid(:, k) = evaluate_p1(x, values(:, k), x_out)
        end do
        call writer%append_snapshot(state%t, on_grid)
        if (.not. state%mesh%is_uniform()) call writer%append_native(x, values)
    end subroutine write_snapshot

    !> With &output error_estimate: the estimate of the snapshot just written
    !> (/snapshots/error_estimate*; error_companion_m).
    subroutine write_error_estimate(writer, companions, state)
        type(h5_writer_t), intent(inout) :: writer
        type(error_companions_t), intent(inout) :: companions
        type(state_t), intent(in) :: state
        real(dp) :: values(N_OUTPUT_FIELDS, N_ESTIMATE_PARTS)

        call companions%estimate(state, values)
        call writer%append_estimate(values)
    end subroutine write_error_estimate

end module run_output_m
