!> Input validation (the ranges and combinations of docs/input.md), run before any
!> allocation or output: the checks go through the groups in the order model, contact,
!> mesh, time, initial, solver, output, and the first failure stops with EXIT_INPUT, naming
!> group.variable, the value given and what is allowed.
module validate_m
    use, intrinsic :: iso_fortran_env, only: error_unit
    use kinds_m, only: dp
    use fields_m, only: N_FIELDS, N_SNAPSHOT_FIELDS, N_SERIES
    use errors_m, only: fatal, EXIT_INPUT
    use config_m, only: config_t, model_t, contact_t, mesh_t, time_t, solver_t, output_t, &
                        number_of_steps, MAX_COMPRESSION, LEN_NAME
    use strings_m, only: format_real, int_str
    use validate_initial_m, only: validate_initial, require_real, NONNEGATIVE, POSITIVE, DIVISOR
    use contact_laws_m, only: law_names, constraint_law
    use material_m, only: model_from_material
    use input_vars_m, only: joined
    implicit none
    private
    public :: validate_config, scheme_rule_t

    !> What validation needs of one time scheme. The schemes are time_scheme_m's (a later
    !> layer): its scheme_rules() is passed to validate_config.
    type :: scheme_rule_t
        character(len=LEN_NAME) :: name = ''       !< a value of &time scheme
        logical :: paper_iteration = .false.       !< solver.method = 'paper' runs this scheme
    end type scheme_rule_t

    real(dp), parameter :: GIB = 1024.0_dp**3
    !> Working memory per mesh node: ~60 reals of field and work arrays plus the band
    !> storage of the monolithic matrix, 2 kl + ku + 1 rows for N_FIELDS interleaved fields
    !> with kl = ku = N_FIELDS + 2 (scheme_m's field order).
    real(dp), parameter :: REALS_PER_NODE = 60.0_dp + real((3 * (N_FIELDS + 2) + 1) * N_FIELDS, dp)
    real(dp), parameter :: MEMORY_LIMIT = 8.0_dp * GIB        !< refuse meshes needing more
    integer, parameter :: MAX_MESH_LEVEL = 30                  !< &mesh max_level
    real(dp), parameter :: MAX_FINE_ELEMENTS = 2.0_dp**30      !< n_elements 2^max_level (round-off of x_i)
    real(dp), parameter :: OUTPUT_WARN = 1.0_dp * GIB         !< warn above this output size
    real(dp), parameter :: OUTPUT_LIMIT = 64.0_dp * GIB       !< refuse output above this size

contains

    !> Apply every check to cfg, in the input's units (with &material SI, before
    !> material_m's nondimensionalise, whose &model is checked here); stop with EXIT_INPUT
    !> at the first failure. A large (but allowed) output size gives a warning on stderr.
    subroutine validate_config(cfg, schemes)
        type(config_t), intent(in) :: cfg
        type(scheme_rule_t), intent(in) :: schemes(:)

        associate (si => cfg%material%present)
            call validate_model(merge(model_from_material(cfg%material), cfg%model, si), si)
            call validate_contact(cfg%contact)
            call validate_mesh(cfg%mesh)
            call validate_time(cfg%time, schemes)
            call validate_initial(cfg%initial, cfg%contact%g, merge(cfg%material%ell, 1.0_dp, si))
        end associate
        call validate_solver(cfg%solver)
        call validate_combination(cfg, schemes)
        call validate_output(cfg%output, cfg%mesh%n_elements, cfg%time)
        call validate_error_estimate(cfg)
    end subroutine validate_config

    !> &output error_estimate: its companion solutions live on every other and every fourth
    !> node of a uniform mesh, or on the bisection of the coarse mesh halved and quartered
    !> (an adaptive mesh: n_elements its coarse elements).
    subroutine validate_error_estimate(cfg)
        type(config_t), intent(in) :: cfg

        if (.not. cfg%output%error_estimate) return
        if (mod(cfg%mesh%n_elements, 4) /= 0 .or. cfg%mesh%n_elements < 8) call fatal(EXIT_INPUT, &
            'output.error_estimate', 'got .true. with mesh.n_elements = ' // int_str(cfg%mesh%n_elements) // &
            '; the built-in estimate needs a multiple of 4 elements, at least 8 (its companion solutions ' // &
            'use every other and every fourth node; on an adaptive mesh, coarse meshes of n_elements / 2 ' // &
            'and n_elements / 4 elements)')
        if (cfg%output%snapshot_dt > 0.0_dp .and. .not. cfg%output%snapshot_land) call fatal(EXIT_INPUT, &
            'output.error_estimate', 'got .true. with output.snapshot_land = .false.; the built-in ' // &
            'estimate is that of the levels the steps reach: let the steps land on the snapshot times ' // &
            '(snapshot_land = .true.)')
    end subroutine validate_error_estimate

    ! ---------------------------------------------------------------- one check per group

    subroutine validate_model(m, from_material)
        type(model_t), intent(in) :: m
        logical, intent(in) :: from_material
        character(len=:), allocatable :: note

        note = ''
        if (from_material) note = ' (computed from &material by (2.10)-(2.11))'
        call require_real(m%rho, 'model.rho', DIVISOR, note)
        call require_real(m%alpha, 'model.alpha', DIVISOR, note)
        call require_real(m%varpi, 'model.varpi', NONNEGATIVE, note)
        call require_real(m%gamma1, 'model.gamma1', NONNEGATIVE, note)
        call require_real(m%gamma2, 'model.gamma2', NONNEGATIVE, note)
        call require_real(m%c, 'model.c', DIVISOR, note)
        call require_real(m%d, 'model.d', NONNEGATIVE, note)
        call require_real(m%r, 'model.r', DIVISOR, note)
        call require_real(m%hbar, 'model.hbar', DIVISOR, note)
        call require_real(m%tau0, 'model.tau0', NONNEGATIVE, note)
        call require_real(m%tau, 'model.tau', NONNEGATIVE, note)
        if (.not. m%c * m%r - m%d**2 > 0.0_dp) call fatal(EXIT_INPUT, 'model.d', 'got d = ' // &
            format_real(m%d) // ' with c = ' // format_real(m%c) // ', r = ' // format_real(m%r) // &
            ': c*r - d**2 = ' // &
            format_real(m%c * m%r - m%d**2) // '; condition (2.16) needs c*r - d**2 > 0' // note)
    end subroutine validate_model

    subroutine validate_contact(contact)
        type(contact_t), intent(in) :: contact

        call require_real(contact%g, 'contact.g', POSITIVE)
        call require_real(contact%eps, 'contact.eps', DIVISOR)
        call require_one_of(contact%law, law_names(), 'contact.law')
        call require_one_of(contact%mass, [character(len=13) :: 'consistent', 'redistributed'], 'contact.mass')
    end subroutine validate_contact

    subroutine validate_mesh(mesh)
        type(mesh_t), intent(in) :: mesh
        real(dp) :: bytes

        call require_at_least(mesh%n_elements, 2, 'mesh.n_elements')
        call require_real(mesh%error_tol, 'mesh.error_tol', POSITIVE, &
                          '(relative L2 error per unit length, e.g. 1e-3)')
        if (mesh%max_level < 0 .or. mesh%max_level > MAX_MESH_LEVEL) call fatal(EXIT_INPUT, 'mesh.max_level', &
            'got ' // int_str(mesh%max_level) // '; must be an integer from 0 (no refinement) to ' // &
            int_str(MAX_MESH_LEVEL) // ' (bisections of a coarse element)')
        call require_at_least(mesh%remesh_every, 1, 'mesh.remesh_every')
        if (mesh%adaptive .and. real(mesh%n_elements, dp) * 2.0_dp**mesh%max_level > MAX_FINE_ELEMENTS) &
            call fatal(EXIT_INPUT, 'mesh.max_level', 'got ' // int_str(mesh%max_level) // &
            ' with n_elements = ' // int_str(mesh%n_elements) // ': the finest elements would be 1/' // &
            int_str(int(min(real(mesh%n_elements, dp) * 2.0_dp**mesh%max_level, 2.0e9_dp))) // &
            ' long; n_elements * 2**max_level must be at most ' // int_str(int(MAX_FINE_ELEMENTS)))
        bytes = 8.0_dp * REALS_PER_NODE * (real(mesh%n_elements, dp) + 1.0_dp)
        if (bytes > MEMORY_LIMIT) call fatal(EXIT_INPUT, 'mesh.n_elements', &
            'got ' // int_str(mesh%n_elements) // &
            '; the arrays would need about ' // gib_str(bytes) // ' GiB, more than the ' // &
            gib_str(MEMORY_LIMIT) // ' GiB allowed; must be at most ' // &
            int_str(int(MEMORY_LIMIT / (8.0_dp * REALS_PER_NODE)) - 1))
    end subroutine validate_mesh

    subroutine validate_time(time, schemes)
        type(time_t), intent(in) :: time
        type(scheme_rule_t), intent(in) :: schemes(:)
        character(len=len(schemes%name)), allocatable :: names(:)

        call require_real(time%dt, 'time.dt', DIVISOR)
        call require_real(time%t_end, 'time.t_end', POSITIVE)
        if (time%t_end < time%dt) call fatal(EXIT_INPUT, 'time.t_end', 'got ' // format_real(time%t_end) // &
            ' < dt = ' // format_real(time%dt) // '; must be >= dt (at least one time step)')
        ! the step counter is a default integer
        if (time%t_end / time%dt > real(huge(0), dp) - 1.0_dp) call fatal(EXIT_INPUT, 'time.dt', 'got ' // &
            format_real(time%dt) // ' with t_end = ' // format_real(time%t_end) // ': t_end/dt = ' // &
            format_real(time%t_end / time%dt) // ' steps; must be at most ' // &
            int_str(huge(0) - 1) // ' steps')
        names = schemes%name   ! contiguous: no array temporary at the call (-fcheck=all warns of one)
        call require_one_of(time%scheme, names, 'time.scheme')
        if (time%adaptive) call validate_step_control(time)
    end subroutine validate_time

    !> &time adaptive = .true.: a relative tolerance in (0, 1) and dt_min <= dt <= dt_max.
    subroutine validate_step_control(time)
        type(time_t), intent(in) :: time

        call require_real(time%error_tol, 'time.error_tol', DIVISOR)
        if (time%error_tol >= 1.0_dp) call fatal(EXIT_INPUT, 'time.error_tol', 'got ' // &
            format_real(time%error_tol) // '; must be in (0, 1): the local error allowed per step, ' // &
            'relative to the largest energy norm of the solution so far (e.g. 1e-5)')
        call require_real(time%dt_min, 'time.dt_min', DIVISOR)
        call require_real(time%dt_max, 'time.dt_max', DIVISOR)
        if (time%dt_min > time%dt_max) call fatal(EXIT_INPUT, 'time.dt_min', 'got ' // &
            format_real(time%dt_min) // ' > dt_max = ' // format_real(time%dt_max) // '; must be <= dt_max')
        if (time%dt < time%dt_min .or. time%dt > time%dt_max) call fatal(EXIT_INPUT, 'time.dt', 'got ' // &
            format_real(time%dt) // ' with adaptive = .true.; the first step must lie in ' // &
            '[dt_min, dt_max] = [' // format_real(time%dt_min) // ', ' // format_real(time%dt_max) // ']')
    end subroutine validate_step_control

    !> The paper's Section 7 iteration is implicit Euler with a lagged contact force: it has
    !> no form for a constraint law (Signorini) and runs one time scheme (implicit Euler).
    subroutine validate_combination(cfg, schemes)
        type(config_t), intent(in) :: cfg
        type(scheme_rule_t), intent(in) :: schemes(:)

        if (cfg%solver%method /= 'paper') return
        if (cfg%mesh%adaptive) call fatal(EXIT_INPUT, 'solver.method', "got 'paper' with mesh.adaptive = " // &
            ".true.: the paper's iteration runs on one fixed mesh; method must be 'monolithic' for an " // &
            'adaptive mesh')
        if (cfg%time%adaptive) call fatal(EXIT_INPUT, 'solver.method', "got 'paper' with time.adaptive = " // &
            ".true.: the paper's iteration runs with one fixed step; method must be 'monolithic' for " // &
            'adaptive steps')
        if (constraint_law(cfg%contact%law)) call fatal(EXIT_INPUT, 'solver.method', "got 'paper' with " // &
            "contact.law = '" // trim(cfg%contact%law) // "': the paper's iteration lags the contact force, " // &
            "which a constraint has not (no Signorini form); method must be 'monolithic' with this law")
        if (.not. any(schemes%name == cfg%time%scheme .and. schemes%paper_iteration)) call fatal(EXIT_INPUT, &
            'solver.method', "got 'paper' with time.scheme = '" // trim(cfg%time%scheme) // "': the paper's " // &
            "iteration is implicit Euler; method must be 'monolithic' with this scheme")
    end subroutine validate_combination

    subroutine validate_solver(solver)
        type(solver_t), intent(in) :: solver

        call require_one_of(solver%method, [character(len=10) :: 'monolithic', 'paper'], 'solver.method')
        call require_real(solver%tol, 'solver.tol', POSITIVE)
        call require_at_least(solver%max_iter, 1, 'solver.max_iter')
    end subroutine validate_solver

    !> Output settings, and the size of <prefix>.h5: a warning above OUTPUT_WARN, an error
    !> above OUTPUT_LIMIT (counting snapshots and series as run_m writes them).
    subroutine validate_output(output, n_elements, time)
        type(output_t), intent(in) :: output
        integer, intent(in) :: n_elements
        type(time_t), intent(in) :: time
        real(dp) :: n_steps, nodes, snapshot_bytes, series_bytes, total
        character(len=:), allocatable :: where

        if (len_trim(output%prefix) == 0) call fatal(EXIT_INPUT, 'output.prefix', &
            "got ''; must be a non-empty path prefix, e.g. 'out/run' (the file is <prefix>.h5)")
        call require_file_prefix(output%prefix)
        call require_at_least(output%snapshot_every, 1, 'output.snapshot_every')
        call require_at_least(output%series_every, 1, 'output.series_every')
        call require_at_least(output%checkpoint_every, 0, 'output.checkpoint_every')
        if (output%n_points < 0 .or. output%n_points == 1) call fatal(EXIT_INPUT, 'output.n_points', &
            'got ' // int_str(output%n_points) // &
            '; must be 0 (the nodes of the coarsest mesh, n_elements + 1) or at ' // &
            'least 2 (points of the snapshot grid /mesh/x)')
        call require_real(output%snapshot_dt, 'output.snapshot_dt', NONNEGATIVE, &
                          ' (0: snapshots every snapshot_every steps)')
        call require_real(output%series_dt, 'output.series_dt', NONNEGATIVE, &
                          ' (0: a series entry every series_every steps)')
        if (output%compression < 0 .or. output%compression > MAX_COMPRESSION) call fatal(EXIT_INPUT, &
            'output.compression', 'got ' // int_str(output%compression) // '; must be an integer from 0 (no ' // &
            'compression) to ' // int_str(MAX_COMPRESSION) // ' (the deflate level of the snapshot fields)')
        n_steps = real(number_of_steps(time%dt, time%t_end), dp)
        nodes = real(n_elements, dp) + 1.0_dp
        if (output%n_points > 0) nodes = real(output%n_points, dp)
        snapshot_bytes = 8.0_dp * N_SNAPSHOT_FIELDS * nodes * &
                         entries(output%snapshot_every, output%snapshot_dt)
        series_bytes = 8.0_dp * N_SERIES * entries(output%series_every, output%series_dt)
        total = snapshot_bytes + series_bytes + 8.0_dp * nodes
        where = 'output.snapshot_every'
        if (output%snapshot_dt > 0.0_dp) where = 'output.snapshot_dt'
        if (series_bytes > snapshot_bytes) where = 'output.series_every'
        if (series_bytes > snapshot_bytes .and. output%series_dt > 0.0_dp) where = 'output.series_dt'
        if (total > OUTPUT_LIMIT) call fatal(EXIT_INPUT, where, 'the output file would be about ' // &
            gib_str(total) // ' GiB (' // gib_str(snapshot_bytes) // ' GiB of snapshots, ' // &
            gib_str(series_bytes) // ' GiB of series), more than the ' // gib_str(OUTPUT_LIMIT) // &
            ' GiB allowed; raise ' // where)
        if (total > OUTPUT_WARN) then
            write (error_unit, '(a)') 'rodcontact: warning: ' // trim(output%prefix) // '.h5 will be about ' // &
                gib_str(total) // ' GiB (' // gib_str(snapshot_bytes) // ' GiB of snapshots); raise ' // &
                where // ' for a smaller file'
            flush (error_unit)
        end if
    contains
        !> The entries written: the initial state, one every `every` steps (or every dt, if
        !> dt > 0), and the last step.
        pure real(dp) function entries(every, dt)
            integer, intent(in) :: every
            real(dp), intent(in) :: dt

            entries = aint(n_steps / every) + 2.0_dp
            if (dt > 0.0_dp) entries = aint(min(time%t_end / dt, 1.0e12_dp)) + 2.0_dp
        end function entries
    end subroutine validate_output

    !> The prefix must name a file: printable characters only (a NUL would cut the name
    !> the C library sees), a last component that is not empty, '.' or '..' ('out/' would
    !> write the hidden file 'out/.h5'), and not filling the whole variable (the namelist
    !> read truncates a longer string without a word).
    subroutine require_file_prefix(prefix)
        character(len=*), intent(in) :: prefix
        character(len=:), allocatable :: p, last, example
        integer :: k, n

        n = len_trim(prefix)
        if (n >= len(prefix)) call fatal(EXIT_INPUT, 'output.prefix', 'got a path of ' // int_str(n) // &
            ' or more characters (cut at ' // int_str(len(prefix)) // '); must be at most ' // &
            int_str(len(prefix) - 1) // ' characters')
        p = prefix(1:n)
        do k = 1, n
            if (iachar(p(k:k)) < 32 .or. iachar(p(k:k)) == 127) call fatal(EXIT_INPUT, 'output.prefix', &
                'got a control character (code ' // int_str(iachar(p(k:k))) // ') at position ' // int_str(k) // &
                '; must be a path of printable characters, e.g. ''out/run'' (the file is <prefix>.h5)')
        end do
        last = p(index(p, '/', back=.true.) + 1:)
        if (len(last) == 0 .or. last == '.' .or. last == '..') then
            example = p // '/run'
            if (p(n:n) == '/') example = p // 'run'
            call fatal(EXIT_INPUT, 'output.prefix', "got '" // p // "', which names a directory; " // &
                       "must end in a file name, e.g. '" // example // "' (the file is " // &
                       example // '.h5)')
        end if
    end subroutine require_file_prefix

    ! ---------------------------------------------------------------- small checks

    subroutine require_at_least(n, n_min, where)
        integer, intent(in) :: n, n_min
        character(len=*), intent(in) :: where

        if (n < n_min) call fatal(EXIT_INPUT, where, 'got ' // int_str(n) // '; must be an integer >= ' // &
                                  int_str(n_min))
    end subroutine require_at_least

    subroutine require_one_of(value, allowed, where)
        character(len=*), intent(in) :: value
        character(len=*), intent(in) :: allowed(:)
        character(len=*), intent(in) :: where

        if (any(allowed == value)) return
        call fatal(EXIT_INPUT, where, "got '" // trim(value) // "'; must be one of " // &
                   joined(allowed, "'", "'"))
    end subroutine require_one_of

    !> bytes in GiB with one decimal.
    pure function gib_str(bytes) result(s)
        real(dp), intent(in) :: bytes
        character(len=:), allocatable :: s
        character(len=32) :: buf
        integer :: ios

        write (buf, '(f0.1)', iostat=ios) bytes / GIB
        s = trim(adjustl(buf))
        if (s(1:1) == '.') s = '0' // s
    end function gib_str

end module validate_m
