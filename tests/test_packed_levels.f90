!> A stepper that keeps its levels packed (stepper_t%keep_levels_packed: the error estimate's
!> companions, error_companion_m) steps bit for bit as one that does not. Experiment 1 on
!> 40 elements, into contact, for Euler, BDF2 and the midpoint rule, with steps of varying
!> size: after every step the packed level, unpacked (unpack_level) or read packed
!> (level_fields), equals the other stepper's level and level before; a copy of a packed
!> state (copy_state) and a level unpacked in between go on bit for bit too (the packed
!> arrays are filled with NaN at each unpack, so that packing again must read the level).
!> A stepper whose right-hand side old_state_rhs_packed cannot build does not pack: the
!> redistributed mass, fields left out of the system (input/impact.nml).
program test_packed_levels
    use kinds_m, only: dp
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use reals_m, only: equal
    use config_m, only: config_t
    use state_m, only: state_t, initial_state, copy_state
    use stepper_m, only: stepper_t, step_result_t
    use shipped_inputs_m, only: load_input, command_arguments
    use testing_m, only: check_true, test_summary
    implicit none
    character(len=:), allocatable :: source_dir, scratch_dir
    character(len=8), parameter :: SCHEMES(3) = [character(len=8) :: 'euler', 'bdf2', 'midpoint']
    integer, parameter :: N_STEPS = 60
    type(config_t) :: cfg
    integer :: j

    call command_arguments(source_dir, scratch_dir)
    call load_input(source_dir, 'exp1', scratch_dir, cfg)
    cfg%mesh%n_elements = 40
    cfg%time%dt = 5.0e-3_dp
    do j = 1, size(SCHEMES)
        cfg%time%scheme = SCHEMES(j)
        call compare(cfg, trim(SCHEMES(j)))
    end do
    cfg%contact%mass = 'redistributed'
    call check_not_packed(cfg, 'the redistributed mass')
    call load_input(source_dir, 'impact', scratch_dir, cfg)
    call check_not_packed(cfg, 'input/impact.nml (fields left out of the system)')
    call test_summary('test_packed_levels')

contains

    !> N_STEPS steps of both steppers from the initial level, sizes cycling through
    !> dt, dt, 2 dt, dt / 2 (a new system now and then, and BDF2's varying ratio).
    subroutine compare(cfg, name)
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in) :: name
        type(stepper_t) :: plain, packed
        type(state_t) :: x, y, y_copy
        type(step_result_t) :: rx, ry
        real(dp) :: dt, factor(4)
        integer :: n, contact_steps
        logical :: same, same_read, ok, went_packed, same_copy

        factor = [1.0_dp, 1.0_dp, 2.0_dp, 0.5_dp]
        call plain%init(cfg, rx)
        call packed%init(cfg, ry)
        call packed%keep_levels_packed()
        call check_true(name//': the stepper keeps its levels packed', packed%packed_levels)
        call initial_state(cfg, x)
        call initial_state(cfg, y)
        same = .true.
        same_read = .true.
        ok = rx%ok .and. ry%ok
        went_packed = .false.
        contact_steps = 0
        do n = 1, N_STEPS
            dt = factor(1 + mod(n, 4)) * cfg%time%dt
            call plain%advance(x, rx, dt)
            call packed%advance(y, ry, dt)
            ok = ok .and. rx%ok .and. ry%ok
            went_packed = went_packed .or. y%packed
            same = same .and. equal(rx%contact_force, ry%contact_force) .and. all(equal(x%u, y%u))
            if (rx%in_contact) contact_steps = contact_steps + 1
            ! read packed
            same_read = same_read .and. all(equal(packed%level_fields(y, .false.), x%w))
            if (allocated(x%u_prev)) same_read = same_read .and. all(equal(x%u_prev, y%u_prev)) .and. &
                                                 all(equal(packed%level_fields(y, .true.), x%w_prev))
            ! unpacked every 7th step (as a companion at a snapshot), then packed again by the next step
            if (mod(n, 7) == 0) then
                call packed%unpack_level(y)
                same = same .and. .not. y%packed .and. all(equal(x%w, y%w))
                if (allocated(x%u_prev)) same = same .and. all(equal(x%w_prev, y%w_prev))
                ! what the packed arrays held must not matter from now on
                if (allocated(y%wp)) y%wp = ieee_value(1.0_dp, ieee_quiet_nan)
                if (allocated(y%wp_prev)) y%wp_prev = ieee_value(1.0_dp, ieee_quiet_nan)
            end if
        end do
        call check_true(name//': every step succeeds, and the level was packed', ok .and. went_packed)
        call check_true(name//': the run reaches contact', contact_steps > 0)
        call check_true(name//': the packed stepper''s levels, unpacked, equal the plain one''s bit for bit', same)
        call check_true(name//': read packed (level_fields), they equal them too', same_read)
        ! a copy of the packed state goes on as the state itself (a companion's copy at a snapshot)
        call copy_state(y, y_copy)
        call packed%advance(y, ry, cfg%time%dt)
        call packed%advance(y_copy, ry, cfg%time%dt)
        call plain%advance(x, rx, cfg%time%dt)
        call packed%unpack_level(y)
        call packed%unpack_level(y_copy)
        same_copy = all(equal(y%u, y_copy%u)) .and. all(equal(y%w, y_copy%w)) .and. all(equal(x%w, y%w))
        call check_true(name//': a copy of a packed state steps as the state', same_copy)
    end subroutine compare

    !> A stepper for cfg keeps its levels unpacked when asked to pack them (what: the case).
    subroutine check_not_packed(cfg, what)
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in) :: what
        type(stepper_t) :: stepper
        type(step_result_t) :: result

        call stepper%init(cfg, result)
        call stepper%keep_levels_packed()
        call check_true(what//': the stepper is set up and does not pack its levels', &
                        result%ok .and. .not. stepper%packed_levels)
    end subroutine check_not_packed

end program test_packed_levels
