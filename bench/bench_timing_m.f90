!> Wall-clock helpers shared by the benchmark programs of bench/ (not part of the library).
module bench_timing_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    implicit none
    private
    public :: wall_seconds, median, num

contains

    !> Wall-clock time in seconds from an arbitrary origin (system_clock, int64 counts:
    !> nanosecond resolution with gfortran on Linux).
    real(dp) function wall_seconds()
        integer(int64) :: count, rate

        call system_clock(count, rate)
        wall_seconds = real(count, dp) / real(rate, dp)
    end function wall_seconds

    !> Median of x (x is not changed).
    pure real(dp) function median(x)
        real(dp), intent(in) :: x(:)
        real(dp) :: y(size(x)), t
        integer :: i, j, n

        n = size(x)
        y = x
        do i = 2, n                  ! insertion sort: a handful of values
            t = y(i)
            j = i - 1
            do while (j >= 1)
                if (y(j) <= t) exit
                y(j + 1) = y(j)
                j = j - 1
            end do
            y(j + 1) = t
        end do
        if (mod(n, 2) == 1) then
            median = y((n + 1) / 2)
        else
            median = 0.5_dp * (y(n / 2) + y(n / 2 + 1))
        end if
    end function median

    !> x as a short string with no blanks (es, 5 significant digits), for key=value output.
    function num(x) result(text)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: buf

        write (buf, '(es12.5)') x
        text = trim(adjustl(buf))
    end function num

end module bench_timing_m
