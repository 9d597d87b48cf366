!> Minimal checks for the test programs: each failed check prints what was expected, what
!> was got and the tolerance; test_summary stops with status 1 if anything failed.
module testing_m
    use kinds_m, only: dp
    use iso_fortran_env, only: error_unit, output_unit
    implicit none
    private
    public :: check_close, check_true, test_summary

    integer, save :: n_checks = 0, n_failed = 0

contains

    !> |got - expected| <= tol (absolute), element-wise for arrays via check_close on maxval.
    subroutine check_close(name, expected, got, tol)
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: expected, got, tol

        n_checks = n_checks + 1
        if (.not. (abs(got - expected) <= tol)) then
            n_failed = n_failed + 1
            write (error_unit, '(a)') 'FAIL '//name
            write (error_unit, '(a,es24.16,a,es24.16,a,es10.3,a,es10.3)') '  expected ', expected, &
                '  got ', got, '  |diff| ', abs(got - expected), '  tol ', tol
        end if
    end subroutine check_close

    subroutine check_true(name, condition, detail)
        character(len=*), intent(in) :: name
        logical, intent(in) :: condition
        character(len=*), intent(in), optional :: detail

        n_checks = n_checks + 1
        if (.not. condition) then
            n_failed = n_failed + 1
            write (error_unit, '(a)') 'FAIL '//name
            if (present(detail)) write (error_unit, '(a)') '  '//detail
        end if
    end subroutine check_true

    !> Print the count and stop 1 when any check failed.
    subroutine test_summary(test_name)
        character(len=*), intent(in) :: test_name

        write (output_unit, '(a,": ",i0," checks, ",i0," failed")') test_name, n_checks, n_failed
        if (n_failed > 0) stop 1
    end subroutine test_summary

end module testing_m
