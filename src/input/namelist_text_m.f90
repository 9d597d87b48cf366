!> The namelist text of the input, before any value is read: the whole source in memory
!> (standard input cannot be rewound), comments blanked, the groups '&name ... /' located
!> (so that an unknown group, a group given twice or stray text is an error, in any order
!> of the groups), and each group split into its assignments 'lhs = value', which the
!> reader (config_reader_m) then reads one at a time.
module namelist_text_m
    use, intrinsic :: iso_fortran_env, only: input_unit, iostat_end, iostat_eor
    use errors_m, only: fatal, EXIT_INPUT, check_allocation
    use config_m, only: LEN_NAME
    use strings_m, only: lower, squeeze, excerpt, quoted, identifier_at, is_name_char, int_str
    use input_vars_m, only: GROUP_NAMES, group_list, var_list, var_kind, kind_description
    implicit none
    private
    public :: string_t, group_t, assignments_t
    public :: read_source, strip_comments, find_groups, split_group
    public :: origin, assignment_lhs, assignment_value, piece

    integer, parameter :: LEN_MSG = 512         !< iomsg buffers

    !> A namelist group found in the input text: positions (line, column) in the text.
    type :: group_t
        character(len=LEN_NAME) :: name = ''   !< lower case, without '&'
        integer :: first(2) = 0                !< the '&' of '&name'
        integer :: body(2) = 0                 !< just after the name
        integer :: term(2) = 0                 !< the terminator '/' or '&end'
        integer :: last(2) = 0                 !< the terminator's last character
        logical :: from_set = .false.          !< made from a --set override (named so in errors)
    end type group_t

    !> The assignments 'lhs = value' of one group: body(first(k):eq(k)-1) = lhs of the k-th.
    type :: assignments_t
        character(len=LEN_NAME) :: group = ''
        character(len=:), allocatable :: body   !< text between the name and the terminator
        integer, allocatable :: first(:)        !< where the k-th left-hand side begins
        integer, allocatable :: eq(:)           !< its '='
        logical :: from_set = .false.           !< made from a --set override
    end type assignments_t

    !> A line of text.
    type :: string_t
        character(len=:), allocatable :: s
    end type string_t

