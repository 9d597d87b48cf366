!> Run configuration: one derived type per namelist group (SPEC section 3), defaults built
!> into the types (the paper's values (7.1) and discretisation), and the namelist reader.
!> The reader takes the whole text into memory, finds the groups itself (so that an unknown
!> group, a group given twice or stray text is an error, in any order of the groups), then
!> reads each group by a namelist read from the internal text. Command-line overrides
!> ('--set group.variable=value') are read the same way, one assignment at a time, after
!> the text, so they pass the same checks and name themselves in any error.
module config_m
    use, intrinsic :: iso_fortran_env, only: input_unit, output_unit, iostat_end, iostat_eor
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
    use, intrinsic :: ieee_exceptions, only: ieee_get_halting_mode, ieee_set_halting_mode, ieee_overflow
    use kinds_m, only: dp
    use errors_m, only: fatal, EXIT_INPUT
    implicit none
    private
    public :: model_t, contact_t, mesh_t, time_t, initial_t, solver_t, output_t, material_t, config_t
    public :: MAX_POLY_DEGREE, LEN_NAME, LEN_PATH
    public :: read_config
    public :: nondim_t, nondim_groups, model_from_material
    public :: format_real, int_str

    integer, parameter :: MAX_POLY_DEGREE = 8   !< *_poly coefficients 0..8 (constant term first)
    integer, parameter :: LEN_NAME = 32         !< length of keyword values ('penalty', 'euler', ...)
    integer, parameter :: LEN_PATH = 1024       !< length of path values (prefix, restart_from)

    !> &model: nondimensional coefficients of (2.11); defaults are the copper values (7.1).
    type :: model_t
        real(dp) :: rho = 1.2298e-17_dp
        real(dp) :: alpha = 0.0163_dp
        real(dp) :: varpi = 0.1_dp
        real(dp) :: gamma1 = 0.01931_dp
        real(dp) :: gamma2 = 4.635e-4_dp
        real(dp) :: c = 1.0136_dp
        real(dp) :: d = 0.00251_dp
        real(dp) :: r = 4.635e-4_dp
        real(dp) :: hbar = 0.03058_dp
        real(dp) :: tau0 = 0.02_dp
        real(dp) :: tau = 0.2_dp
    end type model_t

    !> &contact: obstacle gap g and normal compliance (3.4) with penalty eps.
    type :: contact_t
        real(dp) :: g = 0.1_dp
        real(dp) :: eps = 0.01_dp
        character(len=LEN_NAME) :: law = 'penalty'
    end type contact_t

    !> &mesh: uniform partition of [0,1] into n_elements elements (h = 1/s).
    type :: mesh_t
        integer :: n_elements = 500
    end type mesh_t

    !> &time: implicit Euler step dt up to t_end.
    type :: time_t
        real(dp) :: dt = 1.0e-4_dp
        real(dp) :: t_end = 1.0_dp
        character(len=LEN_NAME) :: scheme = 'euler'
        character(len=LEN_PATH) :: restart_from = ''
    end type time_t

    !> &initial: initial data (2.12) as polynomials in x plus optional steps (amp, x_end).
    type :: initial_t
        real(dp) :: u0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: u1_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: theta0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: p0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: q0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: eta0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: theta0_step(2) = 0.0_dp   !< (amplitude, x_end): adds amplitude on [0, x_end]
        real(dp) :: p0_step(2) = 0.0_dp
    end type initial_t

    !> &solver: how the per-step nonlinearity (contact node) is solved.
    type :: solver_t
        character(len=LEN_NAME) :: method = 'monolithic'
        real(dp) :: tol = 1.0e-7_dp
        integer :: max_iter = 50
    end type solver_t

    !> &output: HDF5 file <prefix>.h5 and what goes into it.
    type :: output_t
        character(len=LEN_PATH) :: prefix = 'out/run'
        integer :: snapshot_every = 100
        integer :: series_every = 1
        integer :: checkpoint_every = 0
        logical :: quiet = .false.
    end type output_t

    !> &material (optional): physical quantities of Table 1 in SI units, from which the
    !> &model values are computed by (2.10)-(2.11) when the group is present.
    type :: material_t
        logical :: present = .false.
        real(dp) :: T0 = 293.0_dp            !< reference temperature [K]
        real(dp) :: rho0 = 8954.0_dp         !< mass density [kg/m^3]
        real(dp) :: cE = 383.1_dp            !< specific heat at constant strain [J/(kg K)]
        real(dp) :: kappa = 386.0_dp         !< thermal conductivity [W/(m K)]
        real(dp) :: lambda = 7.76e10_dp      !< Lame constant [kg/(m s^2)]
        real(dp) :: mu = 3.86e10_dp          !< Lame constant [kg/(m s^2)]
        real(dp) :: alpha_t = 1.78e-5_dp     !< linear thermal expansion [1/K]
        real(dp) :: alpha_c = 1.98e-4_dp     !< linear diffusion expansion [m^3/kg]
        real(dp) :: D = 0.85e-8_dp           !< diffusion coefficient [kg s/m^3]
        real(dp) :: nu = 1.2e4_dp            !< thermodiffusion measure [m^2/(s^2 K)]
        real(dp) :: varrho = 0.9e6_dp        !< diffusive effect measure [m^5/(kg s^2)]
        real(dp) :: ell = 1.0_dp             !< rod length [m]
        real(dp) :: tau0 = 0.0_dp            !< thermal relaxation time [s]
        real(dp) :: tau = 0.0_dp             !< diffusion relaxation time [s]
        real(dp) :: lambda_v = 0.0_dp        !< damping coefficient lambda' [kg/(m s)]
        real(dp) :: mu_v = 0.0_dp            !< damping coefficient mu' [kg/(m s)]
    end type material_t

    !> The whole run configuration.
    type :: config_t
        type(model_t) :: model
        type(contact_t) :: contact
        type(mesh_t) :: mesh
        type(time_t) :: time
        type(initial_t) :: initial
        type(solver_t) :: solver
        type(output_t) :: output
        type(material_t) :: material
        character(len=LEN_PATH) :: source = ''   !< where the namelist came from ('-' = stdin)
        !> the --set overrides applied after it, as given ('' if none; truncated with '...')
        character(len=LEN_PATH) :: overrides = ''
    end type config_t

    integer, parameter :: LEN_MSG = 512         !< iomsg buffers

    !> Namelist groups of SPEC section 3, in the order validation checks them.
    character(len=*), parameter :: GROUP_NAMES(8) = [character(len=8) :: &
        'model', 'contact', 'mesh', 'time', 'initial', 'solver', 'output', 'material']

    !> Variables of each group as 'name:kind' (kind r real, i integer, s quoted string,
    !> l logical, a up to MAX_POLY_DEGREE+1 reals, 2 two reals), for the reader's messages.
    character(len=*), parameter :: VARS_MODEL = &
        'rho:r alpha:r varpi:r gamma1:r gamma2:r c:r d:r r:r hbar:r tau0:r tau:r'
    character(len=*), parameter :: VARS_CONTACT = 'g:r eps:r law:s'
    character(len=*), parameter :: VARS_MESH = 'n_elements:i'
    character(len=*), parameter :: VARS_TIME = 'dt:r t_end:r scheme:s restart_from:s'
    character(len=*), parameter :: VARS_INITIAL = 'u0_poly:a u1_poly:a theta0_poly:a p0_poly:a ' // &
        'q0_poly:a eta0_poly:a theta0_step:2 p0_step:2'
    character(len=*), parameter :: VARS_SOLVER = 'method:s tol:r max_iter:i'
    character(len=*), parameter :: VARS_OUTPUT = &
        'prefix:s snapshot_every:i series_every:i checkpoint_every:i quiet:l'
    character(len=*), parameter :: VARS_MATERIAL = 'T0:r rho0:r cE:r kappa:r lambda:r mu:r ' // &
        'alpha_t:r alpha_c:r D:r nu:r varrho:r ell:r tau0:r tau:r lambda_v:r mu_v:r'

    !> Nondimensional groups of (2.10) computed from &material.
    type :: nondim_t
        real(dp) :: beta1 = 0.0_dp      !< (3 lambda + 2 mu) alpha_t
        real(dp) :: beta2 = 0.0_dp      !< (3 lambda + 2 mu) alpha_c
        real(dp) :: omega = 0.0_dp      !< time scale rho0 cE ell^2 / kappa [s]
        real(dp) :: delta = 0.0_dp      !< sqrt((lambda + 2 mu) / (rho0 cE T0))
        real(dp) :: varsigma = 0.0_dp   !< rho0 ell^2 / (omega^2 (lambda + 2 mu))
        real(dp) :: zeta = 0.0_dp       !< (lambda' + 2 mu') / (omega (lambda + 2 mu))
        real(dp) :: a_check = 0.0_dp    !< a-check = T0 beta1^2 / (rho0 cE (lambda + 2 mu))
        real(dp) :: alpha1 = 0.0_dp     !< (lambda + 2 mu) nu / (beta1 beta2)
        real(dp) :: alpha2 = 0.0_dp     !< (lambda + 2 mu) ell^2 / (D beta2^2 omega)
        real(dp) :: alpha3 = 0.0_dp     !< (lambda + 2 mu) varrho / beta2^2
    end type nondim_t

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

    !> One command-line override 'group.variable=value', split and checked by parse_override.
    type :: override_t
        character(len=:), allocatable :: group   !< lower case
        character(len=:), allocatable :: lhs     !< 'variable' or 'variable(i)', as given
        character(len=:), allocatable :: value   !< namelist value text (strings quoted)
    end type override_t

    !> A line of text.
    type :: string_t
        character(len=:), allocatable :: s
    end type string_t

contains

    !> Read the run configuration from `source` (a file path, or '-' for standard input)
    !> into cfg: every group present overrides the defaults of its type. Then each of
    !> `overrides` ('group.variable=value', as after --set on the command line) is applied
    !> in turn, as if it were the only assignment of a group '&group ... /' read after the
    !> text (so a group the text does not have is fine, and an override of one array
    !> element keeps the others). Only what the reader alone can know is checked here
    !> (text, syntax, names, types, &material); value ranges are checked by validate_m.
    subroutine read_config(source, cfg, overrides)
        character(len=*), intent(in) :: source
        type(config_t), intent(out) :: cfg
        character(len=*), intent(in), optional :: overrides(:)
        type(string_t), allocatable :: lines(:)
        type(group_t), allocatable :: groups(:)
        type(override_t), allocatable :: sets(:)
        type(string_t) :: set_line(1)
        type(group_t) :: set_group
        integer :: k
        logical :: halt_on_overflow

        ! A value like 1e400 reads as +Inf, which validation rejects with a message; a Debug
        ! build's overflow trap must not turn that into a crash inside the namelist read.
        call ieee_get_halting_mode(ieee_overflow, halt_on_overflow)
        call ieee_set_halting_mode(ieee_overflow, .false.)
        cfg%source = source
        ! the overrides are checked first: a misspelt --set fails before stdin is read
        if (present(overrides)) then
            allocate (sets(size(overrides)))
            do k = 1, size(overrides)
                sets(k) = parse_override(overrides(k), sets(:k - 1))
            end do
            cfg%overrides = override_summary(overrides)
        else
            allocate (sets(0))
        end if
        call read_source(source, lines)
        call strip_comments(lines)
        call find_groups(lines, groups)
        call check_model_material(groups, sets)
        do k = 1, size(groups)
            call read_group(lines, groups(k), cfg)
        end do
        do k = 1, size(sets)
            ! '&group lhs = value /' on a line of its own, read like a group of the text
            set_line(1)%s = '&' // sets(k)%group // ' ' // sets(k)%lhs // ' = ' // sets(k)%value // ' /'
            set_group = group_t(name=sets(k)%group, first=[1, 1], body=[1, 2 + len(sets(k)%group)], &
                                term=[1, len(set_line(1)%s)], last=[1, len(set_line(1)%s)], from_set=.true.)
            call read_group(set_line, set_group, cfg)
        end do
        if (cfg%material%present) then
            call check_material(cfg%material)
            cfg%model = model_from_material(cfg%material)
            call echo_material(cfg%material, nondim_groups(cfg%material), cfg%model)
        end if
        call ieee_set_halting_mode(ieee_overflow, halt_on_overflow)
    end subroutine read_config

    !> Read group `grp` of `lines` into its part of cfg, over the values already there.
    subroutine read_group(lines, grp, cfg)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(config_t), intent(inout) :: cfg

        select case (grp%name)
        case ('model')
            call read_model(lines, grp, cfg%model)
        case ('contact')
            call read_contact(lines, grp, cfg%contact)
        case ('mesh')
            call read_mesh(lines, grp, cfg%mesh)
        case ('time')
            call read_time(lines, grp, cfg%time)
        case ('initial')
            call read_initial(lines, grp, cfg%initial)
        case ('solver')
            call read_solver(lines, grp, cfg%solver)
        case ('output')
            call read_output(lines, grp, cfg%output)
        case ('material')
            call read_material(lines, grp, cfg%material)
        end select
    end subroutine read_group

    !> &material and &model together are ambiguous, whether from the text or from --set.
    subroutine check_model_material(groups, sets)
        type(group_t), intent(in) :: groups(:)
        type(override_t), intent(in) :: sets(:)
        character(len=:), allocatable :: where
        logical :: has_model, has_material
        integer :: k

        has_model = any(groups%name == 'model')
        has_material = any(groups%name == 'material')
        where = 'material'
        do k = 1, size(sets)
            if (sets(k)%group == 'model' .or. sets(k)%group == 'material') then
                if (sets(k)%group == 'model') has_model = .true.
                if (sets(k)%group == 'material') has_material = .true.
                if (where == 'material') where = '--set ' // sets(k)%group // '.' // lower(sets(k)%lhs)
            end if
        end do
        if (has_model .and. has_material) &
            call fatal(EXIT_INPUT, where, '&material and &model are both given, which is ambiguous: ' // &
                       '&material computes the &model values by (2.10)-(2.11); give one of the two groups')
    end subroutine check_model_material

    !> Split the override `text` ('group.variable=value' or 'group.variable(i)=value') and
    !> check what can be checked before reading it: a known group and variable, a subscript
    !> only on an array, a value that stays inside one assignment, not given twice. The
    !> value of a string variable is quoted here unless it is quoted already (--set
    !> output.prefix=runs/a), so that the shell need not pass the quotes.
    function parse_override(text, earlier) result(set)
        character(len=*), intent(in) :: text
        type(override_t), intent(in) :: earlier(:)
        type(override_t) :: set
        character(len=:), allocatable :: lhs, name, subscript, value, where, vars
        character :: code
        integer :: eq, dot, k

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
        vars = group_vars(set%group)
        name = identifier_at(set%lhs, 1)
        code = ' '
        if (len(name) > 0) code = var_kind(vars, name)
        if (code == ' ') call fatal(EXIT_INPUT, where, "unknown variable '" // set%lhs // "' in &" // &
            set%group // '; allowed: ' // var_list(vars))
        subscript = squeeze(set%lhs(len(name) + 1:))
        if (len(subscript) > 0) then
            if (code /= 'a' .and. code /= '2') call fatal(EXIT_INPUT, where, "'" // name // "' is not an array; " // &
                'give ' // set%group // '.' // lower(name) // '=value (must be ' // kind_description(code) // ')')
            if (len(subscript) < 3 .or. subscript(1:1) /= '(' .or. subscript(len(subscript):) /= ')') &
                call fatal(EXIT_INPUT, where, "expected a subscript like '" // name // "(1)', got '" // &
                           excerpt(set%lhs) // "'")
            if (verify(subscript(2:len(subscript) - 1), '0123456789') /= 0) &
                call fatal(EXIT_INPUT, where, "expected a subscript like '" // name // "(1)', got '" // &
                           excerpt(set%lhs) // "'")
        end if
        do k = 1, size(earlier)
            if (earlier(k)%group == set%group .and. lower(squeeze(earlier(k)%lhs)) == lower(squeeze(set%lhs))) &
                call fatal(EXIT_INPUT, where, 'given twice on the command line; each --set variable at most once')
        end do
        value = trim(adjustl(text(eq + 1:)))
        if (code == 's') then
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

    !> The nondimensional groups of (2.10) for the physical quantities `mat`.
    pure function nondim_groups(mat) result(nd)
        type(material_t), intent(in) :: mat
        type(nondim_t) :: nd
        real(dp) :: stiffness   ! lambda + 2 mu

        stiffness = mat%lambda + 2.0_dp * mat%mu
        nd%beta1 = (3.0_dp * mat%lambda + 2.0_dp * mat%mu) * mat%alpha_t
        nd%beta2 = (3.0_dp * mat%lambda + 2.0_dp * mat%mu) * mat%alpha_c
        nd%omega = mat%rho0 * mat%cE * mat%ell**2 / mat%kappa
        nd%delta = sqrt(stiffness / (mat%rho0 * mat%cE * mat%T0))
        nd%varsigma = mat%rho0 * mat%ell**2 / (nd%omega**2 * stiffness)
        nd%zeta = (mat%lambda_v + 2.0_dp * mat%mu_v) / (nd%omega * stiffness)
        nd%a_check = mat%T0 * nd%beta1**2 / (mat%rho0 * mat%cE * stiffness)
        nd%alpha1 = stiffness * mat%nu / (nd%beta1 * nd%beta2)
        nd%alpha2 = stiffness * mat%ell**2 / (mat%D * nd%beta2**2 * nd%omega)
        nd%alpha3 = stiffness * mat%varrho / nd%beta2**2
    end function nondim_groups

    !> The coefficients of (2.11) for the physical quantities `mat`; relaxation times are
    !> scaled as tau0* = tau0/omega, tau* = tau/omega.
    pure function model_from_material(mat) result(m)
        type(material_t), intent(in) :: mat
        type(model_t) :: m
        type(nondim_t) :: nd

        nd = nondim_groups(mat)
        associate (a => nd%a_check, alpha1 => nd%alpha1, alpha2 => nd%alpha2, alpha3 => nd%alpha3)
            m%rho = a * nd%varsigma
            m%alpha = a * (1.0_dp - 1.0_dp / alpha3)
            m%varpi = nd%zeta * a
            m%gamma1 = a * (1.0_dp + alpha1 / alpha3)
            m%gamma2 = a / alpha3
            m%c = 1.0_dp + a * alpha1**2 / alpha3
            m%d = alpha1 * a / alpha3
            m%r = a / alpha3
            m%hbar = a / alpha2
        end associate
        m%tau0 = mat%tau0 / nd%omega
        m%tau = mat%tau / nd%omega
    end function model_from_material

    !> x in a plain form for messages: 15 significant digits, trailing zeros
    !> dropped, fixed notation for 1e-4 <= |x| < 1e6, else 1.2298e-17; NaN, Inf, -Inf.
    pure function format_real(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        character(len=:), allocatable :: digits, sign
        integer :: e, expo, ios

        if (ieee_is_nan(x)) then
            s = 'NaN'
            return
        else if (.not. ieee_is_finite(x)) then
            s = merge('-Inf', ' Inf', x < 0.0_dp)
            s = trim(adjustl(s))
            return
        else if (.not. abs(x) > 0.0_dp) then
            s = '0'
            return
        end if
        write (buf, '(es23.14e3)', iostat=ios) x
        buf = adjustl(buf)
        e = index(buf, 'E')
        read (buf(e + 1:), *, iostat=ios) expo
        sign = ''
        if (buf(1:1) == '-') then
            sign = '-'
            buf = buf(2:)
            e = e - 1
        end if
        digits = buf(1:1) // buf(3:e - 1)
        do while (len(digits) > 1 .and. digits(len(digits):) == '0')
            digits = digits(:len(digits) - 1)
        end do
        if (expo >= 0 .and. expo < 6) then
            if (len(digits) <= expo + 1) then
                s = digits // repeat('0', expo + 1 - len(digits))
            else
                s = digits(:expo + 1) // '.' // digits(expo + 2:)
            end if
        else if (expo < 0 .and. expo >= -4) then
            s = '0.' // repeat('0', -expo - 1) // digits
        else
            s = digits(1:1)
            if (len(digits) > 1) s = s // '.' // digits(2:)
            write (buf, '(i0)', iostat=ios) expo
            s = s // 'e' // trim(buf)
        end if
        s = sign // s
    end function format_real

    ! ---------------------------------------------------------------- input text

    !> All lines of the source, read into memory (standard input cannot be rewound).
    subroutine read_source(source, lines)
        character(len=*), intent(in) :: source
        type(string_t), allocatable, intent(out) :: lines(:)
        integer :: unit, ios
        logical :: is_directory
        character(len=LEN_MSG) :: msg

        if (trim(source) == '-') then
            call read_lines(input_unit, 'standard input', lines)
        else
            ! gfortran opens a directory without complaint and then reads nothing from it
            inquire (file=trim(source) // '/.', exist=is_directory)
            if (is_directory) call fatal(EXIT_INPUT, 'input', "cannot open '" // trim(source) // "': it is a directory")
            msg = ''
            open (newunit=unit, file=trim(source), status='old', action='read', iostat=ios, iomsg=msg)
            if (ios /= 0) call fatal(EXIT_INPUT, 'input', "cannot open '" // trim(source) // "': " // trim(msg))
            call read_lines(unit, "'" // trim(source) // "'", lines)
            ! the text is in memory: a failure to close a read-only file cannot lose anything
            close (unit, iostat=ios)
        end if
    end subroutine read_source

    !> Read `unit` to its end, line by line, lines of any length.
    subroutine read_lines(unit, what, lines)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: what
        type(string_t), allocatable, intent(out) :: lines(:)
        type(string_t), allocatable :: grown(:)
        character(len=4096) :: chunk
        character(len=:), allocatable :: line
        character(len=LEN_MSG) :: msg
        integer :: n, ios, n_read

        allocate (lines(64))
        n = 0
        do
            line = ''
            do
                msg = ''
                read (unit, '(a)', advance='no', iostat=ios, iomsg=msg, size=n_read) chunk
                if (ios /= 0 .and. ios /= iostat_eor .and. ios /= iostat_end) &
                    call fatal(EXIT_INPUT, 'input', 'cannot read ' // what // ': ' // trim(msg))
                line = line // chunk(:n_read)
                if (ios /= 0) exit
            end do
            if (ios == iostat_end .and. len(line) == 0) exit
            if (n == size(lines)) then
                allocate (grown(2 * n))
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
        integer :: i, j, k

        allocate (groups(0))
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
    subroutine split_group(lines, grp, vars, asg)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        character(len=*), intent(in) :: vars
        type(assignments_t), intent(out) :: asg
        character(len=:), allocatable :: lhs, name, value, where
        character :: quote
        integer :: j, k, p, n

        asg%group = grp%name
        asg%from_set = grp%from_set
        asg%body = group_body(lines, grp)
        allocate (asg%first(0), asg%eq(0))
        associate (body => asg%body)
            ! each '=' outside quoted strings, and where the variable name before it begins
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
            n = size(asg%eq)
            p = len(body) + 1
            if (n > 0) p = asg%first(1)
            if (verify(body(:p - 1), ' ,') /= 0) call fatal(EXIT_INPUT, origin(asg) // trim(grp%name), &
                "expected 'variable = value' in &" // trim(grp%name) // ", got '" // excerpt(body(:p - 1)) // &
                "'; allowed variables: " // var_list(vars))
        end associate
        do k = 1, n
            lhs = assignment_lhs(asg, k)
            name = identifier_at(lhs, 1)
            value = assignment_value(asg, k)
            where = origin(asg) // trim(grp%name) // '.' // lower(name)
            if (len(name) == 0) call fatal(EXIT_INPUT, origin(asg) // trim(grp%name), &
                "'=' without a variable name in &" // trim(grp%name) // ": '" // &
                excerpt(asg%body(asg%first(k):)) // "'; allowed variables: " // var_list(vars))
            if (var_kind(vars, name) == ' ') call fatal(EXIT_INPUT, where, "unknown variable '" // name // &
                "' in &" // trim(grp%name) // '; allowed: ' // var_list(vars))
            do p = 1, k - 1
                if (lower(squeeze(assignment_lhs(asg, p))) == lower(squeeze(lhs))) &
                    call fatal(EXIT_INPUT, where, "'" // lhs // "' given twice in &" // trim(grp%name))
            end do
            if (verify(value, ' ,') == 0) call fatal(EXIT_INPUT, where, "no value after '" // lhs // &
                " ='; must be " // kind_description(var_kind(vars, name)))
            ! gfortran silently skips an unquoted string value: only the reader can catch it
            if (var_kind(vars, name) == 's' .and. scan(value(1:1), '''"') == 0) call fatal(EXIT_INPUT, where, &
                'got ' // excerpt(value) // '; must be a quoted string, e.g. ' // name // ' = ' // quoted(excerpt(value)))
        end do
    end subroutine split_group

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

    !> After the namelist read of piece(asg, k): on failure, stop naming the variable, the
    !> value given, what is allowed, and gfortran's message.
    subroutine check_read(ios, msg, asg, vars, k)
        integer, intent(in) :: ios
        character(len=*), intent(in) :: msg
        type(assignments_t), intent(in) :: asg
        character(len=*), intent(in) :: vars
        integer, intent(in) :: k
        character(len=:), allocatable :: lhs, name, value

        if (ios == 0) return
        if (k > size(asg%eq)) call fatal(EXIT_INPUT, origin(asg) // trim(asg%group), &
                                         'cannot read &' // trim(asg%group) // ': ' // trim(msg))
        lhs = assignment_lhs(asg, k)
        name = identifier_at(lhs, 1)
        value = assignment_value(asg, k)
        if (len(lhs) > len(name)) value = lhs // ' = ' // value   ! subscripted: show the whole assignment
        call fatal(EXIT_INPUT, origin(asg) // trim(asg%group) // '.' // lower(name), &
                   'got ' // quoted(excerpt(value)) // '; must be ' // kind_description(var_kind(vars, name)) // &
                   ' (namelist read: ' // trim(msg) // ')')
    end subroutine check_read

    ! ---------------------------------------------------------------- one reader per group

    subroutine read_model(lines, grp, m)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(model_t), intent(inout) :: m
        real(dp) :: rho, alpha, varpi, gamma1, gamma2, c, d, r, hbar, tau0, tau
        namelist /model/ rho, alpha, varpi, gamma1, gamma2, c, d, r, hbar, tau0, tau
        type(assignments_t) :: asg
        character(len=:), allocatable :: text
        character(len=LEN_MSG) :: msg
        integer :: k, ios

        rho = m%rho; alpha = m%alpha; varpi = m%varpi; gamma1 = m%gamma1; gamma2 = m%gamma2
        c = m%c; d = m%d; r = m%r; hbar = m%hbar; tau0 = m%tau0; tau = m%tau
        call split_group(lines, grp, VARS_MODEL, asg)
        do k = 1, size(asg%eq) + 1
            text = piece(asg, k)
            read (text, nml=model, iostat=ios, iomsg=msg)
            call check_read(ios, msg, asg, VARS_MODEL, k)
        end do
        m = model_t(rho=rho, alpha=alpha, varpi=varpi, gamma1=gamma1, gamma2=gamma2, c=c, d=d, r=r, &
                    hbar=hbar, tau0=tau0, tau=tau)
    end subroutine read_model

    subroutine read_contact(lines, grp, cont)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(contact_t), intent(inout) :: cont
        real(dp) :: g, eps
        character(len=LEN_NAME) :: law
        namelist /contact/ g, eps, law
        type(assignments_t) :: asg
        character(len=:), allocatable :: text
        character(len=LEN_MSG) :: msg
        integer :: k, ios

        g = cont%g; eps = cont%eps; law = cont%law
        call split_group(lines, grp, VARS_CONTACT, asg)
        do k = 1, size(asg%eq) + 1
            text = piece(asg, k)
            read (text, nml=contact, iostat=ios, iomsg=msg)
            call check_read(ios, msg, asg, VARS_CONTACT, k)
        end do
        cont = contact_t(g=g, eps=eps, law=keyword(law))
    end subroutine read_contact

    subroutine read_mesh(lines, grp, msh)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(mesh_t), intent(inout) :: msh
        integer :: n_elements
        namelist /mesh/ n_elements
        type(assignments_t) :: asg
        character(len=:), allocatable :: text
        character(len=LEN_MSG) :: msg
        integer :: k, ios

        n_elements = msh%n_elements
        call split_group(lines, grp, VARS_MESH, asg)
        do k = 1, size(asg%eq) + 1
            text = piece(asg, k)
            read (text, nml=mesh, iostat=ios, iomsg=msg)
            call check_read(ios, msg, asg, VARS_MESH, k)
        end do
        msh = mesh_t(n_elements=n_elements)
    end subroutine read_mesh

    subroutine read_time(lines, grp, tm)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(time_t), intent(inout) :: tm
        real(dp) :: dt, t_end
        character(len=LEN_NAME) :: scheme
        character(len=LEN_PATH) :: restart_from
        namelist /time/ dt, t_end, scheme, restart_from
        type(assignments_t) :: asg
        character(len=:), allocatable :: text
        character(len=LEN_MSG) :: msg
        integer :: k, ios

        dt = tm%dt; t_end = tm%t_end; scheme = tm%scheme; restart_from = tm%restart_from
        call split_group(lines, grp, VARS_TIME, asg)
        do k = 1, size(asg%eq) + 1
            text = piece(asg, k)
            read (text, nml=time, iostat=ios, iomsg=msg)
            call check_read(ios, msg, asg, VARS_TIME, k)
        end do
        tm = time_t(dt=dt, t_end=t_end, scheme=keyword(scheme), restart_from=restart_from)
    end subroutine read_time

    subroutine read_initial(lines, grp, init)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(initial_t), intent(inout) :: init
        real(dp), dimension(0:MAX_POLY_DEGREE) :: u0_poly, u1_poly, theta0_poly, p0_poly, q0_poly, eta0_poly
        real(dp) :: theta0_step(2), p0_step(2)
        namelist /initial/ u0_poly, u1_poly, theta0_poly, p0_poly, q0_poly, eta0_poly, theta0_step, p0_step
        type(assignments_t) :: asg
        character(len=:), allocatable :: text
        character(len=LEN_MSG) :: msg
        integer :: k, ios

        u0_poly = init%u0_poly; u1_poly = init%u1_poly; theta0_poly = init%theta0_poly
        p0_poly = init%p0_poly; q0_poly = init%q0_poly; eta0_poly = init%eta0_poly
        theta0_step = init%theta0_step; p0_step = init%p0_step
        call split_group(lines, grp, VARS_INITIAL, asg)
        do k = 1, size(asg%eq) + 1
            text = piece(asg, k)
            read (text, nml=initial, iostat=ios, iomsg=msg)
            call check_read(ios, msg, asg, VARS_INITIAL, k)
        end do
        init = initial_t(u0_poly=u0_poly, u1_poly=u1_poly, theta0_poly=theta0_poly, p0_poly=p0_poly, &
                         q0_poly=q0_poly, eta0_poly=eta0_poly, theta0_step=theta0_step, p0_step=p0_step)
    end subroutine read_initial

    subroutine read_solver(lines, grp, solv)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(solver_t), intent(inout) :: solv
        character(len=LEN_NAME) :: method
        real(dp) :: tol
        integer :: max_iter
        namelist /solver/ method, tol, max_iter
        type(assignments_t) :: asg
        character(len=:), allocatable :: text
        character(len=LEN_MSG) :: msg
        integer :: k, ios

        method = solv%method; tol = solv%tol; max_iter = solv%max_iter
        call split_group(lines, grp, VARS_SOLVER, asg)
        do k = 1, size(asg%eq) + 1
            text = piece(asg, k)
            read (text, nml=solver, iostat=ios, iomsg=msg)
            call check_read(ios, msg, asg, VARS_SOLVER, k)
        end do
        solv = solver_t(method=keyword(method), tol=tol, max_iter=max_iter)
    end subroutine read_solver

    subroutine read_output(lines, grp, outp)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(output_t), intent(inout) :: outp
        character(len=LEN_PATH) :: prefix
        integer :: snapshot_every, series_every, checkpoint_every
        logical :: quiet
        namelist /output/ prefix, snapshot_every, series_every, checkpoint_every, quiet
        type(assignments_t) :: asg
        character(len=:), allocatable :: text
        character(len=LEN_MSG) :: msg
        integer :: k, ios

        prefix = outp%prefix; snapshot_every = outp%snapshot_every; series_every = outp%series_every
        checkpoint_every = outp%checkpoint_every; quiet = outp%quiet
        call split_group(lines, grp, VARS_OUTPUT, asg)
        do k = 1, size(asg%eq) + 1
            text = piece(asg, k)
            read (text, nml=output, iostat=ios, iomsg=msg)
            call check_read(ios, msg, asg, VARS_OUTPUT, k)
        end do
        outp = output_t(prefix=prefix, snapshot_every=snapshot_every, series_every=series_every, &
                        checkpoint_every=checkpoint_every, quiet=quiet)
    end subroutine read_output

    subroutine read_material(lines, grp, mat)
        type(string_t), intent(in) :: lines(:)
        type(group_t), intent(in) :: grp
        type(material_t), intent(inout) :: mat
        real(dp) :: T0, rho0, cE, kappa, lambda, mu, alpha_t, alpha_c, D, nu, varrho, ell, tau0, tau, &
                    lambda_v, mu_v
        namelist /material/ T0, rho0, cE, kappa, lambda, mu, alpha_t, alpha_c, D, nu, varrho, ell, tau0, tau, &
                            lambda_v, mu_v
        type(assignments_t) :: asg
        character(len=:), allocatable :: text
        character(len=LEN_MSG) :: msg
        integer :: k, ios

        T0 = mat%T0; rho0 = mat%rho0; cE = mat%cE; kappa = mat%kappa; lambda = mat%lambda; mu = mat%mu
        alpha_t = mat%alpha_t; alpha_c = mat%alpha_c; D = mat%D; nu = mat%nu; varrho = mat%varrho
        ell = mat%ell; tau0 = mat%tau0; tau = mat%tau; lambda_v = mat%lambda_v; mu_v = mat%mu_v
        call split_group(lines, grp, VARS_MATERIAL, asg)
        do k = 1, size(asg%eq) + 1
            text = piece(asg, k)
            read (text, nml=material, iostat=ios, iomsg=msg)
            call check_read(ios, msg, asg, VARS_MATERIAL, k)
        end do
        mat = material_t(present=.true., T0=T0, rho0=rho0, cE=cE, kappa=kappa, lambda=lambda, mu=mu, &
                         alpha_t=alpha_t, alpha_c=alpha_c, D=D, nu=nu, varrho=varrho, ell=ell, tau0=tau0, &
                         tau=tau, lambda_v=lambda_v, mu_v=mu_v)
    end subroutine read_material

    ! ---------------------------------------------------------------- &material

    !> &material must be such that (2.10)-(2.11) can be evaluated: checked here, since the
    !> reader computes &model from it (validate_m then checks the &model values).
    subroutine check_material(mat)
        type(material_t), intent(in) :: mat
        character(len=*), parameter :: names(16) = [character(len=8) :: 'T0', 'rho0', 'cE', 'kappa', &
            'mu', 'alpha_t', 'alpha_c', 'D', 'varrho', 'ell', 'nu', 'tau0', 'tau', 'lambda_v', 'mu_v', 'lambda']
        !  > 0 for the first 10, >= 0 for the next 5, any finite value for lambda
        real(dp) :: values(16)
        integer :: k

        values = [mat%T0, mat%rho0, mat%cE, mat%kappa, mat%mu, mat%alpha_t, mat%alpha_c, mat%D, mat%varrho, &
                  mat%ell, mat%nu, mat%tau0, mat%tau, mat%lambda_v, mat%mu_v, mat%lambda]
        do k = 1, size(values)
            associate (x => values(k), where => 'material.' // trim(names(k)))
                if (.not. ieee_is_finite(x)) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be a finite real number')
                if (k <= 10 .and. .not. x > 0.0_dp) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be > 0')
                if (k > 10 .and. k <= 15 .and. .not. x >= 0.0_dp) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be >= 0')
            end associate
        end do
        if (.not. 3.0_dp * mat%lambda + 2.0_dp * mat%mu > 0.0_dp) call fatal(EXIT_INPUT, 'material.lambda', &
            'got ' // format_real(mat%lambda) // ' with mu = ' // format_real(mat%mu) // &
            '; 3 lambda + 2 mu must be > 0 (beta1, beta2 of (2.2))')
    end subroutine check_material

    !> Echo the physical values and the nondimensional ones computed from them (stdout).
    subroutine echo_material(mat, nd, m)
        type(material_t), intent(in) :: mat
        type(nondim_t), intent(in) :: nd
        type(model_t), intent(in) :: m

        write (output_unit, '(a)') 'rodcontact: &material (SI units) -> &model by (2.10)-(2.11)'
        write (output_unit, '(2x, a)') 'physical'
        call echo_row('T0', mat%T0, 'K')
        call echo_row('rho0', mat%rho0, 'kg/m^3')
        call echo_row('cE', mat%cE, 'J/(kg K)')
        call echo_row('kappa', mat%kappa, 'W/(m K)')
        call echo_row('lambda', mat%lambda, 'kg/(m s^2)')
        call echo_row('mu', mat%mu, 'kg/(m s^2)')
        call echo_row('alpha_t', mat%alpha_t, '1/K')
        call echo_row('alpha_c', mat%alpha_c, 'm^3/kg')
        call echo_row('D', mat%D, 'kg s/m^3')
        call echo_row('nu', mat%nu, 'm^2/(s^2 K)')
        call echo_row('varrho', mat%varrho, 'm^5/(kg s^2)')
        call echo_row('ell', mat%ell, 'm')
        call echo_row('tau0', mat%tau0, 's')
        call echo_row('tau', mat%tau, 's')
        call echo_row('lambda_v', mat%lambda_v, "kg/(m s)  (lambda')")
        call echo_row('mu_v', mat%mu_v, "kg/(m s)  (mu')")
        write (output_unit, '(2x, a)') 'derived (2.10)'
        call echo_row('beta1', nd%beta1, 'kg/(m s^2 K)')
        call echo_row('beta2', nd%beta2, 'm^2/s^2')
        call echo_row('omega', nd%omega, 's  (t = omega t*)')
        call echo_row('delta', nd%delta, '')
        call echo_row('varsigma', nd%varsigma, '')
        call echo_row('zeta', nd%zeta, '')
        call echo_row('a_check', nd%a_check, '')
        call echo_row('alpha1', nd%alpha1, '')
        call echo_row('alpha2', nd%alpha2, '')
        call echo_row('alpha3', nd%alpha3, '')
        write (output_unit, '(2x, a)') '&model (2.11)'
        call echo_row('rho', m%rho, '')
        call echo_row('alpha', m%alpha, '')
        call echo_row('varpi', m%varpi, '')
        call echo_row('gamma1', m%gamma1, '')
        call echo_row('gamma2', m%gamma2, '')
        call echo_row('c', m%c, '')
        call echo_row('d', m%d, '')
        call echo_row('r', m%r, '')
        call echo_row('hbar', m%hbar, '')
        call echo_row('tau0', m%tau0, '(tau0/omega)')
        call echo_row('tau', m%tau, '(tau/omega)')
        flush (output_unit)
    end subroutine echo_material

    subroutine echo_row(name, value, unit)
        character(len=*), intent(in) :: name, unit
        real(dp), intent(in) :: value
        character(len=120) :: row

        write (row, '(4x, a, t17, "= ", es13.6, 2x, a)') name, value, unit
        write (output_unit, '(a)') trim(row)
    end subroutine echo_row

    ! ---------------------------------------------------------------- small helpers

    !> The Fortran name (letters, digits, '_') starting at text(start:); '' if none.
    pure function identifier_at(text, start) result(name)
        character(len=*), intent(in) :: text
        integer, intent(in) :: start
        character(len=:), allocatable :: name
        integer :: j

        j = start
        do while (j <= len(text))
            if (.not. is_name_char(text(j:j))) exit
            j = j + 1
        end do
        name = text(start:j - 1)
    end function identifier_at

    elemental logical function is_name_char(ch)
        character, intent(in) :: ch

        is_name_char = verify(ch, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') == 0
    end function is_name_char

    pure function lower(text) result(low)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: low
        integer :: j

        low = text
        do j = 1, len(text)
            if (text(j:j) >= 'A' .and. text(j:j) <= 'Z') low(j:j) = achar(iachar(text(j:j)) + 32)
        end do
    end function lower

    !> A keyword value as the code compares it: lower case, left-adjusted.
    pure function keyword(text) result(word)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: word

        word = lower(adjustl(text))
    end function keyword

    !> text without blanks (to compare 'a (1)' with 'a(1)').
    pure function squeeze(text) result(packed)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: packed
        integer :: j

        packed = ''
        do j = 1, len(text)
            if (text(j:j) /= ' ') packed = packed // text(j:j)
        end do
    end function squeeze

    !> At most 60 characters of text, for messages.
    pure function excerpt(text) result(short)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: short

        short = trim(adjustl(text))
        if (len(short) > 60) short = short(:57) // '...'
    end function excerpt

    !> text in quotes, unless it is a quoted string already.
    pure function quoted(text) result(q)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: q

        if (scan(text(1:min(1, len(text))), '''"') == 1) then
            q = text
        else
            q = "'" // text // "'"
        end if
    end function quoted

    !> text as a namelist string in single quotes (an inner ' doubled).
    pure function quoted_string(text) result(q)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: q
        integer :: j

        q = "'"
        do j = 1, len(text)
            q = q // text(j:j)
            if (text(j:j) == "'") q = q // "'"
        end do
        q = q // "'"
    end function quoted_string

    !> The 'name:kind ...' table of group `group` (one of GROUP_NAMES).
    pure function group_vars(group) result(vars)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: vars

        select case (group)
        case ('model')
            vars = VARS_MODEL
        case ('contact')
            vars = VARS_CONTACT
        case ('mesh')
            vars = VARS_MESH
        case ('time')
            vars = VARS_TIME
        case ('initial')
            vars = VARS_INITIAL
        case ('solver')
            vars = VARS_SOLVER
        case ('output')
            vars = VARS_OUTPUT
        case default
            vars = VARS_MATERIAL
        end select
    end function group_vars

    pure function int_str(n) result(s)
        integer, intent(in) :: n
        character(len=:), allocatable :: s
        character(len=16) :: buf
        integer :: ios

        write (buf, '(i0)', iostat=ios) n
        s = trim(buf)
    end function int_str

    !> '&model, &contact, ...'
    pure function group_list() result(list)
        character(len=:), allocatable :: list
        integer :: k

        list = '&' // trim(GROUP_NAMES(1))
        do k = 2, size(GROUP_NAMES)
            list = list // ', &' // trim(GROUP_NAMES(k))
        end do
    end function group_list

    !> 'rho, alpha, ...' from a 'name:kind ...' table.
    pure function var_list(vars) result(list)
        character(len=*), intent(in) :: vars
        character(len=:), allocatable :: list
        integer :: j

        list = ''
        do j = 1, len(vars)
            if (vars(j:j) == ':') then
                list = list // ','
            else if (j == 1) then
                list = vars(j:j)
            else if (vars(j - 1:j - 1) /= ':') then
                list = list // vars(j:j)
            end if
        end do
        list = list(:len(list) - 1)
        ! 'rho, alpha': the blanks of the table follow each ','
    end function var_list

    !> The kind code of variable `name` (any case) in a 'name:kind ...' table; ' ' if unknown.
    pure function var_kind(vars, name) result(code)
        character(len=*), intent(in) :: vars, name
        character :: code
        integer :: j

        code = ' '
        j = index(' ' // lower(vars), ' ' // lower(trim(name)) // ':')
        if (j > 0) code = vars(j + len_trim(name) + 1:j + len_trim(name) + 1)
    end function var_kind

    pure function kind_description(code) result(text)
        character, intent(in) :: code
        character(len=:), allocatable :: text

        select case (code)
        case ('r')
            text = 'a real number'
        case ('i')
            text = 'an integer'
        case ('s')
            text = "a quoted string, e.g. 'value'"
        case ('l')
            text = '.true. or .false.'
        case ('a')
            text = 'at most ' // int_str(MAX_POLY_DEGREE + 1) // ' real coefficients c0, c1, ... (of x**0, x**1, ...)'
        case ('2')
            text = 'two real numbers: amplitude, x_end'
        case default
            text = 'a valid value'
        end select
    end function kind_description

end module config_m
