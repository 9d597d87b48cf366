#!/usr/bin/env bash
# Build rodcontact (scripts/setup.sh) and run one experiment.
#
#   scripts/run.sh                      # runs input/exp1.nml -> out/exp1.h5
#   scripts/run.sh input/exp2.nml       # another input file
#   scripts/run.sh INPUT [--set group.variable=value ...] [--resume]
#                                       # the arguments after INPUT go to rodcontact as they are
#                                       # (--resume: continue an interrupted run in place)
#
# The run happens in the current directory: a relative output prefix of the input file
# (&output prefix='out/exp1') is taken from there, as rodcontact itself does (from the
# repository root, scripts/run.sh writes out/exp1.h5 there). Exit status: that of rodcontact
# (0 ok, 2 bad input, 3 numerical failure, 4 output failure, 5 stopped by a signal: the same
# command with --resume continues it), or 1 when setup fails.
# Environment: BUILD_TYPE, BUILD_DIR as for scripts/setup.sh.

set -euo pipefail

if [[ "${1:-}" == -* ]]; then
    sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//' >&2
    [[ "${1:-}" == -h || "${1:-}" == --help ]] && exit 0
    exit 2
fi

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

input="${1:-$repo_root/input/exp1.nml}"
shift $(($# > 0 ? 1 : 0))
if [[ ! -f "$input" ]]; then
    echo "run: input file not found: $input" >&2
    exit 2
fi
input="$(cd "$(dirname "$input")" && pwd)/$(basename "$input")"

"$repo_root/scripts/setup.sh"

build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"

# The output prefix as the input file sets it (comments stripped; default of docs/input.md),
# or as the last --set output.prefix=... of the arguments does (quotes stripped).
prefix="$(sed -e 's/!.*//' "$input" |
          grep -i -o -E "prefix[[:space:]]*=[[:space:]]*('[^']*'|\"[^\"]*\")" |
          tail -n 1 | sed -E "s/^[^=]*=[[:space:]]*['\"](.*)['\"]$/\1/")" || true
prefix="${prefix:-out/run}"
previous=""
for arg in "$@"; do
    [[ $previous == --set ]] && set_value=$arg || set_value=${arg#--set=}
    if [[ ($previous == --set || $arg == --set=*) && ${set_value,,} == output.prefix=* ]]; then
        prefix=${set_value#*=}
        [[ $prefix =~ ^[\'\"](.*)[\'\"]$ ]] && prefix=${BASH_REMATCH[1]}
    fi
    previous=$arg
done
mkdir -p "$(dirname "$prefix")"

echo "run: $build_dir/rodcontact ${input#"$repo_root"/}${*:+ $*}" >&2
status=0
"$build_dir/rodcontact" "$input" "$@" || status=$?
if ((status != 0)); then
    echo "run: rodcontact exited with status $status" >&2
    exit "$status"
fi
if [[ "$prefix" = /* ]]; then out="$prefix.h5"; else out="$(pwd)/$prefix.h5"; fi
if [[ -f "$out" ]]; then
    echo "run: output written to $out"
else
    echo "run: rodcontact succeeded but $out is not there" >&2
    exit 1
fi
