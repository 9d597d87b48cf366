!> The HDF5 writer of the output file (its layout: docs/output.md, where h5py sees the
!> snapshot fields as (n_snap, s+1)): /mesh/x, /series and /snapshots named by fields_m's
!> tables, root and dataset attributes. Written as `<prefix>.h5.part` (resumed in place:
!> RESUMED_SUFFIX), renamed by finish(), its root attribute `status` 'incomplete' until
!> then; in HDF5's SWMR write mode between structural changes (output_file_s).
!> The writer knows nothing of the scheme: it stores what it is given, named by the tables.
module output_m
    use kinds_m, only: dp
    use iso_fortran_env, only: int64
    use strings_m, only: int_str
    use errors_m, only: fatal, fatal_now, EXIT_OUTPUT
    use fsys_m, only: mkdir_p, rename_file, remove_file, parent_dir, dir_exists, create_empty_file, &
                      write_failure_reason, reserve_file_size
    use h5_read_m, only: h5_library_init
    use checkpoint_m, only: checkpoint_t
    use material_m, only: si_scale_t
    use fields_m, only: FIELDS, OUTPUT_ORDER, SNAPSHOTS, N_SNAPSHOT_FIELDS, N_OUTPUT_FIELDS, SERIES, N_SERIES, S_T
    use iso_c_binding, only: c_ptr, c_loc, c_char, c_null_char
    use hdf5, only: hid_t, hsize_t, size_t, h5fcreate_f, h5fclose_f, h5fflush_f, h5fget_filesize_f, &
                    h5pset_cache_f, H5F_ACC_TRUNC_F, &
                    H5F_SCOPE_GLOBAL_F, H5F_CLOSE_STRONG_F, h5pcreate_f, h5pclose_f, &
                    h5pset_chunk_f, h5pset_deflate_f, h5pset_shuffle_f, h5pset_fclose_degree_f, &
                    H5P_FILE_ACCESS_F, &
                    H5P_DATASET_CREATE_F, h5gcreate_f, h5gclose_f, &
                    h5screate_simple_f, h5sclose_f, h5sselect_hyperslab_f, &
                    H5S_UNLIMITED_F, H5S_SELECT_SET_F, h5dcreate_f, h5dclose_f, &
                    h5dwrite_f, h5dset_extent_f, h5dget_space_f, h5dopen_f, &
                    H5T_IEEE_F64LE, H5T_STD_I32LE, H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER, h5screate_f, &
                    H5S_SCALAR_F, H5S_NULL_F, h5acreate_f, h5aclose_f, h5awrite_f, h5aexists_f, h5adelete_f, &
                    h5tcopy_f, h5tclose_f, h5tset_cset_f, H5T_STRING, H5T_CSET_UTF8_F
    implicit none
    private
    public :: h5_writer_t
    public :: SERIES_BUFFER_SIZE, SERIES_CHUNK, CHECKPOINT_LAYOUT, RESUMED_SUFFIX, ESTIMATE_PARTS, estimate_path

    !> Series entries held in memory between writes: memory bounded by 4096 x N_SERIES
    !> reals (192 KiB) whatever the length of the run.
    integer, parameter :: SERIES_BUFFER_SIZE = 4096
    !> Chunk length of the /series datasets and /snapshots/t: 256 entries, 2 KiB of float64,
    !> what a short run pays for each (docs/output.md, "Chunks"); snapshot fields: a row a chunk.
    integer, parameter :: SERIES_CHUNK = 256
    !> Attribute layout of /checkpoint: slotN/<owner>/<array>, slotN/<owner>/scalars (a compound)
    character(len=*), parameter :: CHECKPOINT_LAYOUT = 'slotN/owner/name, slotN/owner/scalars'
    !> The file of a run resumed in place, beside the <prefix>.h5.part it continues
    character(len=*), parameter :: RESUMED_SUFFIX = '.resume.h5.part'
    !> The error estimate's parts: its datasets /snapshots/<part>/<field> (estimate_path), the
    !> final estimate's root attributes <part>.<field>
    character(len=*), parameter :: ESTIMATE_PARTS(3) = [character(len=20) :: 'error_estimate', &
                                                        'error_estimate_time', 'error_estimate_space']

    !> Datasets that grow together by one entry per append, through a buffer written when
    !> full and at every flush (the series; the error estimates)
    type :: buffered_t
        integer(hid_t), allocatable :: ids(:)
        character(len=64), allocatable :: paths(:)
        logical, allocatable :: whole(:)       !< int32 datasets, written from whole numbers
        real(dp), allocatable :: buf(:, :)     !< (entry, dataset)
        integer :: n_buf = 0                   !< entries waiting in buf
        integer(hsize_t) :: n = 0              !< entries in the file
    end type buffered_t

    !> Writer of one rodcontact HDF5 file. Use: create, then any number of append_series /
    !> append_snapshot / attr / flush, then finish (or abandon on an output failure).
    type :: h5_writer_t
        private
        logical :: opened = .false.
        !> true inside create(): a failure there is reported as "cannot create" against
        !> &output prefix, later ones as "cannot write"
        logical :: creating = .false.
        character(len=:), allocatable :: final_path
        character(len=:), allocatable :: part_path
        !> resumed in place: the <prefix>.h5.part that finish() replaces ('' otherwise)
        character(len=:), allocatable :: replaces
        integer :: n_nodes = 0
        integer :: compression = 0                 !< deflate level of the extendible datasets (0: none)
        integer(hid_t) :: file_id = -1
        integer(hid_t) :: lcpl_id = -1             !< link creation: missing groups created
        type(buffered_t) :: series                 !< /series/<name>, in fields_m's SERIES order
        integer(hid_t) :: snap_t_id = -1
        integer(hid_t) :: snap_field_ids(N_SNAPSHOT_FIELDS) = -1
        integer(hsize_t) :: n_snap = 0             !< snapshots in the file
        integer :: checkpoint_slot = 1             !< slot of the last checkpoint (1: none yet, so slot 0 is next)
        !> what the last complete checkpoint is ('step 250 (t = 2.5000E-02)'), '' before the first
        character(len=:), allocatable :: checkpoint_note
        character(len=:), allocatable :: logical_names   !< the logical root attributes, ' '-separated
        integer(hsize_t) :: n_native_snap = 0      !< snapshots in /snapshots/native (adaptive mesh)
        integer(int64) :: n_native_values = 0      !< entries of /snapshots/native/x
        type(si_scale_t), allocatable :: si(:)     !< the datasets' SI scales (create(), &material)
        !> /snapshots/error_estimate*/<field> (estimate_path), from the first append (output_create_s)
        type(buffered_t) :: estimates
        logical :: swmr = .false.                  !< the file is in SWMR write mode (output_file_s)
        logical :: closing = .false.               !< inside finish(): flush() leaves SWMR mode off
        logical :: native_created = .false.        !< /snapshots/native exists (output_create_s)
        integer :: n_checkpoints = 0               !< checkpoints written
        !> the checkpoint's datasets, open from the first checkpoint (output_checkpoint_s),
        !> each known by its first entry
        integer(hid_t), allocatable :: ckpt_ids(:, :)         !< (first entry, slot)
        character(len=64), allocatable :: ckpt_names(:)       !< the entries' names
        integer, allocatable :: ckpt_set(:)                   !< an entry's dataset: its first entry
        integer(hid_t), allocatable :: ckpt_types(:)          !< an owner's scalars' compound type
        integer(hid_t) :: ckpt_current_id = -1                !< /checkpoint/current
    contains
        procedure :: create => writer_create
        procedure :: append_series => writer_append_series
        procedure :: append_snapshot => writer_append_snapshot
        procedure :: append_native => writer_append_native
        procedure :: append_estimate => writer_append_estimate
        procedure, private :: attr_scalar => writer_attr_scalar
        procedure, private :: attr_array => writer_attr_array
        generic :: attr => attr_scalar, attr_array
        procedure :: flush => writer_flush
        procedure :: write_checkpoint => writer_write_checkpoint
        procedure :: write_events => writer_write_events
        procedure :: finish => writer_finish
        procedure :: abandon => writer_abandon
        procedure, private :: check => writer_check
        procedure, private :: need_open => writer_need_open
        procedure, private :: fail => writer_fail
        procedure, private :: start_buffered => writer_start_buffered
        procedure, private :: push => writer_push
        procedure, private :: write_buffer => writer_write_buffer
        procedure, private :: append_rows => writer_append_rows
        procedure, private :: close_dataset => writer_close_dataset
        procedure, private :: hold => writer_hold
        procedure, private :: leave_swmr => writer_leave_swmr
    end type h5_writer_t

    interface   ! the submodules' procedures (output_*_s.f90), their arguments declared here only
        module subroutine writer_create(w, prefix, x, compression, in_place, scales)
            class(h5_writer_t), intent(inout) :: w
            character(len=*), intent(in) :: prefix
            real(dp), intent(in) :: x(0:)
            integer, intent(in), optional :: compression
            logical, intent(in), optional :: in_place
            type(si_scale_t), intent(in), optional :: scales(:)
        end subroutine writer_create

        module subroutine writer_open_file(w, create)
            class(h5_writer_t), intent(inout) :: w
            logical, intent(in) :: create
        end subroutine writer_open_file

        module subroutine writer_flush(w)
            class(h5_writer_t), intent(inout) :: w
        end subroutine writer_flush

        module subroutine writer_leave_swmr(w)
            class(h5_writer_t), intent(inout) :: w
        end subroutine writer_leave_swmr

        module subroutine writer_fail(w, reason)
            class(h5_writer_t), intent(inout) :: w
            character(len=*), intent(in) :: reason
        end subroutine writer_fail

        module subroutine writer_finish(w, status, keep_part)
            class(h5_writer_t), intent(inout) :: w
            character(len=*), intent(in) :: status
            !> .true.: leave the closed file as <prefix>.h5.part (a run stopped by a signal, to be
            !> continued by restart_from), not renamed to <prefix>.h5
            logical, intent(in), optional :: keep_part
        end subroutine writer_finish

        module subroutine writer_abandon(w)
            class(h5_writer_t), intent(inout) :: w
        end subroutine writer_abandon

        module subroutine writer_create_native(w)
            class(h5_writer_t), intent(inout) :: w
        end subroutine writer_create_native

        module subroutine writer_append_rows(w, dset_id, what, offset, block, values, whole)
            class(h5_writer_t), intent(inout) :: w
            integer(hid_t), intent(inout) :: dset_id
            character(len=*), intent(in) :: what
            integer(hsize_t), intent(in) :: offset, block(:)
            real(dp), intent(in) :: values(*)
            logical, intent(in), optional :: whole
        end subroutine writer_append_rows

        module subroutine writer_write_events(w, t, kind)
            class(h5_writer_t), intent(inout) :: w
            real(dp), intent(in) :: t(:)
            integer, intent(in) :: kind(:)
        end subroutine writer_write_events

        module subroutine writer_append_native(w, x, values)
            class(h5_writer_t), intent(inout) :: w
            real(dp), intent(in) :: x(:)
            real(dp), intent(in) :: values(:, :)
        end subroutine writer_append_native

        module subroutine writer_append_estimate(w, values)
            class(h5_writer_t), intent(inout) :: w
            real(dp), intent(in) :: values(N_OUTPUT_FIELDS, size(ESTIMATE_PARTS))
        end subroutine writer_append_estimate

        module subroutine writer_write_checkpoint(w, ckpt, note)
            class(h5_writer_t), intent(inout) :: w
            type(checkpoint_t), intent(in) :: ckpt
            character(len=*), intent(in) :: note
        end subroutine writer_write_checkpoint
    end interface

