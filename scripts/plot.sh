#!/usr/bin/env bash
# Draw any rodcontact output file: the fields as surfaces over (x, t) or as families of
# profiles, or the time series (energy and its parts when present, u at the rod's end with
# the obstacle and the contact intervals shaded, from the contact events or, in a file
# without them, the penetration or contact stress). PNG and PDF. Works on complete, failed
# and interrupted runs (a failed run is drawn up to its last good step, with its status in
# the title).
#
#   scripts/plot.sh RUN.h5 [--style surface|profiles|series|all] [--fields u,P,theta]
#                          [--t-max T] [--out DIR] [--si | --nondimensional]
#
#   scripts/plot.sh out/exp1.h5     ->  out/exp1_surface.png, out/exp1_surface.pdf
#
#   --style    surface (default), profiles or series; 'all' draws the three
#   --fields   comma-separated among u, v, theta, P, q, eta, sigma (default: u P theta q eta,
#              and sigma when the file has /snapshots/sigma)
#   --t-max    last time drawn in surfaces and profiles, in the units drawn (seconds for SI
#              axes; default: the run's last snapshot)
#   --out DIR  where to write <run>_<style>.png and .pdf (default: the directory of RUN.h5);
#              relative paths are taken from the current directory, as for RUN.h5. Nothing
#              else is written (the data for gnuplot go to a temporary directory).
#   --si       axes in SI units with their units (from each dataset's si_factor and
#              si_units): the default for a run with &material, which has the scales
#   --nondimensional  the file's nondimensional values (the default without &material); the
#              title says so
#
# Each axis is in a power of ten of its unit that keeps its tick labels short (mm for a 1 cm
# rod, '[10^6 K]'), named in its label. A state at t = 0 that would flatten the later ones
# (a pulse) is clipped at the frame of the profiles (the panel says so), and the surface
# starts at the next snapshot. A file still being written (a running or killed run's
# .h5.part, status 'incomplete') is drawn as far as it goes, with a message saying how far;
# a surface needs two snapshots and the series two rows (until then: the profiles, or
# nothing). Names are drawn as they are (no gnuplot markup: point_0001 stays point_0001).
# The files written are printed on stdout, one per line.
#
# Needs a Python with h5py (scripts/lib/find_python.sh) and gnuplot with pngcairo and pdfcairo.
# Exit status: 0 drawn; 1 a tool is missing or gnuplot failed; 2 usage error, or RUN.h5 is
# not a rodcontact output file; 3 nothing of the styles asked for can be drawn yet (a run
# that has just started: a series of one row).

set -euo pipefail

scripts="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
say() { echo "plot: $*" >&2; }
usage() { sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//' >&"${2:-2}"; exit "${1:-2}"; }

run="" style=surface fields="" t_max="" out_dir="" units=auto
while (($# > 0)); do
    case "$1" in
        --style | --fields | --t-max | --out)
            (($# >= 2)) || { say "$1 needs a value"; usage; }
            case "$1" in
                --style) style="$2" ;;
                --fields) fields="$2" ;;
                --t-max) t_max="$2" ;;
                --out) out_dir="$2" ;;
            esac
            shift ;;
        --si) units=si ;;
        --nondimensional) units=nondimensional ;;
        -h | --help) usage 0 1 ;;
        -*) say "unknown option '$1'"; usage ;;
        *) [[ -z "$run" ]] || { say "one run file only (got '$run' and '$1')"; usage; }
           run="$1" ;;
    esac
    shift
done
[[ -n "$run" ]] || { say "no run file given"; usage; }
case "$style" in
    surface | profiles | series) styles=("$style") ;;
    all) styles=(surface profiles series) ;;
    *) say "--style must be surface, profiles, series or all, got '$style'"; exit 2 ;;
