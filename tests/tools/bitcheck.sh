#!/usr/bin/env bash
# Same results from two binaries (a refactor's proof): runs a set of short cases that between
# them take every path of the code (schemes, laws, masses, methods, adaptive steps and mesh,
# the error estimate, dense output, checkpoints and restarts) with both binaries, and
# compares the files with `regression.py same` (every dataset and attribute, provenance and
# /checkpoint aside).
#
#   tests/tools/bitcheck.sh OLD_BINARY NEW_BINARY [WORKDIR]
#
# Prints one line a case (SAME, or DIFF with what differs) and then ALL SAME, or exits 1.
# With BITCHECK_IGNORE=ATTR[,ATTR...], those root attributes are left out of the comparison
# (a change that adds one). With BITCHECK_RTOL=1e-12 in the environment, a case that
# differs is compared again with that relative tolerance (every float dataset within RTOL * its largest |value|, integer
# datasets and the /events counts equal): CLOSE when it holds (a changed summation order),
# and the summary says ALL SAME OR CLOSE.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
old="$(realpath "$1")"; new="$(realpath "$2")"
work="${3:-$(mktemp -d)}"; mkdir -p "$work"
py=python3; "$py" -c 'import h5py' 2>/dev/null || py=/usr/bin/python3
in="$repo/input"
short="--set mesh.n_elements=100 --set output.snapshot_every=500"
# The exp2-based cases that end at t = 0.3 have g = 0.098 so that they touch the obstacle: the
# pulses reach g = 0.1 just after t = 0.3 (at s = 100 and 50 their jump lands on a node).
cases=(
  "euler|$in/exp1.nml|$short --set time.t_end=0.3"
  "bdf2|$in/exp1.nml|$short --set time.t_end=0.3 --set time.scheme='bdf2'"
  "midpoint|$in/exp1.nml|$short --set time.t_end=0.3 --set time.scheme='midpoint'"
  "paper|$in/exp1.nml|$short --set time.t_end=0.3 --set solver.method='paper'"
  "signorini|$in/exp2.nml|$short --set time.t_end=0.3 --set contact.law='signorini' --set contact.g=0.098"
  "exp3|$in/exp3.nml|$short --set time.t_end=0.3"
  "thermoelastic|$in/exp1.nml|$short --set time.t_end=0.3 --set model.gamma2=0 --set model.d=0 --set initial.p0_poly=0,0,0,0,0"
  "impact|$in/impact.nml|--set mesh.n_elements=200 --set time.t_end=0.4"
  "impact_sig_redis|$in/impact.nml|--set mesh.n_elements=200 --set time.t_end=0.4 --set contact.law='signorini' --set contact.mass='redistributed'"
  "impact_euler_redis|$in/impact.nml|--set mesh.n_elements=200 --set time.t_end=0.4 --set time.scheme='euler' --set contact.mass='redistributed'"
  "adapt_mid|$in/exp1.nml|--set time.t_end=2 --set time.adaptive=.true. --set time.error_tol=1e-5 --set output.snapshot_dt=0.25"
  "adapt_bdf2|$in/exp1.nml|--set time.t_end=1.6 --set time.adaptive=.true. --set time.scheme='bdf2' --set output.snapshot_dt=0.4 --set output.series_dt=0.01"
  "adapt_euler|$in/exp2.nml|--set time.t_end=0.5 --set time.adaptive=.true. --set output.snapshot_dt=0.1 --set output.snapshot_land=.false."
  "adapt_impact|$in/impact.nml|--set mesh.n_elements=200 --set time.t_end=1 --set time.adaptive=.true. --set time.dt=1e-6 --set time.error_tol=1e-6 --set output.snapshot_dt=0.25"
  "adapt_impact_sig|$in/impact.nml|--set mesh.n_elements=200 --set time.t_end=1 --set time.adaptive=.true. --set time.dt=1e-6 --set contact.law='signorini' --set contact.mass='redistributed' --set output.snapshot_dt=0.25"
  "mesh_adapt|$in/exp2.nml|--set contact.g=0.098 --set mesh.n_elements=50 --set mesh.adaptive=.true. --set mesh.max_level=3 --set time.t_end=0.3 --set output.snapshot_every=500"
  "mesh_adapt_impact|$in/impact.nml|--set mesh.n_elements=100 --set mesh.adaptive=.true. --set mesh.max_level=2 --set time.t_end=0.4 --set contact.mass='redistributed' --set time.scheme='euler'"
  "estimate|$in/exp1.nml|--set mesh.n_elements=200 --set time.t_end=0.4 --set output.snapshot_dt=0.1 --set output.error_estimate=.true."
  "estimate_mid|$in/exp1.nml|--set mesh.n_elements=200 --set time.t_end=0.4 --set time.scheme='midpoint' --set output.snapshot_dt=0.1 --set output.error_estimate=.true."
  "estimate_adapt|$in/exp1.nml|--set mesh.n_elements=100 --set time.t_end=0.4 --set time.adaptive=.true. --set output.snapshot_dt=0.1 --set output.error_estimate=.true."
  "estimate_mesh|$in/exp2.nml|--set mesh.n_elements=48 --set mesh.adaptive=.true. --set mesh.max_level=2 --set time.t_end=0.2 --set output.snapshot_dt=0.05 --set output.error_estimate=.true."
  "series_dt|$in/exp1.nml|$short --set time.t_end=0.3 --set time.scheme='midpoint' --set output.series_dt=0.001"
  "material|$work/material.nml|--set output.snapshot_every=50"
  "estimate_bdf2_sig|$in/exp2.nml|--set contact.g=0.098 --set mesh.n_elements=200 --set time.t_end=0.3 --set time.scheme='bdf2' --set contact.law='signorini' --set output.snapshot_dt=0.1 --set output.error_estimate=.true."
)
# restarts: a run writes checkpoints (the last before its end), a second continues from it
restarts=(
  "rs_bdf2|$in/exp1.nml|$short --set time.t_end=0.3 --set time.scheme='bdf2'|2000"
  "rs_adapt_mid|$in/exp1.nml|--set time.t_end=1 --set time.adaptive=.true. --set time.scheme='midpoint' --set output.snapshot_dt=0.25|300"
  "rs_estimate|$in/exp1.nml|--set mesh.n_elements=100 --set time.t_end=0.4 --set output.snapshot_dt=0.1 --set output.error_estimate=.true.|1500"
  "rs_mesh|$in/exp2.nml|--set contact.g=0.098 --set mesh.n_elements=50 --set mesh.adaptive=.true. --set mesh.max_level=2 --set time.t_end=0.3 --set output.snapshot_every=500|1000"
)
# copper, 1 cm, in SI units: g = 0.5, eps = 0.01, dt = 1e-3, t_end = 0.5, theta0 = 40 x (x-1)^2,
# u1 = 10 x nondimensional, converted by tests/tools/si_input.py
cat > "$work/material.nml" << 'NML'
&material units='SI' ell=0.01 /
&contact  g=0.06205218110031347 eps=1.0853251274570797e-17 /
&mesh     n_elements=100 /
&time     dt=0.0008886729015544042 t_end=0.44433645077720213 /
&initial  theta0_poly = 0, 13926317.701092463, -27852635.402184926, 13926317.701092463
          u1_poly = 0, 1.3965134076165966 /
