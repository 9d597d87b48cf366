!> The shipped experiments of docs/reproduction.md, loaded the way the program loads them
!> (read_config + validate_config + nondimensionalise), with the output redirected into a test's scratch dir.
module shipped_inputs_m
    use config_m, only: config_t
    use config_reader_m, only: read_config
    use validate_m, only: validate_config
    use material_m, only: nondimensionalise
    use time_scheme_m, only: scheme_rules
    implicit none
    private
    public :: SHIPPED_INPUTS, load_input, command_arguments

    character(len=*), parameter :: SHIPPED_INPUTS(6) = [character(len=12) :: &
        'exp1', 'exp1_varpi05', 'exp1_varpi1', 'exp2', 'exp2_amp5', 'exp3']

contains

    !> The two arguments every test program gets from CTest: source dir and scratch dir.
    subroutine command_arguments(source_dir, scratch_dir)
        character(len=:), allocatable, intent(out) :: source_dir, scratch_dir
        character(len=4096) :: buf

        call get_command_argument(1, buf)
        source_dir = trim(buf)
        call get_command_argument(2, buf)
        scratch_dir = trim(buf)
        if (source_dir == '' .or. scratch_dir == '') then
            write (*, '(a)') 'usage: test <source dir> <scratch dir>'
            stop 1
        end if
    end subroutine command_arguments

    !> Read input/<name>.nml, write output to <scratch>/<name>, quietly, and validate.
    subroutine load_input(source_dir, name, scratch_dir, cfg)
        character(len=*), intent(in) :: source_dir, name, scratch_dir
        type(config_t), intent(out) :: cfg

        call read_config(source_dir//'/input/'//trim(name)//'.nml', cfg)
        cfg%output%prefix = scratch_dir//'/'//trim(name)
        cfg%output%quiet = .true.
        call validate_config(cfg, scheme_rules())
        call nondimensionalise(cfg)
    end subroutine load_input

end module shipped_inputs_m
