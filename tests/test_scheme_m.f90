!> The monolithic system of (6.1) against an independent dense assembly written straight
!> from the variational form with quadrature integrals (tests/lib/quadrature_m):
!>  1. every block of the assembled band matrix equals the reference block times the row
!>     scaling of scheme_m (dt, and dt*hbar for (6.1)_5), on 3 and 4 element meshes;
!>  2. one time step of the monolithic banded solver and of the paper iteration equals the
!>     dense semismooth-Newton solution of the same step, with and without active contact;
!>  3. assemble_blocks gives the node blocks of assemble_matrix's band bit for bit, with every
!>     field and with fields left out (uniform and graded meshes, consistent and redistributed
!>     mass).
program test_scheme_m
    use, intrinsic :: iso_fortran_env, only: int64
    use kinds_m, only: dp
    use config_m, only: config_t, model_t
    use banded_m, only: band_t
    use band_reference_m, only: band_entry, band_to_dense
    use fields_m, only: N_FIELDS, F_Q, F_THETA, F_V, F_P, F_ETA, FIELDS, is_dirichlet
    use scheme_m, only: assemble_matrix, assemble_blocks, band_width
    use slots_m, only: MONOLITHIC_SLOTS, THERMAL_SLOTS, MECHANICAL_SLOTS, slots_of
    use state_m, only: state_t
    use mesh_m, only: mesh_t
    use meshes_m, only: uniform_mesh, graded_mesh
    use stepper_m, only: stepper_t, step_result_t
    use quadrature_m, only: integrate_product
    use testing_m, only: check_close, check_true, test_summary
    implicit none
    interface
        subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: dp
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgesv
    end interface
    type(model_t) :: model
    integer :: s

    call check_true('monolithic half-bandwidth is 7', band_width(MONOLITHIC_SLOTS) == 7)
    call check_true('thermal half-bandwidth is 5', band_width(THERMAL_SLOTS) == 5)
    call check_true('mechanical half-bandwidth is 1', band_width(MECHANICAL_SLOTS) == 1)

    model = model_t(rho=0.7_dp, alpha=1.3_dp, varpi=0.2_dp, gamma1=0.4_dp, gamma2=0.3_dp, c=1.1_dp, &
                    d=0.25_dp, r=0.6_dp, hbar=0.8_dp, tau0=0.05_dp, tau=0.3_dp)
    do s = 3, 4
        call check_blocks(model, s, 0.01_dp)
    end do
    call check_blocks(model_t(), 4, 1.0e-4_dp)        ! the paper's (7.1) values

    call check_step(model, 4, 0.01_dp, contact=.false.)
    call check_step(model, 4, 0.01_dp, contact=.true.)
    call check_step(model_t(), 4, 1.0e-4_dp, contact=.false.)
    call check_step(model_t(), 4, 1.0e-4_dp, contact=.true.)

    call check_node_blocks('uniform, s = 7', model, uniform_mesh(7), 0.01_dp)
    call check_node_blocks('uniform, s = 500, (7.1)', model_t(), uniform_mesh(500), 1.0e-3_dp)
    call check_node_blocks('graded', model, graded_mesh([0.0_dp, 0.25_dp, 0.5_dp, 0.625_dp, 0.75_dp, 0.8125_dp, &
                                                         0.875_dp, 0.9375_dp, 1.0_dp]), 0.02_dp)
    model%mass_lumped = 7.0_dp / 16.0_dp       ! &contact mass = 'redistributed' (config_m)
    model%mass_end_moved = .true.
    call check_node_blocks('uniform, redistributed mass', model, uniform_mesh(6), 0.01_dp)
    call test_summary('test_scheme_m')

