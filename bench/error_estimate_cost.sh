#!/usr/bin/env bash
# Benchmark (not a test): what `&output error_estimate = .true.` costs, and where it goes.
# Experiment 1 (input/exp1.nml: s = 500, dt = 1e-4, implicit Euler, a snapshot every 100
# steps) to t = 2 with and without the estimate, in instructions (valgrind callgrind; not
# affected by the machine's load), split into the companions' steps (error_companion_m's
# step_over, inclusive: their right-hand sides, solves, contact), their set-up (factoring
# their systems), the estimate at the snapshots and the rest; and the run's own stepping
# (stepper_advance without the estimate), against which the companions' steps are set: their
# nodes times steps are a fixed share of the run's (A: (s/2 + 1)/(s + 1)/2, C and D:
# (s/4 + 1)/(s + 1)/4 and /8, 0.345 at s = 500), so the ratio stays near that share of the
# run's stepping while a companion's step costs per node nearly what the run's does (less the
# finiteness test).
# Another binary (e.g. the one before a change): BUILD_DIR=<its directory> WP_SKIP_BUILD=1.
# With --cpu N: also CPU time (user + sys) to t = 10, N runs without and N with, alternated,
# their medians and the load average (noisy on a loaded machine; the instruction counts are not).
# Prints a summary; the figures of docs/scheme.md ("The error estimate of a run", Cost) come
# from it.
#
#   bench/error_estimate_cost.sh            # callgrind only, about 2 minutes on 2 cores
#   bench/error_estimate_cost.sh --cpu 5    # and 5 + 5 timed runs to t = 10 (~15 s more)
#
# Environment: BUILD_DIR (as scripts/setup.sh; Release is forced), WP_SKIP_BUILD=1, WP_OUT
# (default out/bench; the raw files go to $WP_OUT/error_estimate_cost).
# Exit status: 0 done; 1 build or run failure; 2 usage.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cpu_runs=0
args=()
while (($#)); do
    case "$1" in
        --cpu)
            [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || { echo "error_estimate_cost: --cpu needs a count" >&2; exit 2; }
            cpu_runs=$2
            shift 2
            ;;
        *) args+=("$1"); shift ;;
    esac
done
. "$repo_root/bench/quick_option.sh" error_estimate_cost "${args[@]}"
. "$repo_root/bench/build_for_bench.sh" rodcontact
command -v valgrind >/dev/null || { say "valgrind is not installed (scripts/setup.sh installs it)"; exit 1; }
raw_dir="$out/error_estimate_cost"
mkdir -p "$raw_dir"
input="$repo_root/input/exp1.nml"
common=(--set output.quiet=.true.)
estimate=(--set output.error_estimate=.true.)

# measure <name> <arg>...: callgrind_annotate --inclusive=yes of one run to t = 2 into <name>.txt
measure() {
    local name="$1"
    shift
    local prefix="$raw_dir/$name"
    rm -f "$prefix.h5"
    if ! valgrind --tool=callgrind --callgrind-out-file="$prefix.cg" "$exe" "$input" "${common[@]}" \
        --set time.t_end=2 --set output.prefix="'$prefix'" "$@" >"$prefix.out" 2>"$prefix.err"; then
        say "run failed: $* (stderr: $prefix.err)"
        exit 1
    fi
    callgrind_annotate --inclusive=yes --threshold=100 "$prefix.cg" >"$prefix.txt" 2>/dev/null
    rm -f "$prefix.cg" "$prefix.h5"
}

measure without &
pid=$!
measure with "${estimate[@]}"
wait "$pid"

# inclusive <name> <function pattern>: the inclusive instructions of the first function matching
inclusive() {
    awk -v pat="$2" '$0 ~ pat { gsub(",", "", $1); print $1; found = 1; exit } END { if (!found) print 0 }' \
        "$raw_dir/$1.txt"
}
total() { awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1; exit }' "$raw_dir/$1.txt"; }

off=$(total without)
on=$(total with)
run_steps=$(inclusive without '_MOD_stepper_advance ')
steps=$(inclusive with 'error_companion_m_MOD_step_over')
setup=$(inclusive with 'error_companion_m_MOD_companions_init ')
estimate_pass=$(inclusive with 'error_companion_m_MOD_companions_estimate ')
landing=$(inclusive with 'land_level')
writer=$(inclusive with '_MOD_writer_append_estimate ')
awk -v off="$off" -v on="$on" -v run="$run_steps" -v steps="$steps" -v setup="$setup" \
    -v est="$estimate_pass" -v land="$landing" -v writer="$writer" 'BEGIN {
    s = 500
    share = ((s / 2 + 1) / 2 + (s / 4 + 1) / 4 + (s / 4 + 1) / 8) / (s + 1)
    extra = on - off
    printf "Experiment 1 to t = 2 (s = 500, dt = 1e-4, Euler), valgrind callgrind:\n"
    printf "  without the estimate  %.4g instructions (the run'"'"'s stepping %.4g)\n", off, run
    printf "  with the estimate     %.4g instructions: %+.2f %%\n", on, 100 * extra / off
    printf "  of the difference (%.4g):\n", extra
    printf "    companions'"'"' steps     %.4g  (%.2f %% of the run; %.3f of the run'"'"'s stepping, nodes x steps %.3f)\n", \
        steps, 100 * steps / off, steps / run, share
    printf "    companions'"'"' set-up    %.4g  (%.2f %%)\n", setup, 100 * setup / off
    printf "    estimate pass         %.4g  (%.2f %%; its landing steps are in the steps)\n", \
        est - land, 100 * (est - land) / off
    printf "    writing the estimate  %.4g  (%.2f %%)\n", writer, 100 * writer / off
    rest = extra - steps - setup - (est - land) - writer
    printf "    the rest              %.4g  (%.2f %%)\n", rest, 100 * rest / off
}'

if ((cpu_runs)); then
    timing="$raw_dir/time.txt"
    without_times=()
    with_times=()
    for ((i = 0; i < cpu_runs; i++)); do
        for mode in without with; do
            extra_args=()
            [[ $mode == with ]] && extra_args=("${estimate[@]}")
            if ! /usr/bin/time -o "$timing" -f "%U %S" "$exe" "$input" "${common[@]}" --set time.t_end=10 \
                --set output.prefix="'$raw_dir/cpu_$mode'" "${extra_args[@]}" >/dev/null 2>&1; then
                say "timed run failed ($mode)"
                exit 1
            fi
            seconds=$(awk '{ print $1 + $2 }' "$timing")
            if [[ $mode == without ]]; then without_times+=("$seconds"); else with_times+=("$seconds"); fi
        done
    done
    rm -f "$raw_dir"/cpu_*.h5 "$timing"
    median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
    m_without=$(median "${without_times[@]}")
    m_with=$(median "${with_times[@]}")
    printf "CPU time to t = 10 (user + sys), %d runs each, alternated; load average %s:\n" "$cpu_runs" \
        "$(cut -d' ' -f1-3 /proc/loadavg)"
    printf "  without: %s\n  with:    %s\n" "${without_times[*]}" "${with_times[*]}"
    awk -v a="$m_without" -v b="$m_with" 'BEGIN { printf "  medians %.2f s and %.2f s: %+.1f %%\n", a, b, 100 * (b / a - 1) }'
fi
