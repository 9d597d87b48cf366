#!/usr/bin/env bash
# The adaptive mesh through the program (&mesh adaptive = .true.; unit checks of graded P1
# and of the transfer between meshes: test_graded_mesh.f90):
#  1. bad &mesh / &output n_points values and the paper's iteration with an adaptive mesh
#     exit 2 with a message naming the variable;
#  2. checkpoint/restart with adaptivity on (BDF2 with adaptive steps, Euler with fixed
#     steps): the split run equals the uninterrupted one bit for bit, /snapshots/native too,
#     and in every counter the checkpoint carries and the events; /snapshots/native holds at
#     the points of /mesh/x the values /snapshots holds there;
#  3. the energy never rises through remeshes: on every shipped input (Euler and midpoint
#     with adaptive steps, BDF2 with fixed steps) the remesh check
#     energy_max_relative_rise_remesh stays at round-off (<= 1e-12) and the step-by-step law
#     (energy_max_relative_rise) as well (Euler, midpoint); the same on 50 random parameter
#     sets (Euler, adaptive steps, contact reached); with the redistributed mass (&contact
#     mass = 'redistributed') on impact.nml through both impacts' onsets and the release
#     (Euler, BDF2, midpoint; Signorini; fixed steps) the remesh check as well (it was up to
#     1.4e-5 (Euler), 2.0e-6 (midpoint), 1.3e-7 (BDF2) with the consistent L2 projection of v);
#  4. a front is followed: on exp2 (BDF2, adaptive steps, 250 coarse elements, 3 levels) at
#     the snapshots t = 0.01 .. 0.04 every element within 0.01 of x = 0.1 + t v_P is refined
#     (h <= 1/500), some at least twice (h <= 1/1000), and the mesh holds fewer than half the
#     2000 elements of the finest uniform mesh (measured 756, 925, 886, 730). (Before the
#     pulses' jump node got the mean of its two sides, the full amplitude there was a
#     grid-scale spike whose oscillation trains had the whole rod behind the front at the
#     finest level, 819 to 1758 elements, and the finest elements sat at the front.)
#  5. the contact claims: exp1, exp2, exp3 on adaptive meshes (coarse mesh 1/100, 2 levels,
#     fixed steps dt = 1e-3) have one contact interval whose onset and release are within
#     0.01 of the paper's (0.19-1.45, 0.30-1.36, 0.31-1.40); /snapshots stay on /mesh/x.
# Usage: bash test_adaptive_mesh.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
. "$src/tests/lib/checks.sh"
cd "$scratch" && rm -rf ./* || exit 1
quiet=(--set output.quiet=.true. --set output.snapshot_every=1000000000)

# 1. bad inputs
bad() {   # bad <variable named in the message> <--set arguments...>
    local name=$1; shift
    "$exe" "$src/input/exp2.nml" "$@" --set output.prefix="'bad'" > bad.out 2> bad.err
    local rc=$?
    check "bad input $*: exit 2" equals 2 "$rc"
    check "bad input $*: message names $name" grep -q "$name" bad.err
    check "bad input $*: no output file" test ! -e bad.h5 -a ! -e bad.h5.part
}
bad mesh.error_tol --set mesh.adaptive=.true. --set mesh.error_tol=0
bad mesh.max_level --set mesh.max_level=-1
bad mesh.max_level --set mesh.max_level=31
bad mesh.max_level --set mesh.adaptive=.true. --set mesh.n_elements=500 --set mesh.max_level=25
bad mesh.remesh_every --set mesh.remesh_every=0
bad output.n_points --set output.n_points=1
bad solver.method --set mesh.adaptive=.true. --set solver.method="'paper'"

# 2. restart with adaptivity on
for case in bdf2_adaptive euler_fixed; do
    if [ $case = bdf2_adaptive ]; then
        args=(--set time.scheme="'bdf2'" --set time.adaptive=.true. --set time.error_tol=1e-5)
    else
        args=(--set time.scheme="'euler'" --set time.dt=1e-3)
    fi
    common=("$src/input/exp1.nml" --set mesh.n_elements=50 --set mesh.adaptive=.true. --set mesh.max_level=3
            "${args[@]}" --set output.quiet=.true. --set output.snapshot_dt=0.05 --set output.checkpoint_every=7)
    "$exe" "${common[@]}" --set time.t_end=0.4 --set output.prefix="'full_$case'" || check "$case: full run" false
    "$exe" "${common[@]}" --set time.t_end=0.2 --set output.prefix="'half_$case'" || check "$case: half run" false
    "$exe" "${common[@]}" --set time.t_end=0.4 --set time.restart_from="'half_$case.h5'" \
        --set output.prefix="'rest_$case'" || check "$case: restarted run" false
    check "$case: split and restarted = uninterrupted, /snapshots/native included" \
        "$py" "$src/tests/tools/regression.py" same "full_$case.h5" "rest_$case.h5"
    # every counter a checkpoint carries (step control, energy monitor, solver, remeshes, the
    # most elements held) and the events, by name (same compares them too; this names what
    # differs)
    check "$case: split and restarted = uninterrupted in the run's counters and events" "$py" -c "
import h5py, sys
a, b = h5py.File('full_$case.h5', 'r'), h5py.File('rest_$case.h5', 'r')
keys = [k for k in a.attrs if k.startswith(('time_', 'energy_', 'solver.', 't_final', 'steps')) or k in ('mesh.remeshes', 'mesh.n_elements_max')]
bad = [k for k in keys if k not in b.attrs or str(a.attrs[k]) != str(b.attrs[k])]
bad += ['/events/' + d for d in a['events'] if a['events'][d][()].tobytes() != b['events'][d][()].tobytes()]
print(' '.join(bad)); sys.exit(1 if bad else 0)"
    check "$case: /snapshots/native = /snapshots at the points of /mesh/x (every one a node)" "$py" - "full_$case.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
native, x_grid = f["snapshots/native"], f["mesh/x"][:]
offset, count = native["offset"][:], native["count"][:]
bad = [] if len(offset) == len(f["snapshots/t"]) > 1 and offset[-1] + count[-1] == len(native["x"]) else ["offsets"]
for k in range(len(offset)):
    x = native["x"][offset[k]:offset[k] + count[k]]
    at = np.clip(np.searchsorted(x, x_grid - 1e-12), 0, len(x) - 1)
    if not (np.all(np.diff(x) > 0) and np.all(np.abs(x[at] - x_grid) <= 1e-12)):
        bad.append(f"snapshot {k}: a point of /mesh/x is not a node")
        continue
    for field in ("u", "v", "theta", "P", "q", "eta"):
        fixed, own = f["snapshots/" + field][k], native[field][offset[k]:offset[k] + count[k]][at]
        if not np.max(np.abs(fixed - own)) <= 1e-13 * max(np.max(np.abs(own)), 1e-300):
            bad.append(f"snapshot {k} (t = {f['snapshots/t'][k]}): {field} differs by {np.max(np.abs(fixed - own)):.3e}")
print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
    check "$case: the mesh changed during the run (remeshes > 0, several mesh sizes)" "$py" -c "
import h5py, sys, numpy as np
f = h5py.File('full_$case.h5', 'r')
sys.exit(0 if f.attrs['mesh.remeshes'] > 0 and len(np.unique(f['series/n_elements'][:])) > 2 else 1)"
done

# 3. energy through remeshes: shipped inputs
for input in "$src"/input/*.nml; do
    name=$(basename "$input" .nml)
    for scheme in euler midpoint bdf2; do
        adapt=(--set time.adaptive=.true.)
        [ $scheme = bdf2 ] && adapt=(--set time.dt=1e-3)
        "$exe" "$input" --set mesh.n_elements=40 --set mesh.adaptive=.true. --set mesh.max_level=3 \
            --set time.t_end=0.5 --set time.scheme="'$scheme'" "${adapt[@]}" "${quiet[@]}" \
            --set output.prefix="'law_${name}_$scheme'" || check "$name $scheme: exit 0" false
    done
done
check "energy through remeshes on every shipped input" "$py" - <<'PY'
import glob, sys, h5py
ok = True
for name in sorted(glob.glob('law_*.h5')):
    a = h5py.File(name, 'r').attrs
    remesh, step = a['energy_max_relative_rise_remesh'], a['energy_max_relative_rise']
    good = remesh <= 1e-12 and (step <= 1e-10 or name.endswith('_bdf2.h5'))
    print(f"{name}: remeshes {a['mesh.remeshes']}, largest rise across a remesh {remesh:.1e}, step law {step:.1e}")
    ok &= bool(good) and a['mesh.remeshes'] > 0
sys.exit(0 if ok else 1)
PY
for scheme in euler bdf2 midpoint; do
    "$exe" "$src/input/impact.nml" --set contact.law="'signorini'" --set contact.mass="'redistributed'" \
        --set mesh.n_elements=250 --set mesh.adaptive=.true. --set mesh.max_level=2 --set time.t_end=1.5 \
        --set time.scheme="'$scheme'" "${quiet[@]}" --set output.prefix="'redistributed_$scheme'" \
        || check "impact.nml, redistributed mass, $scheme: exit 0" false
done
check "energy through remeshes with the redistributed mass (impact.nml)" "$py" - <<'PY'
import glob, sys, h5py
ok = True
for name in sorted(glob.glob('redistributed_*.h5')):
    a = h5py.File(name, 'r').attrs
    remesh = a['energy_max_relative_rise_remesh']
    print(f"{name}: remeshes {a['mesh.remeshes']}, largest rise across a remesh {remesh:.1e}")
    ok &= bool(remesh <= 1e-12) and a['mesh.remeshes'] > 100
sys.exit(0 if ok else 1)
PY
"$py" - > random_sets.txt <<'PY'
import random
random.seed(2027)
def lu(a, b): return 10 ** random.uniform(a, b)
for k in range(50):
    c, r = random.uniform(0.5, 2), random.uniform(0.5, 2)
    d = random.uniform(0, 0.5) * (r * c) ** 0.5
    print(f"--set model.rho={lu(-3, 0):.6g} --set model.alpha={lu(-2, 0):.6g} --set model.varpi={lu(-2, 0):.6g} "
          f"--set model.gamma1={random.uniform(0, 1):.6g} --set model.gamma2={random.uniform(0, 1):.6g} "
          f"--set model.c={c:.6g} --set model.r={r:.6g} --set model.d={d:.6g} --set model.hbar={lu(-2, 0):.6g} "
          f"--set model.tau0={lu(-2, 0):.6g} --set model.tau={lu(-2, 0):.6g} "
          f"--set contact.g={random.uniform(0.01, 0.1):.6g} --set contact.eps={lu(-3, -1):.6g} "
          f"--set contact.law='{random.choice(['penalty', 'signorini'])}'")
PY
k=0
while read -r -a set_args; do
    k=$((k + 1))
    "$exe" "$src/input/exp1.nml" "${set_args[@]}" --set mesh.n_elements=20 --set mesh.adaptive=.true. \
        --set mesh.max_level=3 --set time.t_end=0.5 --set time.dt=1e-3 --set time.adaptive=.true. "${quiet[@]}" \
        --set output.prefix="'random_$k'" || check "random set $k: exit 0 (${set_args[*]})" false
done < random_sets.txt
check "energy through remeshes on 50 random parameter sets" "$py" - <<'PY'
import glob, sys, h5py
worst_remesh, worst_step, n, contact, remeshed = 0.0, 0.0, 0, 0, 0
for name in glob.glob('random_*.h5'):
    a = h5py.File(name, 'r').attrs
    worst_remesh = max(worst_remesh, a['energy_max_relative_rise_remesh'])
    worst_step = max(worst_step, a['energy_max_relative_rise']); n += 1
    contact += a['solver.contact_steps'] > 0
    remeshed += a['mesh.remeshes'] > 0
print(f"{n} runs, {contact} with contact, {remeshed} remeshed; largest rise across a remesh {worst_remesh:.1e}, "
      f"step by step {worst_step:.1e}")
sys.exit(0 if n == 50 and worst_remesh <= 1e-12 and worst_step <= 1e-10 and contact >= 10 and remeshed == 50 else 1)
PY

# 4. the front is followed
"$exe" "$src/input/exp2.nml" --set mesh.n_elements=250 --set mesh.adaptive=.true. --set mesh.max_level=3 \
    --set time.scheme="'bdf2'" --set time.adaptive=.true. --set time.error_tol=1e-4 --set time.t_end=0.04 \
    --set output.snapshot_dt=0.01 --set output.quiet=.true. --set output.prefix="'front'" || check "front run" false
check "exp2: within 0.01 of x = 0.1 + t v_P refined, some twice, at t = 0.01 .. 0.04, < 1000 elements" "$py" - <<'PY'
import sys, h5py, numpy as np
f = h5py.File('front.h5', 'r'); a = f.attrs
v_P = np.sqrt(a['model.hbar'] / (a['model.r'] * a['model.tau']))
ok = True
for k, t in enumerate(f['snapshots/t'][:]):
    if t <= 0: continue
    o, c = int(f['snapshots/native/offset'][k]), int(f['snapshots/native/count'][k])
    x = f['snapshots/native/x'][o:o + c]; h = np.diff(x)
    front = 0.1 + t * v_P
    near = h[np.abs(0.5 * (x[1:] + x[:-1]) - front) < 0.01]
    print(f"t = {t:.2f}: front at {front:.4f}, elements within 0.01 of it from 1/{1 / near.max():.0f} "
          f"to 1/{1 / near.min():.0f}, {c - 1} elements")
    ok &= near.max() <= 1.0 / 500 * (1 + 1e-9) and near.min() <= 1.0 / 1000 * (1 + 1e-9) and c - 1 < 1000
sys.exit(0 if ok else 1)
PY

# 5. the contact claims (onset and release) on adaptive meshes
for name in exp1 exp2 exp3; do
    for mode in uniform adaptive; do
        extra=()
        [ $mode = adaptive ] && extra=(--set mesh.adaptive=.true. --set mesh.max_level=2)
        "$exe" "$src/input/$name.nml" --set mesh.n_elements=100 --set time.dt=1e-3 --set time.t_end=2.0 \
            "${extra[@]}" "${quiet[@]}" --set output.prefix="'claims_${name}_$mode'" || check "$name $mode: exit 0" false
    done
done
check "exp1-exp3 on adaptive meshes: one contact interval, onset and release within 0.01 of the claims; snapshots on /mesh/x" \
    "$py" - <<'PY'
import sys, h5py, numpy as np
# the contact intervals the inputs' headers and docs/reproduction.md state (Section 7)
claims = {'exp1': [0.19, 1.45], 'exp2': [0.30, 1.36], 'exp3': [0.31, 1.40]}
ok = True
for name, claim in claims.items():
    u, a = h5py.File(f'claims_{name}_uniform.h5', 'r'), h5py.File(f'claims_{name}_adaptive.h5', 'r')
    tu, ta = u['events/t'][:], a['events/t'][:]
    good = len(ta) == 2 and list(a['events/kind'][:]) == [1, -1] and np.all(np.abs(ta - claim) <= 0.01)
    good &= a['snapshots/u'].shape[1] == a['mesh/x'].shape[0] == 101
    print(f"{name}: claim {claim}, adaptive mesh {ta}, uniform 1/100 {tu}, remeshes {a.attrs['mesh.remeshes']}")
    ok &= bool(good)
sys.exit(0 if ok else 1)
PY
echo "test_adaptive_mesh: $n_checks checks, $n_failed failed"
[ "$n_failed" -eq 0 ]
