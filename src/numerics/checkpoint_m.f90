!> A checkpoint in memory: everything a run needs to continue exactly (&output
!> checkpoint_every, &time restart_from), as named entries. It is a record, not an owner:
!> each type syncs its own entries 'owner/name' in one routine (docs/output.md,
!> "Checkpoints", lists them). The files layer maps the record to the file's
!> /checkpoint/slotN/<owner>/ and back.
module checkpoint_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use errors_m, only: fatal, EXIT_INPUT, check_allocation
    implicit none
    private
    public :: checkpoint_t, entry_t

    !> One named value: reals or integers, rank 0, 1 or 2 (dims: 1 past the rank), held as
    !> 64-bit words (a real's bits, transfer()), which the files layer writes and reads as
    !> int64 or float64 after is_integer.
    type :: entry_t
        character(len=:), allocatable :: name   !< 'owner/name'
        logical :: is_integer = .false.
        integer :: rank = 0
        integer :: dims(2) = 1
        integer(int64), allocatable :: values(:)
    end type entry_t

    type :: checkpoint_t
        integer :: n = 0                        !< entries(1:n) are in use
        logical :: reading = .false.            !< read from a file: sync gets, else puts
        character(len=:), allocatable :: source   !< the file it was read from, for messages
        type(entry_t), allocatable :: entries(:)
    contains
        generic :: sync => sync_scalar, sync_reals, sync_real2, sync_ints
        procedure :: add, has, find
        procedure, private :: sync_scalar, sync_reals, sync_real2, sync_ints
    end type checkpoint_t

contains

    !> Append an entry (its name unique: a name put twice is a programming error).
    subroutine add(self, entry)
        class(checkpoint_t), intent(inout) :: self
        type(entry_t), intent(in) :: entry
        type(entry_t), allocatable :: grown(:)
        integer :: stat
        character(len=256) :: message

        if (self%has(entry%name)) &
            call fatal(EXIT_INPUT, 'checkpoint', 'internal error: '//entry%name//' put twice')
        if (.not. allocated(self%entries)) allocate (self%entries(0))
        if (self%n == size(self%entries)) then
            allocate (grown(max(64, 2 * self%n)), stat=stat, errmsg=message)
            call check_allocation(stat, message, 'a checkpoint')
            grown(1:self%n) = self%entries
            call move_alloc(grown, self%entries)
        end if
        self%n = self%n + 1
        self%entries(self%n) = entry
    end subroutine add

    logical function has(self, name)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer :: k

        has = .false.
        do k = 1, self%n
            if (self%entries(k)%name == name) has = .true.
        end do
    end function has

    !> The entry `name` (given them, of integers or reals and of that rank): a checkpoint
    !> without it cannot be continued (an input error of the restart).
    function find(self, name, is_integer, rank) result(entry)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        logical, intent(in), optional :: is_integer
        integer, intent(in), optional :: rank
        type(entry_t) :: entry
        integer :: k
        character(len=:), allocatable :: file

        file = 'the checkpoint'
        if (allocated(self%source)) file = "'"//self%source//"': its checkpoint"
        do k = 1, self%n
            if (self%entries(k)%name /= name) cycle
            entry = self%entries(k)
            if (.not. present(rank)) return
            if ((entry%is_integer .eqv. is_integer) .and. entry%rank == rank) return
            call fatal(EXIT_INPUT, 'time.restart_from', file//"'s "//name//' is of another type or rank')
        end do
        call fatal(EXIT_INPUT, 'time.restart_from', file//' has no '//name)
    end function find

    !> An owner's checkpoint routine names each entry once, so that saving and restoring
    !> cannot disagree: sync puts value into a checkpoint being saved, gets it back from one read.
    !> value: real(dp), integer, integer(int64), logical (0 or 1 under name//'_flag'), or an
    !> array below (unallocated: size 0).
    subroutine sync_scalar(self, name, value)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        class(*), intent(inout) :: value
        type(entry_t) :: entry

        entry = entry_t(name, .true., 0, [1, 1], [0_int64])
        select type (value)
        type is (real(dp))
            entry%is_integer = .false.
            entry%values = transfer(value, 0_int64)
        type is (integer)
            entry%values = int(value, int64)
        type is (integer(int64))
            entry%values = value
        type is (logical)
            entry%name = name//'_flag'
            entry%values = merge(1_int64, 0_int64, value)
        end select
        call sync_entry(self, entry)
        select type (value)
        type is (real(dp))
            value = transfer(entry%values(1), value)
        type is (integer)
            value = int(entry%values(1))
        type is (integer(int64))
            value = entry%values(1)
        type is (logical)
            value = entry%values(1) /= 0
        end select
    end subroutine sync_scalar

    subroutine sync_reals(self, name, values)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), allocatable, intent(inout) :: values(:)
        type(entry_t) :: entry

        if (.not. allocated(values)) allocate (values(0))
        entry = entry_t(name, .false., 1, [size(values), 1], &
                        transfer(values, [0_int64]))
        call sync_entry(self, entry)
        if (self%reading) values = transfer(entry%values, [0.0_dp])
    end subroutine sync_reals

    subroutine sync_real2(self, name, values)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), allocatable, intent(inout) :: values(:, :)
        type(entry_t) :: entry

        if (.not. allocated(values)) allocate (values(0, 0))
        entry = entry_t(name, .false., 2, shape(values), &
                        transfer(values, [0_int64]))
        call sync_entry(self, entry)
        if (self%reading) values = reshape(transfer(entry%values, [0.0_dp]), entry%dims)
    end subroutine sync_real2

    subroutine sync_ints(self, name, values)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer(int64), allocatable, intent(inout) :: values(:)
        type(entry_t) :: entry

        if (.not. allocated(values)) allocate (values(0))
        entry = entry_t(name, .true., 1, [size(values), 1], values)
        call sync_entry(self, entry)
        if (self%reading) values = entry%values
    end subroutine sync_ints

    !> Put entry, or (reading) get the one of its name.
    subroutine sync_entry(self, entry)
        type(checkpoint_t), intent(inout) :: self
        type(entry_t), intent(inout) :: entry

        if (self%reading) then
            entry = self%find(entry%name, entry%is_integer, entry%rank)
        else
            call self%add(entry)
        end if
    end subroutine sync_entry

end module checkpoint_m
