#!/usr/bin/env bash
# What a run file holds beyond the fields (docs/output.md; issue 25): /snapshots/sigma is
# alpha u_x + varpi v_x - gamma1 theta - gamma2 P of the snapshot's own fields (the lumped
# projection of the element gradients: central differences inside, one-sided at the ends);
# the /series/energy_<part> add up to /series/energy (1e-12 relative); on a &material run
# every /series, /snapshots and /events dataset has si_factor and h5extract.py --si converts
# each to si_factor times its value; the file is netCDF-4: xarray (h5netcdf) opens the groups
# with coordinates t and x (/snapshots/u is (t, x)) and ncdump -h names every dimension (no
# phony ones); the run's last stderr line names its file, status, contact events and wall
# time (and there is none with quiet).
# Usage: bash test_output_contents.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"

# exp1 into contact (uniform mesh: the output grid is the nodes), and on an adaptive mesh
"$exe" "$src/input/exp1.nml" --set mesh.n_elements=40 --set time.t_end=0.25 --set output.snapshot_every=250 \
    --set output.prefix=run > run.out 2> run.err || { echo "FAIL: the run failed"; cat run.err; exit 1; }
"$exe" "$src/input/exp2.nml" --set time.t_end=0.02 --set mesh.adaptive=.true. --set mesh.max_level=3 \
    --set output.snapshot_every=100 --set output.prefix=am --set output.quiet=.true. > am.out 2> am.err ||
    { echo "FAIL: the adaptive-mesh run failed"; cat am.err; exit 1; }

check "sigma = alpha u_x + varpi v_x - gamma1 theta - gamma2 P of the snapshot fields (1e-12 of max |sigma|)" \
    "$py" - run.h5 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r"); m = lambda n: float(f.attrs["model." + n]); x = f["mesh/x"][:]; s = f["snapshots"]
worst = 0.0
for k in range(s["t"].shape[0]):
    grad = lambda g: np.gradient(s[g][k], x, edge_order=1)   # uniform x: central inside, one-sided at the ends
    want = m("alpha") * grad("u") + m("varpi") * grad("v") - m("gamma1") * s["theta"][k] - m("gamma2") * s["P"][k]
    worst = max(worst, np.max(np.abs(s["sigma"][k] - want)) / np.max(np.abs(want)))
print(f"  largest relative difference {worst:.2e} over {s['t'].shape[0]} snapshots")
sys.exit(0 if worst <= 1e-12 else 1)
PY

for run in run am; do
    check "$run: the eight /series/energy_<part> add up to /series/energy (1e-12 relative)" "$py" - $run.h5 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r"); s = f["series"]
parts = sorted(k for k in s if k.startswith("energy_"))
total = sum(s[k][:] for k in parts); energy = s["energy"][:]
rel = np.max(np.abs(total - energy) / np.abs(energy))
print(f"  {len(parts)} parts {parts}: largest relative difference {rel:.2e}")
sys.exit(0 if len(parts) == 8 and rel <= 1e-12 and s["energy_contact"][-1] >= 0 else 1)
PY
done

check "the run's last stderr line: file, status, contact events, steps, wall time" \
    grep -Eq '^rodcontact: run\.h5 complete; contact: 1 onset \(first t = 0\.[0-9]+\), no releases; 2500 steps, t = 0\.25, wall [0-9.eE+-]+ s; times nondimensional$' \
    <(tail -n 1 run.err)
check "no end line with quiet" bash -c "! grep -q ^rodcontact: am.err"   # (a Debug build may print runtime warnings)

