!> The fully discrete problem (6.1): implicit Euler in time, P1 elements in space, derived
!> from the variational form (not from the block form printed in Section 7, which has typos).
!>
!> Unknowns at t_n: v, q, eta in S_h (zero at x=0) and theta, P in V_h (zero at x=1); the
!> displacement is u^n = u^{n-1} + dt v^n. Each equation of (6.1) is tested with the basis
!> function of its own unknown's space and multiplied by dt; (6.1)_5 is also multiplied by
!> hbar. With that scaling x^T A x is the discrete energy dissipation (Theorem 6.1): the
!> coupling blocks come in pairs that are negatives of each other's transpose.
!>
!> Row (equation) r, column (unknown) c, element matrices Me (mass), Ke (stiffness) and
!> Ge(a,b) = int phi_a phi_b' (see fe_m):
!>   (6.1)_1 v    : v: rho Me + dt (varpi + dt alpha) Ke;  theta: -dt gamma1 Ge^T;  P: -dt gamma2 Ge^T
!>                  rhs: rho Me v^{n-1} - dt alpha Ke u^{n-1} - (dt/eps)[u^n(1)-g]_+ e_s
!>   (6.1)_2 theta: theta: c Me;  P: d Me;  q: dt Ge;  v: dt gamma1 Ge
!>                  rhs: Me (c theta^{n-1} + d P^{n-1})
!>   (6.1)_3 q    : q: (tau0 + dt) Me;  theta: dt Ge                  rhs: tau0 Me q^{n-1}
!>   (6.1)_4 P    : theta: d Me;  P: r Me;  eta: dt hbar Ge;  v: dt gamma2 Ge
!>                  rhs: Me (d theta^{n-1} + r P^{n-1})
!>   (6.1)_5 eta  : eta: hbar (tau + dt) Me;  P: dt hbar Ge          rhs: hbar tau Me eta^{n-1}
!> The contact term is the only nonlinearity; it acts on the v equation at node s only and
!> is handled by the solution methods (stepper_m), never assembled here.
module scheme_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fe_m, only: element_mass, element_stiffness, element_gradient, apply_assembled
    use banded_m, only: band_t
    implicit none
    private
    public :: N_FIELDS, F_Q, F_THETA, F_V, F_P, F_ETA, FIELD_NAMES
    public :: MONOLITHIC_SLOTS, THERMAL_SLOTS, MECHANICAL_SLOTS
    public :: element_block, is_dirichlet, band_width, assemble_matrix
    public :: old_state_rhs, add_lagged_coupling, gather_fields, scatter_fields

    !> Field order within a node. The coupling graph (q-theta, theta-v, theta-P, v-P, P-eta)
    !> is a triangle theta-v-P with q and eta hanging off theta and P; the order q, theta, v,
    !> P, eta puts every coupled pair at most 2 slots apart, so the interleaved system has
    !> kl = ku = 5 + 2 = 7 (an arbitrary order needs up to 9).
    integer, parameter :: N_FIELDS = 5
    integer, parameter :: F_Q = 1, F_THETA = 2, F_V = 3, F_P = 4, F_ETA = 5
    character(len=5), parameter :: FIELD_NAMES(N_FIELDS) = ['q    ', 'theta', 'v    ', 'P    ', 'eta  ']

    !> Slot of each field within a node for the three systems (0: field not in the system).
    !> monolithic: all five fields; the paper's Section 7 splitting: a thermal block
    !> (q, theta, P, eta; kl = ku = 4 + 1 = 5) and a mechanical block (v; tridiagonal).
    integer, parameter :: MONOLITHIC_SLOTS(N_FIELDS) = [1, 2, 3, 4, 5]
    integer, parameter :: THERMAL_SLOTS(N_FIELDS) = [1, 2, 0, 3, 4]
    integer, parameter :: MECHANICAL_SLOTS(N_FIELDS) = [0, 0, 1, 0, 0]

