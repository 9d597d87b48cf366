#!/usr/bin/env bash
# Reproduce the figures of Section 7 of the paper: run every input/exp*.nml that is not
# up to date, then draw Figures 2-7 as PNG and PDF with gnuplot, from the HDF5 files
# (through scripts/h5extract.py, which writes the plotted data as text), in two forms:
#   fig<N>.png           families of profiles at marked times (values can be read off;
#                        fronts of experiment 2 against the predicted ones)
#   fig<N>_surface.png   the same fields as surfaces over (x, t), the form of the paper's
#                        figures, in its panel layout (scripts/lib/plotdata.py and
#                        scripts/gnuplot/run_surface.gp, as scripts/plot.sh draws any run)
# Figure 4 (time series) has one form; it gains a panel with the parts of the energy when
# the files hold them (/series/energy_<part>), and /snapshots/sigma, when present, is drawn
# as a surface (fig2_surface adds it for experiment 1).
#
#   scripts/paper/figures.sh                  # runs into out/, figures into out/figures/
#   scripts/paper/figures.sh --refresh        # the same, figures into figures/ (the committed
#                                             # ones: refresh them after a change of the code)
#   scripts/paper/figures.sh --force          # rerun every input even if its output is up to date
#   scripts/paper/figures.sh --quick          # shortened runs (t_end = 0.3) and their figures, in
#                                       # ${TMPDIR:-/tmp}/rodcontact-quick/{out,figures}
#
# Options:
#   --out DIR       directory of the HDF5 files (default out/, with --quick see above)
#   --figdir DIR    directory of fig2.png ... fig7.pdf (default out/figures/, with --quick see
#                   above, with --refresh the repository's figures/)
#   --refresh       write the figures into the repository's figures/, which are committed (the
#                   default leaves the tracked files alone). Drawing them twice gives the same
#                   files byte for byte: the PDFs' CreationDate is set to the date of the
#                   latest commit (or SOURCE_DATE_EPOCH when set), not the time of drawing
#   --exe PATH      rodcontact binary to use (default: build it with scripts/setup.sh, which
#                   honours BUILD_DIR, and use $BUILD_DIR/rodcontact)
#   --force         rerun every input
#   --quick         shortened copies of the inputs: t_end = 0.3 (a pipeline check, not the paper)
#   --runs-only     only make the HDF5 files (used by scripts/paper/claims.sh)
#   --with-long     also run exp1_long: input/exp1.nml up to t = 60 (for scripts/paper/claims.sh)
#   --resolution S DT   run every input with n_elements = S and dt = DT instead of the
#                   input's (the paper's 500 and 1e-4), snapshots every 0.01 (exp1_long:
#                   every 0.1, series every 0.001) as in the shipped inputs; used by
#                   scripts/paper/accuracy.sh for the claims at other resolutions
#
# A run is skipped when <out>/<name>.h5 is newer than its input and the binary, is complete,
# and was made from the same namelist (the copy <out>/<name>.nml that was run: the input with
# &output prefix and quiet set, and the --quick/--with-long changes). Each run's output goes
# to <out>/<name>.log.
# Needs: a Python with h5py (scripts/lib/find_python.sh), gnuplot with the pngcairo and pdfcairo
# terminals (Debian: gnuplot-nox) and the DejaVu fonts (fonts-dejavu-core).
# Exit status: 0 done; 1 a tool is missing, a run failed or a figure could not be drawn;
# 2 usage error.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
scripts="$repo_root/scripts"

usage() {   # usage [status]: the header comment; on stdout for --help, else on stderr
    if ((${1:-2} == 0)); then
        sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//'
    else
        sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//' >&2
    fi
    exit "${1:-2}"
}
say() { echo "figures: $*" >&2; }

force=0 quick=0 runs_only=0 with_long=0 refresh=0 out_dir="" fig_dir="" exe="" res_s="" res_dt=""
while (($# > 0)); do
    case "$1" in
        --force) force=1 ;;
        --refresh) refresh=1 ;;
        --quick) quick=1 ;;
        --runs-only) runs_only=1 ;;
        --with-long) with_long=1 ;;
        --out | --figdir | --exe)
            (($# >= 2)) || { say "$1 needs a value"; usage; }
            case "$1" in
                --out) out_dir="$2" ;;
                --figdir) fig_dir="$2" ;;
                --exe) exe="$2" ;;
            esac
            shift ;;
        --resolution)
            (($# >= 3)) || { say "--resolution needs S and DT"; usage; }
            res_s="$2" res_dt="$3"
            [[ "$res_s" =~ ^[0-9]+$ ]] || { say "--resolution: S must be a whole number, got '$res_s'"; usage; }
            awk -v d="$res_dt" 'BEGIN { exit !(d + 0 > 0) }' || { say "--resolution: DT must be > 0, got '$res_dt'"; usage; }
            shift 2 ;;
        -h | --help) usage 0 ;;
        *) say "unknown argument '$1'"; usage ;;
    esac
    shift
