#!/usr/bin/env bash
# scripts/scan.sh: --list, --task (the path of a Slurm array task), a parallel run that is
# interrupted and resumed, the collector's CSV (every point exactly once, with a status),
# points that fail with bad input (exit 2) and numerically (exit 3) recorded with their
# messages, and the refusal to mix two scans in one directory.
#
#   bash tests/test_scan.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 all passed, 1 a check failed, 77 skipped (no program).
set -u

prog=${1:-}
src=${2:-}
scratch=${3:-}
if [[ -z "$prog" || ! -x "$prog" ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
if ((BASH_VERSINFO[0] < 5 || (BASH_VERSINFO[0] == 5 && BASH_VERSINFO[1] < 1))); then
    echo "SKIP: scripts/scan.sh needs bash >= 5.1 for parallel runs, this is $BASH_VERSION"
    exit 77
fi
[[ -n "$scratch" ]] || scratch=$(mktemp -d)
mkdir -p "$scratch" && cd "$scratch" || exit 1
scan="$src/scripts/scan.sh"
export RODCONTACT=$prog

n_checks=0
n_failed=0
check() {   # check <description> <command ...>: the command must succeed
    local what=$1
    shift
    n_checks=$((n_checks + 1))
    if "$@"; then
        echo "PASS $what"
    else
        n_failed=$((n_failed + 1))
        echo "FAIL $what"
    fi
}
equals() {  # equals <expected> <got>
    [[ "$1" == "$2" ]] && return 0
    echo "  expected: $1"
    echo "  got:      $2"
    return 1
}

# 3 x 2 points of experiment 2 at its own mesh and time step, t_end = 0.6 (contact at
# t ~ 0.3 for amplitude 20): ~0.2-0.5 s per point. varpi = -1 is bad input (2 points).
dir=myscan
rm -rf "$dir" scan_*.log
args=("$src/input/exp2.nml" --set model.varpi=0.1,0.5,-1
      --set 'initial.theta0_step(1)+initial.p0_step(1)=5:20:2'
      --set time.t_end=0.6 --set output.snapshot_every=1000 --set output.series_every=10)

# --- --list: one line per point, the last axis fastest
list=$(bash "$scan" "${args[@]}" --list)
check "--list prints 6 points" equals 6 "$(wc -l <<< "$list")"
check "--list point 0" equals \
    "0000 --set model.varpi=0.1 --set 'initial.theta0_step(1)=5' --set 'initial.p0_step(1)=5' --set time.t_end=0.6 --set output.snapshot_every=1000 --set output.series_every=10" \
    "$(sed -n 1p <<< "$list")"
check "--list point 5" equals "0005 --set model.varpi=-1 --set 'initial.theta0_step(1)=20' --set 'initial.p0_step(1)=20'" \
    "$(sed -n 6p <<< "$list" | cut -d' ' -f1-7)"
check "a:b:n:log range" equals "0.01 0.1 1" \
    "$(bash "$scan" "$src/input/exp2.nml" --set model.varpi=0.01:1:3:log --list | awk '{sub(/.*=/, "", $3); printf "%s%s", (NR > 1 ? " " : ""), $3}')"
check "a;b list of whole arrays" equals "initial.theta0_step=5,0.1 initial.theta0_step=10,0.2" \
    "$(bash "$scan" "$src/input/exp2.nml" --set 'initial.theta0_step=5,0.1;10,0.2' --list | awk '{printf "%s%s", (NR > 1 ? " " : ""), $3}')"

# --- --task K: what a Slurm array task runs
bash "$scan" "${args[@]}" --out "$dir" --task 4 2> scan_task4.log
check "--task 4 (varpi = -1) exits 2" equals 2 "$?"
check "--task 4 recorded exit status 2" equals 2 "$(sed -n 1p "$dir/point_0004.status")"
check "--task 4 recorded the message" equals "rodcontact: error in model.varpi: got -1; must be >= 0" \
    "$(sed -n 2p "$dir/point_0004.status")"
bash "$scan" "${args[@]}" --out "$dir" --task 1 2> scan_task1.log
check "--task 1 exits 0" equals 0 "$?"
check "--task 1 wrote point_0001.h5" test -f "$dir/point_0001.h5"
stamp=$(stat -c %Y.%s "$dir/point_0001.h5")
bash "$scan" "${args[@]}" --out "$dir" --task 0001 2> scan_task1b.log
check "--task 1 again: skipped, file untouched" \
    bash -c "grep -q 'already complete' scan_task1b.log && [[ \$(stat -c %Y.%s '$dir/point_0001.h5') == '$stamp' ]]"
bash "$scan" "${args[@]}" --out "$dir" --task 6 2> /dev/null
check "--task 6 (out of range) exits 2" equals 2 "$?"

# --- a parallel run, interrupted while point 3 runs (it starts when point 0 or 2 is done)
bash "$scan" "${args[@]}" --out "$dir" -j 2 2> scan_run1.log &
pid=$!
for ((i = 0; i < 600; i++)); do
    [[ -f $dir/point_0003.err ]] && break
    sleep 0.02
done
kill -TERM "$pid"
wait "$pid"
status=$?
check "interrupted scan exits 143" equals 143 "$status"
check "interrupted scan says how to resume" grep -q 'rerun the same command to resume' scan_run1.log
# checked at once: the scan stops its runs before it exits
no_runs_left() {   # no rodcontact of this scan still running ([m]: pgrep must not match itself)
    ! pgrep -f -- "[m]yscan/point_" > /dev/null
}
check "no run left behind after the interrupt" no_runs_left
n_done=$(ls "$dir"/point_*.h5 2> /dev/null | wc -l)
check "the interrupt came before the end (complete points: $n_done < 4)" test "$n_done" -lt 4
bash "$scan" "${args[@]}" --out "$dir" --collect 2> scan_collect1.log
check "CSV after the interrupt: 6 points, each once" equals "0 1 2 3 4 5" \
    "$(tail -n +2 "$dir/summary.csv" | cut -d, -f1 | tr '\n' ' ' | sed 's/ $//')"
check "CSV after the interrupt: some point missing" grep -q ',missing,' "$dir/summary.csv"

# --- Ctrl-C: SIGINT to the whole process group, so the runs get it too (they ignore it:
# started with &), in a scan of its own: a new session, signalled once its first runs go.
# A job started with & here would ignore SIGINT, hence env --default-signal (coreutils >= 8.31).
if command -v setsid > /dev/null && env --default-signal=INT true 2> /dev/null; then
    rm -rf ctrlc
    setsid env --default-signal=INT bash "$scan" "${args[@]}" --out ctrlc -j 2 2> scan_ctrlc.log &
    pid=$!
    for ((i = 0; i < 600; i++)); do
        [[ -f ctrlc/point_0000.err ]] && break
        sleep 0.02
    done
    sleep 0.05
    kill -INT -- "-$pid"
    wait "$pid"
    check "Ctrl-C (INT to the process group): exit 130" equals 130 "$?"
    no_ctrlc_runs_left() { ! pgrep -f -- "[c]trlc/point_" > /dev/null; }
    check "no run left behind after Ctrl-C" no_ctrlc_runs_left
    check "no .part left behind after Ctrl-C" bash -c "! ls ctrlc/*.h5.part 2> /dev/null"
fi
n_done=$(ls "$dir"/point_*.h5 2> /dev/null | wc -l)

# --- resume: only what is not complete runs; failed points are run again and recorded
bash "$scan" "${args[@]}" --out "$dir" -j 2 2> scan_run2.log
status=$?
check "resumed scan exits 1 (failed points)" equals 1 "$status"
check "resumed scan skipped the complete points" grep -q "6 points in $dir/, $n_done already complete, $((6 - n_done)) to run" scan_run2.log
csv="$dir/summary.csv"
check "CSV header" equals \
    "point,model.varpi,initial.theta0_step(1),initial.p0_step(1),time.t_end,output.snapshot_every,output.series_every,status,exit_status,file,contact" \
    "$(head -n 1 "$csv" | cut -d, -f1-11)"
check "CSV: every point exactly once" equals "0 1 2 3 4 5" \
    "$(tail -n +2 "$csv" | cut -d, -f1 | tr '\n' ' ' | sed 's/ $//')"
check "CSV: every row has a status" equals 6 "$(tail -n +2 "$csv" | cut -d, -f8 | grep -c -E '^(complete|failed: .+|missing)$')"
check "CSV: points 0-3 complete with exit status 0" equals "complete,0 complete,0 complete,0 complete,0" \
    "$(sed -n '2,5p' "$csv" | cut -d, -f8,9 | tr '\n' ' ' | sed 's/ $//')"
check "CSV: points 4, 5 failed with exit status 2 and the message" equals \
    "failed: exit 2: error in model.varpi: got -1; must be >= 0,2 failed: exit 2: error in model.varpi: got -1; must be >= 0,2" \
    "$(sed -n '6,7p' "$csv" | cut -d, -f8,9 | tr '\n' ' ' | sed 's/ $//')"
check "CSV: contact only for varpi = 0.1, amplitude 20 (paper: 20 contact, 5 none)" equals "no yes no no" \
    "$(sed -n '2,5p' "$csv" | cut -d, -f11 | tr '\n' ' ' | sed 's/ $//')"
check "CSV: the failed points have empty summary fields" equals ",,,,,,,,,,,,,,,," \
    "$(sed -n 6p "$csv" | cut -d, -f10-)"

# --- a rerun runs only the failed points
bash "$scan" "${args[@]}" --out "$dir" -j 2 2> scan_run3.log
check "rerun: 4 already complete, the 2 failed ones run again" grep -q "4 already complete, 2 to run" scan_run3.log

# --- another scan into the same directory is refused
bash "$scan" "$src/input/exp2.nml" --set model.varpi=0.2,0.3 --out "$dir" 2> scan_other.log
status=$?
check "another scan in the same directory: exit 2" equals 2 "$status"
check "another scan in the same directory: says so" grep -q "holds a scan with another list of points" scan_other.log

# --- a numerical failure (exit 3): the paper iteration on a coarse mesh; the .h5 holds
# the steps before it and its status is the CSV status
num=numscan
rm -rf "$num"
bash "$scan" "$src/input/exp2.nml" --set solver.method=paper,monolithic --set mesh.n_elements=50 \
    --set time.dt=1e-3 --set time.t_end=0.3 --out "$num" -j 2 2> scan_num.log
check "numerical failure: scan exits 1" equals 1 "$?"
check "numerical failure: exit status 3 and the h5 status" \
    grep -q '^0,paper,50,1e-3,0.3,"\{0,1\}failed: step [0-9]* (t = .*did not converge.*,3,numscan/point_0000.h5,' "$num/summary.csv"
check "numerical failure: the other point is complete" grep -q '^1,monolithic,50,1e-3,0.3,complete,0,' "$num/summary.csv"

echo "test_scan: $n_checks checks, $n_failed failed"
if ((n_failed > 0)); then
    for log in scan_*.log; do
        echo "--- $log"
        cat "$log"
    done
    exit 1
fi
