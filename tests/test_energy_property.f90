!> Corollary 6.2 as a property test: for 50 random valid parameter sets (a fixed seed, so a
!> failure is reproducible; the failing set is printed) — varpi, tau0, tau from 0, eps
!> down to 1e-6, coarse and fine meshes, contact and no contact, penalty and Signorini
!> laws — a short run of the monolithic scheme never lets the discrete energy rise:
!> E^n <= E^{n-1} (1 + 1e-12) at every step.
!> The same sets with scheme = 'bdf2': its G-energy (energy_m's bdf2_energy) must never rise
!> in the sets without contact (G-stability of BDF2 for the linear system); with an active
!> penalty BDF2 has no proven law, and the rises found are counted and reported.
program test_energy_property
    use kinds_m, only: dp
    use config_m, only: config_t
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: discrete_energy, bdf2_energy
    use contact_law_m, only: contact_law
    use testing_m, only: check_true, test_summary
    implicit none
    integer, parameter :: N_SETS = 50, N_STEPS = 150
    real(dp), parameter :: MAX_RISE = 1.0e-12_dp
    integer, parameter :: MESHES(4) = [2, 7, 60, 400]
    type(config_t) :: cfg
    type(state_t) :: state
    type(stepper_t) :: stepper
    type(step_result_t) :: result
    real(dp) :: energy, energy_old, rise, worst
    integer :: k, n, n_contact_sets, n_contact_steps, seed_size
    integer, allocatable :: seed(:)
    character(len=400) :: detail
    integer :: n_bdf2_contact_rises, n_bdf2_free
    real(dp) :: worst_bdf2_contact

    call random_seed(size=seed_size)
    allocate (seed(seed_size))
    seed = 20170523
    call random_seed(put=seed)
    n_contact_sets = 0
    worst = -huge(1.0_dp)
    do k = 1, N_SETS
        call random_configuration(cfg)
        call initial_state(cfg, state)
        call stepper%init(cfg, result)
        call check_true('set-up', result%ok, result%message)
        energy = discrete_energy(cfg%model, contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps), &
                                      state%u, state%w)
        rise = -huge(1.0_dp)
        n_contact_steps = 0
        do n = 1, N_STEPS
            call stepper%advance(state, result)
            if (.not. result%ok) exit
            energy_old = energy
            energy = discrete_energy(cfg%model, contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps), &
                                      state%u, state%w)
            rise = max(rise, (energy - energy_old) / energy_old)
            if (result%in_contact) n_contact_steps = n_contact_steps + 1
        end do
        if (n_contact_steps > 0) n_contact_sets = n_contact_sets + 1
        worst = max(worst, rise)
        write (detail, '(a,i0,a,es10.3,a,11es10.2,a,2es9.2,1x,a,a,i0,a,es9.2)') 'set ', k, ': rise ', rise, &
            ' model ', cfg%model, ' eps, g ', cfg%contact%eps, cfg%contact%g, trim(cfg%contact%law), &
            ' s ', cfg%mesh%n_elements, ' dt ', cfg%time%dt
        call check_true('steps succeed', result%ok, trim(detail)//' '//trim(result%message))
        call check_true('energy never rises', rise <= MAX_RISE, detail)
    end do
    write (*, '(a,i0,a,i0,a,es10.3)') 'parameter sets: ', N_SETS, ', with contact: ', n_contact_sets, &
        ', largest relative energy rise over all: ', worst
    call bdf2_sets()
    call check_true('contact occurs in at least a third of the sets', 3 * n_contact_sets >= N_SETS)
    call check_true('no contact in at least a fifth of the sets', 5 * (N_SETS - n_contact_sets) >= N_SETS)
    call test_summary('test_energy_property')

contains

    !> The same random sets (same seed) with BDF2.
    subroutine bdf2_sets()
        real(dp), allocatable :: u_work(:), w_work(:, :)
        real(dp) :: law, law_old
        logical :: contact

        call random_seed(put=seed)
        n_bdf2_contact_rises = 0
        n_bdf2_free = 0
        worst_bdf2_contact = -huge(1.0_dp)
        do k = 1, N_SETS
            call random_configuration(cfg)
            cfg%time%scheme = 'bdf2'
            call initial_state(cfg, state)
            call stepper%init(cfg, result)
            if (allocated(u_work)) deallocate (u_work, w_work)
            allocate (u_work, mold=state%u)
            allocate (w_work, mold=state%w)
            rise = -huge(1.0_dp)
            contact = .false.
            do n = 1, N_STEPS
                call stepper%advance(state, result)
                if (.not. result%ok) exit
                contact = contact .or. result%in_contact
                law_old = law
                call bdf2_energy(cfg%model, contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps), &
                                 state%u, state%w, state%u_prev, state%w_prev, u_work, w_work, law)
                if (n >= 2) rise = max(rise, (law - law_old) / law_old)
            end do
            call check_true('bdf2 steps succeed', result%ok, result%message)
            write (detail, '(a,i0,a,es10.3)') 'bdf2 set ', k, ' without contact: G-energy rise ', rise
            if (.not. contact) then
                n_bdf2_free = n_bdf2_free + 1
                call check_true('bdf2: G-energy never rises without contact', rise <= MAX_RISE, detail)
            else
                worst_bdf2_contact = max(worst_bdf2_contact, rise)
                if (rise > MAX_RISE) n_bdf2_contact_rises = n_bdf2_contact_rises + 1
            end if
        end do
        write (*, '(a,i0,a,i0,a,i0,a,es10.3)') 'bdf2: sets without contact: ', n_bdf2_free, &
            ' (G-energy never rises: asserted); sets with contact: ', N_SETS - n_bdf2_free, &
            ', of which with a G-energy rise: ', n_bdf2_contact_rises, ', largest: ', worst_bdf2_contact
    end subroutine bdf2_sets

    real(dp) function uniform(a, b)
        real(dp), intent(in) :: a, b
        real(dp) :: r
        call random_number(r)
        uniform = a + (b - a) * r
    end function uniform

    real(dp) function log_uniform(a, b)
        real(dp), intent(in) :: a, b
        log_uniform = exp(uniform(log(a), log(b)))
    end function log_uniform

    !> A value that is exactly zero one time in four, else log-uniform in [a, b].
    real(dp) function zero_or_log_uniform(a, b)
        real(dp), intent(in) :: a, b
        zero_or_log_uniform = 0.0_dp
        if (uniform(0.0_dp, 1.0_dp) > 0.25_dp) zero_or_log_uniform = log_uniform(a, b)
    end function zero_or_log_uniform

    subroutine random_configuration(cfg)
        type(config_t), intent(out) :: cfg
        real(dp) :: amplitude

        cfg%model%rho = log_uniform(1.0e-17_dp, 1.0_dp)
        cfg%model%alpha = log_uniform(1.0e-3_dp, 1.0_dp)
        cfg%model%varpi = zero_or_log_uniform(1.0e-4_dp, 1.0_dp)
        cfg%model%gamma1 = uniform(0.0_dp, 0.5_dp)
        cfg%model%gamma2 = uniform(0.0_dp, 0.5_dp)
        cfg%model%c = log_uniform(0.1_dp, 2.0_dp)
        cfg%model%r = log_uniform(1.0e-4_dp, 1.0_dp)
        cfg%model%d = uniform(0.0_dp, 0.99_dp) * sqrt(cfg%model%c * cfg%model%r)   ! (2.16)
        cfg%model%hbar = log_uniform(1.0e-3_dp, 1.0_dp)
        cfg%model%tau0 = zero_or_log_uniform(1.0e-4_dp, 1.0_dp)
        cfg%model%tau = zero_or_log_uniform(1.0e-4_dp, 1.0_dp)
        cfg%contact%eps = log_uniform(1.0e-6_dp, 0.1_dp)
        cfg%contact%g = log_uniform(1.0e-3_dp, 0.2_dp)
        if (uniform(0.0_dp, 1.0_dp) < 0.2_dp) cfg%contact%law = 'signorini'
        cfg%mesh%n_elements = MESHES(1 + int(uniform(0.0_dp, 3.999_dp)))
        cfg%time%dt = log_uniform(1.0e-5_dp, 0.05_dp)
        cfg%time%t_end = N_STEPS * cfg%time%dt
        ! exp1-like data with random amplitudes; u1 = a x pushes the end towards the obstacle
        amplitude = log_uniform(0.1_dp, 50.0_dp)
        cfg%initial%theta0_poly(0:3) = amplitude * [0.0_dp, 1.0_dp, -2.0_dp, 1.0_dp]
        cfg%initial%p0_poly(0:4) = uniform(-1.0_dp, 1.0_dp) * amplitude * [0.0_dp, 0.0_dp, 1.0_dp, -2.0_dp, 1.0_dp]
        cfg%initial%u1_poly(0:1) = [0.0_dp, log_uniform(0.01_dp, 100.0_dp)]
        cfg%initial%q0_poly(0:1) = [0.0_dp, uniform(-1.0_dp, 1.0_dp)]
        cfg%initial%eta0_poly(0:2) = [0.0_dp, 0.0_dp, uniform(-1.0_dp, 1.0_dp)]
        cfg%initial%u0_poly(0:1) = [0.0_dp, uniform(0.0_dp, 1.0_dp) * cfg%contact%g]
    end subroutine random_configuration

end program test_energy_property
