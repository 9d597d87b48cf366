!> Exponential decay (Theorem 5.4) on experiment 1 for varpi in {0, 0.1, 0.5, 1}: the rate c0
!> of E(t) ~ C exp(-c0 t) fitted by least squares to log E on t in [0.5, 3], and a check
!> that the decay is at least exponential: over every window of length 0.25 the energy
!> falls by a factor q < 1 (so E(t) <= E(0) q^floor(t/0.25)). Theorem 5.4 needs varpi > 0
!> (its proof uses the viscous dissipation); varpi = 0 is reported, not asserted.
program test_decay
    use kinds_m, only: dp
    use config_m, only: config_t
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: discrete_energy
    use contact_laws_m, only: contact_law
    use shipped_inputs_m, only: load_input, command_arguments
    use testing_m, only: check_true, test_summary
    implicit none
    real(dp), parameter :: VARPIS(4) = [0.0_dp, 0.1_dp, 0.5_dp, 1.0_dp]
    real(dp), parameter :: T_FIT_START = 0.5_dp, WINDOW = 0.25_dp
    integer, parameter :: SAMPLE_EVERY = 100
    character(len=:), allocatable :: source_dir, scratch_dir
    type(config_t) :: cfg
    type(state_t) :: state
    type(stepper_t) :: stepper
    type(step_result_t) :: result
    real(dp), allocatable :: t(:), energy(:)
    real(dp) :: rate, worst_factor
    integer :: k, n, n_steps, n_samples, lag, i
    character(len=200) :: detail

    call command_arguments(source_dir, scratch_dir)
    write (*, '(a)') '| varpi | fitted c0 (t in [0.5, 3]) | E(3)/E(0) | largest E(t+0.25)/E(t) |'
    write (*, '(a)') '|---|---|---|---|'
    do k = 1, size(VARPIS)
        call load_input(source_dir, 'exp1', scratch_dir, cfg)
        cfg%model%varpi = VARPIS(k)
        n_steps = nint(cfg%time%t_end / cfg%time%dt)
        n_samples = n_steps / SAMPLE_EVERY + 1
        if (allocated(t)) deallocate (t, energy)
        allocate (t(n_samples), energy(n_samples))
        call initial_state(cfg, state)
        call stepper%init(cfg, result)
        t(1) = 0.0_dp
        call discrete_energy(cfg%model, state%u, state%w, state%mesh, energy(1), &
                             law=contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps))
        do n = 1, n_steps
            call stepper%advance(state, result)
            if (.not. result%ok) then
                call check_true('step succeeds', .false., result%message)
                exit
            end if
            if (mod(n, SAMPLE_EVERY) == 0) then
                i = n / SAMPLE_EVERY + 1
                t(i) = state%t
                call discrete_energy(cfg%model, state%u, state%w, state%mesh, energy(i), &
                                     law=contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps))
            end if
        end do
        rate = -slope(t, log(energy), T_FIT_START)
        lag = nint(WINDOW / (SAMPLE_EVERY * cfg%time%dt))
        worst_factor = maxval(energy(1 + lag:) / energy(:n_samples - lag))
        write (*, '(a,f4.2,a,f8.4,a,es10.3,a,f8.5,a)') '| ', VARPIS(k), ' | ', rate, ' | ', &
            energy(n_samples) / energy(1), ' | ', worst_factor, ' |'
        if (VARPIS(k) > 0.0_dp) then
            write (detail, '(a,f5.2,a,f9.5,a,f9.5)') 'varpi = ', VARPIS(k), ': fitted rate ', rate, &
                ', largest energy ratio over a window of 0.25: ', worst_factor
            call check_true('positive decay rate', rate > 0.0_dp, detail)
            call check_true('energy falls by a uniform factor < 1 over every window', worst_factor < 1.0_dp, detail)
        end if
    end do
    call test_summary('test_decay')

contains

    !> Least-squares slope of y against x over the points with x >= x_start.
    pure real(dp) function slope(x, y, x_start)
        real(dp), intent(in) :: x(:), y(:), x_start
        real(dp) :: xm, ym
        logical :: use(size(x))

        use = x >= x_start
        xm = sum(x, mask=use) / count(use)
        ym = sum(y, mask=use) / count(use)
        slope = sum((x - xm) * (y - ym), mask=use) / sum((x - xm)**2, mask=use)
    end function slope

end program test_decay
