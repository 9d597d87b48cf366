!> The discrete energy of Corollary 6.2, the energy law each time scheme guarantees, and
!> the monitor that checks the law every step.
module energy_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fields_m, only: F_Q, F_THETA, F_V, F_P, F_ETA, N_ENERGY_PARTS
    use contact_law_m, only: contact_law_t
    use time_scheme_m, only: time_scheme_t, energy_law_t, LAW_G_ENERGY
    use state_m, only: state_t
    use mesh_m, only: mesh_t
    use reals_m, only: equal
    use fe_m, only: inertia_difference_energy
    use errors_m, only: check_allocation
    use checkpoint_m, only: checkpoint_t
    implicit none
    private
    public :: discrete_energy, linear_energy, linear_energy_by_nodes, bdf2_energy, energy_parts, energy_and_parts, &
              energy_monitor_t
    public :: PART_KINETIC, PART_STRAIN, PART_THERMAL, PART_CHEMICAL, PART_COUPLING, PART_HEAT_FLUX, &
              PART_MASS_FLUX, PART_CONTACT

    !> The sums over the elements of element_sums (E_lin of any model follows from them).
    integer, parameter :: SUM_SCALE = 1, SUM_STRAIN = 2, SUM_KINETIC = 3, SUM_THERMAL = 4, SUM_CHEMICAL = 5, &
                          SUM_COUPLING = 6, SUM_HEAT_FLUX = 7, SUM_MASS_FLUX = 8, N_SUMS = 8

    !> The terms of E^n in energy_parts (the order of fields_m's energy_* series).
    integer, parameter :: PART_KINETIC = 1, PART_STRAIN = 2, PART_THERMAL = 3, PART_CHEMICAL = 4, &
                          PART_COUPLING = 5, PART_HEAT_FLUX = 6, PART_MASS_FLUX = 7, PART_CONTACT = 8

    !> The discrete energy of every level and the largest relative rise of the energy the
    !> scheme's law is stated for (time_scheme_m's energy_law: E^n, or BDF2's G-energy).
    type :: energy_monitor_t
        private
        type(model_t) :: model
        type(model_t) :: law_model     !< the model of the law's energy (time_scheme_m's stiff_limit)
        class(contact_law_t), allocatable :: law
        type(energy_law_t) :: scheme_law   !< the law the time scheme guarantees
        logical :: own_law_model = .false.   !< law_model differs from model
        real(dp) :: energy = 0.0_dp, law_energy = 0.0_dp, max_rise = 0.0_dp
        !> a law stated for constant steps only (BDF2): the largest relative rise at steps
        !> whose size differs from the step before (w /= 1), where the law is not stated (not
        !> in max_rise)
        real(dp) :: max_rise_step_change = 0.0_dp
        logical :: have_law = .false.
        real(dp), allocatable :: u_work(:), w_work(:, :)
        !> the terms of E^n of the level observed last (step parts_step, time parts_t,
        !> parts_nodes nodes), computed with its energy in the same pass; have_parts false
        !> until a level is observed (and after a restart)
        real(dp) :: last_parts(N_ENERGY_PARTS) = 0.0_dp
        logical :: have_parts = .false.
        integer :: parts_step = -1, parts_nodes = -1
        real(dp) :: parts_t = 0.0_dp
    contains
        procedure :: init => monitor_init
        procedure :: observe => monitor_observe
        procedure :: resize => monitor_resize
        procedure :: remeshed => monitor_remeshed
        procedure :: save_checkpoint => monitor_save_checkpoint
        procedure :: restore_checkpoint => monitor_restore_checkpoint
        procedure :: current_energy => monitor_current_energy
        procedure :: rises => monitor_rises
        procedure :: parts => monitor_parts
    end type energy_monitor_t

