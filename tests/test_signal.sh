#!/usr/bin/env bash
# Clean stop on a signal (issue 14, deliverable 6): a run sent SIGTERM, SIGINT or SIGUSR1
# finishes its step, writes a checkpoint (here with checkpoint_every = 0), leaves a valid
# <prefix>.h5.part with status 'interrupted: <signal>' and no <prefix>.h5, and exits 5;
# restart_from on that .h5.part continues bit for bit: /series and /snapshots equal those of
# an uninterrupted run to the same t_end. The signal is sent once the .part has grown after
# its first flush (wait_in_time_loop), not after a fixed sleep: the run's handlers are installed
# before the .part exists, so on a loaded machine too the signal stops it cleanly.
# A signal already pending when the program starts (inherited blocked: the signal mask survives
# exec) stops the run before its first step, with a checkpoint at step 0 to restart from.
# Last, a run resumed in place with --resume (stopped again, killed once, then to its end).
# Usage: bash test_signal.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py to compare the files"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
. "$src/tests/lib/checks.sh"   # wait_in_time_loop

make_input() {   # make_input <file> <prefix> <t_end> [extra &time text]: exp1 on 100 elements
    sed -e 's/n_elements=500/n_elements=100/' -e "s|t_end=3.0 /|t_end=$3 ${4:-} /|" \
        -e "s|prefix='out/exp1'|prefix='$2' quiet=.true.|" "$src/input/exp1.nml" > "$1"
}

# pending_term <args>: run rodcontact <args> with SIGTERM blocked and already pending
pending_term() {
    "$py" -c "
import os, signal, sys
signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGTERM})
os.kill(os.getpid(), signal.SIGTERM)
os.execv(sys.argv[1], sys.argv[1:])" "$exe" "$@"
}

# start <sig> <name>: run <name>.nml in the background and send SIG<sig> in its time loop;
# with <sig> = PENDING_TERM, start it with SIGTERM blocked and already pending
start() {
    if [ "$1" = PENDING_TERM ]; then
        pending_term $2.nml
        return
    fi
    "$exe" $2.nml & pid=$!
    wait_in_time_loop $2.h5.part || echo "note: $2.h5.part did not grow within 15 s; signalling anyway"
    kill -s $1 $pid
    wait $pid
}

