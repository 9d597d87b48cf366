!> The adaptive mesh's pieces (issue 13): P1 on graded meshes and the transfer between meshes.
!>
!>   graded MMS: a manufactured solution linear in t (implicit Euler exact in time) on random
!>       graded meshes (random bisections of 8 coarse elements up to 4 levels, 2:1 graded),
!>       each refinement bisecting every element (h_max halves, the grading stays); errors
!>       in the norms of Corollary 6.4: order 2 in L2 and 1 in H1 of u in h_max (within 0.15).
!>   transfer: random levels moved between random graded meshes (transfer_m): the energy
!>       of Corollary 6.2 (with d /= 0, the coupled theta-P term) never rises, is kept when
!>       the new mesh only adds nodes, u keeps its values at common nodes and at x = 1; the
!>       same with the redistributed velocity mass (&contact mass = 'redistributed': the
!>       kinetic energy v^T M_v v, x = 1 massless), where v(1) is kept too.
!>   buffer: a kink of u at x = 1/2 on 20 coarse elements (one level, buffer 3) makes its two
!>       elements refine and the 3 on either side with them: fine on exactly [0.3, 0.7].
program test_graded_mesh
    use kinds_m, only: dp
    use reals_m, only: equal
    use iso_fortran_env, only: int64
    use config_m, only: model_t, with_contact_mass
    use fields_m, only: N_FIELDS, F_V, is_dirichlet
    use energy_m, only: discrete_energy
    use transfer_m, only: transfer_level, merge_keys
    use adaptive_mesh_m, only: adaptive_mesh_t, nodes_of_keys
    use meshes_m, only: graded_mesh
    use mms_m, only: mms_t, mms_linear_in_t, N_EXACT, U_FIELD
    use convergence_m, only: mms_errors, observed_orders, ERROR_NAMES
    use testing_m, only: check_true, test_summary
    implicit none
    real(dp), parameter :: ORDER_TOL = 0.15_dp
    integer, parameter :: N_COARSE = 8, MAX_LEVEL = 4
    type(model_t) :: unit_model

    unit_model = model_t(rho=1.0_dp, alpha=1.0_dp, varpi=0.1_dp, gamma1=0.5_dp, gamma2=0.5_dp, c=1.0_dp, &
                         d=0.2_dp, r=1.0_dp, hbar=1.0_dp, tau0=0.5_dp, tau=0.5_dp)
    call graded_mms_study(mms_linear_in_t(unit_model, 0.01_dp, 0.1_dp, .false.))
    call transfer_study(unit_model, '')
    call transfer_study(with_contact_mass(unit_model, 'redistributed'), ' (redistributed mass)')
    call buffer_study()
    call test_summary('test_graded_mesh')

