!> The input variables as one table, INPUT_VARS (group, name, kind, unit), and the two
!> routines that know which component of config_t holds each (get_value, read_namelist).
!> Both are generated from config_m's types (its header says how) into the two files
!> included below: a namelist group is a static list of declared variables, so
!> read_namelist declares each input variable as a local of its name and copies it from and
!> back to its component of config_t.
module input_vars_m
    use kinds_m, only: dp
    use config_m, only: config_t, initial_t, MAX_POLY_DEGREE, LEN_NAME, LEN_PATH   ! read_namelist's locals
    use strings_m, only: lower, keyword, int_str
    implicit none
    private
    public :: input_var_t, input_item_t, INPUT_VARS, GROUP_NAMES
    public :: KIND_REAL, KIND_INTEGER, KIND_STRING, KIND_LOGICAL, KIND_COEFFS, KIND_PAIR
    public :: var_kind, input_item, input_items, table_items, read_namelist
    public :: group_list, var_list, joined, kind_description, changes_history

    !> Kinds of input variables (codes as in the reader's messages).
    character, parameter :: KIND_REAL = 'r'      !< a real number
    character, parameter :: KIND_INTEGER = 'i'   !< an integer
    character, parameter :: KIND_STRING = 's'    !< a quoted string
    character, parameter :: KIND_LOGICAL = 'l'   !< .true. or .false.
    character, parameter :: KIND_COEFFS = 'a'    !< up to MAX_POLY_DEGREE+1 polynomial coefficients
    character, parameter :: KIND_PAIR = '2'      !< two reals (amplitude, x_end)

    !> One input variable: &group name = value (generate_input_vars.py checks the lengths).
    type :: input_var_t
        character(len=8) :: group = ''
        character(len=16) :: name = ''      !< as the messages spell it (any case in the input)
        character :: kind = KIND_REAL
        logical :: keyword = .false.        !< a keyword: stored in lower case, left-adjusted
        character(len=24) :: unit = ''      !< unit (&material) or note (&model) in the echo
    end type input_var_t

    include 'input_vars_table.inc'

    !> The value of one input (or of the record of where the input came from), named
    !> 'group.variable' as in the output file. The value is in the component of its kind:
    !> reals (KIND_REAL: one element), int, text (trimmed) or flag.
    type :: input_item_t
        character(len=:), allocatable :: name
        character :: kind = KIND_REAL
        logical :: keyword = .false.
        real(dp), allocatable :: reals(:)
        integer :: int = 0
        character(len=:), allocatable :: text
        logical :: flag = .false.
    end type input_item_t

contains

    !> Whether input variable `var` changes the computed history, so that a restart must
    !> keep it (docs/input.md, &time restart_from): every variable of the physics, contact,
    !> mesh, initial data, solver and time-stepping groups, except the end time and the
    !> restart file itself. &output (where and how often the history is written) may change.
    elemental logical function changes_history(var)
        type(input_var_t), intent(in) :: var

        select case (var%group)
        case ('model', 'material', 'contact', 'mesh', 'initial', 'solver')
            changes_history = .true.
        case ('time')
            changes_history = var%name /= 't_end' .and. var%name /= 'restart_from'
        case ('output')
            ! the steps land on the snapshot times (run_m)
            ! n_points: the width of the /snapshots rows a restart copies
            ! series_dt: the times of the /series entries; snapshot_land: whether steps land
            ! error_estimate: the checkpoint holds the companions or not
            changes_history = var%name == 'snapshot_dt' .or. var%name == 'n_points' .or. &
                              var%name == 'series_dt' .or. var%name == 'snapshot_land' .or. &
                              var%name == 'error_estimate'
        case default
            changes_history = .false.
        end select
    end function changes_history

    !> The kind of variable `name` (any case) of `group`; ' ' if there is no such variable.
    pure function var_kind(group, name) result(kind)
        character(len=*), intent(in) :: group, name
        character :: kind
        integer :: k

        kind = ' '
        do k = 1, size(INPUT_VARS)
            if (INPUT_VARS(k)%group == group .and. lower(INPUT_VARS(k)%name) == lower(name)) &
                kind = INPUT_VARS(k)%kind
        end do
    end function var_kind

    !> The value of input variable INPUT_VARS(k) in cfg.
    function input_item(cfg, k) result(item)
        type(config_t), intent(in) :: cfg
        integer, intent(in) :: k
        type(input_item_t) :: item

        item%name = trim(INPUT_VARS(k)%group) // '.' // trim(INPUT_VARS(k)%name)
        item%kind = INPUT_VARS(k)%kind
        item%keyword = INPUT_VARS(k)%keyword
        call get_value(cfg, k, item)
    end function input_item

    !> Everything the output file records of the input: every input variable (those of
    !> &material only when the group was given; the &model values are then the ones
    !> computed from them), then 'input.source', 'input.overrides' and the tables.
    function input_items(cfg) result(items)
        type(config_t), intent(in) :: cfg
        type(input_item_t), allocatable :: items(:)
        integer :: k

        items = [input_item_t ::]
        do k = 1, size(INPUT_VARS)
            if (INPUT_VARS(k)%group /= 'material' .or. cfg%material%present) &
                items = [items, input_item(cfg, k)]
        end do
        items = [items, string_item('input.source', trim(cfg%source)), &
                 string_item('input.overrides', trim(cfg%overrides)), table_items(cfg%initial)]
    end function input_items

    !> The tables read from &initial's *_file, as items 'initial.<field>_table' (positions,
    !> then values): the output file records them and a restart compares them, not only
    !> the files' names.
    function table_items(init) result(items)
        type(initial_t), intent(in) :: init
        type(input_item_t), allocatable :: items(:)

        allocate (items(0))
        call add('u0', init%u0_table)
        call add('u1', init%u1_table)
        call add('theta0', init%theta0_table)
        call add('p0', init%p0_table)
        call add('q0', init%q0_table)
        call add('eta0', init%eta0_table)
    contains
        subroutine add(name, table)
            character(len=*), intent(in) :: name
            real(dp), intent(in), optional :: table(:, :)
            type(input_item_t) :: item

            if (.not. present(table)) return
            item%name = 'initial.' // name // '_table'
            item%kind = KIND_COEFFS
            item%reals = [table(:, 1), table(:, 2)]
            items = [items, item]
        end subroutine add
    end function table_items

    !> An item of kind KIND_STRING.
    function string_item(name, text) result(item)
        character(len=*), intent(in) :: name, text
        type(input_item_t) :: item

        item%name = name
        item%kind = KIND_STRING
        item%text = text
    end function string_item

    include 'input_vars_access.inc'

    ! ------------------------------------------------ lists and words for messages

    !> '&model, &contact, ...'
    pure function group_list() result(list)
        character(len=:), allocatable :: list

        list = joined(GROUP_NAMES, '&', '')
    end function group_list

    !> 'rho, alpha, ...': the variables of `group`.
    pure function var_list(group) result(list)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: list

        list = joined(pack(INPUT_VARS%name, INPUT_VARS%group == group), '', '')
    end function var_list

    !> The words, each between `before` and `after`, separated by ', '.
    pure function joined(words, before, after) result(list)
        character(len=*), intent(in) :: words(:), before, after
        character(len=:), allocatable :: list
        integer :: k

        list = before // trim(words(1)) // after
        do k = 2, size(words)
            list = list // ', ' // before // trim(words(k)) // after
        end do
    end function joined

    !> What a value of kind `kind` must be, for messages.
    pure function kind_description(kind) result(text)
        character, intent(in) :: kind
        character(len=:), allocatable :: text
        character(len=*), parameter :: KINDS = KIND_REAL // KIND_INTEGER // KIND_STRING // KIND_LOGICAL // &
                                               KIND_PAIR
        character(len=*), parameter :: TEXTS(5) = [character(len=34) :: 'a real number', 'an integer', &
            "a quoted string, e.g. 'value'", '.true. or .false.', 'two real numbers: amplitude, x_end']

        text = 'a valid value'
        if (index(KINDS, kind) > 0) text = trim(TEXTS(index(KINDS, kind)))
        if (kind == KIND_COEFFS) text = 'at most ' // int_str(MAX_POLY_DEGREE + 1) // &
                                        ' real coefficients c0, c1, ... (of x**0, x**1, ...)'
    end function kind_description

end module input_vars_m
