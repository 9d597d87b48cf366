!> Progress report on stderr (README, 'Usage'): step, t, % done, ETA and contact state, for
!> runs longer than about 2 s only, and never with `&output quiet=.true.`.
!>
!>     call progress%start(n_steps, quiet)
!>     do step = 1, n_steps
!>         ...
!>         call progress%update(step, t, in_contact)   ! every step: cheap
!>     end do
!>     call progress%finish()
!>
!> On a terminal the report is one live line rewritten with a carriage return and ended
!> by a newline in finish(); when stderr is a file or a pipe it is a plain line at every
!> ~10 % of the run, so a log holds at most about ten lines.
module progress_m
    use iso_c_binding, only: c_int
    use iso_fortran_env, only: error_unit, int64
    use ieee_arithmetic, only: ieee_is_finite
    use kinds_m, only: dp
    use strings_m, only: int_str
    implicit none
    private
    public :: progress_t
    public :: format_progress_line, format_duration, next_milestone, progress_wanted

    integer, parameter :: N_MILESTONES = 10          !< plain report: a line every 1/10 of the run
    real(dp), parameter :: MIN_RUN_SECONDS = 2.0_dp  !< no report for runs predicted shorter than this
    real(dp), parameter :: SETTLE_SECONDS = 0.5_dp   !< time before the run-length prediction is trusted
    real(dp), parameter :: CHECK_SECONDS = 0.2_dp    !< aimed-for time between two clock readings

    !> State of one progress report; all components private, defaults = inactive.
    type :: progress_t
        private
        logical :: enabled = .false.     !< start() called, not quiet, n_steps > 0
        logical :: shown = .false.       !< the run was judged long enough: reporting
        logical :: live = .false.        !< stderr is a terminal: rewrite one line
        integer :: n_steps = 0
        integer :: next_check = huge(1)  !< step at which update() next reads the clock
        integer :: stride = 1            !< steps between the last two clock readings
        integer :: next_plain = 0        !< step of the next plain (file/pipe) line
        integer :: last_step = 0         !< last state seen by update(), for finish()
        real(dp) :: last_t = 0.0_dp
        character(len=2) :: unit = ''       !< of the times reported: ' s' with &material
        logical :: last_contact = .false.
        integer :: line_length = 0       !< length of the live line on screen, to blank it
        integer(int64) :: count_start = 0_int64
        integer(int64) :: count_rate = 1_int64
    contains
        procedure :: start
        procedure :: update
        procedure :: finish
    end type progress_t

    interface
        !> POSIX isatty(3): 1 when the descriptor is a terminal.
        integer(c_int) function c_isatty(fd) bind(c, name='isatty')
            import :: c_int
            integer(c_int), value, intent(in) :: fd
        end function c_isatty
    end interface

