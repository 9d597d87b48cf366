!> P1 finite elements on the uniform mesh of Section 6: 0 = x_0 < ... < x_s = 1, h = 1/s.
!> Element kernels are exact integrals of products of the two local hat functions
!> phi_1 = (x_b - x)/h, phi_2 = (x - x_a)/h on one element [x_a, x_b].
module fe_m
    use kinds_m, only: dp
    implicit none
    private
    public :: mesh_nodes, element_mass, element_stiffness, element_gradient
    public :: global_mass, global_stiffness, global_gradient, apply_assembled

contains

    !> Nodes x_i = i h, i = 0..s.
    pure function mesh_nodes(s) result(x)
        integer, intent(in) :: s
        real(dp) :: x(0:s)
        integer :: i

        do i = 0, s
            x(i) = real(i, dp) / real(s, dp)
        end do
        x(s) = 1.0_dp
    end function mesh_nodes

    !> Element mass matrix: m(a,b) = int phi_a phi_b dx = h/6 [2 1; 1 2].
    pure function element_mass(h) result(m)
        real(dp), intent(in) :: h
        real(dp) :: m(2, 2)

        m = reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2]) * (h / 6.0_dp)
    end function element_mass

    !> Element stiffness matrix: k(a,b) = int phi_a' phi_b' dx = 1/h [1 -1; -1 1].
    pure function element_stiffness(h) result(k)
        real(dp), intent(in) :: h
        real(dp) :: k(2, 2)

        k = reshape([1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp], [2, 2]) / h
    end function element_stiffness

    !> Element gradient matrix: g(a,b) = int phi_a phi_b' dx  (test function a, derivative
    !> of trial function b) = 1/2 [-1 1; -1 1], independent of h.
    pure function element_gradient() result(g)
        real(dp) :: g(2, 2)

        g = reshape([-0.5_dp, -0.5_dp, 0.5_dp, 0.5_dp], [2, 2])
    end function element_gradient

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

    !> y = A x where A is the global matrix assembled from the element matrix elem on the
    !> s-element mesh (nodes 0..s); x and y have bounds 0..s. Written per node (the
    !> assembled matrix is tridiagonal: elem(2,1), elem(1,1) + elem(2,2), elem(1,2)) so that
    !> the loop vectorises; no allocation (called every time step).
    pure subroutine apply_assembled(elem, x, y)
        real(dp), intent(in) :: elem(2, 2)
        real(dp), intent(in) :: x(0:)
        real(dp), intent(out) :: y(0:)
        integer :: s

        s = ubound(x, 1)
        y(0) = elem(1, 1) * x(0) + elem(1, 2) * x(1)
        y(1:s - 1) = elem(2, 1) * x(0:s - 2) + (elem(2, 2) + elem(1, 1)) * x(1:s - 1) + elem(1, 2) * x(2:s)
        y(s) = elem(2, 1) * x(s - 1) + elem(2, 2) * x(s)
    end subroutine apply_assembled

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

end module fe_m
