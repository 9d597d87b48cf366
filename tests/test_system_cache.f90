!> The cache of factored systems (system_cache_m) never uses a system of another step size:
!> one stepper takes steps of several sizes in an order that reuses, adds and replaces
!> cache entries (more sizes than CACHE_SIZE), each step from the same level; each result
!> must equal bit for bit that of a stepper set up afresh for that step size alone. Then one
!> entry of the cached system of one size is perturbed: steps of every other size must stay
!> bit-identical, and a step of that size must change (the cache is used, and the check sees
!> a wrong system).
program test_system_cache
    use kinds_m, only: dp
    use reals_m, only: equal
    use config_m, only: config_t
    use state_m, only: state_t, initial_state, copy_state
    use stepper_m, only: stepper_t, step_result_t
    use system_cache_m, only: CACHE_SIZE
    use fields_m, only: F_V
    use shipped_inputs_m, only: load_input, command_arguments
    use testing_m, only: check_true, test_summary
    implicit none
    character(len=:), allocatable :: source_dir, scratch_dir
    integer, parameter :: N_SIZES = CACHE_SIZE + 2
    type(config_t) :: cfg
    type(state_t) :: start
    type(stepper_t) :: cached
    type(step_result_t) :: result
    real(dp) :: sizes(N_SIZES)
    integer :: i, j, order(3 * N_SIZES), k_perturbed
    logical :: all_same, same
    character(len=160) :: detail

    call command_arguments(source_dir, scratch_dir)
    call load_input(source_dir, 'exp1', scratch_dir, cfg)
    cfg%mesh%n_elements = 40
    cfg%time%adaptive = .true.       ! the factorisation of adaptive steps (block LU trusted)
    do i = 1, N_SIZES
        sizes(i) = 1.0e-4_dp * 2.0_dp**(0.25_dp * (i - 1))
    end do
    ! sizes 1..N, then back and forth so that entries are found, replaced and found again
    order = [(i, i = 1, N_SIZES), (N_SIZES + 1 - i, i = 1, N_SIZES), (1 + mod(7 * i, N_SIZES), i = 1, N_SIZES)]
    call initial_state(cfg, start)
    cfg%time%dt = sizes(1)
    call cached%init(cfg, result)
    call check_true('set-up', result%ok, result%message)

    all_same = .true.
    do j = 1, size(order)
        same = same_as_fresh(sizes(order(j)))
        all_same = all_same .and. same
    end do
    write (detail, '(i0,a,i0,a)') size(order), ' steps of ', N_SIZES, ' sizes'
    call check_true('every cached step equals bit for bit a step with a system factored for its size', all_same, &
                    trim(detail))

    ! perturb one entry of the factored system of sizes(3) held in the cache
    call step_with(cached, sizes(3))
    k_perturbed = 0
    do i = 1, CACHE_SIZE
        if (equal(cached%cache%systems(i)%dt_eff, sizes(3))) k_perturbed = i
    end do
    call check_true('the system of the last step size is in the cache', k_perturbed > 0)
    if (k_perturbed > 0) then
        ! one entry: the diagonal of the inverted pivot block of node 5 in the v row (v is
        ! nonzero in the first step; other fields' right-hand sides may be zero there)
        associate (g => cached%cache%systems(k_perturbed)%blocks%g, v => cached%slots(F_V))
            g(v, v, 5) = g(v, v, 5) * (1.0_dp + 1.0e-3_dp)
        end associate
        same = same_as_fresh(sizes(3))
        call check_true('with the system of one size perturbed, a step of that size changes', .not. same)
        ! the sizes held in the other entries (found, so nothing is evicted)
        all_same = .true.
        do i = 1, CACHE_SIZE
            if (i == k_perturbed .or. .not. cached%cache%systems(i)%dt_eff > 0.0_dp) cycle
            same = same_as_fresh(cached%cache%systems(i)%dt_eff)
            all_same = all_same .and. same
        end do
        call check_true('with the system of one size perturbed, steps of every other cached size are unchanged', &
                        all_same)
        same = same_as_fresh(sizes(3))
        call check_true('... and the perturbed system is still the one used for its size', .not. same)
    end if
    call test_summary('test_system_cache')

contains

    !> One step of size dt from the start level by the cached stepper, and by a stepper set
    !> up for dt alone: the same bits?
    logical function same_as_fresh(dt) result(same)
        real(dp), intent(in) :: dt
        type(stepper_t) :: fresh
        type(config_t) :: cfg_dt
        type(state_t) :: a, b
        type(step_result_t) :: result_a, result_b

        call copy_state(start, a)
        call cached%advance(a, result_a, dt)
        cfg_dt = cfg
        cfg_dt%time%dt = dt
        call fresh%init(cfg_dt, result_b)
        call copy_state(start, b)
        call fresh%advance(b, result_b, dt)
        same = result_a%ok .and. result_b%ok .and. all(equal(a%u, b%u)) .and. all(equal(a%w, b%w))
    end function same_as_fresh

    subroutine step_with(stepper, dt)
        type(stepper_t), intent(inout) :: stepper
        real(dp), intent(in) :: dt
        type(state_t) :: a
        type(step_result_t) :: r

        call copy_state(start, a)
        call stepper%advance(a, r, dt)
    end subroutine step_with

end program test_system_cache
