!> Self-description of output_m's datasets: long_name and units (CF style; '1' is
!> nondimensional, and long_name names the scale of (2.10)), with &material the factor
!> to SI units, and the HDF5 dimension scales (H5DS) that name each dataset's dimensions and
!> coordinates as netCDF-4 does (docs/output.md, "netCDF"). A submodule, so that it reaches
!> the writer's open datasets.
submodule (output_m) output_describe_s
    use h5ds, only: h5dsset_scale_f, h5dsattach_scale_f
    implicit none

contains

    !> A dataset's long_name: the table's, and for a nondimensional quantity the scale of
    !> (2.10) it is measured in (root attribute scale.<scale> with &material).
    pure module function described(long_name, scale) result(text)
        character(len=*), intent(in) :: long_name, scale
        character(len=:), allocatable :: text

        text = trim(long_name)
        if (scale /= '') text = text//' (nondimensional, scale: '//trim(scale)//')'
    end function described

    !> The CF-style attributes of a dataset: long_name and units ('1': nondimensional).
    module subroutine writer_describe(w, dset_id, what, long_name, units)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: dset_id
        character(len=*), intent(in) :: what, long_name, units

        if (dset_id < 0) call w%fail('internal error: no dataset '//what)
        call w%attr('long_name', trim(long_name), on=dset_id)
        call w%attr('units', trim(units), on=dset_id)
    end subroutine writer_describe

    !> Attributes si_factor and si_units on every dataset whose quantity has fields_m's
    !> scale `scale`: its value in SI units is si_factor times the stored value.
    module subroutine writer_describe_si(w, scale, factor, si_units)
        class(h5_writer_t), intent(inout) :: w
        character(len=*), intent(in) :: scale, si_units
        real(dp), intent(in) :: factor
        integer :: k

        if (w%n_si == size(w%si_names)) call w%fail('internal error: more SI scales than MAX_SI_SCALES')
        w%n_si = w%n_si + 1
        w%si_names(w%n_si) = scale
        w%si_factors(w%n_si) = factor
        w%si_units(w%n_si) = si_units
        do k = 1, N_SERIES
            if (SERIES(k)%scale /= scale) cycle
            call w%attr('si_factor', factor, on=w%series_ids(k))
            call w%attr('si_units', si_units, on=w%series_ids(k))
        end do
        if (SERIES(S_T)%scale == scale) then
            call w%attr('si_factor', factor, on=w%snap_t_id)
            call w%attr('si_units', si_units, on=w%snap_t_id)
        end if
        do k = 1, N_SNAPSHOT_FIELDS
            if (SNAPSHOTS(k)%scale /= scale) cycle
            call w%attr('si_factor', factor, on=w%snap_field_ids(k))
            call w%attr('si_units', si_units, on=w%snap_field_ids(k))
        end do
        if (scale == 'position') then
            call w%attr('si_factor', factor, on=w%mesh_x_id)
            call w%attr('si_units', si_units, on=w%mesh_x_id)
        end if
    end subroutine writer_describe_si

    !> Make dataset dset_id (1D) a dimension scale: the coordinate of the dimension `name`
    !> (netCDF-4: a coordinate variable, named as the dataset).
    module subroutine writer_make_scale(w, dset_id, name, what)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: dset_id
        character(len=*), intent(in) :: name, what
        integer :: hdferr

        call h5dsset_scale_f(dset_id, hdferr, name)
        call w%check(hdferr, 'h5dsset_scale_f '//what)
    end subroutine writer_make_scale

    !> Attach dimension scale scale_id to dimension `dim` of dataset dset_id, counted as h5py
    !> and C count them (0: the first, the slowest-varying; Fortran sees it last). The
    !> Fortran API takes that index plus 1 (measured with h5py: 0 fails, 1 is C's 0).
    module subroutine writer_attach_scale(w, dset_id, scale_id, dim, what)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: dset_id, scale_id
        integer, intent(in) :: dim
        character(len=*), intent(in) :: what
        integer :: hdferr

        call h5dsattach_scale_f(dset_id, scale_id, dim + 1, hdferr)
        call w%check(hdferr, 'h5dsattach_scale_f '//what)
    end subroutine writer_attach_scale

    !> si_factor and si_units on a dataset created after describe_si (/snapshots/native,
    !> /events) whose quantity has scale `scale`; nothing without &material.
    module subroutine writer_describe_si_of(w, dset_id, scale)
        class(h5_writer_t), intent(inout) :: w
        integer(hid_t), intent(in) :: dset_id
        character(len=*), intent(in) :: scale
        integer :: k

        do k = 1, w%n_si
            if (w%si_names(k) /= scale) cycle
            call w%attr('si_factor', w%si_factors(k), on=dset_id)
            call w%attr('si_units', trim(w%si_units(k)), on=dset_id)
        end do
    end subroutine writer_describe_si_of

end submodule output_describe_s