contains
    !> Add one series entry: values(k) of the dataset fields_m's SERIES(k) (integer ones
    !> hold whole numbers). Held in a fixed-size buffer and written SERIES_BUFFER_SIZE
    !> entries at a time: this is called every time step, so it must cost a few stores.
    subroutine writer_append_series(w, values)
        class(h5_writer_t), intent(inout) :: w
        real(dp), intent(in) :: values(N_SERIES)

        call w%need_open('append_series()')
        call w%push(w%series, values)
    end subroutine writer_append_series

    !> Add one snapshot at time t: values(:, k) holds the nodal values (boundary zeros
    !> included) of fields_m's SNAPSHOTS(k). Written to the file at once (one new row per dataset).
    subroutine writer_append_snapshot(w, t, values)
        class(h5_writer_t), intent(inout) :: w
        real(dp), intent(in) :: t
        real(dp), intent(in) :: values(:, :)
        integer :: k

        call w%need_open('append_snapshot()')
        if (any(shape(values) /= [w%n_nodes, N_SNAPSHOT_FIELDS])) &
            call w%fail('internal error: append_snapshot() given arrays whose size is not the number of mesh nodes')
        call w%append_rows(w%snap_t_id, '/snapshots/t', w%n_snap, [1_hsize_t], [t])
        do k = 1, N_SNAPSHOT_FIELDS
            call w%append_rows(w%snap_field_ids(k), '/snapshots/'//trim(SNAPSHOTS(k)%name), w%n_snap, &
                               [int(w%n_nodes, hsize_t), 1_hsize_t], values(:, k))
        end do
        w%n_snap = w%n_snap + 1
    end subroutine writer_append_snapshot

    !> Scalar attribute of the root group (or of dataset `on`), replaced if present: float64,
    !> int32, a variable-length UTF-8 string (h5py: str), or a logical as int32 1 / 0, which
    !> Python tests as it should, listed by finish() in `logical_attributes` (docs/output.md).
    subroutine writer_attr_scalar(w, name, value, on)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        class(*), intent(in), target :: value
        integer(hid_t), intent(in), optional :: on   !< a dataset (default: the root group)
        integer, target :: flag
        integer(hid_t) :: type_id
        integer :: hdferr

        select type (value)
        type is (real(dp))
            call put_attr(w, name, on, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, -1, c_loc(value))
        type is (integer)
            call put_attr(w, name, on, H5T_STD_I32LE, H5T_NATIVE_INTEGER, -1, c_loc(value))
        type is (logical)
            flag = merge(1, 0, value)
            call put_attr(w, name, on, H5T_STD_I32LE, H5T_NATIVE_INTEGER, -1, c_loc(flag))
            if (index(' '//w%logical_names//' ', ' '//name//' ') == 0) &
                w%logical_names = trim(adjustl(w%logical_names//' '//name))
        type is (character(len=*))
            block   ! a variable-length string: a pointer to a NUL-terminated C string
                character(kind=c_char, len=len(value) + 1), target :: chars
                type(c_ptr), target :: str_ptr(1)

                chars = value//c_null_char
                str_ptr(1) = c_loc(chars)
                call h5tcopy_f(H5T_STRING, type_id, hdferr)
                call w%check(hdferr, 'h5tcopy_f (string type) for attribute '//name)
                call h5tset_cset_f(type_id, H5T_CSET_UTF8_F, hdferr)
                call w%check(hdferr, 'h5tset_cset_f for attribute '//name)
                call put_attr(w, name, on, type_id, type_id, -1, c_loc(str_ptr))
                call h5tclose_f(type_id, hdferr)
                call w%check(hdferr, 'h5tclose_f (string type) for attribute '//name)
            end block
        class default
            call w%fail('internal error: an attribute of an unknown type, '//name//' failed')
        end select
    end subroutine writer_attr_scalar

    !> Float64 array attribute (e.g. polynomial coefficients); replaced if present. An empty
    !> array is stored with a null dataspace (h5py: h5py.Empty).
    subroutine writer_attr_array(w, name, values, on)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        real(dp), intent(in), contiguous, target :: values(:)
        integer(hid_t), intent(in), optional :: on

        call put_attr(w, name, on, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, size(values), c_loc(values))
    end subroutine writer_attr_array

    !> Attribute `name` of type file_type on dataset `on` (default: the root group), from buf
    !> in mem_type: a scalar (n < 0), empty (n = 0: a null dataspace) or n values. An older
    !> one is deleted: HDF5 cannot re-create it in place (end-of-run values overwrite).
    subroutine put_attr(w, name, on, file_type, mem_type, n, buf)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in), optional :: on
        integer(hid_t), intent(in) :: file_type, mem_type
        integer, intent(in) :: n
        type(c_ptr), intent(in) :: buf
        integer(hid_t) :: obj_id, space_id, attr_id
        logical :: exists
        integer :: hdferr

        call w%need_open("attribute '"//name//"' written")
        if (w%swmr) then
            ! held dataset identifiers change when SWMR writing ends: none may be the target
            if (present(on)) &
                call w%fail("internal error: attribute '"//name//"' of a dataset in SWMR mode")
            call w%leave_swmr()
        end if
        obj_id = w%file_id
        if (present(on)) obj_id = on
        if (n < 0) call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
        if (n == 0) call h5screate_f(H5S_NULL_F, space_id, hdferr)
        if (n > 0) call h5screate_simple_f(1, [int(n, hsize_t)], space_id, hdferr)
        call w%check(hdferr, 'h5screate_f for attribute '//name)
        call h5aexists_f(obj_id, name, exists, hdferr)
        call w%check(hdferr, 'h5aexists_f attribute '//name)
        if (exists) call h5adelete_f(obj_id, name, hdferr)
        call w%check(hdferr, 'h5adelete_f attribute '//name)
        call h5acreate_f(obj_id, name, file_type, space_id, attr_id, hdferr)
        call w%check(hdferr, 'h5acreate_f attribute '//name)
        if (n /= 0) call h5awrite_f(attr_id, mem_type, buf, hdferr)
        call w%check(hdferr, 'h5awrite_f attribute '//name)
        call h5aclose_f(attr_id, hdferr)
        call w%check(hdferr, 'h5aclose_f attribute '//name)
        call h5sclose_f(space_id, hdferr)
        call w%check(hdferr, 'h5sclose_f for attribute '//name)
    end subroutine put_attr

    !> The dataset of the error estimate's part ESTIMATE_PARTS(part) of field OUTPUT_ORDER(k).
    pure function estimate_path(part, k) result(path)
        integer, intent(in) :: part, k
        character(len=:), allocatable :: path

        path = '/snapshots/'//trim(ESTIMATE_PARTS(part))//'/'//trim(FIELDS(OUTPUT_ORDER(k))%name)
    end function estimate_path

    ! ---------------------------------------------------------------- private helpers

    !> On a negative HDF5 error flag: abandon the file and stop (exit status 4).
    subroutine writer_check(w, hdferr, what)
        class(h5_writer_t), intent(inout) :: w
        integer, intent(in) :: hdferr
        character(len=*), intent(in) :: what

        if (hdferr >= 0) return
        call w%fail(what//' failed')
    end subroutine writer_check

    !> Close dataset dset_id (`what`, for the message) and mark it closed (-1).
    subroutine writer_close_dataset(w, dset_id, what)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(inout) :: dset_id
        character(len=*), intent(in) :: what
        integer :: hdferr

        call h5dclose_f(dset_id, hdferr)
        call w%check(hdferr, 'h5dclose_f '//what)
        dset_id = -1
    end subroutine writer_close_dataset

    !> Open dataset `path` as dset_id unless it is open: leave_swmr closes every dataset, and
    !> each is opened again where it is next written.
    subroutine writer_hold(w, dset_id, path)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(inout) :: dset_id
        character(len=*), intent(in) :: path
        integer :: hdferr

        if (dset_id >= 0) return
        call h5dopen_f(w%file_id, path, dset_id, hdferr)
        call w%check(hdferr, 'h5dopen_f '//path)
    end subroutine writer_hold

    !> Stop (exit 4) when the writer is not open: `what` came out of order.
    subroutine writer_need_open(w, what)
        class(h5_writer_t), intent(in) :: w
        character(len=*), intent(in) :: what

        if (.not. w%opened) &
            call fatal(EXIT_OUTPUT, 'output', 'internal error: '//what//' on a closed writer')
    end subroutine writer_need_open

    !> Set `set` up for n datasets (the caller creates them into set%ids, names them in
    !> set%paths and marks the int32 ones in set%whole), buffering `capacity` entries.
    subroutine writer_start_buffered(w, set, n, capacity)
        class(h5_writer_t), intent(inout) :: w
        type(buffered_t), intent(inout) :: set
        integer, intent(in) :: n, capacity
        integer :: stat
        character(len=256) :: message

        allocate (set%ids(n), set%paths(n), set%whole(n), set%buf(capacity, n), stat=stat, errmsg=message)
        if (stat /= 0) call w%fail('no memory for an output buffer ('//trim(message)//')')
        set%ids = -1
        set%whole = .false.
    end subroutine writer_start_buffered

    !> Add one entry, values(k) of dataset k, to the buffered datasets `set`.
    subroutine writer_push(w, set, values)
        class(h5_writer_t), intent(inout) :: w
        type(buffered_t), intent(inout) :: set
        real(dp), intent(in) :: values(:)

        set%n_buf = set%n_buf + 1
        set%buf(set%n_buf, :) = values
        if (set%n_buf == size(set%buf, 1)) call w%write_buffer(set)
    end subroutine writer_push

    !> Append the entries waiting in the buffer of `set` to its datasets.
    subroutine writer_write_buffer(w, set)
        class(h5_writer_t), intent(inout) :: w
        type(buffered_t), intent(inout) :: set
        integer :: k

        if (set%n_buf == 0) return
        do k = 1, size(set%ids)
            call w%append_rows(set%ids(k), trim(set%paths(k)), set%n, [int(set%n_buf, hsize_t)], &
                               set%buf(1:set%n_buf, k), whole=set%whole(k))
        end do
        set%n = set%n + set%n_buf
        set%n_buf = 0
    end subroutine writer_write_buffer

end module output_m