for sig in TERM INT USR1 PENDING_TERM; do
    name=long_$sig
    make_input $name.nml $name 1000.0          # 10^7 steps: the signal lands mid-run
    start $sig $name; status=$?
    label=$sig; [ $sig = PENDING_TERM ] && sig=TERM
    [ $status -eq 5 ] || fail "SIG$sig: expected exit 5, got $status"
    [ -f $name.h5.part ] || { fail "SIG$sig: no $name.h5.part left"; continue; }
    [ -e $name.h5 ] && fail "SIG$sig: a final $name.h5 exists although the run was stopped"
    read -r file_status step < <("$py" -c "
import h5py
f = h5py.File('$name.h5.part', 'r')
step = f['checkpoint/slot%d/state/scalars' % int(f['checkpoint/current'][0])]['step']
print(f.attrs['status'].replace(' ', '_'), int(step))") || { fail "SIG$sig: .h5.part or its checkpoint unreadable"; continue; }
    [ "$file_status" = "interrupted:_SIG$sig" ] || fail "SIG$sig: status '$file_status', expected 'interrupted: SIG$sig'"
    echo "SIG$label: exit $status, status '$file_status', checkpoint at step $step"
    [ $label = PENDING_TERM ] && [ "$step" != 0 ] && fail "SIGTERM pending at the start: the run took $step steps, expected none"
    # continue 3000 steps past the stop, compare with one run from t = 0 to there
    t_end=$(awk -v n="$step" 'BEGIN { printf "%.4f", (n + 3000) * 1e-4 }')
    make_input rest_$label.nml rest_$label "$t_end" "restart_from='$name.h5.part'"
    make_input ref_$label.nml ref_$label "$t_end"
    "$exe" rest_$label.nml || { fail "SIG$label: restart exit $?"; continue; }
    "$exe" ref_$label.nml || { fail "SIG$sig: reference run exit $?"; continue; }
    if out=$("$py" "$src/tests/tools/regression.py" same ref_$label.h5 rest_$label.h5); then echo "PASS SIG$label: stopped, restarted = uninterrupted, bit for bit ($out)"
    else fail "SIG$label: restarted run differs from the uninterrupted one:"; echo "$out"; fi
done

# Resumed in place (--resume, docs/robustness.md): a run stopped by SIGTERM, resumed with
# --resume and stopped again (its .part replaced by the one with the later checkpoint, no
# other file left), then resumed to the end: <prefix>.h5 equals an uninterrupted run bit for
# bit and no .part is left. Then a resumed run killed by SIGKILL after a checkpoint: the next
# --resume takes over that later checkpoint (restart_step) and ends equal as well.
ckstep() {   # ckstep FILE: the step of FILE's last complete checkpoint (-1: none), as a SWMR reader
    "$py" -c "
import h5py, sys
try:
    f = h5py.File(sys.argv[1], 'r', swmr=True)
    n = int(f['checkpoint/current'][0])
    print(int(f['checkpoint/slot%d/state/scalars' % n]['step']) if n >= 0 else -1)
except Exception:
    print(-1)" "$1"
}
# Stopped before its first step, at a step that checkpoint_every divides (0 here, or where a
# resumed run begins): the file has no checkpoint of that step yet, so the stop writes one; the
# resumed run's file, which replaces the .part, too (the test above once lost it so).
make_input pend.nml pend 1000.0 && sed -i 's/quiet=.true./quiet=.true. checkpoint_every=250/' pend.nml
pending_term pend.nml 2> /dev/null; status=$?
[ $status -eq 5 ] && [ "$(ckstep pend.h5.part)" = 0 ] ||
    fail "stopped at step 0 with checkpoint_every = 250: exit $status, checkpoint step $(ckstep pend.h5.part)"
pending_term pend.nml --resume 2> /dev/null; status=$?
[ $status -eq 5 ] && [ "$(ckstep pend.h5.part)" = 0 ] &&
    echo "PASS stopped before the first step (fresh and resumed, checkpoint_every = 250): checkpoint kept" ||
    fail "resumed and stopped before its first step: exit $status, checkpoint step $(ckstep pend.h5.part)"
leftovers() { ls "$1".* 2> /dev/null | grep -v -x -F -e "$1.nml" -e "$1.err" -e "$1.h5" | tr '\n' ' '; }
make_input inplace.nml inplace 1000.0 "" && sed -i 's/quiet=.true./quiet=.true. checkpoint_every=250/' inplace.nml
start TERM inplace; status=$?
s1=$(ckstep inplace.h5.part)
[ $status -eq 5 ] && [ "$s1" -ge 0 ] || fail "in place: first stop: exit $status, checkpoint step $s1"
"$exe" inplace.nml --resume 2> inplace.err & pid=$!
# in its time loop once its own file has a checkpoint (wait_in_time_loop could see the file grow
# while the history was copied: stopped before its first step, it kept step s1: 3 of 9 runs under load)
for ((i = 0; i < 150; i++)); do [ "$(ckstep inplace.resume.h5.part)" -gt "$s1" ] && break; sleep 0.1; done
kill -s TERM $pid; wait $pid; status=$?
s2=$(ckstep inplace.h5.part)
[ $status -eq 5 ] || fail "in place: the resumed run stopped by SIGTERM: exit $status, expected 5"
[ "$s2" -gt "$s1" ] || fail "in place: after the second stop the .part's checkpoint is at step $s2, not after $s1"
[ -z "$(leftovers inplace)" ] || [ "$(leftovers inplace)" = "inplace.h5.part " ] ||
    fail "in place: after the second stop expected inplace.h5.part alone, found $(leftovers inplace)"
grep -q -F -- "inplace.nml --resume" inplace.err || fail "in place: the stop message names no --resume command: $(cat inplace.err)"
# killed by SIGKILL while resuming, after a checkpoint of its own (later than the .part's)
"$exe" inplace.nml --resume & pid=$!
for ((i = 0; i < 150; i++)); do
    s3=$(ckstep inplace.resume.h5.part); [ "$s3" -gt "$s2" ] && break; sleep 0.1
done
kill -s KILL $pid; wait $pid
s3=$(ckstep inplace.resume.h5.part)   # the last checkpoint before the kill
[ "$s3" -gt "$s2" ] || fail "in place: the resumed run wrote no checkpoint before SIGKILL (step $s3)"
# the wall seconds of the three runs so far, carried by the checkpoint into the resumed file's total
w3=$("$py" -c "
import h5py
f = h5py.File('inplace.resume.h5.part', 'r', swmr=True)
print(float(f['checkpoint/slot%d/run/scalars' % int(f['checkpoint/current'][0])]['wall_seconds']))")
t_end=$(awk -v n="$((s3 + 3000))" 'BEGIN { printf "%.4f", n * 1e-4 }')
if "$exe" inplace.nml --set time.t_end="$t_end" --resume; then
    make_input inplace_ref.nml inplace_ref "$t_end" && sed -i 's/quiet=.true./quiet=.true. checkpoint_every=250/' inplace_ref.nml
    "$exe" inplace_ref.nml || fail "in place: reference run exit $?"
    if out=$("$py" "$src/tests/tools/regression.py" same inplace_ref.h5 inplace.h5); then
        echo "PASS in place: stopped twice, killed once, resumed with --resume = uninterrupted, bit for bit ($out)"
    else fail "in place: the resumed run differs from the uninterrupted one:"; echo "$out"; fi
    [ -z "$(leftovers inplace)" ] && echo "PASS in place: no .part left" ||
        fail "in place: files left beside inplace.h5: $(leftovers inplace)"
    rs=$("$py" -c "import h5py; print(int(h5py.File('inplace.h5', 'r').attrs['restart_step']))")
    [ "$rs" = "$s3" ] || fail "in place: resumed from step $rs, expected the killed resumed run's checkpoint $s3"
    wall=$("$py" -c "import h5py; print(float(h5py.File('inplace.h5', 'r').attrs['wall_seconds']))")
    awk -v w="$wall" -v w3="$w3" 'BEGIN { exit !(w > w3 && w3 > 0) }' &&
        echo "PASS in place: wall_seconds $wall counts the runs before the resume ($w3 s up to its checkpoint)" ||
        fail "in place: wall_seconds $wall does not count the $w3 s of the runs before the resume"
else
    fail "in place: the last --resume exit $?"
fi

echo "test_signal: $failures failed"
[ $failures -eq 0 ]
