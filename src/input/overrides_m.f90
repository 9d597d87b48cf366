!> Command-line overrides '--set group.variable=value': each is split and checked here
!> before the input is read (a misspelt --set fails before standard input is read), then
!> config_reader_m reads it as the only assignment of a group '&group ... /' after the text,
!> so it passes the same checks and names itself in any error.
module overrides_m
    use errors_m, only: fatal, EXIT_INPUT
    use config_m, only: LEN_PATH
    use strings_m, only: lower, squeeze, excerpt, quoted, quoted_string, identifier_at
    use input_vars_m, only: GROUP_NAMES, KIND_COEFFS, KIND_PAIR, KIND_STRING, group_list, var_list, var_kind, &
                            kind_description
    implicit none
    private
    public :: override_t, parse_override, override_summary

    !> One command-line override 'group.variable=value', split and checked by parse_override.
    type :: override_t
        character(len=:), allocatable :: group   !< lower case
        character(len=:), allocatable :: lhs     !< 'variable' or 'variable(i)', as given
        character(len=:), allocatable :: value   !< namelist value text (strings quoted)
    end type override_t

contains

    !> Split the override `text` ('group.variable=value' or 'group.variable(i)=value') and
    !> check what can be checked before reading it: a known group and variable, a subscript
    !> only on an array, a value that stays inside one assignment. The value of a string
    !> variable is quoted here unless it is quoted already (--set output.prefix=runs/a), so
    !> that the shell need not pass the quotes. A variable given twice takes the later value
    !> (the overrides are read in order, as the text's assignments are).
    function parse_override(text) result(set)
        character(len=*), intent(in) :: text
        type(override_t) :: set
        character(len=:), allocatable :: lhs, name, subscript, value, where
        character :: code
        integer :: eq, dot

        eq = index(text, '=')
        lhs = trim(adjustl(text(:max(0, eq - 1))))
        dot = index(lhs, '.')
        if (eq == 0 .or. dot == 0) call fatal(EXIT_INPUT, '--set ' // excerpt(text), &
            "expected group.variable=value, e.g. --set model.varpi=0.3 or --set 'initial.theta0_step(1)=5'; " // &
            'groups: ' // group_list())
        set%group = lower(trim(lhs(:dot - 1)))
        set%lhs = trim(adjustl(lhs(dot + 1:)))
        where = '--set ' // set%group // '.' // lower(set%lhs)
        if (.not. any(GROUP_NAMES == set%group)) call fatal(EXIT_INPUT, where, "unknown namelist group '" // &
            set%group // "'; allowed groups: " // group_list())
        name = identifier_at(set%lhs, 1)
        code = ' '
        if (len(name) > 0) code = var_kind(set%group, name)
        if (code == ' ') call fatal(EXIT_INPUT, where, "unknown variable '" // set%lhs // "' in &" // &
            set%group // '; allowed: ' // var_list(set%group))
        subscript = squeeze(set%lhs(len(name) + 1:))
        if (len(subscript) > 0) then
            if (code /= KIND_COEFFS .and. code /= KIND_PAIR) call fatal(EXIT_INPUT, where, "'" // name // &
                "' is not an array; give " // set%group // '.' // lower(name) // '=value (must be ' // &
                kind_description(code) // ')')
            if (len(subscript) < 3 .or. subscript(1:1) /= '(' .or. subscript(len(subscript):) /= ')') &
                call fatal(EXIT_INPUT, where, "expected a subscript like '" // name // "(1)', got '" // &
                           excerpt(set%lhs) // "'")
            if (verify(subscript(2:len(subscript) - 1), '0123456789') /= 0) &
                call fatal(EXIT_INPUT, where, "expected a subscript like '" // name // "(1)', got '" // &
                           excerpt(set%lhs) // "'")
        end if
        value = trim(adjustl(text(eq + 1:)))
        if (code == KIND_STRING) then
            if (len(value) == 0) then
                value = "''"
            else if (scan(value(1:1), '''"') == 0) then
                value = quoted_string(value)
            end if
        else if (scan(value, '/&$=!''"') > 0) then
            ! any of these would end the assignment or the group early in the namelist text
            call fatal(EXIT_INPUT, where, 'got ' // quoted(excerpt(value)) // '; must be ' // kind_description(code))
        end if
        set%value = value
    end function parse_override

    !> '--set a=1 --set b=2', the record of the overrides in cfg%overrides.
    pure function override_summary(overrides) result(text)
        character(len=*), intent(in) :: overrides(:)
        character(len=LEN_PATH) :: text
        character(len=:), allocatable :: all
        integer :: k

        all = ''
        do k = 1, size(overrides)
            all = all // ' --set ' // trim(adjustl(overrides(k)))
        end do
        all = trim(adjustl(all))
        if (len(all) > LEN_PATH) all = all(:LEN_PATH - 3) // '...'
        text = all
    end function override_summary

end module overrides_m
