!> Corollary 6.2 as a property test: for 50 random valid parameter sets (a fixed seed, so a
!> failure is reproducible; the failing set is printed) — varpi, tau0, tau from 0, eps
!> down to 1e-6, coarse and fine meshes, contact and no contact, penalty and Signorini
!> laws — a short run of the monolithic scheme never lets the discrete energy rise:
!> E^n <= E^{n-1} (1 + 1e-12) at every step.
!> The same sets with scheme = 'bdf2': its G-energy (energy_m's bdf2_energy) must never rise
!> in the sets without contact (G-stability of BDF2 for the linear system); with an active
!> penalty BDF2 has no proven law, and the rises found are counted and reported.
!> The same sets with scheme = 'midpoint': after its damped Euler start-up steps, the energy
!> identity E^n - E^{n-1} = -dt (varpi |v_x|^2 + |q|^2 + hbar |eta|^2)(X^{n-1/2}) holds to
!> 1e-12 (relative) at every step with the penalty law, contact or not, and the left side
!> is at most that with the Signorini law. E uses the step's model (stiff_limit); the
!> dissipation is integrated here from the half level the stepper leaves in w_new.
program test_energy_property
    use kinds_m, only: dp
    use config_m, only: config_t, model_t
    use fields_m, only: F_V, F_Q, F_ETA
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use energy_m, only: discrete_energy, bdf2_energy
    use contact_law_m, only: contact_law_t
    use contact_laws_m, only: contact_law
    use testing_m, only: check_true, test_summary
    implicit none
    integer, parameter :: N_SETS = 50, N_STEPS = 150
    real(dp), parameter :: MAX_RISE = 1.0e-12_dp
    integer, parameter :: MESHES(4) = [2, 7, 60, 400]
    !> every set runs with each velocity mass of &contact mass (fe_m's inertia_element)
    character(len=13), parameter :: MASSES(2) = [character(len=13) :: 'consistent', 'redistributed']
    character(len=13) :: mass
    integer :: im
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
    do im = 1, size(MASSES)
        mass = MASSES(im)
        write (*, '(a)') 'mass = ' // trim(mass)
        call euler_sets()
        call bdf2_sets()
        call midpoint_sets()
        call check_true('contact occurs in at least a third of the sets', 3 * n_contact_sets >= N_SETS)
        call check_true('no contact in at least a fifth of the sets', 5 * (N_SETS - n_contact_sets) >= N_SETS)
    end do
    call test_summary('test_energy_property')

contains

    !> The random sets with implicit Euler: E^n never rises (Theorem 6.1), E with the
    !> velocity's mass of the run (stepper%model).
    subroutine euler_sets()

    call random_seed(put=seed)
    n_contact_sets = 0
    worst = -huge(1.0_dp)
    do k = 1, N_SETS
        call random_configuration(cfg)
        call initial_state(cfg, state)
        call stepper%init(cfg, result)
        call check_true('set-up', result%ok, result%message)
        call discrete_energy(stepper%model, state%u, state%w, state%mesh, energy, &
                             law=contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps))
        rise = -huge(1.0_dp)
        n_contact_steps = 0
        do n = 1, N_STEPS
            call stepper%advance(state, result)
            if (.not. result%ok) exit
            energy_old = energy
            call discrete_energy(stepper%model, state%u, state%w, state%mesh, energy, &
                                 law=contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps))
            rise = max(rise, (energy - energy_old) / energy_old)
            if (result%in_contact) n_contact_steps = n_contact_steps + 1
        end do
        if (n_contact_steps > 0) n_contact_sets = n_contact_sets + 1
        worst = max(worst, rise)
        write (detail, '(a,i0,a,es10.3,a,11es10.2,a,2es9.2,1x,a,1x,a,a,i0,a,es9.2)') 'set ', k, ': rise ', rise, &
            ' model ', cfg%model%rho, cfg%model%alpha, cfg%model%varpi, cfg%model%gamma1, cfg%model%gamma2, &
            cfg%model%c, cfg%model%d, cfg%model%r, cfg%model%hbar, cfg%model%tau0, cfg%model%tau, &
            ' eps, g ', cfg%contact%eps, cfg%contact%g, trim(cfg%contact%law), trim(mass), &
            ' s ', cfg%mesh%n_elements, ' dt ', cfg%time%dt
        call check_true('steps succeed', result%ok, trim(detail)//' '//trim(result%message))
        call check_true('energy never rises', rise <= MAX_RISE, detail)
    end do
    write (*, '(a,i0,a,i0,a,es10.3)') 'parameter sets: ', N_SETS, ', with contact: ', n_contact_sets, &
        ', largest relative energy rise over all: ', worst
    end subroutine euler_sets

    !> The same random sets (same seed) with BDF2.
    subroutine bdf2_sets()
        real(dp), allocatable :: u_work(:), w_work(:, :)
        real(dp) :: law, law_old, lin
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
                call discrete_energy(stepper%model, state%u, state%w, state%mesh, lin)
                call bdf2_energy(stepper%model, contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps), &
                                 state%u, state%w, state%u_prev, state%w_prev, state%mesh, u_work, w_work, lin, law)
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

    !> The same random sets (same seed) with the midpoint rule: the energy identity.
    subroutine midpoint_sets()
        real(dp) :: e_old, e_new, residual, worst_identity, worst_signorini
        integer :: n_contact_midpoint
        class(contact_law_t), allocatable :: law

        call random_seed(put=seed)
        worst_identity = 0.0_dp
        worst_signorini = -huge(1.0_dp)
        n_contact_midpoint = 0
        do k = 1, N_SETS
            call random_configuration(cfg)
            cfg%time%scheme = 'midpoint'
            call initial_state(cfg, state)
            call stepper%init(cfg, result)
            call check_true('midpoint set-up', result%ok, result%message)
            law = contact_law(cfg%contact%law, cfg%contact%g, cfg%contact%eps)
            call discrete_energy(stepper%step_model, state%u, state%w, state%mesh, e_new, law=law)
            rise = 0.0_dp
            contact_seen: block
                logical :: contact
                contact = .false.
                do n = 1, N_STEPS
                    e_old = e_new
                    call stepper%advance(state, result)
                    if (.not. result%ok) exit
                    contact = contact .or. result%in_contact
                    call discrete_energy(stepper%step_model, state%u, state%w, state%mesh, e_new, law=law)
                    if (n <= 2) then     ! the damped Euler start-up steps: E^n <= E^{n-1}
                        residual = e_new - e_old
                    else
                        residual = e_new - e_old + cfg%time%dt * dissipation(stepper%step_model, stepper%w_new)
                    end if
                    residual = residual / max(e_old, tiny(1.0_dp))
                    if (n <= 2 .or. law%is_constraint()) then
                        rise = max(rise, residual)
                    else
                        rise = max(rise, abs(residual))
                    end if
                end do
                if (contact) n_contact_midpoint = n_contact_midpoint + 1
            end block contact_seen
            write (detail, '(a,i0,1x,a,a,es10.3)') 'midpoint set ', k, trim(cfg%contact%law), &
                ': largest relative energy-identity residual ', rise
            call check_true('midpoint steps succeed', result%ok, trim(detail)//' '//trim(result%message))
            call check_true('midpoint: energy identity to round-off (penalty), never a rise (Signorini)', &
                            rise <= MAX_RISE, detail)
            if (law%is_constraint()) then
                worst_signorini = max(worst_signorini, rise)
            else
                worst_identity = max(worst_identity, rise)
            end if
        end do
        write (*, '(a,i0,a,es10.3,a,es10.3)') 'midpoint: sets with contact: ', n_contact_midpoint, &
            '; largest identity residual (penalty): ', worst_identity, '; largest rise (Signorini): ', worst_signorini
        call check_true('midpoint: contact occurs in at least a third of the sets', 3 * n_contact_midpoint >= N_SETS)
    end subroutine midpoint_sets

    !> varpi int v_x^2 + int q^2 + hbar int eta^2 of the P1 fields w (uniform mesh), each
    !> integral element by element: int a^2 = h/3 (a0^2 + a0 a1 + a1^2), int a_x^2 = (a1 - a0)^2 / h.
    function dissipation(model, w) result(d)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: w(0:, :)
        real(dp) :: d, h
        integer :: e

        h = 1.0_dp / real(ubound(w, 1), dp)
        d = 0.0_dp
        do e = 1, ubound(w, 1)
            d = d + model%varpi * (w(e, F_V) - w(e - 1, F_V))**2 / h &
                + h / 3.0_dp * (w(e - 1, F_Q)**2 + w(e - 1, F_Q) * w(e, F_Q) + w(e, F_Q)**2) &
                + model%hbar * h / 3.0_dp * (w(e - 1, F_ETA)**2 + w(e - 1, F_ETA) * w(e, F_ETA) + w(e, F_ETA)**2)
        end do
    end function dissipation

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
        cfg%contact%mass = mass
        cfg%initial%u0_poly(0:1) = [0.0_dp, uniform(0.0_dp, 1.0_dp) * cfg%contact%g]
    end subroutine random_configuration

end program test_energy_property