contains

    subroutine graded_mms_study(mms)
        type(mms_t), intent(in) :: mms
        integer, parameter :: N_MESHES = 4
        integer(int64), allocatable :: k(:)
        real(dp) :: errors(N_EXACT, N_MESHES), h_max(N_MESHES), orders(N_EXACT), expected(N_EXACT)
        real(dp), allocatable :: x(:)
        real(dp) :: grading
        integer :: m, f

        allocate (k, source=random_graded_keys(101))
        do m = 1, N_MESHES
            if (allocated(x)) deallocate (x)
            allocate (x(0:size(k) - 1))    ! (an assignment would give x the lower bound 1)
            x = nodes_of_keys(k, int(N_COARSE, int64) * 2_int64**(MAX_LEVEL + m))
            h_max(m) = maxval(x(1:) - x(:ubound(x, 1) - 1))
            grading = h_max(m) / minval(x(1:) - x(:ubound(x, 1) - 1))
            call mms_errors(mms, ubound(x, 1), 0.05_dp, 0.5_dp, 'monolithic', errors(:, m), nodes=x)
            write (*, '(a,i0,a,i0,a,es9.2,a,6es10.2)') 'mesh ', m, ': ', ubound(x, 1), ' elements, h_max ', &
                h_max(m), ', errors', errors(:, m)
            k = bisect_all(k)
        end do
        expected = 2.0_dp
        expected(U_FIELD) = 1.0_dp
        do f = 1, N_EXACT
            orders(f) = log(errors(f, N_MESHES - 1) / errors(f, N_MESHES)) / log(h_max(N_MESHES - 1) / h_max(N_MESHES))
            call check_true('graded MMS: order of '//trim(ERROR_NAMES(f))//' in h_max', &
                            abs(orders(f) - expected(f)) <= ORDER_TOL, detail_order(orders(f), expected(f)))
        end do
        call check_true('graded MMS: the meshes are graded (h_max / h_min >= 4)', grading >= 4.0_dp, &
                        real_detail('h_max / h_min', grading))
    end subroutine graded_mms_study

    pure function detail_order(got, expected) result(text)
        real(dp), intent(in) :: got, expected
        character(len=64) :: text

        write (text, '(a,f6.3,a,f6.3)') 'observed ', got, ', expected ', expected
    end function detail_order

    !> Keys of a random graded mesh: N_COARSE elements bisected at random up to MAX_LEVEL
    !> times, then 2:1 graded, in units of 1/(N_COARSE 2^MAX_LEVEL) times 2 (so that every
    !> element can be bisected once more by bisect_all without leaving the integers).
    function random_graded_keys(seed) result(k)
        integer, intent(in) :: seed
        integer(int64), allocatable :: k(:)
        type(adaptive_mesh_t) :: mesh
        real(dp), allocatable :: x(:), u(:), w(:, :)
        integer :: pass, s, i
        logical :: changed
        real(dp) :: r

        call seed_random(seed)
        call mesh%init(N_COARSE, MAX_LEVEL, 1.0e-12_dp, 0)
        do pass = 1, MAX_LEVEL
            ! a random rough field makes the indicator refine somewhere
            s = mesh%s()
            x = mesh%nodes()
            allocate (u(0:s), w(0:s, N_FIELDS))
            w = 0.0_dp
            do i = 0, s
                call random_number(r)
                u(i) = merge(1.0_dp, 0.0_dp, r < 0.3_dp)
            end do
            call mesh%adapt(graded_mesh(x), u, w, changed)
            deallocate (u, w)
        end do
        k = 2_int64 * mesh%k
    end function random_graded_keys

    subroutine buffer_study()
        integer, parameter :: N = 20, BUFFER = 3
        type(adaptive_mesh_t) :: mesh
        real(dp), allocatable :: x(:), u(:), w(:, :)
        logical :: changed, fine, inside
        integer :: s, e
        character(len=120) :: detail

        call mesh%init(N, 1, 1.0e-3_dp, BUFFER)
        x = mesh%nodes()
        u = abs(x - 0.5_dp)
        allocate (w(0:N, N_FIELDS))
        w = 0.0_dp
        call mesh%adapt(graded_mesh(x), u, w, changed)
        s = mesh%s()
        deallocate (x)
        allocate (x(0:s))
        x = mesh%nodes()
        do e = 1, s
            fine = x(e) - x(e - 1) < 0.75_dp / N
            inside = 0.5_dp * (x(e - 1) + x(e)) > 0.3_dp .and. 0.5_dp * (x(e - 1) + x(e)) < 0.7_dp
            write (detail, '(a,i0,a,f8.5,a,f8.5,a,l1)') 'element ', e, ' [', x(e - 1), ', ', x(e), '] fine: ', fine
            call check_true('buffer: fine exactly within 3 coarse elements of the kink at 1/2', fine .eqv. inside, &
                            trim(detail))
        end do
        call check_true('buffer: the mesh changed, 8 elements bisected', changed .and. s == N + 8)
    end subroutine buffer_study

    !> Every element bisected (keys doubled, midpoints inserted).
    pure function bisect_all(k) result(k_new)
        integer(int64), intent(in) :: k(0:)
        integer(int64) :: k_new(0:2 * ubound(k, 1))
        integer :: e

        k_new(0) = 2 * k(0)
        do e = 1, ubound(k, 1)
            k_new(2 * e - 1) = k(e - 1) + k(e)
            k_new(2 * e) = 2 * k(e)
        end do
    end function bisect_all

    !> model: whose energy (and velocity mass) the transfer keeps; tag: for the check names.
    subroutine transfer_study(model, tag)
        type(model_t), intent(in) :: model
        character(len=*), intent(in) :: tag
        integer, parameter :: N_TRIALS = 200
        integer(int64), allocatable :: k_old(:), k_new(:), k_fine(:)
        integer(int64) :: n_fine
        real(dp), allocatable :: old(:, :), new(:, :), back(:, :)
        real(dp) :: e_old, e_new, worst_rise, worst_kept
        integer :: trial, f, i, n_lowered
        logical :: u_kept, v_kept

        n_fine = int(N_COARSE, int64) * 2_int64**(MAX_LEVEL + 1)
        allocate (k_old(1), k_new(1), k_fine(1))   ! (reallocated on assignment below)
        worst_rise = -huge(1.0_dp)
        worst_kept = 0.0_dp
        u_kept = .true.
        v_kept = .true.
        n_lowered = 0
        do trial = 1, N_TRIALS
            k_old = random_graded_keys(1000 + trial)
            k_new = random_graded_keys(5000 + trial)
            allocate (old(0:size(k_old) - 1, 0:N_FIELDS), new(0:size(k_new) - 1, 0:N_FIELDS))
            call random_number(old)
            ! every other trial: dips at the nodes the new mesh drops, where dropping them by
            ! interpolation would raise the energy (the projection must not)
            if (mod(trial, 2) == 1) then
                old(:, 0) = 0.0_dp     ! (a rough u's strain energy would hide the rest)
                do i = 0, size(k_old) - 1
                    if (.not. any(k_new == k_old(i + 1))) old(i, :) = 0.05_dp * old(i, :)   ! k_old is 1-based
                end do
            end if
            do f = 1, N_FIELDS
                do i = 0, size(k_old) - 1
                    if (is_dirichlet(f, i, size(k_old) - 1)) old(i, f) = 0.0_dp
                end do
            end do
            old(0, 0) = 0.0_dp
            call transfer_level(k_old, k_new, n_fine, old(:, 0), old(:, 1:), new(:, 0), new(:, 1:), model)
            e_old = energy(model, k_old, old)
            e_new = energy(model, k_new, new)
            worst_rise = max(worst_rise, (e_new - e_old) / e_old)
            if ((e_new - e_old) / e_old < -1.0e-6_dp) n_lowered = n_lowered + 1
            u_kept = u_kept .and. equal(new(ubound(new, 1), 0), old(ubound(old, 1), 0))
            v_kept = v_kept .and. equal(new(ubound(new, 1), F_V), old(ubound(old, 1), F_V))
            ! refinement only: the union of both meshes holds the old function exactly
            k_fine = union(k_old, k_new)
            allocate (back(0:size(k_fine) - 1, 0:N_FIELDS))
            call transfer_level(k_old, k_fine, n_fine, old(:, 0), old(:, 1:), back(:, 0), back(:, 1:), model)
            if (model%mass_end_moved) then
                ! the lumped part of M_v falls where elements split, and x = 1's v carries none
                worst_kept = max(worst_kept, (energy(model, k_fine, back) - e_old) / e_old)
            else
                worst_kept = max(worst_kept, abs(energy(model, k_fine, back) - e_old) / e_old)
            end if
            deallocate (old, new, back)
        end do
        call check_true('transfer: the energy never rises across a remesh (200 random pairs of meshes)' // tag, &
                        worst_rise <= 1.0e-13_dp, real_detail('largest relative rise', worst_rise))
        call check_true('transfer: the trials coarsen (some lower the energy by > 1e-6)' // tag, n_lowered > 0)
        if (model%mass_end_moved) then
            call check_true('transfer: refinement does not raise the energy' // tag, worst_kept <= 1.0e-13_dp, &
                            real_detail('largest relative rise', worst_kept))
        else
            call check_true('transfer: refinement keeps the energy' // tag, worst_kept <= 1.0e-13_dp, &
                            real_detail('largest relative change', worst_kept))
        end if
        call check_true('transfer: u(1) (the contact term) is kept' // tag, u_kept)
        if (model%mass_end_moved) call check_true('transfer: v(1) (massless) is kept' // tag, v_kept)
    end subroutine transfer_study

    !> E_lin of a packed level on keys k with the model's coefficients and velocity mass.
    real(dp) function energy(model, k, level) result(e)
        type(model_t), intent(in) :: model
        integer(int64), intent(in) :: k(0:)
        real(dp), intent(in) :: level(0:, 0:)
        real(dp) :: x(0:size(k) - 1)

        x = nodes_of_keys(k, int(N_COARSE, int64) * 2_int64**(MAX_LEVEL + 1))
        call discrete_energy(model, level(:, 0), level(:, 1:), graded_mesh(x), e)
    end function energy

    !> The sorted union of two increasing key lists (transfer_m%merge_keys).
    function union(a, b) result(c)
        integer(int64), intent(in) :: a(0:), b(0:)
        integer(int64), allocatable :: c(:)
        integer(int64) :: buffer(0:size(a) + size(b))
        integer :: n

        call merge_keys(a, b, buffer, n)
        allocate (c(0:n))
        c = buffer(0:n)
    end function union

    pure function real_detail(what, value) result(text)
        character(len=*), intent(in) :: what
        real(dp), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=16) :: buf

        write (buf, '(es12.4)') value
        text = what//' '//trim(adjustl(buf))
    end function real_detail

    subroutine seed_random(seed)
        integer, intent(in) :: seed
        integer :: n
        integer, allocatable :: values(:)

        call random_seed(size=n)
        allocate (values(n))
        values = seed + 37 * [(n, n = 1, size(values))]
        call random_seed(put=values)
    end subroutine seed_random

end program test_graded_mesh
