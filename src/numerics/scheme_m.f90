!> The fully discrete problem (6.1): implicit Euler in time, P1 elements in space, derived
!> from the variational form (not from the block form printed in Section 7, which has typos).
!> Unknowns at t_n: v, q, eta in S_h (zero at x=0), theta, P in V_h (zero at x=1); u^n =
!> u^{n-1} + dt v^n. Each equation of (6.1) is tested with its own unknown's basis functions
!> and multiplied by dt ((6.1)_5 also by hbar), so that x^T A x is the dissipation of
!> Theorem 6.1: every coupling block comes with its negative transpose. A change must keep
!> that pairing (the contact compliance's sign and the block LU's pivots rest on it). The
!> blocks, right-hand sides and why: docs/scheme.md, "The linear system of one time step".
!> The contact term, the only nonlinearity, acts on the v equation at node s only and is
!> handled by the solution methods (stepper_m), never assembled here.
module scheme_m
    use kinds_m, only: dp
    use reals_m, only: equal, is_zero
    use config_m, only: model_t, config_t
    use fe_m, only: element_mass, element_stiffness, element_gradient, apply_assembled, inertia_element, &
                    add_inertia_difference
    use mesh_m, only: mesh_t
    use banded_m, only: band_t
    use fields_m, only: N_FIELDS, F_Q, F_THETA, F_V, F_P, F_ETA, is_dirichlet, zero_dirichlet
    use errors_m, only: check_allocation
    implicit none
    private
    public :: element_block, band_width, assemble_matrix, assemble_blocks, active_fields
    public :: old_state_rhs, add_lagged_coupling, initial_data_present

