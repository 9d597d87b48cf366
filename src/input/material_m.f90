!> &material: the physical quantities of Table 1 (SI units) and the nondimensional &model
!> coefficients computed from them by (2.10)-(2.11), their check, and the echo of both on
!> standard output.
module material_m
    use, intrinsic :: iso_fortran_env, only: output_unit
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use kinds_m, only: dp
    use errors_m, only: fatal, EXIT_INPUT
    use config_m, only: config_t, material_t, model_t
    use strings_m, only: format_real
    use input_vars_m, only: INPUT_VARS, input_item_t, input_item
    implicit none
    private
    public :: nondim_t, nondim_groups, model_from_material, check_material, echo_material
    public :: si_scale_t, si_scales

    !> Nondimensional groups of (2.10) computed from &material.
    type :: nondim_t
        real(dp) :: beta1 = 0.0_dp      !< (3 lambda + 2 mu) alpha_t
        real(dp) :: beta2 = 0.0_dp      !< (3 lambda + 2 mu) alpha_c
        real(dp) :: omega = 0.0_dp      !< time scale rho0 cE ell^2 / kappa [s]
        real(dp) :: delta = 0.0_dp      !< sqrt((lambda + 2 mu) / (rho0 cE T0))
        real(dp) :: varsigma = 0.0_dp   !< rho0 ell^2 / (omega^2 (lambda + 2 mu))
        real(dp) :: zeta = 0.0_dp       !< (lambda' + 2 mu') / (omega (lambda + 2 mu))
        real(dp) :: a_check = 0.0_dp    !< a-check = T0 beta1^2 / (rho0 cE (lambda + 2 mu))
        real(dp) :: alpha1 = 0.0_dp     !< (lambda + 2 mu) nu / (beta1 beta2)
        real(dp) :: alpha2 = 0.0_dp     !< (lambda + 2 mu) ell^2 / (D beta2^2 omega)
        real(dp) :: alpha3 = 0.0_dp     !< (lambda + 2 mu) varrho / beta2^2
    end type nondim_t

    !> One scale of the nondimensional variables of (2.10): a quantity in SI units is
    !> `factor` times its nondimensional value (x = ell x*, t = omega t*, ...).
    type :: si_scale_t
        character(len=24) :: name = ''    !< as fields_m's scale column
        real(dp) :: factor = 0.0_dp
        character(len=16) :: units = ''   !< SI units of factor
    end type si_scale_t

