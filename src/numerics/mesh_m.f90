!> The mesh of Section 6: nodes 0 = x_0 < x_1 < ... < x_s = 1 and element sizes
!> h_e = x_e - x_{e-1}, e = 1..s. The state owns it (state_m); the stepper keeps a copy of
!> the mesh its factored matrices belong to. The uniform mesh of &mesh n_elements is the
!> graded mesh whose elements all have h_e = 1/s exactly; it remembers that it was built
!> uniform (is_uniform): equal elements take the written-out tridiagonal kernel, and a few
!> choices are kept with it (stepper_m: the LAPACK pivot inverse; output_m: no native
!> snapshots). A mesh of adaptive_mesh_m is graded even where its elements happen to be equal.
module mesh_m
    use kinds_m, only: dp
    use errors_m, only: check_allocation
    use fe_m, only: mesh_nodes, element_mass, element_stiffness, apply_assembled, apply_mass_graded, &
                    apply_stiffness_graded
    implicit none
    private
    public :: mesh_t, copy_mesh

    type :: mesh_t
        real(dp), allocatable :: x(:)   !< the nodes x_i, i = 0..s (written by mesh_m only)
        real(dp), allocatable :: h(:)   !< element sizes h_e, e = 1..s (uniform: 1/s; mesh_m only)
        logical, private :: uniform = .true.          !< built by set_uniform
    contains
        procedure :: s => mesh_elements
        procedure :: is_uniform => mesh_is_uniform
        procedure :: set_uniform => mesh_set_uniform
        procedure :: set_nodes => mesh_set_nodes
        procedure :: apply_mass => mesh_apply_mass
        procedure :: apply_stiffness => mesh_apply_stiffness
    end type mesh_t

contains

    !> Number of elements s.
    pure integer function mesh_elements(self)
        class(mesh_t), intent(in) :: self

        mesh_elements = ubound(self%x, 1)
    end function mesh_elements

    !> Was the mesh built uniform (h_e = 1/s exactly: the kernels for equal elements apply)?
    pure logical function mesh_is_uniform(self)
        class(mesh_t), intent(in) :: self

        mesh_is_uniform = self%uniform
    end function mesh_is_uniform

    !> The uniform mesh of s elements: x_i = i/s, h_e = 1/s.
    subroutine mesh_set_uniform(self, s)
        class(mesh_t), intent(inout) :: self
        integer, intent(in) :: s

        call allocate_arrays(self, s)
        self%x = mesh_nodes(s)
        self%h = 1.0_dp / real(s, dp)
        self%uniform = .true.
    end subroutine mesh_set_uniform

    !> The graded mesh with nodes x(0:s), increasing from 0 to 1.
    subroutine mesh_set_nodes(self, x)
        class(mesh_t), intent(inout) :: self
        real(dp), intent(in) :: x(0:)
        integer :: s

        s = ubound(x, 1)
        call allocate_arrays(self, s)
        self%x = x
        self%h = x(1:s) - x(0:s - 1)
        self%uniform = .false.
    end subroutine mesh_set_nodes

    !> x(0:s) and h(1:s), reallocated only when s changes.
    subroutine allocate_arrays(self, s)
        type(mesh_t), intent(inout) :: self
        integer, intent(in) :: s
        integer :: stat
        character(len=256) :: message

        if (allocated(self%x)) then
            if (ubound(self%x, 1) == s) return
            deallocate (self%x, self%h)
        end if
        allocate (self%x(0:s), self%h(s), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the mesh')
    end subroutine allocate_arrays

    !> copy = mesh, reusing copy's arrays (a rejected adaptive step restores the state from a
    !> copy: the intrinsic assignment would allocate every step). A uniform mesh is fixed by
    !> its size, so its arrays are not copied again.
    subroutine copy_mesh(mesh, copy)
        type(mesh_t), intent(in) :: mesh
        type(mesh_t), intent(inout) :: copy
        logical :: same_uniform

        same_uniform = .false.
        if (allocated(copy%x)) same_uniform = mesh%uniform .and. copy%uniform .and. &
                                              ubound(copy%x, 1) == ubound(mesh%x, 1)
        if (.not. same_uniform) then
            call allocate_arrays(copy, ubound(mesh%x, 1))
            copy%x = mesh%x
            copy%h = mesh%h
        end if
        copy%uniform = mesh%uniform
    end subroutine copy_mesh

    !> y = M x, M the P1 mass matrix of the mesh (int phi_i phi_j dx); x, y have bounds 0..s.
    !> No allocation (called every time step).
    pure subroutine mesh_apply_mass(self, x, y)
        class(mesh_t), intent(in) :: self
        real(dp), intent(in) :: x(0:)
        real(dp), intent(out) :: y(0:)

        if (self%uniform) then
            call apply_assembled(element_mass(self%h(1)), x, y)
        else
            call apply_mass_graded(self%h, x, y)
        end if
    end subroutine mesh_apply_mass

    !> y = K x, K the P1 stiffness matrix of the mesh (int phi_i' phi_j' dx); see apply_mass.
    pure subroutine mesh_apply_stiffness(self, x, y)
        class(mesh_t), intent(in) :: self
        real(dp), intent(in) :: x(0:)
        real(dp), intent(out) :: y(0:)

        if (self%uniform) then
            call apply_assembled(element_stiffness(self%h(1)), x, y)
        else
            call apply_stiffness_graded(self%h, x, y)
        end if
    end subroutine mesh_apply_stiffness

end module mesh_m