contains

    !> E^n = E_lin + 1/(2 eps) [u(1) - g]_+^2 (penalty law; no contact term for Signorini)
    !> of the level (u, w) on mesh.
    pure function discrete_energy(model, law, u, w, mesh) result(energy)
        type(model_t), intent(in) :: model
        class(contact_law_t), intent(in) :: law
        real(dp), intent(in), contiguous :: u(0:)
        real(dp), intent(in), contiguous :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp) :: energy

        real(dp) :: parts(N_ENERGY_PARTS)

        call energy_and_parts(model, law, u, w, mesh, energy, parts)
    end function discrete_energy

    !> E_lin = 1/2 int (rho v^2 + alpha u_x^2 + c theta^2 + r P^2 + 2 d P theta + tau0 q^2
    !>       + tau hbar eta^2) dx, E^n without the contact term; integrals exact for P1 functions
    !> (linear_energy_parts, which also gives the terms one by one).
    pure function linear_energy(model, u, w, mesh) result(energy)
        type(model_t), intent(in) :: model
        real(dp), intent(in), contiguous :: u(0:)
        real(dp), intent(in), contiguous :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp) :: energy
        real(dp) :: parts(N_ENERGY_PARTS)

        call linear_energy_parts(model, u, w, mesh, energy, parts)
    end function linear_energy

    !> E_lin = linear_energy on a uniform mesh, summed by nodes with the coefficients inside
    !> the sum (node_terms): the same integrals in another order, equal to linear_energy to
    !> round-off, not bit for bit (the mass matrix's quadratic form by nodes has no
    !> cancellation beyond a factor 3: h/6 tridiag(1, 4, 1) is positive definite with condition
    !> number 3), in about half the instructions. For the step-size controller's error norm
    !> (step_control_m), where only its size matters; the energy law and the energy series use
    !> linear_energy. On a graded mesh: linear_energy. work(1:s): scratch.
    pure subroutine linear_energy_by_nodes(model, u, w, mesh, work, energy)
        type(model_t), intent(in) :: model
        real(dp), intent(in), contiguous :: u(0:)
        real(dp), intent(in), contiguous :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(inout), contiguous :: work(:)
        real(dp), intent(out) :: energy
        integer :: s

        s = ubound(u, 1)
        if (.not. mesh%is_uniform() .or. size(work) < s) then
            energy = linear_energy(model, u, w, mesh)
            return
        end if
        call node_terms(model, u, w, work(1:s))
        ! 0.5 (scale/6 (mass terms) + alpha strain/scale), scale = h = 1/s (linear_from_sums)
        energy = 0.5_dp * (sum(work(1:s)) + 2.0_dp * (end_terms(model, w, 0) - end_terms(model, w, s))) &
                 / (6.0_dp * real(s, dp)) + inertia_difference(model, w, mesh)
    end subroutine linear_energy_by_nodes

    !> The terms of node i = 1..s of linear_energy_by_nodes, into terms(i): on a uniform mesh
    !> the mass product of element e (nodes e-1, e; element_mass_product) is 2 a0 b0 + 2 a1 b1
    !> + a0 b1 + a1 b0, so its sum over the elements is sum_{i=1..s} (a_i (2 b_i + b_{i-1})
    !> + b_i (2 a_i + a_{i-1})) + 2 a_0 b_0 - 2 a_s b_s (end_terms), and for a = b
    !> 2 sum_i a_i (2 a_i + a_{i-1}) + 2 a_0^2 - 2 a_s^2. terms(i): twice the coefficients
    !> times node i's part, plus 6 alpha s^2 (u_i - u_{i-1})^2 (the strain, scaled to the mass
    !> terms' h/6). An elementwise loop (the compiler pairs the nodes), summed afterwards.
    pure subroutine node_terms(model, u, w, terms)
        type(model_t), intent(in) :: model
        real(dp), intent(in), contiguous :: u(0:)
        real(dp), intent(in), contiguous :: w(0:, :)
        real(dp), intent(out) :: terms(:)
        real(dp) :: k_strain, c_v, c_t, c_p, c_d, c_q, c_e
        integer :: i, s

        s = ubound(u, 1)
        k_strain = 6.0_dp * model%alpha * real(s, dp)**2
        c_v = 2.0_dp * model%rho; c_t = 2.0_dp * model%c; c_p = 2.0_dp * model%r; c_d = 2.0_dp * model%d
        c_q = 2.0_dp * model%tau0; c_e = 2.0_dp * model%tau * model%hbar
        do i = 1, s
            terms(i) = c_v * w(i, F_V) * (2.0_dp * w(i, F_V) + w(i - 1, F_V)) &
                       + c_t * w(i, F_THETA) * (2.0_dp * w(i, F_THETA) + w(i - 1, F_THETA)) &
                       + c_p * w(i, F_P) * (2.0_dp * w(i, F_P) + w(i - 1, F_P)) &
                       + c_d * (w(i, F_P) * (2.0_dp * w(i, F_THETA) + w(i - 1, F_THETA)) &
                                + w(i, F_THETA) * (2.0_dp * w(i, F_P) + w(i - 1, F_P))) &
                       + c_q * w(i, F_Q) * (2.0_dp * w(i, F_Q) + w(i - 1, F_Q)) &
                       + c_e * w(i, F_ETA) * (2.0_dp * w(i, F_ETA) + w(i - 1, F_ETA)) &
                       + k_strain * (u(i) - u(i - 1))**2
        end do
    end subroutine node_terms

    !> The mass terms of node i alone (the end corrections of node_terms' sums):
    !> rho v^2 + c theta^2 + r P^2 + 2 d P theta + tau0 q^2 + tau hbar eta^2 at node i.
    pure real(dp) function end_terms(model, w, i)
        type(model_t), intent(in) :: model
        real(dp), intent(in), contiguous :: w(0:, :)
        integer, intent(in) :: i

        end_terms = model%rho * w(i, F_V)**2 + model%c * w(i, F_THETA)**2 + model%r * w(i, F_P)**2 &
                    + 2.0_dp * model%d * w(i, F_P) * w(i, F_THETA) + model%tau0 * w(i, F_Q)**2 &
                    + model%tau * model%hbar * w(i, F_ETA)**2
    end function end_terms

    !> The terms of E^n = discrete_energy of the level (u, w) on mesh, one by one (PART_*):
    !> 1/2 int rho v^2 (with the velocity mass's inertia_difference), 1/2 int alpha u_x^2,
    !> 1/2 int c theta^2, 1/2 int r P^2, int d theta P, 1/2 int tau0 q^2, 1/2 int tau hbar
    !> eta^2 and the contact term. They add up to discrete_energy to round-off (the sums are
    !> grouped differently).
    pure function energy_parts(model, law, u, w, mesh) result(parts)
        type(model_t), intent(in) :: model
        class(contact_law_t), intent(in) :: law
        real(dp), intent(in), contiguous :: u(0:)
        real(dp), intent(in), contiguous :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp) :: parts(N_ENERGY_PARTS)
        real(dp) :: energy

        call energy_and_parts(model, law, u, w, mesh, energy, parts)
    end function energy_parts

    !> E^n (discrete_energy) and its terms (energy_parts) of the level (u, w) on mesh, from
    !> one pass over the elements.
    pure subroutine energy_and_parts(model, law, u, w, mesh, energy, parts)
        type(model_t), intent(in) :: model
        class(contact_law_t), intent(in) :: law
        real(dp), intent(in), contiguous :: u(0:)
        real(dp), intent(in), contiguous :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(out) :: energy
        real(dp), intent(out) :: parts(N_ENERGY_PARTS)

        call linear_energy_parts(model, u, w, mesh, energy, parts)
        parts(PART_CONTACT) = law%energy(u(ubound(u, 1)))
        energy = energy + parts(PART_CONTACT)
    end subroutine energy_and_parts

    !> E_lin (energy) and its terms (parts, PART_CONTACT set to 0) in one pass over the
    !> elements, which runs every time step (element_sums, then linear_from_sums).
    pure subroutine linear_energy_parts(model, u, w, mesh, energy, parts)
        type(model_t), intent(in) :: model
        real(dp), intent(in), contiguous :: u(0:)
        real(dp), intent(in), contiguous :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(out) :: energy
        real(dp), intent(out) :: parts(N_ENERGY_PARTS)
        real(dp) :: sums(N_SUMS)

        call element_sums(u, w, mesh, sums)
        call linear_from_sums(model, sums, w, mesh, energy, parts)
    end subroutine linear_energy_parts

    !> The sums over the elements E_lin is made of, which do not depend on the model's
    !> coefficients (so E_lin of two models takes one pass): on element e the mass product of
    !> P1 functions a, b is h/6 (2 a0 b0 + a0 b1 + a1 b0 + 2 a1 b1), written here as
    !> h/6 ((a0 + a1)(b0 + b1) + a0 b0 + a1 b1); each product is summed over the elements
    !> (weighted by h_e on a graded mesh, scaled by h = 1/s once at the end on a uniform one).
    !> sums: SUM_* (SUM_SCALE: that scale).
    pure subroutine element_sums(u, w, mesh, sums)
        real(dp), intent(in), contiguous :: u(0:)
        real(dp), intent(in), contiguous :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(out) :: sums(N_SUMS)
        real(dp) :: strain_terms, h_e
        real(dp) :: p_v, p_theta, p_p, p_coupling, p_q, p_eta
        ! the parts' sums (scalars, so that the loop keeps them in registers)
        real(dp) :: kinetic, thermal, chemical, coupling, heat_flux, mass_flux
        integer :: e, s

        s = ubound(u, 1)
        strain_terms = 0.0_dp
        kinetic = 0.0_dp; thermal = 0.0_dp; chemical = 0.0_dp; coupling = 0.0_dp
        heat_flux = 0.0_dp; mass_flux = 0.0_dp
        if (mesh%is_uniform()) then
            do e = 1, s
                call element_products(w, e, p_v, p_theta, p_p, p_coupling, p_q, p_eta)
                strain_terms = strain_terms + (u(e) - u(e - 1))**2
                kinetic = kinetic + p_v; thermal = thermal + p_theta; chemical = chemical + p_p
                coupling = coupling + p_coupling; heat_flux = heat_flux + p_q; mass_flux = mass_flux + p_eta
            end do
            sums(SUM_SCALE) = 1.0_dp / real(s, dp)
        else
            do e = 1, s
                h_e = mesh%h(e)
                call element_products(w, e, p_v, p_theta, p_p, p_coupling, p_q, p_eta)
                strain_terms = strain_terms + (u(e) - u(e - 1))**2 / h_e
                kinetic = kinetic + h_e * p_v; thermal = thermal + h_e * p_theta; chemical = chemical + h_e * p_p
                coupling = coupling + h_e * p_coupling; heat_flux = heat_flux + h_e * p_q
                mass_flux = mass_flux + h_e * p_eta
            end do
            sums(SUM_SCALE) = 1.0_dp
        end if
        sums(SUM_STRAIN:SUM_MASS_FLUX) = [strain_terms, kinetic, thermal, chemical, coupling, heat_flux, mass_flux]
    end subroutine element_sums

    !> E_lin (energy) and its terms (parts, PART_CONTACT set to 0) of model from element_sums
    !> of the level (w: its fields, for the velocity mass's inertia_difference).
    pure subroutine linear_from_sums(model, sums, w, mesh, energy, parts)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: sums(N_SUMS)
        real(dp), intent(in) :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(out) :: energy
        real(dp), intent(out) :: parts(N_ENERGY_PARTS)
        real(dp) :: mass_terms, kinetic_difference

        associate (scale => sums(SUM_SCALE), strain_terms => sums(SUM_STRAIN), kinetic => sums(SUM_KINETIC), &
                   thermal => sums(SUM_THERMAL), chemical => sums(SUM_CHEMICAL), coupling => sums(SUM_COUPLING), &
                   heat_flux => sums(SUM_HEAT_FLUX), mass_flux => sums(SUM_MASS_FLUX))
            ! E_lin from the sums over the elements: one accumulator per term keeps the loop short
            ! (the compiler pairs them in vector registers); the sum of the parts below is E_lin
            ! to round-off
            mass_terms = model%rho * kinetic + model%c * thermal + model%r * chemical + 2.0_dp * model%d * coupling &
                         + model%tau0 * heat_flux + model%tau * model%hbar * mass_flux
            kinetic_difference = inertia_difference(model, w, mesh)
            energy = 0.5_dp * (mass_terms * scale / 6.0_dp + model%alpha * strain_terms / scale) + kinetic_difference
            ! 1/2 int (coefficient f g) = coefficient (h/6) (mass product) / 2
            parts(PART_KINETIC) = model%rho * kinetic * scale / 12.0_dp + kinetic_difference
            parts(PART_STRAIN) = 0.5_dp * model%alpha * strain_terms / scale
            parts(PART_THERMAL) = model%c * thermal * scale / 12.0_dp
            parts(PART_CHEMICAL) = model%r * chemical * scale / 12.0_dp
            parts(PART_COUPLING) = model%d * coupling * scale / 6.0_dp
            parts(PART_HEAT_FLUX) = model%tau0 * heat_flux * scale / 12.0_dp
            parts(PART_MASS_FLUX) = model%tau * model%hbar * mass_flux * scale / 12.0_dp
            parts(PART_CONTACT) = 0.0_dp
        end associate
    end subroutine linear_from_sums

    !> What the velocity's mass of &contact mass adds to the consistent kinetic energy above:
    !> 1/2 rho v^T (M_v - M) v with fe_m's inertia_element (the matrix scheme_m assembles), so
    !> the kinetic energy is the scheme's own; 0 for the consistent mass.
    pure real(dp) function inertia_difference(model, w, mesh) result(energy)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: w(0:, :)
        type(mesh_t), intent(in) :: mesh

        energy = 0.0_dp
        if (model%mass_end_moved .or. model%mass_lumped > 0.0_dp) energy = 0.5_dp * model%rho * &
            inertia_difference_energy(mesh%h, model%mass_lumped, model%mass_end_moved, w(:, F_V))
    end function inertia_difference

    !> The energy of the BDF2 scheme's law: G-stability of BDF2 gives, for the linear part
    !> of (2.11) tested with the new level,
    !>   (3a - 4b + c)/2 . a = [|a|^2 + |2a - b|^2]/4 - [|b|^2 + |2b - c|^2]/4 + |a - 2b + c|^2/4,
    !> so E_G^n = (E_lin(X^n) + E_lin(2 X^n - X^{n-1})) / 2 never rises while the contact
    !> node is inactive. The contact term is added at the current level. With an active
    !> penalty BDF2 has no such law (the nonlinear term is not G-stable).
    !> u_work, w_work: arrays shaped as u, w (no allocation here; called every step).
    !> lin_now: E_lin(X^n) when the caller has it already (it is not computed again).
    subroutine bdf2_energy(model, law, u, w, u_prev, w_prev, mesh, u_work, w_work, energy, lin_now)
        type(model_t), intent(in) :: model
        class(contact_law_t), intent(in) :: law
        real(dp), intent(in), contiguous :: u(0:), w(0:, :), u_prev(0:), w_prev(0:, :)
        type(mesh_t), intent(in) :: mesh           !< the mesh of both levels
        real(dp), intent(inout), contiguous :: u_work(0:), w_work(0:, :)
        real(dp), intent(out) :: energy
        real(dp), intent(in), optional :: lin_now
        real(dp) :: lin

        if (present(lin_now)) then
            lin = lin_now
        else
            lin = linear_energy(model, u, w, mesh)
        end if
        u_work = 2.0_dp * u - u_prev
        w_work = 2.0_dp * w - w_prev
        energy = 0.5_dp * (lin + linear_energy(model, u_work, w_work, mesh)) + law%energy(u(ubound(u, 1)))
    end subroutine bdf2_energy

    !> The energy of the first level and the law of `scheme` it must obey from then on;
    !> step_model: the model of the steps (time_scheme_m's stiff_limit), the model of the law
    !> if the scheme's law says so.
    subroutine monitor_init(self, model, step_model, law, scheme, state)
        class(energy_monitor_t), intent(inout) :: self
        type(model_t), intent(in) :: model, step_model
        class(contact_law_t), intent(in) :: law
        type(time_scheme_t), intent(in) :: scheme
        type(state_t), intent(in) :: state
        integer :: stat
        real(dp) :: energy_lin
        character(len=256) :: message

        self%scheme_law = scheme%energy_law()
        self%model = model
        self%law_model = model
        self%own_law_model = self%scheme_law%step_model
        if (self%own_law_model) self%law_model = step_model
        self%law = law
        call measure_parts(self, state, energy_lin, self%law_energy)
        ! the G-energy needs the level before: it is defined from the second level on
        self%have_law = self%scheme_law%energy /= LAW_G_ENERGY
        self%max_rise = 0.0_dp
        if (self%scheme_law%energy == LAW_G_ENERGY) then
            allocate (self%u_work, mold=state%u, stat=stat, errmsg=message)
            call check_allocation(stat, message, 'the energy monitor''s work arrays')
            allocate (self%w_work, mold=state%w, stat=stat, errmsg=message)
            call check_allocation(stat, message, 'the energy monitor''s work arrays')
        end if
    end subroutine monitor_init

    !> E^n of the new level, and the rise of the law energy: E^n itself (Corollary 6.2, with
    !> the law's model), or the G-energy of bdf2_energy (defined once a previous level
    !> exists, compared from the first BDF2 step on). A law stated for constant steps (BDF2's):
    !> a rise at a step of another size than the one before (step_changed) is kept apart in
    !> max_rise_step_change.
    subroutine monitor_observe(self, state, step_changed)
        class(energy_monitor_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        logical, intent(in), optional :: step_changed
        real(dp) :: law_old, rise
        logical :: had_law, changed

        law_old = self%law_energy
        had_law = self%have_law
        call measure(self, state)
        if (.not. (had_law .and. self%have_law)) return
        rise = (self%law_energy - law_old) / max(law_old, tiny(1.0_dp))
        changed = .false.
        if (present(step_changed)) changed = step_changed .and. self%scheme_law%constant_steps
        if (changed) then
            self%max_rise_step_change = max(self%max_rise_step_change, rise)
        else
            self%max_rise = max(self%max_rise, rise)
        end if
    end subroutine monitor_observe

    !> E^n and the law energy of the level `state` (monitor_observe).
    subroutine measure(self, state)
        class(energy_monitor_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        real(dp) :: energy_lin

        call measure_parts(self, state, energy_lin, self%law_energy)
        if (self%scheme_law%energy == LAW_G_ENERGY) then
            self%have_law = allocated(state%u_prev)
            if (self%have_law) then
                if (size(self%u_work) /= size(state%u)) call self%resize(state)
                call bdf2_energy(self%model, self%law, state%u, state%w, state%u_prev, state%w_prev, state%mesh, &
                                 self%u_work, self%w_work, self%law_energy, lin_now=energy_lin)
            end if
        end if
    end subroutine measure

    !> E^n of the level `state` and its terms (kept for monitor_parts) in one pass; returns
    !> E_lin, E^n without the contact term, and law_energy, E^n with the law's model (the
    !> same sums over the elements: discrete_energy of law_model to the bit).
    subroutine measure_parts(self, state, energy_lin, law_energy)
        class(energy_monitor_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(out) :: energy_lin, law_energy
        real(dp) :: sums(N_SUMS), law_parts(N_ENERGY_PARTS)

        call element_sums(state%u, state%w, state%mesh, sums)
        call linear_from_sums(self%model, sums, state%w, state%mesh, energy_lin, self%last_parts)
        self%last_parts(PART_CONTACT) = self%law%energy(state%u(state%s))
        self%energy = energy_lin + self%last_parts(PART_CONTACT)
        law_energy = self%energy
        if (self%own_law_model) then
            call linear_from_sums(self%law_model, sums, state%w, state%mesh, law_energy, law_parts)
            law_energy = law_energy + self%law%energy(state%u(state%s))
        end if
        self%have_parts = .true.
        self%parts_step = state%step
        self%parts_t = state%t
        self%parts_nodes = size(state%u)
    end subroutine measure_parts

    !> The level has moved to a new mesh (transfer_m): its energies on the new mesh, and
    !> the relative rise of the law energy across the move (0 where the law energy is not
    !> defined before and after it; mesh_m's record_remesh keeps the largest).
    subroutine monitor_remeshed(self, state, rise)
        class(energy_monitor_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        real(dp), intent(out) :: rise
        real(dp) :: law_old
        logical :: had_law

        law_old = self%law_energy
        had_law = self%have_law
        call measure(self, state)
        rise = 0.0_dp
        if (had_law .and. self%have_law) rise = (self%law_energy - law_old) / max(law_old, tiny(1.0_dp))
    end subroutine monitor_remeshed

    !> The work arrays shaped as the state's level (after a remesh).
    subroutine monitor_resize(self, state)
        class(energy_monitor_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        integer :: stat
        character(len=256) :: message

        if (allocated(self%u_work)) deallocate (self%u_work, self%w_work)
        allocate (self%u_work, mold=state%u, stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the energy monitor''s work arrays')
        allocate (self%w_work, mold=state%w, stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the energy monitor''s work arrays')
    end subroutine monitor_resize

    !> E^n of the level observed last.
    pure real(dp) function monitor_current_energy(self) result(energy)
        class(energy_monitor_t), intent(in) :: self

        energy = self%energy
    end function monitor_current_energy

    !> The largest relative rises of the law energy so far (the root attributes
    !> energy_max_relative_rise*): at steps of the step size before, and at steps of another
    !> size (a law stated for constant steps only: BDF2). The rise across remeshes is kept
    !> by the mesh (mesh_m).
    pure subroutine monitor_rises(self, max_rise, max_rise_step_change)
        class(energy_monitor_t), intent(in) :: self
        real(dp), intent(out) :: max_rise, max_rise_step_change

        max_rise = self%max_rise
        max_rise_step_change = self%max_rise_step_change
    end subroutine monitor_rises

    !> The terms of E^n (energy_parts, PART_*) of the level in state, with the monitor's
    !> model and contact law: they add up to current_energy() when state is the level
    !> observed last.
    pure function monitor_parts(self, state) result(parts)
        class(energy_monitor_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp) :: parts(N_ENERGY_PARTS)

        if (self%have_parts .and. state%step == self%parts_step .and. equal(state%t, self%parts_t) &
            .and. size(state%u) == self%parts_nodes) then
            parts = self%last_parts   ! computed with E^n when the level was observed
        else
            parts = energy_parts(self%model, self%law, state%u, state%w, state%mesh)
        end if
    end function monitor_parts

    !> The energies and the largest rises so far into a checkpoint.
    subroutine monitor_save_checkpoint(self, ckpt)
        class(energy_monitor_t), intent(in) :: self
        type(checkpoint_t), intent(inout) :: ckpt

        call ckpt%put('energy_monitor/energy', self%energy)
        call ckpt%put('energy_monitor/law_energy', self%law_energy)
        call ckpt%put('energy_monitor/have_law', self%have_law)
        call ckpt%put('energy_monitor/max_rise', self%max_rise)
        call ckpt%put('energy_monitor/max_rise_step_change', self%max_rise_step_change)
    end subroutine monitor_save_checkpoint

    !> The inverse of save_checkpoint (on a monitor initialised for this run).
    subroutine monitor_restore_checkpoint(self, ckpt)
        class(energy_monitor_t), intent(inout) :: self
        type(checkpoint_t), intent(in) :: ckpt

        call ckpt%get('energy_monitor/energy', self%energy)
        call ckpt%get('energy_monitor/law_energy', self%law_energy)
        call ckpt%get('energy_monitor/have_law', self%have_law)
        call ckpt%get('energy_monitor/max_rise', self%max_rise)
        call ckpt%get('energy_monitor/max_rise_step_change', self%max_rise_step_change)
        self%have_parts = .false.
    end subroutine monitor_restore_checkpoint

    !> The mass products (element_mass_product) of element e of the level w: v v, theta
    !> theta, P P, P theta, q q, eta eta.
    pure subroutine element_products(w, e, p_v, p_theta, p_p, p_coupling, p_q, p_eta)
        real(dp), intent(in), contiguous :: w(0:, :)
        integer, intent(in) :: e
        real(dp), intent(out) :: p_v, p_theta, p_p, p_coupling, p_q, p_eta

        p_v = element_mass_product(w(e - 1, F_V), w(e, F_V), w(e - 1, F_V), w(e, F_V))
        p_theta = element_mass_product(w(e - 1, F_THETA), w(e, F_THETA), w(e - 1, F_THETA), w(e, F_THETA))
        p_p = element_mass_product(w(e - 1, F_P), w(e, F_P), w(e - 1, F_P), w(e, F_P))
        p_coupling = element_mass_product(w(e - 1, F_P), w(e, F_P), w(e - 1, F_THETA), w(e, F_THETA))
        p_q = element_mass_product(w(e - 1, F_Q), w(e, F_Q), w(e - 1, F_Q), w(e, F_Q))
        p_eta = element_mass_product(w(e - 1, F_ETA), w(e, F_ETA), w(e - 1, F_ETA), w(e, F_ETA))
    end subroutine element_products

    !> 6/h times the mass product of two P1 functions on one element (nodal values a0, a1
    !> and b0, b1).
    pure real(dp) function element_mass_product(a0, a1, b0, b1)
        real(dp), intent(in) :: a0, a1, b0, b1

        element_mass_product = (a0 + a1) * (b0 + b1) + a0 * b0 + a1 * b1
    end function element_mass_product

end module energy_m
