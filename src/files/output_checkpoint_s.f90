!> The checkpoint writer of output_m (the layout: docs/output.md, "Checkpoints"): a
!> submodule, so that it reaches the writer's open file without making it public.
submodule (output_m) output_checkpoint_s
    use hdf5, only: H5T_STD_I64LE, &
                    h5kind_to_type, H5_INTEGER_KIND, H5P_DEFAULT_F, &
                    h5tcreate_f, h5tinsert_f, H5T_COMPOUND_F
    use checkpoint_m, only: entry_t
    use errors_m, only: check_allocation
    implicit none

contains

    !> Write the checkpoint ckpt (checkpoint_m's record) into the slot not in use; note says
    !> which state it is ('step 250 (t = ...)', for the message of a later output failure).
    !> Raw data reach the file as they are written, so only after a flush is
    !> /checkpoint/current pointed at the new slot (and flushed): a kill at any moment leaves
    !> the last complete checkpoint (docs/output.md, "Checkpoints" and "A killed run"). The
    !> first checkpoint creates both slots; later ones put the same entries (checked) into
    !> the same datasets.
    module procedure writer_write_checkpoint
        integer :: k, slot
        logical :: first

        call w%need_open('write_checkpoint()')
        slot = 1 - w%checkpoint_slot      ! the slot not holding the last checkpoint
        first = .not. allocated(w%ckpt_set)
        if (first) call create_slots(w, ckpt)   ! (writes it into both)
        if (size(w%ckpt_names) /= ckpt%n) &
            call w%fail('internal error: a checkpoint of other entries than the first')
        do k = 1, ckpt%n
            if (ckpt%entries(k)%name /= w%ckpt_names(k)) &
                call w%fail('internal error: checkpoint entry '//ckpt%entries(k)%name//' out of order')
            if (w%ckpt_set(k) == k .and. .not. first) call put_set(w, k, slot, ckpt)
        end do
        call w%flush()
        call put_current(w, int(slot, int64))
        call w%flush()
        w%checkpoint_slot = slot
        w%checkpoint_note = note
        w%n_checkpoints = w%n_checkpoints + 1
    end procedure writer_write_checkpoint

    !> The first checkpoint creates everything later ones write into, SWMR writing being off
    !> (output_file_s): the groups, the datasets of both slots (written), the pointer
    !> /checkpoint/current (-1: no checkpoint yet), the layout attribute, and for an adaptive
    !> mesh /snapshots/native. A dataset is known by its first entry (ckpt_set): an array
    !> entry's own, or the first scalar of an owner, whose scalars share one dataset.
    subroutine create_slots(w, ckpt)
        class(h5_writer_t), intent(inout) :: w
        type(checkpoint_t), intent(in) :: ckpt
        integer(hid_t) :: group_id, space_id
        character(len=64) :: sets(ckpt%n)
        integer :: k, slot, stat, hdferr
        character(len=256) :: message

        call w%leave_swmr()
        call h5gcreate_f(w%file_id, 'checkpoint', group_id, hdferr)
        call w%check(hdferr, 'h5gcreate_f /checkpoint')
        call w%attr('layout', CHECKPOINT_LAYOUT, on=group_id)
        call h5gclose_f(group_id, hdferr)
        call w%check(hdferr, 'h5gclose_f /checkpoint')
        call h5screate_simple_f(1, [1_hsize_t], space_id, hdferr)
        call w%check(hdferr, 'h5screate_simple_f /checkpoint/current')
        call h5dcreate_f(w%file_id, 'checkpoint/current', H5T_STD_I64LE, space_id, w%ckpt_current_id, hdferr)
        call w%check(hdferr, 'h5dcreate_f /checkpoint/current')
        call h5sclose_f(space_id, hdferr)
        call w%check(hdferr, 'h5sclose_f /checkpoint/current')
        call put_current(w, -1_int64)
        allocate (w%ckpt_names(ckpt%n), w%ckpt_set(ckpt%n), w%ckpt_ids(ckpt%n, 0:1), w%ckpt_types(ckpt%n), &
                  stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the checkpoint writer')
        w%ckpt_ids = -1
        w%ckpt_types = -1
        do k = 1, ckpt%n
            w%ckpt_names(k) = ckpt%entries(k)%name
            sets(k) = set_path(ckpt%entries(k), 0)
            w%ckpt_set(k) = findloc(sets(:k), sets(k), 1)
        end do
        do k = 1, ckpt%n
            if (w%ckpt_set(k) /= k) cycle
            do slot = 0, 1
                call create_set(w, k, slot, ckpt)
            end do
        end do
        if (ckpt%has('adaptive_mesh/keys') .and. .not. w%native_created) call writer_create_native(w)
    end subroutine create_slots

    !> The dataset of an entry in a slot: an array's own, checkpoint/slotN/owner/name; a
    !> scalar's, its owner's checkpoint/slotN/owner/scalars.
    pure function set_path(entry, slot) result(path)
        type(entry_t), intent(in) :: entry
        integer, intent(in) :: slot
        character(len=:), allocatable :: path

        path = 'checkpoint/slot'//int_str(slot)//'/'//entry%name
        if (entry%rank == 0) path = path(:index(path, '/', back=.true.))//'scalars'
    end function set_path

    !> Create the dataset of first entry d in a slot and write it: an owner's scalars as one
    !> compound of named members (int64 or float64, native: the machine's byte order, which
    !> a reader converts), an array chunked and extendible (an adaptive mesh's arrays and the
    !> events change size, and a later checkpoint resizes them in SWMR writing).
    subroutine create_set(w, d, slot, ckpt)
        class(h5_writer_t), intent(inout) :: w
        integer, intent(in) :: d, slot
        type(checkpoint_t), intent(in) :: ckpt
        integer(hid_t) :: space_id, dcpl_id, file_type
        integer(hsize_t) :: dims(2)
        character(len=:), allocatable :: name
        integer :: k, member, hdferr

        name = set_path(ckpt%entries(d), slot)
        associate (entry => ckpt%entries(d))
            dims = int(entry%dims, hsize_t)
            dcpl_id = H5P_DEFAULT_F
            if (entry%rank == 0) then
                if (w%ckpt_types(d) < 0) then
                    call h5tcreate_f(H5T_COMPOUND_F, int(8 * count(w%ckpt_set == d), size_t), w%ckpt_types(d), hdferr)
                    call w%check(hdferr, 'h5tcreate_f /'//name)
                    member = 0
                    do k = d, ckpt%n
                        if (w%ckpt_set(k) /= d) cycle
                        associate (full => ckpt%entries(k)%name)
                            call h5tinsert_f(w%ckpt_types(d), full(index(full, '/', back=.true.) + 1:), &
                                             int(8 * member, size_t), word_type(ckpt%entries(k)), hdferr)
                            call w%check(hdferr, 'h5tinsert_f '//full)
                        end associate
                        member = member + 1
                    end do
                end if
                file_type = w%ckpt_types(d)
                call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
            else
                file_type = merge(H5T_STD_I64LE, H5T_IEEE_F64LE, entry%is_integer)
                call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl_id, hdferr)
                call w%check(hdferr, 'h5pcreate_f (dataset creation) /'//name)
                call h5pset_chunk_f(dcpl_id, entry%rank, max(dims(:entry%rank), 1_hsize_t), hdferr)
                call w%check(hdferr, 'h5pset_chunk_f /'//name)
                call h5screate_simple_f(entry%rank, dims, space_id, hdferr, [H5S_UNLIMITED_F, H5S_UNLIMITED_F])
            end if
            call w%check(hdferr, 'h5screate_f /'//name)
            call h5dcreate_f(w%file_id, name, file_type, space_id, w%ckpt_ids(d, slot), hdferr, dcpl_id, &
                             w%lcpl_id)
            call w%check(hdferr, 'h5dcreate_f /'//name)
            if (entry%rank > 0) call h5pclose_f(dcpl_id, hdferr)
            call w%check(hdferr, 'h5pclose_f /'//name)
            call h5sclose_f(space_id, hdferr)
            call w%check(hdferr, 'h5sclose_f /'//name)
        end associate
        call put_set(w, d, slot, ckpt)
    end subroutine create_set

    !> The memory type of an entry's 64-bit words (checkpoint_m's entry_t).
    function word_type(entry) result(type_id)
        type(entry_t), intent(in) :: entry
        integer(hid_t) :: type_id

        type_id = merge(h5kind_to_type(int64, H5_INTEGER_KIND), H5T_NATIVE_DOUBLE, entry%is_integer)
    end function word_type

    !> Write the dataset of first entry d in a slot (opened if leave_swmr closed it; an array
    !> given its shape, a change only if the shape changed; an owner's scalars packed in their order).
    subroutine put_set(w, d, slot, ckpt)
        class(h5_writer_t), intent(inout) :: w
        integer, intent(in) :: d, slot
        type(checkpoint_t), intent(in), target :: ckpt
        integer(int64), target :: scalars(count(w%ckpt_set == d))
        type(c_ptr) :: buf
        integer :: k, m, hdferr
        character(len=:), allocatable :: name

        name = set_path(ckpt%entries(d), slot)
        associate (id => w%ckpt_ids(d, slot), entry => ckpt%entries(d))
            call w%hold(id, '/'//name)
            if (entry%rank > 0) then
                call h5dset_extent_f(id, int(entry%dims(:entry%rank), hsize_t), hdferr)
                call w%check(hdferr, 'h5dset_extent_f /'//name)
            end if
            hdferr = 0
            if (entry%rank == 0) then
                m = 0
                do k = d, ckpt%n
                    if (w%ckpt_set(k) /= d) cycle
                    m = m + 1
                    scalars(m) = ckpt%entries(k)%values(1)
                end do
                buf = c_loc(scalars)
                call h5dwrite_f(id, w%ckpt_types(d), buf, hdferr)
            else if (size(entry%values) > 0) then
                buf = c_loc(entry%values)
                call h5dwrite_f(id, word_type(entry), buf, hdferr)
            end if
            call w%check(hdferr, 'h5dwrite_f /'//name)
        end associate
    end subroutine put_set

    !> Point /checkpoint/current at a slot (-1: none); opened if leave_swmr closed it.
    subroutine put_current(w, slot)
        class(h5_writer_t), intent(inout) :: w
        integer(int64), intent(in) :: slot
        integer(int64), target :: value(1)
        type(c_ptr) :: buf
        integer :: hdferr

        call w%hold(w%ckpt_current_id, '/checkpoint/current')
        value = slot
        buf = c_loc(value)
        call h5dwrite_f(w%ckpt_current_id, h5kind_to_type(int64, H5_INTEGER_KIND), buf, hdferr)
        call w%check(hdferr, 'h5dwrite_f /checkpoint/current')
    end subroutine put_current

end submodule output_checkpoint_s
