!> Manufactured solutions of (2.11) for the verification tests. Each field is a product
!> X(x) T(t) of two one-variable profiles with analytic derivatives; the source terms of
!> sources_m are computed from the strong form (2.11) so that the product is an exact
!> solution, and the traction b(t) at x = 1 makes it satisfy the normal-compliance
!> condition sigma(1,t) = -(1/eps)[u(1,t) - g]_+ + b(t).
module mms_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use sources_m, only: source_t
    use fields_m, only: N_FIELDS, F_Q, F_THETA, F_V, F_P, F_ETA
    implicit none
    private
    public :: profile_t, mms_t, mms_no_contact, mms_contact, mms_linear_in_x, mms_linear_in_t
    public :: U_FIELD, N_EXACT

    integer, parameter :: U_FIELD = N_FIELDS + 1   !< index of u among the exact fields
    integer, parameter :: N_EXACT = N_FIELDS + 1   !< q, theta, v, P, eta, u

    !> a * g(k z) + poly(z), g in {sin, cos, exp, none}; derivatives of order 0..2.
    type :: profile_t
        character(len=4) :: kind = 'none'
        real(dp) :: a = 0.0_dp
        real(dp) :: k = 1.0_dp
        real(dp) :: poly(0:3) = 0.0_dp
    contains
        procedure :: d => profile_derivative
    end type profile_t

    !> fields: X and T profiles of u, theta, P, q, eta.
    type, extends(source_t) :: mms_t
        type(model_t) :: model
        real(dp) :: eps = 0.01_dp, g = 0.1_dp
        type(profile_t) :: xu, tu, xth, tth, xp, tp, xq, tq, xeta, teta
    contains
        procedure :: evaluate => mms_sources
        procedure :: traction => mms_traction
        procedure :: exact => mms_exact
    end type mms_t

