#!/usr/bin/env bash
# Two binaries' user CPU time on the cases a refactor must not slow down, measured in one
# loop that alternates them (so that the machine's load falls on both alike): the median of
# RUNS runs of each, and the ratio new/old. Not a test (timings of a shared machine are noisy).
#
#   bench/compare_speed.sh OLD_BINARY NEW_BINARY [RUNS]      # RUNS default 5
#
# Cases: exp1 to t = 10, fixed steps, Euler and BDF2; exp1 to t = 60, adaptive midpoint
# (error_tol 1.2e-5); exp1 to t = 2 with &output error_estimate; an adaptive mesh (exp2 to
# t = 2, 250 coarse elements, max_level 4). Also prints which BLAS the binaries load.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
old="$(realpath "$1")"; new="$(realpath "$2")"; runs="${3:-5}"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
in="$repo/input"
cases=(
  "euler_t10|$in/exp1.nml|--set time.t_end=10"
  "bdf2_t10|$in/exp1.nml|--set time.t_end=10 --set time.scheme='bdf2'"
  "adaptive_midpoint_t60|$in/exp1.nml|--set time.t_end=60 --set time.scheme='midpoint' --set time.adaptive=.true. --set time.error_tol=1.2e-5"
  "error_estimate_t2|$in/exp1.nml|--set time.t_end=2 --set output.error_estimate=.true."
  "adaptive_mesh|$in/exp2.nml|--set time.t_end=2 --set mesh.n_elements=250 --set mesh.adaptive=.true. --set mesh.max_level=4"
)
echo "BLAS: $(ldd "$new" | grep -o 'libblas[^ ]* => [^ ]*' | head -1); load: $(cut -d' ' -f1-3 /proc/loadavg)"
cpu() {  # cpu BIN INPUT ARGS: user seconds of one run
    local bin="$1" input="$2"; shift 2
    eval "/usr/bin/time -f %U -o \"$work/time\" \"$bin\" \"$input\" --set output.quiet=.true. \
        --set output.prefix=\"'$work/run'\" $*" > /dev/null 2>&1 || { echo "run failed: $bin $input $*" >&2; exit 1; }
    cat "$work/time"
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
printf '%-24s %10s %10s %8s\n' case old_s new_s new/old
for c in "${cases[@]}"; do
    IFS='|' read -r name input args <<< "$c"
    : > "$work/old"; : > "$work/new"
    for ((k = 0; k < runs; k++)); do
        cpu "$old" "$input" "$args" >> "$work/old"
        cpu "$new" "$input" "$args" >> "$work/new"
    done
    mo=$(median < "$work/old"); mn=$(median < "$work/new")
    printf '%-24s %10s %10s %8.3f\n' "$name" "$mo" "$mn" "$(awk -v a="$mn" -v b="$mo" 'BEGIN {print a / b}')"
done
