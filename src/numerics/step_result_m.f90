!> What one step did (stepper_m, paper_method_m).
module step_result_m
    use kinds_m, only: dp
    implicit none
    private
    public :: step_result_t, fail

    !> ok = .false. with a message on a numerical failure.
    type :: step_result_t
        logical :: ok = .true.
        character(len=256) :: message = ''
        integer :: iterations = 0        !< linear solves of the step (paper: iterations)
        logical :: in_contact = .false.  !< the contact node is active after the step
        !> u(1) - g at the step's end without contact force (monolithic): its sign decides the
        !> contact state of the step; step_control locates contact events with it
        real(dp) :: trial_gap = 0.0_dp
        real(dp) :: contact_force = 0.0_dp  !< lambda = -sigma(1,t_n): (1/eps)[u^n(1)-g]_+, or the
                                            !< Signorini multiplier
    end type step_result_t

contains

    subroutine fail(result, message)
        type(step_result_t), intent(inout) :: result
        character(len=*), intent(in) :: message

        result%ok = .false.
        result%message = message
    end subroutine fail

end module step_result_m