contains

    !> assemble_blocks against the blocks of assemble_matrix's band, every entry bit for bit:
    !> with every field, and with fields left out (the band of slots_of(active) against the
    !> rows and columns of the active fields, which stepper_m factors).
    subroutine check_node_blocks(label, model, mesh, dt)
        character(len=*), intent(in) :: label
        type(model_t), intent(in) :: model
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(in) :: dt
        logical, parameter :: ACTIVE(N_FIELDS, 2) = reshape([.true., .true., .true., .true., .true., &
                                                             .true., .true., .true., .false., .false.], [N_FIELDS, 2])
        type(band_t) :: a
        real(dp), allocatable :: d(:, :, :), e(:, :, :), f(:, :, :)
        integer :: s, i, r, c, n_diff, k, slots(N_FIELDS)

        s = mesh%s()
        allocate (d(N_FIELDS, N_FIELDS, 0:s), e(N_FIELDS, N_FIELDS, 0:s - 1), f(N_FIELDS, N_FIELDS, 0:s - 1))
        call assemble_blocks(model, mesh, dt, d, e, f)
        do k = 1, 2
            slots = slots_of(ACTIVE(:, k))
            call assemble_matrix(model, mesh, dt, slots, a)
            n_diff = 0
            do i = 0, s
                do c = 1, N_FIELDS
                    do r = 1, N_FIELDS
                        if (slots(r) == 0 .or. slots(c) == 0) cycle
                        if (.not. same_bits(d(r, c, i), band_entry(a, at(slots, i, r), at(slots, i, c)))) &
                            n_diff = n_diff + 1
                        if (i == s) cycle
                        if (.not. same_bits(e(r, c, i), band_entry(a, at(slots, i, r), at(slots, i + 1, c)))) &
                            n_diff = n_diff + 1
                        if (.not. same_bits(f(r, c, i), band_entry(a, at(slots, i + 1, r), at(slots, i, c)))) &
                            n_diff = n_diff + 1
                    end do
                end do
            end do
            call check_true('assemble_blocks = the band''s blocks bit for bit, '//label// &
                            trim(merge(' (every field)    ', ' (fields left out)', k == 1)), n_diff == 0)
        end do
    end subroutine check_node_blocks

    !> The row of (node, field) in the band of slots.
    pure integer function at(slots, node, field)
        integer, intent(in) :: slots(N_FIELDS), node, field

        at = count(slots > 0) * node + slots(field)
    end function at

    !> x and y are the same double (sign of zero included).
    elemental logical function same_bits(x, y)
        real(dp), intent(in) :: x, y

        same_bits = transfer(x, 0_int64) == transfer(y, 0_int64)
    end function same_bits

    integer function idx(i, f)
        integer, intent(in) :: i, f
        idx = N_FIELDS * i + MONOLITHIC_SLOTS(f)
    end function idx

    !> Natural (unscaled) reference system of (6.1) for one step: a x = b, tested with each
    !> unknown's own basis functions; Dirichlet unknowns have identity rows.
    subroutine reference_system(model, s, dt, u_old, w_old, a, b)
        type(model_t), intent(in) :: model
        integer, intent(in) :: s
        real(dp), intent(in) :: dt, u_old(0:), w_old(0:, :)
        real(dp), intent(out) :: a(:, :), b(:)
        integer :: i, j, f
        real(dp) :: mij, kij, gij, gji

        a = 0.0_dp
        b = 0.0_dp
        do i = 0, s
            do j = max(0, i - 1), min(s, i + 1)
                mij = integrate_product(i, .false., j, .false., s)      ! int phi_i phi_j
                kij = integrate_product(i, .true., j, .true., s)        ! int phi_i' phi_j'
                gij = integrate_product(i, .false., j, .true., s)       ! int phi_i phi_j'
                gji = integrate_product(j, .false., i, .true., s)       ! int phi_j phi_i'
                ! (6.1)_1: rho/dt (v - v_old) w + (alpha (u_old + dt v) + varpi v - gamma1 theta - gamma2 P) w_x
                a(idx(i, F_V), idx(j, F_V)) = model%rho / dt * mij + (model%varpi + dt * model%alpha) * kij
                a(idx(i, F_V), idx(j, F_THETA)) = -model%gamma1 * gji
                a(idx(i, F_V), idx(j, F_P)) = -model%gamma2 * gji
                b(idx(i, F_V)) = b(idx(i, F_V)) + model%rho / dt * mij * w_old(j, F_V) - model%alpha * kij * u_old(j)
                ! (6.1)_2: c/dt (theta - theta_old) + d/dt (P - P_old) + q_x + gamma1 v_x
                a(idx(i, F_THETA), idx(j, F_THETA)) = model%c / dt * mij
                a(idx(i, F_THETA), idx(j, F_P)) = model%d / dt * mij
                a(idx(i, F_THETA), idx(j, F_Q)) = gij
                a(idx(i, F_THETA), idx(j, F_V)) = model%gamma1 * gij
                b(idx(i, F_THETA)) = b(idx(i, F_THETA)) + mij * (model%c * w_old(j, F_THETA) + model%d * w_old(j, F_P)) / dt
                ! (6.1)_3: tau0/dt (q - q_old) + q + theta_x
                a(idx(i, F_Q), idx(j, F_Q)) = (model%tau0 / dt + 1.0_dp) * mij
                a(idx(i, F_Q), idx(j, F_THETA)) = gij
                b(idx(i, F_Q)) = b(idx(i, F_Q)) + model%tau0 / dt * mij * w_old(j, F_Q)
                ! (6.1)_4: r/dt (P - P_old) + d/dt (theta - theta_old) + hbar eta_x + gamma2 v_x
                a(idx(i, F_P), idx(j, F_THETA)) = model%d / dt * mij
                a(idx(i, F_P), idx(j, F_P)) = model%r / dt * mij
                a(idx(i, F_P), idx(j, F_ETA)) = model%hbar * gij
                a(idx(i, F_P), idx(j, F_V)) = model%gamma2 * gij
                b(idx(i, F_P)) = b(idx(i, F_P)) + mij * (model%d * w_old(j, F_THETA) + model%r * w_old(j, F_P)) / dt
                ! (6.1)_5: tau/dt (eta - eta_old) + eta + P_x
                a(idx(i, F_ETA), idx(j, F_ETA)) = (model%tau / dt + 1.0_dp) * mij
                a(idx(i, F_ETA), idx(j, F_P)) = gij
                b(idx(i, F_ETA)) = b(idx(i, F_ETA)) + model%tau / dt * mij * w_old(j, F_ETA)
            end do
        end do
        do f = 1, N_FIELDS
            do i = 0, s, s
                if (.not. is_dirichlet(f, i, s)) cycle
                a(idx(i, f), :) = 0.0_dp
                a(:, idx(i, f)) = 0.0_dp
                a(idx(i, f), idx(i, f)) = 1.0_dp
                b(idx(i, f)) = 0.0_dp
            end do
        end do
    end subroutine reference_system

    !> Row scaling of scheme_m: every equation times dt, (6.1)_5 also times hbar.
    real(dp) function row_scale(model, dt, f)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: dt
        integer, intent(in) :: f
        row_scale = dt
        if (f == F_ETA) row_scale = dt * model%hbar
    end function row_scale

    subroutine check_blocks(model, s, dt)
        type(model_t), intent(in) :: model
        integer, intent(in) :: s
        real(dp), intent(in) :: dt
        type(band_t) :: band
        real(dp), allocatable :: ref(:, :), b(:), got(:, :), w0(:, :), u0(:)
        integer :: n, i, j, fr, fc
        real(dp) :: expected, scale
        character(len=96) :: name

        n = N_FIELDS * (s + 1)
        allocate (ref(n, n), b(n), w0(0:s, N_FIELDS), u0(0:s))
        w0 = 0.0_dp
        u0 = 0.0_dp
        call reference_system(model, s, dt, u0, w0, ref, b)
        call assemble_matrix(model, uniform_mesh(s), dt, MONOLITHIC_SLOTS, band)
        got = band_to_dense(band)
        do fr = 1, N_FIELDS
            do fc = 1, N_FIELDS
                scale = 0.0_dp
                do i = 0, s
                    do j = 0, s
                        expected = ref(idx(i, fr), idx(j, fc))
                        if (.not. (is_dirichlet(fr, i, s) .or. is_dirichlet(fc, j, s))) &
                            expected = expected * row_scale(model, dt, fr)
                        scale = max(scale, abs(expected))
                    end do
                end do
                do i = 0, s
                    do j = 0, s
                        expected = ref(idx(i, fr), idx(j, fc))
                        if (.not. (is_dirichlet(fr, i, s) .or. is_dirichlet(fc, j, s))) &
                            expected = expected * row_scale(model, dt, fr)
                        write (name, '(a,i0,a,es8.1,5a,i0,a,i0,a)') 'block s=', s, ' dt=', dt, ' (', &
                            trim(FIELDS(fr)%name), ',', trim(FIELDS(fc)%name), ') entry (', i, ',', j, ')'
                        call check_close(trim(name), expected, got(idx(i, fr), idx(j, fc)), 1e-13_dp * max(scale, 1e-300_dp))
                    end do
                end do
            end do
        end do
    end subroutine check_blocks

    !> One step from a smooth state that satisfies the boundary values; contact=.true. starts
    !> from a penetrating end moving into the obstacle so that the penalty stays active.
    subroutine check_step(model, s, dt, contact)
        type(model_t), intent(in) :: model
        integer, intent(in) :: s
        real(dp), intent(in) :: dt
        logical, intent(in) :: contact
        type(config_t) :: cfg
        type(state_t) :: st, st0
        type(stepper_t) :: stepper
        type(step_result_t) :: res
        real(dp), allocatable :: a(:, :), x(:), a0(:, :), b0(:)
        integer, allocatable :: ipiv(:)
        integer :: n, i, f, info, k, cdof, method
        real(dp) :: gap, scale
        logical :: active
        character(len=96) :: name

        cfg%model = model
        cfg%mesh%n_elements = s
        cfg%time%dt = dt
        cfg%contact%g = 0.1_dp
        cfg%contact%eps = 0.01_dp
        st0%s = s
        allocate (st0%u(0:s), st0%w(0:s, N_FIELDS))
        do f = 1, N_FIELDS
            do i = 0, s
                st0%w(i, f) = cos(1.3_dp * i + 0.7_dp * f) * f
                if (is_dirichlet(f, i, s)) st0%w(i, f) = 0.0_dp
            end do
        end do
        do i = 0, s
            st0%u(i) = 0.02_dp * i / s
        end do
        if (contact) then
            st0%u(s) = cfg%contact%g + 1.0e-3_dp       ! already penetrating, moving inwards
            st0%w(:, F_V) = [(5.0_dp * i / s, i = 0, s)]
        end if

        ! dense reference: semismooth Newton on the natural system
        n = N_FIELDS * (s + 1)
        allocate (a0(n, n), b0(n), ipiv(n))
        call reference_system(model, s, dt, st0%u, st0%w, a0, b0)
        cdof = idx(s, F_V)
        active = .false.
        do k = 1, 5
            a = a0
            x = b0
            if (active) then        ! (1/eps)(u_old(1) + dt v_s - g) on the v row at x = 1
                a(cdof, cdof) = a(cdof, cdof) + dt / cfg%contact%eps
                x(cdof) = x(cdof) - (st0%u(s) - cfg%contact%g) / cfg%contact%eps
            end if
            call dgesv(n, 1, a, n, ipiv, x, n, info)
            gap = st0%u(s) + dt * x(cdof) - cfg%contact%g
            if ((gap > 0.0_dp) .eqv. active) exit
            active = gap > 0.0_dp
        end do
        call check_true('reference active set is the expected one', active .eqv. contact)
        scale = maxval(abs(x))

        do method = 1, 2
            st = st0
            cfg%solver%method = merge('monolithic', 'paper     ', method == 1)
            cfg%solver%tol = 1.0e-13_dp
            cfg%solver%max_iter = 500
            call stepper%init(cfg, res)
            call check_true('stepper init', res%ok, res%message)
            call stepper%advance(st, res)
            call check_true('stepper advance', res%ok, res%message)
            call check_true('contact flag', res%in_contact .eqv. contact)
            do f = 1, N_FIELDS
                do i = 0, s
                    write (name, '(4a,l1,a,i0,2a)') trim(cfg%solver%method), ' step vs dense, ', &
                        'contact=', '', contact, ' node ', i, ' field ', trim(FIELDS(f)%name)
                    call check_close(trim(name), x(idx(i, f)), st%w(i, f), 1e-9_dp * scale)
                end do
            end do
            do i = 0, s
                write (name, '(2a,l1,a,i0)') trim(cfg%solver%method), ' u = u_old + dt v, contact=', contact, ' node ', i
                call check_close(trim(name), st0%u(i) + dt * x(idx(i, F_V)), st%u(i), 1e-9_dp * scale * dt + 1e-15_dp)
            end do
            call check_true('step counter', st%step == 1)
        end do
    end subroutine check_step

end program test_scheme_m
