#!/usr/bin/env bash
# Benchmark (not a test): work-precision diagram, error at the final time against the wall
# time of the time stepping, for the implicit Euler scheme (6.1) and BDF2, drawn as
# figures/work_precision.png (gnuplot), with the data and a Markdown summary (pairs,
# speed-up at equal error) for docs/performance.md.
#
#   bench/work_precision.sh            # ~2 minutes on 2 cores
#   bench/work_precision.sh --quick    # a few coarse points only (checks the pipeline;
#                                        # the figure goes to out/bench/work_precision_quick.png)
#
# (a) Manufactured solution: mms_no_contact of tests/lib/mms_m with the O(1) model of
#     tests/test_convergence.f90, to t_end = 1, errors against the exact solution: L2 of
#     theta and H1 of u at t_end. Pairs (h = 1/s, dt), each sequence a line:
#       Euler  h = dt                 (Corollary 6.4's O(h + dt) coupling)
#       Euler  dt = h^2/2             (balances Euler's O(dt) against P1's O(h^2) in L2)
#       Euler  dt = h/8               (balances O(dt) against P1's O(h) in H1; 1/8 from the
#                                     measured constants, see docs/performance.md)
#       BDF2   h = dt
#       BDF2   dt = sqrt(h)/4         (balances O(dt^2) against O(h) in H1)
# (b) Experiment 2 (input/exp2.nml) to t_end = 0.4 (after the contact begins at t ~ 0.30,
#     with the P pulse front still sharp), errors relative to a BDF2 reference run with
#     s = 8000, dt = 4e-5 (checked against s = 4000, dt = 8e-5): L2 of theta, H1 of u and L2
#     of P, with dt = 0.4 h and dt = 0.05 h (the paper's ratio, h = 1/500 and dt = 1e-4)
#     for both schemes.
# (c) Experiment 2, the time error alone: s = 400 fixed, dt = 4e-3 ... 2.5e-4 against a
#     BDF2 run with s = 400, dt = 5e-6, at t = 0.2 (fronts, before the contact) and t = 0.4
#     (after it): observed orders in dt (table only).
# Only the time loop is timed (rodcontact_work_precision, bench/work_precision.f90); runs
# shorter than 0.2 s are repeated and the median taken. The machine may be shared: the
# times are noisy, the ratios between schemes (tens to hundreds) are not.
#
# Environment: BUILD_DIR (as scripts/setup.sh; Release is forced), WP_SKIP_BUILD=1 (the
# caller has built), WP_OUT (data directory, default out/bench).
# Exit status: 0 done; 1 build, run or plot failed.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
quick=0
case "${1:-}" in
    --quick) quick=1 ;;
    "") ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "work_precision: unknown option '$1' (--quick, --help)" >&2; exit 1 ;;
esac

if [[ "${WP_SKIP_BUILD:-0}" != 1 ]]; then
    BUILD_TYPE=Release "$repo_root/scripts/setup.sh"
fi
build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
exe="$build_dir/bench/rodcontact_work_precision"
[[ -x "$exe" ]] || { echo "work_precision: $exe not built" >&2; exit 1; }
out="${WP_OUT:-$repo_root/out/bench}"
mkdir -p "$out" "$repo_root/figures"
python="$(command -v python3 || echo /usr/bin/python3)"

# --- the points ------------------------------------------------------------------------
# scheme:s:dt with dt dividing t_end exactly. The label of each point's sequence is kept
# in a parallel list for the plot.
mms_points=()
mms_labels=()
add_mms() {   # add_mms <label> <scheme> <s> <dt>
    mms_labels+=("$1")
    mms_points+=("$2:$3:$4")
}
exp2_points=()
exp2_labels=()
add_exp2() {
    exp2_labels+=("$1")
    exp2_points+=("$2:$3:$4")
}
if ((quick)); then
    for s in 10 20 40; do
        add_mms euler_h=dt euler "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 1 / s }')"
        add_mms bdf2_h=dt bdf2 "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 1 / s }')"
    done
    exp2_ref="bdf2:800:4e-4"; exp2_tend=0.04
    for s in 100 200; do
        add_exp2 euler_dt=0.4h euler "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 0.4 / s }')"
        add_exp2 bdf2_dt=0.4h bdf2 "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 0.4 / s }')"
    done
    dt_ref="bdf2:100:1e-4"; dt_tends=(0.04); dt_list=(4e-3 2e-3)
