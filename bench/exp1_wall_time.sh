#!/usr/bin/env bash
# Benchmark (not a test): wall time of experiment 1 at the paper's discretisation,
# h = 1/500 and dt = 1e-4 up to t_end = 1.0, i.e. 10,000 implicit Euler steps.
#
#   bench/exp1_wall_time.sh               # 5 runs
#   RUNS=9 bench/exp1_wall_time.sh
#
# Builds Release with scripts/setup.sh (BUILD_DIR is honoured, BUILD_TYPE is forced to
# Release), runs a temporary copy of input/exp1.nml with the discretisation and
# `&output prefix=<tmp> quiet=.true.` set, and prints each wall time, the median and
# what the number depends on: machine, compiler, the BLAS/LAPACK shared objects the
# binary actually resolves (Debian may point libblas.so.3 at OpenBLAS; LAPACK's dgbtrs is
# then 1.5-2x slower on our band, but a time step calls no BLAS/LAPACK routine, only the
# set-up does: see docs/performance.md), and the git commit. scripts/bench.sh is the full
# benchmark.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs="${RUNS:-5}"

BUILD_TYPE=Release "$repo_root/scripts/setup.sh"
cd "$repo_root"

build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
exe="$build_dir/rodcontact"
input="$repo_root/input/exp1.nml"
[[ -f "$input" ]] || { echo "bench: $input not found" >&2; exit 1; }

tmp="$(mktemp -d "${TMPDIR:-/tmp}/rodcontact-bench.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT

# Copy of exp1.nml with the benchmark settings: inside each group named here, earlier
# assignments of these variables are removed and the new ones put before the closing
# '/'; a group that is absent is appended. Everything else (initial data, model,
# snapshot_every, ...) stays as the lead wrote it.
python_any="$(command -v python3 || echo /usr/bin/python3)"
"$python_any" - "$input" "$tmp/bench.nml" "$tmp/bench" <<'PY'
import re
import sys

src, dst, prefix = sys.argv[1:4]
overrides = {
    "mesh": {"n_elements": "500"},
    "time": {"dt": "1.0e-4", "t_end": "1.0"},
    "output": {"prefix": "'%s'" % prefix, "quiet": ".true."},
}
text = open(src).read()
out, i, group, seen = [], 0, None, set()
value = re.compile(r"\s*=\s*('[^']*'|\"[^\"]*\"|[^\s,/!]+)\s*,?", re.S)
while i < len(text):
    ch = text[i]
    if ch in "'\"":                                   # quoted string: copy verbatim
        j = text.index(ch, i + 1) + 1
        out.append(text[i:j]); i = j; continue
    if ch == "!":                                     # comment to end of line
        j = text.find("\n", i); j = len(text) if j < 0 else j
        out.append(text[i:j]); i = j; continue
    if ch == "&" and group is None:                   # group start
        m = re.match(r"&(\w+)", text[i:])
        group = m.group(1).lower(); seen.add(group)
        out.append(m.group(0)); i += len(m.group(0)); continue
    if group is not None and ch == "/":               # group end
        for k, v in overrides.get(group, {}).items():
            out.append(" %s=%s " % (k, v))
        out.append("/"); group = None; i += 1; continue
    if group in overrides and (ch.isalpha()) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
        m = re.match(r"(\w+)", text[i:])
        if m.group(1).lower() in overrides[group]:
            v = value.match(text, i + len(m.group(1)))
            if v:                                     # drop 'name = value,'
                i = v.end(); continue
        out.append(m.group(1)); i += len(m.group(1)); continue
    out.append(ch); i += 1
for g, kv in overrides.items():
    if g not in seen:
        out.append("\n&%s %s /\n" % (g, " ".join("%s=%s" % x for x in kv.items())))
open(dst, "w").write("".join(out))
PY

echo "rodcontact benchmark: exp1, h = 1/500, dt = 1e-4, t_end = 1.0 (10000 steps), $runs runs"
times=()
for ((k = 1; k <= runs; k++)); do
    rm -f "$tmp/bench.h5"
    t0="$(date +%s.%N)"
    if ! "$exe" "$tmp/bench.nml" >"$tmp/stdout" 2>"$tmp/stderr"; then
        echo "bench: run $k failed; input was:" >&2
        cat "$tmp/bench.nml" "$tmp/stderr" >&2
        exit 1
    fi
    t1="$(date +%s.%N)"
    wall="$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')"
    times+=("$wall")
    printf '  run %d: %8.3f s\n' "$k" "$wall"
done
median="$(printf '%s\n' "${times[@]}" | sort -g |
          awk '{ v[NR] = $1 } END { if (NR % 2) m = v[(NR + 1) / 2]; else m = (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%.3f", m }')"
echo "  median: $median s"

# --- what the number depends on -------------------------------------------------------
cpu="$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo 2>/dev/null | head -n 1)"
fc="$(sed -n 's/^CMAKE_Fortran_COMPILER:[A-Z]*=//p' "$build_dir/CMakeCache.txt")"
resolved() {   # $1: regex of library names; prints "name -> real path" for each match
    ldd "$exe" | awk -v re="$1" '$1 ~ re && $3 ~ /^\// { print $1, $3 }' |
        while read -r name path; do echo "$name -> $(readlink -f "$path")"; done
}
blas="$(resolved '^lib(blas|openblas|blis|mkl|satlas|tatlas)')"
lapack="$(resolved '^liblapack')"
commit="$(git -C "$repo_root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if [[ "$commit" != unknown && -n "$(git -C "$repo_root" --no-optional-locks status --porcelain --untracked-files=no 2>/dev/null)" ]]; then
    commit="$commit (with uncommitted changes)"
fi

echo "machine:  $(nproc) cores, ${cpu:-unknown CPU} ($(uname -srm))"
echo "compiler: ${fc:-?}: $("${fc:-gfortran}" --version 2>/dev/null | head -n 1)"
# the flags the library was really compiled with (the cache entry can be overridden)
flags="$(sed -n 's/^Fortran_FLAGS = *//p' "$build_dir/CMakeFiles/rodcontact_lib.dir/flags.make" 2>/dev/null || true)"
echo "flags:    ${flags:-unknown}"
echo "BLAS:     ${blas:-none found by ldd (static or not linked)}"
echo "LAPACK:   ${lapack:-none found by ldd (static or not linked)}"
echo "commit:   $commit"
echo "date:     $(date -u +%Y-%m-%dT%H:%M:%SZ)"
