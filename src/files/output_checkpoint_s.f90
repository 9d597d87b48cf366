!> The checkpoint writer of output_m (see restart_m for what a checkpoint holds): a
!> submodule, so that it reaches the writer's open file without making it public.
submodule (output_m) output_checkpoint_s
    use iso_c_binding, only: c_loc, c_ptr
    use hdf5, only: h5lexists_f, h5dopen_f, h5ldelete_f, h5screate_f, H5S_SCALAR_F, H5T_STD_I64LE, &
                    h5kind_to_type, H5_INTEGER_KIND, h5gopen_f, H5P_DEFAULT_F, &
                    h5tcreate_f, h5tinsert_f, h5tclose_f, H5T_COMPOUND_F
    use checkpoint_m, only: entry_t
    use errors_m, only: check_allocation
    implicit none

contains

    !> Write the checkpoint ckpt: entry 'owner/name' as dataset /checkpoint/slotN/owner/name, or
    !> for a scalar as member name of the owner's compound dataset /checkpoint/slotN/owner/scalars
    !> (docs/output.md), integers as 64-bit integers; note says which
    !> state it is ('step 250 (t = ...)', for the message of a later output failure). Raw
    !> data reach the file as they are written, so a kill in the middle of a checkpoint would
    !> leave a torn one; there are therefore two slots, /checkpoint/slot0 and
    !> /checkpoint/slot1: the new checkpoint goes into the slot not in use, the file is
    !> flushed, and only then /checkpoint/current is pointed at it (and flushed). The flushes
    !> are SWMR writing's (output_file_s), which write a chunk index before what points to
    !> it, so a run killed at any moment leaves the last complete checkpoint, and the history
    !> flushed with it, readable. The first checkpoint creates both slots; later ones write
    !> into the same datasets, held open (a checkpoint puts the same entries every time).
    module procedure writer_write_checkpoint
        integer :: k, d, slot
        logical :: exists
        integer :: hdferr

        call w%need_open('write_checkpoint()')
        call h5lexists_f(w%file_id, 'checkpoint', exists, hdferr)
        call w%check(hdferr, 'h5lexists_f /checkpoint')
        slot = 1 - w%checkpoint_slot      ! the slot not holding the last checkpoint
        if (.not. exists) call create_slots(w, ckpt)
        if (size(w%ckpt_names) /= ckpt%n) call w%fail('internal error: a checkpoint of other entries than the first')
        do k = 1, ckpt%n
            if (ckpt%entries(k)%name /= w%ckpt_names(k)) &
                call w%fail('internal error: checkpoint entry '//ckpt%entries(k)%name//' out of order')
        end do
        do d = 1, size(w%ckpt_types)
            if (exists) call put_set(w, d, slot, ckpt)   ! (create_slots wrote the first)
        end do
        call w%flush()
        call put_int64(w, w%ckpt_current_id, [int(slot, int64)], 'current')
        call w%flush()
        w%checkpoint_slot = slot
        w%checkpoint_note = note
        w%n_checkpoints = w%n_checkpoints + 1
    end procedure writer_write_checkpoint

    !> The first checkpoint creates everything later ones write into, SWMR writing being off
    !> (output_file_s): the groups, the datasets of both slots (written), the pointer
    !> /checkpoint/current (-1: no checkpoint yet), the layout attribute that tells this
    !> layout from the positional one of earlier versions, and for an adaptive mesh
    !> /snapshots/native. An owner's scalars share one dataset, `scalars`, a compound of
    !> named members (one dataset each would cost its creation, ~0.15M instructions).
    subroutine create_slots(w, ckpt)
        class(h5_writer_t), intent(inout) :: w
        type(checkpoint_t), intent(in) :: ckpt
        integer(hid_t) :: group_id, space_id
        character(len=:), allocatable :: failed
        integer :: k, d, slot, stat
        character(len=256) :: message
        integer :: hdferr

        call w%leave_swmr()
        call make_groups(w, 'checkpoint/slot0/x')
        call make_groups(w, 'checkpoint/slot1/x')
        call h5gopen_f(w%file_id, 'checkpoint', group_id, hdferr)
        call w%check(hdferr, 'h5gopen_f /checkpoint')
        call put_attr(group_id, 'layout', CHECKPOINT_LAYOUT, failed)
        if (failed /= '') call w%fail(failed)
        call h5gclose_f(group_id, hdferr)
        call w%check(hdferr, 'h5gclose_f /checkpoint')
        call h5screate_simple_f(1, [1_hsize_t], space_id, hdferr)
        call w%check(hdferr, 'h5screate_simple_f /checkpoint/current')
        call h5dcreate_f(w%file_id, 'checkpoint/current', H5T_STD_I64LE, space_id, w%ckpt_current_id, hdferr)
        call w%check(hdferr, 'h5dcreate_f /checkpoint/current')
        call h5sclose_f(space_id, hdferr)
        call put_int64(w, w%ckpt_current_id, [-1_int64], 'current')
        if (allocated(w%ckpt_names)) deallocate (w%ckpt_ids, w%ckpt_dims, w%ckpt_names, w%ckpt_set, w%ckpt_types)
        allocate (w%ckpt_names(ckpt%n), w%ckpt_set(ckpt%n), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the checkpoint writer')
        d = 0
        do k = 1, ckpt%n
            w%ckpt_names(k) = ckpt%entries(k)%name
            w%ckpt_set(k) = scalars_of(ckpt, k)
            if (w%ckpt_set(k) > 0) w%ckpt_set(k) = w%ckpt_set(w%ckpt_set(k))
            if (w%ckpt_set(k) > 0) cycle
            d = d + 1
            w%ckpt_set(k) = d
        end do
        allocate (w%ckpt_ids(d, 0:1), w%ckpt_dims(2, d, 0:1), w%ckpt_types(d), stat=stat, errmsg=message)
        call check_allocation(stat, message, 'the checkpoint writer')
        w%ckpt_ids = -1
        w%ckpt_types = -1
        do d = 1, size(w%ckpt_types)
            k = findloc(w%ckpt_set, d, 1)
            do slot = 0, 1
                ! an owner's datasets come together: its groups are made at its first
                if (d == 1) then
                    call make_groups(w, 'checkpoint/slot'//int_str(slot)//'/'//ckpt%entries(k)%name)
                else if (parent(ckpt%entries(k)%name) /= parent(w%ckpt_names(findloc(w%ckpt_set, d - 1, 1)))) then
                    call make_groups(w, 'checkpoint/slot'//int_str(slot)//'/'//ckpt%entries(k)%name)
                end if
                call create_set(w, d, slot, ckpt)
            end do
        end do
        if (ckpt%has('adaptive_mesh/keys') .and. .not. w%native_created) call writer_create_native(w)
    end subroutine create_slots

    !> A scalar entry k's first fellow (a scalar of the same owner before it), else 0.
    pure integer function scalars_of(ckpt, k) result(j)
        type(checkpoint_t), intent(in) :: ckpt
        integer, intent(in) :: k

        if (ckpt%entries(k)%rank == 0) then
            do j = 1, k - 1
                if (ckpt%entries(j)%rank > 0) cycle
                if (parent(ckpt%entries(j)%name) == parent(ckpt%entries(k)%name)) return
            end do
        end if
        j = 0
    end function scalars_of

    !> 'a/b/' of 'a/b/c'.
    pure function parent(path) result(head)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: head

        head = path(:index(path, '/', back=.true.))
    end function parent

    !> The path of dataset d in a slot: an array entry's own name, or <owner>/scalars.
    function set_path(w, d, slot, ckpt) result(path)
        class(h5_writer_t), intent(in) :: w
        integer, intent(in) :: d, slot
        type(checkpoint_t), intent(in) :: ckpt
        character(len=:), allocatable :: path

        associate (entry => ckpt%entries(findloc(w%ckpt_set, d, 1)))
            path = 'checkpoint/slot'//int_str(slot)//'/'//entry%name
            if (entry%rank == 0) path = 'checkpoint/slot'//int_str(slot)//'/'//parent(entry%name)//'scalars'
        end associate
    end function set_path

    !> The groups on the path to dataset `path` that do not exist yet.
    subroutine make_groups(w, path)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: path
        logical :: exists
        integer :: i
        integer :: hdferr

        do i = 1, len(path)
            if (path(i:i) /= '/') cycle
            call h5lexists_f(w%file_id, path(:i - 1), exists, hdferr)
            call w%check(hdferr, 'h5lexists_f /'//path(:i - 1))
            if (.not. exists) call w%make_group(path(:i - 1))
        end do
    end subroutine make_groups

    !> Create dataset d in a slot and write it: an owner's scalars as one compound of named
    !> members (integers int64, reals float64), an array chunked and extendible (an adaptive
    !> mesh's arrays and the events change size, and a later checkpoint resizes them in SWMR
    !> writing).
    subroutine create_set(w, d, slot, ckpt)
        class(h5_writer_t), intent(inout) :: w
        integer, intent(in) :: d, slot
        type(checkpoint_t), intent(in) :: ckpt
        integer(hid_t) :: space_id, dcpl_id, file_type
        integer(hsize_t) :: dims(2), maxdims(2)
        character(len=:), allocatable :: name
        integer :: hdferr

        name = set_path(w, d, slot, ckpt)
        associate (entry => ckpt%entries(findloc(w%ckpt_set, d, 1)))
            dims = int(entry%dims, hsize_t)
            maxdims = H5S_UNLIMITED_F
            dcpl_id = H5P_DEFAULT_F
            if (entry%rank == 0) then
                call scalar_types(w, d, ckpt, file_type)
                call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
            else
                file_type = merge(H5T_STD_I64LE, H5T_IEEE_F64LE, entry%is_integer)
                call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl_id, hdferr)
                call w%check(hdferr, 'h5pcreate_f (dataset creation) /'//name)
                call h5pset_chunk_f(dcpl_id, entry%rank, max(dims(:entry%rank), 1_hsize_t), hdferr)
                call w%check(hdferr, 'h5pset_chunk_f /'//name)
                call h5screate_simple_f(entry%rank, dims, space_id, hdferr, maxdims)
            end if
            call w%check(hdferr, 'h5screate_f /'//name)
            call h5dcreate_f(w%file_id, name, file_type, space_id, w%ckpt_ids(d, slot), hdferr, dcpl_id=dcpl_id)
            call w%check(hdferr, 'h5dcreate_f /'//name)
            if (entry%rank > 0) call h5pclose_f(dcpl_id, hdferr)
            if (entry%rank == 0) call h5tclose_f(file_type, hdferr)
            call w%check(hdferr, 'h5pclose_f, h5tclose_f /'//name)
            call h5sclose_f(space_id, hdferr)
            call w%check(hdferr, 'h5sclose_f /'//name)
            w%ckpt_dims(:, d, slot) = entry%dims
        end associate
        call put_set(w, d, slot, ckpt)
    end subroutine create_set

    !> The compound types of dataset d, an owner's scalars: file_type (little-endian) and,
    !> kept for the run, the writer's memory type (native), every member 8 bytes.
    subroutine scalar_types(w, d, ckpt, file_type)
        class(h5_writer_t), intent(inout) :: w
        integer, intent(in) :: d
        type(checkpoint_t), intent(in) :: ckpt
        integer(hid_t), intent(out) :: file_type
        integer(size_t) :: offset
        integer :: k, hdferr
        logical :: fresh

        offset = 8 * count(w%ckpt_set == d)
        call h5tcreate_f(H5T_COMPOUND_F, offset, file_type, hdferr)
        call w%check(hdferr, 'h5tcreate_f (checkpoint scalars)')
        fresh = w%ckpt_types(d) < 0
        if (fresh) call h5tcreate_f(H5T_COMPOUND_F, offset, w%ckpt_types(d), hdferr)
        call w%check(hdferr, 'h5tcreate_f (checkpoint scalars)')
        offset = 0
        do k = 1, ckpt%n
            if (w%ckpt_set(k) /= d) cycle
            associate (entry => ckpt%entries(k), member => ckpt%entries(k)%name(index(ckpt%entries(k)%name, '/', &
                                                                                        back=.true.) + 1:))
                call h5tinsert_f(file_type, member, offset, merge(H5T_STD_I64LE, H5T_IEEE_F64LE, entry%is_integer), &
                                 hdferr)
                call w%check(hdferr, 'h5tinsert_f '//entry%name)
                if (fresh) call h5tinsert_f(w%ckpt_types(d), member, offset, &
                                            merge(h5kind_to_type(int64, H5_INTEGER_KIND), H5T_NATIVE_DOUBLE, &
                                                  entry%is_integer), hdferr)
                call w%check(hdferr, 'h5tinsert_f '//entry%name)
            end associate
            offset = offset + 8
        end do
    end subroutine scalar_types

    !> Write dataset d of a slot (opened if leave_swmr closed it; an array resized if its
    !> shape changed).
    subroutine put_set(w, d, slot, ckpt)
        class(h5_writer_t), intent(inout) :: w
        integer, intent(in) :: d, slot
        type(checkpoint_t), intent(in), target :: ckpt
        integer(int64), target :: scalars(count(w%ckpt_set == d))
        type(c_ptr) :: buf
        integer :: k, m, hdferr

        k = findloc(w%ckpt_set, d, 1)
        associate (id => w%ckpt_ids(d, slot), entry => ckpt%entries(k))
            if (id < 0) then
                call h5dopen_f(w%file_id, set_path(w, d, slot, ckpt), id, hdferr)
                call w%check(hdferr, 'h5dopen_f /'//set_path(w, d, slot, ckpt))
            end if
            if (any(w%ckpt_dims(:, d, slot) /= entry%dims)) then
                call h5dset_extent_f(id, int(entry%dims(:entry%rank), hsize_t), hdferr)
                call w%check(hdferr, 'h5dset_extent_f /'//set_path(w, d, slot, ckpt))
                w%ckpt_dims(:, d, slot) = entry%dims
            end if
            if (entry%rank == 0) then
                m = 0
                do k = k, ckpt%n
                    if (w%ckpt_set(k) /= d) cycle
                    m = m + 1
                    if (ckpt%entries(k)%is_integer) then
                        scalars(m) = ckpt%entries(k)%ints(1)
                    else
                        scalars(m) = transfer(ckpt%entries(k)%reals(1), 0_int64)
                    end if
                end do
                buf = c_loc(scalars)
                call h5dwrite_f(id, w%ckpt_types(d), buf, hdferr)
            else if (product(entry%dims) == 0) then
                return
            else if (entry%is_integer) then
                buf = c_loc(entry%ints)
                call h5dwrite_f(id, h5kind_to_type(int64, H5_INTEGER_KIND), buf, hdferr)
            else
                buf = c_loc(entry%reals)
                call h5dwrite_f(id, H5T_NATIVE_DOUBLE, buf, hdferr)
            end if
            call w%check(hdferr, 'h5dwrite_f /'//set_path(w, d, slot, ckpt))
        end associate
    end subroutine put_set

    !> Write the whole integer dataset dset_id from values.
    subroutine put_int64(w, dset_id, values, name)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: dset_id
        integer(int64), intent(in), target :: values(:)
        character(len=*), intent(in) :: name
        integer :: hdferr
        type(c_ptr) :: buf

        buf = c_loc(values)
        call h5dwrite_f(dset_id, h5kind_to_type(int64, H5_INTEGER_KIND), buf, hdferr)
        call w%check(hdferr, 'h5dwrite_f /checkpoint/'//name)
    end subroutine put_int64

    !> Close the checkpoint's datasets (leave_swmr: the file is closed and reopened; the next
    !> checkpoint opens them again).
    module procedure writer_close_checkpoint
        integer :: k, slot

        if (w%ckpt_current_id >= 0) call w%close_dataset(w%ckpt_current_id, '/checkpoint/current')
        if (.not. allocated(w%ckpt_ids)) return
        do slot = 0, 1
            do k = 1, size(w%ckpt_ids, 1)
                if (w%ckpt_ids(k, slot) >= 0) call w%close_dataset(w%ckpt_ids(k, slot), '(a checkpoint dataset)')
            end do
        end do
    end procedure writer_close_checkpoint

    !> Remove the object `name` if it exists (finish(): what SWMR writing made the run create
    !> in advance and it never used).
    module procedure writer_drop
        logical :: exists
        integer :: hdferr

        call h5lexists_f(w%file_id, name, exists, hdferr)
        call w%check(hdferr, 'h5lexists_f '//name)
        if (.not. exists) return
        call h5ldelete_f(w%file_id, name, hdferr)
        call w%check(hdferr, 'h5ldelete_f '//name)
    end procedure writer_drop

end submodule output_checkpoint_s
