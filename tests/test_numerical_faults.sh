#!/usr/bin/env bash
# Numerical failures through the real program (the README, "exit status"): a run that fails must
#   - exit with status 3,
#   - write one line to stderr naming the step, t and what failed,
#   - leave <prefix>.h5 (never <prefix>.h5.part) that h5py opens, with root attribute
#     status = 'failed: <reason>' (the same step), every field and series value finite,
#     /series holding exactly the steps before the failure (t = 0 included) and
#     /snapshots every snapshot_every-th of them (t = 0 included; the last good step may
#     be added).
# Cases:
#   paper_max_iter  method='paper' max_iter=3 on experiment 1: the lagged penalty needs more
#                   iterations once the rod touches the obstacle (step 191, t = 0.191)
#   paper_varpi0    method='paper' with varpi = 0: the thermo-mechanical splitting diverges
#                   at step 1 (docs/scheme.md), 50 iterations end at ~1e65
#   paper_overflow  the same with max_iter = 100000: the iterates overflow; the only input
#                   found that passes validation and produces a non-finite value (see
#                   docs/robustness.md). In a Debug build (-ffpe-trap=overflow) the overflow
#                   traps: there the case expects SIGFPE with a backtrace through stepper_m.
#   si_seconds      paper_max_iter's input in SI units (&material): the message and the status
#                   attribute give t in seconds ('t = 8.8867E-04 s'; issue 36)
#
#   bash tests/test_numerical_faults.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 all passed, 1 a case failed, 77 skipped (no program, or no Python with h5py).
set -u

