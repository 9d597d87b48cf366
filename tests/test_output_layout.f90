!> The HDF5 file of a whole run (docs/output.md): dataset shapes, the times of the series
!> and snapshots, root attributes, no .part left behind, and the t = 0 entries equal to the
!> initial data: snapshot columns against the initial profiles evaluated here from their
!> formulas, the first energy against an independent quadrature of the P1 interpolants.
program test_output_layout
    use kinds_m, only: dp
    use config_m, only: config_t
    use validate_m, only: validate_config
    use time_scheme_m, only: scheme_rules
    use run_m, only: run_simulation
    use h5_arrays_m, only: read_int_1d, read_real_2d, read_attr_int
    use h5_read_m, only: read_real_1d, read_attr_str, read_attr_real, &
                         dataset_exists
    use fsys_m, only: file_exists
    use quadrature_m, only: hat, hat_dx
    use shipped_inputs_m, only: command_arguments
    use testing_m, only: check_true, check_close, test_summary
    implicit none
    integer, parameter :: s = 8
    character(len=:), allocatable :: source_dir, scratch_dir, file, text
    character(len=*), parameter :: FIELDS(6) = [character(len=5) :: 'u', 'v', 'theta', 'P', 'q', 'eta']
    type(config_t) :: cfg
    real(dp), allocatable :: x(:), t(:), snap(:, :), series(:)
    integer, allocatable :: iterations(:)
    real(dp) :: expected(0:s), value
    integer :: i, f, ivalue
    character(len=64) :: name

    call command_arguments(source_dir, scratch_dir)
    cfg%mesh%n_elements = s
    cfg%time%dt = 0.01_dp
    cfg%time%t_end = 0.05_dp
    cfg%output%snapshot_every = 2
    cfg%output%prefix = scratch_dir//'/nested/dir/layout'
    cfg%output%quiet = .true.
    cfg%model%rho = 0.5_dp                                   ! make every energy term count
    cfg%initial%u0_poly(0:1) = [0.0_dp, 0.05_dp]             ! u0 = 0.05 x
    cfg%initial%u1_poly(0:1) = [0.0_dp, 10.0_dp]             ! u1 = 10 x
    cfg%initial%theta0_poly(0:3) = [0.0_dp, 40.0_dp, -80.0_dp, 40.0_dp]   ! 40 x (x-1)^2
    cfg%initial%p0_step = [20.0_dp, 0.5_dp]                  ! 20 on [0, 0.5)
    cfg%initial%p0_poly(0:1) = [1.0_dp, -1.0_dp]             ! + (1 - x)
    cfg%initial%q0_poly(0:2) = [0.0_dp, 0.3_dp, 0.2_dp]      ! 0.3 x + 0.2 x^2
    cfg%initial%eta0_poly(0:2) = [0.0_dp, 1.0_dp, -1.0_dp]   ! x (1 - x)
    call validate_config(cfg, scheme_rules())
    call run_simulation(cfg)

    file = trim(cfg%output%prefix)//'.h5'
    call check_true('output file exists', file_exists(file))
    call check_true('no .part left', .not. file_exists(file//'.part'))
    call read_attr_str(file, 'status', text)
    call check_true('status = complete', text == 'complete', 'got '//text)
    call read_attr_int(file, 'steps', ivalue)
    call check_true('steps = 5', ivalue == 5)
    call read_attr_real(file, 'model.rho', value)
    call check_close('attribute model.rho', 0.5_dp, value, 0.0_dp)
    call read_attr_str(file, 'solver.method', text)
    call check_true('attribute solver.method', text == 'monolithic')

    call read_real_1d(file, '/mesh/x', x)
    call check_true('/mesh/x has s+1 entries', size(x) == s + 1)
    do i = 0, s
        call check_close('/mesh/x value', real(i, dp) / s, x(i + 1), 1e-15_dp)
    end do
    call read_real_1d(file, '/series/t', t)
    call check_true('/series/t has 6 entries (t = 0 and 5 steps)', size(t) == 6)
    do i = 1, size(t)
        call check_close('/series/t value', 0.01_dp * (i - 1), t(i), 1e-15_dp)
    end do
    call read_real_1d(file, '/snapshots/t', t)
    call check_true('/snapshots/t: t = 0, 0.02, 0.04 and the final 0.05', size(t) == 4)
    if (size(t) == 4) call check_close('last snapshot at t_end', 0.05_dp, t(4), 1e-15_dp)
    call check_close('first snapshot at t = 0', 0.0_dp, t(1), 0.0_dp)

    do f = 1, size(FIELDS)
        call check_true('/snapshots/'//trim(FIELDS(f))//' exists', dataset_exists(file, '/snapshots/'//trim(FIELDS(f))))
        call read_real_2d(file, '/snapshots/'//trim(FIELDS(f)), snap)
        call check_true('/snapshots/'//trim(FIELDS(f))//' is (s+1) x n_snap', all(shape(snap) == [s + 1, 4]))
        do i = 0, s
            expected(i) = initial_value(FIELDS(f), x(i + 1))
        end do
        do i = 0, s
            write (name, '(3a,i0)') 't = 0 snapshot ', trim(FIELDS(f)), ' node ', i
            call check_close(trim(name), expected(i), snap(i + 1, 1), 1e-13_dp)
        end do
    end do
    do f = 1, 5
        call read_real_1d(file, '/series/'//trim(series_name(f)), series)
        call check_true('/series/'//trim(series_name(f))//' has 6 entries', size(series) == 6)
        select case (f)
        case (1); call check_close('t = 0 energy = quadrature of the initial data', reference_energy(), series(1), &
                                   1e-12_dp * reference_energy())
        case (2); call check_close('t = 0 u_end = u0(1)', 0.05_dp, series(1), 1e-15_dp)
        case (3); call check_close('t = 0 penetration', 0.0_dp, series(1), 0.0_dp)
        case (4); call check_close('t = 0 contact_stress', 0.0_dp, series(1), 0.0_dp)
        case (5); call check_true('energy decreases', all(series(2:) <= series(1:5)))
        end select
    end do
    call read_int_1d(file, '/series/iterations', iterations)
    call check_true('t = 0 iterations = 0, then 1 solve per step', &
                    iterations(1) == 0 .and. all(iterations(2:) == 1))
    call test_summary('test_output_layout')

contains

    pure function series_name(k) result(name)
        integer, intent(in) :: k
        character(len=16) :: name
        character(len=16), parameter :: NAMES(5) = [character(len=16) :: 'energy', 'u_end', 'penetration', &
                                                     'contact_stress', 'energy']
        name = NAMES(k)
    end function series_name

    !> The initial data above, from their formulas, with the boundary values of the spaces.
    pure real(dp) function initial_value(field, x)
        character(len=*), intent(in) :: field
        real(dp), intent(in) :: x
        select case (field)
        case ('u'); initial_value = 0.05_dp * x
        case ('v'); initial_value = 10.0_dp * x
        case ('theta'); initial_value = 40.0_dp * x * (x - 1.0_dp)**2
        case ('P')   ! the step's jump at x = 0.5 is node 4: the mean of its two sides there
            initial_value = 1.0_dp - x
            if (abs(x - 0.5_dp) < 1e-12_dp) then
                initial_value = initial_value + 10.0_dp
            else if (x < 0.5_dp) then
                initial_value = initial_value + 20.0_dp
            end if
        case ('q'); initial_value = 0.3_dp * x + 0.2_dp * x**2
        case default; initial_value = x * (1.0_dp - x)
        end select
    end function initial_value

    !> E^0 of Corollary 6.2 by 3-point Gauss quadrature of the P1 interpolants.
    real(dp) function reference_energy()
        real(dp), parameter :: nodes(3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)]
        real(dp), parameter :: weights(3) = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
        real(dp) :: xq, u_x, v, th, p, q, eta, nodal(0:s, 6)
        integer :: e, k, j, ff

        do ff = 1, 6
            do j = 0, s
                nodal(j, ff) = initial_value(FIELDS(ff), real(j, dp) / s)
            end do
        end do
        reference_energy = 0.0_dp
        do e = 1, s
            do k = 1, 3
                xq = (e - 0.5_dp + 0.5_dp * nodes(k)) / s
                u_x = sum([(nodal(j, 1) * hat_dx(j, s, xq), j = 0, s)])
                v = sum([(nodal(j, 2) * hat(j, s, xq), j = 0, s)])
                th = sum([(nodal(j, 3) * hat(j, s, xq), j = 0, s)])
                p = sum([(nodal(j, 4) * hat(j, s, xq), j = 0, s)])
                q = sum([(nodal(j, 5) * hat(j, s, xq), j = 0, s)])
                eta = sum([(nodal(j, 6) * hat(j, s, xq), j = 0, s)])
                associate (m => cfg%model)
                    reference_energy = reference_energy + 0.5_dp * weights(k) / s * 0.5_dp * &
                        (m%rho * v**2 + m%alpha * u_x**2 + m%c * th**2 + m%r * p**2 + 2 * m%d * p * th &
                         + m%tau0 * q**2 + m%tau * m%hbar * eta**2)
                end associate
            end do
        end do
    end function reference_energy

end program test_output_layout