done
every() { awk -v T="$1" -v d="$res_dt" 'BEGIN { n = int(T / d + 0.5); print (n < 1 ? 1 : n) }'; }
res_opts=() res_long=()
if [[ -n "$res_s" ]]; then
    res_opts=(mesh.n_elements="$res_s" time.dt="$res_dt" output.snapshot_every="$(every 0.01)")
    res_long=(mesh.n_elements="$res_s" time.dt="$res_dt" output.snapshot_every="$(every 0.1)"
              output.series_every="$(every 0.001)")
fi

quick_base="${TMPDIR:-/tmp}/rodcontact-quick"
if ((quick)); then
    out_dir="${out_dir:-$quick_base/out}"
    fig_dir="${fig_dir:-$quick_base/figures}"
else
    out_dir="${out_dir:-$repo_root/out}"
    if ((refresh)); then
        fig_dir="${fig_dir:-$repo_root/figures}"
    else
        fig_dir="${fig_dir:-$out_dir/figures}"
    fi
fi
for d in "$out_dir" "$fig_dir"; do
    if [[ "$d" == *"'"* || "$d" == *'"'* ]]; then
        say "directory names with quotes are not supported: $d"
        exit 2
    fi
done
mkdir -p "$out_dir"
out_dir="$(cd "$out_dir" && pwd)"

# --- tools -------------------------------------------------------------------------------
py="$("$scripts/lib/find_python.sh")" || { say "no Python with h5py: cannot read the HDF5 files"; exit 1; }
if ((!runs_only)); then
    if ! command -v gnuplot >/dev/null 2>&1; then
        say "gnuplot not found (Debian: apt-get install gnuplot-nox)"
        exit 1
    fi
    for term in pngcairo pdfcairo; do
        if ! gnuplot -e "set terminal $term" </dev/null >/dev/null 2>&1; then
            say "this gnuplot has no '$term' terminal (Debian's gnuplot-nox has it)"
            exit 1
        fi
    done
