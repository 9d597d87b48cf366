!> A checkpoint in memory: everything a run needs to continue exactly, as the types that
!> hold it save it and restore it (&output checkpoint_every, &time restart_from).
!>
!> checkpoint_t is a record, not an owner: each part is written by the type it belongs to,
!> with that type's own save_checkpoint and read back by its restore_checkpoint:
!>   state_t (state_m)               state, previous, counters COUNTER_STEP, _T, _DT_LAST, _T_ANCHOR, _STEP_ANCHOR;
!>                                   its mesh_t (mesh_m): max_rise_remesh, n_remeshes
!>   stepper_t (stepper_m)           counters COUNTER_SOLVES, _CONTACT_STEPS
!>   energy_monitor_t (energy_m)     counters COUNTER_ENERGY, _LAW_ENERGY, _HAVE_LAW, _MAX_RISE;
!>                                   max_rise_step_change
!>   step_controller_t, error_estimator_t (step_control_m)   control, history
!>   step_driver_t (step_driver_m)   in_contact, events
!>   adaptive_mesh_t (adaptive_mesh_m)   mesh_scale, mesh_keys (has_mesh)
!>   error_companions_t (error_companion_m)   companion_levels, companion_scalars
!>                                   (&output error_estimate only)
!>   run_t (run_m)                   n_elements_max (&mesh adaptive only)
!> How the record is laid out in the file's /checkpoint group is restart_m's business.
module checkpoint_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use fields_m, only: N_FIELDS
    implicit none
    private
    public :: checkpoint_t, N_COUNTERS, COUNTER_STEP, COUNTER_T, COUNTER_SOLVES, COUNTER_CONTACT_STEPS, &
              COUNTER_ENERGY, COUNTER_LAW_ENERGY, COUNTER_HAVE_LAW, COUNTER_MAX_RISE, COUNTER_DT_LAST, &
              COUNTER_T_ANCHOR, COUNTER_STEP_ANCHOR

    !> The scalars of /checkpoint/slotN/counters, by position.
    integer, parameter :: COUNTER_STEP = 1, COUNTER_T = 2, COUNTER_SOLVES = 3, COUNTER_CONTACT_STEPS = 4, &
                          COUNTER_ENERGY = 5, COUNTER_LAW_ENERGY = 6, COUNTER_HAVE_LAW = 7, COUNTER_MAX_RISE = 8, &
                          COUNTER_DT_LAST = 9, COUNTER_T_ANCHOR = 10, COUNTER_STEP_ANCHOR = 11
    integer, parameter :: N_COUNTERS = 11

    type :: checkpoint_t
        real(dp) :: counters(N_COUNTERS) = 0.0_dp
        real(dp), allocatable :: state(:, :)      !< (s+1, 1+N_FIELDS): u, then fields_m's F_*
        real(dp), allocatable :: previous(:, :)   !< the level before (multistep schemes; else unallocated)
        real(dp), allocatable :: control(:)       !< step control's scalars (unallocated: none saved)
        real(dp), allocatable :: history(:, :)    !< the error estimator's past levels
        logical :: in_contact = .false.           !< the contact state events are counted from
        real(dp) :: max_rise_step_change = 0.0_dp
        real(dp), allocatable :: events(:, :)     !< (n_events, 2): t and kind of each event
        logical :: has_mesh = .false.             !< an adaptive mesh is saved
        real(dp) :: mesh_scale(0:N_FIELDS) = 0.0_dp
        real(dp) :: max_rise_remesh = 0.0_dp
        integer :: n_remeshes = 0
        integer(int64), allocatable :: mesh_keys(:)   !< (0:s)
        integer :: n_elements_max = 0             !< the most elements the run has held (0: not saved)
        real(dp), allocatable :: companion_levels(:, :)   !< the error estimate's companions (unallocated: none)
        real(dp), allocatable :: companion_scalars(:)
    end type checkpoint_t

end module checkpoint_m
