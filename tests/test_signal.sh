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

# start <sig> <name>: run <name>.nml in the background and send SIG<sig> in its time loop;
# with <sig> = PENDING_TERM, start it with SIGTERM blocked and already pending
start() {
    if [ "$1" = PENDING_TERM ]; then
        "$py" -c "
import os, signal, sys
signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGTERM})
os.kill(os.getpid(), signal.SIGTERM)
os.execv(sys.argv[1], sys.argv[1:])" "$exe" $2.nml
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

echo "test_signal: $failures failed"
[ $failures -eq 0 ]
