!> Where a file came from (docs/output.md, "Root attributes"): when, on which host, by which
!> command, from which source, with which HDF5 library and compiler, as root attributes
!> (record_provenance); the time and host name come from src/files/provenance_c.c.
module provenance_m
    use iso_c_binding, only: c_char, c_int
    use iso_fortran_env, only: compiler_version
    use hdf5, only: h5get_libversion_f
    use strings_m, only: int_str, from_c_chars
    use output_m, only: h5_writer_t
    implicit none
    private
    public :: record_provenance

    abstract interface
        !> A helper of provenance_c.c: writes a NUL-terminated string of at most n characters
        !> into buf, returns 0 (non-zero: it failed).
        function c_helper(buf, n) bind(C) result(rc)
            import :: c_char, c_int
            character(kind=c_char), intent(out) :: buf(*)
            integer(c_int), value :: n
            integer(c_int) :: rc
        end function c_helper
    end interface

    procedure(c_helper), bind(C, name='rc_utc_now') :: c_utc_now
    procedure(c_helper), bind(C, name='rc_hostname') :: c_hostname

contains

    !> The root attributes version (program_version) and the provenance: created (the UTC
    !> time, ISO 8601: '2026-11-23T07:30:00Z'), source_version, host (gethostname(2)),
    !> command_line, hdf5_version, compiler_version; 'unknown' for any it cannot get.
    subroutine record_provenance(writer, program_version, source_version)
        type(h5_writer_t), intent(inout) :: writer
        character(len=*), intent(in) :: program_version, source_version

        call writer%attr('version', program_version)
        call writer%attr('created', c_text(c_utc_now))
        call writer%attr('source_version', source_version)
        call writer%attr('host', c_text(c_hostname))
        call writer%attr('command_line', command_line())
        call writer%attr('hdf5_version', hdf5_version())
        call writer%attr('compiler_version', compiler_version())
    end subroutine record_provenance

    !> What the C helper `helper` writes, or 'unknown' when it fails.
    function c_text(helper) result(text)
        procedure(c_helper) :: helper
        character(len=:), allocatable :: text
        character(kind=c_char) :: buf(256)

        text = 'unknown'
        if (helper(buf, size(buf, kind=c_int)) == 0) text = from_c_chars(buf)
    end function c_text

    !> The command that started this run, as the shell passed it (arguments joined by ' ').
    function command_line() result(text)
        character(len=:), allocatable :: text
        integer :: length, stat

        text = 'unknown'
        call get_command(length=length, status=stat)
        if (stat > 0 .or. length == 0) return
        text = repeat(' ', length)
        call get_command(text)
    end function command_line

    !> 'major.minor.release' of the HDF5 library this program runs with.
    function hdf5_version() result(text)
        character(len=:), allocatable :: text
        integer :: major, minor, release, hdferr

        call h5get_libversion_f(major, minor, release, hdferr)
        text = 'unknown'
        if (hdferr >= 0) text = int_str(major)//'.'//int_str(minor)//'.'//int_str(release)
    end function hdf5_version

end module provenance_m
