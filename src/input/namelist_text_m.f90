!> The namelist text of the input: the whole source in memory (standard input cannot be
!> rewound), comments blanked, the groups '&name ... /' located (so that an unknown group, a
!> group given twice or stray text is an error, in any order of the groups), and each group
!> split into its assignments 'lhs = value', read one at a time (read_group). A command-line override '--set
!> group.variable=value' becomes a group of that one assignment, read after the text: it
!> passes the same checks and names itself in any error; what only a --set can get wrong
!> (its form, a subscript, a value that would end the group) is checked when it is parsed,
!> before the input is read (a misspelt --set fails before standard input is read).
module namelist_text_m
    use, intrinsic :: iso_fortran_env, only: input_unit, iostat_end, iostat_eor
    use errors_m, only: fatal, EXIT_INPUT, check_allocation
    use config_m, only: config_t, LEN_NAME
    use strings_m, only: lower, squeeze, excerpt, quoted, doubled_quotes, identifier_at, is_name_char, int_str
    use input_vars_m, only: GROUP_NAMES, KIND_COEFFS, KIND_PAIR, KIND_STRING, group_list, var_list, var_kind, &
                            kind_description, read_namelist
    implicit none
    private
    public :: string_t, group_t
    public :: read_source, find_groups, read_group, parse_override, LEN_MSG

    integer, parameter :: LEN_MSG = 512         !< iomsg buffers

    !> A namelist group of the input text, or a --set override as a group of one assignment.
    type :: group_t
        character(len=LEN_NAME) :: name = ''      !< lower case, without '&'
        integer :: line = 0                       !< the line of its '&name' (0: none open)
        character(len=:), allocatable :: origin   !< '--set ' before group.variable in messages, or ''
        character(len=:), allocatable :: body     !< text between the name and the terminator
    end type group_t

    !> A line of text.
    type :: string_t
        character(len=:), allocatable :: s
    end type string_t

