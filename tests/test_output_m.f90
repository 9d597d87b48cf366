!> Tests of output_m (HDF5 writer), h5_read_m (reader) and fsys_m: write files through
!> h5_writer_t, read them back and compare exactly (float64 round-trips bit for bit).
!> argv(1) = source dir (unused), argv(2) = scratch dir this test may write into.
program test_output_m
    use iso_fortran_env, only: error_unit, int64
    use kinds_m, only: dp
    use output_m, only: h5_writer_t, SERIES_BUFFER_SIZE
    use h5_arrays_m, only: read_int_1d, read_real_2d, read_attr_int
    use h5_read_m, only: read_real_1d, read_attr_str, read_attr_real, &
                         read_attr_real_1d, dataset_exists, attr_exists
    use fsys_m, only: file_exists, dir_exists, remove_file, parent_dir, mkdir_p
    use scratch_dirs_m, only: remove_dir
    use fields_m, only: N_TABLE_SERIES => N_SERIES, N_SNAPSHOT_FIELDS
    implicit none

    integer, parameter :: S = 4             !< elements: s+1 = 5 nodes
    integer, parameter :: N_SERIES = 10000  !< crosses the series buffer boundary twice
    integer, parameter :: N_SNAP = 3
    integer, parameter :: FLUSH_AT = 5000   !< an explicit flush() between buffer boundaries

    character(len=:), allocatable :: scratch
    integer :: n_failed = 0

    scratch = scratch_dir()
    call test_fsys()
    call test_full_file()
    call test_nested_prefix()
    call test_abandon()
    call test_replace_older()

    if (n_failed > 0) then
        write (error_unit, '(a, i0, a)') 'test_output_m: ', n_failed, ' check(s) failed'
        stop 1
    end if
    write (*, '(a)') 'test_output_m: all checks passed'

