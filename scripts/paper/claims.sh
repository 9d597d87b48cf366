#!/usr/bin/env bash
# Check every claim of Section 7 of the paper against rodcontact runs and write
# docs/reproduction.md: a table with one row per claim (claim, the paper's words, measured
# value, holds yes/no), how each number is measured, and Figures 2-7.
#
#   scripts/paper/claims.sh                   # runs what is missing into out/, writes docs/reproduction.md
#   scripts/paper/claims.sh --quick           # shortened runs, report only (pipeline check), in
#                                       # ${TMPDIR:-/tmp}/rodcontact-quick/
#
# Options:
#   --out DIR       directory of the HDF5 files (default out/)
#   --doc FILE      document to write (default docs/reproduction.md)
#   --figdir DIR    where the figures are, for the links (default figures/)
#   --exe PATH      rodcontact binary (default: build with scripts/setup.sh)
#   --force         rerun every input
#   --quick         shortened runs (t_end = 0.3): verdicts mean nothing, exit 0 whatever they are
#   --no-runs       use the HDF5 files as they are, run nothing
#   --no-accuracy   leave out the accuracy study (scripts/paper/accuracy.sh: the claims at other
#                   resolutions and the accuracy section; about 10 minutes the first time)
#
# The runs are those of scripts/paper/figures.sh plus exp1_long (input/exp1.nml up to t = 60,
# about 20 s), made by `scripts/paper/figures.sh --runs-only --with-long`, and those of
# scripts/paper/accuracy.sh (other resolutions, references; with --quick its coarse pipeline check).
# Figures are not redrawn: run scripts/paper/figures.sh for them.
# Exit status: 0 every claim holds (or --quick); 1 a claim does not hold, or a run failed;
# 2 usage error or missing data.

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
say() { echo "claims: $*" >&2; }

quick=0 no_runs=0 accuracy=1 out_dir="" doc="" fig_dir="" run_args=()
while (($# > 0)); do
    case "$1" in
        --quick) quick=1; run_args+=(--quick) ;;
        --force) run_args+=(--force) ;;
        --no-runs) no_runs=1 ;;
        --no-accuracy) accuracy=0 ;;
        --out | --doc | --figdir | --exe)
            (($# >= 2)) || { say "$1 needs a value"; usage; }
            case "$1" in
                --out) out_dir="$2" ;;
                --doc) doc="$2" ;;
                --figdir) fig_dir="$2" ;;
                --exe) run_args+=(--exe "$2") ;;
            esac
            shift ;;
        -h | --help) usage 0 ;;
        *) say "unknown argument '$1'"; usage ;;
    esac
    shift
done

quick_base="${TMPDIR:-/tmp}/rodcontact-quick"
if ((quick)); then
    out_dir="${out_dir:-$quick_base/out}"
    doc="${doc:-$quick_base/reproduction.md}"
    fig_dir="${fig_dir:-$quick_base/figures}"
else
    out_dir="${out_dir:-$repo_root/out}"
    doc="${doc:-$repo_root/docs/reproduction.md}"
    fig_dir="${fig_dir:-$repo_root/figures}"
fi

if ((!no_runs)); then
    "$scripts/paper/figures.sh" --runs-only --with-long --out "$out_dir" "${run_args[@]}" || exit 1
fi
py="$("$scripts/lib/find_python.sh")" || { say "no Python with h5py: cannot read the HDF5 files"; exit 2; }

# Provenance: read-only git queries (no index refresh: --no-optional-locks).
commit="$(git -C "$repo_root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if [[ "$commit" != unknown && -n "$(git -C "$repo_root" --no-optional-locks status --porcelain \
        --untracked-files=no 2>/dev/null)" ]]; then
    commit="$commit (with uncommitted changes)"
fi
case "$out_dir" in
    "$repo_root"/*) out_label="${out_dir#"$repo_root"/}/" ;;
    *) out_label="$out_dir" ;;
esac
opts=(--out "$out_dir" --doc "$doc" --figdir "$fig_dir" --commit "$commit" --out-label "$out_label")
if ((quick)); then
    opts+=(--report-only --note "Shortened runs (scripts/paper/claims.sh --quick, t_end = 0.3): a check that the \
pipeline works, not a reproduction. The verdicts below mean nothing.")
fi
if ((accuracy)); then
    if ((quick)); then acc_out="$out_dir/acc"; else acc_out="$out_dir"; fi
    if ((!no_runs)); then
        "$scripts/paper/accuracy.sh" --out "$acc_out" "${run_args[@]}" || exit 1
    fi
    [[ -s "$acc_out/accuracy.md" && -f "$acc_out/accuracy.levels" ]] ||
        { say "no accuracy study in $acc_out (run scripts/paper/accuracy.sh, or use --no-accuracy)"; exit 2; }
    opts+=(--accuracy "$acc_out/accuracy.md")
    while IFS= read -r level; do
        [[ -n "$level" ]] && opts+=(--level "$level")
    done <"$acc_out/accuracy.levels"
fi
# experiment 2 on adaptive meshes (scripts/paper/claims_adaptive.sh), when its section has been made
[[ -s "$out_dir/adaptive/adaptive_claims.md" ]] && opts+=(--adaptive "$out_dir/adaptive/adaptive_claims.md")
status=0
"$py" "$scripts/paper/claims.py" "${opts[@]}" || status=$?
exit "$status"