contains

    !> All lines of the source (a file path, or '-': standard input), read into memory, lines
    !> of any length; a failure is an input error of `var` (default 'input': the namelist's source).
    subroutine read_source(source, lines, var)
        character(len=*), intent(in) :: source
        type(string_t), allocatable, intent(out) :: lines(:)
        character(len=*), intent(in), optional :: var
        type(string_t), allocatable :: grown(:)
        character(len=4096) :: chunk
        character(len=:), allocatable :: line, where, what
        character(len=LEN_MSG) :: msg
        integer :: unit, n, ios, stat, n_read
        logical :: is_directory

        where = 'input'
        if (present(var)) where = var
        unit = input_unit
        what = 'standard input'
        if (trim(source) /= '-') then
            what = "'" // trim(source) // "'"
            ! gfortran opens a directory without complaint and then reads nothing from it
            inquire (file=trim(source) // '/.', exist=is_directory)
            if (is_directory) call fatal(EXIT_INPUT, where, 'cannot open ' // what // ': it is a directory')
            msg = ''
            open (newunit=unit, file=trim(source), status='old', action='read', iostat=ios, iomsg=msg)
            if (ios /= 0) call fatal(EXIT_INPUT, where, 'cannot open ' // what // ': ' // trim(msg))
        end if
        allocate (lines(0))
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
                allocate (grown(max(64, 2 * n)), stat=stat, errmsg=msg)
                call check_allocation(stat, msg, 'the lines of ' // what // ' (' // int_str(n) // ' lines so far)')
                grown(:n) = lines
                call move_alloc(grown, lines)
            end if
            n = n + 1
            lines(n)%s = line
            if (ios == iostat_end) exit
        end do
        lines = lines(:n)
        ! the text is in memory: a failure to close a read-only file cannot lose anything
        if (unit /= input_unit) close (unit, iostat=ios)
    end subroutine read_source

    !> Locate the groups '&name ... /' (or '... &end'), blanking '!' comments (outside quoted
    !> strings), tabs and carriage returns; any other text outside the groups, an unknown
    !> group, a group given twice or a group left open is an input error.
    subroutine find_groups(lines, groups)
        type(string_t), intent(inout) :: lines(:)
        type(group_t), allocatable, intent(out) :: groups(:)
        type(group_t) :: current
        character :: quote
        character(len=:), allocatable :: name
        integer :: i, j, k, start

        name = ''
        groups = [group_t ::]
        do i = 1, size(lines)
            quote = ' '
            start = 1   ! of the part of line i in the current group's body
            j = 1
            do while (j <= len_trim(lines(i)%s))
                associate (ch => lines(i)%s(j:j))
                    if (ch == achar(9) .or. ch == achar(13)) ch = ' '
                    if (quote /= ' ') then
                        if (ch == quote) quote = ' '
                    else if (ch == '!') then
                        lines(i)%s(j:) = ''
                    else if (current%line == 0) then
                        if (ch == '&') then
                            name = lower(identifier_at(lines(i)%s, j + 1))
                            call check_group_name(name, i, groups)
                            current = group_t(name=name, line=i, origin='', body='')
                            start = j + 1 + len(name)
                            j = j + len(name)
                        else if (ch /= ' ') then
                            call fatal(EXIT_INPUT, 'input', 'text outside a namelist group at line ' // &
                                       int_str(i) // ": '" // excerpt(lines(i)%s(j:)) // "'; every group " // &
                                       "starts with '&name' (name one of " // group_list() // &
                                       ") and ends with '/'")
                        end if
                    else if (ch == "'" .or. ch == '"') then
                        quote = ch
                    else if (ch == '/' .or. ch == '&') then
                        k = j
                        if (ch == '&') then
                            name = lower(identifier_at(lines(i)%s, j + 1))
                            if (name /= 'end') call fatal(EXIT_INPUT, trim(current%name), 'group &' // &
                                trim(current%name) // ' (line ' // int_str(current%line) // ') is not ' // &
                                "closed: '&" // name // "' at line " // int_str(i) // " comes before its '/'")
                            k = j + 3
                        end if
                        current%body = current%body // lines(i)%s(start:j - 1) // ' '
                        groups = [groups, current]
                        current%line = 0
                        j = k
                    end if
                end associate
                j = j + 1
            end do
            if (current%line > 0) current%body = current%body // lines(i)%s(start:) // ' '
        end do
        if (current%line > 0) call fatal(EXIT_INPUT, trim(current%name), 'group &' // trim(current%name) // &
            ' (line ' // int_str(current%line) // ") is not closed: missing '/' at its end " // &
            '(or a quoted string without its closing quote)')
    end subroutine find_groups

    !> A group name must be one of GROUP_NAMES and not seen before.
    subroutine check_group_name(name, line, groups)
        character(len=*), intent(in) :: name
        integer, intent(in) :: line
        type(group_t), intent(in) :: groups(:)
        integer :: k

        do k = size(groups), 1, -1   ! a loop: findloc on groups%name copies the strided names (Debug warns)
            if (groups(k)%name == name) exit
        end do
        if (len(name) == 0) call fatal(EXIT_INPUT, 'input', "'&' without a group name at line " // &
                                       int_str(line) // '; allowed groups: ' // group_list())
        if (.not. any(GROUP_NAMES == name)) call fatal(EXIT_INPUT, 'input', "unknown namelist group '&" // &
            name // "' at line " // int_str(line) // '; allowed groups: ' // group_list())
        if (k > 0) call fatal(EXIT_INPUT, name, 'group &' // name // ' given twice (lines ' // &
            int_str(groups(k)%line) // ' and ' // int_str(line) // '); each group may appear at most once')
    end subroutine check_group_name

    !> Read group `grp` into its part of cfg, over the values already there: each assignment
    !> 'lhs = value' by a namelist read of its own ('&group lhs = value /'), so that a bad
    !> value names its variable, after what only the reader can check: a known variable
    !> name, given once, a value after '=', a string quoted.
    subroutine read_group(grp, cfg)
        type(group_t), intent(in) :: grp
        type(config_t), intent(inout) :: cfg
        character(len=:), allocatable :: group, lhs, name, value, where
        character(len=LEN_MSG) :: msg
        character :: kind
        integer, allocatable :: first(:), eq(:)
        integer :: k, p, ios

        group = trim(grp%name)
        call find_assignments(grp%body, first, eq)
        associate (body => grp%body)
            if (verify(body(:first(1) - 1), ' ,') /= 0) call fatal(EXIT_INPUT, grp%origin // group, &
                "expected 'variable = value' in &" // group // ", got '" // excerpt(body(:first(1) - 1)) // &
                "'; allowed variables: " // var_list(group))
            do k = 1, size(eq)
                lhs = trim(adjustl(body(first(k):eq(k) - 1)))
                value = trim(adjustl(body(eq(k) + 1:first(k + 1) - 1)))
                name = identifier_at(lhs, 1)
                where = grp%origin // group // '.' // lower(name)
                if (len(name) == 0) call fatal(EXIT_INPUT, grp%origin // group, "'=' without a variable " // &
                    'name in &' // group // ": '" // excerpt(body(first(k):)) // "'; allowed variables: " // &
                    var_list(group))
                call require_known(where, group, name)
                kind = var_kind(group, name)
                do p = 1, k - 1
                    if (lower(squeeze(body(first(p):eq(p) - 1))) == lower(squeeze(lhs))) &
                        call fatal(EXIT_INPUT, where, "'" // lhs // "' given twice in &" // group)
                end do
                if (verify(value, ' ,') == 0) call fatal(EXIT_INPUT, where, "no value after '" // lhs // &
                    " ='; must be " // kind_description(kind))
                ! gfortran silently skips an unquoted string value: only the reader can catch it
                if (kind == KIND_STRING .and. scan(value(1:1), '''"') == 0) call fatal(EXIT_INPUT, where, &
                    'got ' // excerpt(value) // '; must be a quoted string, e.g. ' // name // ' = ' // &
                    quoted(excerpt(value)))
                call read_namelist(cfg, group, '&' // group // ' ' // lhs // ' = ' // value // ' /', ios, msg)
                if (len(lhs) > len(name)) value = lhs // ' = ' // value   ! subscripted: the whole assignment
                if (ios /= 0) call fatal(EXIT_INPUT, where, 'got ' // quoted(excerpt(value)) // '; must be ' // &
                    kind_description(kind) // ' (namelist read: ' // trim(msg) // ')')
            end do
        end associate
        if (group == 'material') cfg%material%present = .true.
    end subroutine read_group

    !> The variable of left-hand side `lhs` ('name' or 'name(i)') must be one of `group`.
    subroutine require_known(where, group, lhs)
        character(len=*), intent(in) :: where, group, lhs

        if (var_kind(group, identifier_at(lhs, 1)) == ' ') call fatal(EXIT_INPUT, where, "unknown variable '" // &
            lhs // "' in &" // trim(group) // '; allowed: ' // var_list(group))
    end subroutine require_known

    !> The assignments 'lhs = value' of a group's body: eq(k) is the k-th '=' outside quoted
    !> strings, body(first(k):eq(k)-1) its variable name (and subscript, if any), and its value
    !> ends before first(k+1) (first has one more element: len(body) + 1).
    pure subroutine find_assignments(body, first, eq)
        character(len=*), intent(in) :: body
        integer, allocatable, intent(out) :: first(:), eq(:)
        character :: quote
        integer :: j, p

        first = [integer ::]
        eq = [integer ::]
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
                first = [first, p + 1]
                eq = [eq, j]
            end if
        end do
        first = [first, len(body) + 1]
    end subroutine find_assignments

    ! ---------------------------------------------------------------- --set

    !> The override `text` ('group.variable=value' or 'group.variable(i)=value') as a group of
    !> that one assignment, after the checks that can be made before reading it (the header's).
    !> A string value is quoted here unless it is quoted already: the shell need not pass quotes.
    function parse_override(text) result(set)
        character(len=*), intent(in) :: text
        type(group_t) :: set
        character(len=:), allocatable :: lhs, name, subscript, value, where
        character :: code
        integer :: eq, dot

        eq = index(text, '=')
        lhs = trim(adjustl(text(:max(0, eq - 1))))
        dot = index(lhs, '.')
        if (eq == 0 .or. dot == 0) call fatal(EXIT_INPUT, '--set ' // excerpt(text), &
            "expected group.variable=value, e.g. --set model.varpi=0.3 or --set 'initial.theta0_step(1)=5'; " // &
            'groups: ' // group_list())
        set%name = lower(trim(lhs(:dot - 1)))
        set%origin = '--set '
        lhs = trim(adjustl(lhs(dot + 1:)))
        where = '--set ' // trim(set%name) // '.' // lower(lhs)
        if (.not. any(GROUP_NAMES == set%name)) call fatal(EXIT_INPUT, where, "unknown namelist group '" // &
            trim(set%name) // "'; allowed groups: " // group_list())
        call require_known(where, set%name, lhs)
        name = identifier_at(lhs, 1)
        code = var_kind(set%name, name)
        subscript = squeeze(lhs(len(name) + 1:))
        if (len(subscript) > 0) then
            if (code /= KIND_COEFFS .and. code /= KIND_PAIR) call fatal(EXIT_INPUT, where, "'" // name // &
                "' is not an array; give " // trim(set%name) // '.' // lower(name) // '=value (must be ' // &
                kind_description(code) // ')')
            ! '(', digits, ')' (subscript(2:len - 1) is '' when len < 3)
            if (len(subscript) < 3 .or. subscript(1:1) /= '(' .or. subscript(len(subscript):) /= ')' .or. &
                verify(subscript(2:len(subscript) - 1), '0123456789') /= 0) &
                call fatal(EXIT_INPUT, where, "expected a subscript like '" // name // "(1)', got '" // &
                           excerpt(lhs) // "'")
        end if
        value = trim(adjustl(text(eq + 1:)))
        if (code == KIND_STRING) then
            ! a namelist string, an inner ' doubled ('' when empty)
            if (scan(value(1:min(1, len(value))), '''"') == 0) value = doubled_quotes(value, "'")
        else if (scan(value, '/&$=!''"') > 0) then
            ! any of these would end the assignment or the group early in the namelist text
            call fatal(EXIT_INPUT, where, 'got ' // quoted(excerpt(value)) // '; must be ' // &
                       kind_description(code))
        end if
        ! the body of '&group lhs = value /'
        set%body = ' ' // lhs // ' = ' // value // ' '
    end function parse_override

end module namelist_text_m
