!> Creating the writer's file (output_m's create): <prefix>.h5.part with /mesh/x and the
!> empty extendible /series and /snapshots datasets. A submodule of output_m, so that it
!> sets up the writer's private state.
submodule (output_m) output_create_s
    use hdf5, only: h5lcreate_hard_f
    implicit none

contains

    !> Open `<prefix>.h5.part` (creating the parent directory if needed), write /mesh/x and
    !> create the empty extendible /series and /snapshots datasets. x(0:s) are the nodes;
    !> compression (0 .. MAX_COMPRESSION, default 0) the deflate level of the /snapshots
    !> fields (with the shuffle filter before it; 0: no filters).
    module subroutine writer_create(w, prefix, x, compression)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: prefix
        real(dp), intent(in) :: x(0:)
        integer, intent(in), optional :: compression

        character(len=:), allocatable :: dir, message
        logical :: ok
        integer :: hdferr

        if (w%opened) call fatal(EXIT_OUTPUT, 'output', "internal error: create() on a writer that is &
                                 &already writing '"//w%part_path//"'")
        call h5_library_init()
        w%final_path = trim(prefix)//'.h5'
        w%part_path = trim(prefix)//'.h5.part'
        w%creating = .true.
        if (size(x) < 2) call w%fail('internal error: create() given fewer than 2 mesh nodes')
        w%n_nodes = size(x)
        w%compression = 0
        if (present(compression)) w%compression = compression
        if (w%compression < 0 .or. w%compression > MAX_COMPRESSION) &
            call w%fail('internal error: compression level outside 0 .. 9')
        w%n_series_written = 0
        w%n_snap = 0
        w%n_native_snap = 0
        w%n_native_values = 0
        w%n_si = 0
        w%n_buf = 0
        w%logical_names = ''
        w%checkpoint_note = ''
        w%swmr = .false.
        w%closing = .false.
        w%native_created = .false.
        w%n_checkpoints = 0
        w%n_slot_events = 0

        dir = parent_dir(prefix)
        if (len(dir) > 0) then
            if (.not. dir_exists(dir)) then
                call mkdir_p(dir, ok, message)
                if (.not. ok) call w%fail(message)
            end if
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

        call create_datasets(w, x)
        allocate (w%buf(SERIES_BUFFER_SIZE, N_SERIES), stat=hdferr)
        if (hdferr /= 0) call w%fail('cannot allocate the series buffer')
        call w%attr('status', 'incomplete')
        w%creating = .false.
    end subroutine writer_create

    !> /mesh/x with the nodes x(0:s), and the empty extendible /series and /snapshots datasets.
    subroutine create_datasets(w, x)
        class(h5_writer_t), intent(inout) :: w
        real(dp), intent(in) :: x(0:)
        integer(hid_t) :: group_id, space_id, dset_id
        integer(hsize_t) :: dims(1), dims2(2), chunk_rows
        integer :: hdferr, k

        ! /mesh/x
        call h5gcreate_f(w%file_id, 'mesh', group_id, hdferr)
        call w%check(hdferr, 'h5gcreate_f /mesh')
        dims = int(w%n_nodes, hsize_t)
        call h5screate_simple_f(1, dims, space_id, hdferr)
        call w%check(hdferr, 'h5screate_simple_f /mesh/x')
        call h5dcreate_f(group_id, 'x', H5T_IEEE_F64LE, space_id, dset_id, hdferr)
        call w%check(hdferr, 'h5dcreate_f /mesh/x')
        call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, x, dims, hdferr)
        call w%check(hdferr, 'h5dwrite_f /mesh/x')
        w%mesh_x_id = dset_id   ! closed by finish(), after describe_si
        call w%describe(dset_id, '/mesh/x', 'position x along the rod (nondimensional, scale: position)', '1')
        call h5sclose_f(space_id, hdferr)
        call w%check(hdferr, 'h5sclose_f /mesh/x')
        call h5gclose_f(group_id, hdferr)
        call w%check(hdferr, 'h5gclose_f /mesh')

        ! /series/*: 1D, chunks of SERIES_CHUNK entries, written SERIES_BUFFER_SIZE at a time
        call h5gcreate_f(w%file_id, 'series', group_id, hdferr)
        call w%check(hdferr, 'h5gcreate_f /series')
        dims = 0
        do k = 1, N_SERIES
            call w%create_extendible(group_id, '/series/', trim(SERIES(k)%name), &
                                     merge(H5T_STD_I32LE, H5T_IEEE_F64LE, SERIES(k)%is_integer), &
                                     dims, [int(SERIES_CHUNK, hsize_t)], w%series_ids(k))
            call w%describe(w%series_ids(k), '/series/'//trim(SERIES(k)%name), &
                            described(SERIES(k)%long_name, SERIES(k)%scale), SERIES(k)%units)
        end do
        call h5gclose_f(group_id, hdferr)
        call w%check(hdferr, 'h5gclose_f /series')

        ! /snapshots/*: t is 1D, the fields are (s+1, n_snap) growing by one row per snapshot
        call h5gcreate_f(w%file_id, 'snapshots', group_id, hdferr)
        call w%check(hdferr, 'h5gcreate_f /snapshots')
        chunk_rows = 1   ! one row per chunk: each append writes whole chunks (see h5pset_cache_f)
        call w%create_extendible(group_id, '/snapshots/', 't', H5T_IEEE_F64LE, dims, &
                                 [int(SERIES_CHUNK, hsize_t)], w%snap_t_id)
        call w%describe(w%snap_t_id, '/snapshots/t', described(SERIES(S_T)%long_name, SERIES(S_T)%scale), &
                        SERIES(S_T)%units)
        dims2 = [int(w%n_nodes, hsize_t), 0_hsize_t]
        do k = 1, N_SNAPSHOT_FIELDS
            associate (field => SNAPSHOTS(k))
                call w%create_extendible(group_id, '/snapshots/', trim(field%name), H5T_IEEE_F64LE, &
                                         dims2, [int(w%n_nodes, hsize_t), chunk_rows], w%snap_field_ids(k), &
                                         compress=.true.)
                call w%describe(w%snap_field_ids(k), '/snapshots/'//trim(field%name), &
                                described(field%long_name, field%scale), field%units)
            end associate
        end do
        call name_dimensions(w, group_id)
        call h5gclose_f(group_id, hdferr)
        call w%check(hdferr, 'h5gclose_f /snapshots')
    end subroutine create_datasets

    !> The dimension scales (netCDF-4 dimensions and coordinates, docs/output.md): /series/t
    !> of every /series dataset; /snapshots/t and x of every /snapshots field, where
    !> /snapshots/x is /mesh/x itself (a second link to it: netCDF and xarray look for a
    !> dimension's coordinate in the group of the variable or above). snap_group_id: /snapshots.
    subroutine name_dimensions(w, snap_group_id)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: snap_group_id
        integer :: hdferr, k

        call w%make_scale(w%mesh_x_id, 'x', '/mesh/x')
        call h5lcreate_hard_f(w%file_id, '/mesh/x', snap_group_id, 'x', hdferr)
        call w%check(hdferr, 'h5lcreate_hard_f /snapshots/x')
        call w%make_scale(w%series_ids(S_T), 't', '/series/t')
        do k = 1, N_SERIES
            if (k == S_T) cycle
            call w%attach_scale(w%series_ids(k), w%series_ids(S_T), 0, '/series/'//trim(SERIES(k)%name))
        end do
        call w%make_scale(w%snap_t_id, 't', '/snapshots/t')
        do k = 1, N_SNAPSHOT_FIELDS
            call w%attach_scale(w%snap_field_ids(k), w%snap_t_id, 0, '/snapshots/'//trim(SNAPSHOTS(k)%name))
            call w%attach_scale(w%snap_field_ids(k), w%mesh_x_id, 1, '/snapshots/'//trim(SNAPSHOTS(k)%name))
        end do
    end subroutine name_dimensions

    !> Create an empty dataset `name` in group_id whose last dimension is unlimited.
    !> dims gives the initial size (last entry 0), chunk the chunk shape.
    !> With compress (the snapshot fields only) and compression > 0: shuffle and deflate.
    !> Only datasets whose chunks are written once, whole, are compressed: rewriting a
    !> partly filled compressed chunk (the series and /snapshots/t at each flush) moves it,
    !> and HDF5 may reuse the space it leaves for later data, overwriting what the last
    !> flush (and its checkpoint) pointed to; a full disk or a kill would then lose it.
    module subroutine writer_create_extendible(w, group_id, group_path, name, file_type, dims, chunk, dset_id, compress)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: group_id
        character(len=*), intent(in) :: group_path
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: file_type
        integer(hsize_t), intent(in) :: dims(:)
        integer(hsize_t), intent(in) :: chunk(:)
        integer(hid_t), intent(out) :: dset_id
        logical, intent(in), optional :: compress

        logical :: filtered
        integer(hid_t) :: space_id, dcpl_id
        integer(hsize_t) :: maxdims(size(dims))
        integer :: hdferr, rank
        character(len=:), allocatable :: what

        what = group_path//name
        rank = size(dims)
        maxdims = dims
        maxdims(rank) = H5S_UNLIMITED_F
        call h5screate_simple_f(rank, dims, space_id, hdferr, maxdims)
        call w%check(hdferr, 'h5screate_simple_f '//what)
        call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl_id, hdferr)
        call w%check(hdferr, 'h5pcreate_f (dataset creation) '//what)
        call h5pset_chunk_f(dcpl_id, rank, chunk, hdferr)
        call w%check(hdferr, 'h5pset_chunk_f '//what)
        filtered = .false.
        if (present(compress)) filtered = compress .and. w%compression > 0
        if (filtered) then
            ! shuffle first: grouping the bytes of each float by significance lets deflate
            ! find the repeated exponent and sign bytes (docs/performance.md, "Output")
            call h5pset_shuffle_f(dcpl_id, hdferr)
            call w%check(hdferr, 'h5pset_shuffle_f '//what)
            call h5pset_deflate_f(dcpl_id, w%compression, hdferr)
            call w%check(hdferr, 'h5pset_deflate_f '//what)
        end if
        call h5dcreate_f(group_id, name, file_type, space_id, dset_id, hdferr, dcpl_id=dcpl_id)
        call w%check(hdferr, 'h5dcreate_f '//what)
        call h5pclose_f(dcpl_id, hdferr)
        call w%check(hdferr, 'h5pclose_f (dataset creation) '//what)
        call h5sclose_f(space_id, hdferr)
        call w%check(hdferr, 'h5sclose_f '//what)
    end subroutine writer_create_extendible


end submodule output_create_s
