!> Working precision of rodcontact: every real is real(dp).
module kinds_m
    use iso_fortran_env, only: dp => real64
    implicit none
    private
    public :: dp
end module kinds_m
