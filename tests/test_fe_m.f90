!> Every global P1 matrix of fe_m against exact integrals of the hat functions (independent
!> 3-point Gauss quadrature) on 3- and 4-element meshes, including the blocks named in the
!> paper's Section 7: M (V_h mass), M~ (S_h mass), K, K^ and K~.
program test_fe_m
    use kinds_m, only: dp
    use fe_m, only: mesh_nodes, apply_assembled, element_mass
    use fe_dense_m, only: global_mass, global_stiffness, global_gradient
    use quadrature_m, only: integrate_product
    use testing_m, only: check_close, test_summary
    implicit none
    integer :: s, i, j
    real(dp), allocatable :: m(:, :), k(:, :), g(:, :), x(:), y(:), ones(:)
    character(len=64) :: name

    do s = 3, 4
        if (allocated(m)) deallocate (m, k, g)
        allocate (m(0:s, 0:s), k(0:s, 0:s), g(0:s, 0:s), x(0:s), ones(0:s))
        m = global_mass(s)
        k = global_stiffness(s)
        g = global_gradient(s)
        do i = 0, s
            do j = 0, s
                write (name, '(a,i0,a,i0,a,i0,a)') '(s=', s, ') (', i, ',', j, ')'
                call check_close('mass '//trim(name), integrate_product(i, .false., j, .false., s), m(i, j), 1e-14_dp)
                call check_close('stiffness '//trim(name), integrate_product(i, .true., j, .true., s), k(i, j), 1e-12_dp)
                ! gradient(i,j) = int phi_i phi_j' : the paper's K_ij = int xi_i chi_j,x (i<s, j>0)
                ! and K~_ij = int chi_i,x xi_j = gradient(j,i)
                call check_close('gradient '//trim(name), integrate_product(i, .false., j, .true., s), g(i, j), 1e-14_dp)
            end do
        end do
        ! exact values by hand: M~(s,s) = h/3, interior M(i,i) = 2h/3, K^(i,i) = 2/h, K(0,1) = 1/2
        call check_close('M~(s,s) = h/3', 1.0_dp / (3 * s), m(s, s), 1e-15_dp)
        call check_close('M(1,1) = 2h/3', 2.0_dp / (3 * s), m(1, 1), 1e-15_dp)
        call check_close('K^(1,1) = 2/h', 2.0_dp * s, k(1, 1), 1e-12_dp)
        call check_close('K(0,1) = int xi_0 chi_1,x = 1/2', 0.5_dp, g(0, 1), 1e-15_dp)
        call check_close('K(s-1,s) = 1/2', 0.5_dp, g(s - 1, s), 1e-15_dp)
        call check_close('gradient(s,s) = int phi_s phi_s'' = 1/2', 0.5_dp, g(s, s), 1e-15_dp)
        ! apply_assembled agrees with the dense product
        x = mesh_nodes(s)**2 + 1.0_dp
        allocate (y(0:s))
        call apply_assembled(element_mass(1.0_dp / s), x, y)
        do i = 0, s
            write (name, '(a,i0,a,i0)') 'apply_assembled mass s=', s, ' row ', i
            call check_close(trim(name), dot_product(m(i, :), x), y(i), 1e-14_dp)
        end do
        ! int 1 dx = 1: the mass matrix sums to one
        ones = 1.0_dp
        call check_close('sum of mass matrix', 1.0_dp, dot_product(ones, matmul(m, ones)), 1e-14_dp)
        deallocate (y, ones)
        if (s == 3) deallocate (x)
    end do
    x = mesh_nodes(4)
    call check_close('mesh_nodes(4)(1) = 0.25', 0.25_dp, x(1), 0.0_dp)
    call test_summary('test_fe_m')
end program test_fe_m
