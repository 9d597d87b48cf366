!> The namelist reader: read_config reads the input text, then the --set overrides, group by
!> group (namelist_text_m), and the tables of &initial. Only what the reader alone can know is
!> checked here (text, syntax, names, types, &material); value ranges are checked by validate_m.
module config_reader_m
    use, intrinsic :: ieee_exceptions, only: ieee_get_halting_mode, ieee_set_halting_mode, ieee_overflow
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use kinds_m, only: dp
    use errors_m, only: fatal, EXIT_INPUT, check_allocation
    use config_m, only: config_t, initial_t, LEN_PATH
    use strings_m, only: lower, excerpt, quoted, int_str, format_real
    use namelist_text_m, only: string_t, group_t, read_source, find_groups, read_group, &
                               parse_override, LEN_MSG
    use material_m, only: check_material
    implicit none
    private
    public :: read_config

contains

    !> Read the run configuration from `source` (a file path, or '-' for standard input) into
    !> cfg over the defaults of its types, then each of `overrides` ('group.variable=value', as
    !> after --set) as a group of that one assignment read after the text (docs/input.md).
    subroutine read_config(source, cfg, overrides)
        character(len=*), intent(in) :: source
        type(config_t), intent(out) :: cfg
        type(string_t), intent(in), optional :: overrides(:)
        type(string_t), allocatable :: lines(:)
        type(group_t), allocatable :: groups(:), sets(:)
        character(len=:), allocatable :: what, all
        integer :: k
        logical :: halt_on_overflow

        ! A value like 1e400 reads as +Inf, which validation rejects with a message; a Debug
        ! build's overflow trap must not turn that into a crash inside the namelist read.
        call ieee_get_halting_mode(ieee_overflow, halt_on_overflow)
        call ieee_set_halting_mode(ieee_overflow, .false.)
        cfg%source = source
        ! the overrides are checked first: a misspelt --set fails before stdin is read
        sets = [group_t ::]
        all = ''   ! '--set a=1 --set b=2', the record of the overrides
        if (present(overrides)) then
            do k = 1, size(overrides)
                sets = [sets, parse_override(overrides(k)%s)]
                all = all // ' --set ' // trim(adjustl(overrides(k)%s))
            end do
        end if
        cfg%overrides = adjustl(all)
        if (len_trim(adjustl(all)) > LEN_PATH) cfg%overrides(LEN_PATH - 2:) = '...'
        call read_source(source, lines)
        call find_groups(lines, groups)
        ! no group (an empty file, empty standard input: a forgotten '< input.nml') and no --set:
        ! stop rather than run every default silently
        if (size(groups) == 0 .and. size(sets) == 0) then
            what = 'standard input'
            if (source /= '-') what = quoted(source)
            call fatal(EXIT_INPUT, 'input', what // ' holds no namelist group (it is empty or only ' // &
                       'comments); give an input file, or to run with every default value an empty ' // &
                       "group: echo '&model /' | rodcontact")
        end if
        call check_model_material(groups, sets)
        ! each override a group of one assignment, read like a group of the text
        groups = [groups, sets]
        do k = 1, size(groups)
            call read_group(groups(k), cfg)
        end do
        call read_tables(cfg%initial)
        ! &model from &material and the SI inputs: material_m's nondimensionalise, after validation
        if (cfg%material%present) call check_material(cfg%material)
        call ieee_set_halting_mode(ieee_overflow, halt_on_overflow)
    end subroutine read_config

    !> &material and &model together are ambiguous, whether from the text or from --set.
    subroutine check_model_material(groups, sets)
        type(group_t), intent(in) :: groups(:), sets(:)
        character(len=:), allocatable :: where
        integer :: k

        where = 'material'
        do k = size(sets), 1, -1   ! named by the first override of either group
            associate (lhs => sets(k)%body(:index(sets(k)%body, '=') - 1))
                if (any(sets(k)%name == ['model   ', 'material'])) &
                    where = '--set ' // trim(sets(k)%name) // '.' // lower(trim(adjustl(lhs)))
            end associate
        end do
        if (any([groups%name, sets%name] == 'model') .and. any([groups%name, sets%name] == 'material')) &
            call fatal(EXIT_INPUT, where, '&material and &model are both given, which is ambiguous: ' // &
                       '&material computes the &model values by (2.10)-(2.11); give one of the two groups')
    end subroutine check_model_material

    !> The tables of &initial's *_file into its *_table (docs/input.md, "Tables").
    subroutine read_tables(init)
        type(initial_t), intent(inout) :: init

        call read_table(init%u0_file, 'u0', init%u0_table)
        call read_table(init%u1_file, 'u1', init%u1_table)
        call read_table(init%theta0_file, 'theta0', init%theta0_table)
        call read_table(init%p0_file, 'p0', init%p0_table)
        call read_table(init%q0_file, 'q0', init%q0_table)
        call read_table(init%eta0_file, 'eta0', init%eta0_table)
    end subroutine read_tables

    !> The table in `file` (none if ''), rows (position, value): one row a line, two
    !> numbers apart by blanks, a tab or a comma; '#' starts a comment, blank lines are
    !> skipped. Refused, naming the file and line: a file that cannot be read, a line that
    !> is not two finite numbers, positions not increasing, fewer than two rows.
    subroutine read_table(file, name, table)
        character(len=*), intent(in) :: file, name
        real(dp), allocatable, intent(out) :: table(:, :)
        type(string_t), allocatable :: lines(:)
        character(len=:), allocatable :: where, text, first, rest
        integer :: k, j, n, stat, last, ios
        character(len=LEN_MSG) :: msg

        if (file == '') return
        where = 'initial.' // name // '_file'
        call read_source(file, lines, where)
        allocate (table(size(lines), 2), stat=stat, errmsg=msg)
        call check_allocation(stat, msg, 'the table of ' // where)
        n = 0
        do k = 1, size(lines)
            text = lines(k)%s // '#'
            text = text(:index(text, '#') - 1)
            do j = 1, len(text)
                if (index(char(9) // char(13) // ',', text(j:j)) > 0) text(j:j) = ' '
            end do
            text = trim(adjustl(text))
            if (text == '') cycle
            first = text(:index(text // ' ', ' ') - 1)
            rest = trim(adjustl(text(len(first) + 1:)))
            n = n + 1
            ios = verify(text, '0123456789+-.eEdD ') + index(rest, ' ')   ! two numbers, nothing else
            if (ios == 0) read (text, *, iostat=ios) table(n, :)
            if (ios == 0 .and. .not. all(ieee_is_finite(table(n, :)))) ios = 1
            if (ios /= 0) call fatal(EXIT_INPUT, where, quoted(trim(file)) // ' line ' // int_str(k) // &
                ': got ' // quoted(excerpt(text)) // '; each line must be two finite numbers, position and ' // &
                "value, apart by blanks or a comma ('#' starts a comment)")
            if (n > 1) then
                if (table(n, 1) <= table(n - 1, 1)) call fatal(EXIT_INPUT, where, quoted(trim(file)) // &
                    ' line ' // int_str(k) // ': position ' // excerpt(first) // ' after ' // &
                    format_real(table(n - 1, 1)) // ' (line ' // int_str(last) // &
                    '); the positions must increase from row to row')
            end if
            last = k
        end do
        if (n < 2) call fatal(EXIT_INPUT, where, quoted(trim(file)) // ' has ' // int_str(n) // &
                              ' rows; a table needs at least two rows (position, value) covering the rod')
        table = table(:n, :)
    end subroutine read_table

end module config_reader_m
