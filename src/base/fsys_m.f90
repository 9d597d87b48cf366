!> Filesystem helpers (mkdir -p, rename, unlink, existence tests) through iso_c_binding to
!> POSIX, so that no shell is started (no execute_command_line) and every failure comes
!> back with the system's own reason (strerror of the errno that fsys_c.c returns).
module fsys_m
    use iso_c_binding, only: c_char, c_int, c_long_long, c_ptr, c_size_t, c_null_char, c_associated, &
                             c_f_pointer
    use iso_fortran_env, only: int64
    use strings_m, only: from_c_chars
    implicit none
    private
    public :: mkdir_p, rename_file, remove_file, file_exists, dir_exists, &
              parent_dir, create_empty_file, same_file, write_failure_reason, reserve_file_size, &
              from_c_string

    !> The operations of rc_path_op: mkdir (mode 0755), rename, create (or truncate) an empty file.
    integer(c_int), parameter :: OP_MKDIR = 1, OP_RENAME = 2, OP_CREATE_EMPTY = 3

    ! each rc_* of src/base/fsys_c.c returns 0 or the errno of its failure
    interface
        function c_path_op(op, a, b) bind(C, name='rc_path_op') result(err)
            import :: c_char, c_int
            integer(c_int), value, intent(in) :: op
            character(kind=c_char), intent(in) :: a(*), b(*)   !< b: rename's target, else ''
            integer(c_int) :: err
        end function c_path_op

        function c_unlink(path) bind(C, name='unlink') result(rc)
            import :: c_char, c_int
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: rc
        end function c_unlink

        function c_strerror(errnum) bind(C, name='strerror') result(text)
            import :: c_int, c_ptr
            integer(c_int), value, intent(in) :: errnum
            type(c_ptr) :: text
        end function c_strerror

        function c_strlen(text) bind(C, name='strlen') result(n)
            import :: c_ptr, c_size_t
            type(c_ptr), value, intent(in) :: text
            integer(c_size_t) :: n
        end function c_strlen

        function c_reserve(path, bytes) bind(C, name='rc_reserve_file_size') result(err)
            import :: c_char, c_int, c_long_long
            character(kind=c_char), intent(in) :: path(*)
            integer(c_long_long), value, intent(in) :: bytes
            integer(c_int) :: err
        end function c_reserve

        function c_write_errno() bind(C, name='rc_write_errno') result(err)
            import :: c_int
            integer(c_int) :: err
        end function c_write_errno

        function c_same_file(a, b) bind(C, name='rc_same_file') result(same)
            import :: c_char, c_int
            character(kind=c_char), intent(in) :: a(*), b(*)
            integer(c_int) :: same
        end function c_same_file
    end interface

