#!/usr/bin/env bash
# Stress table: short runs of experiments 1 and 2 with one (or a few) parameters pushed to
# extreme values: eps, varpi, tau0 = tau, dt, n_elements, a tiny gap g, a huge initial
# velocity, rho from 1e-17 to 1, and the paper's iteration where it is expected to fail.
# For each run: exit status, status attribute, whether every stored value is finite, the
# largest relative energy rise (the larger of the root attribute energy_max_relative_rise
# and the rise measured on /series/energy, stored every step), contact or not,
# steps and wall time, and a verdict:
#   ok       exit 0, status 'complete', all finite, energy rise <= 1e-12
#   ok (3)   exit 3, status 'failed: <reason>' and one stderr message naming the step
#   PROBLEM  anything else (crash, non-finite value in a complete run, energy rise, ...)
#
#   tests/tools/stress.sh                      # build (scripts/setup.sh), run all, update docs/robustness.md
#   tests/tools/stress.sh --quick              # a reduced set (tests/test_stress_quick.sh)
#   tests/tools/stress.sh --program build/rodcontact --scratch /tmp/stress --output -
#
# Options: --program <rodcontact> (default: build with scripts/setup.sh, use build/rodcontact),
# --scratch <dir> (default: a new temporary directory), --output <file> (default
# docs/robustness.md: the table replaces the lines between '<!-- stress:begin -->' and
# '<!-- stress:end -->'; '-' prints it on stdout), --quick.
# Exit status: 0 every verdict ok, 1 a PROBLEM, 2 usage error or no Python with h5py.
set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
program=""
scratch=""
output="$repo_root/docs/robustness.md"
quick=no
while (($# > 0)); do
    case $1 in
        --program) program=$2; shift 2 ;;
        --scratch) scratch=$2; shift 2 ;;
        --output) output=$2; shift 2 ;;
        --quick) quick=yes; shift ;;
        -h|--help) sed -n '2,22p' "${BASH_SOURCE[0]}"; exit 0 ;;
        *) echo "stress.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
    esac
done
if [[ -z "$program" ]]; then
    "$repo_root/scripts/setup.sh" || exit 2
    program="$repo_root/build/rodcontact"
fi
[[ -x "$program" ]] || { echo "stress.sh: no program at '$program'" >&2; exit 2; }
PY=$("$repo_root/scripts/lib/find_python.sh") || exit 2
[[ -n "$scratch" ]] || scratch=$(mktemp -d)
mkdir -p "$scratch" || exit 2

# Base cases. exp1: the paper's experiment 1 data, h = 1/500, dt = 5e-3, 100 steps to
# t = 0.5 (contact from t ~ 0.19). exp2: the pulses of experiment 2, dt = 1e-3, 200 steps.
declare -A EXP1=(
    [initial]="theta0_poly = 0, 40, -80, 40  p0_poly = 0, 0, 20, -40, 20  u1_poly = 0, 10"
    [mesh.n_elements]=500 [time.dt]=5e-3 [time.t_end]=0.5
)
declare -A EXP2=(
    [initial]="theta0_step = 20, 0.1  p0_step = 20, 0.1"
    [mesh.n_elements]=500 [time.dt]=1e-3 [time.t_end]=0.2
)

rows=()
n_problem=0
n_run=0

