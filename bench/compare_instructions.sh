#!/usr/bin/env bash
# Two binaries' instructions (valgrind callgrind, total Ir: deterministic, unlike a timing on
# a shared machine) on short versions of bench/compare_speed.sh's cases and on a chattering
# contact (work that grows with a run's length), and the ratio new/old.
#
#   bench/compare_instructions.sh OLD_BINARY NEW_BINARY
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
old="$(realpath "$1")"; new="$(realpath "$2")"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
in="$repo/input"
cases=(
  "euler_2000_steps|$in/exp1.nml|--set time.t_end=0.2"
  "bdf2_2000_steps|$in/exp1.nml|--set time.t_end=0.2 --set time.scheme='bdf2'"
  "midpoint_impact|$in/impact.nml|--set time.t_end=0.4"
  "adaptive_midpoint_t10|$in/exp1.nml|--set time.t_end=10 --set time.scheme='midpoint' --set time.adaptive=.true. --set time.error_tol=1.2e-5"
  "adaptive_bdf2_t2|$in/exp1.nml|--set time.t_end=2 --set time.scheme='bdf2' --set time.adaptive=.true."
  "error_estimate_t0.4|$in/exp1.nml|--set time.t_end=0.4 --set output.error_estimate=.true."
  "adaptive_mesh_t0.2|$in/exp2.nml|--set time.t_end=0.2 --set mesh.n_elements=250 --set mesh.adaptive=.true. --set mesh.max_level=4"
  # a Signorini contact that chatters under adaptive steps (test_adaptive's random set 6): 52,908
  # steps, 22,614 events; catches work that grows with the run's length (an event log copied
  # at each append took 4.3x the instructions: 10.87e9 against 2.54e9)
  "chattering_t0.12|$in/exp1.nml|--set model.rho=0.915539 --set model.alpha=0.123386 --set model.varpi=0.131702 --set model.gamma1=0.804894 --set model.gamma2=0.401948 --set model.c=1.50463 --set model.r=0.961441 --set model.d=0.480982 --set model.hbar=0.0254134 --set model.tau0=0.460982 --set model.tau=0.0104365 --set contact.g=0.0234859 --set contact.eps=0.0580876 --set contact.law='signorini' --set mesh.n_elements=20 --set time.t_end=0.12 --set time.dt=1e-3 --set time.adaptive=.true. --set time.scheme='midpoint'"
)
ir() {  # ir BIN INPUT ARGS: total instructions of one run
    local bin="$1" input="$2"; shift 2
    eval "valgrind --tool=callgrind --callgrind-out-file=\"$work/cg\" \"$bin\" \"$input\" \
        --set output.quiet=.true. --set output.prefix=\"'$work/run'\" $*" > /dev/null 2>&1 \
        || { echo "run failed: $bin $input $*" >&2; exit 1; }
    grep '^summary:' "$work/cg" | awk '{print $2}'
}
printf '%-24s %15s %15s %8s\n' case old_Ir new_Ir new/old
for c in "${cases[@]}"; do
    IFS='|' read -r name input args <<< "$c"
    a=$(ir "$old" "$input" "$args"); b=$(ir "$new" "$input" "$args")
    printf '%-24s %15s %15s %8.4f\n' "$name" "$a" "$b" "$(awk -v a="$b" -v b="$a" 'BEGIN {print a / b}')"
done
