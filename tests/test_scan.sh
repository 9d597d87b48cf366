#!/usr/bin/env bash
# scripts/scan.sh: --list, the checks before any run (unknown variable, malformed range,
# a value that does not parse or is out of range, a bad combination: exit 2 naming the axis
# or the point, nothing run), --task and --batch (the path of a Slurm array task), --array,
# a parallel run under GNU parallel that is interrupted and resumed, the collector's CSV
# (every point exactly once, with a status), points that fail at run time with bad input
# (exit 2) and numerically (exit 3) recorded with their messages, and the refusal to mix two
# scans in one directory.
#
#   bash tests/test_scan.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 all passed, 1 a check failed, 77 skipped (no program, or no GNU parallel
# outside CI).
set -u

prog=${1:-}
src=${2:-}
scratch=${3:-}
if [[ -z "$prog" || ! -x "$prog" ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
if ! parallel --version 2> /dev/null | grep -q '^GNU parallel'; then
    # scripts/setup.sh installs it (Debian package parallel): in CI its absence is a failure
    [[ -n ${CI:-} ]] && { echo "FAIL: GNU parallel not found (scripts/setup.sh should have installed it)"; exit 1; }
    echo "SKIP: scripts/scan.sh needs GNU parallel (apt-get install parallel, or scripts/setup.sh)"
    exit 77
fi
[[ -n "$scratch" ]] || scratch=$(mktemp -d)
mkdir -p "$scratch" && cd "$scratch" || exit 1
scan="$src/scripts/scan.sh"
export RODCONTACT=$prog

. "$src/tests/lib/checks.sh"   # check, equals, n_checks, n_failed, wait_in_time_loop

# 3 x 2 points of experiment 2 at its own mesh and time step, t_end = 0.6 (contact at
# t ~ 0.3 for amplitude 20): ~0.2-0.5 s per point.
# names unique to this test process: the "no run left behind" checks look for runs by their
# command line, which must not match the runs of another test_scan running at the same time
dir=myscan_$$
rm -rf "$dir" scan_*.log bad_*
args=("$src/input/exp2.nml" --set model.varpi=0.1,0.5,1
      --set 'initial.theta0_step(1)+initial.p0_step(1)=5:20:2'
      --set time.t_end=0.6 --set output.snapshot_every=1000 --set output.series_every=10)

# --- --list: one line per point, the last axis fastest
list=$(bash "$scan" "${args[@]}" --list)
check "--list prints 6 points" equals 6 "$(wc -l <<< "$list")"
check "--list point 0" equals \
    "0000 --set model.varpi=0.1 --set 'initial.theta0_step(1)=5' --set 'initial.p0_step(1)=5' --set time.t_end=0.6 --set output.snapshot_every=1000 --set output.series_every=10" \
    "$(sed -n 1p <<< "$list")"
check "--list point 5" equals "0005 --set model.varpi=1 --set 'initial.theta0_step(1)=20' --set 'initial.p0_step(1)=20'" \
    "$(sed -n 6p <<< "$list" | cut -d' ' -f1-7)"
check "a:b:n:log range" equals "0.01 0.1 1" \
    "$(bash "$scan" "$src/input/exp2.nml" --set model.varpi=0.01:1:3:log --list | awk '{sub(/.*=/, "", $3); printf "%s%s", (NR > 1 ? " " : ""), $3}')"
check "a;b list of whole arrays" equals "initial.theta0_step=5,0.1 initial.theta0_step=10,0.2" \
    "$(bash "$scan" "$src/input/exp2.nml" --set 'initial.theta0_step=5,0.1;10,0.2' --list | awk '{printf "%s%s", (NR > 1 ? " " : ""), $3}')"

# --- the checks before any run: exit 2 naming the axis (or the point), nothing run
refused() {   # refused <dir> <expected message part> <scan arguments ...>
    local d=$1 part=$2 status
    shift 2
    bash "$scan" "$@" --out "$d" 2> "scan_$d.log"
    status=$?
    [[ $status == 2 ]] || { echo "  exit status $status, expected 2"; return 1; }
    grep -q -F -- "$part" "scan_$d.log" || { echo "  no '$part' in: $(cat "scan_$d.log")"; return 1; }
    ! ls "$d"/point_* > /dev/null 2>&1 || { echo "  point files written: $(ls "$d")"; return 1; }
    [[ ! -f $d/points.txt ]] || { echo "  $d/points.txt written"; return 1; }
}
e2=$src/input/exp2.nml
check "unknown variable: exit 2 naming the axis" \
    refused bad_name "is not valid input: error in --set model.varpii: unknown variable 'varpii' in &model" \
    "$e2" --set time.t_end=0.2 --set model.varpii=0.1,0.2
check "unknown variable: the message names the axis" \
    refused bad_name "axis --set 'model.varpii=0.1,0.2': value '0." \
    "$e2" --set time.t_end=0.2 --set model.varpii=0.1,0.2
check "malformed range: exit 2 naming the axis" \
    refused bad_range "--set 'model.varpi=0.1:1:x': '0.1:1:x' is not a range a:b:n" "$e2" --set model.varpi=0.1:1:x
check "range inside a list: exit 2 naming the axis" \
    refused bad_list "--set 'model.varpi=0:1:3,5': '0:1:3,5' is not a range" "$e2" --set model.varpi=0:1:3,5
check "a value that does not parse: exit 2 naming the axis and the value" \
    refused bad_parse "axis --set 'model.varpi=0.1,abc': value 'abc' (point 1)" "$e2" --set model.varpi=0.1,abc
check "a value out of range at the last point: exit 2 naming the axis" \
    refused bad_value "axis --set 'model.varpi=0.1,0.5,-1': value '-1' (point " \
    "${args[@]/#model.varpi=0.1,0.5,1/model.varpi=0.1,0.5,-1}"
check "a value out of range: the message says why" \
    grep -q -F "is not valid input: error in model.varpi: got -1; must be >= 0; nothing was run" scan_bad_value.log
check "a bad combination of two axes' values: exit 2 naming the axis the message names" \
    refused bad_pair "axis --set 'model.d=0,0.00251': value '0.00251' (point 3) is not valid input: error in model.d: got d = 0.00251 with c = 0.001" \
    "$e2" --set model.c=1,0.001 --set model.d=0,0.00251
check "a bad value whose message names no axis: exit 2 naming the point" \
    refused bad_point "point 1 (--set model.c=0.001 --set time.t_end=0.2) is not valid input: error in model.d" \
    "$e2" --set model.c=1,0.001 --set time.t_end=0.2
check "a bad subscript: exit 2 naming the axis" \
    refused bad_index "axis --set 'initial.theta0_step(3)=1'" "$e2" --set 'initial.theta0_step(3)=1'

# --- --task T: what a Slurm array task runs (here one point per task)
bash "$scan" "${args[@]}" --out "$dir" --task 1 2> scan_task1.log
check "--task 1 exits 0" equals 0 "$?"
check "--task 1 wrote point_0001.h5" test -f "$dir/point_0001.h5"
stamp=$(stat -c %Y.%s "$dir/point_0001.h5")
bash "$scan" "${args[@]}" --out "$dir" --task 0001 2> scan_task1b.log
check "--task 1 again: skipped, file untouched" \
    bash -c "grep -q '1 already complete, 0 to run' scan_task1b.log && [[ \$(stat -c %Y.%s '$dir/point_0001.h5') == '$stamp' ]]"
bash "$scan" "${args[@]}" --out "$dir" --task 6 2> /dev/null
check "--task 6 (out of range) exits 2" equals 2 "$?"
bash "$scan" "${args[@]}" --out "$dir" --task 4 --task bad 2> /dev/null
check "--task bad exits 2" equals 2 "$?"

# --- --batch B --array: the task indices with points to run (task t = points tB .. tB+B-1)
check "--array --batch 4: tasks 0-1 (6 points, point 1 complete)" equals 0-1 \
    "$(bash "$scan" "${args[@]}" --out "$dir" --batch 4 --array 2> /dev/null)"
check "--array --batch 1: every task but 1" equals 0,2-5 \
    "$(bash "$scan" "${args[@]}" --out "$dir" --array 2> /dev/null)"
bash "$scan" "${args[@]}" --out "$dir" --batch 4 --task 2 2> /dev/null
check "--batch 4 --task 2 (out of range: 2 tasks) exits 2" equals 2 "$?"

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
    local left
    left=$(pgrep -a -f -- "[m]yscan_$$/point_") || return 0
    echo "  still running: $left"
    ps -eo pid,ppid,pgid,stat,etime,args --forest | grep -B4 -A1 "[m]yscan_$$/point"
    ls -l --time-style=+%T.%N "$dir"
    return 1
}
check "no run left behind after the interrupt" no_runs_left
n_done=$(ls "$dir"/point_*.h5 2> /dev/null | wc -l)
check "the interrupt came before the end (complete points: $n_done < 4)" test "$n_done" -lt 4
bash "$scan" "${args[@]}" --out "$dir" --collect 2> scan_collect1.log
check "CSV after the interrupt: 6 points, each once" equals "0 1 2 3 4 5" \
    "$(tail -n +2 "$dir/summary.csv" | cut -d, -f1 | tr '\n' ' ' | sed 's/ $//')"
check "CSV after the interrupt: some point not complete" grep -q -E ',(missing|interrupted),' "$dir/summary.csv"
# every point whose run was stopped (exit 5) kept the checkpoint its .err names
stopped_points_kept() {
    local st rc stem
    for st in "$dir"/point_*.status; do
        read -r rc < "$st"
        ((rc == 5)) || continue   # (> 128: killed before its handlers, no checkpoint)
        stem=${st%.status}
        [[ -f $stem.h5.part ]] || { echo "  $stem: exit 5 but no $stem.h5.part"; return 1; }
        grep -q -F -- "--set output.prefix=$stem --set output.quiet=.true. --resume" "$stem.err" ||
            { echo "  $stem.err names no command resuming $stem: $(cat "$stem.err")"; return 1; }
        grep -q "^$((10#${stem##*_})),.*,interrupted,5," "$dir/summary.csv" || { echo "  point ${stem##*_} not 'interrupted,5' in the CSV"; return 1; }
    done
}
check "the points stopped by the interrupt kept their checkpoints, named by their .err, 'interrupted' in the CSV" stopped_points_kept

# --- Ctrl-C: SIGINT to the whole process group, so the runs get it too (they ignore it:
# started with &), in a scan of its own: a new session, signalled once its first runs go.
# A job started with & here would ignore SIGINT, hence env --default-signal (coreutils >= 8.31).
if command -v setsid > /dev/null && env --default-signal=INT true 2> /dev/null; then
    cc=ctrlc_$$
    rm -rf "$cc"
    setsid env --default-signal=INT bash "$scan" "${args[@]}" --out "$cc" -j 2 2> scan_ctrlc.log &
    pid=$!
    for ((i = 0; i < 600; i++)); do
        [[ -f $cc/point_0000.err ]] && break
        sleep 0.02
    done
    sleep 0.05
    kill -INT -- "-$pid"
    wait "$pid"
    check "Ctrl-C (INT to the process group): exit 130" equals 130 "$?"
    no_ctrlc_runs_left() { ! pgrep -f -- "[c]trlc_$$/point_" > /dev/null; }
    check "no run left behind after Ctrl-C" no_ctrlc_runs_left
    # a .part is left only by a run stopped cleanly (exit 5: checkpoint written), or killed by
    # the signal before its handlers were installed (exit > 128: resumed from t = 0)
    check "Ctrl-C: a .part only for a point recorded as stopped by the signal" bash -c '
        for part in "$1"/*.h5.part; do [[ -e $part ]] || continue; rc=$(head -n 1 "${part%.h5.part}.status"); ((rc == 5 || rc > 128)) || exit 1; done' _ "$cc"
    m=$(printf '%o' $((0666 & ~$(umask))))
    check "the scan's files have the mode of the umask ($(umask))" equals "$m $m $m" \
        "$(stat -c %a "$cc/input.nml" "$cc/points.txt" "$dir/summary.csv" 2> /dev/null | tr '\n' ' ' | sed 's/ $//')"
fi
n_done=$(ls "$dir"/point_*.h5 2> /dev/null | wc -l)

# --- resume: only what is not complete runs; failed points are run again and recorded
bash "$scan" "${args[@]}" --out "$dir" -j 2 2> scan_run2.log
status=$?
check "resumed scan exits 0" equals 0 "$status"
check "resumed scan skipped the complete points" grep -q "6 points in $dir/, $n_done already complete, $((6 - n_done)) to run" scan_run2.log
csv="$dir/summary.csv"
check "CSV header" equals \
    "point,model.varpi,initial.theta0_step(1),initial.p0_step(1),time.t_end,output.snapshot_every,output.series_every,status,exit_status,file,contact" \
    "$(head -n 1 "$csv" | cut -d, -f1-11)"
check "CSV: every point exactly once" equals "0 1 2 3 4 5" \
    "$(tail -n +2 "$csv" | cut -d, -f1 | tr '\n' ' ' | sed 's/ $//')"
check "CSV: every row has a status" equals 6 "$(tail -n +2 "$csv" | cut -d, -f8 | grep -c -E '^(complete|failed: .+|missing|interrupted)$')"
check "CSV: every point complete with exit status 0" equals "complete,0 complete,0 complete,0 complete,0 complete,0 complete,0" \
    "$(tail -n +2 "$csv" | cut -d, -f8,9 | tr '\n' ' ' | sed 's/ $//')"
check "CSV: contact only for varpi = 0.1, amplitude 20 (paper: 20 contact, 5 none)" equals "no yes no no no no" \
    "$(tail -n +2 "$csv" | cut -d, -f11 | tr '\n' ' ' | sed 's/ $//')"
check "GNU parallel's job log: one line per point run, exit value 0" equals "$((6 - n_done)) 0" \
    "$(tail -n +2 "$dir/joblog" | wc -l) $(tail -n +2 "$dir/joblog" | cut -f7 | sort -u | tr '\n' ' ' | sed 's/ $//')"

# --- a rerun runs nothing
bash "$scan" "${args[@]}" --out "$dir" -j 2 2> scan_run3.log
check "rerun: 6 already complete, 0 to run, exit 0" \
    bash -c "grep -q '6 already complete, 0 to run' scan_run3.log && ! grep -q failed: '$csv'"

# --- one point interrupted mid-run and resumed: it continues from its checkpoint (fewer steps
# in the resumed run: root attribute restart_step) and its /snapshots equal those of the same
# point run without interruption, bit for bit. The scan is stopped once the point's .part has
# grown after its first flush: the run is then in its time loop, where a signal stops it
# cleanly (before it, the signal would come before rodcontact's handlers).
rs=resume
rm -rf "$rs"
rs_args=("$src/input/exp2.nml" --set time.t_end=3 --set output.snapshot_every=500 --set output.series_every=10
         --set model.varpi=0.1)
bash "$scan" "${rs_args[@]}" --out "$rs" -j 1 2> scan_resume1.log &
pid=$!
wait_in_time_loop "$rs/point_0000.h5.part"
# a second scan into the same directory while this one runs: refused at once, naming it
bash "$scan" "${rs_args[@]}" --out "$rs" -j 1 2> scan_locked.log
status=$?
check "a second scan into a running scan's directory: exit 2" equals 2 "$status"
check "a second scan into a running scan's directory: names the running scan (pid $pid)" \
    grep -q "another scan is running in '$rs' (pid $pid on " scan_locked.log
kill -TERM "$pid"
wait "$pid"
check "scan stopped while its point runs: exit 143" equals 143 "$?"
check "the stopped point: exit 5 recorded, its checkpoint kept" \
    bash -c "[[ \$(head -n 1 $rs/point_0000.status) == 5 && -f $rs/point_0000.h5.part && ! -f $rs/point_0000.h5 ]]"
check "the stopped point's .err names the command that resumes it" \
    grep -q -F -- "--set output.prefix=$rs/point_0000 --set output.quiet=.true. --resume" "$rs/point_0000.err"
bash "$scan" "${rs_args[@]}" --out "$rs" -j 1 2> scan_resume2.log
check "resume: exit 0" equals 0 "$?"
check "resume: the scan says the point continues from its checkpoint" \
    grep -q -F "0 already complete, 1 to run (1 of them continue from their checkpoints)" scan_resume2.log
check "resume: the point complete, no .part or .resume left" \
    bash -c "grep -q '^0,.*,complete,0,' $rs/summary.csv && ! ls $rs/*.part $rs/*.resume 2> /dev/null"
if py=$("$src/scripts/lib/find_python.sh" 2> /dev/null); then
    "$prog" "${rs_args[@]}" --set output.prefix=uninterrupted --set output.quiet=.true.
    check "resume: restarted from its checkpoint (0 < restart_step < steps) and /snapshots bit for bit those of an uninterrupted run" \
        "$py" - "$rs/point_0000.h5" uninterrupted.h5 << 'EOF'
import sys
import h5py
with h5py.File(sys.argv[1], "r") as a, h5py.File(sys.argv[2], "r") as b:
    rs, steps = int(a.attrs.get("restart_step", 0)), int(a.attrs["steps"])
    print(f"  resumed at step {rs} of {steps}")
    ok = 0 < rs < steps and steps == int(b.attrs["steps"])
    for name in b["snapshots"]:
        x, y = a["snapshots"][name][...], b["snapshots"][name][...]
        same = x.shape == y.shape and x.dtype == y.dtype and x.tobytes() == y.tobytes()
        if not same:
            print(f"  /snapshots/{name} differs")
        ok = ok and same
sys.exit(0 if ok else 1)
EOF
fi

# --- a point whose run alone is stopped by a signal (killed by hand, not the scan): recorded
# as interrupted with its checkpoint, and the scan exits 5 (a Slurm task so ends FAILED, not
# COMPLETED); the rerun continues it
kd=killed_$$
rm -rf "$kd"
bash "$scan" "${rs_args[@]}" --out "$kd" -j 1 2> scan_killed.log &
pid=$!
wait_in_time_loop "$kd/point_0000.h5.part"
run_pid=$(pgrep -f -- "[k]illed_$$/point_0000 --set output.quiet")
kill -TERM $run_pid
wait "$pid"
check "the run of a point killed by hand: the scan exits 5" equals 5 "$?"
check "the run of a point killed by hand: 'interrupted' in the CSV, its checkpoint kept" \
    bash -c "grep -q '^0,.*,interrupted,5,' $kd/summary.csv && [[ -f $kd/point_0000.h5.part ]]"
bash "$scan" "${rs_args[@]}" --out "$kd" -j 1 2> scan_killed2.log
check "the point killed by hand: the rerun completes it" equals 0 "$?"

# --- --slurm with a stand-in sbatch (the real one: tests/test_slurm.sh): the array and the
# collect job submitted in one go; the collect job's --wrap, run by /bin/sh as Slurm does,
# collects (a target with '(' in it: an unquoted one is a syntax error in sh)
mkdir -p fakebin
cat > fakebin/sbatch << 'EOF'
#!/usr/bin/env bash
n=$(($(cat sbatch.n 2> /dev/null || echo 0) + 1))
echo "$n" > sbatch.n
printf '%s\n' "$@" > "sbatch.$n.args"
echo "$((100 + n))"
EOF
chmod +x fakebin/sbatch
rm -rf sbatch.* slurmscan
PATH=$PWD/fakebin:$PATH bash "$scan" "${args[@]}" --out slurmscan --batch 4 --slurm --partition=p1 %2 > scan_slurm.out 2> scan_slurm.log
check "--slurm: exit 0, both job ids printed" \
    bash -c "grep -q '^submitted the array: job 101, tasks 0-1%2' scan_slurm.out && grep -q '^submitted the collect job: job 102, after the array ends' scan_slurm.out"
check "--slurm: the array's sbatch options (throttle, logs in DIR/slurm, the template, its options)" \
    bash -c "grep -qx -- '--array=0-1%2' sbatch.1.args && grep -qx -- '--output=$PWD/slurmscan/slurm/%x-%A_%a.out' sbatch.1.args && grep -qx -- '--partition=p1' sbatch.1.args && grep -q 'scripts/slurm/scan_array.sbatch$' sbatch.1.args"
check "--slurm: the collect job depends on the array" grep -qx -- '--dependency=afterany:101' sbatch.2.args
rm -f "slurmscan/summary.csv"
sh -c "$(sed -n '/^--wrap$/{n;p;}' sbatch.2.args)" 2> scan_wrap.log
check "--slurm: the collect job's --wrap runs in /bin/sh and writes DIR/summary.csv" \
    bash -c "[[ -s slurmscan/summary.csv ]] && grep -q 'summary.csv: 6 points' scan_wrap.log"

# --- bad input found only at run time (a restart file that does not exist: --check does not
# open files): the point is recorded as failed with exit status 2 and the message
rt=rtscan
rm -rf "$rt"
bash "$scan" "$e2" --set time.t_end=0.2 --set "time.restart_from=none.h5;''" --out "$rt" -j 2 2> scan_rt.log
check "a point that fails at run time: scan exits 1" equals 1 "$?"
check "a point that fails at run time: recorded with exit status 2 and the message" \
    grep -q "^0,0.2,none.h5,failed: exit 2: error in time.restart_from: got 'none.h5': no such file.*,2,,,," "$rt/summary.csv"
check "a point that fails at run time: the other point is complete" grep -q "^1,0.2,'',complete,0," "$rt/summary.csv"
check "a point that fails at run time: its line on stderr" grep -q "scan: point 0000 failed (exit 2): rodcontact: error in time.restart_from" scan_rt.log

# --- another scan into the same directory is refused
bash "$scan" "$src/input/exp2.nml" --set model.varpi=0.2,0.3 --out "$dir" 2> scan_other.log
status=$?
check "another scan in the same directory: exit 2" equals 2 "$status"
check "another scan in the same directory: says so" grep -q "holds a scan with another list of points" scan_other.log

# --- a numerical failure (exit 3): the paper iteration on a coarse mesh, after the contact
# at t ~ 0.30 (step 303); the .h5 holds the steps before it and its status is the CSV status
num=numscan
rm -rf "$num"
bash "$scan" "$src/input/exp2.nml" --set solver.method=paper,monolithic --set mesh.n_elements=50 \
    --set time.dt=1e-3 --set time.t_end=0.35 --out "$num" -j 2 2> scan_num.log
check "numerical failure: scan exits 1" equals 1 "$?"
check "numerical failure: exit status 3 and the h5 status" \
    grep -q '^0,paper,50,1e-3,0.35,"\{0,1\}failed: step [0-9]* (t = .*did not converge.*,3,numscan/point_0000.h5,' "$num/summary.csv"
check "numerical failure: the other point is complete" grep -q '^1,monolithic,50,1e-3,0.35,complete,0,' "$num/summary.csv"

echo "test_scan: $n_checks checks, $n_failed failed"
if ((n_failed > 0)); then
    for log in scan_*.log; do
        echo "--- $log"
        cat "$log"
    done
    exit 1
fi
