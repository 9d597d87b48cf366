!> Corollary 6.2: E^n <= E^{n-1}. Short runs (to t = 0.3, through the first contact of exp1)
!> of every shipped input with both solution methods, through the whole program path
!> (run_simulation writes the HDF5 file); the energy series is read back from the file and
!> every relative rise must be <= 1e-12. Also checks the run's own 'energy_max_relative_rise'.
!> The third variant is the monolithic method with the midpoint rule (time_scheme_m).
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
    character(len=*), parameter :: METHODS(3) = [character(len=10) :: 'monolithic', 'paper', 'monolithic']
    character(len=*), parameter :: SCHEMES(3) = [character(len=8) :: 'euler', 'euler', 'midpoint']
    type(config_t) :: cfg
    real(dp), allocatable :: energy(:)
    real(dp) :: rise, recorded
    integer :: k, m, n
    character(len=160) :: detail

    call command_arguments(source_dir, scratch_dir)
    do k = 1, size(SHIPPED_INPUTS)
        do m = 1, size(METHODS)
            call load_input(source_dir, SHIPPED_INPUTS(k), scratch_dir, cfg)
            cfg%time%t_end = 0.3_dp
            cfg%solver%method = METHODS(m)
            cfg%time%scheme = SCHEMES(m)
            cfg%output%snapshot_every = 1000
            call run_simulation(cfg)
            file = trim(cfg%output%prefix)//'.h5'
            call read_attr_str(file, 'status', status)
            call check_true(trim(SHIPPED_INPUTS(k))//' '//trim(METHODS(m))//' '//trim(SCHEMES(m))//' status complete', &
                            status == 'complete')
            call read_real_1d(file, '/series/energy', energy)
            call check_true(trim(SHIPPED_INPUTS(k))//' series length', size(energy) == 3001)
            rise = -huge(1.0_dp)
            do n = 2, size(energy)
                rise = max(rise, (energy(n) - energy(n - 1)) / energy(n - 1))
            end do
            write (detail, '(a,es10.3,a,es10.3,a,es10.3,a,es10.3)') 'largest relative rise ', rise, &
                ' > ', MAX_RISE, '; E(0) = ', energy(1), ', E(end) = ', energy(size(energy))
            call check_true(trim(SHIPPED_INPUTS(k))//' '//trim(METHODS(m))//' '//trim(SCHEMES(m))//': energy never rises', &
                            rise <= MAX_RISE, detail)
            call check_true(trim(SHIPPED_INPUTS(k))//': energy decays', energy(size(energy)) < energy(1))
            call read_attr_real(file, 'energy_max_relative_rise', recorded)
            ! the midpoint rule's law is stated for the step's model (rho ~ 1e-17 taken as 0)
            if (SCHEMES(m) == 'euler') &
                call check_close(trim(SHIPPED_INPUTS(k))//' recorded rise attribute', max(rise, 0.0_dp), recorded, 1e-15_dp)
            call check_true(trim(SHIPPED_INPUTS(k))//' recorded law rise', recorded <= MAX_RISE)
            write (*, '(a14,a11,a9,a,es10.3)') SHIPPED_INPUTS(k), METHODS(m), SCHEMES(m), &
                ' largest relative energy rise ', rise
        end do
    end do
    call test_summary('test_energy_law')
end program test_energy_law