else
    for s in 10 20 40 80 160 320 640; do
        add_mms euler_h=dt euler "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 1 / s }')"
    done
    for s in 10 20 40 80; do
        add_mms euler_dt=h^2/2 euler "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 0.5 / (s * s) }')"
    done
    for s in 40 80 160 320 640; do
        add_mms euler_dt=h/8 euler "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 0.125 / s }')"
    done
    for s in 10 20 40 80 160 320 640; do
        add_mms bdf2_h=dt bdf2 "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 1 / s }')"
    done
    for s in 16 64 256 1024 4096; do     # dt = sqrt(h)/4 = 1/16 ... 1/256
        add_mms "bdf2_dt=sqrt(h)/4" bdf2 "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 0.25 / sqrt(s) }')"
    done
    exp2_ref="bdf2:8000:4e-5"; exp2_tend=0.4
    for scheme in euler bdf2; do
        for s in 100 200 400 800 1600; do
            add_exp2 "${scheme}_dt=0.4h" "$scheme" "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 0.4 / s }')"
        done
        for s in 100 200 400 800 1600; do
            add_exp2 "${scheme}_dt=0.05h" "$scheme" "$s" "$(awk -v s="$s" 'BEGIN { printf "%.10g", 0.05 / s }')"
        done
    done
    dt_ref="bdf2:400:5e-6"; dt_tends=(0.2 0.4); dt_list=(4e-3 2e-3 1e-3 5e-4 2.5e-4)
fi
dt_s="$(cut -d: -f2 <<<"$dt_ref")"      # (c): every point on the reference's mesh
dt_points=()
dt_labels=()
for scheme in euler bdf2; do
    for dt in "${dt_list[@]}"; do
        dt_points+=("$scheme:$dt_s:$dt")
        dt_labels+=("${scheme}_s=$dt_s")
    done
done

printf '%s\n' "${mms_labels[@]}" >"$out/work_precision_mms.labels"
printf '%s\n' "${exp2_labels[@]}" >"$out/work_precision_exp2.labels"
echo "work_precision: manufactured solution, ${#mms_points[@]} runs" >&2
"$exe" mms 1 "${mms_points[@]}" >"$out/work_precision_mms.raw"
echo "work_precision: experiment 2 to t = $exp2_tend, reference $exp2_ref, ${#exp2_points[@]} runs" >&2
"$exe" exp2 "$repo_root/input/exp2.nml" "$exp2_tend" "$exp2_ref" "${exp2_points[@]}" >"$out/work_precision_exp2.raw"

for tend in "${dt_tends[@]}"; do
    echo "work_precision: experiment 2, time error alone at t = $tend, reference $dt_ref, ${#dt_points[@]} runs" >&2
    printf '%s\n' "${dt_labels[@]}" >"$out/work_precision_exp2dt_$tend.labels"
    "$exe" exp2dt "$repo_root/input/exp2.nml" "$tend" "$dt_ref" "${dt_points[@]}" >"$out/work_precision_exp2dt_$tend.raw"
done

# --- data files for gnuplot, speed-ups, Markdown summary ----------------------------------
"$python" "$repo_root/bench/work_precision.py" "$out" "$exp2_tend" "${dt_tends[@]}"
figure="$repo_root/figures/work_precision.png"
((quick)) && figure="$out/work_precision_quick.png"      # a pipeline check, not the figure
gnuplot -e "datadir='$out'; out='$figure'" "$repo_root/scripts/gnuplot/work_precision.gp"
echo "work_precision: wrote $figure, $out/work_precision.md" >&2