esac
[[ -f "$run" ]] || { say "$run: no such file"; exit 2; }
out_dir="${out_dir:-$(dirname "$run")}"
name="$(basename "$run")"; name="${name%.part}"; name="${name%.h5}"
mkdir -p "$out_dir" 2>/dev/null || { say "cannot create the directory $out_dir"; exit 1; }
# absolute paths: gnuplot runs in scripts/gnuplot (where its scripts load common.gp)
out_dir="$(cd "$out_dir" && pwd)"
run="$(cd "$(dirname "$run")" && pwd)/$(basename "$run")"
[[ "$out_dir/$name" != *"'"* && "$out_dir/$name" != *'"'* ]] ||
    { say "names with quotes are not supported: $out_dir/$name"; exit 2; }

py="$("$scripts/lib/find_python.sh")" || { say "no Python with h5py (Debian: python3-h5py)"; exit 1; }
command -v gnuplot >/dev/null 2>&1 || { say "gnuplot not found (Debian: gnuplot-nox)"; exit 1; }
data="$(mktemp -d "${TMPDIR:-/tmp}/rodcontact-plot.XXXXXX")"
trap 'rm -rf "$data"' EXIT
opts=()
[[ -n "$fields" ]] && opts+=(--fields "$fields")
[[ -n "$t_max" ]] && opts+=(--t-max "$t_max")
opts+=(--units "$units")
status=0
"$py" "$scripts/lib/plotdata.py" "$run" "$data" "${opts[@]}" || status=$?
if ((status != 0)); then
    ((status == 2)) && exit 2
    say "reading $run failed"; exit 1
fi
title="$name"
param() { awk -F' = ' -v k="$1" '$1 == k { gsub(/"/, "", $2); print $2 }' "$data/params.gp"; }
# A file still being written (or the .part of a killed run): say how far it goes, draw what it
# can (a surface needs two snapshots, the series two rows: gnuplot's 'empty range' otherwise)
n_snap=$(param n_snap) n_series=$(param n_series) run_status=$(param status)
if [[ "$run_status" != complete ]]; then
    say "$(basename "$run"): status '$run_status': drawn as far as it goes, $n_snap snapshot(s) up to t = $(param t_max)$(param t_plain | sed 's/^./ &/') and $n_series series row(s)"
fi
drawable=()
for st in "${styles[@]}"; do
    if [[ "$st" == surface ]] && ((n_snap < 2)); then
        say "no surface: $n_snap snapshot so far (a surface needs two)"
        [[ "$style" == surface ]] && { say "drawing the profiles instead"; drawable+=(profiles); }
    elif [[ "$st" == series ]] && ((n_series < 2)); then
        say "no series: $n_series row so far (a time series needs two)"
    else
        drawable+=("$st")
    fi
done
((${#drawable[@]} > 0)) || { say "nothing to draw yet"; exit 3; }
styles=("${drawable[@]}")
written=()
for st in "${styles[@]}"; do
    case "$st" in
        surface) gp=run_surface.gp h=$(awk -F' = ' '$1 == "n_fields" { print ($2 > 3 ? 1000 : 560) }' "$data/params.gp") ;;
        profiles) gp=run_profiles.gp h=$(awk -F' = ' '$1 == "n_fields" { print ($2 > 3 ? 1000 : 600) }' "$data/params.gp") ;;
        series) gp=run_series.gp h=560 ;;
    esac
    for fmt in png pdf; do
        target="$out_dir/${name}_$st.$fmt"
        tmp="$data/figure.$fmt"   # written here, then moved: never a partial file at $target
        rm -f "$tmp"
        if ! (cd "$scripts/gnuplot" && gnuplot -e "datadir='$data'; out='$tmp'; fmt='$fmt'; W=1500; H=$h; fig_title='$title — $st'; literal=1" "$gp") \
                >"$data/gnuplot.log" 2>&1 || [[ ! -s "$tmp" ]]; then
            say "gnuplot failed on $target:"; cat "$data/gnuplot.log" >&2
            exit 1
        fi
        [[ -s "$data/gnuplot.log" ]] && { say "gnuplot said on $target:"; cat "$data/gnuplot.log" >&2; }
        mv -f "$tmp" "$target" || { say "cannot write $target"; exit 1; }
        written+=("$target")
    done
done
printf '%s\n' "${written[@]}"