fi
if [[ -z "$exe" ]]; then
    "$scripts/setup.sh"
    build_dir="${BUILD_DIR:-build}"
    [[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
    exe="$build_dir/rodcontact"
fi
if [[ ! -x "$exe" ]]; then
    say "rodcontact binary not found or not executable: $exe"
    exit 1
fi

# --- runs --------------------------------------------------------------------------------
# run_one <name> <source input> [group.variable=value ...]
run_one() {
    local name=$1 src=$2
    shift 2
    local copy="$out_dir/$name.nml" h5="$out_dir/$name.h5" log="$out_dir/$name.log"
    "$py" "$scripts/lib/nml_copy.py" "$src" "$copy.new" \
        "output.prefix='$out_dir/$name'" output.quiet=.true. "$@"
    if ((!force)) && [[ -f "$h5" && "$h5" -nt "$src" && "$h5" -nt "$exe" && -f "$copy" ]] &&
        cmp -s "$copy.new" "$copy" &&
        [[ "$("$py" "$scripts/lib/rodrun.py" attr "$h5" status 2>/dev/null)" == complete ]]; then
        rm -f "$copy.new"
        say "$name: up to date ($h5)"
        return 0
    fi
    mv "$copy.new" "$copy"
    local t0 t1 status=0
    t0=$(date +%s.%N)
    "$exe" "$copy" >"$log" 2>&1 || status=$?
    t1=$(date +%s.%N)
    if ((status != 0)); then
        say "$name: rodcontact exited with status $status; its output ($log):"
        tail -n 20 "$log" >&2
        exit 1
    fi
    say "$name: ran in $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s -> $h5"
}

start=$(date +%s.%N)
shopt -s nullglob
inputs=("$repo_root"/input/exp*.nml)
shopt -u nullglob
((${#inputs[@]} > 0)) || { say "no input/exp*.nml found"; exit 1; }
quick_opts=()
((quick)) && quick_opts=(time.t_end=0.3)
for input in "${inputs[@]}"; do
    run_one "$(basename "$input" .nml)" "$input" "${quick_opts[@]}" "${res_opts[@]}"
done
if ((with_long)); then
    if ((quick)); then long_end=0.6; else long_end=60; fi
    run_one exp1_long "$repo_root/input/exp1.nml" time.t_end=$long_end \
        output.snapshot_every=1000 output.series_every=10 "${res_long[@]}"
fi
((runs_only)) && exit 0

# --- figures -----------------------------------------------------------------------------
mkdir -p "$fig_dir"
fig_dir="$(cd "$fig_dir" && pwd)"

# fixed_pdf_date FILE: cairo writes the time of drawing into a PDF (/CreationDate (D:...Z)); this
# replaces it, in place and with the same length (the cross-reference offsets stay right), by
# SOURCE_DATE_EPOCH, else the date of the latest commit, else 2000-01-01: the same figure
# drawn twice is the same file. PNGs carry no time.
pdf_date="$(date -u -d "@${SOURCE_DATE_EPOCH:-$(git -C "$repo_root" log -1 --format=%ct 2>/dev/null || echo 946684800)}" +%Y%m%d%H%M%S)"
fixed_pdf_date() {
    [[ "$1" == *.pdf || "$1" == *.pdf.tmp ]] || return 0
    D="$pdf_date" perl -0777 -pi -e 's{/CreationDate \(D:\d{14}Z\)}{/CreationDate (D:$ENV{D}Z)}g' "$1"
}
data_dir="$(mktemp -d "${TMPDIR:-/tmp}/rodcontact-figdata.XXXXXX")"
trap 'rm -rf "$data_dir"' EXIT
"$py" "$scripts/h5extract.py" "$out_dir" "$data_dir" || { say "extraction from $out_dir failed"; exit 1; }

# figure number, width and height of the PNG in pixels (PDF: the same at 200 px per inch)
sizes=("2 1500 560" "3 1500 560" "4 1500 560" "5 1500 1000" "6 1500 1000" "7 1500 1000")
written=()
for entry in "${sizes[@]}"; do
    read -r n w h <<<"$entry"
    for fmt in png pdf; do
        target="$fig_dir/fig$n.$fmt"
        tmp="$target.tmp"
        rm -f "$tmp"
        if ! (cd "$scripts/gnuplot" &&
              gnuplot -e "datadir='$data_dir'; out='$tmp'; fmt='$fmt'; W=$w; H=$h" "fig$n.gp") \
              >"$data_dir/gnuplot.log" 2>&1 || [[ ! -s "$tmp" ]]; then
            say "gnuplot failed on fig$n.$fmt:"
            cat "$data_dir/gnuplot.log" >&2
            rm -f "$tmp"
            exit 1
        fi
        if [[ -s "$data_dir/gnuplot.log" ]]; then   # warnings: show them, they are bugs here
            say "gnuplot said on fig$n.$fmt:"
            cat "$data_dir/gnuplot.log" >&2
        fi
        fixed_pdf_date "$tmp"
        mv "$tmp" "$target"
        written+=("$target")
    done
done
# surface forms: figure, run, fields, last time, title (the fields and order of the paper's panels)
surfaces=(
    "2|exp1|u,P,theta|1.5|Figure 2 (surfaces): experiment 1, ϖ = 0.1"
    "3|exp1|q,eta|1.5|Figure 3 (surfaces): experiment 1, ϖ = 0.1 — heat flux and diffusion flux"
    "5|exp2|u,P,theta|0.5|Figure 5 (surfaces): experiment 2 — second sound"
    "6|exp2|q,eta|0.5|Figure 6 (surfaces): experiment 2 — heat flux, diffusion flux, contact point"
    "7|exp3|u,P,theta|0.5|Figure 7 (surfaces): experiment 3 (τ = τ₀ = 0) — no second sound"
)
for entry in "${surfaces[@]}"; do
    IFS='|' read -r n run flds tmax ftitle <<<"$entry"
    if [[ "$n" == 2 ]] && "$py" -c 'import sys, h5py; sys.exit(0 if "snapshots/sigma" in h5py.File(sys.argv[1], "r") else 1)'             "$out_dir/$run.h5" 2>/dev/null; then
        flds="$flds,sigma"
    fi
    sdata="$data_dir/surface$n"
    "$py" "$scripts/lib/plotdata.py" "$out_dir/$run.h5" "$sdata" --fields "$flds" --t-max "$tmax" --units paper ||
        { say "extraction for fig${n}_surface failed"; exit 1; }
    extra=""
    [[ "$n" == 6 ]] && extra="with_uend = 1;"
    nf=$(awk -F, '{ print NF }' <<<"$flds")
    if ((nf > 3)); then h=1000; else h=560; fi
    for fmt in png pdf; do
        target="$fig_dir/fig${n}_surface.$fmt"
        tmp="$target.tmp"
        rm -f "$tmp"
        if ! (cd "$scripts/gnuplot" &&
              gnuplot -e "datadir='$sdata'; out='$tmp'; fmt='$fmt'; W=1500; H=$h; fig_title='$ftitle'; $extra" run_surface.gp) \
              >"$data_dir/gnuplot.log" 2>&1 || [[ ! -s "$tmp" ]]; then
            say "gnuplot failed on fig${n}_surface.$fmt:"
            cat "$data_dir/gnuplot.log" >&2
            rm -f "$tmp"
            exit 1
        fi
        if [[ -s "$data_dir/gnuplot.log" ]]; then
            say "gnuplot said on fig${n}_surface.$fmt:"
            cat "$data_dir/gnuplot.log" >&2
        fi
        fixed_pdf_date "$tmp"
        mv "$tmp" "$target"
        written+=("$target")
    done
done
end=$(date +%s.%N)
say "wrote ${#written[@]} files in $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') s:"
printf '  %s\n' "${written[@]}"
