#!/usr/bin/env bash
# Self-describing files (issue 14, deliverable 2): the provenance root attributes (created,
# source_version, host, command_line, hdf5_version, compiler_version), logical attributes
# listed in logical_attributes, long_name and units on every dataset; with &material the
# material values, the derived groups and scales of (2.10), each recomputed here from the
# paper's definitions, and si_factor/si_units on the datasets measured in each scale.
# Usage: bash test_provenance.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
printf "&time t_end=0.002 /\n&mesh n_elements=20 /\n&output prefix='plain' quiet=.true. /\n" > plain.nml
printf "&contact g=0.1 eps=0.01 /\n&initial theta0_poly=0,40,-80,40 p0_poly=0,0,20,-40,20 u1_poly=0,10 /\n&time dt=1e-4 t_end=0.002 /\n&mesh n_elements=20 /\n&output prefix='mat' quiet=.true. /\n" > mat_nd.nml
# the same run in SI units (the defaults of g, eps, dt written out: they are nondimensional)
"$py" "$src/tests/tools/si_input.py" mat_nd.nml T0=300 ell=0.5 tau0=1e-3 tau=2e-3 mu_v=1e13 > mat.nml
"$exe" plain.nml > /dev/null || { echo "FAIL: plain run exit $?"; exit 1; }
"$exe" mat.nml > /dev/null || { echo "FAIL: &material run exit $?"; exit 1; }
# source_version: git describe at configure time, so a commit made since then may be newer;
# it must name a commit of this repository ('unknown' only outside a git checkout)
sv=$("$py" -c "import h5py; print(h5py.File('plain.h5', 'r').attrs['source_version'])")
expected_version=unknown
if git -C "$src" rev-parse --git-dir > /dev/null 2>&1; then
    hash=$(grep -oE '[0-9a-f]{7,40}' <<< "${sv##*-g}" | head -1)
    if [ -n "$hash" ] && git -C "$src" cat-file -e "$hash^{commit}" 2>/dev/null; then expected_version=$sv
    else echo "FAIL: source_version '$sv' names no commit of $src"; exit 1; fi
fi
"$py" - "$expected_version" "$(hostname)" "$exe" <<'PY'
import sys, re, datetime, math, h5py
version, host, exe = sys.argv[1:4]
bad = []
def check(cond, what):
    if not cond:
        bad.append(what)
