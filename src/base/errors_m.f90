!> Exit codes of the README, "exit status" and the one way the program stops on an error.
module errors_m
    use iso_fortran_env, only: error_unit, output_unit
    use iso_c_binding, only: c_int
    implicit none
    private
    public :: EXIT_OK, EXIT_INPUT, EXIT_NUMERIC, EXIT_OUTPUT, EXIT_INTERRUPTED
    public :: fatal, fatal_now, check_allocation

    integer, parameter :: EXIT_OK = 0       !< success
    integer, parameter :: EXIT_INPUT = 2    !< bad input: file, syntax, unknown variable, out-of-range value
    integer, parameter :: EXIT_NUMERIC = 3  !< numerical failure: non-finite value, solver failure, no convergence
    integer, parameter :: EXIT_OUTPUT = 4   !< output failure: cannot create or write the file
    !> stopped by a signal (stop_signal_m): checkpoint in <prefix>.h5.part
    integer, parameter :: EXIT_INTERRUPTED = 5

    interface
        !> C's _exit: end the process without running exit handlers
        subroutine c_exit_now(status) bind(C, name='_exit')
            import :: c_int
            integer(c_int), value, intent(in) :: status
        end subroutine c_exit_now
    end interface

contains

    !> Write "rodcontact: error in <where>: <message>" to stderr and stop with status `code`.
    subroutine fatal(code, where, message)
        integer, intent(in) :: code
        character(len=*), intent(in) :: where
        character(len=*), intent(in) :: message

        write (error_unit, '(a)') 'rodcontact: error in '//trim(where)//': '//trim(message)
        flush (error_unit)
        ! plain STOP: ERROR STOP makes gfortran print a backtrace, which is noise for an input error
        stop code, quiet=.true.
    end subroutine fatal

    !> Like fatal, but the process ends at once (C _exit), without the exit handlers: for a
    !> failed write to the output file, whose HDF5 library would otherwise flush its caches
    !> into the file at exit and could overwrite the consistent state of its last flush
    !> (and its last checkpoint) with a half-written one (output_m).
    subroutine fatal_now(code, where, message)
        integer, intent(in) :: code
        character(len=*), intent(in) :: where
        character(len=*), intent(in) :: message

        flush (output_unit)
        write (error_unit, '(a)') 'rodcontact: error in '//trim(where)//': '//trim(message)
        flush (error_unit)
        call c_exit_now(int(code, c_int))
    end subroutine fatal_now

    !> After `allocate (..., stat=stat, errmsg=message)`: a failed allocation (out of memory)
    !> stops with EXIT_NUMERIC, naming what could not be allocated.
    subroutine check_allocation(stat, message, what)
        integer, intent(in) :: stat
        character(len=*), intent(in) :: message, what

        if (stat /= 0) call fatal(EXIT_NUMERIC, 'memory', 'cannot allocate '//what//': '//trim(message)// &
                                  '; a smaller mesh (&mesh n_elements) or fewer snapshots need less')
    end subroutine check_allocation

end module errors_m
