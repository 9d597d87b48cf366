#!/usr/bin/env bash
# Benchmark (not a test): the impact case (input/impact.nml: an elastic bar hitting the
# obstacle) against its exact solution (tests/tools/exact_impact.py), issue 27: every time
# scheme x contact law x velocity mass (&contact mass = 'consistent' | 'redistributed') at
# S = 1000, dt = 2.5e-4 on impact.nml's (g, A) = (0.05, 1) and on (0.1, 0.5), (0.02, 1.5);
# S = 500 and 2000 (dt = S^-1/4) on impact.nml with Signorini; adaptive midpoint/Signorini
# with the redistributed mass at error_tol 1e-4 ... 1e-7 on all three pairs (steps, rejected steps,
# wall time over the median of 3 fixed-step runs), and on impact.nml the time error at equal work
# against a fixed-step reference (dt = 2.5e-4/32). Measures: max |u(1,t) error|,
# max u(1,t) - g, sigma's L2-in-time error and total variation on each contact interval,
# event count, E(4)/E(0) - 1 and the largest one-step rise, wall time. Writes the section
# "Impact against the exact solution" of docs/performance.md (between its impact-bench
# markers), figures/impact_sigma.png and $IMPACT_BENCH_OUT/impact.json (bench/impact.py).
#
#   bench/impact.sh            # about 2 minutes on 2 cores
#   bench/impact.sh --quick    # impact.nml's pair only, no refinement, one adaptive run;
#                              # prints the section, figure $IMPACT_BENCH_OUT/impact_sigma_quick.png
# Environment: BUILD_DIR (as scripts/setup.sh), IMPACT_BENCH_OUT (run files and impact.json,
# default out/bench/impact). Exit status: 0 done (targets met or not: see the page); 1 build or
# run failure; 2 usage.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$repo_root/bench/quick_option.sh" impact "$@"
build_dir="${BUILD_DIR:-build}"; [[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
out="${IMPACT_BENCH_OUT:-$repo_root/out/bench/impact}"
py="$("$repo_root/scripts/lib/find_python.sh")" || exit 1
"$repo_root/scripts/setup.sh" >&2 || exit 1
mkdir -p "$out" "$repo_root/figures"
args=("$build_dir/rodcontact" "$repo_root" "$out")
[ "$quick" = 1 ] && args+=(--quick)
"$py" "$repo_root/bench/impact.py" "${args[@]}" || { say "failed"; exit 1; }
