!> Unit test of the pure parts of progress_m: the report line, the duration text, the
!> ~10 % schedule of the plain report and the "long enough to report" rule. The object
!> itself is exercised quietly (quiet = .true. must print nothing and must not fail).
program test_progress_m
    use iso_fortran_env, only: error_unit
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use kinds_m, only: dp
    use progress_m, only: progress_t, format_progress_line, format_duration, next_milestone, &
                          progress_wanted
    implicit none

    integer :: n_failed = 0
    integer :: step
    type(progress_t) :: progress

    ! --- one report line -------------------------------------------------------------
    call check_text('line, mid run', &
                    format_progress_line(5000, 10000, 0.5_dp, .true., 12.0_dp), &
                    'step  5000/10000   50.0%  t = 0.500000  ETA 12s  contact')
    call check_text('line, first step, free', &
                    format_progress_line(1, 10000, 1.0e-4_dp, .false., 3725.0_dp), &
                    'step     1/10000    0.0%  t = 0.000100  ETA 1h02m  free')
    call check_text('line, SI run: the unit after t', &
                    format_progress_line(5000, 10000, 0.5_dp, .true., 12.0_dp, ' s'), &
                    'step  5000/10000   50.0%  t = 0.500000 s  ETA 12s  contact')
    call check_text('line, done', &
                    format_progress_line(10000, 10000, 1.0_dp, .false., 0.0_dp), &
                    'step 10000/10000  100.0%  t = 1.000000  ETA 0s  free')
    call check_text('line, unknown ETA, large t', &
                    format_progress_line(7, 9, 2.5e7_dp, .true., -1.0_dp), &
                    'step 7/9   77.8%  t = 2.50000E+07  ETA --  contact')
    call check_text('line, NaN t', &
                    format_progress_line(3, 9, ieee_value(1.0_dp, ieee_quiet_nan), .false., 1.0_dp), &
                    'step 3/9   33.3%  t = NaN  ETA 1s  free')
    call check_int('line length does not change during a run', &
                   len(format_progress_line(9999, 10000, 0.9999_dp, .false., 1.0_dp)), &
                   len(format_progress_line(10, 10000, 0.001_dp, .false., 1.0_dp)))

    ! --- durations ---------------------------------------------------------------------
    call check_text('duration 0', format_duration(0.0_dp), '0s')
    call check_text('duration 59.4', format_duration(59.4_dp), '59s')
    call check_text('duration 185', format_duration(185.0_dp), '3m05s')
    call check_text('duration 3599.6 rounds up', format_duration(3599.6_dp), '1h00m')
    call check_text('duration 7625', format_duration(7625.0_dp), '2h07m')
    call check_text('duration negative', format_duration(-1.0_dp), '--')
    call check_text('duration NaN', format_duration(ieee_value(1.0_dp, ieee_quiet_nan)), '--')

    ! --- the ~10 % schedule of the plain report ------------------------------------------
    call check_int('first milestone of 10000', next_milestone(0, 10000), 1000)
    call check_int('milestone after 1000', next_milestone(1000, 10000), 2000)
    call check_int('milestone after 1001', next_milestone(1001, 10000), 2000)
    call check_int('last milestone of 10000', next_milestone(9999, 10000), 10000)
    call check_int('no milestone after the end', next_milestone(10000, 10000), huge(1))
    call check_int('first milestone of 15 (ceiling)', next_milestone(0, 15), 2)
    call check_int('milestone after 2 of 15', next_milestone(2, 15), 3)
    call check_int('3 steps: every step', next_milestone(1, 3), 2)
    call check_int('no overflow for huge runs', next_milestone(0, 2000000000), 200000000)
    call check_int('lines in a 10000-step run', count_milestones(10000), 10)
    call check_int('lines in a 3-step run', count_milestones(3), 3)

    ! --- when a run is reported ---------------------------------------------------------
    call check_logical('short run (0.3 s of 1 s)', progress_wanted(0.3_dp, 30, 100), .false.)
    call check_logical('prediction not settled', progress_wanted(0.4_dp, 1, 100), .false.)
    call check_logical('predicted 1.2 s', progress_wanted(0.6_dp, 50, 100), .false.)
    call check_logical('predicted 6 s', progress_wanted(0.6_dp, 10, 100), .true.)
    call check_logical('already 2 s', progress_wanted(2.0_dp, 99, 100), .true.)
    call check_logical('finished run', progress_wanted(5.0_dp, 100, 100), .false.)

    ! --- the object: quiet prints nothing, and a fast run prints nothing either ---------
    call progress%start(1000, .true.)
    do step = 1, 1000
        call progress%update(step, real(step, dp) * 1.0e-3_dp, mod(step, 2) == 0)
    end do
    call progress%finish()
    call progress%start(1000, .false.)
    do step = 1, 1000
        call progress%update(step, real(step, dp) * 1.0e-3_dp, .false.)
    end do
    call progress%finish()

    if (n_failed > 0) then
        write (error_unit, '(i0,a)') n_failed, ' check(s) failed'
        stop 1
    end if
    write (*, '(a)') 'test_progress_m: all checks passed'

contains

    !> Number of plain lines the schedule gives for a run of n steps.
    function count_milestones(n) result(lines)
        integer, intent(in) :: n
        integer :: lines

        integer :: step_at

        lines = 0
        step_at = next_milestone(0, n)
        do while (step_at <= n)
            lines = lines + 1
            step_at = next_milestone(step_at, n)
        end do
    end function count_milestones

    subroutine check_text(what, got, expected)
        character(len=*), intent(in) :: what
        character(len=*), intent(in) :: got
        character(len=*), intent(in) :: expected

        if (got /= expected .or. len(got) /= len(expected)) then
            n_failed = n_failed + 1
            write (error_unit, '(a)') 'FAIL '//what
            write (error_unit, '(a)') '  expected: "'//expected//'"'
            write (error_unit, '(a)') '  got:      "'//got//'"'
        end if
    end subroutine check_text

    subroutine check_int(what, got, expected)
        character(len=*), intent(in) :: what
        integer, intent(in) :: got
        integer, intent(in) :: expected

        if (got /= expected) then
            n_failed = n_failed + 1
            write (error_unit, '(a,i0,a,i0)') 'FAIL '//what//': expected ', expected, ', got ', got
        end if
    end subroutine check_int

    subroutine check_logical(what, got, expected)
        character(len=*), intent(in) :: what
        logical, intent(in) :: got
        logical, intent(in) :: expected

        if (got .neqv. expected) then
            n_failed = n_failed + 1
            write (error_unit, '(a,l1,a,l1)') 'FAIL '//what//': expected ', expected, ', got ', got
        end if
    end subroutine check_logical

end program test_progress_m