contains

    function scratch_dir() result(dir)
        character(len=:), allocatable :: dir

        integer :: n, status

        call get_command_argument(2, length=n, status=status)
        if (status /= 0 .or. n == 0) then
            write (error_unit, '(a)') 'usage: test_output_m <source dir> <scratch dir>'
            stop 1
        end if
        allocate (character(len=n) :: dir)
        call get_command_argument(2, dir)
    end function scratch_dir

    ! ------------------------------------------------------------- the data written

    !> Series entry i (0-based) of the test file: deterministic, non-trivial values.
    subroutine series_entry(i, t, energy, u_end, penetration, contact_stress, iterations)
        integer, intent(in) :: i
        real(dp), intent(out) :: t, energy, u_end, penetration, contact_stress
        integer, intent(out) :: iterations

        t = real(i, dp) * 1.0e-4_dp
        energy = 1.0_dp / (1.0_dp + real(i, dp))
        u_end = 0.2_dp * sin(1.0e-3_dp * real(i, dp))
        penetration = max(u_end - 0.1_dp, 0.0_dp)
        contact_stress = -penetration / 0.01_dp
        iterations = mod(i, 7) + 1
    end subroutine series_entry

    !> Nodal values of snapshot m (1-based) of field k.
    function snapshot_field(k, m) result(f)
        integer, intent(in) :: k, m
        real(dp) :: f(0:S)

        integer :: j

        do j = 0, S
            f(j) = real(k, dp) * 100.0_dp + sin(real(j + 7 * m, dp)) / 3.0_dp
        end do
    end function snapshot_field

    !> A series entry as append_series takes it: the first 8 datasets of fields_m's SERIES
    !> (t .. n_elements) given, the energy parts zero.
    function series_row(first) result(row)
        real(dp), intent(in) :: first(8)
        real(dp) :: row(N_TABLE_SERIES)

        row = 0.0_dp
        row(1:8) = first
    end function series_row

    !> Snapshot m as append_snapshot takes it: column k is dataset k (u, v, theta, P, q, eta, sigma).
    function snapshot_fields(m) result(f)
        integer, intent(in) :: m
        real(dp) :: f(0:S, N_SNAPSHOT_FIELDS)
        integer :: k

        do k = 1, N_SNAPSHOT_FIELDS
            f(:, k) = snapshot_field(k, m)
        end do
    end function snapshot_fields

    function snapshot_time(m) result(t)
        integer, intent(in) :: m
        real(dp) :: t

        t = real(m - 1, dp) * 0.25_dp
    end function snapshot_time

    function mesh_nodes() result(x)
        real(dp) :: x(0:S)

        integer :: j

        x = [(real(j, dp) / real(S, dp), j = 0, S)]
    end function mesh_nodes

    ! ------------------------------------------------------------- test cases

    subroutine test_fsys()
        logical :: ok
        integer :: unit
        character(len=:), allocatable :: message

        call check_str('parent_dir(out/run)', 'out', parent_dir('out/run'))
        call check_str('parent_dir(run)', '', parent_dir('run'))
        call check_str('parent_dir(/run)', '/', parent_dir('/run'))
        call check_str('parent_dir(a/b/c)', 'a/b', parent_dir('a/b/c'))
        call check_str('parent_dir(a//b)', 'a', parent_dir('a//b'))
        call check_str('parent_dir(a/b/)', 'a', parent_dir('a/b/'))

        ! mkdir_p must refuse to make a directory below a regular file, with a reason
        call remove_file(scratch//'/plain_file')
        open (newunit=unit, file=scratch//'/plain_file', status='replace', action='write')
        close (unit)
        call mkdir_p(scratch//'/plain_file/sub', ok, message)
        call check_true('mkdir_p below a regular file fails', .not. ok)
        call check_true('mkdir_p failure has a message ('//message//')', len(message) > 0)
        call remove_file(scratch//'/plain_file')
    end subroutine test_fsys

    !> The main case: 10000 series entries, 3 snapshots, attributes (some overwritten).
    subroutine test_full_file()
        type(h5_writer_t) :: w
        character(len=:), allocatable :: prefix, file, str
        real(dp) :: t, energy, u_end, penetration, contact_stress, value
        real(dp), allocatable :: got_1d(:), got_2d(:, :), expected_2d(:, :)
        real(dp), allocatable :: expected_series(:, :)
        integer, allocatable :: expected_iter(:)
        integer :: iterations
        integer, allocatable :: got_int(:)
        integer :: i, k, m, ivalue
        character(len=14), parameter :: names(5) = &
            [character(len=14) :: 't', 'energy', 'u_end', 'penetration', 'contact_stress']
        character(len=5), parameter :: fields(7) = [character(len=5) :: 'u', 'v', 'theta', 'P', 'q', 'eta', 'sigma']

        call check_true('N_SERIES crosses the buffer boundary', N_SERIES > 2 * SERIES_BUFFER_SIZE)
        allocate (expected_series(0:N_SERIES - 1, 5), expected_iter(0:N_SERIES - 1))
        prefix = scratch//'/full'
        file = prefix//'.h5'
        call remove_file(file)

        call w%create(prefix, mesh_nodes())
        call check_true('.h5.part exists while writing', file_exists(prefix//'.h5.part'))
        call w%attr('model.rho', 1.2298e-17_dp)
        call w%attr('mesh.n_elements', S)
        call w%attr('solver.method', 'monolithic')
        call w%attr('output.quiet', .true.)
        call w%attr('contact.other', .false.)
        call w%attr('initial.theta0_poly', [0.0_dp, 40.0_dp, -80.0_dp, 40.0_dp])
        call w%attr('steps', 1)
        call w%attr('wall_seconds', 0.5_dp)
        call w%attr('note', 'a first value that is longer than the second')
        call w%attr('empty', '')

        m = 0
        do i = 0, N_SERIES - 1
            call series_entry(i, t, energy, u_end, penetration, contact_stress, iterations)
            expected_series(i, :) = [t, energy, u_end, penetration, contact_stress]
            expected_iter(i) = iterations
            call w%append_series(series_row([t, energy, u_end, penetration, contact_stress, real(iterations, dp), 0.0_dp, 0.0_dp]))
            if (i == 0 .or. i == FLUSH_AT .or. i == N_SERIES - 1) then
                m = m + 1
                call w%append_snapshot(snapshot_time(m), snapshot_fields(m))
            end if
            if (i == FLUSH_AT) call w%flush()
        end do
        ! end-of-run values replace the earlier ones
        call w%attr('steps', N_SERIES - 1)
        call w%attr('wall_seconds', 1.25_dp)
        call w%attr('note', 'short')
        call w%finish('complete')

        call check_true('.h5.part gone after finish', .not. file_exists(prefix//'.h5.part'))
        call check_true('.h5 exists after finish', file_exists(file))

        call read_real_1d(file, '/mesh/x', got_1d)
        call check_real_1d('/mesh/x', mesh_nodes(), got_1d)
        do k = 1, 5
            call read_real_1d(file, '/series/'//trim(names(k)), got_1d)
            call check_real_1d('/series/'//trim(names(k)), expected_series(:, k), got_1d)
        end do
        call read_int_1d(file, '/series/iterations', got_int)
        call check_int_1d('/series/iterations', expected_iter, got_int)

        call read_real_1d(file, '/snapshots/t', got_1d)
        call check_real_1d('/snapshots/t', [(snapshot_time(m), m = 1, N_SNAP)], got_1d)
        allocate (expected_2d(S + 1, N_SNAP))
        do k = 1, 7
            do m = 1, N_SNAP
                expected_2d(:, m) = snapshot_field(k, m)
            end do
            call read_real_2d(file, '/snapshots/'//trim(fields(k)), got_2d)
            call check_real_2d('/snapshots/'//trim(fields(k)), expected_2d, got_2d)
        end do

        call read_attr_str(file, 'status', str)
        call check_str('attribute status', 'complete', str)
        call read_attr_real(file, 'model.rho', value)
        call check_real_1d('attribute model.rho', [1.2298e-17_dp], [value])
        call read_attr_int(file, 'mesh.n_elements', ivalue)
        call check_int_1d('attribute mesh.n_elements', [S], [ivalue])
        call read_attr_str(file, 'solver.method', str)
        call check_str('attribute solver.method', 'monolithic', str)
        call read_attr_int(file, 'output.quiet', ivalue)
        call check_int_1d('attribute output.quiet (logical as 0/1)', [1], [ivalue])
        call read_attr_int(file, 'contact.other', ivalue)
        call check_int_1d('attribute contact.other (logical as 0/1)', [0], [ivalue])
        call read_attr_real_1d(file, 'initial.theta0_poly', got_1d)
        call check_real_1d('attribute initial.theta0_poly', [0.0_dp, 40.0_dp, -80.0_dp, 40.0_dp], got_1d)
        call read_attr_int(file, 'steps', ivalue)
        call check_int_1d('attribute steps (overwritten)', [N_SERIES - 1], [ivalue])
        call read_attr_real(file, 'wall_seconds', value)
        call check_real_1d('attribute wall_seconds (overwritten)', [1.25_dp], [value])
        call read_attr_str(file, 'note', str)
        call check_str('attribute note (overwritten by a shorter string)', 'short', str)
        call read_attr_str(file, 'empty', str)
        call check_str('attribute empty', '', str)

        call check_true('dataset_exists /series/t', dataset_exists(file, '/series/t'))
        call check_true('dataset_exists /snapshots/P', dataset_exists(file, '/snapshots/P'))
        call check_true('dataset_exists /series (a group) is false', .not. dataset_exists(file, '/series'))
        call check_true('dataset_exists /nope/x is false', .not. dataset_exists(file, '/nope/x'))
        call check_true('attr_exists status', attr_exists(file, 'status'))
        call check_true('attr_exists nope is false', .not. attr_exists(file, 'nope'))
    end subroutine test_full_file

    !> A prefix inside directories that do not exist yet: create() makes them.
    subroutine test_nested_prefix()
        type(h5_writer_t) :: w
        character(len=:), allocatable :: base, prefix, str
        real(dp), allocatable :: got(:)

        base = scratch//'/nested_new'
        prefix = base//'/a/b/run'
        ! leave the directories absent, whatever an earlier run of this test left
        call remove_file(prefix//'.h5')
        call remove_file(prefix//'.h5.part')
        call remove_dir(base//'/a/b')
        call remove_dir(base//'/a')
        call remove_dir(base)
        call check_true('nested directory absent before create', .not. dir_exists(base))

        call w%create(prefix, mesh_nodes())
        call w%append_series(series_row([0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, real(0, dp), 0.0_dp, 0.0_dp]))
        call w%append_snapshot(0.0_dp, snapshot_fields(1))
        call w%finish('complete')

        call check_true('nested directory created', dir_exists(base//'/a/b'))
        call check_true('nested .h5 exists', file_exists(prefix//'.h5'))
        call check_true('nested .h5.part gone', .not. file_exists(prefix//'.h5.part'))
        call read_real_1d(prefix//'.h5', '/series/energy', got)
        call check_real_1d('nested /series/energy', [1.0_dp], got)
        call read_attr_str(prefix//'.h5', 'status', str)
        call check_str('nested attribute status', 'complete', str)
    end subroutine test_nested_prefix

    !> abandon() leaves neither the .part nor a final file behind.
    subroutine test_abandon()
        type(h5_writer_t) :: w
        character(len=:), allocatable :: prefix
        integer :: i

        prefix = scratch//'/abandoned'
        call remove_file(prefix//'.h5')
        call remove_file(prefix//'.h5.part')
        call w%create(prefix, mesh_nodes())
        do i = 1, SERIES_BUFFER_SIZE + 10
            call w%append_series(series_row([real(i, dp), 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, real(i, dp), 0.0_dp, 0.0_dp]))
        end do
        call w%attr('status', 'whatever')
        call w%abandon()
        call check_true('abandon removes .h5.part', .not. file_exists(prefix//'.h5.part'))
        call check_true('abandon leaves no .h5', .not. file_exists(prefix//'.h5'))
        ! a second abandon is harmless
        call w%abandon()
    end subroutine test_abandon

    !> finish() replaces an older file of the same name; an empty series is valid; a failed
    !> status is stored verbatim.
    subroutine test_replace_older()
        type(h5_writer_t) :: w
        character(len=:), allocatable :: prefix, file, str
        real(dp), allocatable :: got(:), got_2d(:, :)
        integer :: ivalue

        prefix = scratch//'/replaced'
        file = prefix//'.h5'
        call w%create(prefix, mesh_nodes())
        call w%attr('run', 1)
        call w%finish('complete')
        call read_real_1d(file, '/series/t', got)
        call check_int_1d('first file: series length (empty)', [0], [size(got)])
        call read_real_2d(file, '/snapshots/u', got_2d)
        call check_int_1d('first file: snapshot shape', [S + 1, 0], shape(got_2d))

        call w%create(prefix, mesh_nodes())
        call w%attr('run', 2)
        call w%append_series(series_row([0.0_dp, 3.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, real(1, dp), 0.0_dp, 0.0_dp]))
        call w%append_series(series_row([0.1_dp, 2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, real(2, dp), 0.0_dp, 0.0_dp]))
        call w%append_series(series_row([0.2_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, real(3, dp), 0.0_dp, 0.0_dp]))
        call w%finish('failed: non-finite value at step 12')

        call read_attr_int(file, 'run', ivalue)
        call check_int_1d('replaced file: attribute run', [2], [ivalue])
        call read_real_1d(file, '/series/energy', got)
        call check_real_1d('replaced file: /series/energy', [3.0_dp, 2.0_dp, 1.0_dp], got)
        call read_attr_str(file, 'status', str)
        call check_str('replaced file: attribute status', 'failed: non-finite value at step 12', str)
    end subroutine test_replace_older

    ! ------------------------------------------------------------- checks

    !> Bitwise comparison: a float64 written and read back must be the same bits.
    pure function differ(expected, got) result(yes)
        real(dp), intent(in) :: expected, got
        logical :: yes

        yes = transfer(expected, 0_int64) /= transfer(got, 0_int64)
    end function differ

    subroutine check_true(label, condition)
        character(len=*), intent(in) :: label
        logical, intent(in) :: condition

        if (condition) return
        n_failed = n_failed + 1
        write (error_unit, '(a)') 'FAIL '//label//': expected .true. / got .false.'
    end subroutine check_true

    subroutine check_str(label, expected, got)
        character(len=*), intent(in) :: label, expected, got

        if (expected == got .and. len(expected) == len(got)) return
        n_failed = n_failed + 1
        write (error_unit, '(a)') 'FAIL '//label//": expected '"//expected//"' / got '"//got//"'"
    end subroutine check_str

    subroutine check_real_1d(label, expected, got)
        character(len=*), intent(in) :: label
        real(dp), intent(in) :: expected(:), got(:)

        integer :: i

        if (size(expected) /= size(got)) then
            n_failed = n_failed + 1
            write (error_unit, '(a, i0, a, i0)') 'FAIL '//label//': expected size ', size(expected), &
                ' / got size ', size(got)
            return
        end if
        do i = 1, size(expected)
            if (differ(expected(i), got(i))) then
                n_failed = n_failed + 1
                write (error_unit, '(a, i0, a, es24.16, a, es24.16, a)') 'FAIL '//label//'(', i, &
                    '): expected ', expected(i), ' / got ', got(i), ' (tolerance 0: exact round trip)'
                return
            end if
        end do
    end subroutine check_real_1d

    subroutine check_real_2d(label, expected, got)
        character(len=*), intent(in) :: label
        real(dp), intent(in) :: expected(:, :), got(:, :)

        integer :: i, j

        if (any(shape(expected) /= shape(got))) then
            n_failed = n_failed + 1
            write (error_unit, '(a, 2(i0, 1x), a, 2(i0, 1x))') 'FAIL '//label//': expected shape ', &
                shape(expected), '/ got shape ', shape(got)
            return
        end if
        do j = 1, size(expected, 2)
            do i = 1, size(expected, 1)
                if (differ(expected(i, j), got(i, j))) then
                    n_failed = n_failed + 1
                    write (error_unit, '(a, i0, a, i0, a, es24.16, a, es24.16, a)') 'FAIL '//label//'(', &
                        i, ',', j, '): expected ', expected(i, j), ' / got ', got(i, j), &
                        ' (tolerance 0: exact round trip)'
                    return
                end if
            end do
        end do
    end subroutine check_real_2d

    subroutine check_int_1d(label, expected, got)
        character(len=*), intent(in) :: label
        integer, intent(in) :: expected(:), got(:)

        integer :: i

        if (size(expected) /= size(got)) then
            n_failed = n_failed + 1
            write (error_unit, '(a, i0, a, i0)') 'FAIL '//label//': expected size ', size(expected), &
                ' / got size ', size(got)
            return
        end if
        do i = 1, size(expected)
            if (expected(i) /= got(i)) then
                n_failed = n_failed + 1
                write (error_unit, '(a, i0, a, i0, a, i0)') 'FAIL '//label//'(', i, '): expected ', &
                    expected(i), ' / got ', got(i)
                return
            end if
        end do
    end subroutine check_int_1d

end program test_output_m
