#!/usr/bin/env bash
# The built-in error estimate (&output error_estimate; src/adaptivity/error_companion_m.f90,
# docs/scheme.md "The error estimate of a run"):
#  1. without the option the file claims no error: root attribute error_estimate =
#     'none: ...', no /snapshots/error_estimate*, no time_error_estimate*; fixed steps carry
#     no step-control attributes, adaptive ones carry step_control_error_sum*;
#  2. with it: /snapshots/error_estimate{,_time,_space}/<field>, one finite value per
#     snapshot with long_name and units, the root attributes error_estimate.<field> etc. =
#     the last snapshot's values; --summary's columns error_<field> hold them;
#  3. refused (exit 2, named): a number of elements (on an adaptive mesh: of coarse
#     elements) that is not a multiple of 4; a restart that switches the option (it changes
#     the checkpoint);
#  4. restart of a run with estimates (fixed BDF2, adaptive midpoint with snapshot_dt; on a
#     uniform and on an adaptive mesh, whose companions remesh with the run) is bit for bit the
#     uninterrupted run, estimates included (the companions are in the checkpoint, their
#     meshes rebuilt from the run's);
#  5. the estimate against the exact solution (bench/error_estimate.py --quick --check):
#     experiment 1 before contact within [1/3, 3] of the true error, experiment 2's fronts
#     within [1/10, 10], every field and snapshot, Euler, BDF2, midpoint with fixed steps, and
#     experiment 1 with adaptive Euler and midpoint steps (the companions land on every
#     snapshot: when they caught up with one shorter step instead, the midpoint rule's v was
#     0.03x its true error); on an adaptive mesh experiment 1 with fixed Euler steps and
#     experiment 2 with fixed midpoint steps (skipped without scipy).
# The manufactured solution's ratios: tests/test_error_estimate_mms.f90.
# Usage: bash test_error_estimate.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
. "$src/tests/lib/checks.sh"
cd "$scratch" && rm -rf ./* || exit 1

exp1=("$src/input/exp1.nml" --set mesh.n_elements=100 --set output.quiet=.true.)
"$exe" "${exp1[@]}" --set time.t_end=0.2 --set output.prefix="'off'" || echo "run off failed"
"$exe" "${exp1[@]}" --set time.t_end=0.2 --set time.adaptive=.true. --set output.prefix="'off_ad'" || echo "run off_ad failed"
"$exe" "${exp1[@]}" --set time.t_end=0.2 --set output.error_estimate=.true. --set output.prefix="'on'" ||
    echo "run on failed"

check "1. without the option: error_estimate says none, no estimate datasets, no time_error_estimate" \
    "$py" - off.h5 off_ad.h5 <<'PY'
import sys, h5py
ok = True
for path in sys.argv[1:]:
    with h5py.File(path, "r") as f:
        a = f.attrs
        text = a.get("error_estimate")
        text = text.decode() if isinstance(text, bytes) else text
        good = (text == "none: set &output error_estimate=.true. or run scripts/converge.sh"
                and "error_estimate" not in f["snapshots"]
                and not any(k.startswith("time_error_estimate") for k in a)
                and not any(k.startswith("error_estimate.") for k in a))
        adaptive = "_ad" in path
        good &= ("step_control_error_sum" in a) == adaptive and ("step_control_error_sum_relative" in a) == adaptive
        good &= ("time_steps_estimated" in a) == adaptive
        print(f"  {path}: error_estimate = {text!r}, step-control attributes: {adaptive}: {'ok' if good else 'WRONG'}")
        ok &= good
sys.exit(0 if ok else 1)
PY

check "2. with the option: three groups of per-snapshot estimates, described, final values as root attributes" \
    "$py" - on.h5 <<'PY'
import sys, h5py, numpy as np
ok = True
with h5py.File(sys.argv[1], "r") as f:
    n = f["snapshots/t"].shape[0]
    for group in ("error_estimate", "error_estimate_time", "error_estimate_space"):
        for field in ("u", "v", "theta", "P", "q", "eta"):
            d = f[f"snapshots/{group}/{field}"]
            v = d[:]
            good = (d.shape == (n,) and np.all(np.isfinite(v)) and v[0] == 0.0 and np.all(v >= 0)
                    and "long_name" in d.attrs and d.attrs["units"] in (b"1", "1")
                    and f.attrs[f"{group}.{field}"] == v[-1])
            if group == "error_estimate" and field != "u":
                good &= bool(v[-1] > 0)
            if not good:
                print(f"  {group}/{field}: shape {d.shape} (n_snap {n}), values {v}, attrs {dict(d.attrs)}")
            ok &= good
    print("  error_estimate:", f.attrs["error_estimate"], "; error_estimate.theta:", f.attrs["error_estimate.theta"])
sys.exit(0 if ok else 1)
PY

summary_has() {   # the --summary row of on.h5 carries the final estimates; off.h5's are empty (NaN)
    "$py" - "$("$exe" --summary-header)" "$("$exe" --summary on.h5)" "$("$exe" --summary off.h5)" <<'PY'
import csv, sys, h5py
h, on, off = (next(csv.reader([a])) for a in sys.argv[1:4])
on, off = dict(zip(h, on)), dict(zip(h, off))
a = h5py.File("on.h5", "r").attrs
ok = all(abs(float(on[f"error_{k}"]) - a[f"error_estimate.{k}"]) <= 1e-12 * a[f"error_estimate.{k}"]
         for k in ("u", "v", "theta", "P", "q", "eta"))
ok &= all(off[f"error_{k}"] in ("", "nan", "NaN") for k in ("u", "theta"))
print("  on:", {k: on[k] for k in h if k.startswith("error_")}, " off error_u:", repr(off["error_u"]))
sys.exit(0 if ok else 1)
PY
}
check "2b. --summary has the final estimates (error_<field>), none without the option" summary_has

refuses() {   # refuses <label> <word in the message> <args...>: exit 2, message names output.error_estimate
    local label=$1 word=$2; shift 2
    "$exe" "$@" --set output.quiet=.true. --set output.prefix="'refused'" >out.txt 2>err.txt
    local status=$?
    if [ "$status" = 2 ] && grep -q "output.error_estimate" err.txt && grep -q "$word" err.txt && [ ! -e refused.h5 ]; then
        echo "  $label: exit 2: $(head -c 200 err.txt)"; return 0
    fi
    echo "  $label: exit $status: $(cat err.txt)"; return 1
}
check "3a. an adaptive mesh of coarse elements not a multiple of 4 is refused" \
    refuses "adaptive mesh, n_elements = 50" "multiple of 4" "$src/input/exp2.nml" --set mesh.adaptive=.true. \
    --set mesh.n_elements=50 --set output.error_estimate=.true.
check "3b. a number of elements that is not a multiple of 4 is refused" \
    refuses "n_elements = 250" "multiple of 4" "$src/input/exp1.nml" --set mesh.n_elements=250 --set output.error_estimate=.true.

# 4. restart: split at T/2 and continued = uninterrupted, estimates included
split_run() {   # split_run <name> <args...>
    local name=$1; shift
    "$exe" "$@" --set time.t_end=0.6 --set output.prefix="'${name}_full'" >/dev/null 2>&1 || echo "$name full failed"
    "$exe" "$@" --set time.t_end=0.3 --set output.checkpoint_every=7 --set output.prefix="'${name}_half'" >/dev/null 2>&1 ||
        echo "$name half failed"
    "$exe" "$@" --set time.t_end=0.6 --set time.restart_from="'${name}_half.h5'" --set output.prefix="'${name}_rest'" \
        >/dev/null 2>&1 || echo "$name restart failed"
    "$py" "$src/tests/tools/regression.py" same "${name}_full.h5" "${name}_rest.h5" &&
        "$py" -c "import h5py, sys; sys.exit(0 if 'error_estimate' in h5py.File('${name}_rest.h5')['snapshots'] else 1)"
}
est=("${exp1[@]}" --set output.error_estimate=.true.)
check "4a. restart with estimates, fixed BDF2 steps: bit for bit the uninterrupted run" \
    split_run fixed "${est[@]}" --set time.scheme="'bdf2'" --set output.snapshot_every=30
check "4b. restart with estimates, adaptive midpoint steps and snapshot_dt: bit for bit the uninterrupted run" \
    split_run adaptive "${est[@]}" --set time.scheme="'midpoint'" --set time.adaptive=.true. --set output.snapshot_dt=0.05
amesh=(--set mesh.adaptive=.true. --set mesh.max_level=2 --set mesh.error_tol=1e-4)
check "4c. restart with estimates on an adaptive mesh, fixed BDF2 steps: bit for bit the uninterrupted run" \
    split_run amesh_fixed "${est[@]}" "${amesh[@]}" --set time.scheme="'bdf2'" --set output.snapshot_every=30
check "4d. restart with estimates on an adaptive mesh, adaptive midpoint steps: bit for bit the uninterrupted run" \
    split_run amesh_adaptive "${est[@]}" "${amesh[@]}" --set time.scheme="'midpoint'" --set time.adaptive=.true. \
    --set output.snapshot_dt=0.05
"$exe" "${exp1[@]}" --set time.t_end=0.6 --set time.restart_from="'fixed_half.h5'" --set time.scheme="'bdf2'" \
    --set output.snapshot_every=30 --set output.prefix="'switched'" >/dev/null 2>err.txt
status=$?
check "3c. a restart that drops the option is refused (exit 2, names output.error_estimate)" \
    test "$status" = 2 -a -n "$(grep output.error_estimate err.txt)"
# a checkpoint whose companion queue was cut short (a damaged file): refused, not read past its end
cp fixed_half.h5 cut_queue.h5 && "$py" -c "
import h5py
with h5py.File('cut_queue.h5', 'r+') as f:
    for slot in ('slot0', 'slot1'):
        g = f['checkpoint/' + slot + '/error_companions/C']
        q = g['queue_t'][:2]; del g['queue_t']; g['queue_t'] = q"
"$exe" "${exp1[@]}" --set time.t_end=0.6 --set time.restart_from="'cut_queue.h5'" --set time.scheme="'bdf2'" \
    --set output.error_estimate=.true. --set output.snapshot_every=30 --set output.prefix="'cut'" >/dev/null 2>err.txt
status=$?
check "3d. a checkpoint with a companion's queue cut short is refused (exit 2, names the companion, no output)" \
    test "$status" = 2 -a -n "$(grep 'companion C has a queue of another size' err.txt)" -a ! -e cut.h5 -a ! -e cut.h5.part

if "$py" -c 'import scipy.fft, scipy.linalg' 2>/dev/null; then
    check "5. estimate / true error on exp1 before contact in [1/3, 3] (fixed steps; adaptive Euler, midpoint; adaptive mesh: Euler), on exp2's fronts in [1/10, 10] (adaptive mesh: midpoint)" \
        "$py" "$src/bench/error_estimate.py" --exe "$exe" --work "$scratch/bench" --quick --check
else
    echo "SKIP 5: $py has no scipy (the exact solution)"
fi

echo "$n_checks checks, $n_failed failed"
((n_failed == 0))
