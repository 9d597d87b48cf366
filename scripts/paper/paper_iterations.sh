#!/usr/bin/env bash
# Measure how many iterations method = 'paper' needs per step on the shipped experiments
# (exp1 to t = 1, exp2 to t = 1, paper's h and dt) from /series/iterations, and write the
# table between the markers <!-- paper-iterations:begin/end --> of docs/scheme.md.
#
#   scripts/paper/paper_iterations.sh          # builds with scripts/setup.sh; a few seconds
#
# Exit status: 0 written; 1 a run failed or the markers are missing.
set -euo pipefail
case ${1:-} in
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;;
    '') ;;
    *) echo "${BASH_SOURCE[0]##*/}: unknown argument '$1' (it takes none; --help)" >&2; exit 2 ;;
esac
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
scripts="$repo_root/scripts"
"$scripts/setup.sh"
build_dir="${BUILD_DIR:-build}"; [[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
py="$("$scripts/lib/find_python.sh")"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/rodcontact-iter.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
for name in exp1 exp2; do
    "$py" "$scripts/lib/nml_copy.py" "$repo_root/input/$name.nml" "$tmp/$name.nml" "output.prefix='$tmp/$name'" \
        output.quiet=.true. time.t_end=1.0 "solver.method='paper'" output.snapshot_every=10000
    "$build_dir/rodcontact" "$tmp/$name.nml" >"$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log" >&2; exit 1; }
done
"$py" - "$tmp" "$repo_root/docs/scheme.md" <<'PY'
import sys, h5py, numpy as np
tmp, doc = sys.argv[1], sys.argv[2]
rows = ["| run (t ≤ 1, h = 1/500, Δt = 1e-4) | steps | iterations per step: steps | in contact: iterations |",
        "|---|---|---|---|"]
for name in ("exp1", "exp2"):
    with h5py.File(f"{tmp}/{name}.h5", "r") as f:
        it = f["series/iterations"][1:]
        pen = f["series/penetration"][1:]
    vals, counts = np.unique(it, return_counts=True)
    hist = ", ".join(f"{v}: {c}" for v, c in zip(vals, counts))
    ci = np.unique(it[pen > 0])
    rows.append(f"| {name} | {it.size} | {hist} | {', '.join(str(v) for v in ci) or '–'} |")
text = open(doc, encoding="utf-8").read()
b, e = "<!-- paper-iterations:begin -->", "<!-- paper-iterations:end -->"
if b not in text or e not in text:
    sys.exit("paper_iterations.sh: markers missing in " + doc)
new = text[:text.index(b) + len(b)] + "\n" + "\n".join(rows) + "\n" + text[text.index(e):]
open(doc, "w", encoding="utf-8").write(new)
print("\n".join(rows))
PY
