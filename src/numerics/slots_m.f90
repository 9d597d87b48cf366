!> The system vector of (6.1): where each field sits within a node (its slot) in the
!> monolithic system, in the paper's Section 7 blocks and in a monolithic system of fewer
!> fields (scheme_m's active_fields), and the fields' way in and out of it: nodes
!> interleaved, unknown (node i, field f) at nf*i + slots(f) of nf*(s+1), nf = count(slots > 0).
module slots_m
    use kinds_m, only: dp
    use fields_m, only: N_FIELDS
    implicit none
    private
    public :: MONOLITHIC_SLOTS, THERMAL_SLOTS, MECHANICAL_SLOTS, slots_of, scatter_fields, gather_fields

    ! Field order within a node (fields_m's F_*). The coupling graph (q-theta, theta-v,
    ! theta-P, v-P, P-eta) is a triangle theta-v-P with q and eta hanging off theta and P;
    ! the order q, theta, v, P, eta puts every coupled pair at most 2 slots apart, so the
    ! interleaved system has kl = ku = 5 + 2 = 7 (an arbitrary order needs up to 9).

    !> Slot of each field within a node for the three systems (0: field not in the system).
    !> monolithic: all five fields; the paper's Section 7 splitting: a thermal block
    !> (q, theta, P, eta; kl = ku = 4 + 1 = 5) and a mechanical block (v; tridiagonal).
    integer, parameter :: MONOLITHIC_SLOTS(N_FIELDS) = [1, 2, 3, 4, 5]
    integer, parameter :: THERMAL_SLOTS(N_FIELDS) = [1, 2, 0, 3, 4]
    integer, parameter :: MECHANICAL_SLOTS(N_FIELDS) = [0, 0, 1, 0, 0]

contains

    !> Slots of the monolithic system holding only the active fields, in the order of
    !> MONOLITHIC_SLOTS (0: field left out).
    pure function slots_of(active) result(slots)
        logical, intent(in) :: active(N_FIELDS)
        integer :: slots(N_FIELDS)
        integer :: f, k

        slots = 0
        k = 0
        do f = 1, N_FIELDS
            if (.not. active(f)) cycle
            k = k + 1
            slots(f) = k
        end do
    end function slots_of

    !> Interleave field-major w(0:s, f) into the system vector x (fields with slots > 0).
    pure subroutine scatter_fields(slots, w, x)
        integer, intent(in) :: slots(N_FIELDS)
        real(dp), intent(in), contiguous :: w(0:, :)
        real(dp), intent(out), contiguous :: x(:)
        integer :: f, nf, i

        nf = count(slots > 0)
        if (nf == N_FIELDS) then
            ! every field: node by node, the five slots of a node stored together
            do i = 0, ubound(w, 1)
                x(N_FIELDS * i + slots) = w(i, :)
            end do
            return
        end if
        ! field by field: field f is every nf-th entry of x from its slot
        do f = 1, N_FIELDS
            if (slots(f) > 0) x(slots(f)::nf) = w(:, f)
        end do
    end subroutine scatter_fields

    !> Inverse of scatter_fields: copy the system vector x into the fields it holds.
    pure subroutine gather_fields(slots, x, w)
        integer, intent(in) :: slots(N_FIELDS)
        real(dp), intent(in), contiguous :: x(:)
        real(dp), intent(inout), contiguous :: w(0:, :)
        integer :: f, nf, i

        nf = count(slots > 0)
        if (nf == N_FIELDS) then
            do i = 0, ubound(w, 1)
                w(i, :) = x(N_FIELDS * i + slots)
            end do
            return
        end if
        do f = 1, N_FIELDS
            if (slots(f) > 0) w(:, f) = x(slots(f)::nf)
        end do
    end subroutine gather_fields

end module slots_m
