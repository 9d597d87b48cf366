#!/usr/bin/env bash
# Checkpoint and restart (&output checkpoint_every, &time restart_from):
#  1. for Euler and BDF2, a run split at T/2 and restarted gives bit-for-bit the series,
#     snapshots and energy bookkeeping of the uninterrupted run;
#  1b. the same on the impact (midpoint rule) split among its bounces: events of both kinds
#     come back from the checkpoint;
#  2. a run killed with SIGKILL leaves its .h5.part with the last checkpoint and the history
#     before it readable (as a SWMR reader) and restartable, the restart leaves it as it was,
#     and the restarted run equals the uninterrupted one bit for bit;
#  3. bad restarts exit 2, write nothing and leave the source as it was: missing file, no
#     checkpoint, a damaged one, one in the positional layout of earlier versions, any input
#     that changes the history changed (named with both values and what may change), t_end
#     before the checkpoint, the output being the source itself, a resume in place of a
#     .h5.part that is not there;
#  4. a restart that changes only t_end and &output settings runs.
# Usage: bash test_restart.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py to compare the files"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# exp1 data on 100 elements; contact starts at t ~ 0.19
make_input() {   # make_input <file> <prefix> <t_end> <scheme> [extra &time text]
    sed -e 's/n_elements=500/n_elements=100/' -e "s|t_end=3.0 /|t_end=$3 scheme='$4' ${5:-} /|" \
        -e "s|prefix='out/exp1'|prefix='$2' checkpoint_every=250 quiet=.true.|" "$src/input/exp1.nml" > "$1"
}
same() {   # same <a.h5> <b.h5>: /series and /snapshots bit for bit, the same run counters
    "$py" "$src/tests/tools/regression.py" same "$1" "$2"
}

for scheme in euler bdf2 midpoint; do
    make_input full_$scheme.nml full_$scheme 0.6 $scheme
    make_input half_$scheme.nml half_$scheme 0.3 $scheme
    make_input rest_$scheme.nml rest_$scheme 0.6 $scheme "restart_from='half_$scheme.h5'"
    "$exe" full_$scheme.nml || fail "$scheme: uninterrupted run exit $?"
    "$exe" half_$scheme.nml || fail "$scheme: first half exit $?"
    "$exe" rest_$scheme.nml || fail "$scheme: restarted run exit $?"
    if out=$(same full_$scheme.h5 rest_$scheme.h5); then echo "PASS $scheme: split at T/2 and restarted = uninterrupted ($out)"
    else fail "$scheme: restarted run differs from the uninterrupted one:"; echo "$out"; fi
done

