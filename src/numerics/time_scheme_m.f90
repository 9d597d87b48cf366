!> The time schemes (&time scheme): how the system of a step comes from the past levels and
!> step sizes, and the energy law each guarantees.
!>
!> Every scheme is one implicit Euler step (6.1) of an effective size dt_eff from a starting
!> level X_from, a combination of past levels: X^n - X_from = dt_eff F(X^n), so one assembly,
!> one contact step and one source treatment serve 'euler' (6.1), 'bdf2' (variable steps, first
!> step Euler) and 'midpoint' (an Euler step of dt/2 to X^{n-1/2}, then X^n = 2 X^{n-1/2} - X^{n-1};
!> first N_DAMPED steps Euler). Derivations and energy laws: docs/scheme.md, "Time schemes
!> (`&time scheme`)" and "The midpoint rule". Everything else the code asks of a scheme is here
!> too (order, error factor, step-ratio bound, law, input rules): a new scheme is a row of
!> SCHEMES and its branches in plan and error_factor (docs/architecture.md, "How to add").
module time_scheme_m
    use kinds_m, only: dp
    use config_m, only: model_t, LEN_NAME
    use fields_m, only: N_FIELDS, F_V, F_Q, F_ETA
    use validate_m, only: scheme_rule_t
    implicit none
    private
    public :: time_scheme_t, time_scheme, step_plan_t, energy_law_t, scheme_rules
    public :: LAW_E, LAW_G_ENERGY

    integer, parameter :: SCHEME_EULER = 1, SCHEME_BDF2 = 2, SCHEME_MIDPOINT = 3
    !> Euler steps before the midpoint rule takes over.
    integer, parameter :: N_DAMPED = 2
    !> A time-derivative coefficient this small relative to the step's other terms is taken
    !> as zero by the midpoint rule (stiff_limit).
    real(dp), parameter :: STIFF_RATIO = 1.0e-8_dp
    !> Variable-step BDF2 is zero-stable for step ratios w = dt_n / dt_{n-1} < 1 + sqrt(2);
    !> adaptive steps stay at 2. Euler and the midpoint rule are one-step methods without
    !> such a bound; they keep the same limit on the controller's growth.
    real(dp), parameter :: BDF2_RATIO_MAX = 2.0_dp

    !> The energies a scheme's law can be stated for (energy_m computes them).
    integer, parameter :: LAW_E = 1          !< E^n of Corollary 6.2 (energy_m's discrete_energy)
    integer, parameter :: LAW_G_ENERGY = 2   !< BDF2's G-energy (energy_m's bdf2_energy)

    !> The energy law a scheme guarantees: the energy that never rises from step to step.
    type :: energy_law_t
        integer :: energy = LAW_E
        !> the law is stated for constant steps only: a rise at a step whose size differs
        !> from the step before is recorded apart (energy_m)
        logical :: constant_steps = .false.
        !> the energy is that of the step's model (stiff_limit), not the paper's
        logical :: step_model = .false.
        character(len=160) :: text = ''   !< root attribute energy_law
    end type energy_law_t

    !> One row per scheme: what the rest of the code asks of it.
    type :: scheme_row_t
        character(len=LEN_NAME) :: name         !< &time scheme
        integer :: order                        !< p: the local error is O(dt^(p+1))
        logical :: keeps_previous_level         !< multistep: X^{n-1} is kept (state_m's u_prev)
        real(dp) :: max_step_ratio              !< largest dt_n / dt_{n-1} of adaptive steps
        logical :: paper_iteration              !< solver.method = 'paper' (Section 7) runs it
        logical :: stiff_limit                  !< negligible rho, tau0, tau taken as 0 (stiff_limit)
        type(energy_law_t) :: law
    end type scheme_row_t

    !> The schemes, indexed by SCHEME_*; validate_m lists their names in this order.
    type(scheme_row_t), parameter :: SCHEMES(3) = [ &
        scheme_row_t('euler', 1, .false., BDF2_RATIO_MAX, .true., .false., &
                     energy_law_t(LAW_E, .false., .false., 'E^n of Corollary 6.2')), &
        scheme_row_t('bdf2', 2, .true., BDF2_RATIO_MAX, .false., .false., &
                     energy_law_t(LAW_G_ENERGY, .true., .false., &
                                  'BDF2 G-energy (E_lin(X^n) + E_lin(2X^n - X^{n-1}))/2 + penalty(u^n)')), &
        scheme_row_t('midpoint', 2, .false., BDF2_RATIO_MAX, .false., .true., &
                     energy_law_t(LAW_E, .false., .true., &
                                  'E^n of Corollary 6.2 with the time-derivative coefficients of the step''s ' // &
                                  'model (rho, tau0, tau taken as 0 where negligible: stiff_limit)'))]

    !> One step: the matrix of (6.1) with dt_eff; the starting level X^{n-1} itself
    !> (from_history = .false.) or (a X^{n-1} - b X^{n-2}) / d; the solution Y is X^n, or
    !> (midpoint) X^n = 2 Y - X^{n-1}; sources are taken at t_n - source_back * dt_n.
    type :: step_plan_t
        real(dp) :: dt_eff = 0.0_dp
        logical :: from_history = .false.
        real(dp) :: a = 1.0_dp, b = 0.0_dp, d = 1.0_dp
        logical :: midpoint = .false.
        real(dp) :: source_back = 0.0_dp
    end type step_plan_t

    type :: time_scheme_t
        integer :: kind = SCHEME_EULER   !< the row of SCHEMES
        !> what the rest of the code asks of the scheme: row%order, row%law, ... (SCHEMES(kind))
        type(scheme_row_t) :: row = SCHEMES(SCHEME_EULER)
    contains
        procedure :: plan => scheme_plan
        procedure :: error_factor => scheme_error_factor
        procedure :: stiff_limit => scheme_stiff_limit
    end type time_scheme_t

contains

    !> The scheme named by &time scheme (a name of SCHEMES; validate_m has checked it).
    pure function time_scheme(name) result(scheme)
        character(len=*), intent(in) :: name
        type(time_scheme_t) :: scheme

        scheme%kind = max(findloc(SCHEMES%name, name, dim=1), SCHEME_EULER)
        scheme%row = SCHEMES(scheme%kind)
    end function time_scheme

    !> What validate_m checks of &time scheme: the names, and which scheme solver.method =
    !> 'paper' runs.
    pure function scheme_rules() result(rules)
        type(scheme_rule_t) :: rules(size(SCHEMES))
        integer :: k

        do k = 1, size(SCHEMES)
            rules(k) = scheme_rule_t(SCHEMES(k)%name, SCHEMES(k)%paper_iteration)
        end do
    end function scheme_rules

    !> The plan of step n+1 (n = steps taken) of size dt from a state whose last step had
    !> size dt_last (0 at t = 0); have_previous: X^{n-1} of a multistep scheme is available.
    pure function scheme_plan(self, dt, dt_last, have_previous, n) result(plan)
        class(time_scheme_t), intent(in) :: self
        real(dp), intent(in) :: dt, dt_last
        logical, intent(in) :: have_previous
        integer, intent(in) :: n
        type(step_plan_t) :: plan
        real(dp) :: w

        plan%dt_eff = dt
        if (self%kind == SCHEME_MIDPOINT .and. n >= N_DAMPED) then
            plan%dt_eff = 0.5_dp * dt
            plan%midpoint = .true.
            plan%source_back = 0.5_dp
            return
        end if
        if (self%kind /= SCHEME_BDF2 .or. .not. have_previous .or. .not. (dt_last > 0.0_dp)) return
        plan%from_history = .true.
        ! BDF2: dt_eff = dt (1+w)/(1+2w), X_from = ((1+w)^2 X^{n-1} - w^2 X^{n-2}) / (1+2w);
        ! constant steps: w = 1 exactly, and these are 2 dt / 3, 4, 1, 3 exactly
        w = dt / dt_last
        plan%dt_eff = dt * (1.0_dp + w) / (1.0_dp + 2.0_dp * w)
        plan%a = (1.0_dp + w)**2
        plan%b = w**2
        plan%d = 1.0_dp + 2.0_dp * w
    end function scheme_plan

    !> Local error of the step / (X^n - P^n), P^n the polynomial of degree p through the
    !> last p+1 levels extrapolated to t_n (step_control_m), from the leading terms;
    !> d(j) = t_n - t_{n-j}, h = h_n = d(1), h_prev = h_{n-1}, w = h / h_prev: Euler h / d_2,
    !> BDF2 h (1+w) / ((1+2w) d_3), midpoint h^2 / (2 d_2 d_3) (constant steps: 1/2, 2/9 and
    !> 1/12 of the p+1-st difference). The local errors: docs/scheme.md, "Why this estimate".
    pure real(dp) function scheme_error_factor(self, d, h_prev) result(factor)
        class(time_scheme_t), intent(in) :: self
        real(dp), intent(in) :: d(:)
        real(dp), intent(in) :: h_prev
        real(dp) :: h, w

        h = d(1)
        select case (self%kind)
        case (SCHEME_BDF2)
            w = h / h_prev
            factor = h * (1.0_dp + w) / ((1.0_dp + 2.0_dp * w) * d(3))
        case (SCHEME_MIDPOINT)
            factor = h**2 / (2.0_dp * d(2) * d(3))
        case default
            factor = h / d(2)
        end select
    end function scheme_error_factor

    !> The model a step of size dt on s elements uses: the paper's, except that the
    !> midpoint rule takes a negligible time-derivative coefficient as zero, so that the
    !> field becomes algebraic (X^n = Y) instead of an undamped stiff mode. Negligible: rho h^2
    !> <= STIFF_RATIO dt (varpi + dt alpha) (the paper's rho ~ 1e-17: quasi-static
    !> mechanics), tau0 <= STIFF_RATIO dt, tau <= STIFF_RATIO dt. algebraic(f): the field f has
    !> no time derivative in the returned model.
    pure subroutine scheme_stiff_limit(self, model, dt, s, step_model, algebraic)
        class(time_scheme_t), intent(in) :: self
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: dt
        integer, intent(in) :: s
        type(model_t), intent(out) :: step_model
        logical, intent(out) :: algebraic(N_FIELDS)

        step_model = model
        algebraic = .false.
        if (.not. self%row%stiff_limit) return
        algebraic(F_V) = model%rho / real(s, dp)**2 <= STIFF_RATIO * dt * (model%varpi + dt * model%alpha)
        algebraic(F_Q) = model%tau0 <= STIFF_RATIO * dt
        algebraic(F_ETA) = model%tau <= STIFF_RATIO * dt
        if (algebraic(F_V)) step_model%rho = 0.0_dp
        if (algebraic(F_Q)) step_model%tau0 = 0.0_dp
        if (algebraic(F_ETA)) step_model%tau = 0.0_dp
    end subroutine scheme_stiff_limit

end module time_scheme_m
