!> The contact events of a run (/events, docs/output.md): a submodule of output_m, so that
!> it reaches the writer's open file.
submodule (output_m) output_events_s
    implicit none

contains

    !> /events/t (float64) and /events/kind (int32, +1 onset, -1 release), n_events long
    !> (possibly 0), written once at the end of the run.
    module subroutine writer_write_events(w, t, kind)
        class(h5_writer_t), intent(inout) :: w
        real(dp), intent(in) :: t(:)
        integer, intent(in) :: kind(:)
        integer(hid_t) :: group_id, space_id, dset_id, t_id
        integer(hsize_t) :: dims(1)
        integer :: hdferr

        if (.not. w%opened) call fatal(EXIT_OUTPUT, 'output', 'internal error: write_events() on a closed writer')
        call w%leave_swmr()   ! a new group: not in SWMR writing (output_file_s)
        call h5gcreate_f(w%file_id, 'events', group_id, hdferr)
        call w%check(hdferr, 'h5gcreate_f /events')
        dims = int(size(t), hsize_t)
        call h5screate_simple_f(1, dims, space_id, hdferr)
        call w%check(hdferr, 'h5screate_simple_f /events')
        call h5dcreate_f(group_id, 't', H5T_IEEE_F64LE, space_id, dset_id, hdferr)
        call w%check(hdferr, 'h5dcreate_f /events/t')
        if (size(t) > 0) then
            call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, t, dims, hdferr)
            call w%check(hdferr, 'h5dwrite_f /events/t')
        end if
        call w%describe(dset_id, '/events/t', described(SERIES(S_T)%long_name//' of a change of the '// &
                        'contact state (interpolated in the step that crosses it)', SERIES(S_T)%scale), &
                        SERIES(S_T)%units)
        call w%describe_si_of(dset_id, SERIES(S_T)%scale)
        call w%make_scale(dset_id, 't', '/events/t')   ! the coordinate of kind (docs/output.md, "netCDF")
        t_id = dset_id
        call h5dcreate_f(group_id, 'kind', H5T_STD_I32LE, space_id, dset_id, hdferr)
        call w%check(hdferr, 'h5dcreate_f /events/kind')
        if (size(kind) > 0) then
            call h5dwrite_f(dset_id, H5T_NATIVE_INTEGER, kind, dims, hdferr)
            call w%check(hdferr, 'h5dwrite_f /events/kind')
        end if
        call w%describe(dset_id, '/events/kind', 'contact event: +1 onset (the rod end reaches the obstacle), '// &
                        '-1 release', '1')
        call w%describe_si_of(dset_id, '')
        call w%attach_scale(dset_id, t_id, 0, '/events/kind')
        call h5dclose_f(dset_id, hdferr)
        call w%check(hdferr, 'h5dclose_f /events/kind')
        call h5dclose_f(t_id, hdferr)
        call w%check(hdferr, 'h5dclose_f /events/t')
        call h5sclose_f(space_id, hdferr)
        call w%check(hdferr, 'h5sclose_f /events')
        call h5gclose_f(group_id, hdferr)
        call w%check(hdferr, 'h5gclose_f /events')
    end subroutine writer_write_events

end submodule output_events_s