# netCDF-4: dimension scales
check "xarray (h5netcdf) opens every group with named coordinates; /snapshots/u is (t, x)" "$py" - run.h5 am.h5 <<'PY'
import sys, h5py, numpy as np
import xarray as xr
bad = []
for path in sys.argv[1:]:
    s = xr.open_dataset(path, group="snapshots", engine="h5netcdf")
    with h5py.File(path, "r") as f:
        if s["u"].dims != ("t", "x") or s["sigma"].dims != ("t", "x"):
            bad.append(f"{path}: /snapshots/u is {s['u'].dims}")
        if not (np.array_equal(s["x"].values, f["mesh/x"][:]) and np.array_equal(s["t"].values, f["snapshots/t"][:])):
            bad.append(f"{path}: the snapshots' coordinates are not /mesh/x and /snapshots/t")
        for c in ("t", "x"):
            if not s[c].attrs.get("long_name") or s[c].attrs.get("units") != "1":
                bad.append(f"{path}: coordinate {c} has no long_name/units")
        series = xr.open_dataset(path, group="series", engine="h5netcdf")
        if list(series.coords) != ["t"] or any(series[v].dims != ("t",) for v in series.data_vars):
            bad.append(f"{path}: /series not all on t")
        events = xr.open_dataset(path, group="events", engine="h5netcdf")
        if events["kind"].dims != ("t",):
            bad.append(f"{path}: /events/kind is {events['kind'].dims}")
        if "snapshots/native" in f:
            native = xr.open_dataset(path, group="snapshots/native", engine="h5netcdf")
            if native["u"].dims != ("x",) or native["offset"].dims != ("t",):
                bad.append(f"{path}: native u {native['u'].dims}, offset {native['offset'].dims}")
            if not np.array_equal(native["x"].values, f["snapshots/native/x"][:]):
                bad.append(f"{path}: native x is not the coordinate of the native fields")
print("\n".join("  " + b for b in bad))
sys.exit(1 if bad else 0)
PY
if command -v ncdump > /dev/null; then
    for run in run am; do
        ncdump -h $run.h5 > $run.cdl 2> $run.cdl.err
        check "$run: ncdump -h reads it; no phony dimensions" \
            bash -c "[[ ! -s $run.cdl.err ]] && ! grep -q phony_dim $run.cdl && grep -q 'double u(t, x)' $run.cdl"
    done
else
    echo "NOTE: no ncdump (Debian package netcdf-bin): the CDL check is left out"
fi

# SI: every dataset of a &material run converts
sed -e 's/n_elements=500/n_elements=20/' -e 's/t_end=3.0/t_end=0.01/' -e "s|prefix='out/exp1'|prefix='mat' quiet=.true.|" \
    "$src/input/exp1.nml" > mat_nd.nml
"$py" "$src/tests/tools/si_input.py" mat_nd.nml ell=1.0 > mat.nml   # the same run in SI units
"$exe" mat.nml > /dev/null 2>&1 || { echo "FAIL: the &material run failed"; exit 1; }
check "&material: every /series, /snapshots, /events dataset has si_factor and si_units" "$py" - mat.h5 <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r"); missing = []
def visit(name, obj):
    if isinstance(obj, h5py.Dataset) and name.split("/")[0] in ("series", "snapshots", "events", "mesh"):
        if "si_factor" not in obj.attrs or "si_units" not in obj.attrs:
            missing.append(name)
f.visititems(visit)
print("  without si_factor:", missing or "none")
sys.exit(1 if missing else 0)
PY
"$py" "$src/scripts/h5extract.py" series mat.h5 --si > si.txt 2> si.err
check "h5extract.py series --si: exit 0 with every dataset" test ! -s si.err
check "h5extract.py series --si: each column is si_factor times the stored value" "$py" - mat.h5 si.txt <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r"); d = np.loadtxt(sys.argv[2])
head = [l for l in open(sys.argv[2]) if l.startswith("# t [")][0].split()[1:]
names = head[0::2]
bad = [n for k, n in enumerate(names)
       if not np.allclose(d[:, k], f["series/" + n].attrs["si_factor"] * f["series/" + n][:], rtol=1e-15, atol=0)]
print(f"  {len(names)} columns; differing: {bad or 'none'}")
sys.exit(0 if len(names) == len(f["series"]) and not bad else 1)
PY
"$py" "$src/scripts/h5extract.py" snapshot mat.h5 --time 0 --si > si_snap.txt 2> /dev/null
check "h5extract.py snapshot --si: sigma in Pa" grep -q 'sigma \[Pa\]' si_snap.txt
check "energy in J/m^2, its si_factor = ell (lambda + 2 mu) delta^2 / a-check" "$py" - mat.h5 <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r"); a = f.attrs
stiff = a["material.lambda"] + 2 * a["material.mu"]
want = a["material.ell"] * stiff * a["derived.delta"] ** 2 / a["derived.a_check"]
e = f["series/energy"].attrs
sys.exit(0 if abs(e["si_factor"] - want) <= 1e-12 * want and e["si_units"] == "J/m^2" else 1)
PY

echo "test_output_contents: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
