#!/usr/bin/env bash
# Benchmark (not a test): sigma's L2-in-time error of the impact case (midpoint, Signorini,
# &contact mass = 'redistributed', dt = S^-1/4) on four (g, A) pairs — impact.nml's (0.05, 1),
# the bench's (0.1, 0.5) and (0.02, 1.5), and (0.03, 0.8) that no choice was made on — at
# S = 500 ... 4000, and where in time the error lies (the first 5 h after each exact onset,
# the step that straddles it, the rest). Writes the section between the impact-pairs markers
# of docs/performance.md (bench/impact_pairs.py); issue 27's "the same on (g, A) pairs the
# benchmark did not tune to".
#
#   bench/impact_pairs.sh            # about 2 minutes on 2 cores
#   bench/impact_pairs.sh --quick    # S = 500 and 1000 only; prints the section
# Environment: BUILD_DIR (as scripts/setup.sh), IMPACT_BENCH_OUT (run files, default
# out/bench/impact). Exit status: 0 done; 1 build or run failure; 2 usage.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$repo_root/bench/quick_option.sh" impact_pairs "$@"
build_dir="${BUILD_DIR:-build}"; [[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
out="${IMPACT_BENCH_OUT:-$repo_root/out/bench/impact}"
py="$("$repo_root/scripts/lib/find_python.sh")" || exit 1
"$repo_root/scripts/setup.sh" >&2 || exit 1
mkdir -p "$out"
args=("$build_dir/rodcontact" "$repo_root" "$out")
[ "$quick" = 1 ] && args+=(--quick)
"$py" "$repo_root/bench/impact_pairs.py" "${args[@]}" || { say "failed"; exit 1; }
