!> One-line summary of a rodcontact HDF5 file (docs/output.md) for parameter scans: whether
!> and when the rod touched the obstacle, how far it went, how the energy decayed, and what
!> the run cost. `rodcontact --summary file.h5` prints summary_row(summarise_file(file));
!> scripts/scan.sh joins the rows of all points of a scan (docs/scans.md).
!>
!> Definitions, on the stored series t_k, E_k, u_k = u(1,t_k), p_k = [u_k - g]_+ and the
!> contact stress sigma_k = sigma(1,t_k) (k = 0..K):
!> - in contact at entry k when p_k > 0 or sigma_k < 0: the normal compliance (3.4) stress
!>   -(1/eps) p_k is nonzero exactly when p_k > 0; with law = 'signorini' u(1,t) <= g and
!>   the contact shows in the multiplier sigma_k only;
!> - contact_time = sum of (t_k - t_{k-1}) over the entries k >= 1 in contact: with
!>   series_every = 1 it is dt times the number of implicit Euler steps in contact;
!> - first/last_contact_t = t_k of the first/last entry in contact;
!> - energy_ratio = E_K / E_0;
!> - decay_rate = -(least-squares slope of log E_k against t_k) over the entries with
!>   t_k >= (t_0 + t_K)/2 (the second half of the run) and E_k > 0, so E ~ exp(-rate t)
!>   there; the fit window is reported as decay_fit_from_t, decay_fit_to_t.
!> A value that does not apply (no contact, fewer than two points to fit, E_0 = 0, an
!> attribute the file lacks) is NaN in summary_t and an empty field in the CSV row.
module summary_m
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
    use kinds_m, only: dp
    use strings_m, only: format_real, doubled_quotes
    use h5_read_m, only: read_real_1d, read_int_1d, read_attr_str, read_attr_real, read_attr_int, attr_exists, is_hdf5_file, &
                         dataset_exists
    use fsys_m, only: file_exists
    implicit none
    private
    public :: summary_t
    public :: summarise_series, summarise_file, summary_problem
    public :: summary_header, summary_row, csv_field

    !> The numbers of one run. NaN (or steps < 0) where a value does not apply.
    type :: summary_t
        character(len=:), allocatable :: file
        character(len=:), allocatable :: status        !< root attribute 'status' ('' if absent)
        logical :: contact = .false.                   !< p_k > 0 for some k
        real(dp) :: first_contact_t = 0.0_dp
        real(dp) :: last_contact_t = 0.0_dp
        real(dp) :: contact_time = 0.0_dp
        real(dp) :: max_penetration = 0.0_dp           !< max_k p_k
        real(dp) :: max_u_end = 0.0_dp                 !< max_k u(1,t_k)
        real(dp) :: t_max_u_end = 0.0_dp               !< the first t_k where it is reached
        real(dp) :: g = 0.0_dp                         !< contact.g of the run
        real(dp) :: energy_ratio = 0.0_dp              !< E_K / E_0
        real(dp) :: decay_rate = 0.0_dp                !< -d(log E)/dt fitted over the window
        real(dp) :: decay_fit_from_t = 0.0_dp
        real(dp) :: decay_fit_to_t = 0.0_dp
        real(dp) :: t_final = 0.0_dp                   !< t_K, the last stored time
        integer :: steps = -1                          !< root attribute 'steps'
        real(dp) :: wall_seconds = 0.0_dp              !< root attribute 'wall_seconds'
        !> root attribute 'step_control_error_sum_relative' of adaptive steps (NaN if absent)
        real(dp) :: time_error = 0.0_dp   ! set to NaN by summarise_file when absent
        !> root attributes 'error_estimate.<field>' (&output error_estimate; NaN if absent),
        !> the fields in ESTIMATE_FIELDS' order
        real(dp) :: error_estimate(6) = 0.0_dp
        !> /events: the onset and the release times, ';'-separated ('' if none or absent)
        character(len=:), allocatable :: onsets, releases
    end type summary_t

    integer, parameter :: N_COLUMNS = 27
    character(len=*), parameter :: ESTIMATE_FIELDS(6) = [character(len=5) :: 'u', 'v', 'theta', 'P', 'q', 'eta']
    character(len=*), parameter :: COLUMNS(N_COLUMNS) = [character(len=16) :: &
        'file', 'status', 'contact', 'first_contact_t', 'last_contact_t', 'contact_time', &
        'max_penetration', 'max_u_end', 't_max_u_end', 'max_u_end_over_g', 'energy_ratio', &
        'decay_rate', 'decay_fit_from_t', 'decay_fit_to_t', 't_final', 'steps', 'wall_seconds', 'g', &
        'step_control_err', 'onset_times', 'release_times', &
        'error_u', 'error_v', 'error_theta', 'error_P', 'error_q', 'error_eta']

