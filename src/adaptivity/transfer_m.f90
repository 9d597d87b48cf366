!> Moving a time level from one mesh to the next (remeshing, adaptive_mesh_m) so that the
!> discrete energy of Corollary 6.2 cannot rise: u by nodal interpolation (the H1-seminorm
!> projection in 1D; x = 1, a node of every mesh, keeps u(1)); v, theta, P, q, eta by the L2
!> projection onto the new space (S_h or V_h, with its zero at x = 0 or x = 1), theta and P by
!> the same one; where the new mesh only adds nodes, both are exact interpolation. v with the
!> redistributed mass: in that mass's own terms (velocity_projection). Why each cannot raise
!> the energy: docs/scheme.md, "Adaptive mesh" ("Transfer: the energy cannot rise").
!> Both meshes are given by the integer keys of adaptive_mesh_m (node i at k_i / n_fine).
!> A state and its stepper move to the new mesh by move_state.
module transfer_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use fields_m, only: N_FIELDS, F_V, is_dirichlet
    use fe_m, only: evaluate_p1, apply_mass_graded, add_inertia_difference, inertia_element
    use config_m, only: model_t
    use state_m, only: state_t, set_mesh
    use stepper_m, only: stepper_t
    use errors_m, only: check_allocation
    use adaptive_mesh_m, only: nodes_of_keys
    implicit none
    private
    public :: transfer_level, merge_keys, move_state

