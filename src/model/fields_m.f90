!> The one description of the fields of (2.11)/(6.1) and of the /series datasets. State,
!> scheme, energy, output, checkpoint/restart and validation iterate over these tables
!> instead of naming the fields one by one (see docs/architecture.md, "Adding a field").
!>
!> Fields: the five unknowns of (6.1) at t_n, q, theta, v, P, eta (F_Q..F_ETA, in the order
!> within a node of the interleaved system, chosen for the band width: scheme_m), and the
!> displacement u (F_U = 0), which is not an unknown of (6.1): u^n = u^{n-1} + dt v^n.
!> A state holds u(0:s) and w(0:s, 1:N_FIELDS); the checkpoint stores them as the columns
!> F_U+1 .. N_FIELDS+1, i.e. u, q, theta, v, P, eta.
module fields_m
    use kinds_m, only: dp
    implicit none
    private
    public :: N_FIELDS, F_U, F_Q, F_THETA, F_V, F_P, F_ETA
    public :: field_t, FIELDS, N_OUTPUT_FIELDS, OUTPUT_ORDER, is_dirichlet, zero_dirichlet
    public :: series_t, SERIES, N_SERIES, S_T, S_ENERGY, S_U_END, S_PENETRATION, S_CONTACT_STRESS, S_ITERATIONS, S_DT, &
              S_N_ELEMENTS, N_ENERGY_PARTS, S_ENERGY_PARTS
    public :: snapshot_t, SNAPSHOTS, N_SNAPSHOT_FIELDS, K_SIGMA

    integer, parameter :: N_FIELDS = 5
    integer, parameter :: F_U = 0, F_Q = 1, F_THETA = 2, F_V = 3, F_P = 4, F_ETA = 5

    !> What a field is (its term in E^n: energy_m).
    type :: field_t
        character(len=8) :: name
        character(len=3) :: space        !< 'S_h' (zero at x = 0) or 'V_h' (zero at x = 1)
        character(len=40) :: long_name
        character(len=8) :: units        !< '1': nondimensional, scales of (2.10)
        character(len=24) :: scale       !< which scale of (2.10): root attribute scale.<scale> (&material)
    end type field_t

    !> Indexed by F_*; names as in the output file (docs/output.md).
    type(field_t), parameter :: FIELDS(F_U:N_FIELDS) = [ &
        field_t('u', 'S_h', 'displacement', '1', 'displacement'), &
        field_t('q', 'S_h', 'heat flux', '1', 'heat_flux'), &
        field_t('theta', 'V_h', 'temperature', '1', 'temperature'), &
        field_t('v', 'S_h', 'velocity', '1', 'velocity'), &
        field_t('P', 'V_h', 'chemical potential', '1', 'chemical_potential'), &
        field_t('eta', 'S_h', 'diffusion flux', '1', 'diffusion_flux')]

    !> The order of the fields in /snapshots (and of every reader): u, v, theta, P, q, eta.
    integer, parameter :: N_OUTPUT_FIELDS = N_FIELDS + 1
    integer, parameter :: OUTPUT_ORDER(N_OUTPUT_FIELDS) = [F_U, F_V, F_THETA, F_P, F_Q, F_ETA]

    !> One /series dataset (docs/output.md): one value per stored time level.
    type :: series_t
        character(len=16) :: name
        character(len=48) :: long_name
        logical :: is_integer            !< stored as int32 (else float64)
        character(len=8) :: units        !< '1': nondimensional, scales of (2.10)
        character(len=24) :: scale       !< as field_t's scale; '' when there is no physical scale
    end type series_t

    !> The datasets (rows of SERIES): N_SCALAR_SERIES of their own (S_*), then the terms
    !> of E^n (energy_m's discrete_energy, in this order, S_ENERGY_PARTS), which add up to
    !> /series/energy.
    integer, parameter :: S_T = 1, S_ENERGY = 2, S_U_END = 3, S_PENETRATION = 4, S_CONTACT_STRESS = 5, &
                          S_ITERATIONS = 6, S_DT = 7, S_N_ELEMENTS = 8, N_SCALAR_SERIES = 8
    integer, parameter :: N_ENERGY_PARTS = 8
    integer, parameter :: N_SERIES = N_SCALAR_SERIES + N_ENERGY_PARTS
    integer :: k_   !< the index of the implied do loops of S_ENERGY_PARTS and SNAPSHOTS
    integer, parameter :: S_ENERGY_PARTS(N_ENERGY_PARTS) = N_SCALAR_SERIES + [(k_, k_ = 1, N_ENERGY_PARTS)]
    type(series_t), parameter :: SERIES(N_SERIES) = [ &
        series_t('t', 'time t_n', .false., '1', 'time'), &
        series_t('energy', 'discrete energy E^n of Corollary 6.2', .false., '1', 'energy'), &
        series_t('u_end', 'displacement of the free end u(1,t)', .false., '1', 'displacement'), &
        series_t('penetration', 'penetration [u(1,t) - g]_+', .false., '1', 'displacement'), &
        series_t('contact_stress', 'contact stress sigma(1,t)', .false., '1', 'stress'), &
        series_t('iterations', 'linear solves of the step', .true., '1', ''), &
        series_t('dt', 'step t_n - t_{n-1} (0 at t = 0)', .false., '1', 'time'), &
        series_t('n_elements', 'elements of the mesh of t_n', .true., '1', ''), &
        series_t('energy_kinetic', 'kinetic part of E^n: 1/2 int rho v^2', .false., '1', 'energy'), &
        series_t('energy_strain', 'strain part of E^n: 1/2 int alpha u_x^2', .false., '1', 'energy'), &
        series_t('energy_thermal', 'thermal part of E^n: 1/2 int c theta^2', .false., '1', 'energy'), &
        series_t('energy_chemical', 'chemical part of E^n: 1/2 int r P^2', .false., '1', 'energy'), &
        series_t('energy_coupling', 'theta-P part of E^n: int d theta P', .false., '1', 'energy'), &
        series_t('energy_heat_flux', 'heat-flux part of E^n: 1/2 int tau0 q^2', .false., '1', 'energy'), &
        series_t('energy_mass_flux', 'mass-flux part of E^n: 1/2 int tau hbar eta^2', .false., '1', 'energy'), &
        series_t('energy_contact', 'contact part of E^n: [u(1) - g]_+^2 / (2 eps)', .false., '1', 'energy')]

    !> One /snapshots dataset (docs/output.md): a field of OUTPUT_ORDER, or a quantity derived
    !> from the fields (K_SIGMA: the stress of (2.14), stress_m).
    type :: snapshot_t
        character(len=8) :: name
        character(len=64) :: long_name
        character(len=8) :: units        !< '1': nondimensional
        character(len=24) :: scale       !< as field_t's scale
    end type snapshot_t

    type(field_t), parameter :: OUT(N_OUTPUT_FIELDS) = FIELDS(OUTPUT_ORDER)   !< the output fields in order
    integer, parameter :: N_SNAPSHOT_FIELDS = N_OUTPUT_FIELDS + 1
    integer, parameter :: K_SIGMA = N_OUTPUT_FIELDS + 1
    !> The /snapshots datasets in their order: the fields of OUTPUT_ORDER (one row each,
    !> N_OUTPUT_FIELDS of them), then sigma.
    type(snapshot_t), parameter :: SNAPSHOTS(N_SNAPSHOT_FIELDS) = [ &
        (snapshot_t(OUT(k_)%name, OUT(k_)%long_name, OUT(k_)%units, OUT(k_)%scale), k_ = 1, N_OUTPUT_FIELDS), &
        snapshot_t('sigma', 'stress sigma = alpha u_x + varpi v_x - gamma1 theta - gamma2 P', '1', 'stress')]

contains

    !> Is (field, node) a Dirichlet value on a mesh with nodes 0..s? S_h fields vanish at
    !> x = 0, V_h fields at x = 1 (Section 6).
    pure logical function is_dirichlet(field, node, s)
        integer, intent(in) :: field, node, s

        if (FIELDS(field)%space == 'S_h') then
            is_dirichlet = node == 0
        else
            is_dirichlet = node == s
        end if
    end function is_dirichlet

    !> The Dirichlet values of the fields w(0:s, 1:N_FIELDS) (or of their equations' rows) zero.
    pure subroutine zero_dirichlet(w)
        real(dp), intent(inout) :: w(0:, :)
        integer :: f, s

        s = ubound(w, 1)
        do f = 1, N_FIELDS
            if (is_dirichlet(f, 0, s)) w(0, f) = 0.0_dp
            if (is_dirichlet(f, s, s)) w(s, f) = 0.0_dp
        end do
    end subroutine zero_dirichlet

end module fields_m