# run_case <base exp1|exp2> <label> [group.variable=value ...]
run_case() {
    local base=$1 label=$2
    shift 2
    declare -A p=()
    local key
    if [[ $base == exp1 ]]; then
        for key in "${!EXP1[@]}"; do p[$key]=${EXP1[$key]}; done
    else
        for key in "${!EXP2[@]}"; do p[$key]=${EXP2[$key]}; done
    fi
    local setting
    for setting in "$@"; do
        p[${setting%%=*}]=${setting#*=}
    done
    n_run=$((n_run + 1))
    local dir="$scratch/run$n_run"
    rm -rf "$dir" && mkdir -p "$dir"
    local input="$dir/input.nml" group text
    : > "$input"
    for group in model contact mesh time solver; do
        text=""
        for key in "${!p[@]}"; do
            [[ $key == "$group".* ]] && text+=" ${key#*.} = ${p[$key]}"
        done
        [[ -n "$text" ]] && echo "&$group$text /" >> "$input"
    done
    echo "&initial ${p[initial]} /" >> "$input"
    echo "&output prefix = '$dir/run' quiet = .true. snapshot_every = 50 /" >> "$input"

    local start end status
    start=$(date +%s.%N)
    timeout 600 "$program" "$input" > "$dir/stdout" 2> "$dir/stderr" < /dev/null
    status=$?
    end=$(date +%s.%N)
    local wall
    wall=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')

    local info="-|-|-|-|-"
    if [[ -f "$dir/run.h5" ]]; then
        info=$("$PY" - "$dir/run.h5" "$repo_root/scripts/lib" 2>&1 <<'PYTHON'
import sys
import numpy as np
sys.path.insert(0, sys.argv[2])
import rodrun
with rodrun.open_run(sys.argv[1], checked=False) as f:
    status = rodrun.text(f.attrs["status"])
    def all_finite(group):   # every numeric dataset below group, subgroups (/snapshots/native) included
        found = []
        group.visititems(lambda name, obj: found.append(obj) if isinstance(obj, rodrun.h5py.Dataset) else None)
        return all(np.all(np.isfinite(d[()])) for d in found if d.dtype.kind == "f")
    finite = all(all_finite(f[g]) for g in ("series", "snapshots"))
    # the attribute, and the same measured on the stored series (every step here)
    energy = f["series/energy"][:]
    rise_series = np.max(np.diff(energy) / np.maximum(energy[:-1], 1e-300)) if len(energy) > 1 else 0.0
    rise = max(float(f.attrs["energy_max_relative_rise"]), float(rise_series), 0.0)
    contact = "yes" if f["series/penetration"][:].max() > 0 else "no"
    print(f"{status}|{'yes' if finite else 'NO'}|{rise:.1e}|{contact}|{int(f.attrs['steps'])}")
PYTHON
        ) || info="unreadable|-|-|-|-"
    fi
    local h5_status finite rise contact steps
    IFS='|' read -r h5_status finite rise contact steps <<< "$info"
    local verdict=PROBLEM
    local n_err
    n_err=$(wc -l < "$dir/stderr")
    if [[ $status -eq 0 && "$h5_status" == complete && "$finite" == yes ]] &&
        awk -v r="$rise" 'BEGIN { exit !(r <= 1e-12) }'; then
        verdict=ok
    elif [[ $status -eq 3 && "$h5_status" == failed:* && "$finite" == yes && $n_err -eq 1 ]] &&
        grep -q '^rodcontact: error in solver: step [0-9]* (t = ' "$dir/stderr"; then
        verdict="ok (3)"
    fi
    [[ $verdict == PROBLEM ]] && n_problem=$((n_problem + 1))
    local changed="$*"
    changed=${changed//initial=theta0_poly = 0, 40, -80, 40  p0_poly = 0, 0, 20, -40, 20  /initial.}
    [[ -n "$changed" ]] || changed="(base)"
    # the reason of a failure, shortened for the table
    local reason="${h5_status#failed: }"
    [[ "$h5_status" == failed:* ]] && h5_status="failed: ${reason:0:70}"
    [[ $status -ne 0 && $status -ne 3 ]] && h5_status="$h5_status; stderr: $(head -c 120 "$dir/stderr" | tr '\n|' ' /')"
    rows+=("| $label | $base | ${changed//|//} | $status | $h5_status | $finite | $rise | $contact | $steps | $wall | $verdict |")
    echo "stress: $label: exit $status, $h5_status, finite $finite, rise $rise, contact $contact, ${wall}s: $verdict" >&2
}

if [[ $quick == yes ]]; then
    run_case exp1 "base" 
    run_case exp1 "eps" contact.eps=1e-8
    run_case exp1 "varpi" model.varpi=0
    run_case exp1 "tau0, tau" model.tau0=0 model.tau=0
    run_case exp1 "dt" time.dt=1e-7 time.t_end=1e-5
    run_case exp1 "dt" time.dt=0.5 time.t_end=50
    run_case exp1 "n_elements" mesh.n_elements=2
    run_case exp1 "g" contact.g=1e-12
    run_case exp1 "u1 = 1e6 x" "initial=theta0_poly = 0, 40, -80, 40  p0_poly = 0, 0, 20, -40, 20  u1_poly = 0, 1e6"
    run_case exp1 "rho" model.rho=1
    run_case exp1 "paper, eps" solver.method="'paper'" contact.eps=1e-4
    run_case exp2 "combined" model.rho=1e-17 model.varpi=0 time.dt=1e-7 time.t_end=1e-5
else
    run_case exp1 "base"
    run_case exp2 "base"
    for v in 1 1e-2 1e-4 1e-6 1e-8; do run_case exp1 "eps" contact.eps=$v; done
    for v in 1 1e-8; do run_case exp2 "eps" contact.eps=$v; done
    for v in 0 1e-6 0.1 10; do run_case exp1 "varpi" model.varpi=$v; done
    for v in 0 1e-6 0.2 10; do run_case exp1 "tau0, tau" model.tau0=$v model.tau=$v; done
    run_case exp1 "tau0 only" model.tau0=10 model.tau=0
    run_case exp2 "tau0, tau" model.tau0=0 model.tau=0
    run_case exp2 "tau0, tau" model.tau0=10 model.tau=10
    run_case exp1 "dt" time.dt=1e-7 time.t_end=1e-5
    run_case exp1 "dt" time.dt=1e-4 time.t_end=0.02
    run_case exp1 "dt" time.dt=1e-2 time.t_end=1
    run_case exp1 "dt" time.dt=0.5 time.t_end=50
    run_case exp2 "dt" time.dt=1e-7 time.t_end=1e-5
    run_case exp2 "dt" time.dt=0.5 time.t_end=50
    for v in 2 500 100000; do run_case exp1 "n_elements" mesh.n_elements=$v; done
    run_case exp2 "n_elements" mesh.n_elements=100000
    run_case exp1 "g" contact.g=1e-12
    run_case exp2 "g" contact.g=1e-12
    run_case exp1 "u1 = 1e6 x" \
        "initial=theta0_poly = 0, 40, -80, 40  p0_poly = 0, 0, 20, -40, 20  u1_poly = 0, 1e6"
    run_case exp1 "u1 = 1e6 x, eps" contact.eps=1e-8 \
        "initial=theta0_poly = 0, 40, -80, 40  p0_poly = 0, 0, 20, -40, 20  u1_poly = 0, 1e6"
    for v in 1e-17 1e-12 1e-6 1e-2 1; do run_case exp1 "rho" model.rho=$v; done
    run_case exp1 "rho, varpi, dt" model.rho=1e-17 model.varpi=0 time.dt=1e-7 time.t_end=1e-5
    run_case exp2 "rho, varpi, dt" model.rho=1e-17 model.varpi=0 time.dt=1e-7 time.t_end=1e-5
    run_case exp1 "rho, varpi, eps, dt" model.rho=1 model.varpi=0 contact.eps=1e-8 time.dt=0.5 time.t_end=50
    run_case exp1 "varpi, eps, dt" model.varpi=0 contact.eps=1e-8 time.dt=1e-7 time.t_end=1e-5
    run_case exp1 "n_elements, dt" mesh.n_elements=100000 time.dt=1e-7 time.t_end=1e-5
    run_case exp1 "paper" solver.method="'paper'"
    run_case exp1 "paper, eps" solver.method="'paper'" contact.eps=1e-4
    run_case exp1 "paper, varpi" solver.method="'paper'" model.varpi=0
    run_case exp1 "paper, rho" solver.method="'paper'" model.rho=1
    run_case exp1 "paper, dt" solver.method="'paper'" time.dt=1e-7 time.t_end=1e-5
    run_case exp2 "paper" solver.method="'paper'"
fi

table=$(
    echo "| case | base | changed | exit | status | finite | energy rise | contact | steps | wall s | verdict |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|"
    printf '%s\n' "${rows[@]}"
    echo
    echo "$n_run runs, $n_problem with verdict PROBLEM; rodcontact $("$program" --version | awk '{print $2}')," \
        "$(uname -m), $(nproc) cores, $(date -u +%Y-%m-%d)."
)
if [[ "$output" == - ]]; then
    echo "$table"
elif [[ -f "$output" ]] && grep -q '<!-- stress:begin -->' "$output"; then
    tmp="$output.tmp.$$"
    awk -v table="$table" '
        /<!-- stress:begin -->/ { print; print table; skip = 1; next }
        /<!-- stress:end -->/ { skip = 0 }
        !skip { print }' "$output" > "$tmp" && mv "$tmp" "$output"
    echo "stress: table written to $output" >&2
else
    echo "$table" > "$output"
    echo "stress: table written to $output (no stress markers found: the whole file)" >&2
fi
[[ $n_problem -eq 0 ]]
