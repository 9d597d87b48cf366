#!/usr/bin/env bash
# Benchmark (not a test): work-precision of the three time schemes, implicit Euler (6.1),
# BDF2 and the midpoint rule (&time scheme='midpoint'), on experiment 1 and on the impact
# case, drawn as figures/work_precision_schemes.png (gnuplot), with the data and a Markdown
# section for docs/performance.md (out/bench/work_precision_schemes.md; bench/report.py
# includes it).
#
#   bench/work_precision_schemes.sh            # ~2.5 minutes on 2 cores
#   bench/work_precision_schemes.sh --quick    # a few coarse points (checks the pipeline;
#                                                # the figure goes to out/bench-quick/)
#
# (a) Experiment 1 (input/exp1.nml, h = 1/500), the time error alone: dt = 4e-4 ... 2.5e-5
#     for each scheme against a midpoint run with dt = 2.5e-6 on the same mesh, to t = 2
#     (contact from t ~ 0.19 to ~ 1.45): max over t_n <= 2 of |u(1,t_n) - u_ref(1,t_n)|,
#     the same before the reference's first contact, and the errors at t = 2 (relative L2
#     of theta, H1 of u). The reference is checked against the same scheme with 2 dt.
# (b) The impact case (input/impact.nml, s = 1000), both contact laws, to t = 4,
#     dt = 1e-3 ... 6.25e-5: max over t_n < 1 - sqrt(0.9) of |u(1,t_n) - (t_n - t_n^2/2)|
#     (the exact pre-contact solution), E(4)/E(0) - 1 and the largest one-step rise of E^n.
#     Floor check: the pre-contact error of a fine run with s = 4000 (is the floor the mesh?).
# Only the steps are timed (rodcontact_work_precision, modes uend and impact of
# bench/work_precision.f90: each stepper%advance timed alone, the recording of u(1,t) and
# E^n after it is not); the points of one command are run round robin, 5 rounds, and the median taken.
#
# Environment: BUILD_DIR (as scripts/setup.sh; Release is forced), WP_SKIP_BUILD=1 (the
# caller has built), WP_OUT (data directory, default out/bench; --quick: out/bench-quick).
# Exit status: 0 done; 1 build, run or plot failed; 2 usage.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$repo_root/bench/quick_option.sh" work_precision_schemes "$@"

. "$repo_root/bench/build_for_bench.sh" bench/rodcontact_work_precision
mkdir -p "$out" "$repo_root/figures"
python="$(command -v python3 || echo /usr/bin/python3)"
schemes=(euler bdf2 midpoint)

# --- the points ------------------------------------------------------------------------
if ((quick)); then
    exp1_tend=0.4; exp1_ref=midpoint:500:2e-5; exp1_dts=(4e-4 2e-4)
    impact_tend=0.5; impact_dts=(1e-3 5e-4)
else
    exp1_tend=2; exp1_ref=midpoint:500:2.5e-6; exp1_dts=(4e-4 2e-4 1e-4 5e-5 2.5e-5)
    impact_tend=4; impact_dts=(1e-3 5e-4 2.5e-4 1.25e-4 6.25e-5)
fi
floor_points=(midpoint:1000:6.25e-5 midpoint:4000:3.125e-5)   # to t = 0.1, after the onset

meta="$out/wps_meta.txt"
{
    echo "load_start=$(cut -d' ' -f1-3 /proc/loadavg)"
    echo "blas=$(ldd "$exe" | awk '$1 ~ /^lib(blas|lapack|openblas)/ { printf "%s -> %s; ", $1, $3 }')"
    echo "commit=$(git -C "$repo_root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
    echo "exp1_tend=$exp1_tend"
    echo "impact_tend=$impact_tend"
} >"$meta"

points=()
for scheme in "${schemes[@]}"; do
    for dt in "${exp1_dts[@]}"; do points+=("$scheme:500:$dt"); done
done
say "experiment 1 to t = $exp1_tend, reference $exp1_ref, ${#points[@]} points"
"$exe" uend "$repo_root/input/exp1.nml" "$exp1_tend" "$exp1_ref" "${points[@]}" >"$out/wps_exp1.raw"

points=()
for scheme in "${schemes[@]}"; do
    for dt in "${impact_dts[@]}"; do points+=("$scheme:1000:$dt"); done
done
for law in penalty signorini; do
    say "impact case to t = $impact_tend, $law law, ${#points[@]} points"
    "$exe" impact "$repo_root/input/impact.nml" "$impact_tend" "$law" "${points[@]}" >"$out/wps_impact_$law.raw"
done
say "impact case: the floor of the pre-contact error (s = 1000 and 4000, to t = 0.1)"
"$exe" impact "$repo_root/input/impact.nml" 0.1 penalty "${floor_points[@]}" >"$out/wps_impact_floor.raw"
echo "load_end=$(cut -d' ' -f1-3 /proc/loadavg)" >>"$meta"

# --- data files for gnuplot, Markdown section, figure -----------------------------------------
"$python" "$repo_root/bench/work_precision_schemes.py" "$out"
figure="$repo_root/figures/work_precision_schemes.png"
((quick)) && figure="$out/work_precision_schemes_quick.png"      # a pipeline check, not the figure
gnuplot -e "datadir='$out'; out='$figure'" "$repo_root/scripts/gnuplot/work_precision_schemes.gp"
say "wrote $figure, $out/work_precision_schemes.md"
