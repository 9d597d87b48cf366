!> The discrete energy E^n of Corollary 6.2 and its terms (one routine, one pass over the
!> level), the energy of the BDF2 scheme's law, and the monitor that checks the law every step.
module energy_m
    use kinds_m, only: dp
    use config_m, only: model_t
    use fields_m, only: F_Q, F_THETA, F_V, F_P, F_ETA, N_ENERGY_PARTS
    use contact_law_m, only: contact_law_t
    use time_scheme_m, only: time_scheme_t, energy_law_t, LAW_G_ENERGY
    use state_m, only: state_t
    use mesh_m, only: mesh_t
    use reals_m, only: equal
    use fe_m, only: add_inertia_difference
    use errors_m, only: check_allocation
    use checkpoint_m, only: checkpoint_t
    implicit none
    private
    public :: discrete_energy, bdf2_energy, energy_monitor_t
    public :: PART_KINETIC, PART_STRAIN, PART_THERMAL, PART_CHEMICAL, PART_COUPLING, PART_HEAT_FLUX, &
              PART_MASS_FLUX, PART_CONTACT

    !> The terms of E^n (the order of fields_m's energy_* series).
    integer, parameter :: PART_KINETIC = 1, PART_STRAIN = 2, PART_THERMAL = 3, PART_CHEMICAL = 4, &
                          PART_COUPLING = 5, PART_HEAT_FLUX = 6, PART_MASS_FLUX = 7, PART_CONTACT = 8
    !> The terms 1/2 int coefficient a b dx of two fields: a = w(:, MASS_A(k)), b = w(:, MASS_B(k))
    !> in term MASS_PARTS(k).
    integer, parameter :: MASS_PARTS(6) = [PART_KINETIC, PART_THERMAL, PART_CHEMICAL, PART_COUPLING, &
                                           PART_HEAT_FLUX, PART_MASS_FLUX]
    integer, parameter :: MASS_A(6) = [F_V, F_THETA, F_P, F_P, F_Q, F_ETA]
    integer, parameter :: MASS_B(6) = [F_V, F_THETA, F_P, F_THETA, F_Q, F_ETA]
    !> level_sums' integrals to the terms' 1/2 int: 1/12 of 6 int a b, 1/2 of int u_x^2.
    real(dp), parameter :: HALF_OF_SUMS(PART_MASS_FLUX) = [1, 6, 1, 1, 1, 1, 1] / 12.0_dp

    !> The discrete energy of every level and the largest relative rise of the energy the
    !> scheme's law is stated for (time_scheme_m's energy_law: E^n, or BDF2's G-energy).
    type :: energy_monitor_t
        private
        type(model_t) :: model
        type(model_t) :: law_model     !< the model of the law's energy (time_scheme_m's stiff_limit)
        class(contact_law_t), allocatable :: law
        type(energy_law_t) :: scheme_law   !< the law the time scheme guarantees
        real(dp) :: energy = 0.0_dp, law_energy = 0.0_dp, max_rise = 0.0_dp
        !> a law stated for constant steps only (BDF2): the largest relative rise at steps
        !> whose size differs from the step before (w /= 1), where the law is not stated (not
        !> in max_rise)
        real(dp) :: max_rise_step_change = 0.0_dp
        !> remeshes, the largest relative rise across one (transfer_m's: round-off only)
        integer :: n_remeshes = 0
        real(dp) :: max_rise_remesh = 0.0_dp
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
        procedure :: checkpoint => monitor_checkpoint
        procedure :: current_energy => monitor_current_energy
        procedure :: rises => monitor_rises
        procedure :: parts => monitor_parts
    end type energy_monitor_t

contains

    !> E^n of Corollary 6.2 of the level (u, w) on mesh and its terms (PART_*), from one pass
    !> over the level (level_sums): E_lin = 1/2 int (rho v^2 + alpha u_x^2 + c theta^2 + r P^2
    !> + 2 d P theta + tau0 q^2 + tau hbar eta^2) dx, exact for P1 functions (the kinetic term
    !> with the velocity mass's inertia_difference), plus the contact term of law at u(1)
    !> (1/(2 eps) [u(1) - g]_+^2 for the penalty; none for Signorini). energy: the sum of the
    !> terms. Without law: E_lin. law_energy: E^n with law_model's coefficients, from the same
    !> pass (the midpoint rule's law: time_scheme_m's stiff_limit).
    pure subroutine discrete_energy(model, u, w, mesh, energy, parts, law, law_model, law_energy)
        type(model_t), intent(in) :: model
        real(dp), intent(in), contiguous :: u(0:), w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(out) :: energy
        real(dp), intent(out), optional :: parts(N_ENERGY_PARTS)
        class(contact_law_t), intent(in), optional :: law
        type(model_t), intent(in), optional :: law_model
        real(dp), intent(out), optional :: law_energy
        real(dp) :: sums(PART_MASS_FLUX), terms(N_ENERGY_PARTS)

        call level_sums(u, w, mesh, sums)
        terms(PART_CONTACT) = 0.0_dp
        if (present(law)) terms(PART_CONTACT) = law%energy(u(ubound(u, 1)))
        call model_terms(model, sums, w, mesh, terms)
        energy = sum(terms)
        if (present(parts)) parts = terms
        if (present(law_energy)) then
            call model_terms(law_model, sums, w, mesh, terms)
            law_energy = sum(terms)
        end if
    end subroutine discrete_energy

    !> The terms of E^n but the contact term (terms(1:PART_MASS_FLUX)) of model from level_sums.
    pure subroutine model_terms(model, sums, w, mesh, terms)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: sums(PART_MASS_FLUX)
        real(dp), intent(in), contiguous :: w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(inout) :: terms(N_ENERGY_PARTS)

        terms(:PART_MASS_FLUX) = [model%rho, model%alpha, model%c, model%r, 2.0_dp * model%d, model%tau0, &
                                  model%tau * model%hbar] * HALF_OF_SUMS * sums
        terms(PART_KINETIC) = terms(PART_KINETIC) + inertia_difference(model, w, mesh)
    end subroutine model_terms

    !> The integrals E^n's terms are made of, without the coefficients, exact for P1 functions:
    !> sums(PART_STRAIN) = int u_x^2, sums(MASS_PARTS(k)) = 6 int a b (fields MASS_A(k), MASS_B(k)).
    !> On element e, 6 int a b = h_e (2 a0 b0 + a0 b1 + a1 b0 + 2 a1 b1). On a uniform mesh the
    !> sum over the elements is taken by nodes, in fewer operations: h (sum_{i=1..s} N_i
    !> + 2 a_0 b_0 - 2 a_s b_s), N_i = a_i (2 b_i + b_{i-1}) + b_i (2 a_i + a_{i-1}); the nodes
    !> of odd and of even index are summed apart (two lanes, one vector register).
    pure subroutine level_sums(u, w, mesh, sums)
        real(dp), intent(in), contiguous :: u(0:), w(0:, :)
        type(mesh_t), intent(in) :: mesh
        real(dp), intent(out) :: sums(PART_MASS_FLUX)
        real(dp) :: lanes(2, PART_MASS_FLUX), h
        integer :: i, k, s

        s = ubound(u, 1)
        if (.not. mesh%is_uniform()) then
            sums = 0.0_dp
            do i = 1, s
                h = mesh%h(i)
                sums(PART_STRAIN) = sums(PART_STRAIN) + (u(i) - u(i - 1))**2 / h
                do k = 1, size(MASS_PARTS)
                    associate (a0 => w(i - 1, MASS_A(k)), a1 => w(i, MASS_A(k)), b0 => w(i - 1, MASS_B(k)), &
                               b1 => w(i, MASS_B(k)), total => sums(MASS_PARTS(k)))
                        total = total + h * ((a0 + a1) * (b0 + b1) + a0 * b0 + a1 * b1)
                    end associate
                end do
            end do
            return
        end if
        ! N_i of nodes i, i + 1, halved for a = b: a_i (2 a_i + a_{i-1}); the coupling's is
        ! halved at the end (exact; kept out of the loop, which it would slow down)
        lanes = 0.0_dp
        do i = 1, s - 1, 2
            lanes(:, PART_STRAIN) = lanes(:, PART_STRAIN) + (u(i:i + 1) - u(i - 1:i))**2
            do k = 1, size(MASS_PARTS)
                associate (a => w(i - 1:i + 1, MASS_A(k)), b => w(i - 1:i + 1, MASS_B(k)), &
                           lane => lanes(:, MASS_PARTS(k)))
                    lane = lane + a(2:3) * (2.0_dp * b(2:3) + b(1:2))
                    if (MASS_A(k) /= MASS_B(k)) lane = lane + b(2:3) * (2.0_dp * a(2:3) + a(1:2))
                end associate
            end do
        end do
        sums = lanes(1, :) + lanes(2, :)
        sums(PART_COUPLING) = 0.5_dp * sums(PART_COUPLING)
        if (mod(s, 2) == 1) then   ! node s, alone
            sums(PART_STRAIN) = sums(PART_STRAIN) + (u(s) - u(s - 1))**2
            sums(MASS_PARTS) = sums(MASS_PARTS) + 0.5_dp * (w(s, MASS_A) * (2.0_dp * w(s, MASS_B) + w(s - 1, MASS_B)) &
                                                            + w(s, MASS_B) * (2.0_dp * w(s, MASS_A) + w(s - 1, MASS_A)))
        end if
        sums(PART_STRAIN) = sums(PART_STRAIN) * real(s, dp)
        sums(MASS_PARTS) = 2.0_dp * (sums(MASS_PARTS) + w(0, MASS_A) * w(0, MASS_B) - w(s, MASS_A) * w(s, MASS_B)) &
                           / real(s, dp)
    end subroutine level_sums

    !> What the velocity's mass of &contact mass adds to the consistent kinetic energy above:
    !> 1/2 rho v^T (M_v - M) v with fe_m's inertia_element (the matrix scheme_m assembles), so
    !> the kinetic energy is the scheme's own; 0 for the consistent mass.
    pure real(dp) function inertia_difference(model, w, mesh) result(energy)
        type(model_t), intent(in) :: model
        real(dp), intent(in) :: w(0:, :)
        type(mesh_t), intent(in) :: mesh

        energy = 0.0_dp
        if (.not. (model%mass_end_moved .or. model%mass_lumped > 0.0_dp)) return
        block
            real(dp) :: y(0:ubound(w, 1))   ! (M_v - M) v
            y = 0.0_dp
            call add_inertia_difference(mesh%h, model%mass_lumped, model%mass_end_moved, w(:, F_V), y)
            energy = 0.5_dp * model%rho * dot_product(w(:, F_V), y)
        end block
    end function inertia_difference

    !> The energy of the BDF2 scheme's law, E_G^n = (E_lin(X^n) + E_lin(2 X^n - X^{n-1})) / 2
    !> plus the contact term at the current level: it never rises while the contact node is
    !> inactive (G-stability; derivation: docs/scheme.md, "Time schemes (`&time scheme`)").
    !> u_work, w_work: arrays shaped as u, w (no allocation here; called every step).
    !> lin: E_lin(X^n), which the caller has from discrete_energy.
    subroutine bdf2_energy(model, law, u, w, u_prev, w_prev, mesh, u_work, w_work, lin, energy)
        type(model_t), intent(in) :: model
        class(contact_law_t), intent(in) :: law
        real(dp), intent(in), contiguous :: u(0:), w(0:, :), u_prev(0:), w_prev(0:, :)
        type(mesh_t), intent(in) :: mesh           !< the mesh of both levels
        real(dp), intent(inout), contiguous :: u_work(0:), w_work(0:, :)
        real(dp), intent(in) :: lin
        real(dp), intent(out) :: energy
        real(dp) :: lin_extrapolated

        u_work = 2.0_dp * u - u_prev
        w_work = 2.0_dp * w - w_prev
        call discrete_energy(model, u_work, w_work, mesh, lin_extrapolated)
        energy = 0.5_dp * (lin + lin_extrapolated) + law%energy(u(ubound(u, 1)))
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

        self%scheme_law = scheme%row%law
        self%model = model
        self%law_model = model
        if (self%scheme_law%step_model) self%law_model = step_model
        self%law = law
        if (self%scheme_law%energy == LAW_G_ENERGY) call self%resize(state)
        call measure(self, state)
        ! the G-energy needs the level before: it is defined from the second level on
        self%have_law = self%scheme_law%energy /= LAW_G_ENERGY
        self%max_rise = 0.0_dp
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
        real(dp) :: rise
        logical :: changed

        call measure_rise(self, state, rise)
        changed = .false.
        if (present(step_changed)) changed = step_changed .and. self%scheme_law%constant_steps
        if (changed) then
            self%max_rise_step_change = max(self%max_rise_step_change, rise)
        else
            self%max_rise = max(self%max_rise, rise)
        end if
    end subroutine monitor_observe

    !> E^n of the level `state` and its terms (kept for monitor_parts) from one pass, and the
    !> law energy: E^n with the law's model, or the G-energy once a previous level exists.
    subroutine measure(self, state)
        class(energy_monitor_t), intent(inout) :: self
        type(state_t), intent(in) :: state

        call discrete_energy(self%model, state%u, state%w, state%mesh, self%energy, self%last_parts, self%law, &
                             self%law_model, self%law_energy)
        self%have_parts = .true.
        self%parts_step = state%step
        self%parts_t = state%t
        self%parts_nodes = size(state%u)
        if (self%scheme_law%energy /= LAW_G_ENERGY) return
        self%have_law = allocated(state%u_prev)
        if (.not. self%have_law) return
        if (size(self%u_work) /= size(state%u)) call self%resize(state)
        call bdf2_energy(self%model, self%law, state%u, state%w, state%u_prev, state%w_prev, state%mesh, &
                         self%u_work, self%w_work, sum(self%last_parts(:PART_MASS_FLUX)), &
                         self%law_energy)
    end subroutine measure

    !> The energies of the level and the relative rise of the law energy since the level
    !> measured before (0 where the law energy is not defined before and after).
    subroutine measure_rise(self, state, rise)
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
    end subroutine measure_rise

    !> The level has moved to a new mesh (transfer_m): measured, the remesh counted.
    subroutine monitor_remeshed(self, state)
        class(energy_monitor_t), intent(inout) :: self
        type(state_t), intent(in) :: state
        real(dp) :: rise

        call measure_rise(self, state, rise)
        self%n_remeshes = self%n_remeshes + 1
        self%max_rise_remesh = max(self%max_rise_remesh, rise)
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
    !> energy_max_relative_rise*): at steps of the step size before, at steps of another
    !> size (a law stated for constant steps only: BDF2), and across remeshes (and their count).
    pure subroutine monitor_rises(self, max_rise, max_rise_step_change, max_rise_remesh, &
                                  n_remeshes)
        class(energy_monitor_t), intent(in) :: self
        real(dp), intent(out) :: max_rise, max_rise_step_change
        real(dp), intent(out), optional :: max_rise_remesh
        integer, intent(out), optional :: n_remeshes

        max_rise = self%max_rise
        max_rise_step_change = self%max_rise_step_change
        if (present(max_rise_remesh)) max_rise_remesh = self%max_rise_remesh
        if (present(n_remeshes)) n_remeshes = self%n_remeshes
    end subroutine monitor_rises

    !> The terms of E^n (discrete_energy's parts, PART_*) of the level in state, with the
    !> monitor's model and contact law: they add up to current_energy() when state is the
    !> level observed last.
    pure function monitor_parts(self, state) result(parts)
        class(energy_monitor_t), intent(in) :: self
        type(state_t), intent(in) :: state
        real(dp) :: parts(N_ENERGY_PARTS)
        real(dp) :: energy

        if (self%have_parts .and. state%step == self%parts_step .and. equal(state%t, self%parts_t) &
            .and. size(state%u) == self%parts_nodes) then
            parts = self%last_parts   ! computed with E^n when the level was observed
        else
            call discrete_energy(self%model, state%u, state%w, state%mesh, energy, parts, self%law)
        end if
    end function monitor_parts

    !> The energies and the largest rises so far in a checkpoint (checkpoint_m's sync; restored
    !> on a monitor initialised for this run); the remeshes under their old owner, mesh.
    subroutine monitor_checkpoint(self, ckpt)
        class(energy_monitor_t), intent(inout) :: self
        type(checkpoint_t), intent(inout) :: ckpt

        call ckpt%sync('energy_monitor/energy', self%energy)
        call ckpt%sync('energy_monitor/law_energy', self%law_energy)
        call ckpt%sync('energy_monitor/have_law', self%have_law)
        call ckpt%sync('energy_monitor/max_rise', self%max_rise)
        call ckpt%sync('energy_monitor/max_rise_step_change', self%max_rise_step_change)
        call ckpt%sync('mesh/n_remeshes', self%n_remeshes)
        call ckpt%sync('mesh/max_rise_remesh', self%max_rise_remesh)
        if (ckpt%reading) self%have_parts = .false.
    end subroutine monitor_checkpoint

end module energy_m
