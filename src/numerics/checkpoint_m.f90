!> A checkpoint in memory: everything a run needs to continue exactly (&output
!> checkpoint_every, &time restart_from), as named entries. It is a record, not an owner:
!> each type puts its own entries 'owner/name' and gets them back (docs/output.md,
!> "Checkpoints", lists them), best in one routine of sync calls. An entry is
!> reals or integers (int64), a scalar or an array of rank 1 or 2; a logical is the integer
!> 0 or 1 under a name ending in _flag. The files layer maps the record to the file's
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
        generic :: put => put_real, put_reals, put_real2, put_int, put_int64, put_ints, put_flag
        generic :: get => get_real, get_reals, get_real2, get_int, get_int64, get_ints, get_flag
        procedure :: add, has, find, sync
        procedure, private :: word
        procedure, private :: put_real, put_reals, put_real2, put_int, put_int64, put_ints, put_flag
        procedure, private :: get_real, get_reals, get_real2, get_int, get_int64, get_ints, get_flag
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

    !> The entry `name`, of integers or reals and of that rank: a checkpoint without it
    !> cannot be continued (an input error of the restart).
    function find(self, name, is_integer, rank) result(entry)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        logical, intent(in) :: is_integer
        integer, intent(in) :: rank
        type(entry_t) :: entry
        integer :: k
        character(len=:), allocatable :: file

        file = 'the checkpoint'
        if (allocated(self%source)) file = "'"//self%source//"': its checkpoint"
        do k = 1, self%n
            if (self%entries(k)%name /= name) cycle
            entry = self%entries(k)
            if ((entry%is_integer .eqv. is_integer) .and. entry%rank == rank) return
            call fatal(EXIT_INPUT, 'time.restart_from', file//"'s "//name//' is of another type or rank')
        end do
        call fatal(EXIT_INPUT, 'time.restart_from', file//' has no '//name)
    end function find

    !> An owner's one checkpoint routine names each scalar entry once: sync puts value into a
    !> checkpoint being saved and gets it back from one being read (reading), so that saving
    !> and restoring cannot disagree. value: real(dp), integer, integer(int64) or logical.
    subroutine sync(self, name, value)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        class(*), intent(inout) :: value

        select type (value)
        type is (real(dp))
            if (self%reading) call self%get(name, value)
            if (.not. self%reading) call self%put(name, value)
        type is (integer)
            if (self%reading) call self%get(name, value)
            if (.not. self%reading) call self%put(name, value)
        type is (integer(int64))
            if (self%reading) call self%get(name, value)
            if (.not. self%reading) call self%put(name, value)
        type is (logical)
            if (self%reading) call self%get(name, value)
            if (.not. self%reading) call self%put(name, value)
        class default
            call fatal(EXIT_INPUT, 'checkpoint', 'internal error: the type of '//name)
        end select
    end subroutine sync

    !> The one word of scalar entry `name` (find's refusals).
    integer(int64) function word(self, name, is_integer)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        logical, intent(in) :: is_integer
        type(entry_t) :: entry

        entry = self%find(name, is_integer, 0)
        word = entry%values(1)
    end function word

    subroutine put_real(self, name, value)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: value

        call self%add(entry_t(name, .false., 0, [1, 1], [transfer(value, 0_int64)]))
    end subroutine put_real

    subroutine put_reals(self, name, values)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: values(:)

        call self%add(entry_t(name, .false., 1, [size(values), 1], &
                              transfer(values, 0_int64, size(values))))
    end subroutine put_reals

    subroutine put_real2(self, name, values)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: values(:, :)

        call self%add(entry_t(name, .false., 2, shape(values), transfer(values, 0_int64, size(values))))
    end subroutine put_real2

    subroutine put_int(self, name, value)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer, intent(in) :: value

        call self%add(entry_t(name, .true., 0, [1, 1], [int(value, int64)]))
    end subroutine put_int

    subroutine put_int64(self, name, value)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer(int64), intent(in) :: value

        call self%add(entry_t(name, .true., 0, [1, 1], [value]))
    end subroutine put_int64

    subroutine put_ints(self, name, values)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer(int64), intent(in) :: values(:)

        call self%add(entry_t(name, .true., 1, [size(values), 1], values))
    end subroutine put_ints

    !> A logical, as the integer 1 (true) or 0 under a name ending in _flag.
    subroutine put_flag(self, name, flag)
        class(checkpoint_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        logical, intent(in) :: flag

        call self%add(entry_t(name//'_flag', .true., 0, [1, 1], [merge(1_int64, 0_int64, flag)]))
    end subroutine put_flag

    subroutine get_real(self, name, value)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(out) :: value

        value = transfer(self%word(name, .false.), value)
    end subroutine get_real

    subroutine get_reals(self, name, values)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        real(dp), allocatable, intent(out) :: values(:)
        type(entry_t) :: entry

        entry = self%find(name, .false., 1)
        values = transfer(entry%values, 0.0_dp, size(entry%values))
    end subroutine get_reals

    subroutine get_real2(self, name, values)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        real(dp), allocatable, intent(out) :: values(:, :)
        type(entry_t) :: entry

        entry = self%find(name, .false., 2)
        values = reshape(transfer(entry%values, 0.0_dp, size(entry%values)), entry%dims)
    end subroutine get_real2

    subroutine get_int(self, name, value)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer, intent(out) :: value

        value = int(self%word(name, .true.))
    end subroutine get_int

    subroutine get_int64(self, name, value)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer(int64), intent(out) :: value

        value = self%word(name, .true.)
    end subroutine get_int64

    subroutine get_ints(self, name, values)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer(int64), allocatable, intent(out) :: values(:)
        type(entry_t) :: entry

        entry = self%find(name, .true., 1)
        values = entry%values
    end subroutine get_ints

    !> The logical put_flag wrote under name//'_flag'.
    subroutine get_flag(self, name, flag)
        class(checkpoint_t), intent(in) :: self
        character(len=*), intent(in) :: name
        logical, intent(out) :: flag

        flag = self%word(name//'_flag', .true.) /= 0
    end subroutine get_flag

end module checkpoint_m
