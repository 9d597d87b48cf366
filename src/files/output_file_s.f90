!> The writer's file itself (output_m): opening it with HDF5's 1.10 format, its
!> single-writer/multiple-reader (SWMR) write mode, room for its flushes (reserve), failing
!> (fail) and closing it (finish, abandon). Crash safety: docs/output.md, "A killed run".
!> SWMR mode forbids new objects, attributes and deletions (HDF5 1.10 then corrupts its
!> metadata cache), so whatever needs one ends it first (leave_swmr: the file is closed,
!> clean, and reopened), and the next flush() starts it again.
submodule (output_m) output_file_s
    use hdf5, only: h5fopen_f, H5F_ACC_RDWR_F, h5pset_libver_bounds_f, H5F_LIBVER_V110_F, &
                    h5lexists_f, h5ldelete_f
    use h5ds, only: h5dsdetach_scale_f
    use h5_swmr_m, only: start_swmr_write
    implicit none

contains

    !> Create (create = .true.: truncating) or reopen the .part file for writing, in HDF5's
    !> 1.10 format (which SWMR needs), with strong close degree and no chunk cache.
    module procedure writer_open_file
        integer(hid_t) :: fapl_id
        integer :: hdferr

        ! strong close: h5fclose_f also closes any object still open, so abandon() after a
        ! failure half-way through cannot leave the file held open
        call h5pcreate_f(H5P_FILE_ACCESS_F, fapl_id, hdferr)
        call w%check(hdferr, 'h5pcreate_f (file access)')
        call h5pset_fclose_degree_f(fapl_id, H5F_CLOSE_STRONG_F, hdferr)
        call w%check(hdferr, 'h5pset_fclose_degree_f')
        ! no chunk cache: every chunk is written, and its space allocated, by the h5dwrite_f
        ! that fills it, so that a full disk fails there, between flushes, and a flush writes
        ! metadata only, into space reserved for it first (appends write whole chunks)
        call h5pset_cache_f(fapl_id, 0, 0_size_t, 0_size_t, 0.75, hdferr)
        call w%check(hdferr, 'h5pset_cache_f')
        ! the 1.10 format (superblock 3; the chunk index of an extendible dataset is an
        ! extensible array, HDF5's default B-tree parameters no longer apply): SWMR writing needs it
        call h5pset_libver_bounds_f(fapl_id, H5F_LIBVER_V110_F, H5F_LIBVER_V110_F, hdferr)
        call w%check(hdferr, 'h5pset_libver_bounds_f')
        if (create) then
            call h5fcreate_f(w%part_path, H5F_ACC_TRUNC_F, w%file_id, hdferr, access_prp=fapl_id)
            call w%check(hdferr, 'h5fcreate_f')
        else
            call h5fopen_f(w%part_path, H5F_ACC_RDWR_F, w%file_id, hdferr, access_prp=fapl_id)
            call w%check(hdferr, 'h5fopen_f (reopening after SWMR writing)')
        end if
        call h5pclose_f(fapl_id, hdferr)
        call w%check(hdferr, 'h5pclose_f (file access)')
    end procedure writer_open_file

    !> Write the buffered series entries and flush HDF5's caches to disk, so that a later
    !> crash leaves everything appended so far readable in the .part file; then (re)start
    !> SWMR writing (until the next structural change, flushes are then crash-safe), except
    !> while finish() closes the file.
    module procedure writer_flush
        integer :: hdferr

        call w%need_open('flush()')
        call w%write_buffer(w%series)
        call w%write_buffer(w%estimates)
        call reserve(w)
        call h5fflush_f(w%file_id, H5F_SCOPE_GLOBAL_F, hdferr)
        call w%check(hdferr, 'h5fflush_f')
        if (w%swmr .or. w%closing) return
        call w%check(start_swmr_write(w%file_id), 'H5Fstart_swmr_write')
        w%swmr = .true.
    end procedure writer_flush

    !> Leave SWMR writing before a structural change (a new object or attribute, a deletion):
    !> close the file, which a SWMR close leaves clean and complete, and reopen it. Nothing to
    !> do outside SWMR mode.
    module procedure writer_leave_swmr
        integer :: hdferr

        if (.not. w%swmr) return
        call w%write_buffer(w%series)
        call w%write_buffer(w%estimates)
        call reserve(w)
        ! the strong close degree (writer_open_file) closes every dataset too: each is opened
        ! again where it is next written (hold)
        call h5fclose_f(w%file_id, hdferr)
        call w%check(hdferr, 'h5fclose_f (leaving SWMR writing)')
        w%swmr = .false.
        if (allocated(w%ckpt_ids)) w%ckpt_ids = -1
        w%ckpt_current_id = -1
        w%snap_t_id = -1
        w%snap_field_ids = -1
        w%series%ids = -1
        if (allocated(w%estimates%ids)) w%estimates%ids = -1
        call writer_open_file(w, create=.false.)
    end procedure writer_leave_swmr

    !> Write the buffered series, root attribute `status` ('complete', or 'failed: <reason>'
    !> after a numerical failure), close the file and rename `<prefix>.h5.part` to
    !> `<prefix>.h5`, replacing an older file of that name. A run resumed in place renames
    !> its file instead, each rename atomic, so that a valid file is always there: to
    !> `<prefix>.h5`, then deletes the `<prefix>.h5.part` it continued; with keep_part over
    !> that .part (its checkpoint is later).
    module procedure writer_finish
        integer :: hdferr
        logical :: ok
        character(len=:), allocatable :: message, target

        call w%need_open('finish()')
        call w%leave_swmr()
        w%closing = .true.
        call tidy(w)
        call w%attr('status', status)
        call w%attr('logical_attributes', w%logical_names)
        call w%flush()   ! with its space reserved; closing then writes nothing new
        ! the strong close degree (writer_open_file) also closes every dataset the writer
        ! holds; the next create() starts from a reset writer
        call h5fclose_f(w%file_id, hdferr)
        call w%check(hdferr, 'h5fclose_f')
        call h5pclose_f(w%lcpl_id, hdferr)
        call w%check(hdferr, 'h5pclose_f (link creation)')
        w%lcpl_id = -1
        w%file_id = -1
        w%opened = .false.
        w%swmr = .false.

        target = w%final_path
        if (present(keep_part)) then
            if (keep_part .and. w%replaces == '') return
            if (keep_part) target = w%replaces
        end if
        call rename_file(w%part_path, target, ok, message)
        ! the .part file is complete and valid here: keep it rather than lose the run
        if (.not. ok) call fatal(EXIT_OUTPUT, 'output', message//" (the complete results are in '" &
                                 //w%part_path//"')")
        if (w%replaces /= '' .and. target == w%final_path) call remove_file(w%replaces)
    end procedure writer_finish

    !> Close whatever is open, ignoring errors, and delete the .part file. For output
    !> failures, where no valid file can be promised. A writer that is not open is left alone.
    module procedure writer_abandon
        integer :: hdferr

        if (.not. w%opened) return
        w%opened = .false.
        w%swmr = .false.
        ! the file was opened with H5F_CLOSE_STRONG, so this also closes every dataset
        if (w%file_id >= 0) call h5fclose_f(w%file_id, hdferr)
        if (w%lcpl_id >= 0) call h5pclose_f(w%lcpl_id, hdferr)
        w%lcpl_id = -1
        w%file_id = -1
        call remove_file(w%part_path)
    end procedure writer_abandon

    !> Reserve disk space up to the end of the space HDF5 has allocated in the file, before a
    !> flush writes the metadata that lies there. A flush that fails half-way (disk full, file
    !> size limit) would write the superblock with the new end of the file but not all that
    !> lies before it: a file that no longer opens ('truncated file'). Failing here instead
    !> leaves the file as the previous flush wrote it, with its checkpoint.
    subroutine reserve(w)
        class(h5_writer_t), intent(inout) :: w
        integer(hsize_t) :: bytes
        integer :: hdferr
        logical :: ok
        character(len=:), allocatable :: message

        call h5fget_filesize_f(w%file_id, bytes, hdferr)
        call w%check(hdferr, 'h5fget_filesize_f')
        call reserve_file_size(w%part_path, int(bytes, int64), ok, message)
        if (.not. ok) &
            call w%fail('no room to flush its '//int_str(int(bytes / 1024))//' KiB ('//message//')')
    end subroutine reserve

    !> Abandon the file and stop with a message naming the file and the reason. During
    !> create() the fault is the &output prefix; later it is a write failure.
    module procedure writer_fail
        character(len=:), allocatable :: path, system, keep

        system = write_failure_reason()   ! first: errno of the failed write, before any other call
        if (allocated(w%part_path)) then
            path = w%part_path
        else
            path = '(no file)'
        end if
        if (w%creating) then
            ! abandon() only acts on an open writer; the empty .part may exist already
            call w%abandon()
            call remove_file(path)
            call fatal(EXIT_OUTPUT, 'output.prefix', "cannot create '"//path//"': "//reason// &
                       '; &output prefix must name a file in a directory that exists or can be created, '// &
                       'and that this user may write to')
        else
            ! A failed write (disk full, file size limit, I/O error): the file on disk is as
            ! the last flush left it (every checkpoint flushes), plus raw data past its end.
            ! Closing it, or HDF5's own shutdown at exit, would flush the caches half-way
            ! and could leave a file that no longer opens; so it is left as it is, like the
            ! .part of a killed run, and the process ends at once (fatal_now).
            if (system /= '') system = ' ('//system//')'
            if (w%checkpoint_note /= '') then
                keep = '; the file is left as its last flush wrote it, with the checkpoint of '// &
                       w%checkpoint_note//': free space, then continue it with the same command and --resume'
            else if (w%replaces /= '') then
                keep = "; '"//w%replaces//"' still holds the checkpoint this run resumed from: free space, "// &
                       'then continue it with the same command and --resume'
            else
                keep = "; the file is left as its last flush wrote it; it holds no checkpoint (&output "// &
                       'checkpoint_every > 0 makes a long run restartable after such a failure)'
            end if
            call fatal_now(EXIT_OUTPUT, 'output', "cannot write '"//path//"': "//reason//system//keep)
        end if
    end procedure writer_fail

    !> Remove what SWMR writing made the run create in advance and it never used, so that
    !> the finished file holds what it held before SWMR: the second checkpoint slot of a run
    !> with one checkpoint, /snapshots/native of an adaptive mesh that never left the output
    !> grid (with its offset and count detached from /snapshots/t).
    subroutine tidy(w)
        class(h5_writer_t), intent(inout) :: w

        if (w%n_checkpoints == 1) call drop(w, '/checkpoint/slot1')
        if (w%native_created .and. w%n_native_snap == 0) then
            call detach_native(w)
            call drop(w, '/snapshots/native')
        end if
    end subroutine tidy

    !> Detach /snapshots/native/offset and count from their dimension scale /snapshots/t
    !> (before deleting them).
    subroutine detach_native(w)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), parameter :: NAMES(2) = [character(len=24) :: &
            '/snapshots/native/offset', '/snapshots/native/count']
        integer(hid_t) :: dset_id
        integer :: hdferr, k

        call w%hold(w%snap_t_id, '/snapshots/t')
        do k = 1, size(NAMES)
            associate (name => trim(NAMES(k)))
                dset_id = -1
                call w%hold(dset_id, name)
                call h5dsdetach_scale_f(dset_id, w%snap_t_id, 1, hdferr)
                call w%check(hdferr, 'h5dsdetach_scale_f '//name)
                call w%close_dataset(dset_id, name)
            end associate
        end do
    end subroutine detach_native

    !> Remove the object `name` if it exists (finish(): what SWMR writing made the run create
    !> in advance and it never used).
    subroutine drop(w, name)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: name
        logical :: exists
        integer :: hdferr

        call h5lexists_f(w%file_id, name, exists, hdferr)
        call w%check(hdferr, 'h5lexists_f '//name)
        if (.not. exists) return
        call h5ldelete_f(w%file_id, name, hdferr)
        call w%check(hdferr, 'h5ldelete_f '//name)
    end subroutine drop

end submodule output_file_s
