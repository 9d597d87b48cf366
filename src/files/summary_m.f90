!> The rows of `rodcontact --summary` (summary_row(summarise_file(file)): one per run, what
!> scripts/scan.sh joins) and `--events` (write_event_rows: one per contact event) of
!> rodcontact HDF5 files. Each column's definition and units (file_in_si): docs/scans.md.
!> A value that does not apply is NaN in summary_t and an empty field in the CSV row.
module summary_m
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use, intrinsic :: iso_fortran_env, only: int64
    use kinds_m, only: dp
    use strings_m, only: format_real, doubled_quotes, int_str
    use h5_read_m, only: read_real_1d, read_attr_str, read_attr_real, attr_exists, is_hdf5_file, &
                         dataset_exists
    use fsys_m, only: file_exists
    use fields_m, only: FIELDS, OUTPUT_ORDER, N_OUTPUT_FIELDS
    implicit none
    private
    public :: summary_t
    public :: summarise_series, summarise_file, summary_problem
    public :: summary_header, summary_row, csv_field
    public :: events_header, write_event_rows, file_in_si

    !> A quiet NaN: what a value that does not apply is
    real(dp), parameter :: NAN = transfer(9221120237041090560_int64, 1.0_dp)   ! 0x7FF8000000000000

    !> The numbers of one run. NaN (or steps < 0) where a value does not apply.
    type :: summary_t
        character(len=:), allocatable :: file
        character(len=:), allocatable :: status        !< root attribute 'status' ('' if absent)
        logical :: contact = .false.                   !< p_k > 0 for some k
        real(dp) :: first_contact_t = NAN
        real(dp) :: last_contact_t = NAN
        real(dp) :: contact_time = 0.0_dp
        real(dp) :: max_penetration = NAN              !< max_k p_k
        real(dp) :: max_u_end = NAN                    !< max_k u(1,t_k)
        real(dp) :: t_max_u_end = NAN                  !< the first t_k where it is reached
        real(dp) :: g = NAN                            !< contact.g of the run
        real(dp) :: energy_ratio = NAN                 !< E_K / E_0
        real(dp) :: decay_rate = NAN                   !< -d(log E)/dt fitted over the window
        real(dp) :: decay_fit_from_t = NAN
        real(dp) :: decay_fit_to_t = NAN
        real(dp) :: t_final = NAN                      !< t_K, the last stored time
        integer :: steps = -1                          !< root attribute 'steps'
        real(dp) :: wall_seconds = NAN                 !< root attribute 'wall_seconds'
        !> root attribute 'step_control_error_sum_relative' of adaptive steps (NaN if absent)
        real(dp) :: time_error = NAN
        !> root attributes 'error_estimate.<field>' (&output error_estimate; NaN if absent),
        !> the fields in fields_m's OUTPUT_ORDER
        real(dp) :: error_estimate(N_OUTPUT_FIELDS) = NAN
        !> /events in time order: each event's time and whether it is an onset (else a
        !> release); none when absent (has_events false)
        logical :: has_events = .false.
        real(dp), allocatable :: event_t(:)
        logical, allocatable :: onset(:)
    end type summary_t

    integer, parameter :: N_COLUMNS = 31
    character(len=*), parameter :: COLUMNS(N_COLUMNS) = [character(len=16) :: &
        'file', 'status', 'contact', 'first_contact_t', 'last_contact_t', 'contact_time', &
        'max_penetration', 'max_u_end', 't_max_u_end', 'max_u_end_over_g', 'energy_ratio', &
        'decay_rate', 'decay_fit_from_t', 'decay_fit_to_t', 't_final', 'steps', 'wall_seconds', 'g', &
        'step_control_err', 'n_onsets', 'first_onset_t', 'last_onset_t', 'n_releases', 'first_release_t', &
        'last_release_t', 'error_u', 'error_v', 'error_theta', 'error_P', 'error_q', 'error_eta']
    !> Each column's quantity: T a time, L a length, R a rate, W wall seconds, ' ' no unit.
    character(len=N_COLUMNS), parameter :: KINDS = '   TTTLLT  RTTT WL  TT TT      '

