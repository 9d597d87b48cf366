!> Clean stop on a signal (docs/output.md; README, exit status 5): the handlers of
!> src/driver/signals_c.c, and whether a signal has arrived, asked once per time step.
module stop_signal_m
    use iso_c_binding, only: c_int
    use errors_m, only: fatal, EXIT_OUTPUT
    implicit none
    private
    public :: install_stop_handlers, stop_signal_arrived, stop_signal_name

    interface
        function c_install() bind(C, name='rc_install_stop_handlers') result(rc)
            import :: c_int
            integer(c_int) :: rc
        end function c_install

        function c_stop_signal() bind(C, name='rc_stop_signal') result(sig)
            import :: c_int
            integer(c_int) :: sig
        end function c_stop_signal
    end interface

    !> rc_stop_signal's 1, 2, 3
    character(len=*), parameter :: NAMES(3) = [character(len=7) :: 'SIGTERM', 'SIGINT', 'SIGUSR1']

contains

    !> From now on SIGTERM, SIGINT and SIGUSR1 only set the flag that stop_signal_name reads,
    !> and a write past the file size limit (ulimit -f) fails with EFBIG instead of killing
    !> the run with SIGXFSZ, so that it ends like a full disk: message, exit status 4, the
    !> .h5.part with its last checkpoint left to restart from (output_m).
    subroutine install_stop_handlers()
        if (c_install() /= 0) call fatal(EXIT_OUTPUT, 'signals', 'cannot install the handlers of SIGTERM, ' // &
                                         'SIGINT and SIGUSR1 or ignore SIGXFSZ (sigaction or sigprocmask failed)')
    end subroutine install_stop_handlers

    !> A stop signal has arrived (the time loop's test after every step: no allocation, unlike
    !> stop_signal_name).
    logical function stop_signal_arrived()
        stop_signal_arrived = c_stop_signal() /= 0
    end function stop_signal_arrived

    !> 'SIGTERM', 'SIGINT' or 'SIGUSR1' when one of them has arrived, else ''.
    function stop_signal_name() result(name)
        character(len=:), allocatable :: name
        integer :: k

        name = ''
        k = c_stop_signal()
        if (k > 0) name = trim(NAMES(k))
    end function stop_signal_name

end module stop_signal_m