contains

    !> All lines of the source, read into memory (standard input cannot be rewound); a
    !> failure is an input error of `var` (default 'input': the namelist's source).
    subroutine read_source(source, lines, var)
        character(len=*), intent(in) :: source
        type(string_t), allocatable, intent(out) :: lines(:)
        character(len=*), intent(in), optional :: var
        integer :: unit, ios
        logical :: is_directory
        character(len=LEN_MSG) :: msg
        character(len=:), allocatable :: where

        where = 'input'
        if (present(var)) where = var
        if (trim(source) == '-') then
            call read_lines(input_unit, 'standard input', where, lines)
        else
            ! gfortran opens a directory without complaint and then reads nothing from it
            inquire (file=trim(source) // '/.', exist=is_directory)
            if (is_directory) call fatal(EXIT_INPUT, where, "cannot open '" // trim(source) // "': it is a directory")
            msg = ''
            open (newunit=unit, file=trim(source), status='old', action='read', iostat=ios, iomsg=msg)
            if (ios /= 0) call fatal(EXIT_INPUT, where, "cannot open '" // trim(source) // "': " // trim(msg))
            call read_lines(unit, "'" // trim(source) // "'", where, lines)
            ! the text is in memory: a failure to close a read-only file cannot lose anything
            close (unit, iostat=ios)
        end if
    end subroutine read_source

    !> Read `unit` to its end, line by line, lines of any length.
    subroutine read_lines(unit, what, where, lines)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: what, where
        type(string_t), allocatable, intent(out) :: lines(:)
        type(string_t), allocatable :: grown(:)
        character(len=4096) :: chunk
        character(len=:), allocatable :: line
        character(len=LEN_MSG) :: msg
        integer :: n, ios, n_read

        allocate (lines(64), stat=ios, errmsg=msg)
        call check_allocation(ios, msg, 'the lines of ' // what)
        n = 0
        do
            line = ''
            do
                msg = ''
                read (unit, '(a)', advance='no', iostat=ios, iomsg=msg, size=n_read) chunk
                if (ios /= 0 .and. ios /= iostat_eor .and. ios /= iostat_end) &
                    call fatal(EXIT_INPUT, where, 'cannot read ' // what // ': ' // trim(msg))
                line = line // chunk(:n_read)
                if (ios /= 0) exit
            end do
            if (ios == iostat_end .and. len(line) == 0) exit
            if (n == size(lines)) then
                allocate (grown(2 * n), stat=ios, errmsg=msg)
                call check_allocation(ios, msg, 'the lines of ' // what // ' (' // int_str(n) // ' lines so far)')
                grown(:n) = lines
                call move_alloc(grown, lines)
            end if
            n = n + 1
            lines(n)%s = line
            if (ios == iostat_end) exit
        end do
        lines = lines(:n)
    end subroutine read_lines

    !> Blank out '!' comments (outside quoted strings); tabs and carriage returns become blanks.
    pure subroutine strip_comments(lines)
        type(string_t), intent(inout) :: lines(:)
        character :: quote
        integer :: i, j

        do i = 1, size(lines)
            quote = ' '
            associate (line => lines(i)%s)
                do j = 1, len(line)
                    if (line(j:j) == achar(9) .or. line(j:j) == achar(13)) line(j:j) = ' '
                    if (quote /= ' ') then
                        if (line(j:j) == quote) quote = ' '
                    else if (line(j:j) == "'" .or. line(j:j) == '"') then
                        quote = line(j:j)
                    else if (line(j:j) == '!') then
                        line(j:) = ''
                        exit
                    end if
                end do
            end associate
        end do
    end subroutine strip_comments

    !> Locate the groups '&name ... /' (or '... &end'); any other text outside them, an
    !> unknown group, a group given twice or a group left open is an input error.
    subroutine find_groups(lines, groups)
        type(string_t), intent(in) :: lines(:)
        type(group_t), allocatable, intent(out) :: groups(:)
        type(group_t) :: current
        character :: quote
        character(len=:), allocatable :: name
        logical :: inside
        integer :: i, j, k, stat
        character(len=LEN_MSG) :: msg

        name = ''
        allocate (groups(0), stat=stat, errmsg=msg)
        call check_allocation(stat, msg, 'the namelist groups')
        inside = .false.
        do i = 1, size(lines)
            quote = ' '
            j = 1
            do while (j <= len_trim(lines(i)%s))
                associate (ch => lines(i)%s(j:j))
                    if (.not. inside) then
                        if (ch == '&') then
                            name = lower(identifier_at(lines(i)%s, j + 1))
                            call check_group_name(name, i, groups)
                            current = group_t(name=name, first=[i, j], body=[i, j + 1 + len(name)])
                            inside = .true.
                            j = j + len(name)
                        else if (ch /= ' ') then
                            call fatal(EXIT_INPUT, 'input', 'text outside a namelist group at line ' // &
                                       int_str(i) // ": '" // excerpt(lines(i)%s(j:)) // "'; every group " // &
                                       "starts with '&name' (name one of " // group_list() // ") and ends with '/'")
                        end if
                    else if (quote /= ' ') then
                        if (ch == quote) quote = ' '
                    else if (ch == "'" .or. ch == '"') then
                        quote = ch
                    else if (ch == '/' .or. ch == '&') then
                        k = j
                        if (ch == '&') then
                            name = lower(identifier_at(lines(i)%s, j + 1))
                            if (name /= 'end') call fatal(EXIT_INPUT, trim(current%name), 'group &' // &
                                trim(current%name) // ' (line ' // int_str(current%first(1)) // ') is not ' // &
                                "closed: '&" // name // "' at line " // int_str(i) // " comes before its '/'")
                            k = j + 3
                        end if
                        current%term = [i, j]
                        current%last = [i, k]
                        groups = [groups, current]
                        inside = .false.
                        j = k
                    end if
                end associate
                j = j + 1
            end do
        end do
        if (inside) call fatal(EXIT_INPUT, trim(current%name), 'group &' // trim(current%name) // &
                               ' (line ' // int_str(current%first(1)) // ") is not closed: missing '/' " // &
                               'at its end (or a quoted string without its closing quote)')
    end subroutine find_groups

    !> A group name must be one of GROUP_NAMES and not seen before.
    subroutine check_group_name(name, line, groups)
        character(len=*), intent(in) :: name
        integer, intent(in) :: line
        type(group_t), intent(in) :: groups(:)
        integer :: k

        if (len(name) == 0) call fatal(EXIT_INPUT, 'input', "'&' without a group name at line " // int_str(line) // &
                                       '; allowed groups: ' // group_list())
        if (.not. any(GROUP_NAMES == name)) call fatal(EXIT_INPUT, 'input', "unknown namelist group '&" // name // &
                                                       "' at line " // int_str(line) // '; allowed groups: ' // group_list())
        do k = 1, size(groups)
            if (groups(k)%name == name) call fatal(EXIT_INPUT, name, 'group &' // name // ' given twice (lines ' // &
                int_str(groups(k)%first(1)) // ' and ' // int_str(line) // '); each group may appear at most once')
        end do
    end subroutine check_group_name

    !> The text between the group's name and its terminator, lines joined by a blank.
    pure function group_body(lines, grp) result(body)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        character(len=:), allocatable :: body
        integer :: i, first_col, last_col

        body = ''
        do i = grp%body(1), grp%term(1)
            first_col = 1
            if (i == grp%body(1)) first_col = grp%body(2)
            last_col = len(lines(i)%s)
            if (i == grp%term(1)) last_col = grp%term(2) - 1
            body = body // lines(i)%s(first_col:last_col) // ' '
        end do
    end function group_body

    !> Split the group into its assignments 'lhs = value' and check what only the reader can:
    !> known variable names, each given once, a value after '=', strings quoted.
    subroutine split_group(lines, grp, asg)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(assignments_t), intent(out) :: asg
        character(len=:), allocatable :: lhs, name, value, where
        integer :: k, p, n

        asg%group = grp%name
        asg%from_set = grp%from_set
        asg%body = group_body(lines, grp)
        call find_assignments(asg)
        n = size(asg%eq)
        p = len(asg%body) + 1
        if (n > 0) p = asg%first(1)
        if (verify(asg%body(:p - 1), ' ,') /= 0) call fatal(EXIT_INPUT, origin(asg) // trim(grp%name), &
            "expected 'variable = value' in &" // trim(grp%name) // ", got '" // excerpt(asg%body(:p - 1)) // &
            "'; allowed variables: " // var_list(grp%name))
        do k = 1, n
            lhs = assignment_lhs(asg, k)
            name = identifier_at(lhs, 1)
            value = assignment_value(asg, k)
            where = origin(asg) // trim(grp%name) // '.' // lower(name)
            if (len(name) == 0) call fatal(EXIT_INPUT, origin(asg) // trim(grp%name), &
                "'=' without a variable name in &" // trim(grp%name) // ": '" // &
                excerpt(asg%body(asg%first(k):)) // "'; allowed variables: " // var_list(grp%name))
            if (var_kind(grp%name, name) == ' ') call fatal(EXIT_INPUT, where, "unknown variable '" // name // &
                "' in &" // trim(grp%name) // '; allowed: ' // var_list(grp%name))
            do p = 1, k - 1
                if (lower(squeeze(assignment_lhs(asg, p))) == lower(squeeze(lhs))) &
                    call fatal(EXIT_INPUT, where, "'" // lhs // "' given twice in &" // trim(grp%name))
            end do
            if (verify(value, ' ,') == 0) call fatal(EXIT_INPUT, where, "no value after '" // lhs // &
                " ='; must be " // kind_description(var_kind(grp%name, name)))
            ! gfortran silently skips an unquoted string value: only the reader can catch it
            if (var_kind(grp%name, name) == 's' .and. scan(value(1:1), '''"') == 0) call fatal(EXIT_INPUT, where, &
                'got ' // excerpt(value) // '; must be a quoted string, e.g. ' // name // ' = ' // quoted(excerpt(value)))
        end do
    end subroutine split_group

    !> asg%first and asg%eq of the assignments in asg%body: each '=' outside quoted strings,
    !> and where the variable name before it (and its subscript, if any) begins.
    subroutine find_assignments(asg)
        type(assignments_t), intent(inout) :: asg
        character :: quote
        character(len=LEN_MSG) :: msg
        integer :: j, p, stat

        allocate (asg%first(0), asg%eq(0), stat=stat, errmsg=msg)
        call check_allocation(stat, msg, 'the assignments of &' // trim(asg%group))
        associate (body => asg%body)
            quote = ' '
            do j = 1, len(body)
                if (quote /= ' ') then
                    if (body(j:j) == quote) quote = ' '
                else if (body(j:j) == "'" .or. body(j:j) == '"') then
                    quote = body(j:j)
                else if (body(j:j) == '=') then
                    p = len_trim(body(:j - 1))
                    if (p > 0) then   ! skip a subscript: name(2) = ...
                        if (body(p:p) == ')') p = len_trim(body(:max(0, index(body(:p), '(', back=.true.) - 1)))
                    end if
                    do while (p > 0)
                        if (.not. is_name_char(body(p:p))) exit
                        p = p - 1
                    end do
                    asg%first = [asg%first, p + 1]
                    asg%eq = [asg%eq, j]
                end if
            end do
        end associate
    end subroutine find_assignments

    !> '--set ' before group.variable in messages about an override, '' for the text.
    pure function origin(asg) result(prefix)
        type(assignments_t), intent(in) :: asg
        character(len=:), allocatable :: prefix

        if (asg%from_set) then
            prefix = '--set '
        else
            prefix = ''
        end if
    end function origin

    !> The left-hand side 'name' or 'name(i)' of assignment k.
    pure function assignment_lhs(asg, k) result(lhs)
        type(assignments_t), intent(in) :: asg
        integer, intent(in) :: k
        character(len=:), allocatable :: lhs

        lhs = trim(adjustl(asg%body(asg%first(k):asg%eq(k) - 1)))
    end function assignment_lhs

    !> The value text of assignment k (up to the next variable name).
    pure function assignment_value(asg, k) result(value)
        type(assignments_t), intent(in) :: asg
        integer, intent(in) :: k
        character(len=:), allocatable :: value

        if (k < size(asg%eq)) then
            value = trim(adjustl(asg%body(asg%eq(k) + 1:asg%first(k + 1) - 1)))
        else
            value = trim(adjustl(asg%body(asg%eq(k) + 1:)))
        end if
    end function assignment_value

    !> Namelist text of assignment k alone ('&group lhs = value /': reading it alone names
    !> the variable when a value is bad), or of the whole group for k = size(asg%eq) + 1.
    pure function piece(asg, k) result(text)
        type(assignments_t), intent(in) :: asg
        integer, intent(in) :: k
        character(len=:), allocatable :: text

        if (k <= size(asg%eq)) then
            text = '&' // trim(asg%group) // ' ' // assignment_lhs(asg, k) // ' = ' // assignment_value(asg, k) // ' /'
        else
            text = '&' // trim(asg%group) // ' ' // asg%body // ' /'
        end if
    end function piece


end module namelist_text_m