for name in ("plain.h5", "mat.h5"):
    f = h5py.File(name, "r")
    a = f.attrs
    created = a.get("created", "")
    check(re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", created), f"{name}: created = {created!r}, not UTC ISO 8601")
    if re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", created):
        age = datetime.datetime.now(datetime.timezone.utc) - datetime.datetime.strptime(
            created, "%Y-%m-%dT%H:%M:%SZ").replace(tzinfo=datetime.timezone.utc)
        check(abs(age.total_seconds()) < 600, f"{name}: created = {created} is {age} from now (not UTC?)")
    sv = a.get("source_version", "")
    check(sv == version,
          f"{name}: source_version = {sv!r}, expected git describe {version!r}")
    check(a.get("host") == host, f"{name}: host = {a.get('host')!r}, expected {host!r}")
    check(a.get("command_line", "").startswith(exe) and name.replace(".h5", ".nml") in a.get("command_line", ""),
          f"{name}: command_line = {a.get('command_line')!r}")
    check(a.get("hdf5_version") == h5py.version.hdf5_version,
          f"{name}: hdf5_version = {a.get('hdf5_version')!r}, h5py's library is {h5py.version.hdf5_version}")
    check("GCC" in a.get("compiler_version", "") or "Fortran" in a.get("compiler_version", ""),
          f"{name}: compiler_version = {a.get('compiler_version')!r}")
    logicals = a.get("logical_attributes", "").split()
    check(set(logicals) == {"mesh.adaptive", "time.adaptive", "output.quiet", "output.error_estimate", "output.snapshot_land", "solver.block_solver"}, f"{name}: logical_attributes = {logicals}")
    for k in logicals:
        check(k in a and int(a[k]) in (0, 1), f"{name}: logical attribute {k} = {a.get(k)!r}, not 0/1")
    def visit(path, obj):
        if isinstance(obj, h5py.Dataset) and not path.startswith("checkpoint"):
            check(obj.attrs.get("long_name", "") != "" and "units" in obj.attrs,
                  f"{name}: /{path} lacks long_name or units")
    f.visititems(visit)
    check("scale: temperature" in f["snapshots/theta"].attrs["long_name"],
          f"{name}: /snapshots/theta long_name does not name its scale")

plain, mat = h5py.File("plain.h5", "r"), h5py.File("mat.h5", "r")
check(not any(k.startswith(("material.", "scale.", "derived.")) for k in plain.attrs),
      "plain.h5 (no &material) has material/scale attributes")
check("si_factor" not in plain["snapshots/u"].attrs, "plain.h5: si_factor without &material")
# Table 1 defaults with the values of mat.nml, and the scales of (2.10) recomputed here
m = dict(T0=300.0, rho0=8954.0, cE=383.1, kappa=386.0, lam=7.76e10, mu=3.86e10, alpha_t=1.78e-5,
         alpha_c=1.98e-4, D=0.85e-8, ell=0.5)
for k, v in (("T0", 300.0), ("ell", 0.5), ("tau0", 1e-3), ("tau", 2e-3), ("mu_v", 1e13), ("rho0", 8954.0)):
    check(mat.attrs.get("material." + k) == v, f"mat.h5: material.{k} = {mat.attrs.get('material.' + k)}, expected {v}")
stiff = m["lam"] + 2 * m["mu"]
beta1, beta2 = (3 * m["lam"] + 2 * m["mu"]) * m["alpha_t"], (3 * m["lam"] + 2 * m["mu"]) * m["alpha_c"]
omega = m["rho0"] * m["cE"] * m["ell"] ** 2 / m["kappa"]
delta = math.sqrt(stiff / (m["rho0"] * m["cE"] * m["T0"]))
scales = {"time": (omega, "s"), "position": (m["ell"], "m"), "displacement": (m["ell"] * delta, "m"),
          "velocity": (m["ell"] * delta / omega, "m/s"), "temperature": (stiff * delta / beta1, "K"),
          "chemical_potential": (beta2 * delta, "J/kg"), "stress": (stiff * delta * m["rho0"] * m["cE"] * stiff / (m["T0"] * beta1 ** 2), "Pa"),
          "heat_flux": (m["rho0"] * m["cE"] * delta * m["ell"] * stiff / (omega * beta1), "W/m^2"),
          "diffusion_flux": (m["D"] * beta2 * delta / m["ell"], "kg/(m^2 s)"),
          "energy": (m["ell"] * stiff * delta ** 2 * m["rho0"] * m["cE"] * stiff / (m["T0"] * beta1 ** 2), "J/m^2")}
for k, (factor, units) in scales.items():
    got = mat.attrs.get("scale." + k, float("nan"))
    check(abs(got - factor) <= 1e-12 * abs(factor), f"mat.h5: scale.{k} = {got}, expected {factor}")
    check(mat.attrs.get(f"scale.{k}.units") == units, f"mat.h5: scale.{k}.units = {mat.attrs.get(f'scale.{k}.units')}")
check(abs(mat.attrs["derived.omega"] - omega) <= 1e-12 * omega, "mat.h5: derived.omega")
check(abs(mat.attrs["model.tau0"] - 1e-3 / omega) <= 1e-12 * 1e-3 / omega, "mat.h5: model.tau0 is not tau0/omega")
for path, scale in (("mesh/x", "position"), ("snapshots/t", "time"), ("series/t", "time"), ("snapshots/u", "displacement"),
                    ("series/u_end", "displacement"), ("snapshots/v", "velocity"), ("snapshots/theta", "temperature"),
                    ("snapshots/P", "chemical_potential"), ("snapshots/q", "heat_flux"),
                    ("snapshots/eta", "diffusion_flux"), ("series/contact_stress", "stress"),
                    ("snapshots/sigma", "stress"), ("series/energy", "energy"), ("series/energy_thermal", "energy")):
    at = mat[path].attrs
    check(at.get("si_factor") == mat.attrs["scale." + scale] and at.get("si_units") == scales[scale][1],
          f"mat.h5: /{path} si_factor {at.get('si_factor')} {at.get('si_units')}, expected scale.{scale}")
# The scales against the physics, not against their formulas: at the inner nodes of the last
# snapshot, the SI fields must satisfy the dimensional laws (2.2) and (2.9) in one dimension,
#   sigma = (lambda + 2 mu) u_x + (lambda' + 2 mu') v_x - beta1 (T - T0) - beta2 C,
#   P = -beta2 u_x + varrho C - nu (T - T0)   (C eliminated with the second),
# with u_x, v_x the averages of the two neighbouring elements' gradients (as /snapshots/sigma
# is placed on the nodes: docs/output.md). A wrong displacement, velocity, temperature,
# chemical-potential or stress factor breaks the balance.
def si(path):
    return mat[path][()] * mat[path].attrs["si_factor"]
a = {k: float(mat.attrs["material." + k]) for k in ("lambda", "mu", "lambda_v", "mu_v", "nu", "varrho")}
x, u, v, T, P, sig = si("mesh/x"), si("snapshots/u")[-1], si("snapshots/v")[-1], si("snapshots/theta")[-1], \
    si("snapshots/P")[-1], si("snapshots/sigma")[-1]
grad = lambda f: ((f[1:-1] - f[:-2]) / (x[1:-1] - x[:-2]) + (f[2:] - f[1:-1]) / (x[2:] - x[1:-1])) / 2
ux, vx, Ti, Pi = grad(u), grad(v), T[1:-1], P[1:-1]
C = (Pi + beta2 * ux + a["nu"] * Ti) / a["varrho"]
terms = [(a["lambda"] + 2 * a["mu"]) * ux, (a["lambda_v"] + 2 * a["mu_v"]) * vx, -beta1 * Ti, -beta2 * C]
law = sum(terms)
size = sum(abs(t) for t in terms).max()
check(size > 0 and abs(sig[1:-1] - law).max() <= 1e-8 * size,
      f"mat.h5: SI fields break (2.2)/(2.9): max |sigma - law| = {abs(sig[1:-1] - law).max():.3e} of {size:.3e}")
check(all(abs(t).max() > 1e-3 * size for t in terms[:3]),
      "mat.h5: the (2.2) check is not sensitive (the u_x, v_x or theta term negligible)")
check(mat["series/iterations"].attrs.get("si_factor") == 1.0, "mat.h5: /series/iterations (a count) has no si_factor 1")
print("\n".join("FAIL: " + b for b in bad) if bad else "PASS: provenance, logicals, descriptions and SI scales")
sys.exit(1 if bad else 0)
PY