prog=${1:-}
source_dir=${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
scratch=${3:-$(mktemp -d)}
if [[ -z "$prog" || ! -x "$prog" ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
if ! PY=$("$source_dir/scripts/lib/find_python.sh"); then
    echo "SKIP: no Python with h5py"
    exit 77
fi
mkdir -p "$scratch" || exit 1

# A build with floating-point traps (Debug) stops at the first overflow with SIGFPE.
traps=no
cache="$(dirname "$prog")/CMakeCache.txt"
if [[ -f "$cache" ]] && grep -q '^CMAKE_BUILD_TYPE:[A-Z]*=Debug$' "$cache"; then
    traps=yes
fi

n_failed=0
n_case=0
EXP1="&initial theta0_poly = 0, 40, -80, 40  p0_poly = 0, 0, 20, -40, 20  u1_poly = 0, 10 /
&mesh n_elements = 50 /
&time dt = 1e-3, t_end = 0.5 /"

fail() {
    n_failed=$((n_failed + 1))
    echo "FAIL $1"
    shift
    printf '  %s\n' "$@"
}

# run_case <name> <snapshot_every> <series_every> <expected failed step or ''> <reason regex> <namelist>
run_case() {
    local name=$1 snap=$2 series=$3 expect_step=$4 reason=$5 text=$6
    n_case=$((n_case + 1))
    local dir="$scratch/$name"
    rm -rf "$dir" && mkdir -p "$dir"
    printf '%s\n' "$text" "&output prefix='$dir/run' quiet=.true. snapshot_every=$snap series_every=$series /" \
        > "$dir/input.nml"
    "$prog" "$dir/input.nml" > "$dir/stdout" 2> "$dir/stderr" < /dev/null
    local status=$?
    local problems=()
    [[ $status -eq 3 ]] || problems+=("exit status: expected 3, got $status")
    local n_lines
    n_lines=$(wc -l < "$dir/stderr")
    [[ $n_lines -eq 1 ]] || problems+=("stderr: expected exactly 1 line, got $n_lines")
    local message
    message=$(head -n 1 "$dir/stderr")
    [[ "$message" =~ ^"rodcontact: error in solver: step "([0-9]+)" (t = "\ *([0-9.eE+-]+)"): " ]] ||
        problems+=("stderr: expected 'rodcontact: error in solver: step N (t = T): <reason>', got '$message'")
    local step=${BASH_REMATCH[1]:-0} t=${BASH_REMATCH[2]:-0}
    [[ -z "$expect_step" || "$step" == "$expect_step" ]] || problems+=("failed step: expected $expect_step, got $step")
    [[ "$message" =~ $reason ]] || problems+=("stderr: expected the reason to match '$reason'")
    [[ -e "$dir/run.h5.part" ]] && problems+=("output: $dir/run.h5.part left behind")
    if [[ -e "$dir/run.h5" ]]; then
        local check
        check=$("$PY" - "$dir/run.h5" "$step" "$t" "$snap" "$series" 2>&1 <<'PYTHON'
import sys
import h5py
import numpy as np

path, step, t_fail, snap, series = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
problems = []
with h5py.File(path, "r") as f:
    status = f.attrs["status"]
    status = status.decode() if isinstance(status, bytes) else str(status)
    dt = float(f.attrs["time.dt"])
    if not status.startswith("failed: "):
        problems.append(f"status: expected 'failed: ...', got {status!r}")
    if f"step {step} " not in status:
        problems.append(f"status: expected it to name step {step}, got {status!r}")
    if abs(t_fail - step * dt) > 1e-9 * max(1.0, t_fail):
        problems.append(f"message: t = {t_fail} is not step {step} * dt = {step * dt}")
    last_good = step - 1
    # series: t = 0 and every series-th step up to the last good one (that one may be added)
    t = f["series/t"][:]
    steps = np.rint(t / dt).astype(int)
    expected = list(range(0, last_good + 1, series))
    if list(steps) != expected and list(steps) != expected + [last_good]:
        problems.append(f"series/t: expected steps {expected[:3]}...{expected[-3:]} ({len(expected)}), "
                        f"got {list(steps[:3])}...{list(steps[-3:])} ({len(steps)})")
    for name in ("t", "energy", "u_end", "penetration", "contact_stress"):
        values = f["series/" + name][:]
        if values.shape != t.shape:
            problems.append(f"series/{name}: expected shape {t.shape}, got {values.shape}")
        if not np.all(np.isfinite(values)):
            problems.append(f"series/{name}: non-finite values")
    energy = f["series/energy"][:]
    if len(energy) > 1 and np.max(np.diff(energy) / np.maximum(energy[:-1], 1e-300)) > 1e-12:
        problems.append("series/energy rises")
    ts = f["snapshots/t"][:]
    snap_steps = np.rint(ts / dt).astype(int)
    expected = list(range(0, last_good + 1, snap))
    if list(snap_steps) != expected and list(snap_steps) != expected + [last_good]:
        problems.append(f"snapshots/t: expected steps {expected}, got {list(snap_steps)}")
    for name in ("u", "v", "theta", "P", "q", "eta"):
        values = f["snapshots/" + name][:]
        if values.shape[0] != len(ts):
            problems.append(f"snapshots/{name}: expected {len(ts)} rows, got {values.shape[0]}")
        if not np.all(np.isfinite(values)):
            problems.append(f"snapshots/{name}: non-finite values")
    print(f"status {status!r}; {len(t)} series entries, {len(ts)} snapshots")
for p in problems:
    print("PROBLEM " + p)
PYTHON
        )
        [[ $? -eq 0 ]] || problems+=("h5py could not read $dir/run.h5: $check")
        while IFS= read -r line; do
            [[ "$line" == PROBLEM* ]] && problems+=("${line#PROBLEM }")
        done <<< "$check"
    else
        problems+=("output: expected $dir/run.h5, found: $(ls "$dir" | tr '\n' ' ')")
    fi
    if [[ ${#problems[@]} -eq 0 ]]; then
        echo "PASS $name: $message"
        echo "     $(grep -v '^PROBLEM' <<< "$check")"
    else
        fail "$name" "${problems[@]}"
    fi
}

# (a) iteration not converged, at a step well inside the run: series every step and every
# 3rd, snapshots every 7th step
run_case paper_max_iter 7 1 191 "paper iteration did not converge in 3 iterations" \
    "$EXP1
&solver method = 'paper', max_iter = 3 /"
run_case paper_max_iter_series3 7 3 191 "paper iteration did not converge in 3 iterations" \
    "$EXP1
&solver method = 'paper', max_iter = 3 /"
# (a) the splitting diverges at once (varpi = 0): only the t = 0 entries
run_case paper_varpi0 10 1 1 "did not converge|diverg" \
    "$EXP1
&model varpi = 0 /
&solver method = 'paper' /"

# (b) non-finite value: the diverging iteration left to overflow
name=paper_overflow
text="$EXP1
&model varpi = 0 /
&solver method = 'paper', max_iter = 100000 /"
if [[ $traps == yes ]]; then
    n_case=$((n_case + 1))
    dir="$scratch/$name"
    rm -rf "$dir" && mkdir -p "$dir"
    printf '%s\n' "$text" "&output prefix='$dir/run' quiet=.true. /" > "$dir/input.nml"
    "$prog" "$dir/input.nml" > "$dir/stdout" 2> "$dir/stderr" < /dev/null
    status=$?
    if grep -q 'SIGFPE' "$dir/stderr" && grep -q 'stepper_m' "$dir/stderr"; then
        echo "PASS $name (build with floating-point traps): the overflow traps in" \
            "$(grep -m 1 -A 1 'MOD_\|advance' "$dir/stderr" | tail -n 1 | tr -s ' ')"
    elif [[ $status -eq 3 ]] && grep -q 'rodcontact: error in solver: step 1 ' "$dir/stderr"; then
        # the iteration may stop a diverging iterate before it overflows
        echo "PASS $name (build with floating-point traps): $(head -n 1 "$dir/stderr")"
    else
        fail "$name" "expected SIGFPE through stepper_m (traps) or exit 3, got status $status:" \
            "$(head -c 600 "$dir/stderr")"
    fi
else
    run_case "$name" 10 1 1 "non-finite value|diverg" "$text"
fi

# (c) with &material (SI input, tests/tools/si_input.py; the time scale is 0.8887 s) the
# step's t is in seconds, with the unit, in the message and the status attribute (issue 36):
# the splitting of the SI material's varpi = 0 diverges
name=si_seconds
n_case=$((n_case + 1))
dir="$scratch/$name"
rm -rf "$dir" && mkdir -p "$dir"
printf '%s\n' "$EXP1" "&solver method = 'paper', max_iter = 3 /" "&output prefix='$dir/run' quiet=.true. /" \
    > "$dir/plain.nml"
"$PY" "$source_dir/tests/tools/si_input.py" "$dir/plain.nml" ell=0.01 > "$dir/input.nml"
"$prog" "$dir/input.nml" > "$dir/stdout" 2> "$dir/stderr" < /dev/null
status=$?
message=$(head -n 1 "$dir/stderr")
check=$("$PY" - "$dir/run.h5" "$message" 2>&1 <<'PYTHON'
import re, sys
import h5py
path, message = sys.argv[1], sys.argv[2]
label = re.match(r"rodcontact: error in solver: (step (\d+) \(t = *(\S+) s\)): ", message)
if not label:
    sys.exit(f"expected 'step N (t = T s): ' in the message, got {message!r}")
dt = 1e-3 * 0.8886729015544042   # the SI step
if abs(float(label[3]) - int(label[2]) * dt) > 1e-4 * int(label[2]) * dt:
    sys.exit(f"t = {label[3]} s is not step {label[2]} * dt = {int(label[2]) * dt} s")
status = h5py.File(path, "r").attrs["status"]
status = status.decode() if isinstance(status, bytes) else str(status)
if not status.startswith("failed: " + label[1] + ": "):
    sys.exit(f"status attribute: expected 'failed: {label[1]}: ...', got {status!r}")
PYTHON
)
if [[ $status -eq 3 && -z "$check" ]]; then
    echo "PASS $name: $message"
else
    fail "$name" "exit status $status (expected 3); $check"
fi

echo "test_numerical_faults: $n_case cases, $n_failed failed"
[[ $n_failed -eq 0 ]]
