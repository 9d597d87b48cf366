!> The energy monitor (energy_m's energy_monitor_t) fed levels whose energies are known:
!>  1. Euler: E^n of each level is E_lin + 1/(2 eps) [u(1) - g]_+^2 (Corollary 6.2), written
!>     out here independently of energy_m (P1 mass products, penalty term by hand); a level
!>     whose energy rises by a known factor gives max_rise = (E^n - E^{n-1}) / E^{n-1}, a
!>     falling one leaves it; its law holds for any steps, so a rise at a changed step size
!>     (step_changed) is in max_rise too;
!>  2. BDF2: the law's energy is the G-energy (E_lin(X^n) + E_lin(2 X^n - X^{n-1}))/2 +
!>     penalty(u^n); no rise is recorded before the first level with a previous level; a rise
!>     at a step of another size (step_changed) goes to max_rise_step_change, not max_rise;
!>  3. a remesh (remeshed) gives the rise of the law energy across it, which the monitor
!>     keeps as max_rise_remesh and counts, apart from max_rise, also through a checkpoint.
!>  4. energy_m's discrete_energy (E_lin without a contact law), summed by nodes on a uniform
!>     mesh, against E_lin written out here and against its own sum by elements on the same
!>     nodes as a graded mesh, to round-off, on a smooth and on a sawtooth level (where the
!>     sums by nodes cancel most), on an odd and an even number of elements; its parts add
!>     up to it.
!> The runs' own checks (test_energy_law) see only levels whose energy falls, where a monitor
!> that compared a level with itself would also report 0.
program test_energy_monitor
    use, intrinsic :: iso_fortran_env, only: int64
    use kinds_m, only: dp
    use config_m, only: model_t
    use contact_law_m, only: contact_law_t
    use contact_laws_m, only: contact_law
    use time_scheme_m, only: time_scheme
    use state_m, only: state_t
    use energy_m, only: energy_monitor_t, discrete_energy
    use meshes_m, only: graded_mesh
    use checkpoint_m, only: checkpoint_t
    use fields_m, only: N_FIELDS, F_Q, F_THETA, F_V, F_P, F_ETA, N_ENERGY_PARTS
    use testing_m, only: check_close, check_true, test_summary
    implicit none

    integer, parameter :: S = 8
    real(dp), parameter :: G = 0.1_dp, EPS = 0.01_dp, TOL = 1.0e-13_dp
    type(model_t), parameter :: MODEL = model_t(rho=1.5_dp, alpha=0.7_dp, varpi=0.1_dp, gamma1=0.3_dp, gamma2=0.2_dp, &
                                                c=1.1_dp, d=0.2_dp, r=0.9_dp, hbar=0.8_dp, tau0=0.6_dp, tau=0.4_dp)
    class(contact_law_t), allocatable :: law
    type(state_t) :: x0

    law = contact_law('penalty', G, EPS)
    x0 = level(1.0_dp, 0.05_dp)
    call euler_checks()
    call bdf2_checks()
    call one_pass_checks()
    call test_summary('test_energy_monitor')

contains

    subroutine euler_checks()
        type(energy_monitor_t) :: monitor
        type(state_t) :: x1, x2, x3
        real(dp) :: rise, max_rise, max_rise_step_change

        call monitor%init(MODEL, MODEL, law, time_scheme('euler'), x0)
        call check_close('Euler: E^0 of the first level', energy(x0), monitor%current_energy(), TOL * energy(x0))
        x1 = level(1.3_dp, 0.08_dp)
        call monitor%observe(x1)
        call monitor%rises(max_rise, max_rise_step_change)
        rise = (energy(x1) - energy(x0)) / energy(x0)
        call check_true('Euler: the test level has a rising energy', rise > 0.5_dp)
        call check_close('Euler: E^1', energy(x1), monitor%current_energy(), TOL * energy(x1))
        call check_close('Euler: max_rise after a rising level = (E^1 - E^0)/E^0', rise, max_rise, TOL)
        x2 = level(0.5_dp, 0.02_dp)
        call monitor%observe(x2)
        call monitor%rises(max_rise, max_rise_step_change)
        call check_close('Euler: a falling level leaves max_rise', rise, max_rise, TOL)
        ! in contact: u(1) = 0.15 > g, the penalty term 1/(2 eps) (u(1) - g)^2 = 0.125 counts
        ! at a changed step size: Euler's law holds for any steps, so the rise is in max_rise
        x3 = level(0.5_dp, 0.15_dp)
        call monitor%observe(x3, step_changed=.true.)
        call monitor%rises(max_rise, max_rise_step_change)
        call check_close('Euler: E^3 with the penalty term', linear_energy(x3) + 0.5_dp / EPS * (0.15_dp - G)**2, &
                         monitor%current_energy(), TOL * energy(x3))
        call check_close('Euler: max_rise after a rise into contact', &
                         max(rise, (energy(x3) - energy(x2)) / energy(x2)), max_rise, TOL)
        call check_close('Euler: its law is not for constant steps only: max_rise_step_change stays 0', 0.0_dp, &
                         max_rise_step_change, 0.0_dp)
    end subroutine euler_checks

    subroutine bdf2_checks()
        type(energy_monitor_t) :: monitor, monitor2
        type(state_t) :: x1, x2, x3, x4
        type(checkpoint_t) :: ckpt
        real(dp) :: law_energy
        real(dp) :: rise, max_rise, max_rise_step_change, rise_remesh
        integer :: n_remeshes

        call monitor%init(MODEL, MODEL, law, time_scheme('bdf2'), x0)
        x1 = with_previous(level(0.9_dp, 0.04_dp), x0)
        call monitor%observe(x1)
        call monitor%rises(max_rise, max_rise_step_change)
        call check_close('BDF2: no rise before a G-energy exists', 0.0_dp, max_rise, 0.0_dp)
        call check_close('BDF2: E^1 (not the G-energy)', energy(x1), monitor%current_energy(), TOL * energy(x1))
        ! the law energy is private to the monitor: read it from what it saves in a checkpoint
        call monitor%checkpoint(ckpt)
        ckpt%reading = .true.
        call ckpt%sync('energy_monitor/law_energy', law_energy)
        call check_close('BDF2: the law energy is the G-energy', g_energy(x1, x0), law_energy, TOL * g_energy(x1, x0))
        x2 = with_previous(level(1.2_dp, 0.12_dp), x1)
        call monitor%observe(x2)
        call monitor%rises(max_rise, max_rise_step_change)
        rise = (g_energy(x2, x1) - g_energy(x1, x0)) / g_energy(x1, x0)
        call check_true('BDF2: the test level has a rising G-energy', rise > 0.5_dp)
        call check_close('BDF2: max_rise of the G-energy', rise, max_rise, TOL)
        x3 = with_previous(level(1.6_dp, 0.11_dp), x2)
        call monitor%observe(x3, step_changed=.true.)
        call monitor%rises(max_rise, max_rise_step_change)
        call check_close('BDF2: a rise at a changed step is not in max_rise', rise, max_rise, TOL)
        call check_close('BDF2: a rise at a changed step is in max_rise_step_change', &
                         (g_energy(x3, x2) - g_energy(x2, x1)) / g_energy(x2, x1), max_rise_step_change, TOL)
        ! a remesh as step_driver_m records it: the monitor measures the rise and keeps it
        x4 = with_previous(level(2.0_dp, 0.11_dp), x3)
        call monitor%remeshed(x4)
        call monitor%rises(max_rise, max_rise_step_change, rise_remesh, n_remeshes)
        call check_true('BDF2: a remesh is counted', n_remeshes == 1)
        call check_close('BDF2: max_rise_remesh', (g_energy(x4, x3) - g_energy(x3, x2)) / g_energy(x3, x2), &
                         rise_remesh, TOL)
        call check_close('BDF2: a remesh leaves max_rise', rise, max_rise, TOL)
        ! the remesh record through a checkpoint, on a new monitor
        ckpt = checkpoint_t()
        call monitor%checkpoint(ckpt)
        ckpt%reading = .true.
        call monitor2%init(MODEL, MODEL, law, time_scheme('bdf2'), x0)
        call monitor2%checkpoint(ckpt)
        call monitor2%rises(max_rise, max_rise_step_change, rise_remesh, n_remeshes)
        call check_true('BDF2: a checkpoint keeps the remesh count', n_remeshes == 1)
        call check_close('BDF2: a checkpoint keeps max_rise_remesh', &
                         (g_energy(x4, x3) - g_energy(x3, x2)) / g_energy(x3, x2), rise_remesh, TOL)
    end subroutine bdf2_checks

    !> A level on the uniform mesh of n elements (S if absent): every field a different smooth
    !> profile times amplitude, u(1) = u_end.
    type(state_t) function level(amplitude, u_end, n) result(x)
        real(dp), intent(in) :: amplitude, u_end
        integer, intent(in), optional :: n
        integer :: i, f
        real(dp) :: xi

        x%s = S
        if (present(n)) x%s = n
        call x%mesh%set_uniform(x%s)
        allocate (x%u(0:x%s), x%w(0:x%s, N_FIELDS))
        do i = 0, x%s
            xi = real(i, dp) / x%s
            x%u(i) = u_end * xi**2 + 0.01_dp * amplitude * sin(3.0_dp * xi)
            do f = 1, N_FIELDS
                x%w(i, f) = amplitude * cos(real(f, dp) * xi + 0.3_dp * f)
            end do
        end do
        x%u(x%s) = u_end
    end function level

    !> 4. (module header)
    subroutine one_pass_checks()
        type(state_t) :: x
        real(dp) :: by_nodes, by_elements, parts(N_ENERGY_PARTS)
        integer :: i, j, n
        character(len=40) :: tag

        do n = S - 1, S
            x = level(1.0_dp, 0.05_dp, n)
            write (tag, '(a,i0,a)') ', smooth level, ', n, ' elements'
            do i = 1, 2
                if (i == 2) then
                    x%u = 0.01_dp * [(real((-1)**j, dp), j = 0, n)]
                    x%w = spread([(real((-1)**j, dp), j = 0, n)], 2, N_FIELDS) &
                          * spread([1.0_dp, 0.5_dp, 2.0_dp, 0.7_dp, 1.3_dp], 1, n + 1)
                    write (tag, '(a,i0,a)') ', sawtooth level, ', n, ' elements'
                end if
                call discrete_energy(MODEL, x%u, x%w, x%mesh, by_nodes, parts)
                call check_close('E_lin by nodes'//trim(tag), linear_energy(x), by_nodes, TOL * linear_energy(x))
                call check_true('its parts add up to it'//trim(tag), &
                                transfer(sum(parts), 0_int64) == transfer(by_nodes, 0_int64))
                call discrete_energy(MODEL, x%u, x%w, graded_mesh(x%mesh%x), by_elements)
                call check_close('E_lin by elements (graded mesh)'//trim(tag), linear_energy(x), by_elements, &
                                 TOL * linear_energy(x))
            end do
        end do
    end subroutine one_pass_checks

    type(state_t) function with_previous(x, previous) result(y)
        type(state_t), intent(in) :: x, previous

        y = x
        y%u_prev = previous%u
        y%w_prev = previous%w
    end function with_previous

    !> E^n = E_lin + 1/(2 eps) [u(1) - g]_+^2.
    real(dp) function energy(x)
        type(state_t), intent(in) :: x

        energy = linear_energy(x) + 0.5_dp / EPS * max(x%u(x%s) - G, 0.0_dp)**2
    end function energy

    !> (E_lin(X^n) + E_lin(2 X^n - X^{n-1}))/2 + penalty(u^n) for x = X^n, previous = X^{n-1}.
    real(dp) function g_energy(x, previous)
        type(state_t), intent(in) :: x, previous
        type(state_t) :: extrapolated

        extrapolated = x
        extrapolated%u = 2.0_dp * x%u - previous%u
        extrapolated%w = 2.0_dp * x%w - previous%w
        g_energy = 0.5_dp * (linear_energy(x) + linear_energy(extrapolated)) + 0.5_dp / EPS * max(x%u(x%s) - G, 0.0_dp)**2
    end function g_energy

    !> 1/2 int (rho v^2 + alpha u_x^2 + c theta^2 + r P^2 + 2 d P theta + tau0 q^2 + tau hbar eta^2)
    !> for P1 functions on the uniform mesh of x%s elements.
    real(dp) function linear_energy(x)
        type(state_t), intent(in) :: x
        integer :: e

        linear_energy = 0.0_dp
        do e = 1, x%s
            linear_energy = linear_energy + MODEL%alpha * (x%u(e) - x%u(e - 1))**2 * x%s &
                + MODEL%rho * mass(x, e, F_V, F_V) + MODEL%c * mass(x, e, F_THETA, F_THETA) &
                + MODEL%r * mass(x, e, F_P, F_P) + 2.0_dp * MODEL%d * mass(x, e, F_P, F_THETA) &
                + MODEL%tau0 * mass(x, e, F_Q, F_Q) + MODEL%tau * MODEL%hbar * mass(x, e, F_ETA, F_ETA)
        end do
        linear_energy = 0.5_dp * linear_energy
    end function linear_energy

    !> int_e f_a f_b dx for P1 fields a, b on element e: element mass matrix h/6 [2 1; 1 2].
    real(dp) function mass(x, e, a, b)
        type(state_t), intent(in) :: x
        integer, intent(in) :: e, a, b

        mass = (2.0_dp * x%w(e - 1, a) * x%w(e - 1, b) + x%w(e - 1, a) * x%w(e, b) &
                + x%w(e, a) * x%w(e - 1, b) + 2.0_dp * x%w(e, a) * x%w(e, b)) / (6.0_dp * x%s)
    end function mass

end program test_energy_monitor
