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
    use errors_m, only: check_allocation
    use checkpoint_m, only: checkpoint_t, COUNTER_ENERGY, COUNTER_LAW_ENERGY, COUNTER_HAVE_LAW, COUNTER_MAX_RISE
    implicit none
    private
    public :: discrete_energy, linear_energy, bdf2_energy, energy_parts, energy_monitor_t
    public :: PART_KINETIC, PART_STRAIN, PART_THERMAL, PART_CHEMICAL, PART_COUPLING, PART_HEAT_FLUX, &
              PART_MASS_FLUX, PART_CONTACT

    !> The terms of E^n in energy_parts (the order of fields_m's energy_* series).
    integer, parameter :: PART_KINETIC = 1, PART_STRAIN = 2, PART_THERMAL = 3, PART_CHEMICAL = 4, &
                          PART_COUPLING = 5, PART_HEAT_FLUX = 6, PART_MASS_FLUX = 7, PART_CONTACT = 8

    !> The discrete energy of every level and the largest relative rise of the energy the
    !> scheme's law is stated for (time_scheme_m's energy_law: E^n, or BDF2's G-energy).
    type :: energy_monitor_t
        private
        type(model_t) :: model
        type(model_t) :: law_model     !< the model of the law's energy (time_scheme_m's stiff_limit)
        type(contact_law_t) :: law
        type(energy_law_t) :: scheme_law   !< the law the time scheme guarantees
        logical :: own_law_model = .false.   !< law_model differs from model
        real(dp) :: energy = 0.0_dp, law_energy = 0.0_dp, max_rise = 0.0_dp
        !> a law stated for constant steps only (BDF2): the largest relative rise at steps
        !> whose size differs from the step before (w /= 1), where the law is not stated (not
        !> in max_rise)
        real(dp) :: max_rise_step_change = 0.0_dp
        logical :: have_law = .false.
        real(dp), allocatable :: u_work(:), w_work(:, :)
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
        type(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: u(0:)
        real(dp), intent(in) :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp) :: energy

        energy = linear_energy(model, u, w, mesh) + law%energy(u(ubound(u, 1)))
    end function discrete_energy

    !> E_lin = 1/2 int (rho v^2 + alpha u_x^2 + c theta^2 + r P^2 + 2 d P theta + tau0 q^2
    !>       + tau hbar eta^2) dx, E^n without the contact term; integrals exact for P1 functions.
    !> On a uniform mesh the sums over the elements are scaled by h = 1/s once, at the end.
    pure function linear_energy(model, u, w, mesh) result(energy)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: u(0:)
        real(dp), intent(in) :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp) :: energy
        real(dp) :: mass_terms, strain_terms, h_e
        integer :: e, s

        ! One pass over the elements (this runs every time step): on element e the mass
        ! product of P1 functions a, b is h/6 (2 a0 b0 + a0 b1 + a1 b0 + 2 a1 b1), written
        ! here as h/6 ((a0 + a1)(b0 + b1) + a0 b0 + a1 b1) for every pair of fields.
        s = ubound(u, 1)
        mass_terms = 0.0_dp
        strain_terms = 0.0_dp
        if (.not. mesh%is_uniform()) then
            do e = 1, s
                h_e = mesh%h(e)
                mass_terms = mass_terms + h_e * element_energy_density(model, w(e - 1, :), w(e, :))
                strain_terms = strain_terms + (u(e) - u(e - 1))**2 / h_e
            end do
            energy = 0.5_dp * (mass_terms / 6.0_dp + model%alpha * strain_terms)
            return
        end if
        do e = 1, s
            mass_terms = mass_terms &
                + model%rho * element_mass_product(w(e - 1, F_V), w(e, F_V), w(e - 1, F_V), w(e, F_V)) &
                + model%c * element_mass_product(w(e - 1, F_THETA), w(e, F_THETA), w(e - 1, F_THETA), w(e, F_THETA)) &
                + model%r * element_mass_product(w(e - 1, F_P), w(e, F_P), w(e - 1, F_P), w(e, F_P)) &
                + 2.0_dp * model%d * element_mass_product(w(e - 1, F_P), w(e, F_P), w(e - 1, F_THETA), w(e, F_THETA)) &
                + model%tau0 * element_mass_product(w(e - 1, F_Q), w(e, F_Q), w(e - 1, F_Q), w(e, F_Q)) &
                + model%tau * model%hbar * element_mass_product(w(e - 1, F_ETA), w(e, F_ETA), w(e - 1, F_ETA), w(e, F_ETA))
            strain_terms = strain_terms + (u(e) - u(e - 1))**2
        end do
        energy = 0.5_dp * (mass_terms / (6.0_dp * real(s, dp)) + model%alpha * strain_terms * real(s, dp))
    end function linear_energy

    !> The terms of E^n = discrete_energy of the level (u, w) on mesh, one by one (PART_*):
    !> 1/2 int rho v^2, 1/2 int alpha u_x^2, 1/2 int c theta^2, 1/2 int r P^2, int d theta P,
    !> 1/2 int tau0 q^2, 1/2 int tau hbar eta^2 (exact for P1 functions, as linear_energy)
    !> and the contact term. They add up to discrete_energy to round-off (the sums are
    !> grouped differently). Called when a series entry is written.
    pure function energy_parts(model, law, u, w, mesh) result(parts)
        type(model_t), intent(in) :: model
        type(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: u(0:)
        real(dp), intent(in) :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp) :: parts(N_ENERGY_PARTS)
        real(dp) :: kinetic, thermal, chemical, coupling, heat_flux, mass_flux, strain, h_e
        integer :: e, s
        logical :: uniform

        ! the mass products of the parts (6/h times, as linear_energy: summed with weights
        ! h_e on a graded mesh, 1 on a uniform one, scaled by h = 1/s at the end); scalar
        ! sums, so that the loop keeps them in registers (it runs at every series entry)
        s = ubound(u, 1)
        uniform = mesh%is_uniform()
        kinetic = 0.0_dp; thermal = 0.0_dp; chemical = 0.0_dp; coupling = 0.0_dp
        heat_flux = 0.0_dp; mass_flux = 0.0_dp; strain = 0.0_dp
        h_e = 1.0_dp
        do e = 1, s
            if (.not. uniform) h_e = mesh%h(e)
            kinetic = kinetic + h_e * self_product(w(e - 1, F_V), w(e, F_V))
            thermal = thermal + h_e * self_product(w(e - 1, F_THETA), w(e, F_THETA))
            chemical = chemical + h_e * self_product(w(e - 1, F_P), w(e, F_P))
            coupling = coupling + h_e * element_mass_product(w(e - 1, F_P), w(e, F_P), w(e - 1, F_THETA), w(e, F_THETA))
            heat_flux = heat_flux + h_e * self_product(w(e - 1, F_Q), w(e, F_Q))
            mass_flux = mass_flux + h_e * self_product(w(e - 1, F_ETA), w(e, F_ETA))
            strain = strain + (u(e) - u(e - 1))**2 / h_e
        end do
        if (uniform) then
            h_e = 1.0_dp / real(s, dp)
            kinetic = kinetic * h_e; thermal = thermal * h_e; chemical = chemical * h_e
            coupling = coupling * h_e; heat_flux = heat_flux * h_e; mass_flux = mass_flux * h_e
            strain = strain * real(s, dp)
        end if
        ! 1/2 int (coefficient f g) = coefficient (h/6) (mass product) / 2
        parts(PART_KINETIC) = model%rho * kinetic / 12.0_dp
        parts(PART_STRAIN) = 0.5_dp * model%alpha * strain
        parts(PART_THERMAL) = model%c * thermal / 12.0_dp
        parts(PART_CHEMICAL) = model%r * chemical / 12.0_dp
        parts(PART_COUPLING) = model%d * coupling / 6.0_dp
        parts(PART_HEAT_FLUX) = model%tau0 * heat_flux / 12.0_dp
        parts(PART_MASS_FLUX) = model%tau * model%hbar * mass_flux / 12.0_dp
        parts(PART_CONTACT) = law%energy(u(s))
    end function energy_parts

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
        type(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: u(0:), w(0:, :), u_prev(0:), w_prev(0:, :)
        type(mesh_t), intent(in) :: mesh           !< the mesh of both levels
        real(dp), intent(inout) :: u_work(0:), w_work(0:, :)
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
        type(contact_law_t), intent(in) :: law
        type(time_scheme_t), intent(in) :: scheme
        type(state_t), intent(in) :: state
        integer :: stat
        character(len=256) :: message

        self%scheme_law = scheme%energy_law()
        self%model = model
        self%law_model = model
        self%own_law_model = self%scheme_law%step_model
        if (self%own_law_model) self%law_model = step_model
        self%law = law
        self%energy = discrete_energy(model, law, state%u, state%w, state%mesh)
        self%law_energy = self%energy
        if (self%own_law_model) self%law_energy = discrete_energy(self%law_model, law, state%u, state%w, state%mesh)
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

        energy_lin = linear_energy(self%model, state%u, state%w, state%mesh)
        self%energy = energy_lin + self%law%energy(state%u(state%s))
        self%law_energy = self%energy
        if (self%own_law_model) self%law_energy = discrete_energy(self%law_model, self%law, state%u, state%w, state%mesh)
        if (self%scheme_law%energy == LAW_G_ENERGY) then
            self%have_law = allocated(state%u_prev)
            if (self%have_law) then
                if (size(self%u_work) /= size(state%u)) call self%resize(state)
                call bdf2_energy(self%model, self%law, state%u, state%w, state%u_prev, state%w_prev, state%mesh, &
                                 self%u_work, self%w_work, self%law_energy, lin_now=energy_lin)
            end if
        end if
    end subroutine measure

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

        parts = energy_parts(self%model, self%law, state%u, state%w, state%mesh)
    end function monitor_parts

    !> The energies and the largest rises so far into a checkpoint.
    subroutine monitor_save_checkpoint(self, ckpt)
        class(energy_monitor_t), intent(in) :: self
        type(checkpoint_t), intent(inout) :: ckpt

        ckpt%counters(COUNTER_ENERGY) = self%energy
        ckpt%counters(COUNTER_LAW_ENERGY) = self%law_energy
        ckpt%counters(COUNTER_HAVE_LAW) = merge(1.0_dp, 0.0_dp, self%have_law)
        ckpt%counters(COUNTER_MAX_RISE) = self%max_rise
        ckpt%max_rise_step_change = self%max_rise_step_change
    end subroutine monitor_save_checkpoint

    !> The inverse of save_checkpoint (on a monitor initialised for this run).
    subroutine monitor_restore_checkpoint(self, ckpt)
        class(energy_monitor_t), intent(inout) :: self
        type(checkpoint_t), intent(in) :: ckpt

        self%energy = ckpt%counters(COUNTER_ENERGY)
        self%law_energy = ckpt%counters(COUNTER_LAW_ENERGY)
        self%have_law = ckpt%counters(COUNTER_HAVE_LAW) > 0.0_dp
        self%max_rise = ckpt%counters(COUNTER_MAX_RISE)
        self%max_rise_step_change = ckpt%max_rise_step_change
    end subroutine monitor_restore_checkpoint

    !> 6/h times the integrand of 2 E_lin without the strain term on one element whose
    !> end nodes hold the fields w0, w1 (fields_m's F_*).
    pure real(dp) function element_energy_density(model, w0, w1) result(density)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: w0(:), w1(:)

        density = model%rho * element_mass_product(w0(F_V), w1(F_V), w0(F_V), w1(F_V)) &
            + model%c * element_mass_product(w0(F_THETA), w1(F_THETA), w0(F_THETA), w1(F_THETA)) &
            + model%r * element_mass_product(w0(F_P), w1(F_P), w0(F_P), w1(F_P)) &
            + 2.0_dp * model%d * element_mass_product(w0(F_P), w1(F_P), w0(F_THETA), w1(F_THETA)) &
            + model%tau0 * element_mass_product(w0(F_Q), w1(F_Q), w0(F_Q), w1(F_Q)) &
            + model%tau * model%hbar * element_mass_product(w0(F_ETA), w1(F_ETA), w0(F_ETA), w1(F_ETA))
    end function element_energy_density

    !> element_mass_product(a0, a1, a0, a1): 6/h times the mass product of a P1 function
    !> with itself on one element.
    pure real(dp) function self_product(a0, a1)
        real(dp), intent(in) :: a0, a1

        self_product = 2.0_dp * (a0 * a0 + a0 * a1 + a1 * a1)
    end function self_product

    !> 6/h times the mass product of two P1 functions on one element (nodal values a0, a1
    !> and b0, b1).
    pure real(dp) function element_mass_product(a0, a1, b0, b1)
        real(dp), intent(in) :: a0, a1, b0, b1

        element_mass_product = (a0 + a1) * (b0 + b1) + a0 * b0 + a1 * b1
    end function element_mass_product

end module energy_m
