!> The contact laws by the name of &contact law: the one table a new law joins, a row of
!> law_row (docs/architecture.md, "A contact law"). validate_m allows exactly these names.
!> A caller that makes a law gets contact_law_t from here too.
module contact_laws_m
    use kinds_m, only: dp
    use contact_law_m, only: contact_law_t
    use contact_penalty_m, only: penalty_law_t
    use contact_signorini_m, only: signorini_law_t
    implicit none
    private
    public :: contact_law_t, contact_law, law_names, constraint_law

contains

    !> The table: row k's input name and a law of its type (no row k: name = '').
    subroutine law_row(k, name, law)
        integer, intent(in) :: k
        character(len=:), allocatable, intent(out) :: name
        class(contact_law_t), allocatable, intent(out) :: law

        select case (k)
        case (1)
            name = 'penalty'            ! normal compliance (3.4)
            allocate (penalty_law_t :: law)
        case (2)
            name = 'signorini'          ! the Signorini condition (2.14)
            allocate (signorini_law_t :: law)
        case default
            name = ''
        end select
    end subroutine law_row

    !> The law named by &contact law, with the gap g and compliance eps of &contact.
    function contact_law(name, g, eps) result(law)
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: g, eps
        class(contact_law_t), allocatable :: law
        character(len=:), allocatable :: row_name
        integer :: k

        k = 0
        do
            k = k + 1
            call law_row(k, row_name, law)
            if (row_name == '') &
                error stop 'contact_laws_m: a law not in the table (validate_m checks the name)'
            if (row_name == name) exit
        end do
        law%g = g
        law%eps = eps
    end function contact_law

    !> The names of the table's rows, in order: the values &contact law allows.
    function law_names() result(names)
        character(len=:), allocatable :: names(:)
        character(len=:), allocatable :: name
        class(contact_law_t), allocatable :: law
        character(len=32) :: found(32)   ! room for 32 laws
        integer :: k

        do k = 1, size(found)
            call law_row(k, name, law)
            if (name == '') exit
            found(k) = name
        end do
        names = found(:k - 1)
    end function law_names

    !> Whether the law of this name is a constraint (its is_constraint), for validate_m.
    logical function constraint_law(name)
        character(len=*), intent(in) :: name
        class(contact_law_t), allocatable :: law

        law = contact_law(name, 0.0_dp, 1.0_dp)
        constraint_law = law%is_constraint()
    end function constraint_law

end module contact_laws_m