contains

    !> The series part of the summary (everything but file, status, steps, wall seconds).
    !> t, energy, u_end, penetration, contact_stress: the /series datasets; g: the gap.
    pure function summarise_series(t, energy, u_end, penetration, contact_stress, g) result(s)
        real(dp), intent(in) :: t(:), energy(:), u_end(:), penetration(:), contact_stress(:)
        real(dp), intent(in) :: g
        type(summary_t) :: s
        real(dp) :: nan, t_half
        integer :: k, n
        logical :: in_fit(size(t)), touching(size(t))

        nan = ieee_value(0.0_dp, ieee_quiet_nan)
        s%g = g
        n = size(t)
        if (n == 0) then
            s%first_contact_t = nan; s%last_contact_t = nan; s%max_penetration = nan; s%max_u_end = nan
            s%t_max_u_end = nan; s%energy_ratio = nan; s%decay_rate = nan; s%decay_fit_from_t = nan
            s%decay_fit_to_t = nan; s%t_final = nan
            return
        end if
        s%t_final = t(n)
        touching = penetration > 0.0_dp .or. contact_stress < 0.0_dp
        s%contact = any(touching)
        s%first_contact_t = nan
        s%last_contact_t = nan
        if (s%contact) then
            s%first_contact_t = t(findloc(touching, .true., dim=1))
            s%last_contact_t = t(findloc(touching, .true., dim=1, back=.true.))
        end if
        s%contact_time = 0.0_dp
        do k = 2, n
            if (touching(k)) s%contact_time = s%contact_time + (t(k) - t(k - 1))
        end do
        s%max_penetration = maxval(penetration)
        s%max_u_end = maxval(u_end)
        s%t_max_u_end = t(maxloc(u_end, dim=1))
        if (energy(1) > 0.0_dp) then
            s%energy_ratio = energy(n) / energy(1)
        else
            s%energy_ratio = nan
        end if
        t_half = 0.5_dp * (t(1) + t(n))
        in_fit = t >= t_half .and. energy > 0.0_dp
        s%decay_rate = -log_slope(pack(t, in_fit), pack(energy, in_fit))
        if (count(in_fit) >= 2) then
            s%decay_fit_from_t = minval(t, mask=in_fit)
            s%decay_fit_to_t = maxval(t, mask=in_fit)
        else
            s%decay_fit_from_t = nan
            s%decay_fit_to_t = nan
        end if
    end function summarise_series

    !> Least-squares slope of log(y) against x; NaN for fewer than two points or all x equal.
    pure function log_slope(x, y) result(slope)
        real(dp), intent(in) :: x(:), y(:)
        real(dp) :: slope
        real(dp) :: x_mean, ly_mean, sxx

        slope = ieee_value(0.0_dp, ieee_quiet_nan)
        if (size(x) < 2) return
        ! centred sums: t ~ 1 and log E ~ -10 would lose digits in the raw normal equations
        x_mean = sum(x) / size(x)
        ly_mean = sum(log(y)) / size(y)
        sxx = sum((x - x_mean)**2)
        if (.not. sxx > 0.0_dp) return
        slope = sum((x - x_mean) * (log(y) - ly_mean)) / sxx
    end function log_slope

    !> Summary of the rodcontact HDF5 file `file`: series from /series, 'status', 'steps',
    !> 'wall_seconds' and 'contact.g' from the root attributes when present (a run killed
    !> before the end leaves a .h5.part without 'steps' and 'wall_seconds').
    function summarise_file(file) result(s)
        character(len=*), intent(in) :: file
        type(summary_t) :: s
        real(dp), allocatable :: t(:), energy(:), u_end(:), penetration(:), contact_stress(:)
        real(dp) :: g
        integer :: k
        character(len=:), allocatable :: status

        call read_real_1d(file, '/series/t', t)
        call read_real_1d(file, '/series/energy', energy)
        call read_real_1d(file, '/series/u_end', u_end)
        call read_real_1d(file, '/series/penetration', penetration)
        call read_real_1d(file, '/series/contact_stress', contact_stress)
        g = ieee_value(0.0_dp, ieee_quiet_nan)
        if (attr_exists(file, 'contact.g')) call read_attr_real(file, 'contact.g', g)
        s = summarise_series(t, energy, u_end, penetration, contact_stress, g)
        s%file = file
        s%status = ''
        if (attr_exists(file, 'status')) then
            call read_attr_str(file, 'status', status)
            s%status = status
        end if
        if (attr_exists(file, 'steps')) call read_attr_int(file, 'steps', s%steps)
        s%wall_seconds = ieee_value(0.0_dp, ieee_quiet_nan)
        if (attr_exists(file, 'wall_seconds')) call read_attr_real(file, 'wall_seconds', s%wall_seconds)
        s%time_error = ieee_value(0.0_dp, ieee_quiet_nan)
        if (attr_exists(file, 'step_control_error_sum_relative')) &
            call read_attr_real(file, 'step_control_error_sum_relative', s%time_error)
        s%error_estimate = ieee_value(0.0_dp, ieee_quiet_nan)
        do k = 1, size(ESTIMATE_FIELDS)
            if (attr_exists(file, 'error_estimate.'//trim(ESTIMATE_FIELDS(k)))) &
                call read_attr_real(file, 'error_estimate.'//trim(ESTIMATE_FIELDS(k)), s%error_estimate(k))
        end do
        call read_events(file, s)
    end function summarise_file

    !> The onset and release times of /events (absent in files of older versions).
    subroutine read_events(file, s)
        character(len=*), intent(in) :: file
        type(summary_t), intent(inout) :: s
        real(dp), allocatable :: t(:)
        integer, allocatable :: kind(:)
        integer :: k

        s%onsets = ''
        s%releases = ''
        if (.not. dataset_exists(file, '/events/t')) return
        if (.not. dataset_exists(file, '/events/kind')) return
        call read_real_1d(file, '/events/t', t)
        call read_int_1d(file, '/events/kind', kind)
        do k = 1, min(size(t), size(kind))
            if (kind(k) > 0) then
                s%onsets = s%onsets // merge(';', ' ', len(s%onsets) > 0) // format_real(t(k))
            else
                s%releases = s%releases // merge(';', ' ', len(s%releases) > 0) // format_real(t(k))
            end if
        end do
        s%onsets = trim(adjustl(s%onsets))
        s%releases = trim(adjustl(s%releases))
    end subroutine read_events

    !> Why `file` cannot be summarised ('' when it can): it does not exist, is not a readable
    !> HDF5 file, or is not a rodcontact output file (no /series datasets the summary reads, or
    !> no root attribute 'status'). Tested before any read, which would stop the whole summary
    !> (exit 2) at the first file it cannot read.
    function summary_problem(file) result(reason)
        character(len=*), intent(in) :: file
        character(len=:), allocatable :: reason
        character(len=*), parameter :: NEEDED(5) = [character(len=24) :: '/series/t', '/series/energy', &
            '/series/u_end', '/series/penetration', '/series/contact_stress']
        integer :: k

        reason = ''
        if (.not. file_exists(file)) then
            reason = 'no such file'
        else if (.not. is_hdf5_file(file)) then
            reason = 'not an HDF5 file, or not readable'
        else if (.not. attr_exists(file, 'status')) then
            reason = "not a rodcontact output file (no root attribute 'status')"
        else
            do k = 1, size(NEEDED)
                if (.not. dataset_exists(file, trim(NEEDED(k)))) then
                    reason = 'not a rodcontact output file (no dataset '//trim(NEEDED(k))//')'
                    return
                end if
            end do
        end if
    end function summary_problem

    !> 'file,status,contact,...': the CSV header of summary_row.
    pure function summary_header() result(line)
        character(len=:), allocatable :: line
        integer :: k

        line = trim(COLUMNS(1))
        do k = 2, N_COLUMNS
            line = line // ',' // trim(COLUMNS(k))
        end do
    end function summary_header

    !> One CSV row (RFC 4180 quoting) in the order of summary_header; reals with 15
    !> significant digits; a value that does not apply is an empty field.
    pure function summary_row(s) result(line)
        type(summary_t), intent(in) :: s
        character(len=:), allocatable :: line
        character(len=16) :: buf
        character(len=:), allocatable :: steps, contact
        integer :: k

        contact = 'no'
        if (s%contact) contact = 'yes'
        steps = ''
        if (s%steps >= 0) then
            write (buf, '(i0)') s%steps
            steps = trim(buf)
        end if
        line = csv_field(s%file) // ',' // csv_field(s%status) // ',' // contact // &
               ',' // num(s%first_contact_t) // ',' // num(s%last_contact_t) // ',' // num(s%contact_time) // &
               ',' // num(s%max_penetration) // ',' // num(s%max_u_end) // ',' // num(s%t_max_u_end) // &
               ',' // num(ratio_to_g(s)) // ',' // num(s%energy_ratio) // ',' // num(s%decay_rate) // &
               ',' // num(s%decay_fit_from_t) // ',' // num(s%decay_fit_to_t) // ',' // num(s%t_final) // &
               ',' // steps // ',' // num(s%wall_seconds) // ',' // num(s%g) // ',' // num(s%time_error) // &
               ',' // csv_field(text_or_empty(s%onsets)) // ',' // csv_field(text_or_empty(s%releases))
        do k = 1, size(s%error_estimate)
            line = line // ',' // num(s%error_estimate(k))
        end do
    end function summary_row

    pure function text_or_empty(text) result(out)
        character(len=:), allocatable, intent(in) :: text
        character(len=:), allocatable :: out

        out = ''
        if (allocated(text)) out = text
    end function text_or_empty

    !> max u(1,t)/g; NaN when g is unknown (NaN) or 0 (a summary_t not filled in).
    pure function ratio_to_g(s) result(ratio)
        type(summary_t), intent(in) :: s
        real(dp) :: ratio

        ratio = ieee_value(0.0_dp, ieee_quiet_nan)
        if (ieee_is_finite(s%g)) then
            if (abs(s%g) > 0.0_dp) ratio = s%max_u_end / s%g
        end if
    end function ratio_to_g

    !> x to 15 significant digits, '' for NaN or +-Inf (not applicable).
    pure function num(x) result(text)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text

        ! no comparison with x: one with a NaN raises IEEE invalid (a trap in Debug builds)
        if (ieee_is_finite(x)) then
            text = format_real(x)
        else
            text = ''
        end if
    end function num

    !> text as one CSV field: in double quotes (inner ones doubled) when it holds a comma,
    !> a double quote or a line break, as is otherwise (RFC 4180).
    pure function csv_field(text) result(field)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: field

        if (scan(text, ',"' // achar(10) // achar(13)) == 0) then
            field = text
        else
            field = doubled_quotes(text, '"')
        end if
    end function csv_field

end module summary_m
