#!/usr/bin/env bash
# Adaptive time steps through the program (&time adaptive = .true.; unit checks of the
# controller and of the estimate against the true error: test_step_control.f90):
#  1. exp1 (h = 1/100) to t = 2, which holds the contact onset (t ~ 0.19) and release
#     (t ~ 1.45), against a fixed-step BDF2 run with dt = 2.5e-5 on the same mesh: for the
#     midpoint rule and BDF2 the achieved max |u(1,t) - reference| and the event times'
#     errors shrink as error_tol goes 1e-4 -> 1e-5 -> 1e-6 (the error by at least 5x over
#     the two decades; the event error at 1e-6 below those at 1e-4 and 1e-5); steps are
#     rejected somewhere and grow to at least 20 (5) times the first one at 1e-4 (below); snapshots sit at exactly
#     k snapshot_dt; /series/dt adds up to t;
#  2. the energy law on every shipped input (h = 1/50, t_end <= 1) with adaptive Euler
#     (E^n <= E^{n-1}) and midpoint steps (the identity), and on 50 random parameter sets:
#     the root attribute energy_max_relative_rise (the monitor's check, step by step) stays
#     at round-off (<= 1e-10). BDF2's law (G-energy, constant steps, contact node inactive;
#     rises at step-size changes are recorded apart) is checked the same way on the shipped
#     inputs that do not reach the obstacle (docs/scheme.md).
# Usage: bash test_adaptive.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
. "$src/tests/lib/checks.sh"
cd "$scratch" && rm -rf ./* || exit 1

common=(--set mesh.n_elements=100 --set time.t_end=2.0 --set output.quiet=.true. --set output.snapshot_every=1000000000)
"$exe" "$src/input/exp1.nml" "${common[@]}" --set time.scheme="'bdf2'" --set time.dt=2.5e-5 \
    --set output.prefix="'ref'" || { echo "FAIL: reference run"; exit 1; }
for scheme in midpoint bdf2; do
    for tol in 1e-4 1e-5 1e-6; do
        "$exe" "$src/input/exp1.nml" "${common[@]}" --set time.scheme="'$scheme'" --set time.adaptive=.true. \
            --set time.error_tol=$tol --set output.snapshot_dt=0.25 \
            --set output.prefix="'${scheme}_$tol'" || check "$scheme error_tol=$tol: exit 0" false
    done
    check "$scheme: error, event times and the estimate shrink with error_tol; rejections, growth, exact snapshot times" \
        "$py" - "$scheme" <<'EOF'
import sys, h5py, numpy as np
scheme = sys.argv[1]
ref = h5py.File('ref.h5', 'r'); tr, ur = ref['series/t'][:], ref['series/u_end'][:]
ev_ref = ref['events/t'][:]
ok = len(ev_ref) == 2 and list(ref['events/kind'][:]) == [1, -1]
errors, event_errors = [], []
for tol in ['1e-4', '1e-5', '1e-6']:
    f = h5py.File(f'{scheme}_{tol}.h5', 'r')
    t, u, dt = f['series/t'][:], f['series/u_end'][:], f['series/dt'][:]
    errors.append(np.abs(u - np.interp(t, tr, ur)).max())
    ev = f['events/t'][:]
    event_errors.append(np.abs(ev - ev_ref).max() if len(ev) == len(ev_ref) else np.inf)
    a = f.attrs
    print(f"{scheme} error_tol={tol}: steps {a['steps']}, rejected {a['time_steps_rejected']}, "
          f"max|u(1,t) - ref| {errors[-1]:.2e}, events {ev} (ref {ev_ref}), "
          f"step_control_error_sum_relative {a['step_control_error_sum_relative']:.2e}, dt in [{dt[1:].min():.1e}, {dt.max():.1e}]")
    rejected = a['time_steps_rejected'] if tol == '1e-4' else rejected + a['time_steps_rejected']
    ok &= dt.max() >= (20 if tol == '1e-4' else 5) * dt[1]     # grown in the quiet phase
    ok &= abs(np.sum(dt) - t[-1]) <= 1e-12 and abs(t[-1] - 2.0) <= 1e-12
    snaps = f['snapshots/t'][:]
    ok &= np.array_equal(snaps, np.array([0.25 * k for k in range(0, 9)]))   # at k snapshot_dt exactly
ok &= rejected > 0
ok &= errors[0] > errors[1] > errors[2] and errors[0] > 5 * errors[2]
ok &= event_errors[0] > event_errors[2] and event_errors[1] > event_errors[2]
sys.exit(0 if ok else 1)
EOF
done

# --summary reports the events (counts, first and last times) and the time error estimate;
# --events lists them
row=$("$exe" --summary midpoint_1e-6.h5 | tail -1)
check "--summary: onset and release times and step_control_err of midpoint_1e-6.h5 ($row)" \
    "$py" -c "import csv, sys; r = list(csv.reader([sys.argv[1]]))[0]; h = list(csv.reader([sys.argv[2]]))[0]
d = dict(zip(h, r)); sys.exit(0 if d['n_onsets'] == '1' and d['n_releases'] == '1' and abs(float(d['first_onset_t [1]']) - 0.1906) < 1e-3 and abs(float(d['first_release_t [1]']) - 1.447) < 1e-3 and float(d['step_control_err']) > 0 else 1)" "$row" "$("$exe" --summary-header)"
check "--events: one row per event (the onset, then the release)" equals "1,onset 2,release" \
    "$("$exe" --events midpoint_1e-6.h5 | tail -n +2 | cut -d, -f2,3 | tr '\n' ' ' | sed 's/ $//')"

# 2. the energy law: shipped inputs
for input in "$src"/input/*.nml; do
    name=$(basename "$input" .nml)
    t_end=$("$py" -c "import re,sys; m = re.search(r't_end\s*=\s*([0-9.eE+-]+)', open(sys.argv[1]).read()); print(min(float(m.group(1)), 1.0))" "$input")
    for scheme in euler midpoint bdf2; do
        "$exe" "$input" --set mesh.n_elements=50 --set time.t_end="$t_end" --set time.adaptive=.true. \
            --set time.scheme="'$scheme'" --set output.quiet=.true. --set output.snapshot_every=1000000000 \
            --set output.prefix="'law_${name}_$scheme'" || check "$name $scheme adaptive: exit 0" false
    done
done
check "energy law with adaptive steps on every shipped input (Euler, midpoint: every step; BDF2: its constant-step steps)" \
    "$py" - <<'EOF'
import glob, sys, h5py
ok = True
for name in sorted(glob.glob('law_*.h5')):
    a = h5py.File(name, 'r').attrs
    rise = a['energy_max_relative_rise']
    bound = 1e-10
    good = rise <= bound or (name.endswith('_bdf2.h5') and a['solver.contact_steps'] > 0)
    print(f"{name}: steps {a['steps']}, contact steps {a['solver.contact_steps']}, law's max relative rise {rise:.2e}"
          + ('' if good or not name.endswith('_bdf2.h5') else ' (BDF2)'))
    ok &= bool(good)
sys.exit(0 if ok else 1)
EOF

# 2b. 50 random parameter sets (penalty and Signorini, contact reached), Euler and midpoint
"$py" - "$src/input/exp1.nml" > random_sets.txt <<'EOF'
import random, sys
random.seed(2026)
def lu(a, b): return 10 ** random.uniform(a, b)
for k in range(50):
    rho, alpha, varpi = lu(-3, 0), lu(-2, 0), lu(-2, 0)
    c, r = random.uniform(0.5, 2), random.uniform(0.5, 2)
    d = random.uniform(0, 0.5) * (r * c) ** 0.5
    law = random.choice(['penalty', 'signorini'])
    print(f"--set model.rho={rho:.6g} --set model.alpha={alpha:.6g} --set model.varpi={varpi:.6g} "
          f"--set model.gamma1={random.uniform(0, 1):.6g} --set model.gamma2={random.uniform(0, 1):.6g} "
          f"--set model.c={c:.6g} --set model.r={r:.6g} --set model.d={d:.6g} --set model.hbar={lu(-2, 0):.6g} "
          f"--set model.tau0={lu(-2, 0):.6g} --set model.tau={lu(-2, 0):.6g} "
          f"--set contact.g={random.uniform(0.01, 0.1):.6g} --set contact.eps={lu(-3, -1):.6g} --set contact.law='{law}'")
EOF
k=0
while read -r -a set_args; do
    k=$((k + 1))
    for scheme in euler midpoint; do
        "$exe" "$src/input/exp1.nml" "${set_args[@]}" --set mesh.n_elements=20 --set time.t_end=0.5 \
            --set time.dt=1e-3 --set time.adaptive=.true. --set time.scheme="'$scheme'" --set output.quiet=.true. \
            --set output.snapshot_every=1000000000 --set output.prefix="'random_${k}_$scheme'" \
            || check "random set $k $scheme: exit 0 (${set_args[*]})" false
    done
done < random_sets.txt
check "energy law with adaptive steps on 50 random parameter sets (Euler, midpoint)" "$py" - <<'EOF'
import glob, sys, h5py
worst, n, contact = 0.0, 0, 0
for name in glob.glob('random_*.h5'):
    a = h5py.File(name, 'r').attrs
    worst = max(worst, a['energy_max_relative_rise']); n += 1
    contact += a['solver.contact_steps'] > 0
print(f"{n} runs, {contact} with contact, largest relative rise of the law's energy {worst:.2e}")
sys.exit(0 if n == 100 and worst <= 1e-10 and contact >= 20 else 1)
EOF

echo "test_adaptive: $n_checks checks, $n_failed failed"
[ "$n_failed" -eq 0 ]
