!> The stress of (2.14), sigma = alpha u_x + varpi u_xt - gamma1 theta - gamma2 P, of a
!> discrete level at the nodes of its mesh (written as /snapshots/sigma, docs/output.md).
module stress_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fields_m, only: F_V, F_THETA, F_P
    use mesh_m, only: mesh_t
    implicit none
    private
    public :: nodal_stress

contains

    !> sigma at the nodes 0..s of the level (u, w) on mesh. u_x and v_x (= u_xt, as in the
    !> viscous term of (6.1)) are constant on each element; at an inner node they are the
    !> lumped-mass L2 projection of those constants, the average of the two elements' values
    !> weighted by their lengths, (f(i+1) - f(i-1)) / (x(i+1) - x(i-1)); at the ends the one
    !> element's value. theta and P are the nodal values.
    pure function nodal_stress(model, u, w, mesh) result(sigma)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: u(0:)
        real(dp), intent(in) :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp) :: sigma(0:ubound(u, 1))
        integer :: s, i, left, right

        s = ubound(u, 1)
        do i = 0, s
            left = max(i - 1, 0)
            right = min(i + 1, s)
            associate (dx => mesh%x(right) - mesh%x(left))
                sigma(i) = model%alpha * (u(right) - u(left)) / dx &
                           + model%varpi * (w(right, F_V) - w(left, F_V)) / dx &
                           - model%gamma1 * w(i, F_THETA) - model%gamma2 * w(i, F_P)
            end associate
        end do
    end function nodal_stress

end module stress_m
