!> What a run writes while it runs: the fixed output grid, one series entry, one snapshot
!> (the solution interpolated to the output grid, and on a graded mesh its nodal values),
!> and both between the steps (dense output) from the scheme's interpolant, by the same
!> procedures. The time loop (run_m) says when; this module says what.
module run_output_m
    use kinds_m, only: dp
    use config_m, only: config_t, model_t
    use fe_m, only: mesh_nodes, evaluate_p1
    use fields_m, only: N_SERIES, S_T, S_ENERGY, S_U_END, S_PENETRATION, S_CONTACT_STRESS, S_ITERATIONS, S_DT, &
                        S_N_ELEMENTS, S_ENERGY_PARTS, N_ENERGY_PARTS, N_OUTPUT_FIELDS, OUTPUT_ORDER, N_SNAPSHOT_FIELDS, &
                        K_SIGMA
    use state_m, only: state_t, field_values, copy_state
    use stress_m, only: nodal_stress
    use stepper_m, only: stepper_t, step_result_t
    use contact_law_m, only: contact_law_t
    use energy_m, only: energy_monitor_t, discrete_energy
    use step_driver_m, only: step_driver_t
    use error_estimator_m, only: MAX_LEVELS
    use output_m, only: h5_writer_t
    use errors_m, only: check_allocation
    use error_companion_m, only: error_companions_t, N_ESTIMATE_PARTS
    implicit none
    private
    public :: output_grid, write_series, write_dense_series, dense_series, write_snapshot, write_dense_snapshots, &
              write_error_estimate

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

    !> One series entry (fields_m's SERIES) of the level in state: level_series, then
    !> step_series. initial: the level is the initial data, reached without a step (its
    !> lambda is the law's force at its u(1)).
    subroutine write_series(writer, stepper, state, monitor, result, initial)
        type(h5_writer_t), intent(inout) :: writer
        type(stepper_t), intent(in) :: stepper
        type(state_t), intent(in) :: state
        type(energy_monitor_t), intent(in) :: monitor   !< has observed the level in state
        type(step_result_t), intent(in) :: result
        logical, intent(in), optional :: initial
        real(dp) :: values(N_SERIES)
        logical :: from_law

        from_law = .false.
        if (present(initial)) from_law = initial
        call level_series(state, monitor%current_energy(), monitor%parts(state), values)
        call step_series(stepper%law, state, result, state%t, from_law, values)
        call writer%append_series(values)
    end subroutine write_series

    !> The series values that are a function of a level alone (u, w on its mesh; energy:
    !> its E^n, parts: E's terms, energy_m's discrete_energy); the others are 0 here.
    !> Dense output interpolates these between the steps (write_dense_series).
    pure subroutine level_series(level, energy, parts, values)
        type(state_t), intent(in) :: level
        real(dp), intent(in) :: energy, parts(N_ENERGY_PARTS)
        real(dp), intent(out) :: values(N_SERIES)

        values = 0.0_dp
        values(S_ENERGY) = energy
        values(S_U_END) = level%u(level%s)
        values(S_ENERGY_PARTS) = parts
    end subroutine level_series

    !> The other series values of an entry at t of the last step (state: its end), from
    !> level_series' (interpolated between the steps): the contact stress is sigma(1,t) =
    !> -lambda, the step's (normal compliance (3.4) or the Signorini multiplier), or with
    !> from_law the law's force at u(1,t).
    subroutine step_series(law, state, result, t, from_law, values)
        class(contact_law_t), intent(in) :: law
        type(state_t), intent(in) :: state
        type(step_result_t), intent(in) :: result
        real(dp), intent(in) :: t
        logical, intent(in) :: from_law
        real(dp), intent(inout) :: values(N_SERIES)

        values(S_T) = t
        values(S_PENETRATION) = law%penetration(values(S_U_END))
        values(S_CONTACT_STRESS) = -result%contact_force
        if (from_law) values(S_CONTACT_STRESS) = -law%force(values(S_U_END))
        values(S_ITERATIONS) = real(result%iterations, dp)
        values(S_DT) = state%dt_last
        values(S_N_ELEMENTS) = real(state%s, dp)
    end subroutine step_series

    !> Dense output (&output series_dt) of the step just taken from t_before (state: its
    !> end): the entries at the times n_next series_dt in (t_before, t_n]: dense_series, then
    !> step_series (the penalty law's lambda at the interpolated u(1); Signorini: the step's
    !> multiplier). at_end: an entry so written is at t_n (to round-off).
    subroutine write_dense_series(writer, driver, stepper, state, monitor, result, t_before, series_dt, n_next, &
                                  at_end)
        type(h5_writer_t), intent(inout) :: writer
        type(step_driver_t), intent(in) :: driver
        type(stepper_t), intent(in) :: stepper
        type(state_t), intent(in) :: state
        type(energy_monitor_t), intent(in) :: monitor   !< has observed the level in state
        type(step_result_t), intent(in) :: result
        real(dp), intent(in) :: t_before, series_dt
        integer, intent(inout) :: n_next
        logical, intent(inout) :: at_end
        real(dp) :: rows(N_SERIES, MAX_LEVELS), values(N_SERIES), t, slack
        integer :: n_rows

        n_rows = 0
        slack = 1.0e-9_dp * state%dt_last
        do
            t = real(n_next, dp) * series_dt
            if (t > state%t + slack .or. t <= t_before) exit
            call dense_series(driver, stepper, state, monitor, t, rows, n_rows, values)
            call step_series(stepper%law, state, result, t, .not. stepper%law%is_constraint(), values)
            call writer%append_series(values)
            n_next = n_next + 1
            at_end = at_end .or. t >= state%t - slack
        end do
    end subroutine write_dense_series

    !> The level_series values at t in the last accepted step (state: its end): the scheme's
    !> interpolant (step_driver_t%dense_weights) of those of the step's n_rows levels, rows(:,
    !> j) of the j-th most recent (state's with the monitor's energy, then
    !> step_driver_t%past_level's), computed when n_rows = 0 (once per step).
    subroutine dense_series(driver, stepper, state, monitor, t, rows, n_rows, values)
        type(step_driver_t), intent(in) :: driver
        type(stepper_t), intent(in) :: stepper
        type(state_t), intent(in) :: state
        type(energy_monitor_t), intent(in) :: monitor   !< has observed the level in state
        real(dp), intent(in) :: t
        real(dp), intent(inout) :: rows(N_SERIES, MAX_LEVELS)
        integer, intent(inout) :: n_rows
        real(dp), intent(out) :: values(N_SERIES)
        real(dp) :: weight(MAX_LEVELS), energy, parts(N_ENERGY_PARTS)
        type(state_t) :: level
        integer :: j, n

        call driver%dense_weights(state, t, n, weight)
        if (n_rows == 0) then
            call level_series(state, monitor%current_energy(), monitor%parts(state), rows(:, 1))
            do j = 2, max(n, 2)
                call driver%past_level(state, j, level)
                call discrete_energy(stepper%model, level%u, level%w, level%mesh, energy, parts, stepper%law)
                call level_series(level, energy, parts, rows(:, j))
            end do
        end if
        n_rows = max(n, 2)
        values = weight(1) * rows(:, 1)
        do j = 2, n_rows
            values = values + weight(j) * rows(:, j)
        end do
    end subroutine dense_series

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

    !> Dense output (&output snapshot_dt, snapshot_land = .false.) of the step just taken
    !> from t_before (state: its end): the snapshots at the times n_next snapshot_dt in
    !> (t_before, t_n], each write_snapshot of the level the scheme's interpolant gives
    !> (step_driver_t%dense_level). at_end: a snapshot so written is at t_n (to round-off).
    subroutine write_dense_snapshots(writer, driver, state, model, x_out, t_before, snapshot_dt, n_next, at_end)
        type(h5_writer_t), intent(inout) :: writer
        type(step_driver_t), intent(in) :: driver
        type(state_t), intent(in) :: state
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: x_out(:), t_before, snapshot_dt
        integer, intent(inout) :: n_next
        logical, intent(inout) :: at_end
        type(state_t) :: level
        real(dp) :: t, slack

        slack = 1.0e-9_dp * state%dt_last
        do
            t = real(n_next, dp) * snapshot_dt
            if (t > state%t + slack .or. t <= t_before) exit
            call copy_state(state, level)
            call driver%dense_level(state, t, level%u, level%w)
            level%t = t
            call write_snapshot(writer, level, model, x_out)
            n_next = n_next + 1
            at_end = at_end .or. t >= state%t - slack
        end do
    end subroutine write_dense_snapshots

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
