!> Corollary 6.2: E^n <= E^{n-1}. Short runs (to t = 0.3, through the first contact of exp1)
!> of every shipped input with both solution methods, through the whole program path
!> (run_simulation writes the HDF5 file); the energy series is read back from the file and
!> every relative rise must be <= 1e-12. Also checks the run's own 'energy_max_relative_rise'.
!> The third variant is the monolithic method with the midpoint rule (time_scheme_m); the fourth
!> and fifth are Euler and the midpoint rule with &contact mass = 'redistributed' (E^n with that
!> velocity mass, the one the run's monitor and /series/energy use).
!> The same runs check /series/contact_stress against the penalty law (3.4) applied to
!> /series/u_end: sigma(1,t_n) = -(1/eps) [u^n(1) - g]_+ for Euler (both methods), and for
!> the midpoint rule -(phi(u^n(1)) - phi(u^{n-1}(1))) / (u^n(1) - u^{n-1}(1)), phi(u) =
!> 1/(2 eps) [u - g]_+^2 (its discrete gradient); contact must be reached in some run.
program test_energy_law
    use kinds_m, only: dp
    use config_m, only: config_t
    use run_m, only: run_simulation
    use h5_read_m, only: read_real_1d, read_attr_real, read_attr_str
    use shipped_inputs_m, only: SHIPPED_INPUTS, load_input, command_arguments
    use testing_m, only: check_true, check_close, test_summary
    implicit none
    real(dp), parameter :: MAX_RISE = 1.0e-12_dp
    character(len=:), allocatable :: source_dir, scratch_dir, file, status
    character(len=*), parameter :: METHODS(5) = [character(len=10) :: 'monolithic', 'paper', 'monolithic', &
                                                 'monolithic', 'monolithic']
    character(len=*), parameter :: SCHEMES(5) = [character(len=8) :: 'euler', 'euler', 'midpoint', 'euler', 'midpoint']
    character(len=*), parameter :: MASSES(5) = [character(len=13) :: 'consistent', 'consistent', 'consistent', &
                                                'redistributed', 'redistributed']
    type(config_t) :: cfg
    real(dp), allocatable :: energy(:), u_end(:), stress(:)
    real(dp) :: rise, recorded, stress_error, largest_stress
    integer :: k, m, n
    character(len=160) :: detail
    character(len=80) :: label

    call command_arguments(source_dir, scratch_dir)
    largest_stress = 0.0_dp
    do k = 1, size(SHIPPED_INPUTS)
        do m = 1, size(METHODS)
            call load_input(source_dir, SHIPPED_INPUTS(k), scratch_dir, cfg)
            cfg%time%t_end = 0.3_dp
            cfg%solver%method = METHODS(m)
            cfg%time%scheme = SCHEMES(m)
            cfg%contact%mass = MASSES(m)
            label = trim(SHIPPED_INPUTS(k))//' '//trim(METHODS(m))//' '//trim(SCHEMES(m))//' '//trim(MASSES(m))
            cfg%output%snapshot_every = 1000
            call run_simulation(cfg)
            file = trim(cfg%output%prefix)//'.h5'
            call read_attr_str(file, 'status', status)
            call check_true(trim(label)//' status complete', &
                            status == 'complete')
            call read_real_1d(file, '/series/energy', energy)
            call check_true(trim(SHIPPED_INPUTS(k))//' series length', size(energy) == 3001)
            rise = -huge(1.0_dp)
            do n = 2, size(energy)
                rise = max(rise, (energy(n) - energy(n - 1)) / energy(n - 1))
            end do
            write (detail, '(a,es10.3,a,es10.3,a,es10.3,a,es10.3)') 'largest relative rise ', rise, &
                ' > ', MAX_RISE, '; E(0) = ', energy(1), ', E(end) = ', energy(size(energy))
            call check_true(trim(label)//': energy never rises', &
                            rise <= MAX_RISE, detail)
            call check_true(trim(SHIPPED_INPUTS(k))//': energy decays', energy(size(energy)) < energy(1))
            call read_attr_real(file, 'energy_max_relative_rise', recorded)
            ! the midpoint rule's law is stated for the step's model (rho ~ 1e-17 taken as 0)
            if (SCHEMES(m) == 'euler') &
                call check_close(trim(SHIPPED_INPUTS(k))//' recorded rise attribute', max(rise, 0.0_dp), recorded, 1e-15_dp)
            call check_true(trim(SHIPPED_INPUTS(k))//' recorded law rise', recorded <= MAX_RISE)
            call read_real_1d(file, '/series/u_end', u_end)
            call read_real_1d(file, '/series/contact_stress', stress)
            stress_error = 0.0_dp
            do n = 4, size(stress)     ! the midpoint rule starts with N_DAMPED = 2 Euler steps
                stress_error = max(stress_error, abs(stress(n) - law_stress(SCHEMES(m), u_end(n - 1), u_end(n), &
                                                                            cfg%contact%g, cfg%contact%eps)))
            end do
            largest_stress = max(largest_stress, maxval(abs(stress)))
            write (detail, '(a,es10.3,a,es10.3)') 'largest |sigma - law(u_end)| ', stress_error, &
                ', largest |sigma| ', maxval(abs(stress))
            call check_true(trim(label)// &
                            ': contact stress = the penalty law of u(1,t)', &
                            stress_error <= 1.0e-9_dp * max(1.0_dp, maxval(abs(stress))), trim(detail))
            write (*, '(a14,a11,a9,a14,a,es10.3)') SHIPPED_INPUTS(k), METHODS(m), SCHEMES(m), MASSES(m), &
                ' largest relative energy rise ', rise
        end do
    end do
    call check_true('contact reached in the runs (largest |sigma(1,t)| > 0.01)', largest_stress > 0.01_dp)
    call test_summary('test_energy_law')

contains

    !> sigma(1,t_n) of the penalty law (3.4), sigma = -lambda, from u(1) at t_{n-1} and t_n:
    !> lambda = (1/eps) [u^n(1) - g]_+ (Euler), the discrete gradient of
    !> phi(u) = 1/(2 eps) [u - g]_+^2 between the two (midpoint rule).
    pure real(dp) function law_stress(scheme, u_old, u_new, g, eps) result(sigma)
        character(len=*), intent(in) :: scheme
        real(dp), intent(in) :: u_old, u_new, g, eps

        if (scheme /= 'midpoint') then
            sigma = -max(u_new - g, 0.0_dp) / eps
        else if (max(u_old, u_new) <= g) then
            sigma = 0.0_dp
        else if (abs(u_new - u_old) <= 1.0e-12_dp) then
            sigma = -(0.5_dp * (u_old + u_new) - g) / eps
        else
            sigma = -0.5_dp / eps * (max(u_new - g, 0.0_dp)**2 - max(u_old - g, 0.0_dp)**2) / (u_new - u_old)
        end if
    end function law_stress

end program test_energy_law
