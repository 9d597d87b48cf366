!> Dense global P1 matrices on the uniform mesh, assembled from fe_m's element kernels: for
!> tests that compare them with independent quadrature (the program never forms them).
module fe_dense_m
    use kinds_m, only: dp
    use fe_m, only: element_mass, element_stiffness, element_gradient
    implicit none
    private
    public :: global_mass, global_stiffness, global_gradient

contains

    !> Dense global matrix int phi_i phi_j dx over all nodes 0..s (for tests and small checks).
    pure function global_mass(s) result(a)
        integer, intent(in) :: s
        real(dp) :: a(0:s, 0:s)

        a = assemble_dense(s, element_mass(1.0_dp / real(s, dp)))
    end function global_mass

    !> Dense global matrix int phi_i' phi_j' dx over all nodes 0..s.
    pure function global_stiffness(s) result(a)
        integer, intent(in) :: s
        real(dp) :: a(0:s, 0:s)

        a = assemble_dense(s, element_stiffness(1.0_dp / real(s, dp)))
    end function global_stiffness

    !> Dense global matrix int phi_i phi_j' dx over all nodes 0..s.
    pure function global_gradient(s) result(a)
        integer, intent(in) :: s
        real(dp) :: a(0:s, 0:s)

        a = assemble_dense(s, element_gradient())
    end function global_gradient

    pure function assemble_dense(s, elem) result(a)
        integer, intent(in) :: s
        real(dp), intent(in) :: elem(2, 2)
        real(dp) :: a(0:s, 0:s)
        integer :: e

        a = 0.0_dp
        do e = 1, s
            a(e - 1:e, e - 1:e) = a(e - 1:e, e - 1:e) + elem
        end do
    end function assemble_dense

end module fe_dense_m
