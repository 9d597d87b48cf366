!> Run configuration: one derived type per namelist group (docs/input.md), with the
!> defaults built into the types (the paper's values (7.1) and discretisation), and the
!> rules that belong to the settings themselves (the number of time steps).
!>
!> These types are the one list of input variables: every component of config_t of a
!> derived type is a namelist group, every component of that type an input variable, in
!> the order of the messages, the &material echo and the output file. The build generates
!> input_vars_m's table and namelist reads from them (src/input/generate_input_vars.py), so
!> a new input variable is one line here of a type the generator takes, and its line in
!> docs/input.md (docs/architecture.md, "An input variable": the types, `[unit]`, `!< not an
!> input`). The reader is config_reader_m.
module config_m
    use kinds_m, only: dp
    implicit none
    private
    public :: model_t, contact_t, mesh_t, time_t, initial_t, solver_t, output_t, material_t, config_t
    public :: MAX_POLY_DEGREE, LEN_NAME, LEN_PATH, MAX_COMPRESSION
    public :: number_of_steps, with_contact_mass

    integer, parameter :: MAX_POLY_DEGREE = 8   !< *_poly coefficients 0..8 (constant term first)
    integer, parameter :: LEN_NAME = 32         !< length of keyword values ('penalty', 'euler', ...)
    integer, parameter :: LEN_PATH = 1024       !< length of path values (prefix, restart_from)
    integer, parameter :: MAX_COMPRESSION = 9   !< &output compression: HDF5's deflate levels 0 (none) .. 9

    !> &model: nondimensional coefficients of (2.11); defaults are the copper values (7.1).
    type :: model_t
        real(dp) :: rho = 1.2298e-17_dp
        real(dp) :: alpha = 0.0163_dp
        real(dp) :: varpi = 0.1_dp
        real(dp) :: gamma1 = 0.01931_dp
        real(dp) :: gamma2 = 4.635e-4_dp
        real(dp) :: c = 1.0136_dp
        real(dp) :: d = 0.00251_dp
        real(dp) :: r = 4.635e-4_dp
        real(dp) :: hbar = 0.03058_dp
        real(dp) :: tau0 = 0.02_dp   !< tau0 of &material / omega, in the echo [(tau0/omega)]
        real(dp) :: tau = 0.2_dp     !< tau of &material / omega, in the echo [(tau/omega)]
        ! the velocity's mass (fe_m's inertia_element), set from &contact mass by with_contact_mass
        real(dp) :: mass_lumped = 0.0_dp     !< not an input: the lumped fraction of the blend
        logical :: mass_end_moved = .false.  !< not an input: the contact node massless
    end type model_t

    !> &contact: obstacle gap g and normal compliance (3.4) with penalty eps.
    type :: contact_t
        real(dp) :: g = 0.1_dp
        real(dp) :: eps = 0.01_dp
        character(len=LEN_NAME) :: law = 'penalty'
        character(len=LEN_NAME) :: mass = 'consistent'
    end type contact_t

    !> &mesh: uniform partition of [0,1] into n_elements elements (h = 1/s); with adaptive =
    !> .true. the coarsest mesh, bisected up to max_level times where the error indicator
    !> (adaptive_mesh_m) exceeds error_tol, checked every remesh_every steps.
    type :: mesh_t
        integer :: n_elements = 500
        logical :: adaptive = .false.
        real(dp) :: error_tol = 1.0e-3_dp   !< relative L2 interpolation error per unit length
        integer :: max_level = 5
        integer :: remesh_every = 10
    end type mesh_t

    !> &time: step dt up to t_end; with adaptive = .true., dt is the first step and the
    !> steps are chosen by the local error estimate (step_control_m) within [dt_min, dt_max].
    type :: time_t
        real(dp) :: dt = 1.0e-4_dp
        real(dp) :: t_end = 1.0_dp
        character(len=LEN_NAME) :: scheme = 'euler'
        character(len=LEN_PATH) :: restart_from = ''
        logical :: adaptive = .false.
        real(dp) :: error_tol = 1.0e-5_dp   !< local error per step / largest energy norm so far
        real(dp) :: dt_min = 1.0e-10_dp
        real(dp) :: dt_max = 1.0_dp
    end type time_t

    !> &initial: initial data (2.12) as polynomials in x plus optional steps (amp, x_end)
    !> and tables (*_file: rows of position and value, read into *_table by config_reader_m).
    type :: initial_t
        real(dp) :: u0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: u1_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: theta0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: p0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: q0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: eta0_poly(0:MAX_POLY_DEGREE) = 0.0_dp
        real(dp) :: theta0_step(2) = 0.0_dp   !< (amplitude, x_end): adds amplitude where x <= x_end
        real(dp) :: p0_step(2) = 0.0_dp
        character(len=LEN_PATH) :: u0_file = ''
        character(len=LEN_PATH) :: u1_file = ''
        character(len=LEN_PATH) :: theta0_file = ''
        character(len=LEN_PATH) :: p0_file = ''
        character(len=LEN_PATH) :: q0_file = ''
        character(len=LEN_PATH) :: eta0_file = ''
        real(dp), allocatable :: u0_table(:, :)   !< not an input: u0_file's rows (position, value)
        real(dp), allocatable :: u1_table(:, :)       !< not an input
        real(dp), allocatable :: theta0_table(:, :)   !< not an input
        real(dp), allocatable :: p0_table(:, :)       !< not an input
        real(dp), allocatable :: q0_table(:, :)       !< not an input
        real(dp), allocatable :: eta0_table(:, :)     !< not an input
    end type initial_t

    !> &solver: how the per-step nonlinearity (contact node) is solved.
    type :: solver_t
        character(len=LEN_NAME) :: method = 'monolithic'
        real(dp) :: tol = 1.0e-7_dp
        integer :: max_iter = 50
    end type solver_t

    !> &output: HDF5 file <prefix>.h5 and what goes into it (each variable: docs/input.md;
    !> compression's default: docs/performance.md, "Output: chunks and compression").
    type :: output_t
        character(len=LEN_PATH) :: prefix = 'out/run'
        integer :: snapshot_every = 100
        real(dp) :: snapshot_dt = 0.0_dp
        integer :: series_every = 1
        real(dp) :: series_dt = 0.0_dp
        logical :: snapshot_land = .true.
        integer :: checkpoint_every = 0
        integer :: compression = 0
        logical :: quiet = .false.
        integer :: n_points = 0
        logical :: error_estimate = .false.
    end type output_t

    !> &material (optional): physical quantities of Table 1 in SI units, from which the
    !> &model values are computed by (2.10)-(2.11) when the group is present; every other
    !> input with a unit is then in SI units too (units = 'SI' says so, material_m converts).
    type :: material_t
        logical :: present = .false.         !< not an input: the group was given
        character(len=LEN_NAME) :: units = ''   !< 'SI' (required): the input's unit system
        real(dp) :: T0 = 293.0_dp            !< reference temperature [K]
        real(dp) :: rho0 = 8954.0_dp         !< mass density [kg/m^3]
        real(dp) :: cE = 383.1_dp            !< specific heat at constant strain [J/(kg K)]
        real(dp) :: kappa = 386.0_dp         !< thermal conductivity [W/(m K)]
        real(dp) :: lambda = 7.76e10_dp      !< Lame constant [kg/(m s^2)]
        real(dp) :: mu = 3.86e10_dp          !< Lame constant [kg/(m s^2)]
        real(dp) :: alpha_t = 1.78e-5_dp     !< linear thermal expansion [1/K]
        real(dp) :: alpha_c = 1.98e-4_dp     !< linear diffusion expansion [m^3/kg]
        real(dp) :: D = 0.85e-8_dp           !< diffusion coefficient [kg s/m^3]
        real(dp) :: nu = 1.2e4_dp            !< thermodiffusion measure [m^2/(s^2 K)]
        real(dp) :: varrho = 0.9e6_dp        !< diffusive effect measure [m^5/(kg s^2)]
        real(dp) :: ell = 1.0_dp             !< rod length [m]
        real(dp) :: tau0 = 0.0_dp            !< thermal relaxation time [s]
        real(dp) :: tau = 0.0_dp             !< diffusion relaxation time [s]
        real(dp) :: lambda_v = 0.0_dp        !< damping coefficient lambda' [kg/(m s)  (lambda')]
        real(dp) :: mu_v = 0.0_dp            !< damping coefficient mu' [kg/(m s)  (mu')]
    end type material_t

    !> The whole run configuration.
    type :: config_t
        type(model_t) :: model
        type(contact_t) :: contact
        type(mesh_t) :: mesh
        type(time_t) :: time
        type(initial_t) :: initial
        type(solver_t) :: solver
        type(output_t) :: output
        type(material_t) :: material
        character(len=LEN_PATH) :: source = ''   !< where the namelist came from ('-' = stdin)
        !> the --set overrides applied after it, as given ('' if none; truncated with '...')
        character(len=LEN_PATH) :: overrides = ''
    end type config_t