contains

    !> Element matrix of the block (equation row, unknown col) of (6.1), scaled as in the
    !> module header; zero where the equation does not involve the unknown.
    pure function element_block(model, h, dt, row, col) result(m)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: h, dt
        integer, intent(in) :: row, col
        real(dp) :: m(2, 2)
        real(dp) :: me(2, 2), ke(2, 2), ge(2, 2)

        me = element_mass(h)
        ke = element_stiffness(h)
        ge = element_gradient()
        m = 0.0_dp
        select case (row)
        case (F_V)        ! (6.1)_1, equation of motion; int (... - gamma1 theta - gamma2 P) w_x
            select case (col)
            case (F_V); m = model%rho * me + dt * (model%varpi + dt * model%alpha) * ke
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

    !> Is (field, node) a Dirichlet value? v, q, eta vanish at x=0 (S_h); theta, P at x=1 (V_h).
    pure logical function is_dirichlet(field, node, s)
        integer, intent(in) :: field, node, s

        select case (field)
        case (F_V, F_Q, F_ETA); is_dirichlet = node == 0
        case default; is_dirichlet = node == s
        end select
    end function is_dirichlet

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

    !> Does equation `row` of (6.1) involve unknown `col`?
    pure logical function couples(row, col)
        integer, intent(in) :: row, col
        type(model_t) :: unit_model

        unit_model = model_t(rho=1.0_dp, alpha=1.0_dp, varpi=1.0_dp, gamma1=1.0_dp, gamma2=1.0_dp, &
                             c=1.0_dp, d=1.0_dp, r=1.0_dp, hbar=1.0_dp, tau0=1.0_dp, tau=1.0_dp)
        couples = any(element_block(unit_model, 1.0_dp, 1.0_dp, row, col) /= 0.0_dp)
    end function couples

    !> Assemble the matrix of (6.1) restricted to the fields with slots(f) > 0, nodes
    !> interleaved: unknown (node i, field f) is row/column nf*i + slots(f), nf = count(slots>0).
    !> Dirichlet unknowns get identity rows. The contact term is not included.
    subroutine assemble_matrix(model, s, dt, slots, a)
        type(model_t), intent(in) :: model
        integer, intent(in) :: s
        real(dp), intent(in) :: dt
        integer, intent(in) :: slots(N_FIELDS)
        type(band_t), intent(inout) :: a
        integer :: nf, kw, e, row, col, ia, ib
        real(dp) :: m(2, 2), h

        nf = count(slots > 0)
        kw = band_width(slots)
        h = 1.0_dp / real(s, dp)
        call a%init(nf * (s + 1), kw, kw)
        do e = 1, s
            do row = 1, N_FIELDS
                if (slots(row) == 0) cycle
                do col = 1, N_FIELDS
                    if (slots(col) == 0) cycle
                    m = element_block(model, h, dt, row, col)
                    if (all(m == 0.0_dp)) cycle
                    do ia = 1, 2
                        do ib = 1, 2
                            call a%add(nf * (e - 2 + ia) + slots(row), nf * (e - 2 + ib) + slots(col), m(ia, ib))
                        end do
                    end do
                end do
            end do
        end do
        do row = 1, N_FIELDS
            if (slots(row) == 0) cycle
            if (is_dirichlet(row, 0, s)) call a%set_identity_row(slots(row))
            if (is_dirichlet(row, s, s)) call a%set_identity_row(nf * s + slots(row))
        end do
    end subroutine assemble_matrix

    !> Right-hand side of (6.1) from the previous time level (module header), field-major:
    !> b(:, f) is the right-hand side of the equation of field f. Dirichlet rows are zero.
    !> The contact term is not included. No allocation: called every time step.
    subroutine old_state_rhs(model, dt, u_old, w_old, b, work)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: dt
        real(dp), intent(in) :: u_old(0:)          !< u^{n-1}
        real(dp), intent(in) :: w_old(0:, :)       !< fields at t_{n-1}, w_old(:, f)
        real(dp), intent(out) :: b(0:, :)
        real(dp), intent(inout) :: work(0:)        !< scratch of size s+1
        integer :: s
        real(dp) :: h, me(2, 2), ke(2, 2)

        s = ubound(u_old, 1)
        h = 1.0_dp / real(s, dp)
        me = element_mass(h)
        ke = element_stiffness(h)
        ! (6.1)_1: rho Me v^{n-1} - dt alpha Ke u^{n-1}
        call apply_assembled(me, w_old(:, F_V), b(:, F_V))
        call apply_assembled(ke, u_old, work)
        b(:, F_V) = model%rho * b(:, F_V) - dt * model%alpha * work
        ! (6.1)_2: Me (c theta^{n-1} + d P^{n-1})
        work = model%c * w_old(:, F_THETA) + model%d * w_old(:, F_P)
        call apply_assembled(me, work, b(:, F_THETA))
        ! (6.1)_3: tau0 Me q^{n-1}
        call apply_assembled(me, w_old(:, F_Q), b(:, F_Q))
        b(:, F_Q) = model%tau0 * b(:, F_Q)
        ! (6.1)_4: Me (d theta^{n-1} + r P^{n-1})
        work = model%d * w_old(:, F_THETA) + model%r * w_old(:, F_P)
        call apply_assembled(me, work, b(:, F_P))
        ! (6.1)_5 times hbar: hbar tau Me eta^{n-1}
        call apply_assembled(me, w_old(:, F_ETA), b(:, F_ETA))
        b(:, F_ETA) = model%hbar * model%tau * b(:, F_ETA)
        call zero_dirichlet_rows(b)
    end subroutine old_state_rhs

    !> b(:, row) -= (block (row, col) of (6.1)) * w(:, col) for every coupling from a field
    !> in the system (slots > 0) to one outside it (slots == 0): the lagged terms of the
    !> paper's Section 7 splitting moved to the right-hand side. Dirichlet rows stay zero.
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
                if (all(m == 0.0_dp)) cycle
                call apply_assembled(m, w(:, col), work)
                b(:, row) = b(:, row) - work
            end do
        end do
        call zero_dirichlet_rows(b)
    end subroutine add_lagged_coupling

    pure subroutine zero_dirichlet_rows(b)
        real(dp), intent(inout) :: b(0:, :)
        integer :: f, s

        s = ubound(b, 1)
        do f = 1, N_FIELDS
            if (is_dirichlet(f, 0, s)) b(0, f) = 0.0_dp
            if (is_dirichlet(f, s, s)) b(s, f) = 0.0_dp
        end do
    end subroutine zero_dirichlet_rows

    !> Interleave field-major w(0:s, f) into the system vector x (fields with slots > 0).
    pure subroutine scatter_fields(slots, w, x)
        integer, intent(in) :: slots(N_FIELDS)
        real(dp), intent(in) :: w(0:, :)
        real(dp), intent(out) :: x(:)
        integer :: f, nf, i

        nf = count(slots > 0)
        do f = 1, N_FIELDS
            if (slots(f) == 0) cycle
            do i = 0, ubound(w, 1)
                x(nf * i + slots(f)) = w(i, f)
            end do
        end do
    end subroutine scatter_fields

    !> Inverse of scatter_fields: copy the system vector x into the fields it holds.
    pure subroutine gather_fields(slots, x, w)
        integer, intent(in) :: slots(N_FIELDS)
        real(dp), intent(in) :: x(:)
        real(dp), intent(inout) :: w(0:, :)
        integer :: f, nf, i

        nf = count(slots > 0)
        do f = 1, N_FIELDS
            if (slots(f) == 0) cycle
            do i = 0, ubound(w, 1)
                w(i, f) = x(nf * i + slots(f))
            end do
        end do
    end subroutine gather_fields

end module scheme_m
