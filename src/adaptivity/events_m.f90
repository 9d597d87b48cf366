!> Contact events: the times at which the contact node becomes active (onset) or inactive
!> (release), as /events/t and /events/kind record them (docs/output.md).
module events_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use checkpoint_m, only: checkpoint_t
    implicit none
    private
    public :: event_log_t, EVENT_ONSET, EVENT_RELEASE, crossing_time, event_landing
    public :: MAX_LANDINGS, LANDING_FRACTION, LINEAR_CUT_MIN

    integer, parameter :: EVENT_ONSET = 1, EVENT_RELEASE = -1
    !> An event this close to a step's start or end (a fraction of the step) is taken as there:
    !> the step is accepted, not cut (event_landing)
    real(dp), parameter :: LANDING_FRACTION = 1.0e-9_dp
    !> Cuts of one step at a located event, at most (then the step that changes the contact
    !> state is accepted as it is)
    integer, parameter :: MAX_LANDINGS = 6
    !> An event located by the straight line between the gaps only (no interpolant) is not cut to
    !> closer than this fraction of the step to the step's start: a slow, tangential crossing (a
    !> penalty release) is then met short step after step, each linear location falling short
    real(dp), parameter :: LINEAR_CUT_MIN = 1.0e-2_dp

    !> The events of a run, in order: the first n of t and kind, which grow by doubling (a
    !> contact that chatters under adaptive steps can log an event every other step, and
    !> appending them one at a time made such a run quadratic in its events)
    type :: event_log_t
        private
        integer :: n = 0
        real(dp), allocatable :: t(:)
        integer, allocatable :: kind(:)
    contains
        procedure :: add => log_add
        procedure :: times => log_times
        procedure :: kinds => log_kinds
        procedure :: checkpoint => log_checkpoint
    end type event_log_t

contains

    !> Record an event of kind EVENT_ONSET or EVENT_RELEASE at time t.
    subroutine log_add(self, t, kind)
        class(event_log_t), intent(inout) :: self
        real(dp), intent(in) :: t
        integer, intent(in) :: kind

        if (.not. allocated(self%t)) allocate (self%t(0), self%kind(0))
        if (self%n == size(self%t)) then   ! full: double, by at least 8
            self%t = [self%t, spread(0.0_dp, 1, max(8, self%n))]
            self%kind = [self%kind, spread(0, 1, max(8, self%n))]
        end if
        self%n = self%n + 1
        self%t(self%n) = t
        self%kind(self%n) = kind
    end subroutine log_add

    !> The event times.
    pure function log_times(self) result(t)
        class(event_log_t), intent(in) :: self
        real(dp), allocatable :: t(:)

        t = [real(dp) ::]
        if (allocated(self%t)) t = self%t(:self%n)
    end function log_times

    !> The event kinds (EVENT_ONSET, EVENT_RELEASE).
    pure function log_kinds(self) result(kind)
        class(event_log_t), intent(in) :: self
        integer, allocatable :: kind(:)

        kind = [integer ::]
        if (allocated(self%kind)) kind = self%kind(:self%n)
    end function log_kinds

    !> The log into a checkpoint, or back from one (checkpoint_m's reading): events/t and
    !> events/kind (as the file's /events).
    subroutine log_checkpoint(self, ckpt)
        class(event_log_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt
        real(dp), allocatable :: t(:)
        integer(int64), allocatable :: kind(:)

        allocate (t, source=self%times())
        allocate (kind, source=int(self%kinds(), int64))
        call ckpt%sync('events/t', t)
        call ckpt%sync('events/kind', kind)
        if (.not. ckpt%reading) return
        self%t = t
        self%kind = int(kind)
        self%n = size(t)
    end subroutine log_checkpoint

    !> The time in [t_start, t_start + dt] at which the contact state of a step changes: the
    !> trial gap u(1) - g (the gap the step would have without contact force) goes from
    !> gap_start at t_start to gap_end at t_start + dt; interpolated linearly when the two
    !> have strictly opposite signs, else the end of the step (e.g. a Signorini release,
    !> which starts from a zero gap).
    pure real(dp) function crossing_time(t_start, dt, gap_start, gap_end) result(t)
        real(dp), intent(in) :: t_start, dt, gap_start, gap_end

        t = t_start + dt
        if ((gap_start < 0.0_dp .and. gap_end > 0.0_dp) .or. (gap_start > 0.0_dp .and. gap_end < 0.0_dp)) &
            t = t_start + dt * gap_start / (gap_start - gap_end)
    end function crossing_time

    !> Whether a step from t_start of size dt that changed the contact state, with its event
    !> located at t_event, is cut to end there (adaptive steps): cut (dt_land = t_event - t_start)
    !> when the event is inside the step, more than LANDING_FRACTION dt and more than dt_min
    !> from either end; no when it is at the step's start (the step before ended on it: the
    !> contact state changes at the start, and the step is right as it is) or at its end.
    pure subroutine event_landing(t_start, dt, t_event, dt_min, cut, dt_land)
        real(dp), intent(in) :: t_start, dt, t_event, dt_min
        logical, intent(out) :: cut
        real(dp), intent(out) :: dt_land
        real(dp) :: close

        dt_land = t_event - t_start
        close = max(LANDING_FRACTION * dt, dt_min)
        cut = dt_land > close .and. dt - dt_land > close
    end subroutine event_landing

end module events_m
