!> Convergence of the fully discrete scheme (6.1) on manufactured solutions (tests/lib/mms_m)
!> run through the library's own time stepping with source terms (sources_m). Errors in
!> the norms of Corollary 6.4 (L2 of q, theta, v, P, eta; H1 of u), max over time levels.
!>
!>   dt study  : fields linear in x (exactly in the P1 spaces: no spatial error), s = 4;
!>               expected order 1 (implicit Euler), with and without penalised contact.
!>   h study   : fields linear in t with v constant (implicit Euler exact in time);
!>               expected order 2 for the L2 errors (P1, optimal) and 1 for H1 of u.
!>   h = dt    : smooth in x and t, no contact; expected order 1 (Corollary 6.4: O(h + dt)).
!> Each observed order between the two finest levels must be within 0.15 of the expected.
!> Three time schemes: 'euler' (6.1), 'bdf2' and 'midpoint' (expected order 2 in dt; h = dt: 2 for the
!> L2 errors, 1 for H1 of u, which the P1 space limits to O(h)).
!> Coefficients: an O(1) model (below), where all fields reach the asymptotic regime on
!> these meshes; `--report` also prints the paper's (7.1) values and the contact h = dt
!> study (slower) as Markdown for docs/verification.md.
program test_convergence
    use kinds_m, only: dp
    use config_m, only: model_t
    use mms_m, only: mms_t, mms_no_contact, mms_contact, mms_linear_in_x, mms_linear_in_t, N_EXACT, U_FIELD
    use convergence_m, only: mms_errors, observed_orders, ERROR_NAMES
    use testing_m, only: check_true, test_summary
    implicit none
    real(dp), parameter :: EPS = 0.01_dp, G = 0.1_dp, ORDER_TOL = 0.15_dp
    type(model_t) :: unit_model
    character(len=16) :: arg
    logical :: report
    character(len=:), allocatable :: scheme
    integer :: k_scheme
    character(len=*), parameter :: SCHEMES(3) = [character(len=8) :: 'euler', 'bdf2', 'midpoint']

    call get_command_argument(3, arg)
    report = arg == '--report'
    unit_model = model_t(rho=1.0_dp, alpha=1.0_dp, varpi=0.1_dp, gamma1=0.5_dp, gamma2=0.5_dp, c=1.0_dp, &
                         d=0.2_dp, r=1.0_dp, hbar=1.0_dp, tau0=0.5_dp, tau=0.5_dp)

    do k_scheme = 1, size(SCHEMES)
    scheme = trim(SCHEMES(k_scheme))
    write (*, '(/,a,a)') '### time scheme: ', scheme
    call dt_study('dt study, no contact (fields linear in x, s = 4)', &
                  mms_linear_in_x(unit_model, EPS, G, .false.), 0.02_dp)
    call dt_study('dt study, penalised contact for t in (0, 1/2) (fields linear in x, s = 4)', &
                  mms_linear_in_x(unit_model, EPS, G, .true.), 0.0025_dp)
    call h_study('h study, no contact (fields linear in t, dt = 0.05)', mms_linear_in_t(unit_model, EPS, G, .false.))
    call h_study('h study, contact from t = 0.2 (fields linear in t, dt = 0.05)', &
                 mms_linear_in_t(unit_model, EPS, G, .true.))
    call hdt_study('h = dt, no contact (smooth in x and t)', mms_no_contact(unit_model), 20, .true.)
    if (report) then
        call hdt_study('h = dt, penalised contact (smooth; asymptotic only from s = 320)', &
                       mms_contact(unit_model, EPS, G), 80, .false.)
        call dt_study('paper values (7.1) with rho = 0.5: dt study, no contact', &
                      mms_linear_in_x(model_t(rho=0.5_dp), EPS, G, .false.), 0.02_dp, .false.)
        call h_study('paper values (7.1) with rho = 0.5: h study, no contact', &
                     mms_linear_in_t(model_t(rho=0.5_dp), EPS, G, .false.), .false.)
        call hdt_study('paper values (7.1) with rho = 0.5: h = dt, no contact', &
                       mms_no_contact(model_t(rho=0.5_dp)), 20, .false.)
    end if
    end do
    call test_summary('test_convergence')

