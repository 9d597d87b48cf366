#!/usr/bin/env bash
# Output faults (issue 14, deliverable 7): a disk that fills up mid-run, simulated by a file
# size limit (ulimit -f; the program ignores SIGXFSZ itself, so the write fails with EFBIG as
# on a full disk instead of the signal killing it):
#  1. after a checkpoint: exit 4, a message on stderr naming the .h5.part, the system's
#     reason and the checkpoint; no <prefix>.h5; the .h5.part readable, its last checkpoint
#     restartable, and the continued run equal bit for bit to an uninterrupted one
#     (tests/tools/regression.py same), with compression 0 (the default) and 4;
#  2. before any checkpoint: exit 4, the message says there is none, the .h5.part is a
#     readable file (inputs, initial state) with status 'incomplete'.
# Also: the short file of issue 14 (2 snapshots at s = 500) is under 150 kB, and compression
# changes the layout but not the data.
# Usage: bash test_output_faults.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py to read the files"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"

# exp1 at s = 500, a snapshot every 10 steps (24 kB each), a checkpoint every 250 steps
# (the first at ~0.65 MB of file): 2000 steps, a 5 MB file
run() { "$exe" "$src/input/exp1.nml" --set time.t_end=0.2 --set output.snapshot_every=10 \
    --set output.checkpoint_every=250 --set output.quiet=.true. "$@"; }
run --set output.prefix=ref || { echo "FAIL: the uninterrupted run failed (exit $?)"; exit 1; }

for level in 0 4; do
    # 1 MiB: hit between the checkpoints at steps 250 and 500
    (ulimit -f 1024; run --set output.prefix=full$level --set output.compression=$level 2> full$level.err)
    status=$?
    err=$(cat full$level.err)
    check "compression $level, disk full after a checkpoint: exit 4" equals 4 "$status"
    check "compression $level: the message names the file, the reason and the checkpoint" \
        grep -q "cannot write 'full$level.h5.part': .*(File too large).*checkpoint of step 250.*the same command and --resume" full$level.err
    [[ -n "$err" ]] && echo "  stderr: $err"
    # (a Debug build adds gfortran's -fcheck runtime warnings, two lines each: not counted)
    check "compression $level: no HDF5 error stack on stderr" equals 1 \
        "$(grep -v -e '^At line [0-9]* of file ' -e '^Fortran runtime warning: ' full$level.err | wc -l)"
    check "compression $level: no full$level.h5 under the final name" test ! -e full$level.h5
    check "compression $level: the .h5.part is left" test -f full$level.h5.part
    step=$("$py" -c "
import h5py
f = h5py.File('full$level.h5.part', 'r', swmr=True)   # left open by its SWMR writer
print(int(f['checkpoint/slot%d/state/scalars' % int(f['checkpoint/current'][0])]['step']))" 2>&1)
    check "compression $level: the .h5.part opens, its last checkpoint is at step 250" equals 250 "$step"
    run --set output.prefix=full$level --set output.compression=$level --resume
    check "compression $level: the same command with --resume (normal limit) exits 0" equals 0 "$?"
    check "compression $level: the resumed run equals the uninterrupted one bit for bit" \
        "$py" "$src/tests/tools/regression.py" same ref.h5 full$level.h5
    check "compression $level: no .part left" test ! -e full$level.h5.part -a ! -e full$level.resume.h5.part
done

# before the first checkpoint (400 kB): the file holds what its first flush wrote
(ulimit -f 400; run --set output.prefix=early 2> early.err)
check "disk full before any checkpoint: exit 4" equals 4 "$?"
check "the message says the file holds no checkpoint" grep -q "cannot write 'early.h5.part': .*holds no checkpoint" early.err
got=$("$py" -c "
import h5py
f = h5py.File('early.h5.part', 'r', swmr=True)   # left open by its SWMR writer
print(f.attrs['status'], f.attrs['model.varpi'], f['snapshots/t'][0])" 2>&1)
check "the .h5.part of a run stopped before its first checkpoint is readable (status, inputs, t = 0)" \
    equals "incomplete 0.1 0.0" "$got"

# small files: 2 snapshots at s = 500 under 150 kB (137 kB: 16 series, 7 snapshot datasets;
# 95 kB before the energy parts and sigma); compression keeps the data
"$exe" "$src/input/exp1.nml" --set time.t_end=0.01 --set output.prefix=short --set output.quiet=.true.
bytes=$(stat -c %s short.h5)
check "2 snapshots at s = 500: $bytes bytes < 150 kB" test "$bytes" -lt 150000
for level in 1 9; do
    "$exe" "$src/input/exp1.nml" --set time.t_end=0.01 --set output.prefix=short$level --set output.quiet=.true. \
        --set output.compression=$level
    small=$(stat -c %s short$level.h5)
    check "compression $level: $small bytes, smaller than $bytes" test "$small" -lt "$bytes"
    check "compression $level: the same data as without" "$py" "$src/tests/tools/regression.py" same short.h5 short$level.h5
    check "compression $level: recorded as output.compression" equals "$level" \
        "$("$py" -c "import h5py; print(h5py.File('short$level.h5', 'r').attrs['output.compression'])")"
done

echo "test_output_faults: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
