!> P1 finite elements on the mesh of Section 6 (mesh_m): 0 = x_0 < ... < x_s = 1, uniform
!> (h = 1/s) or graded (element sizes h_e = x_e - x_{e-1}, &mesh adaptive). Element kernels
!> are exact integrals of products of the two local hat functions phi_1 = (x_b - x)/h,
!> phi_2 = (x - x_a)/h on one element [x_a, x_b]; a graded mesh uses the same kernels with
!> each element's own h.
module fe_m
    use kinds_m, only: dp
    use reals_m, only: equal
    implicit none
    private
    public :: mesh_nodes, element_mass, element_stiffness, element_gradient
    public :: apply_assembled, apply_mass_graded, apply_stiffness_graded, evaluate_p1
    public :: inertia_element, add_inertia_difference

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

    !> y = M x, M the mass matrix assembled from element_mass(h(e)) on the graded mesh with
    !> element sizes h(1:s); x, y have bounds 0..s. No allocation (called every time step).
    pure subroutine apply_mass_graded(h, x, y)
        real(dp), intent(in) :: h(:)
        real(dp), intent(in) :: x(0:)
        real(dp), intent(out) :: y(0:)
        integer :: s

        s = ubound(x, 1)
        y(0) = h(1) * (2.0_dp * x(0) + x(1)) / 6.0_dp
        y(1:s - 1) = (h(1:s - 1) * (x(0:s - 2) + 2.0_dp * x(1:s - 1)) &
                      + h(2:s) * (2.0_dp * x(1:s - 1) + x(2:s))) / 6.0_dp
        y(s) = h(s) * (x(s - 1) + 2.0_dp * x(s)) / 6.0_dp
    end subroutine apply_mass_graded

    !> y = K x, K the stiffness matrix assembled from element_stiffness(h(e)) (see
    !> apply_mass_graded).
    pure subroutine apply_stiffness_graded(h, x, y)
        real(dp), intent(in) :: h(:)
        real(dp), intent(in) :: x(0:)
        real(dp), intent(out) :: y(0:)
        integer :: s

        s = ubound(x, 1)
        y(0) = (x(0) - x(1)) / h(1)
        y(1:s - 1) = (x(1:s - 1) - x(0:s - 2)) / h(1:s - 1) + (x(1:s - 1) - x(2:s)) / h(2:s)
        y(s) = (x(s) - x(s - 1)) / h(s)
    end subroutine apply_stiffness_graded

    !> The P1 function with nodal values f(0:s) on the nodes x(0:s) (increasing, x(0) = 0,
    !> x(s) = 1) at the increasing points p(:) of [0, 1]: one merge-like pass.
    pure function evaluate_p1(x, f, p) result(values)
        real(dp), intent(in) :: x(0:), f(0:), p(:)
        real(dp) :: values(size(p))
        integer :: j, e, s
        real(dp) :: weight

        s = ubound(x, 1)
        e = 1
        do j = 1, size(p)
            do while (e < s .and. p(j) > x(e))
                e = e + 1
            end do
            weight = (p(j) - x(e - 1)) / (x(e) - x(e - 1))
            values(j) = (1.0_dp - weight) * f(e - 1) + weight * f(e)
            if (equal(p(j), x(e - 1))) values(j) = f(e - 1)
            if (equal(p(j), x(e))) values(j) = f(e)
        end do
    end function evaluate_p1

    !> Element matrix of the velocity's mass, the inertia of (6.1)_1, with the mass
    !> redistribution of docs/scheme.md ("Mass redistribution"): the blend
    !> (1 - lumped) h/6 [2 1; 1 2] + lumped h/2 [1 0; 0 1], and, on the last element (it holds
    !> the contact node x = 1) when end_moved, [h 0; 0 0]: the element's whole mass h on its
    !> other node, the contact node massless. lumped = 0, end_moved = .false.: element_mass(h).
    !> Every use of the velocity's mass goes through this function: the matrix
    !> (scheme_m), and through add_inertia_difference the old level's term and the kinetic
    !> energy (energy_m), so that the energy is the scheme's own.
    pure function inertia_element(h, lumped, end_moved, last) result(m)
        real(dp), intent(in) :: h, lumped
        logical, intent(in) :: end_moved, last
        real(dp) :: m(2, 2)

        if (end_moved .and. last) then
            m = reshape([h, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2])
        else
            m = (1.0_dp - lumped) * element_mass(h) &
                + lumped * reshape([h, 0.0_dp, 0.0_dp, h], [2, 2]) / 2.0_dp
        end if
    end function inertia_element

    !> y += (M_v - M) x on the mesh with element sizes h(1:s): M_v the velocity's mass of
    !> inertia_element, M the consistent P1 mass (apply_mass_graded); x, y bounds 0..s.
    !> The blend's difference is h times that of h = 1 (inertia_element is linear in h), so the
    !> interior is one vectorised pass; the contact node's element is taken as it is.
    pure subroutine add_inertia_difference(h, lumped, end_moved, x, y)
        real(dp), intent(in) :: h(:), lumped
        logical, intent(in) :: end_moved
        real(dp), intent(in) :: x(0:)
        real(dp), intent(inout) :: y(0:)
        real(dp) :: d(2, 2), d1(2, 2)
        integer :: s

        s = ubound(x, 1)
        if (lumped > 0.0_dp) then
            d1 = inertia_element(1.0_dp, lumped, .false., .false.) - element_mass(1.0_dp)
            ! elements 1..s-1 (the last one below): rows e-1 and e of element e
            y(0:s - 2) = y(0:s - 2) + h(1:s - 1) * (d1(1, 1) * x(0:s - 2) + d1(1, 2) * x(1:s - 1))
            y(1:s - 1) = y(1:s - 1) + h(1:s - 1) * (d1(2, 1) * x(0:s - 2) + d1(2, 2) * x(1:s - 1))
        end if
        d = inertia_element(h(s), lumped, end_moved, .true.) - element_mass(h(s))
        y(s - 1) = y(s - 1) + d(1, 1) * x(s - 1) + d(1, 2) * x(s)
        y(s) = y(s) + d(2, 1) * x(s - 1) + d(2, 2) * x(s)
    end subroutine add_inertia_difference

end module fe_m