contains

    !> Number of time steps N: t_end/dt rounded to the nearest integer when t_end is a
    !> multiple of dt to round-off, else rounded up; the run ends at t_N = N dt.
    pure integer function number_of_steps(dt, t_end)
        real(dp), intent(in) :: dt, t_end
        real(dp) :: ratio

        ratio = t_end / dt
        if (abs(ratio - anint(ratio)) <= 1.0e-9_dp * ratio) then
            number_of_steps = nint(ratio)
        else
            number_of_steps = ceiling(ratio)
        end if
    end function number_of_steps

    !> The model with the velocity's mass of &contact mass (docs/scheme.md, "Mass
    !> redistribution"): 'redistributed' blends 9/16 consistent and 7/16 lumped mass and moves
    !> the contact node's element's mass to its other node; 'consistent' leaves the P1 mass.
    pure function with_contact_mass(model, mass) result(m)
        type(model_t), intent(in) :: model
        character(len=*), intent(in) :: mass
        type(model_t) :: m

        m = model
        m%mass_lumped = 0.0_dp
        m%mass_end_moved = .false.
        if (trim(mass) == 'redistributed') then
            m%mass_lumped = 7.0_dp / 16.0_dp
            m%mass_end_moved = .true.
        end if
    end function with_contact_mass

end module config_m
