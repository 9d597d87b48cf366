!> The time schemes (&time scheme): how the system of a step comes from the past levels and
!> step sizes, and the energy law each guarantees.
!>
!> Every scheme here is one implicit Euler step (6.1) of an effective size dt_eff taken from
!> a starting level X_from that is a combination of past levels:
!>   X^n - X_from = dt_eff F(X^n)   (F: the right-hand side of (2.11)),  u^n = u_from + dt_eff v^n,
!> so one assembly (scheme_m), one contact step (contact_law_m) and one source treatment
!> serve all of them. The stepper asks plan() for (dt_eff, X_from) every step and factors
!> the matrix of (6.1) only when dt_eff changes.
!>
!>   'euler' (6.1):  dt_eff = dt_n, X_from = X^{n-1}.
!>       Law: E^n <= E^{n-1} for any step sequence (Theorem 6.1, Corollary 6.2).
!>   'bdf2': variable-step BDF2 with ratio w = dt_n / dt_{n-1},
!>       ((1+2w) X^n - (1+w)^2 X^{n-1} + w^2 X^{n-2}) / ((1+w) dt_n) = F(X^n), i.e.
!>       dt_eff = dt_n (1+w)/(1+2w), X_from = ((1+w)^2 X^{n-1} - w^2 X^{n-2}) / (1+2w);
!>       constant steps (w = 1): dt_eff = 2 dt/3, X_from = (4 X^{n-1} - X^{n-2})/3. The
!>       first step (no X^{n-2}) is an Euler step.
!>       Law (constant steps, contact node inactive): the G-energy
!>       (E_lin(X^n) + E_lin(2 X^n - X^{n-1}))/2 + penalty(u^n) never rises (energy_m).
!>       With an active penalty or a varying step no law is proven.
!>   'midpoint': the implicit midpoint rule (X^n - X^{n-1})/dt = F(X^{n-1/2}),
!>       X^{n-1/2} = (X^n + X^{n-1})/2, with the discrete-gradient contact force
!>       (phi(u^n(1)) - phi(u^{n-1}(1))) / (u^n(1) - u^{n-1}(1)) (contact_law_m). As an Euler
!>       step: Y = X^{n-1/2} is the Euler step of size dt/2 from X^{n-1} (dt_eff = dt/2), then
!>       X^n = 2 Y - X^{n-1} (midpoint = .true.); fields without a time derivative in the
!>       step's model (algebraic: stiff_limit) take X^n = Y. The first N_DAMPED steps are
!>       Euler steps, which damp the stiff modes of rough initial data (the midpoint rule is
!>       not L-stable); they keep E^n <= E^{n-1}.
!>       Law: E^n - E^{n-1} = -dt (varpi |v_x|^2 + |q|^2 + hbar |eta|^2)(X^{n-1/2}) <= 0 with
!>       the penalty law, exactly (to round-off); Signorini: <= 0 (docs/scheme.md).
module time_scheme_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fields_m, only: N_FIELDS, F_V, F_Q, F_ETA
    implicit none
    private
    public :: time_scheme_t, time_scheme, step_plan_t

    integer, parameter :: SCHEME_EULER = 1, SCHEME_BDF2 = 2, SCHEME_MIDPOINT = 3
    !> Euler steps before the midpoint rule takes over.
    integer, parameter :: N_DAMPED = 2
    !> A time-derivative coefficient this small relative to the step's other terms is taken
    !> as zero by the midpoint rule (stiff_limit).
    real(dp), parameter :: STIFF_RATIO = 1.0e-8_dp

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
        integer :: kind = SCHEME_EULER
    contains
        procedure :: plan => scheme_plan
        procedure :: keeps_previous_level => scheme_keeps_previous_level
        procedure :: is_bdf2 => scheme_is_bdf2
        procedure :: is_midpoint => scheme_is_midpoint
        procedure :: stiff_limit => scheme_stiff_limit
        procedure :: law => scheme_law
    end type time_scheme_t

contains

    !> The scheme named by &time scheme ('euler', 'bdf2' or 'midpoint'; validate_m has checked it).
    pure function time_scheme(name) result(scheme)
        character(len=*), intent(in) :: name
        type(time_scheme_t) :: scheme

        scheme%kind = SCHEME_EULER
        if (trim(name) == 'bdf2') scheme%kind = SCHEME_BDF2
        if (trim(name) == 'midpoint') scheme%kind = SCHEME_MIDPOINT
    end function time_scheme

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
        ! constant steps: w = 1 exactly, and these are 2 dt / 3, 4, 1, 3 exactly
        w = dt / dt_last
        plan%dt_eff = dt * (1.0_dp + w) / (1.0_dp + 2.0_dp * w)
        plan%a = (1.0_dp + w)**2
        plan%b = w**2
        plan%d = 1.0_dp + 2.0_dp * w
    end function scheme_plan

    !> Does the scheme need X^{n-1} kept when X^n is computed?
    pure logical function scheme_keeps_previous_level(self)
        class(time_scheme_t), intent(in) :: self

        scheme_keeps_previous_level = self%kind == SCHEME_BDF2
    end function scheme_keeps_previous_level

    pure logical function scheme_is_bdf2(self)
        class(time_scheme_t), intent(in) :: self

        scheme_is_bdf2 = self%kind == SCHEME_BDF2
    end function scheme_is_bdf2

    pure logical function scheme_is_midpoint(self)
        class(time_scheme_t), intent(in) :: self

        scheme_is_midpoint = self%kind == SCHEME_MIDPOINT
    end function scheme_is_midpoint

    !> The energy whose decrease the scheme guarantees (root attribute energy_law).
    pure function scheme_law(self) result(text)
        class(time_scheme_t), intent(in) :: self
        character(len=:), allocatable :: text

        if (self%kind == SCHEME_BDF2) then
            text = 'BDF2 G-energy (E_lin(X^n) + E_lin(2X^n - X^{n-1}))/2 + penalty(u^n)'
        else if (self%kind == SCHEME_MIDPOINT) then
            text = 'E^n of Corollary 6.2 with the time-derivative coefficients of the step''s model ' // &
                   '(rho, tau0, tau taken as 0 where negligible: stiff_limit)'
        else
            text = 'E^n of Corollary 6.2'
        end if
    end function scheme_law

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
        if (self%kind /= SCHEME_MIDPOINT) return
        if (model%rho / real(s, dp)**2 <= STIFF_RATIO * dt * (model%varpi + dt * model%alpha)) step_model%rho = 0.0_dp
        if (model%tau0 <= STIFF_RATIO * dt) step_model%tau0 = 0.0_dp
        if (model%tau <= STIFF_RATIO * dt) step_model%tau = 0.0_dp
        algebraic(F_V) = step_model%rho == 0.0_dp
        algebraic(F_Q) = step_model%tau0 == 0.0_dp
        algebraic(F_ETA) = step_model%tau == 0.0_dp
    end subroutine scheme_stiff_limit

end module time_scheme_m