contains

    pure real(dp) function profile_derivative(self, z, order)
        class(profile_t), intent(in) :: self
        real(dp), intent(in) :: z
        integer, intent(in) :: order
        real(dp) :: kz, p

        kz = self%k * z
        select case (self%kind)
        case ('sin'); p = self%a * self%k**order * trig(kz, order)
        case ('cos'); p = self%a * self%k**order * trig(kz, order + 1)
        case ('exp'); p = self%a * self%k**order * exp(kz)
        case default; p = 0.0_dp
        end select
        select case (order)
        case (0); p = p + self%poly(0) + z * (self%poly(1) + z * (self%poly(2) + z * self%poly(3)))
        case (1); p = p + self%poly(1) + z * (2 * self%poly(2) + 3 * z * self%poly(3))
        case (2); p = p + 2 * self%poly(2) + 6 * z * self%poly(3)
        end select
        profile_derivative = p
    end function profile_derivative

    !> d^n/dz^n sin(z): sin, cos, -sin, -cos, ...
    pure real(dp) function trig(z, n)
        real(dp), intent(in) :: z
        integer, intent(in) :: n

        select case (mod(n, 4))
        case (0); trig = sin(z)
        case (1); trig = cos(z)
        case (2); trig = -sin(z)
        case default; trig = -cos(z)
        end select
    end function trig

    !> Right-hand sides of (2.11) for the exact fields (sources_m's convention).
    pure function mms_sources(self, t, x) result(f)
        class(mms_t), intent(in) :: self
        real(dp), intent(in) :: t, x
        real(dp) :: f(N_FIELDS)
        real(dp) :: u_tt, u_xx, u_xxt, u_xt, th_x, th_t, p_x, p_t, q, q_x, q_t, eta, eta_x, eta_t

        associate (m => self%model)
            u_tt = self%xu%d(x, 0) * self%tu%d(t, 2)
            u_xx = self%xu%d(x, 2) * self%tu%d(t, 0)
            u_xxt = self%xu%d(x, 2) * self%tu%d(t, 1)
            u_xt = self%xu%d(x, 1) * self%tu%d(t, 1)
            th_x = self%xth%d(x, 1) * self%tth%d(t, 0)
            th_t = self%xth%d(x, 0) * self%tth%d(t, 1)
            p_x = self%xp%d(x, 1) * self%tp%d(t, 0)
            p_t = self%xp%d(x, 0) * self%tp%d(t, 1)
            q = self%xq%d(x, 0) * self%tq%d(t, 0)
            q_x = self%xq%d(x, 1) * self%tq%d(t, 0)
            q_t = self%xq%d(x, 0) * self%tq%d(t, 1)
            eta = self%xeta%d(x, 0) * self%teta%d(t, 0)
            eta_x = self%xeta%d(x, 1) * self%teta%d(t, 0)
            eta_t = self%xeta%d(x, 0) * self%teta%d(t, 1)
            f(F_V) = m%rho * u_tt - m%alpha * u_xx - m%varpi * u_xxt + m%gamma1 * th_x + m%gamma2 * p_x
            f(F_THETA) = m%c * th_t + m%d * p_t + q_x + m%gamma1 * u_xt
            f(F_Q) = m%tau0 * q_t + q + th_x
            f(F_P) = m%d * th_t + m%r * p_t + m%hbar * eta_x + m%gamma2 * u_xt
            f(F_ETA) = m%tau * eta_t + eta + p_x
        end associate
    end function mms_sources

    !> b(t) = sigma(1,t) + (1/eps)[u(1,t) - g]_+ for the exact fields.
    pure real(dp) function mms_traction(self, t)
        class(mms_t), intent(in) :: self
        real(dp), intent(in) :: t
        real(dp) :: sigma, u_end

        associate (m => self%model)
            sigma = m%alpha * self%xu%d(1.0_dp, 1) * self%tu%d(t, 0) + m%varpi * self%xu%d(1.0_dp, 1) * self%tu%d(t, 1) &
                    - m%gamma1 * self%xth%d(1.0_dp, 0) * self%tth%d(t, 0) - m%gamma2 * self%xp%d(1.0_dp, 0) * self%tp%d(t, 0)
        end associate
        u_end = self%xu%d(1.0_dp, 0) * self%tu%d(t, 0)
        mms_traction = sigma + max(u_end - self%g, 0.0_dp) / self%eps
    end function mms_traction

    !> Exact field (scheme_m's F_* index, or U_FIELD) or its x-derivative (dx = 1) at (t, x).
    pure real(dp) function mms_exact(self, field, t, x, dx)
        class(mms_t), intent(in) :: self
        integer, intent(in) :: field, dx
        real(dp), intent(in) :: t, x

        select case (field)
        case (U_FIELD); mms_exact = self%xu%d(x, dx) * self%tu%d(t, 0)
        case (F_V); mms_exact = self%xu%d(x, dx) * self%tu%d(t, 1)
        case (F_THETA); mms_exact = self%xth%d(x, dx) * self%tth%d(t, 0)
        case (F_P); mms_exact = self%xp%d(x, dx) * self%tp%d(t, 0)
        case (F_Q); mms_exact = self%xq%d(x, dx) * self%tq%d(t, 0)
        case default; mms_exact = self%xeta%d(x, dx) * self%teta%d(t, 0)
        end select
    end function mms_exact

    !> Smooth in x and t, boundary values of the spaces, u(1,t) <= 0.06 < g: no contact.
    function mms_no_contact(model) result(m)
        type(model_t), intent(in) :: model
        type(mms_t) :: m
        real(dp), parameter :: pi = acos(-1.0_dp)

        m%model = model
        m%xu = profile_t(kind='sin', a=0.03_dp, k=0.5_dp * pi)            ! u = 0.03 sin(pi x/2)(1 + sin 2t)
        m%tu = profile_t(kind='sin', a=1.0_dp, k=2.0_dp, poly=[1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])
        m%xth = profile_t(kind='cos', a=2.0_dp, k=0.5_dp * pi)            ! theta = 2 cos(pi x/2) e^{-t}
        m%tth = profile_t(kind='exp', a=1.0_dp, k=-1.0_dp)
        m%xp = profile_t(poly=[1.0_dp, 0.0_dp, -1.0_dp, 0.0_dp])          ! P = (1 - x^2) cos 3t
        m%tp = profile_t(kind='cos', a=1.0_dp, k=3.0_dp)
        m%xq = profile_t(kind='sin', a=1.5_dp, k=pi)                      ! q = 1.5 sin(pi x) cos 2t
        m%tq = profile_t(kind='cos', a=1.0_dp, k=2.0_dp)
        m%xeta = profile_t(poly=[0.0_dp, 2.0_dp, -1.0_dp, 0.0_dp])        ! eta = x (2 - x) e^{-2t}
        m%teta = profile_t(kind='exp', a=1.0_dp, k=-2.0_dp)
    end function mms_no_contact

    !> As mms_no_contact, but u = x (g + 0.02 sin(2 pi t)) sin-modulated in x: the end
    !> penetrates the obstacle (penalised contact) for t in (0, 1/2) and leaves it after.
    function mms_contact(model, eps, g) result(m)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: eps, g
        type(mms_t) :: m
        real(dp), parameter :: pi = acos(-1.0_dp)

        m = mms_no_contact(model)
        m%eps = eps
        m%g = g
        m%xu = profile_t(kind='sin', a=1.0_dp, k=0.5_dp * pi)            ! u = sin(pi x/2)(g + 0.02 sin 2 pi t)
        m%tu = profile_t(kind='sin', a=0.02_dp, k=2.0_dp * pi, poly=[g, 0.0_dp, 0.0_dp, 0.0_dp])
    end function mms_contact

    !> Every field linear in x (so in the P1 spaces): the spatial error vanishes and only the
    !> time discretisation error remains. contact = .true.: u(1,t) = g + 0.02 sin(2 pi t).
    function mms_linear_in_x(model, eps, g, contact) result(m)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: eps, g
        logical, intent(in) :: contact
        type(mms_t) :: m
        real(dp), parameter :: pi = acos(-1.0_dp)

        m = mms_no_contact(model)
        m%eps = eps
        m%g = g
        m%xu = profile_t(poly=[0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp])
        m%tu = profile_t(kind='sin', a=0.02_dp, k=2.0_dp, poly=[0.03_dp, 0.0_dp, 0.0_dp, 0.0_dp])
        if (contact) m%tu = profile_t(kind='sin', a=0.02_dp, k=2.0_dp * pi, poly=[g, 0.0_dp, 0.0_dp, 0.0_dp])
        m%xth = profile_t(poly=[2.0_dp, -2.0_dp, 0.0_dp, 0.0_dp])
        m%xp = profile_t(poly=[1.0_dp, -1.0_dp, 0.0_dp, 0.0_dp])
        m%xq = profile_t(poly=[0.0_dp, 1.5_dp, 0.0_dp, 0.0_dp])
        m%xeta = profile_t(poly=[0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp])
    end function mms_linear_in_x

    !> Every field linear in t and v = u_t constant in time: implicit Euler is exact in
    !> time, and only the spatial error remains. contact = .true.: u(1,t) = 0.5 t crosses
    !> g = 0.1 at t = 0.2.
    function mms_linear_in_t(model, eps, g, contact) result(m)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: eps, g
        logical, intent(in) :: contact
        type(mms_t) :: m

        m = mms_no_contact(model)
        m%eps = eps
        m%g = g
        m%tu = profile_t(poly=[0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp])          ! u(1,t) = 0.03 t (no contact)
        if (contact) m%tu = profile_t(poly=[0.0_dp, 0.5_dp / 0.03_dp, 0.0_dp, 0.0_dp])
        m%tth = profile_t(poly=[1.0_dp, -0.5_dp, 0.0_dp, 0.0_dp])
        m%tp = profile_t(poly=[1.0_dp, 0.3_dp, 0.0_dp, 0.0_dp])
        m%tq = profile_t(poly=[1.0_dp, -0.2_dp, 0.0_dp, 0.0_dp])
        m%teta = profile_t(poly=[0.5_dp, 0.4_dp, 0.0_dp, 0.0_dp])
    end function mms_linear_in_t

end module mms_m
