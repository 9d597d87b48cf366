!> Creating the writer's file (output_m's create), /events at the end of the run, the groups
!> and datasets of the other parts (create_dataset), and their self-description
!> (docs/output.md, "Datasets" and "netCDF"): CF-style long_name and units, with &material the
!> factor to SI units, and the HDF5 dimension scales. And what a snapshot adds beyond the
!> output grid: on an adaptive mesh the snapshot on its own mesh (/snapshots/native; every
!> append opens, extends, writes and closes its datasets), and with &output error_estimate
!> the estimates (/snapshots/error_estimate*; error_companion_m computes them), created by the
!> first append, kept open until finish() and buffered as the series are. A submodule of
!> output_m, so that it sets up the writer's private state.
submodule (output_m) output_create_s
    use hdf5, only: h5lcreate_hard_f, H5P_DEFAULT_F, H5T_STD_I64LE, H5P_LINK_CREATE_F, &
                    h5pset_create_inter_group_f
    use h5ds, only: h5dsset_scale_f, h5dsattach_scale_f
    implicit none

    integer(hsize_t), parameter :: CHUNK(1) = [int(SERIES_CHUNK, hsize_t)]
    character(len=*), parameter :: GROUP = '/snapshots/native'
    integer(hsize_t), parameter :: VALUES_CHUNK(1) = [4096_hsize_t]   !< float64 entries (32 KiB)
    character(len=*), parameter :: WHAT(3) = [character(len=40) :: '(time and space)', &
                                              '(time part)', '(space part)']