contains

    !> The scales of (2.10) for &material `mat`: x* = x/ell, t* = t/omega,
    !> theta = beta1 (T - T0)/((lambda + 2 mu) delta), P* = P/(beta2 delta),
    !> q* = omega beta1 q/(rho0 cE delta ell (lambda + 2 mu)), eta* = ell eta/(D beta2 delta).
    !> Displacement and stress: (2.10) follows from (2.1)-(2.9) only with u* = u/(delta ell)
    !> (the coupling a-check of the heat equation and u_xx - theta_x of the momentum equation
    !> both need it; the paper prints u* = delta u/ell), so u = delta ell u*, v = u_t takes the
    !> displacement over the time scale, and the stress of (2.10) is (lambda + 2 mu) delta
    !> times sigma*; the sigma of (2.11) (the code's, /series/contact_stress, /snapshots/sigma)
    !> is a-check times that of (2.10), hence (lambda + 2 mu) delta / a-check.
    !> The energy E^n of Corollary 6.2 (per unit cross-section, J/m^2): its thermal term
    !> 1/2 int theta^2 dx* is 1/2 int rho0 cE (T - T0)^2 / T0 dx over ell, which with the
    !> temperature scale is ell (lambda + 2 mu) delta^2 / a-check times it.
    pure function si_scales(mat) result(scales)
        type(material_t), intent(in) :: mat
        type(si_scale_t) :: scales(10)
        type(nondim_t) :: nd
        real(dp) :: stiffness

        nd = nondim_groups(mat)
        stiffness = mat%lambda + 2.0_dp * mat%mu
        scales(1) = si_scale_t('time', nd%omega, 's')
        scales(2) = si_scale_t('position', mat%ell, 'm')
        scales(3) = si_scale_t('displacement', mat%ell * nd%delta, 'm')
        scales(4) = si_scale_t('velocity', mat%ell * nd%delta / nd%omega, 'm/s')
        scales(5) = si_scale_t('temperature', stiffness * nd%delta / nd%beta1, 'K')   ! of T - T0
        scales(6) = si_scale_t('chemical_potential', nd%beta2 * nd%delta, 'J/kg')
        scales(7) = si_scale_t('stress', stiffness * nd%delta / nd%a_check, 'Pa')
        scales(8) = si_scale_t('heat_flux', mat%rho0 * mat%cE * nd%delta * mat%ell * stiffness / (nd%omega * nd%beta1), &
                               'W/m^2')
        scales(9) = si_scale_t('diffusion_flux', mat%D * nd%beta2 * nd%delta / mat%ell, 'kg/(m^2 s)')
        scales(10) = si_scale_t('energy', mat%ell * stiffness * nd%delta**2 / nd%a_check, 'J/m^2')
    end function si_scales

    !> The nondimensional groups of (2.10) for the physical quantities `mat`.
    pure function nondim_groups(mat) result(nd)
        type(material_t), intent(in) :: mat
        type(nondim_t) :: nd
        real(dp) :: stiffness   ! lambda + 2 mu

        stiffness = mat%lambda + 2.0_dp * mat%mu
        nd%beta1 = (3.0_dp * mat%lambda + 2.0_dp * mat%mu) * mat%alpha_t
        nd%beta2 = (3.0_dp * mat%lambda + 2.0_dp * mat%mu) * mat%alpha_c
        nd%omega = mat%rho0 * mat%cE * mat%ell**2 / mat%kappa
        nd%delta = sqrt(stiffness / (mat%rho0 * mat%cE * mat%T0))
        nd%varsigma = mat%rho0 * mat%ell**2 / (nd%omega**2 * stiffness)
        nd%zeta = (mat%lambda_v + 2.0_dp * mat%mu_v) / (nd%omega * stiffness)
        nd%a_check = mat%T0 * nd%beta1**2 / (mat%rho0 * mat%cE * stiffness)
        nd%alpha1 = stiffness * mat%nu / (nd%beta1 * nd%beta2)
        nd%alpha2 = stiffness * mat%ell**2 / (mat%D * nd%beta2**2 * nd%omega)
        nd%alpha3 = stiffness * mat%varrho / nd%beta2**2
    end function nondim_groups

    !> The coefficients of (2.11) for the physical quantities `mat`; relaxation times are
    !> scaled as tau0* = tau0/omega, tau* = tau/omega.
    pure function model_from_material(mat) result(m)
        type(material_t), intent(in) :: mat
        type(model_t) :: m
        type(nondim_t) :: nd

        nd = nondim_groups(mat)
        associate (a => nd%a_check, alpha1 => nd%alpha1, alpha2 => nd%alpha2, alpha3 => nd%alpha3)
            m%rho = a * nd%varsigma
            m%alpha = a * (1.0_dp - 1.0_dp / alpha3)
            m%varpi = nd%zeta * a
            m%gamma1 = a * (1.0_dp + alpha1 / alpha3)
            m%gamma2 = a / alpha3
            m%c = 1.0_dp + a * alpha1**2 / alpha3
            m%d = alpha1 * a / alpha3
            m%r = a / alpha3
            m%hbar = a / alpha2
        end associate
        m%tau0 = mat%tau0 / nd%omega
        m%tau = mat%tau / nd%omega
    end function model_from_material

    !> &material must be such that (2.10)-(2.11) can be evaluated: checked here, since the
    !> reader computes &model from it (validate_m then checks the &model values).
    subroutine check_material(mat)
        type(material_t), intent(in) :: mat
        character(len=*), parameter :: names(16) = [character(len=8) :: 'T0', 'rho0', 'cE', 'kappa', &
            'mu', 'alpha_t', 'alpha_c', 'D', 'varrho', 'ell', 'nu', 'tau0', 'tau', 'lambda_v', 'mu_v', 'lambda']
        !  > 0 for the first 10, >= 0 for the next 5, any finite value for lambda
        real(dp) :: values(16)
        integer :: k

        values = [mat%T0, mat%rho0, mat%cE, mat%kappa, mat%mu, mat%alpha_t, mat%alpha_c, mat%D, mat%varrho, &
                  mat%ell, mat%nu, mat%tau0, mat%tau, mat%lambda_v, mat%mu_v, mat%lambda]
        do k = 1, size(values)
            associate (x => values(k), where => 'material.' // trim(names(k)))
                if (.not. ieee_is_finite(x)) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be a finite real number')
                if (k <= 10 .and. .not. x > 0.0_dp) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be > 0')
                if (k > 10 .and. k <= 15 .and. .not. x >= 0.0_dp) &
                    call fatal(EXIT_INPUT, where, 'got ' // format_real(x) // '; must be >= 0')
            end associate
        end do
        if (.not. 3.0_dp * mat%lambda + 2.0_dp * mat%mu > 0.0_dp) call fatal(EXIT_INPUT, 'material.lambda', &
            'got ' // format_real(mat%lambda) // ' with mu = ' // format_real(mat%mu) // &
            '; 3 lambda + 2 mu must be > 0 (beta1, beta2 of (2.2))')
    end subroutine check_material

    !> Echo the physical values of cfg%material, the nondimensional groups nd computed from
    !> them and the &model values cfg%model (stdout).
    subroutine echo_material(cfg, nd)
        type(config_t), intent(in) :: cfg
        type(nondim_t), intent(in) :: nd

        write (output_unit, '(a)') 'rodcontact: &material (SI units) -> &model by (2.10)-(2.11)'
        write (output_unit, '(2x, a)') 'physical'
        call echo_group(cfg, 'material')
        write (output_unit, '(2x, a)') 'derived (2.10)'
        call echo_row('beta1', nd%beta1, 'kg/(m s^2 K)')
        call echo_row('beta2', nd%beta2, 'm^2/s^2')
        call echo_row('omega', nd%omega, 's  (t = omega t*)')
        call echo_row('delta', nd%delta, '')
        call echo_row('varsigma', nd%varsigma, '')
        call echo_row('zeta', nd%zeta, '')
        call echo_row('a_check', nd%a_check, '')
        call echo_row('alpha1', nd%alpha1, '')
        call echo_row('alpha2', nd%alpha2, '')
        call echo_row('alpha3', nd%alpha3, '')
        write (output_unit, '(2x, a)') '&model (2.11)'
        call echo_group(cfg, 'model')
        flush (output_unit)
    end subroutine echo_material

    !> One row per variable of `group` (all real), with its unit or note from INPUT_VARS.
    subroutine echo_group(cfg, group)
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in) :: group
        type(input_item_t) :: item
        integer :: k

        do k = 1, size(INPUT_VARS)
            if (INPUT_VARS(k)%group /= group) cycle
            item = input_item(cfg, k)
            call echo_row(trim(INPUT_VARS(k)%name), item%reals(1), trim(INPUT_VARS(k)%unit))
        end do
    end subroutine echo_group

    subroutine echo_row(name, value, unit)
        character(len=*), intent(in) :: name, unit
        real(dp), intent(in) :: value
        character(len=120) :: row

        write (row, '(4x, a, t17, "= ", es13.6, 2x, a)') name, value, unit
        write (output_unit, '(a)') trim(row)
    end subroutine echo_row

end module material_m
