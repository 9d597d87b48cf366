!> Meshes for the tests: mesh_m's mesh_t built in one expression.
module meshes_m
    use kinds_m, only: dp
    use mesh_m, only: mesh_t
    implicit none
    private
    public :: uniform_mesh, graded_mesh

contains

    !> The uniform mesh of s elements.
    function uniform_mesh(s) result(mesh)
        integer, intent(in) :: s
        type(mesh_t) :: mesh

        call mesh%set_uniform(s)
    end function uniform_mesh

    !> The graded mesh with nodes x(0:s).
    function graded_mesh(x) result(mesh)
        real(dp), intent(in) :: x(0:)
        type(mesh_t) :: mesh

        call mesh%set_nodes(x)
    end function graded_mesh

end module meshes_m
