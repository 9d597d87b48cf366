!> method='monolithic' (exact contact step) and method='paper' (Section 7 iteration stopped
!> at tol) solve the same discrete problem (6.1): on every shipped input, run to t = 0.4
!> (through the first contact of exp1) step by step with both, and require the largest
!> difference of any nodal value, relative to max(1, |value|), to stay below 10 tol, for
!> the default tol = 1e-7 and for tol = 1e-10. `--report` adds the difference against tol
!> over 1e-3 ... 1e-10 on exp1 (Markdown, for docs/verification.md).
program test_methods_agree
    use kinds_m, only: dp
    use config_m, only: config_t
    use state_m, only: state_t, initial_state
    use stepper_m, only: stepper_t, step_result_t
    use shipped_inputs_m, only: SHIPPED_INPUTS, load_input, command_arguments
    use testing_m, only: check_true, test_summary
    implicit none
    character(len=:), allocatable :: source_dir, scratch_dir
    real(dp), parameter :: TOLS(2) = [1.0e-7_dp, 1.0e-10_dp]
    type(config_t) :: cfg, cfg_paper
    type(state_t) :: mono, paper
    type(stepper_t) :: step_mono, step_paper
    type(step_result_t) :: res_mono, res_paper
    real(dp) :: diff, max_diff
    integer :: k, it, n, n_contact, iterations
    character(len=200) :: detail
    character(len=16) :: arg

    call command_arguments(source_dir, scratch_dir)
    call get_command_argument(3, arg)
    if (arg == '--report') call tolerance_table()
    do it = 1, size(TOLS)
        do k = 1, size(SHIPPED_INPUTS)
            call load_input(source_dir, SHIPPED_INPUTS(k), scratch_dir, cfg)
            cfg%solver%method = 'monolithic'
            cfg_paper = cfg
            cfg_paper%solver%method = 'paper'
            cfg_paper%solver%tol = TOLS(it)
            call initial_state(cfg, mono)
            call initial_state(cfg_paper, paper)
            call step_mono%init(cfg, res_mono)
            call step_paper%init(cfg_paper, res_paper)
            call check_true('init', res_mono%ok .and. res_paper%ok)
            max_diff = 0.0_dp
            n_contact = 0
            iterations = 0
            do n = 1, nint(0.4_dp / cfg%time%dt)
                call step_mono%advance(mono, res_mono)
                call step_paper%advance(paper, res_paper)
                if (.not. (res_mono%ok .and. res_paper%ok)) then
                    call check_true(trim(SHIPPED_INPUTS(k))//' steps succeed', .false., &
                                    trim(res_mono%message)//' / '//trim(res_paper%message))
                    exit
                end if
                diff = max(maxval(abs(mono%w - paper%w)) / max(1.0_dp, maxval(abs(mono%w))), &
                           maxval(abs(mono%u - paper%u)) / max(1.0_dp, maxval(abs(mono%u))))
                max_diff = max(max_diff, diff)
                if (res_mono%in_contact) n_contact = n_contact + 1
                iterations = iterations + res_paper%iterations
            end do
            write (detail, '(a,es10.3,a,es10.3)') 'largest relative difference ', max_diff, ' > 10 tol = ', 10 * TOLS(it)
            call check_true(trim(SHIPPED_INPUTS(k))//' methods agree', max_diff <= 10.0_dp * TOLS(it), detail)
            write (*, '(a14,a,es8.1,a,es10.3,a,i5,a,f5.2)') SHIPPED_INPUTS(k), ' tol ', TOLS(it), &
                ' max rel diff ', max_diff, ' contact steps ', n_contact, ' paper its/step ', &
                real(iterations, dp) / n
        end do
    end do
    call test_summary('test_methods_agree')

contains

    !> Largest difference (relative to max(1, |value|)) between the methods on exp1 to
    !> t = 0.4, and the mean number of paper iterations per step, for tol = 1e-3 ... 1e-10.
    subroutine tolerance_table()
        integer :: p

        write (*, '(a)') '| tol | max relative difference | difference / tol | paper iterations per step |'
        write (*, '(a)') '|---|---|---|---|'
        do p = 3, 10
            call load_input(source_dir, 'exp1', scratch_dir, cfg)
            cfg_paper = cfg
            cfg_paper%solver%method = 'paper'
            cfg_paper%solver%tol = 10.0_dp**(-p)
            call initial_state(cfg, mono)
            call initial_state(cfg_paper, paper)
            call step_mono%init(cfg, res_mono)
            call step_paper%init(cfg_paper, res_paper)
            max_diff = 0.0_dp
            iterations = 0
            do n = 1, nint(0.4_dp / cfg%time%dt)
                call step_mono%advance(mono, res_mono)
                call step_paper%advance(paper, res_paper)
                if (.not. (res_mono%ok .and. res_paper%ok)) error stop 'tolerance_table: a step failed'
                max_diff = max(max_diff, maxval(abs(mono%w - paper%w)) / max(1.0_dp, maxval(abs(mono%w))))
                iterations = iterations + res_paper%iterations
            end do
            write (*, '(a,es8.1,a,es10.3,a,f6.3,a,f5.2,a)') '| ', cfg_paper%solver%tol, ' | ', max_diff, ' | ', &
                max_diff / cfg_paper%solver%tol, ' | ', real(iterations, dp) / (n - 1), ' |'
        end do
    end subroutine tolerance_table

end program test_methods_agree