NML
status=0
run() {  # run BIN NAME INPUT ARGS...
    local bin="$1" name="$2" input="$3"; shift 3
    eval "\"$bin\" \"$input\" --set output.prefix=\"'$work/$name'\" --set output.quiet=.true. $*" \
        > "$work/$name.log" 2>&1
}
compare() {  # compare NAME
    local out
    local ignore=()
    [[ -n "${BITCHECK_IGNORE:-}" ]] && ignore=(--ignore "$BITCHECK_IGNORE")
    if out=$("$py" "$repo/tests/tools/regression.py" same "$work/$1_old.h5" "$work/$1_new.h5" "${ignore[@]}" 2>&1); then
        echo "SAME  $1"
    elif [[ -n "${BITCHECK_RTOL:-}" ]] && close=$("$py" - "$work/$1_old.h5" "$work/$1_new.h5" "$BITCHECK_RTOL" << 'PY'
import sys, h5py, numpy as np
a, b, rtol = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r"), float(sys.argv[3])
worst, bad = 0.0, []
def visit(name, obj):
    global worst
    if not isinstance(obj, h5py.Dataset) or name.startswith("checkpoint"):
        return
    if name not in b:
        bad.append(f"/{name} missing"); return
    x, y = obj[()], b[name][()]
    if x.shape != y.shape:
        bad.append(f"/{name} shapes {x.shape} {y.shape}"); return
    if x.dtype.kind == "f":
        scale = float(np.max(np.abs(x))) if x.size else 0.0
        d = float(np.max(np.abs(x - y))) if x.size else 0.0
        r = d / scale if scale > 0 else d
        worst = max(worst, r)
        if r > rtol: bad.append(f"/{name} rel {r:.2e}")
    elif x.dtype.kind in "iu" and not np.array_equal(x, y):
        bad.append(f"/{name} integers differ")
a.visititems(visit)
print("; ".join(bad[:4]) if bad else f"max rel {worst:.2e}")
sys.exit(1 if bad else 0)
PY
); then
        echo "CLOSE $1: $close"
    else
        echo "DIFF  $1: $(echo "$out" | head -5 | tr '\n' ' ')"; status=1
    fi
}
for c in "${cases[@]}"; do
    IFS='|' read -r name input args <<< "$c"
    run "$old" "${name}_old" "$input" "$args" || { echo "FAIL  $name (old binary, $work/${name}_old.log)"; status=1; continue; }
    run "$new" "${name}_new" "$input" "$args" || { echo "FAIL  $name (new binary, $work/${name}_new.log)"; status=1; continue; }
    compare "$name"
done
for c in "${restarts[@]}"; do
    IFS='|' read -r name input args every <<< "$c"
    ck="--set output.checkpoint_every=$every"
    # each binary continues from its own checkpoint (the checkpoint's layout may differ)
    for side in old new; do
        bin=$old; [[ $side == new ]] && bin=$new
        run "$bin" "${name}_ck_$side" "$input" "$args $ck" \
            && run "$bin" "${name}_$side" "$input" "$args --set time.restart_from=\"'$work/${name}_ck_$side.h5'\"" \
            || { echo "FAIL  $name ($side binary: $work/${name}_ck_$side.log, ${name}_$side.log)"; status=1; continue 2; }
    done
    compare "$name"
done
if [[ $status == 0 ]]; then
    [[ -n "${BITCHECK_RTOL:-}" ]] && echo "ALL SAME OR CLOSE (rtol $BITCHECK_RTOL)" || echo "ALL SAME"
else
    echo "SOME DIFFER (files in $work)"
fi
exit $status