contains

    !> Element matrix of the block (equation row, unknown col) of (6.1), scaled as in the
    !> module header; zero where the equation does not involve the unknown. last: the element
    !> holds the contact node x = 1 (the velocity's mass of &contact mass = 'redistributed'
    !> differs there: fe_m's inertia_element).
    pure function element_block(model, h, dt, row, col, last) result(m)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: h, dt
        integer, intent(in) :: row, col
        logical, intent(in), optional :: last
        real(dp) :: m(2, 2)
        real(dp) :: me(2, 2), ke(2, 2), ge(2, 2)
        logical :: is_last

        is_last = .false.
        if (present(last)) is_last = last
        me = element_mass(h)
        ke = element_stiffness(h)
        ge = element_gradient()
        m = 0.0_dp
        select case (row)
        case (F_V)        ! (6.1)_1, equation of motion; int (... - gamma1 theta - gamma2 P) w_x
            select case (col)
            case (F_V); m = model%rho * inertia_element(h, model%mass_lumped, model%mass_end_moved, is_last) &
                            + dt * (model%varpi + dt * model%alpha) * ke
            case (F_THETA); m = -dt * model%gamma1 * transpose(ge)
            case (F_P); m = -dt * model%gamma2 * transpose(ge)
            end select
        case (F_THETA)    ! (6.1)_2, energy balance; int (c theta_t + d P_t + q_x + gamma1 v_x) vartheta
            select case (col)
            case (F_THETA); m = model%c * me
            case (F_P); m = model%d * me
            case (F_Q); m = dt * ge
            case (F_V); m = dt * model%gamma1 * ge
            end select
        case (F_Q)        ! (6.1)_3, Cattaneo law for q; int (tau0 q_t + q + theta_x) phi
            select case (col)
            case (F_Q); m = (model%tau0 + dt) * me
            case (F_THETA); m = dt * ge
            end select
        case (F_P)        ! (6.1)_4, mass balance; int (r P_t + d theta_t + hbar eta_x + gamma2 v_x) z
            select case (col)
            case (F_THETA); m = model%d * me
            case (F_P); m = model%r * me
            case (F_ETA); m = dt * model%hbar * ge
            case (F_V); m = dt * model%gamma2 * ge
            end select
        case (F_ETA)      ! (6.1)_5 times hbar, Cattaneo law for eta; int (tau eta_t + eta + P_x) psi
            select case (col)
            case (F_ETA); m = model%hbar * (model%tau + dt) * me
            case (F_P); m = dt * model%hbar * ge
            end select
        end select
    end function element_block

    !> Half-bandwidth (kl = ku) of a system with the given slots: one node's worth of slots
    !> plus the largest slot distance between two coupled fields of the system.
    pure integer function band_width(slots)
        integer, intent(in) :: slots(N_FIELDS)
        integer :: row, col

        band_width = count(slots > 0)
        do row = 1, N_FIELDS
            do col = 1, N_FIELDS
                if (slots(row) > 0 .and. slots(col) > 0 .and. couples(row, col)) &
                    band_width = max(band_width, count(slots > 0) + abs(slots(row) - slots(col)))
            end do
        end do
    end function band_width

    !> Does equation `row` of (6.1) involve unknown `col` (for some coefficients, or for the
    !> given model)?
    pure logical function couples(row, col, model)
        integer, intent(in) :: row, col
        type(model_t), intent(in), optional :: model
        type(model_t) :: m

        m = model_t(rho=1.0_dp, alpha=1.0_dp, varpi=1.0_dp, gamma1=1.0_dp, gamma2=1.0_dp, &
                    c=1.0_dp, d=1.0_dp, r=1.0_dp, hbar=1.0_dp, tau0=1.0_dp, tau=1.0_dp)
        if (present(model)) m = model
        couples = .not. all(is_zero(element_block(m, 1.0_dp, 1.0_dp, row, col)))
    end function couples

    !> The fields that can be nonzero: v (moved by the initial velocity, the contact force and
    !> every coupling) and every field coupled to it through the model's nonzero coefficients,
    !> plus any group of fields not coupled to v whose initial data (has_data) are not all
    !> zero. A group of fields with zero data and no coupling to the rest stays zero for all
    !> time ((6.1) is linear in it and homogeneous), so it is left out of the system (e.g.
    !> P and eta of a thermoelastic scene with gamma2 = d = 0 and P0 = eta0 = 0).
    pure function active_fields(model, has_data) result(active)
        type(model_t), intent(in) :: model
        logical, intent(in) :: has_data(N_FIELDS)   !< nonzero initial data or sources
        logical :: active(N_FIELDS)
        logical :: linked(N_FIELDS, N_FIELDS)
        integer :: f, g, k

        do f = 1, N_FIELDS
            do g = 1, N_FIELDS
                linked(f, g) = f == g .or. couples(f, g, model) .or. couples(g, f, model)
            end do
        end do
        ! transitive closure (Warshall): linked(f, g) iff f and g are in one group
        do k = 1, N_FIELDS
            do f = 1, N_FIELDS
                do g = 1, N_FIELDS
                    linked(f, g) = linked(f, g) .or. (linked(f, k) .and. linked(k, g))
                end do
            end do
        end do
        do f = 1, N_FIELDS
            active(f) = linked(f, F_V) .or. any(linked(f, :) .and. has_data)
        end do
    end function active_fields

    !> Which fields have nonzero initial data (a field with none may be left out: active_fields).
    pure function initial_data_present(cfg) result(has_data)
        type(config_t), intent(in) :: cfg
        logical :: has_data(N_FIELDS)

        associate (init => cfg%initial)
            has_data(F_V) = .true.
            has_data(F_Q) = .not. all(is_zero(init%q0_poly)) .or. allocated(init%q0_table)
            has_data(F_THETA) = .not. (all(is_zero(init%theta0_poly)) .and. is_zero(init%theta0_step(1))) &
                                .or. allocated(init%theta0_table)
            has_data(F_P) = .not. (all(is_zero(init%p0_poly)) .and. is_zero(init%p0_step(1))) &
                            .or. allocated(init%p0_table)
            has_data(F_ETA) = .not. all(is_zero(init%eta0_poly)) .or. allocated(init%eta0_table)
        end associate
    end function initial_data_present

    !> The matrix of (6.1) restricted to the fields with slots(f) > 0 as a band (the check
    !> and fallback of the block LU, and the paper's Section 7 blocks), nodes interleaved:
    !> unknown (node i, field f) is row/column nf*i + slots(f), nf = count(slots>0). The
    !> entries are assemble_blocks' (Dirichlet unknowns with identity rows, no contact term).
    subroutine assemble_matrix(model, mesh, dt, slots, a)
        type(model_t), intent(in) :: model
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(in) :: dt
        integer, intent(in) :: slots(N_FIELDS)
        type(band_t), intent(inout) :: a
        real(dp), allocatable :: d(:, :, :)
        integer :: nf, kw, s, i, row, col, r, c
        integer :: stat
        character(len=256) :: message

        s = mesh%s()
        nf = count(slots > 0)
        kw = band_width(slots)
        allocate (d(N_FIELDS, N_FIELDS, 0:3 * s), stat=stat, errmsg=message)   ! D_i, then E_i and F_i
        call check_allocation(stat, message, 'the blocks of the band')
        call assemble_blocks(model, mesh, dt, d(:, :, :s), d(:, :, s + 1:2 * s), d(:, :, 2 * s + 1:))
        call a%init(nf * (s + 1), kw, kw)
        do i = 0, s
            do col = 1, N_FIELDS
                do row = 1, N_FIELDS
                    if (slots(row) == 0 .or. slots(col) == 0) cycle
                    r = nf * i + slots(row)
                    c = nf * i + slots(col)
                    call a%add(r, c, d(row, col, i))
                    ! E_i, F_i: entries outside the band are zero (band_width)
                    if (i == s .or. abs(r - c) + nf > kw) cycle
                    call a%add(r, c + nf, d(row, col, s + 1 + i))
                    call a%add(r + nf, c, d(row, col, 2 * s + 1 + i))
                end do
            end do
        end do
    end subroutine assemble_matrix

    !> The matrix of (6.1) with every field as its node blocks (block_tridiagonal_m's factor;
    !> assemble_matrix's band): d(:, :, i) = D_i (node i), e(:, :, i) = E_i (row node i,
    !> column node i+1), f(:, :, i) = F_i (row node i+1, column node i), each s+1 (d) or s
    !> (e, f) blocks. D_i is the sum of the element on its left and then the element on its
    !> right, starting at +0. Element blocks are computed again only where the element size
    !> changes (and for the contact node's element). Dirichlet unknowns get identity rows.
    subroutine assemble_blocks(model, mesh, dt, d, e, f)
        type(model_t), intent(in) :: model
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(in) :: dt
        !> (N_FIELDS, N_FIELDS, 0:)
        real(dp), intent(out), contiguous :: d(:, :, 0:), e(:, :, 0:), f(:, :, 0:)
        real(dp), parameter :: ZERO(N_FIELDS, N_FIELDS) = 0.0_dp
        real(dp) :: h_e, m(2, 2), m11(N_FIELDS, N_FIELDS), m12(N_FIELDS, N_FIELDS), m21(N_FIELDS, N_FIELDS), &
                    m22(N_FIELDS, N_FIELDS)
        integer :: s, el, row, col

        s = mesh%s()
        h_e = 0.0_dp
        d(:, :, 0) = ZERO
        do el = 1, s
            if (el == 1 .or. el == s .or. .not. equal(mesh%h(el), h_e)) then
                h_e = mesh%h(el)
                do col = 1, N_FIELDS
                    do row = 1, N_FIELDS
                        m = element_block(model, h_e, dt, row, col, last=el == s)
                        m11(row, col) = m(1, 1)
                        m21(row, col) = m(2, 1)
                        m12(row, col) = m(1, 2)
                        m22(row, col) = m(2, 2)
                    end do
                end do
                m12 = ZERO + m12   ! -0 as +0, as a sum into a zero matrix gives
                m21 = ZERO + m21
                m22 = ZERO + m22
            end if
            d(:, :, el - 1) = d(:, :, el - 1) + m11
            d(:, :, el) = m22
            e(:, :, el - 1) = m12
            f(:, :, el - 1) = m21
        end do
        call dirichlet_blocks(s, d, e, f)
    end subroutine assemble_blocks

    !> assemble_blocks' Dirichlet unknowns as identity rows (assemble_matrix's too): the row
    !> and column of (node 0, field) in D_0, E_0, F_0 and of (node s, field) in D_s, F_{s-1},
    !> E_{s-1} zero, the diagonal entry 1.
    pure subroutine dirichlet_blocks(s, d, e, f)
        integer, intent(in) :: s
        real(dp), intent(inout) :: d(:, :, 0:), e(:, :, 0:), f(:, :, 0:)
        integer :: row

        do row = 1, N_FIELDS
            if (is_dirichlet(row, 0, s)) then
                d(row, :, 0) = 0.0_dp
                d(:, row, 0) = 0.0_dp
                e(row, :, 0) = 0.0_dp
                f(:, row, 0) = 0.0_dp
                d(row, row, 0) = 1.0_dp
            end if
            if (is_dirichlet(row, s, s)) then
                d(row, :, s) = 0.0_dp
                d(:, row, s) = 0.0_dp
                f(row, :, s - 1) = 0.0_dp
                e(:, row, s - 1) = 0.0_dp
                d(row, row, s) = 1.0_dp
            end if
        end do
    end subroutine dirichlet_blocks

    !> Right-hand side of (6.1) from the previous time level (docs/scheme.md's table) of the fields
    !> with slots(f) > 0: y(i, f), the right-hand side of field f's equation at node i (a
    !> column each, contiguous, so they vectorise; the caller zeroes the Dirichlet rows and
    !> interleaves them into the system vector: slots_m's scatter_fields). The contact term is
    !> not included. No allocation: called every time step. mesh: the mesh of the level (its
    !> mass and stiffness matrices).
    subroutine old_state_rhs(model, dt, u_old, w_old, slots, y, work, mesh)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: dt
        real(dp), intent(in) :: u_old(0:)          !< u^{n-1}
        real(dp), intent(in) :: w_old(0:, :)       !< fields at t_{n-1}, w_old(:, f)
        integer, intent(in) :: slots(N_FIELDS)
        real(dp), intent(out) :: y(0:ubound(u_old, 1), N_FIELDS)   !< field f's equation
        real(dp), intent(out) :: work(0:ubound(u_old, 1))           !< scratch
        type(mesh_t), intent(in) :: mesh

        ! (6.1)_1: rho Me v^{n-1} - dt alpha Ke u^{n-1}
        call mesh%apply_mass(w_old(:, F_V), y(:, F_V))
        if (model%mass_end_moved .or. model%mass_lumped > 0.0_dp) &
            call add_inertia_difference(mesh%h, model%mass_lumped, model%mass_end_moved, w_old(:, F_V), &
                                        y(:, F_V))
        call mesh%apply_stiffness(u_old, work)
        y(:, F_V) = model%rho * y(:, F_V) - dt * model%alpha * work
        if (slots(F_THETA) > 0) then   ! (6.1)_2: Me (c theta^{n-1} + d P^{n-1})
            work = model%c * w_old(:, F_THETA) + model%d * w_old(:, F_P)
            call mesh%apply_mass(work, y(:, F_THETA))
        end if
        if (slots(F_Q) > 0) then       ! (6.1)_3: tau0 Me q^{n-1}
            call mesh%apply_mass(w_old(:, F_Q), y(:, F_Q))
            y(:, F_Q) = model%tau0 * y(:, F_Q)
        end if
        if (slots(F_P) > 0) then       ! (6.1)_4: Me (d theta^{n-1} + r P^{n-1})
            work = model%d * w_old(:, F_THETA) + model%r * w_old(:, F_P)
            call mesh%apply_mass(work, y(:, F_P))
        end if
        if (slots(F_ETA) > 0) then     ! (6.1)_5 times hbar: hbar tau Me eta^{n-1}
            call mesh%apply_mass(w_old(:, F_ETA), y(:, F_ETA))
            y(:, F_ETA) = model%hbar * model%tau * y(:, F_ETA)
        end if
    end subroutine old_state_rhs

    !> b(:, row) -= (block (row, col) of (6.1)) * w(:, col) for every coupling from a field
    !> in the system (slots > 0) to one outside it (slots == 0): the lagged terms of the
    !> paper's Section 7 splitting moved to the right-hand side. Dirichlet rows stay zero.
    !> Uniform mesh only (validate_m refuses the paper's method on an adaptive mesh).
    subroutine add_lagged_coupling(model, dt, slots, w, b, work)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: dt
        integer, intent(in) :: slots(N_FIELDS)
        real(dp), intent(in) :: w(0:, :)
        real(dp), intent(inout) :: b(0:, :)
        real(dp), intent(inout) :: work(0:)
        integer :: row, col
        real(dp) :: m(2, 2), h

        h = 1.0_dp / real(ubound(w, 1), dp)
        do row = 1, N_FIELDS
            if (slots(row) == 0) cycle
            do col = 1, N_FIELDS
                if (slots(col) /= 0) cycle
                m = element_block(model, h, dt, row, col)
                if (all(is_zero(m))) cycle
                call apply_assembled(m, w(:, col), work)
                b(:, row) = b(:, row) - work
            end do
        end do
        call zero_dirichlet(b)
    end subroutine add_lagged_coupling

end module scheme_m
