!> The mesh type (mesh_m): the uniform mesh is the graded mesh with h_e = 1/s exactly; its
!> mass and stiffness products (written-out kernel for the uniform mesh, per-element sizes
!> for a graded one) against the dense matrices assembled from fe_m's element matrices; a copy
!> takes the nodes of its source also when both have the same number of elements.
program test_mesh_m
    use kinds_m, only: dp
    use fe_m, only: mesh_nodes, element_mass, element_stiffness
    use mesh_m, only: mesh_t, copy_mesh
    use meshes_m, only: uniform_mesh, graded_mesh
    use testing_m, only: check_close, check_true, test_summary
    implicit none
    real(dp), parameter :: X_GRADED(0:4) = [0.0_dp, 0.125_dp, 0.25_dp, 0.5_dp, 1.0_dp]
    type(mesh_t) :: uniform, graded, copy

    uniform = uniform_mesh(4)
    graded = graded_mesh(X_GRADED)
    call check_true('uniform_mesh(4) is uniform, graded_mesh is not', &
                    uniform%is_uniform() .and. .not. graded%is_uniform())
    call check_true('uniform_mesh(4): 4 elements', uniform%s() == 4)
    call check_close('uniform_mesh(4): the nodes of mesh_nodes(4)', 0.0_dp, &
                     maxval(abs(uniform%x - mesh_nodes(4))), 0.0_dp)
    call check_close('uniform_mesh(4): every h_e = 1/4 exactly', 0.0_dp, maxval(abs(uniform%h - 0.25_dp)), 0.0_dp)
    call check_close('graded_mesh: h_e = x_e - x_{e-1}', 0.0_dp, &
                     maxval(abs(graded%h - [0.125_dp, 0.125_dp, 0.25_dp, 0.5_dp])), 0.0_dp)
    call check_products(uniform, 'uniform')
    call check_products(graded, 'graded')
    call check_copies()
    call test_summary('test_mesh_m')

contains

    !> mesh%apply_mass and apply_stiffness against the dense matrices assembled element by
    !> element from element_mass(h_e) and element_stiffness(h_e).
    subroutine check_products(mesh, name)
        type(mesh_t), intent(in) :: mesh
        character(len=*), intent(in) :: name
        real(dp) :: m(0:mesh%s(), 0:mesh%s()), k(0:mesh%s(), 0:mesh%s()), f(0:mesh%s()), y(0:mesh%s())
        integer :: e, i

        m = 0.0_dp
        k = 0.0_dp
        do e = 1, mesh%s()
            m(e - 1:e, e - 1:e) = m(e - 1:e, e - 1:e) + element_mass(mesh%h(e))
            k(e - 1:e, e - 1:e) = k(e - 1:e, e - 1:e) + element_stiffness(mesh%h(e))
        end do
        f = [(sin(3.0_dp * mesh%x(i)) + 1.0_dp, i = 0, mesh%s())]
        call mesh%apply_mass(f, y)
        call check_close(name//': |M f - dense M f|', 0.0_dp, maxval(abs(y - matmul(m, f))), 1.0e-15_dp)
        call mesh%apply_stiffness(f, y)
        call check_close(name//': |K f - dense K f|', 0.0_dp, maxval(abs(y - matmul(k, f))), 1.0e-13_dp)
    end subroutine check_products

    !> copy_mesh between a graded and a uniform mesh of the same size.
    subroutine check_copies()
        type(mesh_t) :: mesh

        mesh = uniform_mesh(4)
        call mesh%set_nodes(X_GRADED)
        ! a copy onto a uniform mesh of the same size takes the graded nodes, and back
        copy = uniform_mesh(4)
        call copy_mesh(mesh, copy)
        call check_true('copy of a graded mesh: graded', .not. copy%is_uniform())
        call check_close('copy of a graded mesh: its nodes', 0.0_dp, maxval(abs(copy%x - X_GRADED)), 0.0_dp)
        call check_close('copy of a graded mesh: its sizes', 0.0_dp, maxval(abs(copy%h - mesh%h)), 0.0_dp)
        call copy_mesh(uniform_mesh(4), copy)
        call check_true('copy of a uniform mesh onto a graded one: uniform', copy%is_uniform())
        call check_close('copy of a uniform mesh onto a graded one of the same size: uniform nodes', 0.0_dp, &
                         maxval(abs(copy%x - mesh_nodes(4))), 0.0_dp)
        call check_close('... and sizes', 0.0_dp, maxval(abs(copy%h - 0.25_dp)), 0.0_dp)
    end subroutine check_copies

end program test_mesh_m
