!> The input variables of docs/input.md as one table, INPUT_VARS (group, name, kind, unit),
!> and the one routine that knows which component of config_t holds each of them. The
!> table drives the reader's checks and messages (known names, kinds, 'allowed: ...'), the
!> namelist read of each assignment, the echo of &material, and the record of the inputs in
!> the output file (input_items).
!>
!> What Fortran does not let a table do: a namelist group is a static list of declared
!> variables, so `access` declares each input variable once more as a local of its name,
!> lists it in its group's namelist statement and links it to its component of config_t
!> (one line each). A new input variable is therefore a component of its type in config_m,
!> an entry of INPUT_VARS, and three mentions in `access`; everything else follows.
module input_vars_m
    use kinds_m, only: dp
    use config_m, only: config_t, MAX_POLY_DEGREE, LEN_NAME, LEN_PATH
    use errors_m, only: fatal, EXIT_OUTPUT
    use strings_m, only: lower, keyword, int_str
    implicit none
    private
    public :: input_var_t, input_item_t, INPUT_VARS, GROUP_NAMES
    public :: KIND_REAL, KIND_INTEGER, KIND_STRING, KIND_LOGICAL, KIND_COEFFS, KIND_PAIR
    public :: find_input, var_kind, input_item, input_items, read_namelist
    public :: group_list, var_list, kind_description, changes_history

    !> Kinds of input variables (codes as in the reader's messages).
    character, parameter :: KIND_REAL = 'r'      !< a real number
    character, parameter :: KIND_INTEGER = 'i'   !< an integer
    character, parameter :: KIND_STRING = 's'    !< a quoted string
    character, parameter :: KIND_LOGICAL = 'l'   !< .true. or .false.
    character, parameter :: KIND_COEFFS = 'a'    !< up to MAX_POLY_DEGREE+1 polynomial coefficients
    character, parameter :: KIND_PAIR = '2'      !< two reals (amplitude, x_end)

    !> One input variable: &group name = value.
    type :: input_var_t
        character(len=8) :: group = ''
        character(len=16) :: name = ''      !< as the messages spell it (any case in the input)
        character :: kind = KIND_REAL
        logical :: keyword = .false.        !< a keyword: stored in lower case, left-adjusted
        character(len=24) :: unit = ''      !< unit (&material) or note (&model) in the echo
    end type input_var_t

    !> Namelist groups of docs/input.md, in the order validation checks them.
    character(len=*), parameter :: GROUP_NAMES(8) = [character(len=8) :: &
        'model', 'contact', 'mesh', 'time', 'initial', 'solver', 'output', 'material']

    !> Every input variable, by group in the order of GROUP_NAMES; within a group in the
    !> order of the messages, the echo and the file.
    type(input_var_t), parameter :: INPUT_VARS(*) = [ &
        input_var_t('model', 'rho', KIND_REAL, .false., ''), &
        input_var_t('model', 'alpha', KIND_REAL, .false., ''), &
        input_var_t('model', 'varpi', KIND_REAL, .false., ''), &
        input_var_t('model', 'gamma1', KIND_REAL, .false., ''), &
        input_var_t('model', 'gamma2', KIND_REAL, .false., ''), &
        input_var_t('model', 'c', KIND_REAL, .false., ''), &
        input_var_t('model', 'd', KIND_REAL, .false., ''), &
        input_var_t('model', 'r', KIND_REAL, .false., ''), &
        input_var_t('model', 'hbar', KIND_REAL, .false., ''), &
        input_var_t('model', 'tau0', KIND_REAL, .false., '(tau0/omega)'), &
        input_var_t('model', 'tau', KIND_REAL, .false., '(tau/omega)'), &
        input_var_t('contact', 'g', KIND_REAL, .false., ''), &
        input_var_t('contact', 'eps', KIND_REAL, .false., ''), &
        input_var_t('contact', 'law', KIND_STRING, .true., ''), &
        input_var_t('mesh', 'n_elements', KIND_INTEGER, .false., ''), &
        input_var_t('mesh', 'adaptive', KIND_LOGICAL, .false., ''), &
        input_var_t('mesh', 'error_tol', KIND_REAL, .false., ''), &
        input_var_t('mesh', 'max_level', KIND_INTEGER, .false., ''), &
        input_var_t('mesh', 'remesh_every', KIND_INTEGER, .false., ''), &
        input_var_t('time', 'dt', KIND_REAL, .false., ''), &
        input_var_t('time', 't_end', KIND_REAL, .false., ''), &
        input_var_t('time', 'scheme', KIND_STRING, .true., ''), &
        input_var_t('time', 'restart_from', KIND_STRING, .false., ''), &
        input_var_t('time', 'adaptive', KIND_LOGICAL, .false., ''), &
        input_var_t('time', 'error_tol', KIND_REAL, .false., ''), &
        input_var_t('time', 'dt_min', KIND_REAL, .false., ''), &
        input_var_t('time', 'dt_max', KIND_REAL, .false., ''), &
        input_var_t('initial', 'u0_poly', KIND_COEFFS, .false., ''), &
        input_var_t('initial', 'u1_poly', KIND_COEFFS, .false., ''), &
        input_var_t('initial', 'theta0_poly', KIND_COEFFS, .false., ''), &
        input_var_t('initial', 'p0_poly', KIND_COEFFS, .false., ''), &
        input_var_t('initial', 'q0_poly', KIND_COEFFS, .false., ''), &
        input_var_t('initial', 'eta0_poly', KIND_COEFFS, .false., ''), &
        input_var_t('initial', 'theta0_step', KIND_PAIR, .false., ''), &
        input_var_t('initial', 'p0_step', KIND_PAIR, .false., ''), &
        input_var_t('solver', 'method', KIND_STRING, .true., ''), &
        input_var_t('solver', 'tol', KIND_REAL, .false., ''), &
        input_var_t('solver', 'max_iter', KIND_INTEGER, .false., ''), &
        input_var_t('output', 'prefix', KIND_STRING, .false., ''), &
        input_var_t('output', 'snapshot_every', KIND_INTEGER, .false., ''), &
        input_var_t('output', 'snapshot_dt', KIND_REAL, .false., ''), &
        input_var_t('output', 'series_every', KIND_INTEGER, .false., ''), &
        input_var_t('output', 'checkpoint_every', KIND_INTEGER, .false., ''), &
        input_var_t('output', 'compression', KIND_INTEGER, .false., ''), &
        input_var_t('output', 'quiet', KIND_LOGICAL, .false., ''), &
        input_var_t('output', 'n_points', KIND_INTEGER, .false., ''), &
        input_var_t('material', 'T0', KIND_REAL, .false., 'K'), &
        input_var_t('material', 'rho0', KIND_REAL, .false., 'kg/m^3'), &
        input_var_t('material', 'cE', KIND_REAL, .false., 'J/(kg K)'), &
        input_var_t('material', 'kappa', KIND_REAL, .false., 'W/(m K)'), &
        input_var_t('material', 'lambda', KIND_REAL, .false., 'kg/(m s^2)'), &
        input_var_t('material', 'mu', KIND_REAL, .false., 'kg/(m s^2)'), &
        input_var_t('material', 'alpha_t', KIND_REAL, .false., '1/K'), &
        input_var_t('material', 'alpha_c', KIND_REAL, .false., 'm^3/kg'), &
        input_var_t('material', 'D', KIND_REAL, .false., 'kg s/m^3'), &
        input_var_t('material', 'nu', KIND_REAL, .false., 'm^2/(s^2 K)'), &
        input_var_t('material', 'varrho', KIND_REAL, .false., 'm^5/(kg s^2)'), &
        input_var_t('material', 'ell', KIND_REAL, .false., 'm'), &
        input_var_t('material', 'tau0', KIND_REAL, .false., 's'), &
        input_var_t('material', 'tau', KIND_REAL, .false., 's'), &
        input_var_t('material', 'lambda_v', KIND_REAL, .false., "kg/(m s)  (lambda')"), &
        input_var_t('material', 'mu_v', KIND_REAL, .false., "kg/(m s)  (mu')")]

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

    !> What access does: copy a variable into an item, or read a namelist text of its group.
    integer, parameter :: GET_ITEM = 1, READ_TEXT = 2
    !> What link does with one variable: copy it into an item, into the namelist's local of
    !> its name, or from that local back into config_t.
    integer, parameter :: TO_ITEM = 1, TO_LOCAL = 2, FROM_LOCAL = 3

contains

    !> Index in INPUT_VARS of variable `name` (any case) of `group`; 0 if there is none.
    pure integer function find_input(group, name)
        character(len=*), intent(in) :: group, name
        integer :: k

        find_input = 0
        do k = 1, size(INPUT_VARS)
            if (INPUT_VARS(k)%group == group .and. lower(INPUT_VARS(k)%name) == lower(name)) find_input = k
        end do
    end function find_input

    !> Whether input variable `var` changes the computed history, so that a restart must
    !> keep it (docs/input.md): every variable of the physics, contact, mesh, initial data,
    !> solver and time-stepping groups, except the end time and the restart file itself.
    !> &output (where and how often the history is written) may change.
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
            changes_history = var%name == 'snapshot_dt' .or. var%name == 'n_points'
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
        k = find_input(group, name)
        if (k > 0) kind = INPUT_VARS(k)%kind
    end function var_kind

    !> The value of input variable INPUT_VARS(k) in cfg.
    function input_item(cfg, k) result(item)
        type(config_t), intent(in) :: cfg
        integer, intent(in) :: k
        type(input_item_t) :: item
        type(config_t) :: copy   ! access links components both ways; cfg stays intent(in)

        copy = cfg
        call access(copy, k, GET_ITEM, item)
    end function input_item

    !> Everything the output file records of the input: every input variable (those of
    !> &material only when the group was given; the &model values are then the ones
    !> computed from them), then 'input.source' and 'input.overrides'.
    function input_items(cfg) result(items)
        type(config_t), intent(in) :: cfg
        type(input_item_t), allocatable :: items(:)
        character(len=512) :: msg
        integer :: k, n, stat
        logical :: recorded(size(INPUT_VARS))

        recorded = INPUT_VARS%group /= 'material' .or. cfg%material%present
        allocate (items(count(recorded) + 2), stat=stat, errmsg=msg)
        if (stat /= 0) call fatal(EXIT_OUTPUT, 'input record', 'out of memory: ' // trim(msg))
        n = 0
        do k = 1, size(INPUT_VARS)
            if (.not. recorded(k)) cycle
            n = n + 1
            items(n) = input_item(cfg, k)
        end do
        items(n + 1) = string_item('input.source', trim(cfg%source))
        items(n + 2) = string_item('input.overrides', trim(cfg%overrides))
    end function input_items

    !> An item of kind KIND_STRING.
    function string_item(name, text) result(item)
        character(len=*), intent(in) :: name, text
        type(input_item_t) :: item

        item%name = name
        item%kind = KIND_STRING
        item%text = text
    end function string_item

    !> Read the namelist `text` ('&group ... /', assignments of variables of `group`) over
    !> the values of the group in cfg; ios and msg as from the namelist read.
    subroutine read_namelist(cfg, group, text, ios, msg)
        type(config_t), intent(inout) :: cfg
        character(len=*), intent(in) :: group, text
        integer, intent(out) :: ios
        character(len=*), intent(out) :: msg
        integer :: k

        k = findloc(INPUT_VARS%group, group, dim=1)
        call access(cfg, k, READ_TEXT, text=text, ios=ios, msg=msg)
    end subroutine read_namelist

    !> With `action` GET_ITEM: item = the value of INPUT_VARS(k) in cfg. With READ_TEXT: the
    !> namelist read of `text` in the group of INPUT_VARS(k), from and back to cfg.
    subroutine access(cfg, k, action, item, text, ios, msg)
        type(config_t), intent(inout) :: cfg
        integer, intent(in) :: k, action
        type(input_item_t), intent(out), optional :: item
        character(len=*), intent(in), optional :: text
        integer, intent(out), optional :: ios
        character(len=*), intent(out), optional :: msg
        ! The namelist objects: one local per input variable, named as in the input. &model
        ! and &material share d (D), tau0 and tau; only one group is read at a time.
        real(dp) :: rho, alpha, varpi, gamma1, gamma2, c, d, r, hbar, tau0, tau
        real(dp) :: g, eps, dt, t_end, tol, error_tol, dt_min, dt_max, snapshot_dt
        real(dp), dimension(0:MAX_POLY_DEGREE) :: u0_poly, u1_poly, theta0_poly, p0_poly, q0_poly, eta0_poly
        real(dp) :: theta0_step(2), p0_step(2)
        real(dp) :: T0, rho0, cE, kappa, lambda, mu, alpha_t, alpha_c, nu, varrho, ell, lambda_v, mu_v
        integer :: n_elements, max_iter, snapshot_every, series_every, checkpoint_every, compression, max_level, &
                   remesh_every, n_points
        character(len=LEN_NAME) :: law, scheme, method
        character(len=LEN_PATH) :: restart_from, prefix
        logical :: quiet, adaptive
        namelist /model/ rho, alpha, varpi, gamma1, gamma2, c, d, r, hbar, tau0, tau
        namelist /contact/ g, eps, law
        namelist /mesh/ n_elements, adaptive, error_tol, max_level, remesh_every
        namelist /time/ dt, t_end, scheme, restart_from, adaptive, error_tol, dt_min, dt_max
        namelist /initial/ u0_poly, u1_poly, theta0_poly, p0_poly, q0_poly, eta0_poly, theta0_step, p0_step
        namelist /solver/ method, tol, max_iter
        namelist /output/ prefix, snapshot_every, snapshot_dt, series_every, checkpoint_every, compression, quiet, &
                          n_points
        namelist /material/ T0, rho0, cE, kappa, lambda, mu, alpha_t, alpha_c, D, nu, varrho, ell, tau0, tau, &
                            lambda_v, mu_v
        type(input_item_t) :: work
        integer :: j

        if (action == GET_ITEM) then
            call visit(k, TO_ITEM, item)
            return
        end if
        associate (group => INPUT_VARS(k)%group)
            do j = 1, size(INPUT_VARS)
                if (INPUT_VARS(j)%group == group) call visit(j, TO_LOCAL, work)
            end do
            select case (group)
            case ('model'); read (text, nml=model, iostat=ios, iomsg=msg)
            case ('contact'); read (text, nml=contact, iostat=ios, iomsg=msg)
            case ('mesh'); read (text, nml=mesh, iostat=ios, iomsg=msg)
            case ('time'); read (text, nml=time, iostat=ios, iomsg=msg)
            case ('initial'); read (text, nml=initial, iostat=ios, iomsg=msg)
            case ('solver'); read (text, nml=solver, iostat=ios, iomsg=msg)
            case ('output'); read (text, nml=output, iostat=ios, iomsg=msg)
            case ('material'); read (text, nml=material, iostat=ios, iomsg=msg)
            end select
            if (ios /= 0) return
            do j = 1, size(INPUT_VARS)
                if (INPUT_VARS(j)%group == group) call visit(j, FROM_LOCAL, work)
            end do
        end associate

    contains

        !> The one line per input variable that names its component of config_t.
        subroutine visit(j, act, it)
            integer, intent(in) :: j, act
            type(input_item_t), intent(out) :: it

            it%name = trim(INPUT_VARS(j)%group) // '.' // trim(INPUT_VARS(j)%name)
            it%kind = INPUT_VARS(j)%kind
            it%keyword = INPUT_VARS(j)%keyword
            select case (it%name)
            case ('model.rho'); call link(it, act, r=cfg%model%rho, r_local=rho)
            case ('model.alpha'); call link(it, act, r=cfg%model%alpha, r_local=alpha)
            case ('model.varpi'); call link(it, act, r=cfg%model%varpi, r_local=varpi)
            case ('model.gamma1'); call link(it, act, r=cfg%model%gamma1, r_local=gamma1)
            case ('model.gamma2'); call link(it, act, r=cfg%model%gamma2, r_local=gamma2)
            case ('model.c'); call link(it, act, r=cfg%model%c, r_local=c)
            case ('model.d'); call link(it, act, r=cfg%model%d, r_local=d)
            case ('model.r'); call link(it, act, r=cfg%model%r, r_local=r)
            case ('model.hbar'); call link(it, act, r=cfg%model%hbar, r_local=hbar)
            case ('model.tau0'); call link(it, act, r=cfg%model%tau0, r_local=tau0)
            case ('model.tau'); call link(it, act, r=cfg%model%tau, r_local=tau)
            case ('contact.g'); call link(it, act, r=cfg%contact%g, r_local=g)
            case ('contact.eps'); call link(it, act, r=cfg%contact%eps, r_local=eps)
            case ('contact.law'); call link(it, act, s=cfg%contact%law, s_local=law)
            case ('mesh.n_elements'); call link(it, act, i=cfg%mesh%n_elements, i_local=n_elements)
            case ('mesh.adaptive'); call link(it, act, l=cfg%mesh%adaptive, l_local=adaptive)
            case ('mesh.error_tol'); call link(it, act, r=cfg%mesh%error_tol, r_local=error_tol)
            case ('mesh.max_level'); call link(it, act, i=cfg%mesh%max_level, i_local=max_level)
            case ('mesh.remesh_every'); call link(it, act, i=cfg%mesh%remesh_every, i_local=remesh_every)
            case ('time.dt'); call link(it, act, r=cfg%time%dt, r_local=dt)
            case ('time.t_end'); call link(it, act, r=cfg%time%t_end, r_local=t_end)
            case ('time.scheme'); call link(it, act, s=cfg%time%scheme, s_local=scheme)
            case ('time.restart_from'); call link(it, act, s=cfg%time%restart_from, s_local=restart_from)
            case ('time.adaptive'); call link(it, act, l=cfg%time%adaptive, l_local=adaptive)
            case ('time.error_tol'); call link(it, act, r=cfg%time%error_tol, r_local=error_tol)
            case ('time.dt_min'); call link(it, act, r=cfg%time%dt_min, r_local=dt_min)
            case ('time.dt_max'); call link(it, act, r=cfg%time%dt_max, r_local=dt_max)
            case ('initial.u0_poly'); call link(it, act, a=cfg%initial%u0_poly, a_local=u0_poly)
            case ('initial.u1_poly'); call link(it, act, a=cfg%initial%u1_poly, a_local=u1_poly)
            case ('initial.theta0_poly'); call link(it, act, a=cfg%initial%theta0_poly, a_local=theta0_poly)
            case ('initial.p0_poly'); call link(it, act, a=cfg%initial%p0_poly, a_local=p0_poly)
            case ('initial.q0_poly'); call link(it, act, a=cfg%initial%q0_poly, a_local=q0_poly)
            case ('initial.eta0_poly'); call link(it, act, a=cfg%initial%eta0_poly, a_local=eta0_poly)
            case ('initial.theta0_step'); call link(it, act, a=cfg%initial%theta0_step, a_local=theta0_step)
            case ('initial.p0_step'); call link(it, act, a=cfg%initial%p0_step, a_local=p0_step)
            case ('solver.method'); call link(it, act, s=cfg%solver%method, s_local=method)
            case ('solver.tol'); call link(it, act, r=cfg%solver%tol, r_local=tol)
            case ('solver.max_iter'); call link(it, act, i=cfg%solver%max_iter, i_local=max_iter)
            case ('output.prefix'); call link(it, act, s=cfg%output%prefix, s_local=prefix)
            case ('output.snapshot_every'); call link(it, act, i=cfg%output%snapshot_every, i_local=snapshot_every)
            case ('output.snapshot_dt'); call link(it, act, r=cfg%output%snapshot_dt, r_local=snapshot_dt)
            case ('output.series_every'); call link(it, act, i=cfg%output%series_every, i_local=series_every)
            case ('output.checkpoint_every'); call link(it, act, i=cfg%output%checkpoint_every, i_local=checkpoint_every)
            case ('output.compression'); call link(it, act, i=cfg%output%compression, i_local=compression)
            case ('output.n_points'); call link(it, act, i=cfg%output%n_points, i_local=n_points)
            case ('output.quiet'); call link(it, act, l=cfg%output%quiet, l_local=quiet)
            case ('material.T0'); call link(it, act, r=cfg%material%T0, r_local=T0)
            case ('material.rho0'); call link(it, act, r=cfg%material%rho0, r_local=rho0)
            case ('material.cE'); call link(it, act, r=cfg%material%cE, r_local=cE)
            case ('material.kappa'); call link(it, act, r=cfg%material%kappa, r_local=kappa)
            case ('material.lambda'); call link(it, act, r=cfg%material%lambda, r_local=lambda)
            case ('material.mu'); call link(it, act, r=cfg%material%mu, r_local=mu)
            case ('material.alpha_t'); call link(it, act, r=cfg%material%alpha_t, r_local=alpha_t)
            case ('material.alpha_c'); call link(it, act, r=cfg%material%alpha_c, r_local=alpha_c)
            case ('material.D'); call link(it, act, r=cfg%material%D, r_local=d)
            case ('material.nu'); call link(it, act, r=cfg%material%nu, r_local=nu)
            case ('material.varrho'); call link(it, act, r=cfg%material%varrho, r_local=varrho)
            case ('material.ell'); call link(it, act, r=cfg%material%ell, r_local=ell)
            case ('material.tau0'); call link(it, act, r=cfg%material%tau0, r_local=tau0)
            case ('material.tau'); call link(it, act, r=cfg%material%tau, r_local=tau)
            case ('material.lambda_v'); call link(it, act, r=cfg%material%lambda_v, r_local=lambda_v)
            case ('material.mu_v'); call link(it, act, r=cfg%material%mu_v, r_local=mu_v)
            case default
                error stop 'input_vars_m: an entry of INPUT_VARS has no component of config_t in access'
            end select
        end subroutine visit

    end subroutine access

    ! ------------------------------------------------ a component, its namelist local, an item

    !> With act TO_ITEM: item = the value of the component; TO_LOCAL: the namelist's local =
    !> the component; FROM_LOCAL: the component = the local (a keyword as the code compares
    !> it: lower case, left-adjusted). Exactly one pair of component and local is given: r
    !> (a real), a (real coefficients or a pair), i (an integer), s (a string), l (a logical).
    subroutine link(item, act, r, r_local, a, a_local, i, i_local, s, s_local, l, l_local)
        type(input_item_t), intent(inout) :: item
        integer, intent(in) :: act
        real(dp), intent(inout), optional :: r, r_local, a(:), a_local(:)
        integer, intent(inout), optional :: i, i_local
        character(len=*), intent(inout), optional :: s, s_local
        logical, intent(inout), optional :: l, l_local
        character :: kind

        kind = merge(KIND_REAL, ' ', present(r))
        if (present(a)) kind = merge(KIND_PAIR, KIND_COEFFS, size(a) == 2)
        if (present(i)) kind = KIND_INTEGER
        if (present(s)) kind = KIND_STRING
        if (present(l)) kind = KIND_LOGICAL
        call require_kind(item, kind)
        if (act == TO_ITEM) then
            if (present(r)) item%reals = [r]
            if (present(a)) item%reals = a
            if (present(i)) item%int = i
            if (present(s)) item%text = trim(s)
            if (present(l)) item%flag = l
        else if (act == TO_LOCAL) then
            if (present(r)) r_local = r
            if (present(a)) a_local = a
            if (present(i)) i_local = i
            if (present(s)) s_local = s
            if (present(l)) l_local = l
        else
            if (present(r)) r = r_local
            if (present(a)) a = a_local
            if (present(i)) i = i_local
            if (present(s)) s = merge(keyword(s_local), s_local, item%keyword)
            if (present(l)) l = l_local
        end if
    end subroutine link

    !> INPUT_VARS and access must agree on the kind of each variable (a programming error).
    subroutine require_kind(item, kind)
        type(input_item_t), intent(in) :: item
        character, intent(in) :: kind

        if (item%kind /= kind) error stop 'input_vars_m: INPUT_VARS and access disagree on a kind'
    end subroutine require_kind

    ! ------------------------------------------------ lists and words for messages

    !> '&model, &contact, ...'
    pure function group_list() result(list)
        character(len=:), allocatable :: list

        list = joined(GROUP_NAMES, '&')
    end function group_list

    !> 'rho, alpha, ...': the variables of `group`.
    pure function var_list(group) result(list)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: list

        list = joined(pack(INPUT_VARS%name, INPUT_VARS%group == group), '')
    end function var_list

    !> The words, each after `mark`, separated by ', '.
    pure function joined(words, mark) result(list)
        character(len=*), intent(in) :: words(:), mark
        character(len=:), allocatable :: list
        integer :: k

        list = mark // trim(words(1))
        do k = 2, size(words)
            list = list // ', ' // mark // trim(words(k))
        end do
    end function joined

    !> What a value of kind `kind` must be, for messages.
    pure function kind_description(kind) result(text)
        character, intent(in) :: kind
        character(len=:), allocatable :: text

        select case (kind)
        case (KIND_REAL)
            text = 'a real number'
        case (KIND_INTEGER)
            text = 'an integer'
        case (KIND_STRING)
            text = "a quoted string, e.g. 'value'"
        case (KIND_LOGICAL)
            text = '.true. or .false.'
        case (KIND_COEFFS)
            text = 'at most ' // int_str(MAX_POLY_DEGREE + 1) // ' real coefficients c0, c1, ... (of x**0, x**1, ...)'
        case (KIND_PAIR)
            text = 'two real numbers: amplitude, x_end'
        case default
            text = 'a valid value'
        end select
    end function kind_description

end module input_vars_m