contains

    !> The series part of the summary (everything but file, status, steps, wall seconds).
    !> t, energy, u_end, penetration, contact_stress: the /series datasets; g: the gap.
    pure function summarise_series(t, energy, u_end, penetration, contact_stress, g) result(s)
        real(dp), intent(in) :: t(:), energy(:), u_end(:), penetration(:), contact_stress(:)
        real(dp), intent(in) :: g
        type(summary_t) :: s
        real(dp) :: t_half
        integer :: k, n
        logical :: in_fit(size(t)), touching(size(t))

        s%g = g
        n = size(t)
        if (n == 0) return
        s%t_final = t(n)
        touching = penetration > 0.0_dp .or. contact_stress < 0.0_dp
        s%contact = any(touching)
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
        if (energy(1) > 0.0_dp) s%energy_ratio = energy(n) / energy(1)
        t_half = 0.5_dp * (t(1) + t(n))
        in_fit = t >= t_half .and. energy > 0.0_dp
        s%decay_rate = -log_slope(pack(t, in_fit), pack(energy, in_fit))
        if (count(in_fit) >= 2) then
            s%decay_fit_from_t = minval(t, mask=in_fit)
            s%decay_fit_to_t = maxval(t, mask=in_fit)
        end if
    end function summarise_series

    !> Least-squares slope of log(y) against x; NaN for fewer than two points or all x equal.
    pure function log_slope(x, y) result(slope)
        real(dp), intent(in) :: x(:), y(:)
        real(dp) :: slope
        real(dp) :: x_mean, ly_mean, sxx

        slope = NAN
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
    function summarise_file(file, nondimensional) result(s)
        character(len=*), intent(in) :: file
        logical, intent(in) :: nondimensional   !< the file's own values, not SI
        type(summary_t) :: s
        real(dp), allocatable :: t(:), energy(:), u_end(:), penetration(:), contact_stress(:)
        integer :: k

        call read_real_1d(file, '/series/t', t)
        call read_real_1d(file, '/series/energy', energy)
        call read_real_1d(file, '/series/u_end', u_end)
        call read_real_1d(file, '/series/penetration', penetration)
        call read_real_1d(file, '/series/contact_stress', contact_stress)
        s = summarise_series(t, energy, u_end, penetration, contact_stress, attr_or_nan(file, 'contact.g'))
        s%file = file
        s%status = ''
        if (attr_exists(file, 'status')) call read_attr_str(file, 'status', s%status)
        if (attr_exists(file, 'steps')) s%steps = nint(attr_or_nan(file, 'steps'))
        s%wall_seconds = attr_or_nan(file, 'wall_seconds')
        s%time_error = attr_or_nan(file, 'step_control_error_sum_relative')
        do k = 1, N_OUTPUT_FIELDS
            s%error_estimate(k) = attr_or_nan(file, 'error_estimate.'//trim(FIELDS(OUTPUT_ORDER(k))%name))
        end do
        call read_events(file, s)
        if (.not. nondimensional) then
            if (file_in_si(file)) call to_si(file, s)
        end if
    end function summarise_file

    !> The real root attribute `name` of file; NaN when the file lacks it.
    function attr_or_nan(file, name) result(x)
        character(len=*), intent(in) :: file, name
        real(dp) :: x

        x = NAN
        if (attr_exists(file, name)) call read_attr_real(file, name, x)
    end function attr_or_nan

    !> Whether the file of a run is read in SI: its root attribute 'units' ('SI' or
    !> 'nondimensional'), or in a file without it, whether it has SI scales (&material).
    function file_in_si(file) result(si)
        character(len=*), intent(in) :: file
        logical :: si
        character(len=:), allocatable :: units

        si = attr_exists(file, 'scale.time')
        if (.not. attr_exists(file, 'units')) return
        call read_attr_str(file, 'units', units)
        si = units == 'SI'
    end function file_in_si

    !> s's times and lengths in SI: scale.time (omega of (2.10), s), scale.displacement (m).
    subroutine to_si(file, s)
        character(len=*), intent(in) :: file
        type(summary_t), intent(inout) :: s
        real(dp) :: tf, lf

        call read_attr_real(file, 'scale.time', tf)
        call read_attr_real(file, 'scale.displacement', lf)
        s%first_contact_t = tf * s%first_contact_t
        s%last_contact_t = tf * s%last_contact_t
        s%contact_time = tf * s%contact_time
        s%t_max_u_end = tf * s%t_max_u_end
        s%decay_fit_from_t = tf * s%decay_fit_from_t
        s%decay_fit_to_t = tf * s%decay_fit_to_t
        s%t_final = tf * s%t_final
        s%decay_rate = s%decay_rate / tf
        s%event_t = tf * s%event_t
        s%max_penetration = lf * s%max_penetration
        s%max_u_end = lf * s%max_u_end
        s%g = lf * s%g
    end subroutine to_si

    !> The unit of a column of quantity kind (KINDS) in a table in SI or nondimensional.
    pure function unit_label(kind, si) result(label)
        character, intent(in) :: kind
        logical, intent(in) :: si
        character(len=:), allocatable :: label
        character(len=*), parameter :: SI_UNITS(4) = [character(len=6) :: ' [s]', ' [m]', ' [1/s]', ' [s]']
        integer :: k

        k = index('TLRW', kind)
        label = ''
        if (k > 0) label = trim(merge(SI_UNITS(k), ' [1]  ', si .or. kind == 'W'))
    end function unit_label

    !> The contact events of /events (absent in files of older versions).
    subroutine read_events(file, s)
        character(len=*), intent(in) :: file
        type(summary_t), intent(inout) :: s
        real(dp), allocatable :: t(:), kind(:)
        integer :: n

        allocate (s%event_t(0), s%onset(0))
        if (.not. dataset_exists(file, '/events/t')) return
        if (.not. dataset_exists(file, '/events/kind')) return
        s%has_events = .true.
        call read_real_1d(file, '/events/t', t)
        call read_real_1d(file, '/events/kind', kind)
        n = min(size(t), size(kind))
        s%event_t = t(1:n)
        s%onset = kind(1:n) > 0
    end subroutine read_events

    !> 'file,event,kind,t [s]' (or t [1]): the CSV header of write_event_rows.
    pure function events_header(si) result(line)
        logical, intent(in) :: si
        character(len=:), allocatable :: line

        line = 'file,event,kind,t' // unit_label('T', si)
    end function events_header

    !> One CSV row per contact event of s, in time order: the file, the event's number (1, 2,
    !> ...), 'onset' or 'release', and its time (15 significant digits); nothing without events.
    subroutine write_event_rows(unit, s)
        integer, intent(in) :: unit
        type(summary_t), intent(in) :: s
        integer :: n

        if (.not. s%has_events) return
        do n = 1, size(s%event_t)
            write (unit, '(a)') csv_field(s%file) // ',' // int_str(n) // ',' // &
                trim(merge('onset  ', 'release', s%onset(n))) // ',' // num(s%event_t(n))
        end do
    end subroutine write_event_rows

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

    !> 'file,status,contact,first_contact_t [s],...': the CSV header of summary_row, the
    !> units those of a summary in SI (si) or nondimensional.
    pure function summary_header(si) result(line)
        logical, intent(in) :: si
        character(len=:), allocatable :: line
        integer :: k

        line = trim(COLUMNS(1))
        do k = 2, N_COLUMNS
            line = line // ',' // trim(COLUMNS(k)) // unit_label(KINDS(k:k), si)
        end do
    end function summary_header

    !> One CSV row (RFC 4180 quoting) in the order of summary_header; reals with 15
    !> significant digits; a value that does not apply is an empty field.
    pure function summary_row(s) result(line)
        type(summary_t), intent(in) :: s
        character(len=:), allocatable :: line
        character(len=:), allocatable :: steps
        integer :: k

        steps = ''
        if (s%steps >= 0) steps = int_str(s%steps)
        line = csv_field(s%file) // ',' // csv_field(s%status) // ',' // trim(merge('yes', 'no ', s%contact)) // &
               ',' // num(s%first_contact_t) // ',' // num(s%last_contact_t) // ',' // num(s%contact_time) // &
               ',' // num(s%max_penetration) // ',' // num(s%max_u_end) // ',' // num(s%t_max_u_end) // &
               ',' // num(ratio_to_g(s)) // ',' // num(s%energy_ratio) // ',' // num(s%decay_rate) // &
               ',' // num(s%decay_fit_from_t) // ',' // num(s%decay_fit_to_t) // ',' // num(s%t_final) // &
               ',' // steps // ',' // num(s%wall_seconds) // ',' // num(s%g) // ',' // num(s%time_error) // &
               ',' // event_columns(s)
        do k = 1, size(s%error_estimate)
            line = line // ',' // num(s%error_estimate(k))
        end do
    end function summary_row

    !> n_onsets,first_onset_t,last_onset_t,n_releases,first_release_t,last_release_t: empty
    !> without /events; the counts 0 and the times empty when there are none of a kind.
    pure function event_columns(s) result(text)
        type(summary_t), intent(in) :: s
        character(len=:), allocatable :: text

        if (.not. s%has_events .or. .not. allocated(s%event_t) .or. .not. allocated(s%onset)) then
            text = ',,,,,'
            return
        end if
        text = first_last(pack(s%event_t, s%onset)) // ',' // first_last(pack(s%event_t, .not. s%onset))
    end function event_columns

    !> 'n,first,last' of the times t (first and last empty when there are none).
    pure function first_last(t) result(text)
        real(dp), intent(in) :: t(:)
        character(len=:), allocatable :: text

        text = int_str(size(t)) // ',,'
        if (size(t) > 0) text = int_str(size(t)) // ',' // num(t(1)) // ',' // num(t(size(t)))
    end function first_last

    !> max u(1,t)/g; NaN when g is unknown (NaN) or 0 (a summary_t not filled in).
    pure function ratio_to_g(s) result(ratio)
        type(summary_t), intent(in) :: s
        real(dp) :: ratio

        ratio = NAN
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
