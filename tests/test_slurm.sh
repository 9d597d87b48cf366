#!/usr/bin/env bash
# scripts/slurm/scan_array.sbatch on a real one-node Slurm cluster, started for this test only:
# munged, slurmctld and slurmd on this host, over the loopback address, with their keys,
# sockets, spool and logs in a temporary directory. A 6-point scan (3 array tasks of 2 points,
# one task at a time: %1) is submitted; one point fails numerically (recorded, its task still
# completes); one task is sent SIGTERM while it runs (what --signal=B:TERM sends before the
# time limit) and leaves its points resumable; the resubmission of what --array prints runs
# only the points that are not complete; the collected summary.csv equals the same scan run
# locally with scripts/scan.sh (every column but wall_seconds). Every daemon is stopped by its
# pid at the end, also on failure.
#
#   bash tests/test_slurm.sh <path to rodcontact> <source dir> <scratch dir>
# Needs root and the Debian packages slurm-wlm, munge, parallel (installed here when missing).
# Exit status: 0 passed, 1 a check failed, 77 skipped (no program; not root, not Debian, or the
# packages could not be installed, outside CI: with CI set those fail).
set -u

prog=${1:-}
src=${2:-}
scratch=${3:-}
t_test=$(date +%s.%N)
skip() {   # skip MESSAGE: exit 77, or fail in CI, where this test must run
    if [[ -n ${CI:-} ]]; then
        echo "FAIL (CI must run this test): $*"
        exit 1
    fi
    echo "SKIP: $*"
    exit 77
}
if [[ -z $prog || ! -x $prog ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
[[ $(id -u) == 0 ]] || skip "needs root to start munged, slurmctld and slurmd (this is uid $(id -u))"
[[ -n "$scratch" ]] || scratch=$(mktemp -d)
mkdir -p "$scratch" && cd "$scratch" || exit 1
scratch=$(pwd)
prog=$(cd "$(dirname "$prog")" && pwd)/$(basename "$prog")
scan="$src/scripts/scan.sh"
sbatch_script="$src/scripts/slurm/scan_array.sbatch"

# ---------------------------------------------------------------- packages
have_all() {
    local c
    for c in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel; do
        command -v "$c" > /dev/null || PATH=$PATH:/usr/sbin command -v "$c" > /dev/null || return 1
    done
    parallel --version 2> /dev/null | grep -q '^GNU parallel'
}
export PATH=$PATH:/usr/sbin:/sbin
if ! have_all; then
    command -v apt-get > /dev/null || skip "slurm-wlm, munge or GNU parallel missing and no apt-get (not Debian)"
    echo "installing the Debian packages slurm-wlm munge parallel (log: $scratch/apt.log)"
    { DEBIAN_FRONTEND=noninteractive apt-get update -q &&
      DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm munge parallel; } > apt.log 2>&1 ||
        { tail -n 20 apt.log; skip "could not install slurm-wlm munge parallel (apt.log above)"; }
    have_all || skip "slurm-wlm, munge and parallel installed, but a command is still missing"
fi

. "$src/tests/lib/checks.sh"   # check, equals, n_checks, n_failed
elapsed() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$1" "$(date +%s.%N)"; }

# ---------------------------------------------------------------- the cluster
# Everything in a temporary directory outside the scratch directory (munged's socket path
# must be short); its logs are copied to the scratch directory at the end.
cluster=$(mktemp -d "${TMPDIR:-/tmp}/rodcontact-slurm.XXXXXX") || exit 1
# munged refuses a socket in a directory that not everyone can search
chmod 755 "$cluster"
mkdir -p "$cluster/munge" "$cluster/ctld" "$cluster/d" "$cluster/log"
pids=()
stop_cluster() {   # every daemon started here, by pid: TERM, then KILL after 10 s
    local pid i
    trap '' INT TERM
    ((${#pids[@]} > 0)) || return 0
    # jobs still running (after a failure): cancelled while slurmctld is there to do it
    [[ -n ${SLURM_CONF:-} ]] && timeout 10 scancel --quiet --name=rodcontact-scan > /dev/null 2>&1
    [[ -n ${SLURM_CONF:-} ]] && timeout 10 scancel --quiet --name=rodcontact-collect > /dev/null 2>&1
    # slurmd, slurmctld, then munged (the last started first)
    for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
        kill -TERM "${pids[i]}" 2> /dev/null
    done
    for pid in "${pids[@]}"; do
        for ((i = 0; i < 100; i++)); do
            kill -0 "$pid" 2> /dev/null || break
            sleep 0.1
        done
        kill -KILL "$pid" 2> /dev/null
        wait "$pid" 2> /dev/null
    done
    pids=()
    cp -r "$cluster/log" "$scratch/cluster-logs" 2> /dev/null
    cp "$cluster/slurm.conf" "$scratch/cluster-logs/" 2> /dev/null
    rm -rf "$cluster"
}
trap stop_cluster EXIT
trap 'exit 1' INT TERM

# two free TCP ports on the loopback address (no listener answers there)
port_free() { ! (exec 3<> "/dev/tcp/127.0.0.1/$1") 2> /dev/null; }
for ((i = 0; i < 50; i++)); do
    port=$((20000 + RANDOM % 20000))
    port_free "$port" && port_free $((port + 1)) && break
done

t_start=$(date +%s.%N)
mungekey --create --keyfile="$cluster/munge/munge.key" > /dev/null 2>&1 ||
    dd if=/dev/urandom of="$cluster/munge/munge.key" bs=1024 count=1 status=none
chmod 600 "$cluster/munge/munge.key"
munged --foreground --key-file="$cluster/munge/munge.key" --socket="$cluster/munge/munge.socket" \
       --pid-file="$cluster/munge/munged.pid" --seed-file="$cluster/munge/munged.seed" \
       --log-file="$cluster/log/munged.log" > "$cluster/log/munged.out" 2>&1 &
pids=($!)
for ((i = 0; i < 100; i++)); do
    [[ -S $cluster/munge/munge.socket ]] && break
    sleep 0.05
done
[[ -S $cluster/munge/munge.socket ]] || { cat "$cluster/log/munged.out"; echo "FAIL munged did not start"; exit 1; }

# this host as the node, with the CPUs, sockets, cores and memory that slurmd finds
node=$(slurmd -C | head -n 1 | sed -e 's/^NodeName=[^ ]*//' -e 's/UpTime=.*//')
cat > "$cluster/slurm.conf" << EOF
ClusterName=rodtest$port
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$cluster/munge/munge.socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
KillWait=10
MinJobAge=600
StateSaveLocation=$cluster/ctld
SlurmdSpoolDir=$cluster/d
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
SlurmctldLogFile=$cluster/log/slurmctld.log
SlurmdLogFile=$cluster/log/slurmd.log
NodeName=localhost NodeAddr=127.0.0.1 $node State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$cluster/slurm.conf
slurmctld -D -f "$SLURM_CONF" > "$cluster/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N localhost -f "$SLURM_CONF" > "$cluster/log/slurmd.out" 2>&1 &
pids+=($!)
state=""
for ((i = 0; i < 300; i++)); do
    state=$(sinfo -h -n localhost -o %T 2> /dev/null)
    [[ $state == idle ]] && break
    sleep 0.1
done
t_up=$(elapsed "$t_start")
check "the one-node cluster is up: node idle (after $t_up s)" equals idle "$state"
if [[ $state != idle ]]; then
    tail -n 20 "$cluster"/log/*
    exit 1
fi
echo "cluster start-up (munged, slurmctld, slurmd until the node is idle): $t_up s"

# ---------------------------------------------------------------- the scan
# 3 x 2 points of experiment 2 on a coarse grid (h = 1/200, dt = 1e-3) to t = 16: about 1 s
# a point with the paper's iteration, 0.15 s monolithic; the paper's iteration fails to
# converge at varpi = 0.1 (point 0: exit 3, the steps before it in its .h5).
args=("$src/input/exp2.nml" --set model.varpi=0.1,0.3,1 --set solver.method=paper,monolithic
      --set mesh.n_elements=200 --set time.dt=1e-3 --set time.t_end=16
      --set output.snapshot_every=100000 --set output.series_every=10 --out scan)
export RODCONTACT=$prog RODCONTACT_ROOT=$src
py=$("$src/scripts/lib/find_python.sh") || exit 1

# the same scan locally, for the reference table
mkdir -p local cluster
(cd local && rm -rf scan && bash "$scan" "${args[@]}" -j 2 2> ../local.log)
check "local scan: exit 1 (point 0 fails numerically)" equals 1 "$?"

cd cluster || exit 1
rm -rf scan slurm-*.out
range=$(bash "$scan" "${args[@]}" --batch 2 --array 2> ../array1.log)
check "--array --batch 2: 3 tasks, 0-2" equals 0-2 "$range"

# statuses CSV: 'K:status' for every row of a summary.csv, the status up to its first ':'
statuses() {
    python3 -c 'import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(" ".join(r["point"] + ":" + r["status"].split(":")[0] for r in rows))' "$1"
}
# without_wall CSV: the summary.csv without its wall_seconds column
without_wall() {
    python3 -c 'import csv, sys
w = csv.writer(sys.stdout, lineterminator="\n")
for row in csv.DictReader(open(sys.argv[1])):
    row.pop("wall_seconds [s]")
    w.writerow(row.keys()) if row["point"] == "0" else None
    w.writerow(row.values())' "$1"
}

# wait_array JOBID: until squeue shows none of its tasks (at most 120 s)
wait_array() {
    local i
    for ((i = 0; i < 1200; i++)); do
        [[ -z $(squeue -h -j "$1" 2> /dev/null) ]] && return 0
        sleep 0.1
    done
    echo "  array $1 still in squeue after 120 s:"
    squeue -j "$1"
    return 1
}
# task_states JOBID: 'T:STATE:EXIT' per array task, by task, from slurmctld's job records
# (accounting is off, sacct has nothing)
task_states() {
    scontrol -o show job "$1" | sed -n 's/.*ArrayTaskId=\([0-9]*\) .*JobState=\([A-Z_]*\) .*ExitCode=\([0-9:]*\).*/\1:\2:\3/p' |
        sort -n | tr '\n' ' ' | sed 's/ $//'
}

t_submit=$(date +%s.%N)
jid=$(sbatch --parsable --array="$range%1" "$sbatch_script" "${args[@]}" --batch 2)
check "sbatch accepted the array (job $jid)" test -n "$jid"
# task 1 (points 2, 3) is sent SIGTERM while point 2 (about 1 s) runs
for ((i = 0; i < 600; i++)); do
    [[ -f scan/point_0002.err ]] && break
    sleep 0.05
done
sleep 0.3
scancel --signal=TERM --batch "${jid}_1"
check "the array ended" wait_array "$jid"
echo "array of 3 tasks ended $(elapsed "$t_submit") s after sbatch"
check "task 0 (a failed point among its points) and task 2 completed, task 1 (SIGTERM) failed with 143" \
    equals "0:COMPLETED:0:0 1:FAILED:143:0 2:COMPLETED:0:0" "$(task_states "$jid")"
check "task 1: stopped on the signal, says how to resume" \
    grep -q 'interrupted (signal 15) while running the points.*rerun the same command to resume' "slurm-rodcontact-scan-${jid}_1.out"
check "task 1: point 2 stopped with its checkpoint (exit 5, .h5.part kept), point 3 not run" \
    bash -c '[[ $(head -n 1 scan/point_0002.status) == 5 && -f scan/point_0002.h5.part && ! -e scan/point_0003.status ]]'
bash "$scan" "${args[@]}" --collect 2> ../collect1.log
check "after the signal: point 2 interrupted, 3 missing, point 0 failed, the others complete" equals \
    "0:failed 1:complete 2:interrupted 3:missing 4:complete 5:complete" "$(statuses scan/summary.csv)"

# resubmission: the tasks with a point that is not complete (point 0 failed: task 0; task 1)
range=$(bash "$scan" "${args[@]}" --batch 2 --array 2> ../array2.log)
check "--array after the signal: tasks 0-1" equals 0-1 "$range"
stamps=$(stat -c '%n %Y.%s' scan/point_0001.h5 scan/point_0004.h5 scan/point_0005.h5)
jid2=$(sbatch --parsable --array="$range%1" "$sbatch_script" "${args[@]}" --batch 2)
check "the resubmitted array ended" wait_array "$jid2"
check "resubmitted tasks 0 and 1 completed" equals "0:COMPLETED:0:0 1:COMPLETED:0:0" "$(task_states "$jid2")"
check "resubmission: task 0 skipped its complete point 1 and ran point 0 again" \
    grep -q 'task 0: points 0..1 of 6 in scan/, 1 already complete, 1 to run' "slurm-rodcontact-scan-${jid2}_0.out"
check "resubmission: task 1 ran points 2, 3" \
    grep -q 'task 1: points 2..3 of 6 in scan/, 0 already complete, 2 to run' "slurm-rodcontact-scan-${jid2}_1.out"
check "resubmission: point 2 continued from its checkpoint (root attribute restart_step)" \
    bash -c "$py"' -c "import h5py, sys; sys.exit(0 if h5py.File(\"scan/point_0002.h5\").attrs.get(\"restart_step\", 0) > 0 else 1)"'
check "resubmission: the complete points' files untouched" \
    equals "$stamps" "$(stat -c '%n %Y.%s' scan/point_0001.h5 scan/point_0004.h5 scan/point_0005.h5)"
check "left to run: only task 0 (its point 0 fails again)" \
    equals 0 "$(bash "$scan" "${args[@]}" --batch 2 --array 2> /dev/null)"

# ---------------------------------------------------------------- the table
bash "$scan" "${args[@]}" --collect 2> ../collect2.log
check "cluster summary.csv: every point complete but point 0 (numerical failure, recorded)" equals \
    "0:failed 1:complete 2:complete 3:complete 4:complete 5:complete" "$(statuses scan/summary.csv)"
check "cluster summary.csv: point 0 'failed: step ... did not converge', exit status 3" \
    grep -q '^0,0.1,paper,200,1e-3,16,100000,10,"\{0,1\}failed: step [0-9]* (t = .*did not converge.*,3,' scan/summary.csv
check "the header has a wall_seconds column" grep -q ',wall_seconds \[s\],' scan/summary.csv
check "cluster summary.csv = local summary.csv (every column but wall_seconds)" \
    diff <(without_wall ../local/scan/summary.csv) <(without_wall scan/summary.csv)
cd "$scratch" || exit 1

# ---------------------------------------------------------------- scan.sh --slurm
# The array and the collect job in one command, from another directory than the repository;
# the Slurm logs under the scan directory.
mkdir -p oneshot && cd oneshot || exit 1
rm -rf scan
bash "$scan" "${args[@]}" --batch 2 --slurm %1 --time=10 > ../slurm_submit.out 2> ../slurm_submit.log
check "--slurm: exit 0" equals 0 "$?"
jid3=$(sed -n 's/^submitted the array: job \([0-9]*\),.*/\1/p' ../slurm_submit.out)
cid3=$(sed -n 's/^submitted the collect job: job \([0-9]*\),.*/\1/p' ../slurm_submit.out)
check "--slurm printed the array's and the collect job's ids ($jid3, $cid3)" test -n "$jid3" -a -n "$cid3"
check "--slurm: the array ended" wait_array "$jid3"
check "--slurm: the collect job ended" wait_array "$cid3"
check "--slurm: the collect job completed" equals "COMPLETED:0:0" \
    "$(scontrol -o show job "$cid3" | sed -n 's/.*JobState=\([A-Z_]*\) .*ExitCode=\([0-9:]*\).*/\1:\2/p')"
check "--slurm: the collect job's summary.csv = local summary.csv (every column but wall_seconds)" \
    diff <(without_wall ../local/scan/summary.csv) <(without_wall scan/summary.csv)
check "--slurm: the Slurm logs in scan/slurm/ (3 tasks and the collect job), none here" \
    bash -c "[[ \$(ls scan/slurm/rodcontact-scan-${jid3}_*.out | wc -l) == 3 && -f scan/slurm/rodcontact-collect-$cid3.out ]] && ! ls slurm-*.out 2> /dev/null"
cd "$scratch" || exit 1

# ---------------------------------------------------------------- stop
cluster_dir=$cluster
stop_cluster
left=$(pgrep -a -f -- "$cluster_dir")
check "every daemon stopped" equals "" "$left"

echo "test_slurm: $n_checks checks, $n_failed failed; cluster start-up $t_up s, test wall time $(elapsed "$t_test") s"
if ((n_failed > 0)); then
    for log in local.log array1.log array2.log collect1.log collect2.log cluster/slurm-*.out slurm_submit.* oneshot/scan/slurm/*.out; do
        [[ -f $log ]] && { echo "--- $log"; cat "$log"; }
    done
    for log in cluster-logs/*.log; do
        [[ -f $log ]] && { echo "--- $log (last 30 lines)"; tail -n 30 "$log"; }
    done
    exit 1
fi
