#!/usr/bin/env bash
# Do the GCI bands of scripts/converge.sh hold the true error? Six small cases that the
# method was not tuned on (tests/test_converge.sh's case is experiment 1 at varpi = 0.1).
# The first benchmark's three (the method's last changes were measured on them):
#   exp1, varpi = 0.3, g = 0.05  implicit Euler, through the first contact (t <= 0.6)
#   exp2, amplitude 12, BDF2 the two pulses of height 12 instead of 20, before contact (t <= 0.25)
#   impact, g = 0.08         the midpoint rule, a gap of 0.08 instead of 0.05 (t <= 0.5)
# and three added before the rule for oscillatory convergence changed (issue 26), each
# family with another scheme, another material or pulse, another gap:
#   exp3, midpoint           Fourier and Fick laws (tau = tau0 = 0), through the first contact (t <= 0.5)
#   exp1, varpi = 0.2, g = 0.08, BDF2   through the first contact (t <= 0.6)
#   impact, g = 0.03, u1 = 0.8 x, Euler a slower bar and a smaller gap (t <= 0.5)
# each a converge.sh ladder of three levels refined in time and space together by 2 whose
# finest level is the shipped input's resolution (exp1, exp2, exp3: s = 500, dt = 1e-4; impact:
# s = 1000, dt = 2.5e-4), against a truth 8 times finer in h and dt than that (4 times with
# --quick) and, before the first contact, the exact solution (tests/tools/exact_linear.py). Writes
# OUT/converge_bands/table.md (the table of docs/verification.md, "Checking convergence with
# scripts/converge.sh") and, unless CB_NO_SPLICE=1 or --quick, puts it into docs/verification.md
# between its converge_bands markers.
#
#   bench/converge_bands.sh            # about 70 s on 2 cores at load 6
#   bench/converge_bands.sh --quick    # truths 4 x finer only (as long: the exact solutions and
#                                      # the ladders dominate); the page is left alone
#
# Environment: WP_SKIP_BUILD=1 (use the existing build), BUILD_DIR, WP_OUT (default out/bench
# or out/bench-quick), CB_NO_SPLICE=1.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$repo_root/bench/quick_option.sh" converge_bands "$@"
. "$repo_root/bench/build_for_bench.sh" rodcontact
dir="$out/converge_bands"
rm -rf "$dir"
mkdir -p "$dir"
py="$("$repo_root/scripts/lib/find_python.sh")" || exit 1
"$py" -c 'import scipy.fft, scipy.linalg' 2> /dev/null ||
    { say "$py cannot import scipy (Debian: apt-get install python3-scipy)"; exit 1; }
truth_factor=$((quick ? 4 : 8))       # the truth's h and dt: the finest level's / truth_factor

# study NAME LABEL INPUT N DT EXACT ARGS...: the ladder (base N elements, step DT) in
# DIR/NAME, its truth (N * 4 * truth_factor elements, DT / (4 * truth_factor)), the comparison
study() {
    local name=$1 label=$2 input=$3 n=$4 dt=$5 exact=$6
    shift 6
    say "$name: converge.sh (n = $n, dt = $dt, 3 levels, both refined by 2)"
    RODCONTACT=$exe bash "$repo_root/scripts/converge.sh" "$input" --set "mesh.n_elements=$n" \
        --set "time.dt=$dt" "$@" --out "$dir/$name" > "$dir/$name.table" 2> "$dir/$name.log" ||
        { say "$name: converge.sh failed: $(tail -n 3 "$dir/$name.log")"; exit 1; }
    local nt dtt
    nt=$((n * 4 * truth_factor))
    dtt=$(awk -v d="$dt" -v f="$truth_factor" 'BEGIN { printf "%.15g", d / (4 * f) }')
    say "$name: truth (n = $nt, dt = $dtt)"
    local snap arg args=()
    snap=$("$py" "$repo_root/scripts/lib/rodrun.py" attr "$dir/$name/level_0/point_0000.h5" output.snapshot_every)
    for arg in "$@"; do
        [[ $arg == output.snapshot_every=* ]] && { unset 'args[-1]'; continue; }
        args+=("$arg")
    done
    "$exe" "$input" --set "mesh.n_elements=$nt" --set "time.dt=$dtt" "${args[@]}" \
        --set "output.snapshot_every=$((snap * 4 * truth_factor))" --set output.series_every=1 \
        --set "output.prefix=$dir/${name}_truth" --set output.quiet=.true. > /dev/null 2> "$dir/${name}_truth.err" ||
        { say "$name: the truth run failed: $(head -n 3 "$dir/${name}_truth.err")"; exit 1; }
    local extra=()
    ((exact)) && extra=(--exact)
    "$py" "$repo_root/bench/converge_bands.py" compare "$dir/$name" --truth "$dir/${name}_truth.h5" \
        "${extra[@]}" --case "$label" --csv "$dir/$name.csv" > "$dir/$name.compare"
    tail -n 1 "$dir/$name.compare" >&2
}

