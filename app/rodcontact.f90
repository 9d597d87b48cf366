!> rodcontact: a thermoviscoelastic rod with mass diffusion and second sound hitting a rigid
!> obstacle (Aouadi, Copetti & Fernandez, ESAIM: M2AN 2017). Thin driver: read, validate, run.
!>
!>   rodcontact < input.nml      namelist on standard input
!>   rodcontact input.nml        namelist file as argument ('-' for standard input)
!>   rodcontact --help | --version
program rodcontact
    use iso_fortran_env, only: output_unit
    use config_m, only: config_t, read_config
    use validate_m, only: validate_config
    use run_m, only: run_simulation
    use errors_m, only: fatal, EXIT_INPUT
    use version_m, only: PROGRAM_VERSION
    implicit none
    type(config_t) :: cfg
    character(len=:), allocatable :: source

    call parse_command_line(source)
    call read_config(source, cfg)
    call validate_config(cfg)
    call run_simulation(cfg)

contains

    subroutine parse_command_line(source)
        character(len=:), allocatable, intent(out) :: source
        character(len=:), allocatable :: arg
        integer :: n_args, length

        n_args = command_argument_count()
        source = '-'
        if (n_args == 0) return
        if (n_args > 1) call fatal(EXIT_INPUT, 'command line', &
                                   'expected at most one argument (the input file); try rodcontact --help')
        call get_command_argument(1, length=length)
        allocate (character(len=length) :: arg)
        call get_command_argument(1, arg)
        select case (arg)
        case ('-h', '--help')
            call print_help()
            stop
        case ('-V', '--version')
            write (output_unit, '(a)') 'rodcontact '//PROGRAM_VERSION
            stop
        case default
            if (len(arg) > 1) then
                if (arg(1:1) == '-') call fatal(EXIT_INPUT, 'command line', "unknown option '"//arg// &
                                                "'; allowed: --help, --version, or an input file")
            end if
            source = arg
        end select
    end subroutine parse_command_line

    subroutine print_help()
        write (output_unit, '(a)') &
            'rodcontact '//PROGRAM_VERSION//' - 1D thermoviscoelastic diffusion contact problem with second sound', &
            '(Aouadi, Copetti & Fernandez, ESAIM: M2AN 2017): P1 finite elements, implicit Euler, normal compliance.', &
            '', &
            'Usage:', &
            '  rodcontact < input.nml     read the namelist input from standard input', &
            '  rodcontact input.nml       read it from a file (- for standard input)', &
            '  rodcontact --help          this text', &
            '  rodcontact --version       the program version', &
            '', &
            'Namelist groups (all optional, any order, each at most once):', &
            '  &model &contact &mesh &time &initial &solver &output &material', &
            '  see docs/input.md for every variable, its default and allowed range.', &
            '', &
            'Output: <prefix>.h5 (HDF5: /mesh/x, /series/*, /snapshots/*, root attributes),', &
            '  written as <prefix>.h5.part and renamed when complete.', &
            '', &
            'Exit status: 0 success, 2 bad input, 3 numerical failure, 4 output failure.'
    end subroutine print_help

end program rodcontact