contains

    !> Open `<prefix>.h5.part` (creating the parent directory if needed), write /mesh/x and
    !> create the empty extendible /series and /snapshots datasets. x(0:s) are the nodes;
    !> compression (0 .. 9, validated by the input, default 0) the deflate level of the /snapshots
    !> fields (with the shuffle filter before it; 0: no filters). in_place: the run resumes
    !> <prefix>.h5.part, which stays as it is until finish(); the file is <prefix>//RESUMED_SUFFIX.
    !> scales (&material): the SI scales, labelling every dataset measured in one (label()).
    module procedure writer_create
        character(len=:), allocatable :: dir, message
        logical :: ok
        integer :: hdferr

        if (w%opened) call fatal(EXIT_OUTPUT, 'output', "internal error: create() on a writer that is &
                                 &already writing '"//w%part_path//"'")
        call h5_library_init()
        call reset(w)
        w%final_path = trim(prefix)//'.h5'
        w%part_path = trim(prefix)//'.h5.part'
        w%replaces = ''
        if (present(in_place)) then
            if (in_place) w%replaces = w%part_path
            if (in_place) w%part_path = trim(prefix)//RESUMED_SUFFIX
        end if
        ! a new .part: a resumed run's file left beside the old one no longer continues it
        if (w%replaces == '') call remove_file(trim(prefix)//RESUMED_SUFFIX)
        w%creating = .true.
        w%n_nodes = size(x)
        if (present(scales)) w%si = scales
        if (present(compression)) w%compression = compression
        w%logical_names = ''
        w%checkpoint_note = ''

        dir = parent_dir(prefix)
        if (len(dir) > 0) then   ! (mkdir_p leaves the directories that exist as they are)
            call mkdir_p(dir, ok, message)
            if (.not. ok) call w%fail(message)
        end if
        ! finish() renames the .part file to <prefix>.h5, which fails on a directory: say so
        ! now, not after the whole run
        if (dir_exists(w%final_path)) call w%fail("'"//w%final_path//"' exists and is a directory")
        ! HDF5 says only that h5fcreate_f failed; creating the file first gets the system's
        ! reason ('Permission denied', 'Is a directory', ...) for the message
        call create_empty_file(w%part_path, ok, message)
        if (.not. ok) call w%fail(message)

        ! from here on abandon() has something to close
        w%opened = .true.
        call writer_open_file(w, create=.true.)
        call h5pcreate_f(H5P_LINK_CREATE_F, w%lcpl_id, hdferr)
        call w%check(hdferr, 'h5pcreate_f (link creation)')
        call h5pset_create_inter_group_f(w%lcpl_id, 1, hdferr)
        call w%check(hdferr, 'h5pset_create_inter_group_f')

        call create_layout(w, x)
        call w%attr('status', 'incomplete')
        w%creating = .false.
    end procedure writer_create

    !> Every component of the writer at its default (intent(out): default initialisation).
    subroutine reset(w)
        type(h5_writer_t), intent(out) :: w
    end subroutine reset

    !> /mesh/x with the nodes x(0:s), and the empty extendible /series and /snapshots datasets:
    !> the series 1D, chunks of SERIES_CHUNK entries written SERIES_BUFFER_SIZE at a time;
    !> /snapshots/t 1D, the fields (s+1, n_snap) growing by one row per snapshot, one row per
    !> chunk, so that each append writes whole chunks (see h5pset_cache_f). Their dimension
    !> scales: docs/output.md, "netCDF" (which says why /snapshots/x is a link to /mesh/x).
    subroutine create_layout(w, x)
        class(h5_writer_t), intent(inout) :: w
        real(dp), intent(in) :: x(0:)
        integer(hid_t) :: x_id
        integer :: hdferr, k

        call create_dataset(w, '/mesh/x', H5T_IEEE_F64LE, CHUNK, x_id, &
                            'position x along the rod (nondimensional, scale: position)', &
                            '1', si='position', scale='x', values=x)
        call w%start_buffered(w%series, N_SERIES, SERIES_BUFFER_SIZE)
        w%series%paths = '/series/'//SERIES%name
        w%series%whole = SERIES%is_integer
        associate (t => SERIES(S_T), ids => w%series%ids)
            call create_dataset(w, trim(w%series%paths(S_T)), H5T_IEEE_F64LE, CHUNK, &
                                ids(S_T), described(t%long_name, t%scale), t%units, si=t%scale, &
                                scale='t')
            call create_dataset(w, '/snapshots/t', H5T_IEEE_F64LE, CHUNK, &
                                w%snap_t_id, described(t%long_name, t%scale), &
                                t%units, si=t%scale, scale='t')
        end associate
        do k = 1, N_SERIES
            if (k == S_T) cycle
            associate (f => SERIES(k), ids => w%series%ids)
                call create_dataset(w, trim(w%series%paths(k)), &
                                    merge(H5T_STD_I32LE, H5T_IEEE_F64LE, f%is_integer), &
                                    CHUNK, ids(k), described(f%long_name, f%scale), &
                                    f%units, si=f%scale, coords=[ids(S_T)])
            end associate
        end do
        do k = 1, N_SNAPSHOT_FIELDS
            associate (f => SNAPSHOTS(k))
                call create_dataset(w, '/snapshots/'//trim(f%name), H5T_IEEE_F64LE, &
                                    [int(w%n_nodes, hsize_t), 1_hsize_t], w%snap_field_ids(k), &
                                    described(f%long_name, f%scale), f%units, si=f%scale, &
                                    coords=[w%snap_t_id, x_id], compress=.true.)
            end associate
        end do
        call h5lcreate_hard_f(w%file_id, '/mesh/x', w%file_id, '/snapshots/x', hdferr)
        call w%check(hdferr, 'h5lcreate_hard_f /snapshots/x')
        call w%close_dataset(x_id, '/mesh/x')
    end subroutine create_layout

    !> Create a dataset at `path` and label it (label()): with `values`, 1D, written once and
    !> whole (float64, or int32 from whole numbers); else empty, of chunks of shape `chunk`, its
    !> last dimension unlimited (and 0), the others those of the chunk. With compress and
    !> compression > 0: shuffle and deflate, for datasets whose chunks are written once, whole
    !> (the snapshot fields: docs/output.md, "Chunks and compression", says why only they).
    subroutine create_dataset(w, path, file_type, chunk, dset_id, long_name, units, si, scale, coords, &
                              compress, values)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: path, long_name, units
        integer(hid_t), intent(in) :: file_type
        integer(hsize_t), intent(in) :: chunk(:)
        integer(hid_t), intent(out) :: dset_id
        character(len=*), intent(in), optional :: si, scale
        integer(hid_t), intent(in), optional :: coords(:)
        logical, intent(in), optional :: compress
        real(dp), intent(in), optional :: values(:)
        logical :: filtered
        integer(hid_t) :: space_id, dcpl_id
        integer(hsize_t) :: dims(size(chunk)), maxdims(size(chunk)), n(1)
        integer :: hdferr

        dims = chunk
        dims(size(chunk)) = 0
        maxdims = chunk
        maxdims(size(chunk)) = H5S_UNLIMITED_F
        dcpl_id = H5P_DEFAULT_F
        if (present(values)) then
            n = int(size(values), hsize_t)
            call h5screate_simple_f(1, n, space_id, hdferr)
        else
            call h5screate_simple_f(size(chunk), dims, space_id, hdferr, maxdims)
        end if
        call w%check(hdferr, 'h5screate_simple_f '//path)
        if (.not. present(values)) then
            call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl_id, hdferr)
            call w%check(hdferr, 'h5pcreate_f (dataset creation) '//path)
            call h5pset_chunk_f(dcpl_id, size(chunk), chunk, hdferr)
            call w%check(hdferr, 'h5pset_chunk_f '//path)
        end if
        filtered = .false.
        if (present(compress)) filtered = compress .and. w%compression > 0
        if (filtered) then
            ! shuffle first: grouping the bytes of each float by significance lets deflate
            ! find the repeated exponent and sign bytes (docs/performance.md, "Output")
            call h5pset_shuffle_f(dcpl_id, hdferr)
            call w%check(hdferr, 'h5pset_shuffle_f '//path)
            call h5pset_deflate_f(dcpl_id, w%compression, hdferr)
            call w%check(hdferr, 'h5pset_deflate_f '//path)
        end if
        call h5dcreate_f(w%file_id, path, file_type, space_id, dset_id, hdferr, dcpl_id, w%lcpl_id)
        call w%check(hdferr, 'h5dcreate_f '//path)
        if (present(values)) then
            if (file_type == H5T_STD_I32LE .and. n(1) > 0) then   ! no conversion buffer (append_rows)
                call h5dwrite_f(dset_id, H5T_NATIVE_INTEGER, nint(values), n, hdferr)
            else if (n(1) > 0) then
                call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, values, n, hdferr)
            end if
            call w%check(hdferr, 'h5dwrite_f '//path)
        else
            call h5pclose_f(dcpl_id, hdferr)
            call w%check(hdferr, 'h5pclose_f (dataset creation) '//path)
        end if
        call close_spaces(w, path, space_id)
        call label(w, dset_id, path, long_name, units, si, scale, coords)
    end subroutine create_dataset

    !> Grow extendible dataset dset_id (`what`) along its last dimension from `offset` to
    !> offset + block(rank), and write values, block's elements in Fortran order, there; with
    !> whole, as integers (whole numbers in values): an int32 dataset written from doubles
    !> would make HDF5 allocate a conversion buffer at every write.
    !> Arguments (w, dset_id, what, offset, block, values, whole): output_m's interface.
    module procedure writer_append_rows
        integer(hsize_t) :: new_dims(size(block)), start(size(block)), n
        integer(hid_t) :: file_space, mem_space
        integer :: hdferr, rank
        logical :: integers

        call w%hold(dset_id, what)
        rank = size(block)
        new_dims = block
        new_dims(rank) = offset + block(rank)
        start = 0
        start(rank) = offset
        call h5dset_extent_f(dset_id, new_dims, hdferr)
        call w%check(hdferr, 'h5dset_extent_f '//what)
        call h5dget_space_f(dset_id, file_space, hdferr)
        call w%check(hdferr, 'h5dget_space_f '//what)
        call h5sselect_hyperslab_f(file_space, H5S_SELECT_SET_F, start, block, hdferr)
        call w%check(hdferr, 'h5sselect_hyperslab_f '//what)
        call h5screate_simple_f(rank, block, mem_space, hdferr)
        call w%check(hdferr, 'h5screate_simple_f (memory) '//what)
        n = product(block)
        integers = .false.
        if (present(whole)) integers = whole
        if (integers) then
            call h5dwrite_f(dset_id, H5T_NATIVE_INTEGER, nint(values(1:n)), block, hdferr, &
                            mem_space_id=mem_space, file_space_id=file_space)
        else
            call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, values(1:n), block, hdferr, &
                            mem_space_id=mem_space, file_space_id=file_space)
        end if
        call w%check(hdferr, 'h5dwrite_f '//what)
        call close_spaces(w, what, file_space, mem_space)
    end procedure writer_append_rows

    !> Close the dataspace space_id of `what` (for the message), and mem_space, a memory
    !> dataspace for it.
    subroutine close_spaces(w, what, space_id, mem_space)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: what
        integer(hid_t), intent(in) :: space_id
        integer(hid_t), intent(in), optional :: mem_space
        integer :: hdferr

        call h5sclose_f(space_id, hdferr)
        call w%check(hdferr, 'h5sclose_f '//what)
        if (.not. present(mem_space)) return
        call h5sclose_f(mem_space, hdferr)
        call w%check(hdferr, 'h5sclose_f (memory) '//what)
    end subroutine close_spaces

    !> /events/t (float64) and /events/kind (int32, +1 onset, -1 release), n_events long
    !> (possibly 0), written once at the end of the run; t is the coordinate of kind
    !> (docs/output.md, "netCDF").
    module procedure writer_write_events
        integer(hid_t) :: t_id, kind_id

        call w%need_open('write_events()')
        call w%leave_swmr()   ! a new group: not in SWMR writing (output_file_s)
        associate (time => SERIES(S_T))
            call create_dataset(w, '/events/t', H5T_IEEE_F64LE, CHUNK, t_id, &
                                described(trim(time%long_name)//' of a change of the contact '// &
                                          'state (interpolated in the step that crosses it)', &
                                          time%scale), time%units, si=time%scale, scale='t', values=t)
        end associate
        call create_dataset(w, '/events/kind', H5T_STD_I32LE, CHUNK, kind_id, &
                            'contact event: +1 onset (the rod end reaches the obstacle), -1 release', &
                            '1', si='', coords=[t_id], values=real(kind, dp))
        call w%close_dataset(kind_id, '/events/kind')
        call w%close_dataset(t_id, '/events/t')
    end procedure writer_write_events

    !> A dataset's long_name: the table's, and for a nondimensional quantity the scale of
    !> (2.10) it is measured in (root attribute scale.<scale> with &material).
    pure function described(long_name, scale) result(text)
        character(len=*), intent(in) :: long_name, scale
        character(len=:), allocatable :: text

        text = trim(long_name)
        if (scale /= '') text = text//' (nondimensional, scale: '//trim(scale)//')'
    end function described

    !> The CF-style attributes of dataset dset_id (`path`): long_name and units ('1':
    !> nondimensional), and when its quantity has fields_m's scale `si`, one of create()'s
    !> SI scales (&material), si_factor and si_units: its value in SI units is si_factor
    !> times the stored value. With `scale`, it is the dimension scale (netCDF-4: the coordinate
    !> variable) of the dimension of that name; coords(j), if given, is the dimension scale
    !> of its dimension j, counted as h5py counts them (1: the slowest-varying; the Fortran
    !> API counts them so, C and h5py from 0).
    subroutine label(w, dset_id, path, long_name, units, si, scale, coords)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: dset_id
        character(len=*), intent(in) :: path, long_name, units
        character(len=*), intent(in), optional :: si, scale
        integer(hid_t), intent(in), optional :: coords(:)
        integer :: hdferr, k

        call w%attr('long_name', trim(long_name), on=dset_id)
        call w%attr('units', trim(units), on=dset_id)
        if (present(si) .and. allocated(w%si)) then
            do k = 1, size(w%si)
                if (w%si(k)%name /= si) cycle
                call w%attr('si_factor', w%si(k)%factor, on=dset_id)
                call w%attr('si_units', trim(w%si(k)%units), on=dset_id)
            end do
        end if
        if (present(scale)) then
            call h5dsset_scale_f(dset_id, hdferr, scale)
            call w%check(hdferr, 'h5dsset_scale_f '//path)
        end if
        if (.not. present(coords)) return
        do k = 1, size(coords)
            call h5dsattach_scale_f(dset_id, coords(k), k, hdferr)
            call w%check(hdferr, 'h5dsattach_scale_f '//path)
        end do
    end subroutine label

    !> Append one snapshot on its own mesh: nodes x(0:s), values(0:s, k) of the field
    !> fields_m's SNAPSHOTS(k).
    module procedure writer_append_native
        integer(hsize_t) :: n, at
        integer :: k

        call w%need_open('append_native()')
        if (size(values, 1) /= size(x) .or. size(values, 2) /= N_SNAPSHOT_FIELDS) &
            call w%fail('internal error: append_native() given fields that do not match the nodes')
        if (.not. w%native_created) call writer_create_native(w)
        n = int(size(x), hsize_t)
        at = int(w%n_native_values, hsize_t)
        call append(w, 'x', at, x)
        do k = 1, N_SNAPSHOT_FIELDS
            call append(w, trim(SNAPSHOTS(k)%name), at, values(:, k))
        end do
        ! int64, written from a double (exact below 2^53)
        call append(w, 'offset', w%n_native_snap, [real(w%n_native_values, dp)])
        call append(w, 'count', w%n_native_snap, [real(n, dp)])
        w%n_native_values = w%n_native_values + int(n, int64)
        w%n_native_snap = w%n_native_snap + 1
    end procedure writer_append_native

    !> The group and its empty datasets with their dimension scales (docs/output.md, "netCDF").
    !> Created by the first append, or by the first checkpoint of an adaptive mesh
    !> (write_checkpoint), so that SWMR writing need not end for it later (output_file_s).
    module procedure writer_create_native
        integer(hid_t) :: dset_id, x_id
        integer :: k

        call w%leave_swmr()
        call w%hold(w%snap_t_id, '/snapshots/t')   ! (create_index's coordinate)
        w%native_created = .true.
        call create_dataset(w, GROUP//'/x', H5T_IEEE_F64LE, VALUES_CHUNK, x_id, &
                            'nodes of the mesh of each snapshot, concatenated (see offset, count)', &
                            '1', si='position', scale='x')
        do k = 1, N_SNAPSHOT_FIELDS
            associate (f => SNAPSHOTS(k), path => GROUP//'/'//trim(SNAPSHOTS(k)%name))
                call create_dataset(w, path, H5T_IEEE_F64LE, VALUES_CHUNK, dset_id, &
                                    described(trim(f%long_name)//' at the nodes of its own '// &
                                              'mesh (native/x)', f%scale), &
                                    f%units, si=f%scale, coords=[x_id])
                call w%close_dataset(dset_id, path)
            end associate
        end do
        call w%close_dataset(x_id, GROUP//'/x')
        call create_index(w, 'offset', 'first entry of each snapshot in native/x and the fields')
        call create_index(w, 'count', 'number of nodes of each snapshot''s mesh')
    end procedure writer_create_native

    !> GROUP/name, int64, one entry per snapshot: its coordinate is /snapshots/t.
    subroutine create_index(w, name, long_name)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name, long_name
        integer(hid_t) :: dset_id

        call create_dataset(w, GROUP//'/'//name, H5T_STD_I64LE, CHUNK, dset_id, &
                            long_name, '1', si='', coords=[w%snap_t_id])
        call w%close_dataset(dset_id, GROUP//'/'//name)
    end subroutine create_index

    !> Append values to GROUP/name from entry `at` (every append opens and closes it).
    subroutine append(w, name, at, values)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        integer(hsize_t), intent(in) :: at
        real(dp), intent(in) :: values(:)
        integer(hid_t) :: dset_id

        dset_id = -1   ! (append_rows opens it)
        call w%append_rows(dset_id, GROUP//'/'//name, at, [int(size(values), hsize_t)], values)
        call w%close_dataset(dset_id, GROUP//'/'//name)
    end subroutine append

    !> Append one snapshot's estimates: values(k, part) of field OUTPUT_ORDER(k), part 1 the
    !> total, 2 the time part, 3 the space part. Buffered for SERIES_CHUNK snapshots and
    !> written when the buffer is full and at every flush() (18 small writes per snapshot
    !> would cost more than the estimate).
    module procedure writer_append_estimate

        call w%need_open('append_estimate()')
        if (.not. allocated(w%estimates%ids)) call open_estimate(w)
        call w%push(w%estimates, reshape(values, [size(values)]))
    end procedure writer_append_estimate

    !> The groups and their datasets: created by the first append of the file (a restart's
    !> copy of the history included), kept open.
    subroutine open_estimate(w)
        class(h5_writer_t), intent(inout) :: w
        character(len=64) :: paths(N_OUTPUT_FIELDS, size(ESTIMATE_PARTS))
        integer :: k, part

        call w%leave_swmr()   ! new groups: not in SWMR writing (output_file_s)
        do part = 1, size(ESTIMATE_PARTS)
            do k = 1, N_OUTPUT_FIELDS
                paths(k, part) = estimate_path(part, k)
            end do
        end do
        call w%start_buffered(w%estimates, size(paths), SERIES_CHUNK)
        w%estimates%paths = [paths]
        do part = 1, size(ESTIMATE_PARTS)
            do k = 1, N_OUTPUT_FIELDS
                call create_dataset(w, trim(paths(k, part)), H5T_IEEE_F64LE, CHUNK, &
                                    w%estimates%ids(k + N_OUTPUT_FIELDS * (part - 1)), &
                                    'estimated relative L2 error of '// &
                                    trim(FIELDS(OUTPUT_ORDER(k))%long_name)// &
                                    ' at each snapshot '//trim(WHAT(part)), '1')
            end do
        end do
    end subroutine open_estimate

end submodule output_create_s
