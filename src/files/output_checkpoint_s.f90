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
    !> flushed). The flushes are SWMR writing's (output_file_s), which write a chunk index
    !> before what points to it, so a run killed at any moment leaves the last complete
    !> checkpoint, and the history flushed with it, readable.
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

        if (.not. w%opened) call fatal(EXIT_OUTPUT, 'output', 'internal error: write_checkpoint() on a closed writer')
        call h5lexists_f(w%file_id, 'checkpoint', exists, hdferr)
        call w%check(hdferr, 'h5lexists_f /checkpoint')
        if (.not. exists) then
            ! the first checkpoint creates everything later ones write into, SWMR writing
            ! being off (output_file_s): both slots, the pointer (-1: no checkpoint yet), and
            ! for an adaptive mesh /snapshots/native
            call w%leave_swmr()
            do k = 1, size(GROUPS)
                call h5gcreate_f(w%file_id, trim(GROUPS(k)), group_id, hdferr)
                call w%check(hdferr, 'h5gcreate_f /'//trim(GROUPS(k)))
                call h5gclose_f(group_id, hdferr)
                call w%check(hdferr, 'h5gclose_f /'//trim(GROUPS(k)))
            end do
            call w%put_real('/checkpoint/current', [-1.0_dp], [1, 1])
            do k = 0, 1
                call put_slot(w, '/checkpoint/slot'//int_str(k), .true., state, counters, previous, control, history, &
                              events, mesh, companion_levels, companion_scalars)
            end do
            if (present(mesh) .and. .not. w%native_created) call writer_create_native(w)
        end if
        w%checkpoint_slot = 1 - w%checkpoint_slot      ! the slot not holding the last checkpoint
        call put_slot(w, '/checkpoint/slot'//int_str(w%checkpoint_slot), .false., state, counters, previous, control, &
                      history, events, mesh, companion_levels, companion_scalars)
        call w%flush()
        call w%put_real('/checkpoint/current', [real(w%checkpoint_slot, dp)], [1, 1])
        call w%flush()
        w%checkpoint_note = note
        w%n_checkpoints = w%n_checkpoints + 1
        w%n_slot_events(w%checkpoint_slot) = 0
        if (present(events)) w%n_slot_events(w%checkpoint_slot) = size(events, 1)
    end subroutine writer_write_checkpoint

    !> Write (create_only: create, at their shapes) the datasets of one checkpoint slot
    !> (write_checkpoint's arguments).
    subroutine put_slot(w, slot, create_only, state, counters, previous, control, history, events, mesh, &
                        companion_levels, companion_scalars)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: slot
        logical, intent(in) :: create_only
        real(dp), intent(in) :: state(:, :), counters(:)
        real(dp), intent(in), optional :: previous(:, :), control(:), history(:, :), events(:, :), mesh(:)
        real(dp), intent(in), optional :: companion_levels(:, :), companion_scalars(:)

        call w%put_real(slot//'/state', state, shape(state), create_only)
        call w%put_real(slot//'/counters', counters, [size(counters), 1], create_only)
        if (present(previous)) call w%put_real(slot//'/previous', previous, shape(previous), create_only)
        if (present(control)) call w%put_real(slot//'/control', control, [size(control), 1], create_only)
        if (present(history)) call w%put_real(slot//'/history', history, shape(history), create_only)
        if (present(mesh)) call w%put_real(slot//'/mesh', mesh, [size(mesh), 1], create_only)
        if (present(companion_levels)) call w%put_real(slot//'/companion_levels', companion_levels, &
                                                       shape(companion_levels), create_only)
        if (present(companion_scalars)) call w%put_real(slot//'/companion_scalars', companion_scalars, &
                                                        [size(companion_scalars), 1], create_only)
        ! the events grow from one checkpoint to the next; an empty list is removed by finish()
        if (present(events)) call w%put_real(slot//'/events', events, shape(events), create_only)
    end subroutine put_slot

    !> Remove the object `name` if it exists (finish(): what SWMR writing made the run create
    !> in advance and it never used).
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

    !> Write a real dataset (rank 1 when shape2(2) == 1, else rank 2); create_only: create
    !> it, empty, at that shape. A dataset of another shape (the events, the arrays on an
    !> adaptive mesh) is resized: datasets are chunked and extendible, so that a checkpoint
    !> rewrites its slot in SWMR writing; creating one ends SWMR writing (output_file_s).
    module subroutine writer_put_real(w, name, values, shape2, create_only)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: values(*)
        integer, intent(in) :: shape2(2)
        logical, intent(in), optional :: create_only

        integer(hid_t) :: dset_id, space_id, dcpl_id
        integer(hsize_t) :: dims(2), maxdims(2)
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
            call h5dset_extent_f(dset_id, dims(1:rank), hdferr)
            call w%check(hdferr, 'h5dset_extent_f '//name)
        else
            call w%leave_swmr()
            maxdims = H5S_UNLIMITED_F
            call h5screate_simple_f(rank, dims(1:rank), space_id, hdferr, maxdims(1:rank))
            call w%check(hdferr, 'h5screate_simple_f '//name)
            call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl_id, hdferr)
            call w%check(hdferr, 'h5pcreate_f (dataset creation) '//name)
            call h5pset_chunk_f(dcpl_id, rank, max(dims(1:rank), 1_hsize_t), hdferr)
            call w%check(hdferr, 'h5pset_chunk_f '//name)
            call h5dcreate_f(w%file_id, name, H5T_NATIVE_DOUBLE, space_id, dset_id, hdferr, dcpl_id=dcpl_id)
            call w%check(hdferr, 'h5dcreate_f '//name)
            call h5pclose_f(dcpl_id, hdferr)
            call w%check(hdferr, 'h5pclose_f (dataset creation) '//name)
            call h5sclose_f(space_id, hdferr)
            call w%check(hdferr, 'h5sclose_f '//name)
        end if
        if (product(shape2) > 0 .and. .not. present_and_true(create_only)) then
            call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, values(1:product(shape2)), dims(1:rank), hdferr)
            call w%check(hdferr, 'h5dwrite_f '//name)
        end if
        call h5dclose_f(dset_id, hdferr)
        call w%check(hdferr, 'h5dclose_f '//name)
    end subroutine writer_put_real

    pure logical function present_and_true(flag)
        logical, intent(in), optional :: flag

        present_and_true = .false.
        if (present(flag)) present_and_true = flag
    end function present_and_true

end submodule output_checkpoint_s