study exp1_varpi03 "exp1, ϖ = 0.3, g = 0.05, Euler" "$repo_root/input/exp1.nml" 125 4e-4 1 \
    --set model.varpi=0.3 --set contact.g=0.05 --set time.t_end=0.6 --set output.snapshot_every=250
study exp2_amp12 "exp2, amplitude 12, BDF2" "$repo_root/input/exp2.nml" 125 4e-4 1 \
    --set 'initial.theta0_step=12,0.1' --set 'initial.p0_step=12,0.1' --set time.scheme=bdf2 \
    --set time.t_end=0.25 --set output.snapshot_every=125
study impact_g008 "impact, g = 0.08, midpoint" "$repo_root/input/impact.nml" 250 1e-3 0 \
    --set contact.g=0.08 --set time.t_end=0.5 --set output.snapshot_every=100
study exp3_midpoint "exp3, midpoint" "$repo_root/input/exp3.nml" 125 4e-4 1 \
    --set time.scheme=midpoint --set time.t_end=0.5 --set output.snapshot_every=125
study exp1_varpi02 "exp1, ϖ = 0.2, g = 0.08, BDF2" "$repo_root/input/exp1.nml" 125 4e-4 1 \
    --set model.varpi=0.2 --set contact.g=0.08 --set time.scheme=bdf2 --set time.t_end=0.6 \
    --set output.snapshot_every=250
study impact_g003 "impact, g = 0.03, u1 = 0.8 x, Euler" "$repo_root/input/impact.nml" 250 1e-3 0 \
    --set contact.g=0.03 --set 'initial.u1_poly=0,0.8' --set time.scheme=euler --set time.t_end=0.5 \
    --set output.snapshot_every=100

"$py" "$repo_root/bench/converge_bands.py" report --md "$dir/table.md" \
    --group "the first benchmark's three cases" "$dir"/exp1_varpi03.csv "$dir"/exp2_amp12.csv "$dir"/impact_g008.csv \
    --group "the three cases added in issue 26" "$dir"/exp3_midpoint.csv "$dir"/exp1_varpi02.csv "$dir"/impact_g003.csv \
    > /dev/null
{
    echo "Measured by \`bench/converge_bands.sh$( ((quick)) && echo ' --quick')\` ($(date -u +%Y-%m-%d),"
    echo "load average $(cut -d' ' -f1 /proc/loadavg) on $(nproc) cores; truth ${truth_factor}x finer than the finest level):"
    echo
    cat "$dir/table.md"
} > "$dir/table.tmp" && mv "$dir/table.tmp" "$dir/table.md"
cat "$dir/table.md"
page="$repo_root/docs/verification.md"
if ((quick == 0)) && [[ ${CB_NO_SPLICE:-0} != 1 ]]; then
    grep -q '^<!-- converge_bands begin -->$' "$page" && grep -q '^<!-- converge_bands end -->$' "$page" ||
        { say "no converge_bands markers in $page: the table is in $dir/table.md"; exit 1; }
    awk -v table="$dir/table.md" '
        /^<!-- converge_bands begin -->$/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
        /^<!-- converge_bands end -->$/ { skip = 0 }
        !skip' "$page" > "$dir/page.tmp" && mv "$dir/page.tmp" "$page"
    say "wrote the table into $page"
fi
