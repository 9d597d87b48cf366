!> The checkpoint writer of output_m (see restart_m for what a checkpoint holds): a
!> submodule, so that it reaches the writer's open file without making it public.
submodule (output_m) output_checkpoint_s
    use hdf5, only: h5lexists_f, h5dopen_f, h5ldelete_f
    implicit none

contains

    !> Write the restart data: state (s+1, 6) with columns u, q, theta, v, P, eta; counters
    !> (a real vector, see restart_m); previous (s+1, 6), the level before, for multistep
    !> schemes; note says which state it is ('step 250 (t = ...)', for the message of a later
    !> output failure). Raw data reach the file as they are written, so a kill in the middle of a
    !> checkpoint would leave a torn one; there are therefore two slots,
    !> /checkpoint/slot0 and /checkpoint/slot1: the new checkpoint goes into the slot not in
    !> use, the file is flushed, and only then /checkpoint/current is pointed at it (and
    !> flushed). A run killed at any moment leaves the last complete checkpoint readable.
    module subroutine writer_write_checkpoint(w, state, counters, note, previous, control, history, events, mesh, &
                                                    companion_levels, companion_scalars)
        class(h5_writer_t), intent(inout) :: w
        real(dp), intent(in) :: state(:, :)
        real(dp), intent(in) :: counters(:)
        character(len=*), intent(in) :: note
        real(dp), intent(in), optional :: previous(:, :)
        real(dp), intent(in), optional :: control(:)      !< step control's scalars (step_control_m)
        real(dp), intent(in), optional :: history(:, :)   !< the error estimator's past levels
        real(dp), intent(in), optional :: events(:, :)    !< (n_events, 2): t and kind of each event
        !> adaptive mesh: its field scales, the remesh counters, then its node keys (restart_m)
        real(dp), intent(in), optional :: mesh(:)
        !> &output error_estimate: its companions' levels and scalars (error_companion_m)
        real(dp), intent(in), optional :: companion_levels(:, :), companion_scalars(:)

        integer(hid_t) :: group_id
        logical :: exists
        integer :: hdferr, k
        character(len=*), parameter :: GROUPS(3) = [character(len=17) :: &
            'checkpoint', 'checkpoint/slot0', 'checkpoint/slot1']
        character(len=:), allocatable :: slot

        if (.not. w%opened) call fatal(EXIT_OUTPUT, 'output', 'internal error: write_checkpoint() on a closed writer')
        do k = 1, size(GROUPS)
            call h5lexists_f(w%file_id, trim(GROUPS(k)), exists, hdferr)
            call w%check(hdferr, 'h5lexists_f /'//trim(GROUPS(k)))
            if (exists) cycle
            call h5gcreate_f(w%file_id, trim(GROUPS(k)), group_id, hdferr)
            call w%check(hdferr, 'h5gcreate_f /'//trim(GROUPS(k)))
            call h5gclose_f(group_id, hdferr)
            call w%check(hdferr, 'h5gclose_f /'//trim(GROUPS(k)))
        end do
        w%checkpoint_slot = 1 - w%checkpoint_slot      ! the slot not holding the last checkpoint
        slot = '/checkpoint/slot0'
        if (w%checkpoint_slot == 1) slot = '/checkpoint/slot1'
        if (present(mesh)) then
            ! the mesh changes size between checkpoints: the arrays on it are written afresh
            call w%drop(slot//'/state')
            call w%drop(slot//'/previous')
            call w%drop(slot//'/history')
            call w%drop(slot//'/mesh')
        end if
        call w%put_real(slot//'/state', state, [size(state, 1), size(state, 2)])
        call w%put_real(slot//'/counters', counters, [size(counters), 1])
        if (present(previous)) call w%put_real(slot//'/previous', previous, [size(previous, 1), size(previous, 2)])
        if (present(control)) call w%put_real(slot//'/control', control, [size(control), 1])
        if (present(history)) call w%put_real(slot//'/history', history, [size(history, 1), size(history, 2)])
        if (present(mesh)) call w%put_real(slot//'/mesh', mesh, [size(mesh), 1])
        if (present(companion_levels)) call w%put_real(slot//'/companion_levels', companion_levels, &
                                                       [size(companion_levels, 1), size(companion_levels, 2)])
        if (present(companion_scalars)) call w%put_real(slot//'/companion_scalars', companion_scalars, &
                                                        [size(companion_scalars), 1])
        call w%drop(slot//'/events')
        if (present(events)) then
            if (size(events, 1) > 0) call w%put_real(slot//'/events', events, [size(events, 1), size(events, 2)])
        end if
        call w%flush()
        call w%put_real('/checkpoint/current', [real(w%checkpoint_slot, dp)], [1, 1])
        call w%flush()
        w%checkpoint_note = note
    end subroutine writer_write_checkpoint

    !> Remove the dataset `name` if it exists (a slot's event list changes length).
    module subroutine writer_drop(w, name)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        logical :: exists
        integer :: hdferr

        call h5lexists_f(w%file_id, name, exists, hdferr)
        call w%check(hdferr, 'h5lexists_f '//name)
        if (.not. exists) return
        call h5ldelete_f(w%file_id, name, hdferr)
        call w%check(hdferr, 'h5ldelete_f '//name)
    end subroutine writer_drop

    !> Write a fixed-size real dataset (rank 1 when shape(2) == 1, else rank 2), creating it
    !> on the first call.
    module subroutine writer_put_real(w, name, values, shape2)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: values(*)
        integer, intent(in) :: shape2(2)

        integer(hid_t) :: dset_id, space_id
        integer(hsize_t) :: dims(2)
        integer :: rank, hdferr
        logical :: exists

        dims = int(shape2, hsize_t)
        rank = 2
        if (shape2(2) == 1) rank = 1
        call h5lexists_f(w%file_id, name, exists, hdferr)
        call w%check(hdferr, 'h5lexists_f '//name)
        if (exists) then
            call h5dopen_f(w%file_id, name, dset_id, hdferr)
            call w%check(hdferr, 'h5dopen_f '//name)
        else
            call h5screate_simple_f(rank, dims(1:rank), space_id, hdferr)
            call w%check(hdferr, 'h5screate_simple_f '//name)
            call h5dcreate_f(w%file_id, name, H5T_NATIVE_DOUBLE, space_id, dset_id, hdferr)
            call w%check(hdferr, 'h5dcreate_f '//name)
            call h5sclose_f(space_id, hdferr)
            call w%check(hdferr, 'h5sclose_f '//name)
        end if
        call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, values(1:product(shape2)), dims(1:rank), hdferr)
        call w%check(hdferr, 'h5dwrite_f '//name)
        call h5dclose_f(dset_id, hdferr)
        call w%check(hdferr, 'h5dclose_f '//name)
    end subroutine writer_put_real

end submodule output_checkpoint_s
