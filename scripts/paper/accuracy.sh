#!/usr/bin/env bash
# Make the runs of the accuracy study of docs/reproduction.md and write its section (a
# markdown fragment that scripts/paper/claims.py puts into the document):
#   - the paper's runs (out/, as scripts/paper/figures.sh --with-long makes them);
#   - the six inputs at three other resolutions, h and dt refined together:
#     s = 250, dt = 2e-4; s = 1000, dt = 5e-5; s = 2000, dt = 2.5e-5 (out/res/s<S>/);
#     exp1_long at s = 250 and 1000 (at s = 2000 it would take ~7 min: the s = 1000 copy is
#     used there, and the document says so);
#   - references after contact: exp1, exp2, exp3 to t = 1 with BDF2 at s = 4000,
#     dt = 1.25e-5 and s = 8000, dt = 6.25e-6 (out/ref/bdf2_s<S>/), the finest uniform runs
#     that take about a minute each here; the two are compared to say how converged they are.
# Runs that are up to date are reused; the first call takes about 10 minutes on one core.
#
#   scripts/paper/accuracy.sh                  # writes out/accuracy.md
#   scripts/paper/accuracy.sh --quick          # a pipeline check: coarse stand-ins (s = 100, 200,
#                                        # 400; references s = 800, 1600 to t = 0.4), seconds
#
# Options: --out DIR (default out/, with --quick ${TMPDIR:-/tmp}/rodcontact-quick/acc),
#          --exe PATH (default: build with scripts/setup.sh), --force (rerun everything).
# Then scripts/paper/claims.sh (which calls this script) writes docs/reproduction.md with it.
# Exit status: 0 written; 1 a run or the analysis failed; 2 usage error.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
scripts="$repo_root/scripts"
say() { echo "accuracy: $*" >&2; }
usage() { sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//' >&2; exit "${1:-2}"; }

quick=0 force=() out_dir="" exe=""
while (($# > 0)); do
    case "$1" in
        --quick) quick=1 ;;
        --force) force=(--force) ;;
        --out | --exe)
            (($# >= 2)) || { say "$1 needs a value"; usage; }
            [[ "$1" == --out ]] && out_dir="$2" || exe="$2"
            shift ;;
        -h | --help) usage 0 ;;
        *) say "unknown argument '$1'"; usage ;;
    esac
    shift
done
if ((quick)); then
    out_dir="${out_dir:-${TMPDIR:-/tmp}/rodcontact-quick/acc}"
    levels=("100 1e-3" "200 5e-4" "400 2.5e-4") paper_level="200 5e-4"
    refs=("800 1.25e-4" "1600 6.25e-5") ref_end=0.4
else
    out_dir="${out_dir:-$repo_root/out}"
    levels=("250 2e-4" "1000 5e-5" "2000 2.5e-5") paper_level=""
    refs=("4000 1.25e-5" "8000 6.25e-6") ref_end=1.0
fi
mkdir -p "$out_dir"
out_dir="$(cd "$out_dir" && pwd)"
if [[ -z "$exe" ]]; then
    "$scripts/setup.sh"
    build_dir="${BUILD_DIR:-build}"
    [[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
    exe="$build_dir/rodcontact"
fi
py="$("$scripts/lib/find_python.sh")" || { say "no Python with h5py"; exit 1; }
"$py" -c 'import scipy.linalg, scipy.fft' 2>/dev/null ||
    { say "$py cannot import scipy (Debian: python3-scipy; scripts/setup.sh installs it)"; exit 1; }

# 1. the paper's runs and the other resolutions (scripts/paper/figures.sh does the runs)
if ((quick)); then
    read -r s dt <<<"$paper_level"
    "$scripts/paper/figures.sh" --runs-only --with-long --quick --exe "$exe" --out "$out_dir/paper" \
        --resolution "$s" "$dt" "${force[@]}" || exit 1
    paper_dir="$out_dir/paper"
else
    "$scripts/paper/figures.sh" --runs-only --with-long --exe "$exe" --out "$out_dir" "${force[@]}" || exit 1
    paper_dir="$out_dir"
fi
res_args=()
long_dir=""
for level in "${levels[@]}"; do
    read -r s dt <<<"$level"
    [[ "$level" == "$paper_level" ]] && continue
    dir="$out_dir/res/s$s"
    long=(--with-long)
    ((!quick && s > 1000)) && long=()
    qk=()
    ((quick)) && qk=(--quick)
    "$scripts/paper/figures.sh" --runs-only "${long[@]}" "${qk[@]}" --exe "$exe" --out "$dir" \
        --resolution "$s" "$dt" "${force[@]}" || exit 1
    if ((${#long[@]} > 0)); then
        long_dir="$dir"
    else   # the long copy of the finest resolution that has one (stated in the document)
        ln -sf "$long_dir/exp1_long.h5" "$dir/exp1_long.h5"
    fi
    res_args+=(--level "s=$s, Δt=$dt=$dir")
done

# 2. references after contact: BDF2, exp1 exp2 exp3 to t = ref_end
ref_args=()
for level in "${refs[@]}"; do
    read -r s dt <<<"$level"
    dir="$out_dir/ref/bdf2_s$s"
    mkdir -p "$dir"
    snap=$(awk -v d="$dt" 'BEGIN { print int(0.01 / d + 0.5) }')
    for name in exp1 exp2 exp3; do
        copy="$dir/$name.nml" h5="$dir/$name.h5"
        "$py" "$scripts/lib/nml_copy.py" "$repo_root/input/$name.nml" "$copy.new" \
            "output.prefix='$dir/$name'" output.quiet=.true. mesh.n_elements="$s" time.dt="$dt" \
            time.scheme="'bdf2'" time.t_end="$ref_end" output.snapshot_every="$snap" output.series_every=1
        if ((${#force[@]} == 0)) && [[ -f "$h5" && "$h5" -nt "$exe" && -f "$copy" ]] && cmp -s "$copy.new" "$copy"; then
            rm -f "$copy.new"
            say "ref s=$s $name: up to date"
            continue
        fi
        mv "$copy.new" "$copy"
        say "ref s=$s $name: running (BDF2, dt = $dt, to t = $ref_end)"
        "$exe" "$copy" >"$dir/$name.log" 2>&1 || { say "run failed: $(tail -n 3 "$dir/$name.log")"; exit 1; }
    done
    ref_args+=(--ref "BDF2 s=$s, Δt=$dt=$dir")
done

# 3. the analysis
"$py" "$scripts/paper/accuracy.py" --paper "$paper_dir" "${res_args[@]}" "${ref_args[@]}" \
    --md "$out_dir/accuracy.md" $( ((quick)) && echo --quick --modes 16384) || exit 1
# for scripts/paper/claims.sh: the resolutions, one 'LABEL=DIR' per line
printf '%s\n' "${res_args[@]}" | sed -n 's/^--level$//;t;p' >"$out_dir/accuracy.levels"
say "wrote $out_dir/accuracy.md"