contains

    !> The state on the mesh of keys k_old (its level, and the level before of a multistep
    !> scheme) moved onto the mesh of keys k_new (move_level), and the stepper onto it.
    subroutine move_state(k_old, k_new, n_fine, stepper, state)
        integer(int64), intent(in) :: k_old(0:), k_new(0:), n_fine
        type(stepper_t), intent(inout) :: stepper
        type(state_t), intent(inout) :: state

        call move_level(k_old, k_new, n_fine, stepper%model, state%u, state%w)
        if (allocated(state%u_prev)) &
            call move_level(k_old, k_new, n_fine, stepper%model, state%u_prev, state%w_prev)
        call set_mesh(state, nodes_of_keys(k_new, n_fine))
        call stepper%remesh(state)
    end subroutine move_state

    !> One level (u, w) moved from keys k_old to keys k_new (u and w reallocated).
    subroutine move_level(k_old, k_new, n_fine, model, u, w)
        integer(int64), intent(in) :: k_old(0:), k_new(0:), n_fine
        type(model_t), intent(in) :: model
        real(dp), allocatable, intent(inout) :: u(:), w(:, :)
        real(dp), allocatable :: u_new(:), w_new(:, :)
        integer :: stat
        character(len=256) :: message

        allocate (u_new(0:ubound(k_new, 1)), w_new(0:ubound(k_new, 1), N_FIELDS), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the remeshed state')
        call transfer_level(k_old, k_new, n_fine, u, w, u_new, w_new, model)
        call move_alloc(u_new, u)
        call move_alloc(w_new, w)
    end subroutine move_level

    !> (u_new, w_new) = the level (u_old, w_old) on keys k_old moved to keys k_new (module
    !> header); model: the run's model, whose velocity mass (mass_lumped, mass_end_moved) v
    !> is moved in.
    subroutine transfer_level(k_old, k_new, n_fine, u_old, w_old, u_new, w_new, model)
        integer(int64), intent(in) :: k_old(0:), k_new(0:), n_fine
        real(dp), intent(in) :: u_old(0:), w_old(0:, :)
        real(dp), intent(out) :: u_new(0:), w_new(0:, :)
        type(model_t), intent(in) :: model
        real(dp) :: x_old(0:ubound(k_old, 1)), x_new(0:ubound(k_new, 1))
        integer(int64) :: k_union(0:ubound(k_old, 1) + ubound(k_new, 1))
        integer :: f, s_old, s_new, n
        logical :: refinement_only, massless_end

        x_old = nodes_of_keys(k_old, n_fine)
        x_new = nodes_of_keys(k_new, n_fine)
        s_old = ubound(k_old, 1)
        s_new = ubound(k_new, 1)
        call merge_keys(k_old, k_new, k_union, n)
        refinement_only = n == s_new   ! every old key is a new one
        massless_end = model%mass_end_moved .and. min(s_old, s_new) > 1
        u_new = evaluate_p1(x_old, u_old, x_new)
        do f = 1, N_FIELDS
            if (massless_end .and. f == F_V) then
                call velocity_projection(k_old, k_new, n_fine, model%mass_lumped, w_old(:, f), &
                                         w_new(:, f))
                w_new(s_new, f) = w_old(s_old, f)
            else if (refinement_only) then
                w_new(:, f) = evaluate_p1(x_old, w_old(:, f), x_new)
            else
                call l2_projection(k_old, k_new, n_fine, w_old(:, f), f, w_new(:, f))
            end if
        end do
    end subroutine transfer_level

    !> g = the L2 projection of the P1 function f (keys k_old) onto the P1 space of field
    !> `field` on keys k_new: M g = b with b_i = int f phi_i, integrated exactly on the
    !> elements of the union of both meshes (on each, f and phi_i are linear), and g = 0 at
    !> the field's Dirichlet node.
    subroutine l2_projection(k_old, k_new, n_fine, f, field, g)
        integer(int64), intent(in) :: k_old(0:), k_new(0:), n_fine
        real(dp), intent(in) :: f(0:)
        integer, intent(in) :: field
        real(dp), intent(out) :: g(0:)
        real(dp) :: b(0:ubound(k_new, 1)), diag(0:ubound(k_new, 1)), off(ubound(k_new, 1))
        real(dp) :: a, c, fa, fc, xl, xr, pa, pc, len
        integer(int64) :: ka, kc
        integer :: i, j, e, s

        s = ubound(k_new, 1)
        b = 0.0_dp
        ! walk the union of both meshes: [ka, kc] lies in old element i and new element e
        i = 1
        e = 1
        ka = 0
        do while (ka < n_fine)
            kc = min(k_old(i), k_new(e))
            a = real(ka, dp) / real(n_fine, dp)
            c = real(kc, dp) / real(n_fine, dp)
            fa = f(i - 1) + (f(i) - f(i - 1)) * real(ka - k_old(i - 1), dp) &
                 / real(k_old(i) - k_old(i - 1), dp)
            fc = f(i - 1) + (f(i) - f(i - 1)) * real(kc - k_old(i - 1), dp) &
                 / real(k_old(i) - k_old(i - 1), dp)
            ! the hat of the new element's left node at a and c (the right node's is 1 - it)
            xl = real(k_new(e - 1), dp)
            xr = real(k_new(e), dp)
            pa = (xr - real(ka, dp)) / (xr - xl)
            pc = (xr - real(kc, dp)) / (xr - xl)
            len = c - a
            b(e - 1) = b(e - 1) + len / 6.0_dp * (2.0_dp * fa * pa + fa * pc + fc * pa + 2.0_dp * fc * pc)
            b(e) = b(e) + len / 6.0_dp * (2.0_dp * fa * (1.0_dp - pa) + fa * (1.0_dp - pc) + fc * (1.0_dp - pa) &
                                          + 2.0_dp * fc * (1.0_dp - pc))
            ka = kc
            if (kc == k_old(i) .and. i < ubound(k_old, 1)) i = i + 1
            if (kc == k_new(e) .and. e < s) e = e + 1
        end do
        ! the mass matrix of the new mesh (tridiagonal, symmetric positive definite)
        diag = 0.0_dp
        do j = 1, s
            len = real(k_new(j) - k_new(j - 1), dp) / real(n_fine, dp)
            diag(j - 1) = diag(j - 1) + len / 3.0_dp
            diag(j) = diag(j) + len / 3.0_dp
            off(j) = len / 6.0_dp
        end do
        if (is_dirichlet(field, 0, s)) then
            call solve_tridiagonal(diag(1:), off(2:), b(1:), g(1:))
            g(0) = 0.0_dp
        else
            call solve_tridiagonal(diag(:s - 1), off(:s - 1), b(:s - 1), g(:s - 1))
            g(s) = 0.0_dp
        end if
    end subroutine l2_projection

    !> g = the velocity f (keys k_old) moved to keys k_new so that the kinetic energy v^T M_v v
    !> of the redistributed mass (fe_m's inertia_element with `lumped`) cannot rise: f taken
    !> constant on its last element (f_s = f_{s-1}), g sought among such functions (the caller
    !> puts back x = 1's own v), M_v^new g = I_new^T M_v^U I_old f on the union U of both meshes
    !> (I: the interpolation onto U); where the new mesh only adds nodes, g = I_new f. Why:
    !> docs/scheme.md, "Mass redistribution at the contact node" (its adaptive-mesh item).
    subroutine velocity_projection(k_old, k_new, n_fine, lumped, f, g)
        integer(int64), intent(in) :: k_old(0:), k_new(0:), n_fine
        real(dp), intent(in) :: lumped
        real(dp), intent(in) :: f(0:)
        real(dp), intent(out) :: g(0:)
        integer(int64) :: k_union(0:ubound(k_old, 1) + ubound(k_new, 1))
        real(dp) :: f_tied(0:ubound(k_old, 1)), b(0:ubound(k_new, 1))
        real(dp) :: diag(0:ubound(k_new, 1)), off(ubound(k_new, 1))
        real(dp) :: m(2, 2), w
        integer :: s, n, j, e

        s = ubound(k_new, 1)
        f_tied = f
        f_tied(ubound(f, 1)) = f(ubound(f, 1) - 1)
        call merge_keys(k_old, k_new, k_union, n)
        block
            real(dp) :: x_union(0:n), f_union(0:n), y(0:n)

            x_union = nodes_of_keys(k_union(0:n), n_fine)
            f_union = evaluate_p1(nodes_of_keys(k_old, n_fine), f_tied, x_union)
            call apply_mass_graded(x_union(1:n) - x_union(0:n - 1), f_union, y)
            call add_inertia_difference(x_union(1:n) - x_union(0:n - 1), lumped, .true., f_union, y)
            ! b = I_new^T y: each node of U to the two nodes of its new element, by their hats
            b = 0.0_dp
            e = 1
            do j = 0, n
                do while (e < s .and. k_union(j) > k_new(e))
                    e = e + 1
                end do
                w = real(k_union(j) - k_new(e - 1), dp) / real(k_new(e) - k_new(e - 1), dp)
                b(e - 1) = b(e - 1) + (1.0_dp - w) * y(j)
                b(e) = b(e) + w * y(j)
            end do
        end block
        ! M_v on the new mesh; the unknown g_{s-1} = g_s (row and column s added to s - 1); g_0 = 0
        diag = 0.0_dp
        do e = 1, s
            m = inertia_element(real(k_new(e) - k_new(e - 1), dp) / real(n_fine, dp), &
                                lumped, .true., e == s)
            diag(e - 1) = diag(e - 1) + m(1, 1)
            diag(e) = diag(e) + m(2, 2)
            off(e) = m(1, 2)
        end do
        diag(s - 1) = diag(s - 1) + diag(s) + 2.0_dp * off(s)
        b(s - 1) = b(s - 1) + b(s)
        call solve_tridiagonal(diag(1:s - 1), off(2:s - 1), b(1:s - 1), g(1:s - 1))
        g(0) = 0.0_dp
        g(s) = g(s - 1)
    end subroutine velocity_projection

    !> k(0:n) = the increasing union of the increasing keys a and b (each key once), which end
    !> on the same key (n_fine: both meshes end at x = 1), so that neither runs out first.
    pure subroutine merge_keys(a, b, k, n)
        integer(int64), intent(in) :: a(0:), b(0:)
        integer(int64), intent(out) :: k(0:)
        integer, intent(out) :: n
        integer :: i, j

        i = 0
        j = 0
        n = -1
        do while (i <= ubound(a, 1))
            n = n + 1
            k(n) = min(a(i), b(j))
            if (a(i) == k(n)) i = i + 1
            if (b(j) == k(n)) j = j + 1
        end do
    end subroutine merge_keys

    !> x = A^{-1} b for the symmetric tridiagonal A with diagonal d(1:n), off-diagonal o(1:n-1)
    !> (positive definite: elimination without pivoting is stable).
    pure subroutine solve_tridiagonal(d, o, b, x)
        real(dp), intent(in) :: d(:), o(:), b(:)
        real(dp), intent(out) :: x(:)
        real(dp) :: pivot(size(d)), y(size(d))
        integer :: j, n

        n = size(d)
        pivot(1) = d(1)
        y(1) = b(1)
        do j = 2, n
            pivot(j) = d(j) - o(j - 1)**2 / pivot(j - 1)
            y(j) = b(j) - o(j - 1) / pivot(j - 1) * y(j - 1)
        end do
        x(n) = y(n) / pivot(n)
        do j = n - 1, 1, -1
            x(j) = (y(j) - o(j) * x(j + 1)) / pivot(j)
        end do
    end subroutine solve_tridiagonal

end module transfer_m
