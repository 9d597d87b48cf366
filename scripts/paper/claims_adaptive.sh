#!/usr/bin/env bash
# The claims about experiment 2 (C7, C8: the fronts; C10: contact) checked on runs with the
# adaptive mesh (issue 13), measured as scripts/paper/claims.sh measures them: runs input/exp2.nml
# twice with &mesh adaptive = .true. into OUT (default out/adaptive/), writes
# OUT/adaptive_claims.md and puts it into docs/reproduction.md as its section "Experiment 2
# on adaptive meshes" (scripts/paper/claims.sh keeps it there when it rewrites the page).
#
#   scripts/paper/claims_adaptive.sh [--out DIR] [--no-splice]     # about 1 minute
#
# The runs: (a) the paper's steps (implicit Euler, dt = 1e-4) on the default adaptive mesh
# (coarse 1/500, max_level 5, error_tol 1e-3); (b) BDF2 with adaptive steps (error_tol 1e-4)
# on a coarse mesh 1/250 with max_level 3. Both to t = 2 (contact and release).
# Exit status: 0 every claim holds on both; 1 one does not, or a run failed; 2 usage.
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
say() { echo "claims_adaptive: $*" >&2; }
out="$repo_root/out/adaptive" splice=1
while (($#)); do
    case "$1" in
        --out) out="${2:?--out needs a directory}"; shift 2 ;;
        --no-splice) splice=0; shift ;;
        -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;;
        *) say "unknown option '$1' (--out DIR, --no-splice, --help)"; exit 2 ;;
    esac
done
"$repo_root/scripts/setup.sh" >&2 || exit 1
exe="$repo_root/build/rodcontact"
py="$("$repo_root/scripts/lib/find_python.sh")" || exit 1
mkdir -p "$out"
common=(--set output.snapshot_dt=0.01 --set output.quiet=.true. --set mesh.adaptive=.true.)
"$exe" "$repo_root/input/exp2.nml" "${common[@]}" --set output.prefix="'$out/exp2_adaptive_euler'" ||
    { say "run (a) failed"; exit 1; }
"$exe" "$repo_root/input/exp2.nml" "${common[@]}" --set output.prefix="'$out/exp2_adaptive_bdf2'" \
    --set mesh.n_elements=250 --set mesh.max_level=3 --set time.scheme="'bdf2'" --set time.adaptive=.true. \
    --set time.error_tol=1e-4 || { say "run (b) failed"; exit 1; }
status=0
"$py" "$repo_root/scripts/paper/claims_adaptive.py" "$out" exp2_adaptive_euler exp2_adaptive_bdf2 \
    >"$out/adaptive_claims.md" || status=$?
((status == 2)) && exit 2
if ((splice)); then
    "$py" "$repo_root/scripts/paper/claims_adaptive.py" --splice "$out/adaptive_claims.md" "$repo_root/docs/reproduction.md"
    say "section written to docs/reproduction.md"
fi
((status == 0)) && say "every claim holds on both runs" || say "a claim does not hold (see $out/adaptive_claims.md)"
exit "$status"