# adaptive steps (with the contact events of exp1 inside both halves' range and snapshots
# at exact times): the controller, the estimator's levels and the events continue exactly
for scheme in euler bdf2 midpoint; do
    ad="adaptive=.true. error_tol=1e-5"
    make_input afull_$scheme.nml afull_$scheme 0.6 $scheme "$ad"
    make_input ahalf_$scheme.nml ahalf_$scheme 0.3 $scheme "$ad"
    make_input arest_$scheme.nml arest_$scheme 0.6 $scheme "$ad restart_from='ahalf_$scheme.h5'"
    sed -i -e 's/checkpoint_every=250/checkpoint_every=7 snapshot_dt=0.05/' afull_$scheme.nml ahalf_$scheme.nml arest_$scheme.nml
    "$exe" afull_$scheme.nml || fail "adaptive $scheme: uninterrupted run exit $?"
    "$exe" ahalf_$scheme.nml || fail "adaptive $scheme: first half exit $?"
    "$exe" arest_$scheme.nml || fail "adaptive $scheme: restarted run exit $?"
    if out=$(same afull_$scheme.h5 arest_$scheme.h5); then echo "PASS adaptive $scheme: split and restarted = uninterrupted ($out)"
    else fail "adaptive $scheme: restarted run differs from the uninterrupted one:"; echo "$out"; fi
    ev=$("$py" -c "import h5py; a, b = h5py.File('afull_$scheme.h5'), h5py.File('arest_$scheme.h5')
print(list(a['events/t'][:]) == list(b['events/t'][:]) and list(a['events/kind'][:]) == list(b['events/kind'][:]) and len(a['events/t']) > 0)")
    [ "$ev" = True ] || fail "adaptive $scheme: /events differ after the restart (or are empty)"
done

# dense output (issue 24): series entries at k series_dt and snapshots at k snapshot_dt from the
# scheme's interpolant, steps not landing on them; a checkpoint in the middle of a step sequence;
# adaptive BDF2, and fixed midpoint steps (which keep their levels only for dense output)
for mode in "--set time.adaptive=.true. --set time.scheme='bdf2' --set output.checkpoint_every=37" \
            "--set time.scheme='midpoint' --set output.checkpoint_every=777"; do
    read -r -a how <<<"$mode"
    dense=(--set mesh.n_elements=100 --set output.quiet=.true. "${how[@]}"
           --set output.series_dt=0.0137 --set output.snapshot_dt=0.05 --set output.snapshot_land=.false.)
    "$exe" "$src/input/exp1.nml" "${dense[@]}" --set time.t_end=0.6 --set output.prefix="'dfull'" || fail "dense: run exit $?"
    "$exe" "$src/input/exp1.nml" "${dense[@]}" --set time.t_end=0.3 --set output.prefix="'dhalf'" ||
        fail "dense: first half exit $?"
    "$exe" "$src/input/exp1.nml" "${dense[@]}" --set time.t_end=0.6 --set time.restart_from="'dhalf.h5'" \
        --set output.prefix="'drest'" || fail "dense: restarted run exit $?"
    if out=$(same dfull.h5 drest.h5); then echo "PASS dense output ($mode): restarted = uninterrupted ($out)"
    else fail "dense output ($mode): restarted run differs from the uninterrupted one:"; echo "$out"; fi
    rm -f dfull.h5 dhalf.h5 drest.h5
done

# contact events of both kinds before the checkpoint (the impact's bounces, midpoint rule):
# restored with their kinds
imp=("$src/input/impact.nml" --set mesh.n_elements=100 --set output.quiet=.true. --set output.checkpoint_every=100)
"$exe" "${imp[@]}" --set time.t_end=0.3 --set output.prefix="'ifull'" || fail "impact: uninterrupted run exit $?"
"$exe" "${imp[@]}" --set time.t_end=0.2 --set output.prefix="'ihalf'" || fail "impact: first half exit $?"
"$exe" "${imp[@]}" --set time.t_end=0.3 --set time.restart_from="'ihalf.h5'" --set output.prefix="'irest'" \
    || fail "impact: restarted run exit $?"
kinds=$("$py" -c "import h5py; print(sorted(set(h5py.File('ihalf.h5', 'r')['events/kind'][:].tolist())))")
[ "$kinds" = "[-1, 1]" ] || fail "impact: the first half should hold onsets and releases, has kinds $kinds"
if out=$(same ifull.h5 irest.h5); then echo "PASS impact: split among the bounces and restarted = uninterrupted ($out)"
else fail "impact: restarted run differs from the uninterrupted one:"; echo "$out"; fi

# killed run: long enough (10^7 steps) that the kill lands mid-run; checkpoints every 250 steps
make_input long.nml long 1000.0 euler
timeout -s KILL 1 "$exe" long.nml
status=$?
[ $status -eq 137 ] || fail "killed run: expected exit 137 (SIGKILL), got $status"
[ -f long.h5.part ] || fail "killed run: no long.h5.part left"
[ -f long.h5 ] && fail "killed run: a final long.h5 exists although the run was killed"
# the killed SWMR writer left the file marked as open: read as a SWMR reader (docs/output.md),
# the checkpoint and the whole history up to it
step=$("$py" -c "
import h5py
f = h5py.File('long.h5.part', 'r', swmr=True)
g = f['checkpoint/slot%d' % int(f['checkpoint/current'][0])]
g.visititems(lambda name, item: item[()] if isinstance(item, h5py.Dataset) else None)
n = int(g['state/scalars']['step'])
for group in ('series', 'snapshots'):
    for name in f[group]:
        if isinstance(f[group][name], h5py.Dataset): f[group][name][()]
assert f['series/t'].size > n
print(n)") || fail "killed run: the .part file, its checkpoint or its history is not readable"
echo "killed run: last checkpoint at step ${step:-?}"
part_sum=$(md5sum < long.h5.part)
# continue 5000 steps past the last checkpoint, and compare with a run from t = 0 to there
t_end=$(awk -v n="${step:-0}" 'BEGIN { printf "%.4f", (n + 5000) * 1e-4 }')
make_input long_rest.nml long_rest "$t_end" euler "restart_from='long.h5.part'"
make_input long_ref.nml long_ref "$t_end" euler
if [ "${step:-0}" -gt 0 ]; then
    "$exe" long_rest.nml || fail "restart from the killed run: exit $?"
    "$exe" long_ref.nml || fail "reference run: exit $?"
    if out=$(same long_ref.h5 long_rest.h5); then echo "PASS: restart from a SIGKILLed run = uninterrupted ($out)"
    else fail "restart from the killed run differs:"; echo "$out"; fi
    [ "$(md5sum < long.h5.part)" = "$part_sum" ] || fail "restart from the killed run changed its .h5.part"
else
    fail "killed run: no checkpoint step (${step:-none}): the kill landed before the first checkpoint"
fi

# bad restarts: exit 2, message naming time.restart_from (or what else is wrong, and the
# values), no output file; the file restarted from is left as it was
bad() {   # bad <what> <restart_from value> <sed expression or ''> [pattern the message must hold ...]
    local what=$1 from=$2 expr=$3; shift 3
    make_input bad.nml bad 0.6 euler "restart_from='$from'"
    [ -n "$expr" ] && sed -i -e "$expr" bad.nml
    rm -f bad.h5 bad.h5.part
    local before=""; [ -f "$from" ] && before=$(md5sum < "$from")
    err=$("$exe" bad.nml 2>&1 >/dev/null); st=$?
    local after=""; [ -f "$from" ] && after=$(md5sum < "$from")
    local missing=""
    for pattern in "${@:-time.restart_from}"; do grep -qF -- "$pattern" <<< "$err" || missing="$missing '$pattern'"; done
    if [ $st -ne 2 ]; then fail "$what: expected exit 2, got $st ($err)"
    elif [ -n "$missing" ]; then fail "$what: message lacks$missing: $err"
    elif [ -e bad.h5 ] || [ -e bad.h5.part ]; then fail "$what: an output file was left"
    elif [ "$before" != "$after" ]; then fail "$what: the file restarted from ($from) was changed"
    else echo "PASS $what: $err"; fi
}
bad "missing restart file" "does-not-exist.h5" ''
make_input nock.nml nock 0.01 euler; sed -i 's/checkpoint_every=250/checkpoint_every=0/' nock.nml; "$exe" nock.nml
bad "file without checkpoint" "nock.h5" ''
# a damaged checkpoint (its state's level removed): an input error, exit 2, naming the file
cp half_euler.h5 damaged.h5 && "$py" -c "
import h5py
with h5py.File('damaged.h5', 'r+') as f:
    for slot in ('slot0', 'slot1'):
        if 'checkpoint/' + slot + '/state/level' in f:
            del f['checkpoint/' + slot + '/state/level']"
bad "damaged restart file" "damaged.h5" '' "damaged.h5" "has no state/level"
# a checkpoint in the positional layout of the versions before named entries (written by
# 9efb09e with this test's make_input, t_end = 0.025, checkpoint_every = 250): refused, with
# what to do instead
gzip -dc "$src/tests/reference/checkpoint_positional.h5.gz" > positional.h5
bad "checkpoint in the positional layout" "positional.h5" '' "positional.h5" "positional layout" \
    "run again from the start" "restart with the version that wrote"
bad "restart on another mesh" "half_euler.h5" 's/n_elements=100/n_elements=50/' mesh.n_elements "was 100" "has 50" "may change"
bad "restart with another dt" "half_euler.h5" 's/dt=1e-4/dt=2e-4/' time.dt "was 0.0001" "has 0.0002"
# every group that shapes the history, driven through --set-free edits of the input
bad "restart with another varpi" "half_euler.h5" 's/varpi *= *0.1/varpi=0.9/' model.varpi "was 0.1" "has 0.9" \
    time.t_end output.snapshot_every output.checkpoint_every output.quiet
bad "restart with other initial data" "half_euler.h5" 's/theta0_poly = 0, 40, -80, 40/theta0_poly = 0, 20, -40, 20/' \
    initial.theta0_poly "was 0, 40, -80, 40" "has 0, 20, -40, 20"
bad "restart with another contact gap" "half_euler.h5" 's/g=0.1 eps/g=0.2 eps/' contact.g "was 0.1" "has 0.2"
bad "restart with another solver tolerance" "half_euler.h5" 's|&time|\&solver tol=1e-8 /\n\&time|' solver.tol
bad "restart with another scheme" "half_euler.h5" "s/scheme='euler'/scheme='bdf2'/" time.scheme "'euler'" "'bdf2'"
bad "restart with &material added" "half_euler.h5" '/^&model/,/tau=0.2 \//d; s|&time|\&material units='"'SI'"' ell=1.0 /\n\&time|' \
    "a restart must keep every input"
# t_end before the checkpoint (at t = 0.3): exit 2 naming time.t_end and the checkpoint's time
bad "restart with t_end before the checkpoint" "half_euler.h5" 's/t_end=0.6/t_end=0.1/' time.t_end "t = 0.3"
# the output may never be the file restarted from: its own .h5, or the .h5.part of a killed run
bad "restart into its own file" "half_euler.h5" "s|prefix='bad'|prefix='half_euler'|" "is a file this run writes"
bad "restart into its own file by another path" "half_euler.h5" "s|prefix='bad'|prefix='./../$(basename "$PWD")/half_euler'|" \
    "is a file this run writes"
# its own .h5.part is resumed in place (tests/test_signal.sh); --resume without one: nothing to resume
bad "resume in place without a .h5.part" "bad.h5.part" '' "no such file, nothing to resume" "without --resume"
# the file a run resumed in place writes (<prefix>.resume.h5.part) is refused too; a new run
# (a new .part) deletes it, since it no longer continues that .part
cp half_euler.h5 bad.resume.h5.part
bad "restart from its own .resume.h5.part" "bad.resume.h5.part" '' "is a file this run writes" "--resume"
make_input fresh.nml fresh 0.01 euler && cp half_euler.h5 fresh.resume.h5.part
"$exe" fresh.nml && [ ! -e fresh.resume.h5.part ] && echo "PASS a new run deletes a stale <prefix>.resume.h5.part" ||
    fail "a new run left fresh.resume.h5.part (a resumed run's file that no longer continues its .part)"
# what may change: t_end, output intervals, checkpoint interval, quiet, prefix
make_input ok.nml ok 0.35 euler "restart_from='half_euler.h5'"
sed -i -e 's/checkpoint_every=250/checkpoint_every=100 series_every=2/' -e 's/snapshot_every=100/snapshot_every=50/' -e 's/quiet=.true./quiet=.false./' ok.nml
if "$exe" ok.nml > /dev/null 2>&1; then echo "PASS restart with other t_end and &output settings runs"
else fail "restart with other t_end and &output settings: exit $?"; fi

echo "test_restart: $failures failed"
[ $failures -eq 0 ]
