!> Tests of summary_m (rodcontact --summary): files with known series are written through
!> output_m's h5_writer_t, summarised, and every number is compared with its value worked
!> out by hand from the construction below; then the CSV row, field by field.
!> argv(1) = source dir (unused), argv(2) = scratch dir this test may write into.
program test_summary_m
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    use kinds_m, only: dp
    use output_m, only: h5_writer_t
    use fields_m, only: N_SERIES
    use summary_m, only: summary_t, summarise_file, summarise_series, summary_header, summary_row, csv_field
    use fsys_m, only: remove_file
    use testing_m, only: check_close, check_true, test_summary
    use shipped_inputs_m, only: command_arguments
    implicit none

    real(dp), parameter :: G = 0.1_dp          !< obstacle gap of the test files
    real(dp), parameter :: RATE = 3.0_dp       !< E(t) = 2 exp(-RATE t)
    real(dp), parameter :: TOL = 1.0e-12_dp
    character(len=:), allocatable :: source_dir, scratch

    call command_arguments(source_dir, scratch)
    call test_contact_file()
    call test_failed_file()
    call test_series_edge_cases()
    call test_csv_field()
    call test_summary('test_summary_m')

contains

    !> The known run: t_k = 0.01 k for k <= 60, then 0.02 steps up to t = 1.2 (k = 90);
    !> E_k = 2 exp(-3 t_k); u(1,t_k) = 0.05 except 0.12 for k = 20..29 and 0.13, 0.14,
    !> 0.16, 0.14, 0.13 for k = 58..62 (the last two after the change of spacing).
    subroutine known_series(t, energy, u_end)
        real(dp), allocatable, intent(out) :: t(:), energy(:), u_end(:)
        integer :: k

        allocate (t(0:90), energy(0:90), u_end(0:90))
        do k = 0, 90
            if (k <= 60) then
                t(k) = 0.01_dp * k
            else
                t(k) = 0.6_dp + 0.02_dp * (k - 60)
            end if
        end do
        energy = 2.0_dp * exp(-RATE * t)
        u_end = 0.05_dp
        u_end(20:29) = 0.12_dp
        u_end(58:62) = [0.13_dp, 0.14_dp, 0.16_dp, 0.14_dp, 0.13_dp]
    end subroutine known_series

    !> Write <scratch>/<name>.h5 with the given series and root attributes.
    subroutine write_file(name, t, energy, u_end, status, with_counters)
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: t(:), energy(:), u_end(:)
        character(len=*), intent(in) :: status
        logical, intent(in) :: with_counters
        type(h5_writer_t) :: w
        real(dp) :: pen
        integer :: k, j

        call remove_file(scratch // '/' // name // '.h5')
        call w%create(scratch // '/' // name, [0.0_dp, 0.5_dp, 1.0_dp])
        call w%attr('contact.g', G)
        do k = 1, size(t)
            pen = max(u_end(k) - G, 0.0_dp)
            call w%append_series([t(k), energy(k), u_end(k), pen, -pen / 0.01_dp, 1.0_dp, 0.0_dp, 0.0_dp, &
                                  [(0.0_dp, j = 9, N_SERIES)]])   ! the energy parts: zero
        end do
        if (with_counters) then
            call w%attr('steps', 120)
            call w%attr('wall_seconds', 1.25_dp)
        end if
        call w%finish(status)
    end subroutine write_file

    subroutine test_contact_file()
        real(dp), allocatable :: t(:), energy(:), u_end(:)
        type(summary_t) :: s
        character(len=:), allocatable :: file, row, expected

        call known_series(t, energy, u_end)
        call write_file('known', t, energy, u_end, 'complete', .true.)
        file = scratch // '/known.h5'
        s = summarise_file(file, .false.)
        call check_true('file', s%file == file, 'got ' // s%file)
        call check_true('status', s%status == 'complete', 'got ' // s%status)
        call check_true('contact', s%contact)
        call check_close('first_contact_t (k = 20)', 0.20_dp, s%first_contact_t, TOL)
        call check_close('last_contact_t (k = 62)', 0.64_dp, s%last_contact_t, TOL)
        ! 10 entries k = 20..29 and 3 entries k = 58..60 of spacing 0.01, 2 entries k = 61, 62 of 0.02
        call check_close('contact_time', 10 * 0.01_dp + 3 * 0.01_dp + 2 * 0.02_dp, s%contact_time, TOL)
        call check_close('max_penetration', 0.16_dp - G, s%max_penetration, TOL)
        call check_close('max_u_end', 0.16_dp, s%max_u_end, 0.0_dp)
        call check_close('t_max_u_end (k = 60)', 0.60_dp, s%t_max_u_end, TOL)
        call check_close('g', G, s%g, 0.0_dp)
        call check_close('energy_ratio = exp(-3 * 1.2)', exp(-RATE * 1.2_dp), s%energy_ratio, TOL)
        call check_close('decay_rate (exact exponential)', RATE, s%decay_rate, 1.0e-10_dp)
        call check_close('decay_fit_from_t (first t >= 0.6)', 0.6_dp, s%decay_fit_from_t, TOL)
        call check_close('decay_fit_to_t', 1.2_dp, s%decay_fit_to_t, TOL)
        call check_close('t_final', 1.2_dp, s%t_final, TOL)
        call check_true('steps', s%steps == 120)
        call check_close('wall_seconds', 1.25_dp, s%wall_seconds, 0.0_dp)

        ! the row: the same numbers in the header's order, 15 significant digits
        row = summary_row(s)
        call check_true('header has 31 columns', count_commas(summary_header(.false.)) == 30, summary_header(.false.))
        call check_true('header starts with file,status,contact', &
                        index(summary_header(.false.), 'file,status,contact,first_contact_t [1],') == 1, &
                        summary_header(.false.))
        call check_true('SI header: decay_rate [1/s], wall_seconds [s], g [m]', index(summary_header(.true.), &
                        ',decay_rate [1/s],') > 0 .and. index(summary_header(.true.), ',wall_seconds [s],g [m],') > 0, &
                        summary_header(.true.))
        expected = file // ',complete,yes,0.2,0.64,0.17,0.06,0.16,0.6,1.6,' // &
                   '0.0273237224472926,3,0.6,1.2,1.2,120,1.25,0.1,,,,,,,,,,,,,'
        call check_true('row', row == expected, 'expected ' // expected // new_line('a') // '  got      ' // row)
    end subroutine test_contact_file

    !> A failed run without contact, and without the end-of-run counters: not-applicable
    !> values are empty fields; a status with commas is quoted.
    subroutine test_failed_file()
        real(dp), allocatable :: t(:), energy(:), u_end(:)
        type(summary_t) :: s
        character(len=:), allocatable :: file, row, expected
        integer :: k

        allocate (t(0:3), energy(0:3), u_end(0:3))
        t = [(0.5_dp * k, k = 0, 3)]
        energy = [4.0_dp, 2.0_dp, 1.0_dp, 0.5_dp]
        u_end = [0.0_dp, 0.02_dp, 0.1_dp, 0.03_dp]   ! u = g exactly is not contact
        call write_file('failed', t, energy, u_end, 'failed: step 4 (t = 2), no "convergence"', .false.)
        file = scratch // '/failed.h5'
        s = summarise_file(file, .false.)
        call check_true('failed: status', s%status == 'failed: step 4 (t = 2), no "convergence"', 'got ' // s%status)
        call check_true('failed: no contact at u = g', .not. s%contact)
        call check_true('failed: first_contact_t NaN', ieee_is_nan(s%first_contact_t))
        call check_close('failed: contact_time', 0.0_dp, s%contact_time, 0.0_dp)
        call check_close('failed: max_u_end', 0.1_dp, s%max_u_end, 0.0_dp)
        call check_close('failed: energy_ratio', 0.125_dp, s%energy_ratio, 0.0_dp)
        ! window t >= 0.75: t = 1, 1.5; E halves every 0.5 -> rate 2 log 2
        call check_close('failed: decay_rate', 2.0_dp * log(2.0_dp), s%decay_rate, TOL)
        call check_close('failed: decay_fit_from_t', 1.0_dp, s%decay_fit_from_t, 0.0_dp)
        call check_true('failed: steps absent', s%steps < 0)
        call check_true('failed: wall_seconds absent', ieee_is_nan(s%wall_seconds))
        row = summary_row(s)
        expected = file // ',"failed: step 4 (t = 2), no ""convergence""",no,,,0,0,0.1,1,1,0.125,' // &
                   '1.38629436111989,1,1.5,1.5,,,0.1,,,,,,,,,,,,,'
        call check_true('failed: row', row == expected, 'expected ' // expected // new_line('a') // '  got      ' // row)
    end subroutine test_failed_file

    subroutine test_series_edge_cases()
        type(summary_t) :: s

        ! in contact at t = 0: it counts for first_contact_t but has no interval before it
        s = summarise_series([0.0_dp, 1.0_dp, 2.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [0.2_dp, 0.2_dp, 0.0_dp], &
                             [0.1_dp, 0.1_dp, 0.0_dp], [-10.0_dp, -10.0_dp, 0.0_dp], G)
        call check_close('edge: first_contact_t at t = 0', 0.0_dp, s%first_contact_t, 0.0_dp)
        call check_close('edge: contact_time', 1.0_dp, s%contact_time, 0.0_dp)
        call check_close('edge: last_contact_t', 1.0_dp, s%last_contact_t, 0.0_dp)
        call check_true('edge: E(0) = 0 gives no energy_ratio', ieee_is_nan(s%energy_ratio))
        call check_true('edge: E = 0 gives no decay_rate', ieee_is_nan(s%decay_rate))
        ! one point in the window: no fit
        s = summarise_series([0.0_dp, 1.0_dp], [1.0_dp, 0.5_dp], [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], &
                             [0.0_dp, 0.0_dp], G)
        call check_true('edge: one point in the window gives no decay_rate', ieee_is_nan(s%decay_rate))
        call check_true('edge: and no window', ieee_is_nan(s%decay_fit_from_t))
        ! an empty series (a run killed before its first write)
        s = summarise_series([real(dp) ::], [real(dp) ::], [real(dp) ::], [real(dp) ::], [real(dp) ::], G)
        call check_true('edge: empty series', ieee_is_nan(s%max_u_end) .and. .not. s%contact)
        ! Signorini law: u(1,t) = g, no penetration, the contact is in the multiplier only
        s = summarise_series([0.0_dp, 0.5_dp, 1.0_dp, 1.5_dp], [4.0_dp, 3.0_dp, 2.0_dp, 1.0_dp], &
                             [0.05_dp, G, G, 0.09_dp], [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], &
                             [0.0_dp, -3.0_dp, -1.0_dp, 0.0_dp], G)
        call check_true('signorini: contact from the stress', s%contact)
        call check_close('signorini: first_contact_t', 0.5_dp, s%first_contact_t, 0.0_dp)
        call check_close('signorini: last_contact_t', 1.0_dp, s%last_contact_t, 0.0_dp)
        call check_close('signorini: contact_time', 1.0_dp, s%contact_time, 0.0_dp)
        call check_close('signorini: max_penetration', 0.0_dp, s%max_penetration, 0.0_dp)
    end subroutine test_series_edge_cases

    subroutine test_csv_field()
        call check_true('csv_field plain', csv_field('a b') == 'a b')
        call check_true('csv_field comma', csv_field('a,b') == '"a,b"')
        call check_true('csv_field quote', csv_field('say "x"') == '"say ""x"""')
    end subroutine test_csv_field

    integer function count_commas(text) result(n)
        character(len=*), intent(in) :: text
        integer :: j

        n = 0
        do j = 1, len(text)
            if (text(j:j) == ',') n = n + 1
        end do
    end function count_commas

end program test_summary_m
