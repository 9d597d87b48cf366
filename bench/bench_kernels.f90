!> Benchmark (not a test): the per-step cost of rodcontact against the banded-solve floor,
!> all measured in one process on the same machine state.
!>
!>   rodcontact_bench_kernels <input.nml> <s> [batch_seconds] [batches]
!>
!> Reads the namelist (scripts/bench.sh passes input/exp1.nml: the paper's (7.1) model and
!> exp1's initial data), sets n_elements = s and, with the input's dt (1e-4 for exp1):
!>   1. assembles the monolithic matrix of (6.1) (5 fields interleaved, kl = ku = 7), factors
!>      it with dgbtrf (band_t%factor) and the block-tridiagonal LU (block_tridiagonal_t%factor
!>      on the band's node blocks: band_reference_m's factor_band_blocks), and times on the same factors one
!>        dgbtrs        LAPACK's band substitution (tests/lib band_reference_m) - the floor
!>        band_solve    the same substitution as plain loops (band_t%solve)
!>        block_solve   the block-tridiagonal substitution (block_tridiagonal_t%solve)
!>      each on a fresh copy of the same right-hand side; the copy is timed on its own
!>      ('rhs_copy') and subtracted;
!>   2. times one full time step, stepper_t%advance, from exp1's initial data for
!>        step_monolithic_euler, step_monolithic_bdf2, step_paper_euler
!>      (the state advances from t = 0 through the timed steps; 'iterations' is the mean
!>      number of linear solves per step, the paper iteration's count).
!> Each case: repetitions per batch calibrated to about batch_seconds (default 0.02 s, at
!> least 2); `batches` rounds (default 7), each timing every case once (round robin, so
!> that a change of load on a shared machine hits all cases alike). Output: one line per
!> case, key=value fields: us = median over the rounds of the time per call, ns per unknown
!> (n = 5 (s+1) unknowns), ratio_dgbtrs = median over the rounds of (time per call) / (one
!> dgbtrs in the same round), the fastest and slowest round.
program bench_kernels
    use kinds_m, only: dp
    use reals_m, only: equal
    use config_m, only: config_t
    use config_reader_m, only: read_config
    use banded_m, only: band_t, lapack_info_message
    use band_reference_m, only: solve_with_dgbtrs, factor_band_blocks
    use block_tridiagonal_m, only: block_tridiagonal_t
    use scheme_m, only: assemble_matrix
    use slots_m, only: MONOLITHIC_SLOTS
    use meshes_m, only: uniform_mesh
    use fields_m, only: N_FIELDS
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use bench_timing_m, only: wall_seconds, median, num
    implicit none

    integer, parameter :: K_COPY = 1, K_DGBTRS = 2, K_BAND = 3, K_BLOCK = 4, &
                          K_EULER = 5, K_BDF2 = 6, K_PAPER = 7, K_MIDPOINT = 8, K_THERMO = 9, N_CASES = 9
    character(len=*), parameter :: CASE_NAMES(N_CASES) = [character(len=24) :: 'rhs_copy', 'dgbtrs', &
        'band_solve', 'block_solve', 'step_monolithic_euler', 'step_monolithic_bdf2', 'step_paper_euler', &
        'step_monolithic_midpoint', 'step_thermoelastic_euler']

    type(config_t) :: cfg
    type(band_t) :: a
    type(block_tridiagonal_t) :: blocks
    type(stepper_t) :: steppers(K_EULER:K_THERMO)
    type(state_t) :: states(K_EULER:K_THERMO)
    type(step_result_t) :: result
    real(dp), allocatable :: rhs(:), x(:), x_ref(:)
    real(dp) :: setup_seconds, batch_seconds, per_call(N_CASES), sink, diff_band, diff_block
    integer :: s, n, info, k, b, batches, iters, reps(N_CASES), total_iterations(N_CASES)
    real(dp) :: t0
    real(dp), allocatable :: times(:, :), ratios(:, :)
    character(len=1024) :: path, arg

    ! --- arguments ----------------------------------------------------------------------
    if (command_argument_count() < 2) then
        write (*, '(a)') 'usage: rodcontact_bench_kernels <input.nml> <s> [batch_seconds] [batches]'
        stop 2
    end if
    call get_command_argument(1, path)
    call get_command_argument(2, arg)
    read (arg, *) s
    batch_seconds = 0.02_dp
    batches = 7
    if (command_argument_count() >= 3) then
        call get_command_argument(3, arg)
        read (arg, *) batch_seconds
    end if
    if (command_argument_count() >= 4) then
        call get_command_argument(4, arg)
        read (arg, *) batches
    end if

    allocate (times(N_CASES, batches), ratios(N_CASES, batches))
    call read_config(trim(path), cfg)
    cfg%mesh%n_elements = s
    cfg%output%quiet = .true.
    n = N_FIELDS * (s + 1)

    ! --- 1. the monolithic matrix, factored twice -----------------------------------------
    setup_seconds = wall_seconds()
    call assemble_matrix(cfg%model, uniform_mesh(s), cfg%time%dt, MONOLITHIC_SLOTS, a)
    call factor_band_blocks(blocks, a, N_FIELDS, info, .false.)   ! on the unfactored band
    if (info /= 0) then
        write (*, '(a,i0)') 'bench_kernels: block factorisation failed at node ', info
        stop 1
    end if
    call a%factor(info)
    if (info /= 0) then
        write (*, '(a)') 'bench_kernels: '//lapack_info_message('dgbtrf', info)
        stop 1
    end if
    allocate (rhs(n), x(n), x_ref(n))
    do k = 1, n
        rhs(k) = sin(0.1_dp * k) + 0.5_dp      ! any smooth, non-zero right-hand side
    end do
    ! the three substitutions must give the same answer (else the timings mean nothing)
    x_ref = rhs
    call solve_with_dgbtrs(a, x_ref, info)
    if (info /= 0) stop 1
    x = rhs
    call a%solve(x)
    diff_band = maxval(abs(x - x_ref)) / maxval(abs(x_ref))
    x = rhs
    call blocks%solve(x)
    diff_block = maxval(abs(x - x_ref)) / maxval(abs(x_ref))

    ! --- 2. the steppers, from exp1's initial data -----------------------------------------
    do k = K_EULER, K_THERMO
        select case (k)
        case (K_EULER)
            cfg%time%scheme = 'euler'
            cfg%solver%method = 'monolithic'
        case (K_BDF2)
            cfg%time%scheme = 'bdf2'
            cfg%solver%method = 'monolithic'
        case (K_PAPER)
            cfg%time%scheme = 'euler'
            cfg%solver%method = 'paper'
        case (K_MIDPOINT)
            cfg%time%scheme = 'midpoint'
            cfg%solver%method = 'monolithic'
        case (K_THERMO)
            ! thermoelastic scene: gamma2 = d = 0 and P0 = 0, so P and eta are left out
            ! of the system (scheme_m's active_fields): 3 unknowns per node instead of 5
            cfg%time%scheme = 'euler'
            cfg%solver%method = 'monolithic'
            cfg%model%gamma2 = 0.0_dp
            cfg%model%d = 0.0_dp
            cfg%initial%p0_poly = 0.0_dp
        end select
        call initial_state(cfg, states(k))
        call steppers(k)%init(cfg, result)
        if (.not. result%ok) then
            write (*, '(a)') 'bench_kernels: stepper init failed: '//trim(result%message)
            stop 1
        end if
    end do

    setup_seconds = wall_seconds() - setup_seconds
    write (*, '(a,i0,a,i0,a,i0,a,i0,a,a,a,l1,a,l1,a,a,a,a,a,a)') 'setup s=', s, ' n=', n, ' kl=', a%kl, &
        ' ku=', a%ku, ' dt=', num(cfg%time%dt), ' stepper_uses_block_solver=', steppers(K_EULER)%uses_block_solver(), &
        ' bdf2_stepper_uses_block_solver=', steppers(K_BDF2)%uses_block_solver(), &
        ' band_vs_dgbtrs=', num(diff_band), ' block_vs_dgbtrs=', num(diff_block), ' setup_seconds=', num(setup_seconds)

    ! Round robin: every batch round times each case once, so that a change of the machine's
    ! load during the run hits all cases alike; the ratio to dgbtrs is taken within a round.
    sink = 0.0_dp
    total_iterations = 0
    do k = 1, N_CASES
        reps(k) = calibrated_reps(k)
    end do
    do b = 1, batches
        do k = 1, N_CASES
            t0 = wall_seconds()
            call run_batch(k, reps(k), iters)
            times(k, b) = (wall_seconds() - t0) / reps(k)
            total_iterations(k) = total_iterations(k) + iters
        end do
        ! the solves are timed with a fresh copy of the right-hand side: subtract the copy
        times(K_DGBTRS:K_BLOCK, b) = times(K_DGBTRS:K_BLOCK, b) - times(K_COPY, b)
        ratios(:, b) = times(:, b) / times(K_DGBTRS, b)
    end do
    do k = 1, N_CASES
        per_call(k) = median(times(k, :))
        write (*, '(a,a,a,i0,a,i0,a,f0.3,a,f0.3,a,f0.4,a,f0.3,a,f0.3,a,i0,a,i0,a,f0.3)') 'case=', trim(CASE_NAMES(k)), &
            ' s=', s, ' n=', n, ' us=', 1.0e6_dp * per_call(k), ' ns_per_unknown=', 1.0e9_dp * per_call(k) / n, &
            ' ratio_dgbtrs=', median(ratios(k, :)), ' us_min=', 1.0e6_dp * minval(times(k, :)), &
            ' us_max=', 1.0e6_dp * maxval(times(k, :)), ' reps=', reps(k), ' batches=', batches, &
            ' iterations=', real(total_iterations(k), dp) / real(reps(k) * batches, dp)
    end do
    if (equal(sink, 42.0_dp)) write (*, *) sink      ! keeps the copy loop from being optimised away

contains

    !> Repetitions of case k that take about batch_seconds (at least 2), from two single
    !> calls (the first one warms the caches; the BDF2 stepper takes its first, Euler, step
    !> here, so that every timed BDF2 step is a second-order one).
    integer function calibrated_reps(k)
        integer, intent(in) :: k
        real(dp) :: t0, one
        integer :: iters

        call run_batch(k, 1, iters)
        t0 = wall_seconds()
        call run_batch(k, 1, iters)
        one = max(wall_seconds() - t0, 1.0e-8_dp)
        calibrated_reps = max(2, nint(batch_seconds / one))
    end function calibrated_reps

    !> reps calls of case k; iters: the linear solves they made (1 per solve call).
    subroutine run_batch(k, reps, iters)
        integer, intent(in) :: k, reps
        integer, intent(out) :: iters
        integer :: r, info

        iters = 0
        select case (k)
        case (K_COPY)
            do r = 1, reps
                x = rhs
                sink = sink + x(1 + mod(r, n))
            end do
            iters = 0
        case (K_DGBTRS)
            do r = 1, reps
                x = rhs
                call solve_with_dgbtrs(a, x, info)
            end do
            iters = reps
        case (K_BAND)
            do r = 1, reps
                x = rhs
                call a%solve(x)
            end do
            iters = reps
        case (K_BLOCK)
            do r = 1, reps
                x = rhs
                call blocks%solve(x)
            end do
            iters = reps
        case default
            do r = 1, reps
                call steppers(k)%advance(states(k), result)
                if (.not. result%ok) then
                    write (*, '(a)') 'bench_kernels: step failed: '//trim(result%message)
                    stop 1
                end if
                iters = iters + result%iterations
            end do
        end select
        sink = sink + x(1)
    end subroutine run_batch

end program bench_kernels
