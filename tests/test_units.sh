#!/usr/bin/env bash
# One unit convention (issue 36, docs/input.md "Units"): with &material every input that has
# a unit is SI, without it every input is nondimensional. An SI run equals the nondimensional
# run of the same inputs converted by hand (the scales of (2.10) computed here, by
# tests/tools/si_input.py, from the material values: not by rodcontact), every dataset to
# 1e-12 relative, on two materials (Table 1 copper with ell = 1 cm, and another, with
# viscosity, relaxation times, every initial profile, steps, two tables, a penalty contact, snapshot_dt
# and series_dt; adaptive steps on the second); the root attribute units; --check prints the
# nondimensional values derived; a restart of an SI run with its SI input continues it bit
# for bit; and an input that mixes the two systems is refused (exit 2, the variable named).
# Usage: bash test_units.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"
to_si() { "$py" "$src/tests/tools/si_input.py" "$@"; }

# the same datasets (/mesh, /series, /snapshots, /events) within 1e-12 of each one's largest value
close() {
    "$py" - "$1" "$2" << 'PY'
import sys, h5py, numpy as np
a, b, bad, n = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r"), [], [0]
def visit(name, obj):
    if not isinstance(obj, h5py.Dataset) or name.split("/")[0] not in ("mesh", "series", "snapshots", "events"):
        return
    n[0] += 1
    x, y = obj[()], b[name][()] if name in b else None
    if y is None or x.shape != y.shape:
        bad.append(f"{name}: {x.shape} vs {None if y is None else y.shape}"); return
    scale = float(np.max(np.abs(x))) if x.size else 0.0
    d = float(np.max(np.abs(x.astype(float) - y.astype(float)))) if x.size else 0.0
    if d > 1e-12 * scale or (x.dtype.kind in "iu" and d > 0):
        bad.append(f"{name}: max diff {d:.3e}, scale {scale:.3e}")
a.visititems(visit)
print(f"  {n[0]} datasets compared" + "".join("\n  " + p for p in bad))
sys.exit(1 if bad or n[0] < 20 else 0)
PY
}

# nondimensional inputs: every initial profile, both steps, contact by the penalty
cat > a.nml << 'EOF'
&contact g=0.05 eps=0.01 /
&mesh    n_elements=40 /
&time    dt=1e-3 t_end=0.3 /
&initial u0_poly = 0, 0.02   u1_poly = 0, 5   theta0_poly = 0, 40, -80, 40   p0_poly = 0, 0, 20, -40, 20
         q0_poly = 0, 1, -0.5   eta0_poly = 0, 0.3, 0.2   theta0_step = 5, 0.25   p0_step = 3, 0.5
         theta0_file = 'theta0.txt'   u1_file = 'u1.txt' /
&output  snapshot_dt=0.05 series_dt=0.01 quiet=.true. /
EOF
printf '0 2\n0.3 1.5\n0.7 4\n1 0\n' > theta0.txt   # tables: positions, values
printf '0 0\n0.5 -1\n1 2\n' > u1.txt
cp theta0.txt theta0_b.txt && cp u1.txt u1_b.txt   # b's own (their SI copies differ)
sed -e 's/theta0.txt/theta0_b.txt/; s/u1.txt/u1_b.txt/' -e 's/dt=1e-3 t_end=0.3/dt=1e-3 t_end=0.4 adaptive=.true. dt_min=1e-6 dt_max=0.02/' a.nml > b.nml
copper="ell=0.01 tau0=0.015 tau=0.1 mu_v=2e11"
other="T0=300 rho0=2700 cE=900 kappa=237 lambda=5.1e10 mu=2.6e10 alpha_t=2.3e-5 alpha_c=1.5e-4 D=1e-8 nu=1e4 \
varrho=1.2e6 ell=0.05 tau0=0.2 tau=1.5 lambda_v=1e11 mu_v=5e10"
for case in "a|$copper" "b|$other"; do
    IFS='|' read -r name material <<< "$case"
    # shellcheck disable=SC2086 # the material values are separate arguments
    to_si "$name.nml" $material > "${name}_si.nml" && to_si "$name.nml" $material --model > "${name}_nd.nml"
    "$exe" "${name}_si.nml" --set output.prefix="${name}_si" > "${name}_si.out" 2>&1
    check "$name: the SI run runs" equals 0 $?
    "$exe" "${name}_nd.nml" --set output.prefix="${name}_nd" > "${name}_nd.out" 2>&1
    check "$name: the nondimensional run of the converted inputs runs" equals 0 $?
    check "$name: SI run = nondimensional run, every dataset to 1e-12" close "${name}_si.h5" "${name}_nd.h5"
    check "$name: it has contact events" "$py" -c "import h5py, sys; sys.exit(int(h5py.File('${name}_si.h5')['events/t'].size < 1))"
done
check "units = 'SI' with &material, 'nondimensional' without" equals "SI nondimensional" \
    "$("$py" -c "import h5py; print(h5py.File('a_si.h5').attrs['units'], h5py.File('a_nd.h5').attrs['units'])")"
# --check prints what it derived: the &model values and the converted inputs
"$exe" --check a_si.nml > check.out 2>&1
check "--check: exit 0" equals 0 $?
dt_nd=$("$py" -c "print(float(open('check.out').read().split('time.dt')[1].split('=')[1].split()[0]))")
check "--check prints time.dt nondimensional (1e-3)" "$py" -c "import sys; sys.exit(abs($dt_nd - 1e-3) > 1e-9)"
check "--check prints model.rho, contact.g, initial.theta0_poly and what is off" \
    bash -c "grep -q '^    rho  *=' check.out && grep -q '^    contact.g ' check.out &&
             grep -q '^    initial.theta0_poly ' check.out && grep -q '^  off: diffusion' <('$exe' --check \
             <(sed 's/tau=0.1 //' a_si.nml))"

# a restart of an SI run from its SI input continues it bit for bit
"$exe" a_si.nml --set output.prefix=ck --set output.checkpoint_every=150 > /dev/null 2>&1 &&
    "$exe" a_si.nml --set output.prefix=rs --set "time.restart_from=ck.h5" > /dev/null 2>&1
check "restart of an SI run with its SI input: exit 0" equals 0 $?
check "the restarted SI run = the uninterrupted one" "$py" "$src/tests/tools/regression.py" same rs.h5 a_si.h5

# mixing the systems is refused
refused() {  # refused WHAT VARIABLE TEXT INPUT [ARGS ...]
    local what=$1 var=$2 text=$3 input=$4; shift 4
    "$exe" "$input" "$@" > mix.out 2> mix.err
    local status=$?
    check "refused: $what (exit 2, names $var)" \
        bash -c "[[ $status == 2 ]] && grep -qF 'error in $var: ' mix.err && grep -qF \"$text\" mix.err"
}
sed "s/units='SI' //" a_si.nml > old.nml
refused "&material without units = 'SI' (a nondimensional input)" material.units "say so with units = 'SI'" old.nml
refused "--set of &material on a nondimensional input" material.units "say so with units = 'SI'" a.nml \
    --set material.ell=0.01
refused "--set material.ell=... with &model" "--set material.ell" "both given" a_nd.nml --set material.ell=0.01 \
    --set material.units=SI
refused "another units" material.units "got 'nondimensional'" a_si.nml --set material.units=nondimensional
refused "a nondimensional step end on a 1 cm rod" initial.theta0_step "<= 0.01 (the rod's length" a_si.nml \
    --set 'initial.theta0_step(2)=0.25'

echo "test_units: $n_checks checks, $n_failed failed"
((n_failed == 0))