contains

    subroutine dt_study(title, mms, dt0, assert)
        character(len=*), intent(in) :: title
        type(mms_t), intent(in) :: mms
        real(dp), intent(in) :: dt0
        logical, intent(in), optional :: assert
        real(dp) :: errors(N_EXACT, 5), expected(N_EXACT)
        integer :: k
        character(len=24) :: labels(5)

        do k = 1, 5
            call mms_errors(mms, 4, dt0 / 2**(k - 1), 1.0_dp, 'monolithic', errors(:, k), scheme)
            write (labels(k), '(a,es8.2)') 'dt=', dt0 / 2**(k - 1)
        end do
        expected = 1.0_dp
        if (scheme /= 'euler') expected = 2.0_dp
        call conclude(title, errors, labels, expected, assert)
    end subroutine dt_study

    subroutine h_study(title, mms, assert)
        character(len=*), intent(in) :: title
        type(mms_t), intent(in) :: mms
        logical, intent(in), optional :: assert
        real(dp) :: errors(N_EXACT, 5), expected(N_EXACT)
        integer :: k
        character(len=24) :: labels(5)

        do k = 1, 5
            call mms_errors(mms, 16 * 2**(k - 1), 0.05_dp, 0.5_dp, 'monolithic', errors(:, k), scheme)
            write (labels(k), '(a,i0)') 's=', 16 * 2**(k - 1)
        end do
        expected = 2.0_dp
        expected(U_FIELD) = 1.0_dp
        call conclude(title, errors, labels, expected, assert)
    end subroutine h_study

    subroutine hdt_study(title, mms, s0, assert)
        character(len=*), intent(in) :: title
        type(mms_t), intent(in) :: mms
        integer, intent(in) :: s0
        logical, intent(in) :: assert
        real(dp) :: errors(N_EXACT, 5), expected(N_EXACT)
        integer :: k, s
        character(len=24) :: labels(5)

        do k = 1, 5
            s = s0 * 2**(k - 1)
            call mms_errors(mms, s, 1.0_dp / s, 1.0_dp, 'monolithic', errors(:, k), scheme)
            write (labels(k), '(a,i0)') 'h=dt=1/', s
        end do
        expected = 1.0_dp
        if (scheme /= 'euler') expected = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 1.0_dp]
        call conclude(title, errors, labels, expected, assert)
    end subroutine hdt_study

    !> Print the table (Markdown) and assert the finest observed orders.
    subroutine conclude(title, errors, labels, expected, assert)
        character(len=*), intent(in) :: title
        real(dp), intent(in) :: errors(:, :), expected(:)
        character(len=*), intent(in) :: labels(:)
        logical, intent(in), optional :: assert
        real(dp) :: orders(size(errors, 1), size(errors, 2) - 1)
        integer :: f, k, last
        character(len=200) :: detail
        logical :: do_assert

        do_assert = .true.
        if (present(assert)) do_assert = assert
        orders = observed_orders(errors, 2.0_dp)
        last = size(orders, 2)
        write (*, '(/,a,a,a)') '#### ', title, merge(' (asserted)', '           ', do_assert)
        write (*, '(a)', advance='no') '| norm |'
        do k = 1, size(labels)
            write (*, '(1x,a,1x,a)', advance='no') trim(labels(k)), '|'
        end do
        write (*, '(a)') ' observed orders | expected |'
        write (*, '(a)') '|---|'//repeat('---|', size(labels))//'---|---|'
        do f = 1, size(errors, 1)
            write (*, '(a,a,a)', advance='no') '| ', trim(ERROR_NAMES(f)), ' |'
            do k = 1, size(errors, 2)
                write (*, '(es10.3,a)', advance='no') errors(f, k), ' |'
            end do
            write (*, '(1x,*(f5.2,:,", "))', advance='no') orders(f, :)
            write (*, '(a,f4.1,a)') ' | ', expected(f), ' |'
            if (do_assert) then
                write (detail, '(a,f6.3,a,f4.1,a,f5.2)') 'observed order ', orders(f, last), ' expected ', &
                    expected(f), ' tolerance ', ORDER_TOL
                call check_true(scheme//': '//title//': '//trim(ERROR_NAMES(f)), &
                                abs(orders(f, last) - expected(f)) <= ORDER_TOL, detail)
            end if
        end do
    end subroutine conclude

end program test_convergence