contains

    !> Begin a report for a run of n_steps steps; quiet = .true. turns it off entirely;
    !> unit: that of the times reported (' s'; none when absent).
    subroutine start(this, n_steps, quiet, unit)
        class(progress_t), intent(inout) :: this
        integer, intent(in) :: n_steps
        logical, intent(in) :: quiet
        character(len=*), intent(in), optional :: unit

        call clear(this)
        this%n_steps = n_steps
        if (present(unit)) this%unit = unit
        this%enabled = (.not. quiet) .and. n_steps > 0
        if (.not. this%enabled) return

        this%live = c_isatty(2_c_int) == 1_c_int
        call system_clock(this%count_start, this%count_rate)
        if (this%count_rate <= 0_int64) then
            ! no clock on this system: no ETA, no 2 s rule possible, so no report
            this%enabled = .false.
            return
        end if
        this%next_plain = next_milestone(0, n_steps)
        this%next_check = 1
    end subroutine start

    !> Report the state after time step `step` (1..n_steps) at time t. Called every step:
    !> all but a few calls only store the state and return after one integer comparison.
    subroutine update(this, step, t, in_contact)
        class(progress_t), intent(inout) :: this
        integer, intent(in) :: step
        real(dp), intent(in) :: t
        logical, intent(in) :: in_contact

        real(dp) :: elapsed, per_step, eta
        integer :: stride
        integer(int64) :: count_now

        this%last_step = step
        this%last_t = t
        this%last_contact = in_contact
        if (step < this%next_check) return

        call system_clock(count_now)
        elapsed = real(count_now - this%count_start, dp) / real(this%count_rate, dp)
        per_step = elapsed / real(max(step, 1), dp)
        eta = per_step * real(max(this%n_steps - step, 0), dp)

        if (.not. this%shown) this%shown = progress_wanted(elapsed, step, this%n_steps)

        if (this%shown .and. (this%live .or. step >= this%next_plain)) &
            call write_line(this, format_progress_line(step, this%n_steps, t, in_contact, eta, trim(this%unit)))
        if (step >= this%next_plain) this%next_plain = next_milestone(step, this%n_steps)

        ! Next clock reading about CHECK_SECONDS from now, and never past the next plain line.
        ! The stride at most doubles, so a few fast first steps cannot hide slow later ones.
        if (per_step > 0.0_dp) then
            stride = int(min(CHECK_SECONDS / per_step, real(this%n_steps, dp))) + 1
        else
            stride = 2 * this%stride
        end if
        this%stride = max(1, min(stride, 2 * this%stride, this%n_steps))
        this%next_check = step + this%stride
        if (.not. this%live) this%next_check = min(this%next_check, this%next_plain)
    end subroutine update

    !> End the report: on a terminal, draw the final state and end the line; in a log,
    !> write the last line if the 100 % line has not been written (a run that stopped
    !> early shows its last step and ETA '--'). Silent if nothing was shown. Call it
    !> before writing anything else to stderr, e.g. the message of a numerical failure.
    subroutine finish(this)
        class(progress_t), intent(inout) :: this

        real(dp) :: eta

        eta = 0.0_dp
        if (this%last_step < this%n_steps) eta = -1.0_dp   ! stopped early: no ETA
        if (this%enabled .and. this%shown .and. &
            (this%live .or. this%last_step < this%n_steps .or. this%next_plain <= this%n_steps)) then
            call write_line(this, format_progress_line(this%last_step, this%n_steps, this%last_t, &
                                                       this%last_contact, eta, trim(this%unit)))
            if (this%live) write (error_unit, '(a)') ''
            flush (error_unit)
        end if
        call clear(this)
    end subroutine finish

    !> report as an inactive one (intent(out): every component to its default).
    subroutine clear(report)
        type(progress_t), intent(out) :: report
    end subroutine clear

    !> Write a report line: on a terminal rewrite the live line (carriage return, text, blanks
    !> over a longer old line), else a line of its own.
    subroutine write_line(this, line)
        class(progress_t), intent(inout) :: this
        character(len=*), intent(in) :: line

        if (this%live) then
            write (error_unit, '(a)', advance='no') achar(13)//line// &
                repeat(' ', max(this%line_length - len(line), 0))
            this%line_length = len(line)
        else
            write (error_unit, '(a)') line
        end if
        flush (error_unit)
    end subroutine write_line

    !> Should a run that has taken `elapsed` seconds for `step` of `n_steps` steps be
    !> reported? Yes once its prediction has settled (SETTLE_SECONDS) and predicts a
    !> total of at least MIN_RUN_SECONDS, or as soon as it has taken MIN_RUN_SECONDS.
    pure function progress_wanted(elapsed, step, n_steps) result(wanted)
        real(dp), intent(in) :: elapsed
        integer, intent(in) :: step
        integer, intent(in) :: n_steps
        logical :: wanted

        real(dp) :: predicted

        if (step >= n_steps) then
            wanted = .false.           ! finished: nothing left to report progress on
        else if (elapsed >= MIN_RUN_SECONDS) then
            wanted = .true.
        else if (elapsed < SETTLE_SECONDS .or. step < 1) then
            wanted = .false.
        else
            predicted = elapsed / real(step, dp) * real(n_steps, dp)
            wanted = predicted >= MIN_RUN_SECONDS
        end if
    end function progress_wanted

    !> The step after `step` at which the plain report writes its next line: the smallest
    !> ceiling(k n_steps / N_MILESTONES), k = 1..N_MILESTONES, greater than step;
    !> huge(1) when there is none (step >= n_steps).
    pure function next_milestone(step, n_steps) result(next)
        integer, intent(in) :: step
        integer, intent(in) :: n_steps
        integer :: next
        integer(int64) :: k

        ! ceiling(k n_steps/10) > step exactly when k n_steps/10 > step: the first such k; int64:
        ! k n_steps cannot overflow
        k = int(N_MILESTONES, int64) * step / max(n_steps, 1) + 1
        next = huge(1)
        if (k <= N_MILESTONES .and. n_steps > 0) &
            next = int((k * n_steps + N_MILESTONES - 1) / N_MILESTONES)
    end function next_milestone

    !> One report line, e.g.
    !>   'step  5000/10000   50.0%  t = 0.500000  ETA 12s  contact'
    pure function format_progress_line(step, n_steps, t, in_contact, eta_seconds, unit) result(line)
        integer, intent(in) :: step
        integer, intent(in) :: n_steps
        real(dp), intent(in) :: t
        logical, intent(in) :: in_contact
        real(dp), intent(in) :: eta_seconds   !< negative: unknown
        character(len=*), intent(in), optional :: unit   !< of t, after it (' s')
        character(len=:), allocatable :: line

        character(len=8) :: percent_text
        character(len=32) :: t_text
        real(dp) :: percent

        percent = 100.0_dp * real(step, dp) / real(max(n_steps, 1), dp)
        write (percent_text, '(f5.1,a)') percent, '%'
        ! not f0.6: that drops the leading zero of 0.5; NaN and Infinity are not compared
        write (t_text, '(f15.6)') t
        if (ieee_is_finite(t)) then
            if (abs(t) >= 1.0e6_dp) write (t_text, '(es12.5)') t
        end if
        ! the step as wide as n_steps, so that the line keeps its length during a run
        line = 'step '//repeat(' ', max(len(int_str(n_steps)) - len(int_str(step)), 0))// &
               int_str(step)//'/'//int_str(n_steps)//'  '//trim(percent_text)// &
               '  t = '//trim(adjustl(t_text))
        if (present(unit)) line = line//unit
        line = line//'  ETA '//format_duration(eta_seconds)//'  '//trim(merge('contact', 'free   ', in_contact))
    end function format_progress_line

    !> A duration for people: '42s', '3m05s', '2h07m', '--' when unknown (negative or not finite).
    pure function format_duration(seconds) result(text)
        real(dp), intent(in) :: seconds
        character(len=:), allocatable :: text

        character(len=24) :: buffer
        integer(int64) :: total

        text = '--'
        ! ieee_is_finite first: comparing a NaN would raise (and trap in Debug builds)
        if (.not. ieee_is_finite(seconds)) return
        if (seconds < 0.0_dp .or. seconds >= 1.0e12_dp) return
        total = nint(seconds, int64)
        if (total < 60_int64) then
            write (buffer, '(i0,a)') total, 's'
        else if (total < 3600_int64) then
            write (buffer, '(i0,a,i2.2,a)') total / 60_int64, 'm', mod(total, 60_int64), 's'
        else
            write (buffer, '(i0,a,i2.2,a)') total / 3600_int64, 'h', mod(total, 3600_int64) / 60_int64, 'm'
        end if
        text = trim(buffer)
    end function format_duration

end module progress_m
