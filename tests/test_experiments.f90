!> The shipped experiments run in full through the program path, checked against the
!> paper's Section 7 text: exp1 (varpi = 0.1) comes into contact and later leaves it;
!> varpi = 0.5 and 1: no contact at any time; exp2: contact; pulses of amplitude 5: no
!> contact; exp3 (tau = tau0 = 0): contact. Every run: status 'complete' and an energy
!> that never rises (relative rise <= 1e-12).
program test_experiments
    use kinds_m, only: dp
    use reals_m, only: is_zero
    use config_m, only: config_t
    use run_m, only: run_simulation
    use h5_read_m, only: read_real_1d, read_attr_str
    use shipped_inputs_m, only: SHIPPED_INPUTS, load_input, command_arguments
    use testing_m, only: check_true, test_summary
    implicit none
    ! expected contact behaviour per shipped input: 'contact-release' or 'none'
    character(len=*), parameter :: EXPECTED(6) = [character(len=15) :: &
        'contact-release', 'none', 'none', 'contact-release', 'none', 'contact-release']
    character(len=:), allocatable :: source_dir, scratch_dir, file, status
    type(config_t) :: cfg
    real(dp), allocatable :: t(:), u_end(:), pen(:), energy(:)
    real(dp) :: rise, t_first, t_last
    integer :: k, n, first, last
    character(len=200) :: detail

    call command_arguments(source_dir, scratch_dir)
    do k = 1, size(SHIPPED_INPUTS)
        call load_input(source_dir, SHIPPED_INPUTS(k), scratch_dir, cfg)
        call run_simulation(cfg)
        file = trim(cfg%output%prefix)//'.h5'
        call read_attr_str(file, 'status', status)
        call check_true(trim(SHIPPED_INPUTS(k))//': status complete', status == 'complete')
        call read_real_1d(file, '/series/t', t)
        call read_real_1d(file, '/series/u_end', u_end)
        call read_real_1d(file, '/series/penetration', pen)
        call read_real_1d(file, '/series/energy', energy)
        rise = maxval((energy(2:) - energy(:size(energy) - 1)) / energy(:size(energy) - 1))
        write (detail, '(a,es10.3)') 'largest relative energy rise ', rise
        call check_true(trim(SHIPPED_INPUTS(k))//': energy never rises', rise <= 1.0e-12_dp, detail)
        first = findloc(pen > 0.0_dp, .true., dim=1)
        last = findloc(pen > 0.0_dp, .true., dim=1, back=.true.)
        t_first = -1.0_dp
        t_last = -1.0_dp
        if (first > 0) t_first = t(first)
        if (last > 0) t_last = t(last)
        write (detail, '(a,f8.5,a,f8.4,a,f8.4,a,f8.4)') 'max u(1,t) = ', maxval(u_end), ' (g = ', cfg%contact%g, &
            '), first contact t = ', t_first, ', last contact t = ', t_last
        write (*, '(a14,1x,a)') SHIPPED_INPUTS(k), trim(detail)
        select case (trim(EXPECTED(k)))
        case ('none')
            call check_true(trim(SHIPPED_INPUTS(k))//': no contact at any time', maxval(u_end) < cfg%contact%g, detail)
        case ('contact-release')
            call check_true(trim(SHIPPED_INPUTS(k))//': contact', first > 0, detail)
            call check_true(trim(SHIPPED_INPUTS(k))//': contact is lost before t_end', &
                            last > 0 .and. last < size(pen), detail)
            n = size(pen)
            call check_true(trim(SHIPPED_INPUTS(k))//': no second contact', &
                            all(pen(first:last) > 0.0_dp) .and. all(is_zero(pen(last + 1:n))), detail)
        end select
    end do
    call test_summary('test_experiments')
end program test_experiments
