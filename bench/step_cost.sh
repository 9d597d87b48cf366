#!/usr/bin/env bash
# Benchmark (not a test): the cost of one adaptive step against one fixed step of the same
# scheme, in instructions (valgrind callgrind; the machine may be loaded, instruction counts
# are not affected), on experiment 1 (input/exp1.nml, h = 1/500), and how much of it is the
# assembly and factorisation of the system of (6.1) at a new step size (setup_monolithic).
# Writes $WP_OUT/step_cost.md (the section "Per-step cost: adaptive against fixed steps" of
# docs/performance.md, which bench/step_cost.py inserts).
#
#   bench/step_cost.sh           # euler, bdf2, midpoint; about 3 minutes on 2 cores
#   bench/step_cost.sh --quick   # midpoint only, shorter runs
#
# One step's cost is the difference of two runs, to t1 and to t2, divided by the difference
# of their step counts (set-up and output cancel): fixed steps dt = 1e-4 from t1 = 0.25 to
# t2 = 0.5; adaptive steps (error_tol = 1e-5, 1e-7) over the same interval. And the whole run
# of the benchmark's target, adaptive midpoint at error_tol = 1e-5 to t = 60 (all its step
# sizes, from 1e-4 to 1: instructions of the run over its steps; not with --quick).
# Environment: BUILD_DIR (as scripts/setup.sh; Release is forced), WP_SKIP_BUILD=1, WP_OUT
# (default out/bench; --quick: out/bench-quick), STEP_COST_DOC (the page the section is spliced
# into, default docs/performance.md; empty: none, as scripts/bench.sh runs it, whose
# bench/report.py takes $WP_OUT/step_cost.md; --quick writes no page).
# Exit status: 0 done; 1 build or run failure; 2 usage.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$repo_root/bench/quick_option.sh" step_cost "$@"
. "$repo_root/bench/build_for_bench.sh" rodcontact
command -v valgrind >/dev/null || { say "valgrind is not installed (scripts/setup.sh installs it)"; exit 1; }
py="$("$repo_root/scripts/lib/find_python.sh")" || exit 1
raw_dir="$out/step_cost"
mkdir -p "$raw_dir"
input="$repo_root/input/exp1.nml"
if ((quick)); then
    schemes=(midpoint); t1=0.1; t2=0.2; tols=(1e-5)
else
    schemes=(euler bdf2 midpoint); t1=0.25; t2=0.5; tols=(1e-5 1e-7)
fi
common=(--set output.snapshot_every=1000000000 --set output.quiet=.true.)

# measure <name> <t_end> <arg>...: callgrind_annotate --inclusive=yes of one run into <name>_<t_end>.txt
measure() {
    local name="$1" t_end="$2"
    shift 2
    local prefix="$raw_dir/${name}_$t_end"
    rm -f "$prefix.h5"
    if ! env LD_LIBRARY_PATH="$ref_libs" valgrind --tool=callgrind --callgrind-out-file="$prefix.cg" \
        "$exe" "$input" "${common[@]}" --set output.prefix="'$prefix'" --set time.t_end="$t_end" "$@" \
        >"$prefix.out" 2>"$prefix.err"; then
        say "run failed: $* (stderr: $prefix.err)"
        exit 1
    fi
    callgrind_annotate --inclusive=yes "$prefix.cg" >"$prefix.txt" 2>/dev/null
    echo "steps=$("$py" "$repo_root/scripts/lib/rodrun.py" attr "$prefix.h5" steps)" >>"$prefix.txt"
    rm -f "$prefix.cg" "$prefix.h5"
}

: >"$raw_dir/cases.txt"
for scheme in "${schemes[@]}"; do
    for t in "$t1" "$t2"; do
        measure "fixed_$scheme" "$t" --set time.scheme="'$scheme'" --set time.dt=1e-4
        for tol in "${tols[@]}"; do
            measure "adaptive_${scheme}_$tol" "$t" --set time.scheme="'$scheme'" --set time.adaptive=.true. \
                --set time.error_tol="$tol"
        done
    done
    echo "fixed_$scheme $t1 $t2" >>"$raw_dir/cases.txt"
    for tol in "${tols[@]}"; do echo "adaptive_${scheme}_$tol $t1 $t2" >>"$raw_dir/cases.txt"; done
done
if ((!quick)); then
    measure adaptive_midpoint_1e-5 60 --set time.scheme="'midpoint'" --set time.adaptive=.true. --set time.error_tol=1e-5
    echo "adaptive_midpoint_1e-5 0 60" >>"$raw_dir/cases.txt"
fi
doc="${STEP_COST_DOC-$repo_root/docs/performance.md}"
((quick)) && doc=""
"$py" "$repo_root/bench/step_cost.py" "$raw_dir" "$out/step_cost.md" $doc
cat "$out/step_cost.md"
