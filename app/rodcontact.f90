!> rodcontact: a thermoviscoelastic rod with mass diffusion and second sound hitting a rigid
!> obstacle (Aouadi, Copetti & Fernandez, ESAIM: M2AN 2017). Thin driver: read, validate, run.
!> The usage is print_help's text (rodcontact --help).
program rodcontact
    use iso_fortran_env, only: output_unit
    use config_m, only: config_t
    use config_reader_m, only: read_config
    use namelist_text_m, only: string_t
    use validate_m, only: validate_config
    use material_m, only: nondimensionalise
    use time_scheme_m, only: scheme_rules
    use run_m, only: run_simulation
    use summary_m, only: summary_header, summary_row, summarise_file, summary_problem, events_header, &
                         write_event_rows, file_in_si
    use errors_m, only: fatal, EXIT_INPUT
    use version_m, only: PROGRAM_VERSION, VERSION_LINE
    implicit none
    type(config_t) :: cfg
    character(len=:), allocatable :: source, table
    type(string_t), allocatable :: overrides(:)
    integer :: source_arg, first_file
    logical :: check_only, resume, nondimensional

    call parse_command_line(source_arg, overrides, first_file, check_only, resume, table, nondimensional)
    if (table /= '') then
        if (source_arg > 0 .or. size(overrides) > 0 .or. check_only) call fatal(EXIT_INPUT, 'command line', &
            table // ' takes only HDF5 files, no input file, --set or --check')
        call write_table(table, first_file, nondimensional)
        stop
    end if
    if (nondimensional) call fatal(EXIT_INPUT, 'command line', &
        '--nondimensional is for --summary, --events and --summary-header')
    source = '-'
    if (source_arg > 0) source = argument(source_arg)
    call read_config(source, cfg, overrides)
    ! --resume: restart from the run's own .part, which the run then replaces (restart_m)
    if (resume) cfg%time%restart_from = trim(cfg%output%prefix)//'.h5.part'
    call validate_config(cfg, scheme_rules())
    call nondimensionalise(cfg)   ! with &material (SI inputs); echoes what it derived
    ! --check: the input checks of a run and nothing else (no file written), for scripts/scan.sh
    if (check_only) stop
    call run_simulation(cfg, resume_command(source))

contains

    !> --summary, --events or --summary-header (table) of the files that the arguments from
    !> `first` on name (every one but --nondimensional), in their input's units (file_in_si),
    !> or nondimensional. Every file is checked before any row is written: a bad one, or one
    !> of the other unit system than the first, is an input error.
    subroutine write_table(table, first, nondimensional)
        character(len=*), intent(in) :: table
        integer, intent(in) :: first
        logical, intent(inout) :: nondimensional
        character(len=:), allocatable :: file, problem
        character(len=*), parameter :: SYSTEM(0:1) = ['nondimensional', 'SI            ']
        integer, allocatable :: args(:)
        logical, allocatable :: si(:)
        integer :: k

        allocate (args(0))
        do k = first, command_argument_count()
            if (argument(k) == '--nondimensional') nondimensional = .true.
            if (argument(k) /= '--nondimensional') args = [args, k]
        end do
        if (size(args) == 0 .and. table /= '--summary-header') call fatal(EXIT_INPUT, 'command line', &
            table // ' needs a file: rodcontact ' // table // ' <prefix>.h5 [more files ...]')
        allocate (si(size(args)))
        do k = 1, size(args)
            file = argument(args(k))
            problem = summary_problem(file)
            if (problem /= '') call fatal(EXIT_INPUT, 'command line', table // ": '" // file // "': " // &
                problem // '; give rodcontact output files (<prefix>.h5 or <prefix>.h5.part)')
            si(k) = file_in_si(file) .and. .not. nondimensional
            if (si(k) .neqv. si(1)) call fatal(EXIT_INPUT, 'command line', table // ": '" // file // "' is " // &
                trim(SYSTEM(merge(1, 0, si(k)))) // ", '" // argument(args(1)) // "' " // &
                trim(SYSTEM(merge(1, 0, si(1)))) // '; one table holds one unit system: give --nondimensional')
        end do
        if (table == '--summary-header') write (output_unit, '(a)') summary_header(any(si))
        if (table == '--events') write (output_unit, '(a)') events_header(any(si))
        do k = 1, size(args)
            if (table == '--events') then
                call write_event_rows(output_unit, summarise_file(argument(args(k)), nondimensional))
            else if (table == '--summary') then
                write (output_unit, '(a)') summary_row(summarise_file(argument(args(k)), nondimensional))
            end if
        end do
    end subroutine write_table

    !> The argument that is the input source (0 if none: standard input), the --set values (overrides: --set X or
    !> --set=X), --summary, --events or --summary-header (table: which, '' if none; its files
    !> are the arguments from first_file on), and whether --nondimensional, --check and
    !> --resume were given. --help and --version print and stop.
    subroutine parse_command_line(source_arg, overrides, first_file, check_only, resume, table, nondimensional)
        integer, intent(out) :: source_arg
        type(string_t), allocatable, intent(out) :: overrides(:)
        integer, intent(out) :: first_file
        logical, intent(out) :: check_only, resume
        character(len=:), allocatable, intent(out) :: table
        logical, intent(out) :: nondimensional
        character(len=:), allocatable :: arg
        integer :: i

        source_arg = 0
        first_file = 0
        check_only = .false.
        resume = .false.
        table = ''
        nondimensional = .false.
        allocate (overrides(0))
        i = 0
        do while (i < command_argument_count())
            i = i + 1
            arg = argument(i)
            select case (arg)
            case ('-h', '--help')
                call print_help()
                stop
            case ('-V', '--version')
                write (output_unit, '(a)') VERSION_LINE
                stop
            case ('--summary', '--events', '--summary-header')
                table = arg
                first_file = i + 1
                exit
            case ('--nondimensional')
                nondimensional = .true.
            case ('--check')
                check_only = .true.
            case ('--resume')
                resume = .true.
            case ('--set')
                if (i == command_argument_count()) call fatal(EXIT_INPUT, 'command line', '--set needs an ' // &
                    'argument group.variable=value, e.g. --set model.varpi=0.3')
                i = i + 1
                arg = argument(i)
                overrides = [overrides, string_t(arg)]
            case default
                if (len(arg) > 6 .and. index(arg, '--set=') == 1) then
                    overrides = [overrides, string_t(arg(7:))]
                else if (len(arg) > 1 .and. index(arg, '-') == 1) then
                    call fatal(EXIT_INPUT, 'command line', "unknown option '" // arg // "'; allowed: --set " // &
                        'group.variable=value, --summary file.h5, --summary-header, --events file.h5, ' // &
                        '--nondimensional, --check, --resume, --help, --version, and one input file')
                else if (source_arg > 0) then
                    call fatal(EXIT_INPUT, 'command line', "a second input file '" // arg // "' after '" // &
                        argument(source_arg) // "'; give one input file (or none: standard input)")
                else
                    source_arg = i
                end if
            end select
        end do
    end subroutine parse_command_line

    function argument(i) result(arg)
        integer, intent(in) :: i
        character(len=:), allocatable :: arg
        integer :: length

        call get_command_argument(i, length=length)
        allocate (character(len=length) :: arg)
        if (length > 0) call get_command_argument(i, arg)
    end function argument

    !> The command that continues this run in place, for the message of a stop signal: the
    !> program and its arguments as given (each a word of a POSIX shell), then --resume.
    function resume_command(source) result(text)
        character(len=*), intent(in) :: source
        character(len=:), allocatable :: text
        integer :: i

        text = shell_word(argument(0))
        do i = 1, command_argument_count()
            if (argument(i) /= '--resume') text = text // ' ' // shell_word(argument(i))
        end do
        text = text // ' --resume'
        if (source == '-') text = text // ' < (the same input)'
    end function resume_command

    !> arg as one word of a POSIX shell: as it is when every character is safe, else quoted.
    pure function shell_word(arg) result(word)
        character(len=*), intent(in) :: arg
        character(len=:), allocatable :: word
        character(len=*), parameter :: SAFE = 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:@%'
        integer :: k

        word = arg
        if (len(arg) > 0 .and. verify(arg, SAFE) == 0) return
        word = "'"
        do k = 1, len(arg)
            word = word // arg(k:k)
            if (arg(k:k) == "'") word = word // "\''"   ! ' ends the quoting, \' is a quote, ' resumes
        end do
        word = word // "'"
    end function shell_word

    subroutine print_help()
        write (output_unit, '(a)') &
            'rodcontact '//PROGRAM_VERSION//' - 1D thermoviscoelastic diffusion contact problem with second sound', &
            '(Aouadi, Copetti & Fernandez, ESAIM: M2AN 2017): P1 finite elements, implicit Euler, normal compliance.', &
            '', &
            'Usage:', &
            '  rodcontact < input.nml     read the namelist input from standard input', &
            '  rodcontact input.nml       read it from a file (- for standard input)', &
            '  rodcontact input.nml --set group.variable=value [--set ...]', &
            '                             override input values after the file (also with stdin), e.g.', &
            '                               --set model.varpi=0.3 --set output.prefix=runs/a', &
            "                               --set initial.theta0_step=5,0.1 --set 'initial.p0_step(1)=5'", &
            '                             strings need no quotes; same checks and messages as the file;', &
            '                             a later --set of a variable overrides an earlier one', &
            '  rodcontact input.nml [--set ...] --resume', &
            '                             continue the interrupted run in place from the checkpoint in', &
            '                             <prefix>.h5.part: the finished <prefix>.h5 replaces the .part', &
            '  rodcontact --check input.nml [--set ...]', &
            '                             the input checks of a run (not those of the output file or of', &
            '                             restart_from), no file written: exit 0, or 2 with the message', &
            '  rodcontact --summary f.h5 [g.h5 ...]', &
            '                             one CSV row per run: status, contact times, max penetration,', &
            '                             max u(1,t), energy ratio and decay rate, steps, wall seconds,', &
            '                             time error estimate, contact onsets and releases (count,', &
            '                             first and last time);', &
            '                             a missing, unreadable or non-rodcontact file exits 2', &
            '  rodcontact --summary-header [f.h5]  the CSV header of --summary (see docs/scans.md)', &
            '  rodcontact --events f.h5 [g.h5 ...]', &
            '                             the contact events of /events, one CSV row each:', &
            '                             file,event,kind,t [s] (kind: onset or release)', &
            '                             units named per column: SI with &material, else [1];', &
            '                             --nondimensional: the file''s own values', &
            '  rodcontact --help          this text', &
            '  rodcontact --version       the program version', &
            '', &
            'Namelist groups (all optional, any order, each at most once):', &
            '  &model &contact &mesh &time &initial &solver &output &material', &
            '  see docs/input.md for every variable, its default and allowed range.', &
            '', &
            'Output: <prefix>.h5 (HDF5: /mesh/x, /series/*, /snapshots/*, root attributes),', &
            '  written as <prefix>.h5.part and renamed when complete; &output compression=0..9 deflates', &
            '  the snapshot fields (default 0). Text for gnuplot: scripts/h5extract.py (docs/output.md).', &
            'Parameter scans: scripts/scan.sh (docs/scans.md).', &
            '', &
            'Stopping: SIGTERM, SIGINT (Ctrl-C) or SIGUSR1 (Slurm: --signal=USR1@<seconds>) ends a run', &
            '  after the current step: it writes a checkpoint and leaves <prefix>.h5.part with status', &
            "  'interrupted: <signal>'; the same command with --resume added continues it (the message", &
            '  prints that command). A second signal of the same kind ends the program at once.', &
            '', &
            'Exit status: 0 success, 2 bad input, 3 numerical failure, 4 output failure (cannot create', &
            '  or write the file; a full disk or file size limit leaves <prefix>.h5.part as its last', &
            '  checkpoint wrote it, to continue with --resume), 5 stopped by a signal (checkpoint in', &
            '  <prefix>.h5.part).'
    end subroutine print_help

end program rodcontact
