!> The Signorini limit (Section 4): law = 'signorini' solves u(1) <= g exactly with the same
!> active-set step (no penalty); on experiments 1 and 2 it never penetrates (u(1,t) <= g to
!> round-off), its energy never rises, and it does come into contact. The penalty runs
!> converge to it as eps -> 0: the maximum penetration is O(eps) (observed order 1 within
!> 0.15 per decade) and max_t |u_eps(1,t) - u_S(1,t)| decreases at least linearly.
!> Runs use the shipped data on a coarser mesh and to t = 0.6 (through the first contact)
!> so that the test takes seconds; `--report` prints the tables for docs/verification.md.
program test_signorini
    use kinds_m, only: dp
    use config_m, only: config_t
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: discrete_energy
    use contact_laws_m, only: contact_law
    use shipped_inputs_m, only: load_input, command_arguments
    use testing_m, only: check_true, test_summary
    implicit none
    real(dp), parameter :: EPSILONS(7) = [1.0e-2_dp, 1.0e-3_dp, 1.0e-4_dp, 1.0e-5_dp, 1.0e-6_dp, 1.0e-7_dp, 1.0e-8_dp]
    character(len=*), parameter :: EXPERIMENTS(2) = [character(len=4) :: 'exp1', 'exp2']
    character(len=:), allocatable :: source_dir, scratch_dir
    real(dp), allocatable :: u_sig(:), u_pen(:)
    real(dp) :: max_pen(size(EPSILONS)), distance(size(EPSILONS)), rise, max_overshoot, order
    integer :: k, j, n_contact
    character(len=200) :: detail

    call command_arguments(source_dir, scratch_dir)
    do j = 1, size(EXPERIMENTS)
        call run(EXPERIMENTS(j), 'signorini', 0.01_dp, u_sig, rise, n_contact)
        max_overshoot = maxval(u_sig) - 0.1_dp
        write (detail, '(a,es10.3,a,es10.3,a,i0)') 'max u(1,t) - g = ', max_overshoot, ', largest relative energy rise ', &
            rise, ', contact steps ', n_contact
        write (*, '(a,a,a)') trim(EXPERIMENTS(j)), ' signorini: ', trim(detail)
        call check_true(trim(EXPERIMENTS(j))//' signorini: never penetrates', max_overshoot <= 1.0e-14_dp, detail)
        call check_true(trim(EXPERIMENTS(j))//' signorini: energy never rises', rise <= 1.0e-12_dp, detail)
        call check_true(trim(EXPERIMENTS(j))//' signorini: contact occurs', n_contact > 0, detail)
        write (*, '(/,a,a)') '| eps | max penetration | order | max_t |u_eps(1,t) - u_S(1,t)| | order | ', trim(EXPERIMENTS(j))
        write (*, '(a)') '|---|---|---|---|---|'
        do k = 1, size(EPSILONS)
            call run(EXPERIMENTS(j), 'penalty', EPSILONS(k), u_pen, rise, n_contact)
            max_pen(k) = max(maxval(u_pen) - 0.1_dp, 0.0_dp)
            distance(k) = maxval(abs(u_pen - u_sig))
        end do
        write (*, '(a,es8.1,a,es10.3,a,es10.3,a)') '| ', EPSILONS(1), ' | ', max_pen(1), ' | | ', distance(1), ' | |'
        do k = 2, size(EPSILONS)
            order = log10(max_pen(k - 1) / max_pen(k))
            write (*, '(a,es8.1,a,es10.3,a,f5.2,a,es10.3,a,f5.2,a)') '| ', EPSILONS(k), ' | ', max_pen(k), ' | ', &
                order, ' | ', distance(k), ' | ', log10(distance(k - 1) / distance(k)), ' |'
            write (detail, '(a,es8.1,a,f6.3)') 'eps = ', EPSILONS(k), ': observed order of the max penetration ', order
            call check_true(trim(EXPERIMENTS(j))//' penetration is O(eps)', abs(order - 1.0_dp) <= 0.15_dp, detail)
            write (detail, '(a,es8.1,a,es10.3,a,es10.3)') 'eps = ', EPSILONS(k), ': distance to Signorini ', &
                distance(k), ' previous ', distance(k - 1)
            call check_true(trim(EXPERIMENTS(j))//' u(1,t) converges to the Signorini run', &
                            distance(k) <= 0.2_dp * distance(k - 1) .or. distance(k) <= 1.0e-12_dp, detail)
        end do
    end do
    call test_summary('test_signorini')

contains

    !> u(1, t_n) for every step of a run of the shipped experiment with the given law and eps.
    subroutine run(name, law, eps, u_end, max_rise, n_contact)
        character(len=*), intent(in) :: name, law
        real(dp), intent(in) :: eps
        real(dp), allocatable, intent(out) :: u_end(:)
        real(dp), intent(out) :: max_rise
        integer, intent(out) :: n_contact
        type(config_t) :: cfg
        type(state_t) :: state
        type(stepper_t) :: stepper
        type(step_result_t) :: result
        real(dp) :: energy, energy_old
        integer :: n, n_steps

        call load_input(source_dir, name, scratch_dir, cfg)
        cfg%mesh%n_elements = 100
        cfg%time%t_end = 0.6_dp
        cfg%contact%law = law
        cfg%contact%eps = eps
        n_steps = nint(cfg%time%t_end / cfg%time%dt)
        allocate (u_end(n_steps))
        call initial_state(cfg, state)
        call stepper%init(cfg, result)
        call discrete_energy(cfg%model, state%u, state%w, state%mesh, energy, &
                             law=contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps))
        max_rise = -huge(1.0_dp)
        n_contact = 0
        do n = 1, n_steps
            call stepper%advance(state, result)
            if (.not. result%ok) error stop 'test_signorini: a step failed'
            energy_old = energy
            call discrete_energy(cfg%model, state%u, state%w, state%mesh, energy, &
                                 law=contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps))
            max_rise = max(max_rise, (energy - energy_old) / energy_old)
            if (result%in_contact) n_contact = n_contact + 1
            u_end(n) = state%u(state%s)
        end do
    end subroutine run

end program test_signorini