contains

    !> Create directory `path` and any missing parents with mode 0755, like `mkdir -p`.
    !> An existing directory is success; ok=.false. and a message naming the directory
    !> and the system's reason otherwise.
    recursive subroutine mkdir_p(path, ok, message)
        character(len=*), intent(in) :: path
        logical, intent(out) :: ok
        character(len=:), allocatable, intent(out) :: message
        character(len=:), allocatable :: p
        integer :: err

        p = trim(path)
        ok = .false.
        message = 'cannot create a directory with an empty name'
        if (len(p) == 0) return
        ok = dir_exists(p)
        message = ''
        if (ok) return
        if (len(parent_dir(p)) > 0) call mkdir_p(parent_dir(p), ok, message)
        if (len(message) > 0) return
        err = c_path_op(OP_MKDIR, p//c_null_char, c_null_char)
        ok = err == 0
        ! another process may have created it between the test and mkdir
        if (.not. ok) ok = dir_exists(p)
        if (ok) return
        message = "cannot create directory '"//p//"': "//strerror(err)
        ! EEXIST's 'File exists' would not say what is wrong
        if (file_exists(p)) message = "'"//p//"' exists and is not a directory"
    end subroutine mkdir_p

    !> Rename `from` to `to` (C rename: atomic, replaces an existing `to` on the same filesystem).
    subroutine rename_file(from, to, ok, message)
        character(len=*), intent(in) :: from
        character(len=*), intent(in) :: to
        logical, intent(out) :: ok
        character(len=:), allocatable, intent(out) :: message

        integer :: err

        err = c_path_op(OP_RENAME, trim(from)//c_null_char, trim(to)//c_null_char)
        ok = err == 0
        message = ''
        if (.not. ok) message = "cannot rename '"//trim(from)//"' to '"//trim(to)//"': "//strerror(err)
    end subroutine rename_file

    !> Remove a file if it exists. Errors are ignored: callers use this to clean up after
    !> a failure that they are already reporting, and a missing file is the wanted state.
    subroutine remove_file(path)
        character(len=*), intent(in) :: path

        integer(c_int) :: rc

        rc = c_unlink(trim(path)//c_null_char)
    end subroutine remove_file

    !> True when `path` names an existing file, directory or other filesystem object.
    function file_exists(path) result(yes)
        character(len=*), intent(in) :: path
        logical :: yes

        inquire (file=trim(path), exist=yes)   ! gfortran: access(2), so directories too
    end function file_exists

    !> True when paths a and b both exist and are the same file (same device and inode:
    !> through relative paths, '..', symbolic and hard links alike).
    function same_file(a, b) result(yes)
        character(len=*), intent(in) :: a, b
        logical :: yes

        yes = (c_same_file(trim(a)//c_null_char, trim(b)//c_null_char) == 1)
    end function same_file

    !> True when `path` names an existing directory ('<path>/.' resolves only through a
    !> directory, so this needs no struct stat, whose layout is platform-specific).
    function dir_exists(path) result(yes)
        character(len=*), intent(in) :: path
        logical :: yes

        inquire (file=trim(path)//'/.', exist=yes)
    end function dir_exists

    !> Directory part of `path`: 'out/run' -> 'out', '/run' -> '/', 'run' -> ''.
    function parent_dir(path) result(dir)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: dir

        integer :: n, i

        n = len_trim(path)
        ! a trailing '/' names the directory itself, not a child ('a/b/' -> 'a')
        do while (n > 1)
            if (path(n:n) /= '/') exit
            n = n - 1
        end do
        i = index(path(1:n), '/', back=.true.)
        if (i == 0) then
            dir = ''
            return
        end if
        ! drop the separator and any repeated ones before it ('a//b' -> 'a')
        do while (i > 1)
            if (path(i-1:i-1) /= '/') exit
            i = i - 1
        end do
        if (i == 1) then
            dir = '/'
        else
            dir = path(1:i-1)
        end if
    end function parent_dir

    !> Create (or truncate) `path` as an empty file. Used to learn, with the system's own
    !> reason, whether a file can be created there before handing the name to a library
    !> (HDF5) that reports only that it failed.
    subroutine create_empty_file(path, ok, message)
        character(len=*), intent(in) :: path
        logical, intent(out) :: ok
        character(len=:), allocatable, intent(out) :: message

        integer :: err

        err = c_path_op(OP_CREATE_EMPTY, trim(path)//c_null_char, c_null_char)
        ok = err == 0
        message = strerror(err)
    end subroutine create_empty_file

    !> Reserve disk space for the first `bytes` bytes of file `path` (it grows to that size if
    !> shorter; its contents stay). ok=.false. and the system's reason ('No space left on
    !> device', 'File too large') when the space is not there.
    subroutine reserve_file_size(path, bytes, ok, message)
        character(len=*), intent(in) :: path
        integer(int64), intent(in) :: bytes
        logical, intent(out) :: ok
        character(len=:), allocatable, intent(out) :: message
        integer(c_int) :: err

        err = c_reserve(trim(path)//c_null_char, int(bytes, c_long_long))
        ok = err == 0
        message = strerror(int(err))
    end subroutine reserve_file_size

    !> The system's reason for a failed write when errno names one about space or the device
    !> ('No space left on device', 'File too large', 'Disk quota exceeded', ...), else ''.
    !> Call it right after the failing call (HDF5 keeps the errno of its failed write).
    function write_failure_reason() result(text)
        character(len=:), allocatable :: text

        text = strerror(int(c_write_errno()))
    end function write_failure_reason

    !> strerror(err) as a Fortran string; '' for 0 (no error).
    function strerror(err) result(text)
        integer, intent(in) :: err
        character(len=:), allocatable :: text

        text = ''
        if (err /= 0) text = from_c_string(c_strerror(int(err, c_int)), 'unknown error')
    end function strerror

    !> The NUL-terminated C string at `text` as a Fortran string (`null` for a null pointer).
    function from_c_string(text, null) result(string)
        type(c_ptr), intent(in) :: text
        character(len=*), intent(in) :: null
        character(len=:), allocatable :: string
        character(kind=c_char), pointer :: chars(:)

        string = null
        if (.not. c_associated(text)) return
        call c_f_pointer(text, chars, [c_strlen(text)])
        string = from_c_chars(chars)
    end function from_c_string

end module fsys_m
