#!/usr/bin/env python3
"""Each term of the discrete energy E^n, computed here from a run's snapshot fields, against the
run's /series/energy_<part> at the snapshot times (tests/test_energy_parts.sh).

    energy_parts.py FILE.h5 [FILE.h5 ...]

E^n (Section 5, the discrete counterpart of (5.1)) on the run's P1 mesh /mesh/x, every integral of
a product of two P1 functions taken exactly, element by element (h/6 (2 a0 b0 + a0 b1 + a1 b0 + 2 a1 b1)):
  kinetic   rho/2 int v^2        strain    alpha/2 int u_x^2     thermal   c/2 int theta^2
  chemical  r/2 int P^2          coupling  d int P theta         heat_flux tau0/2 int q^2
  mass_flux tau hbar/2 int eta^2 contact   penalty: 1/(2 eps) [u(1) - g]_+^2, Signorini: 0
The coefficients are the file's model.* and contact.* attributes. Only runs with the consistent
mass on one fixed mesh are read (the velocity mass of &contact mass adds a term this does not
compute). Each part must agree to RTOL of the largest |E^n| of the run, and the stored energy
must be the sum of its parts; a part that is never above 1e-6 of E^n in any file is reported,
since it would be checked by nothing. Exit 1 on any disagreement.
"""
import sys

import h5py
import numpy as np

RTOL = 1e-10
PARTS = ["kinetic", "strain", "thermal", "chemical", "coupling", "heat_flux", "mass_flux", "contact"]


def mass_product(x, a, b):
    """int a b for P1 functions a, b with nodal values on the nodes x (exact)."""
    h = np.diff(x)
    return np.sum(h / 6.0 * (2 * a[:-1] * b[:-1] + a[:-1] * b[1:] + a[1:] * b[:-1] + 2 * a[1:] * b[1:]))


def parts_of(f, k):
    """The parts of E^n at snapshot k of the open file f, from its fields."""
    m = {name: float(f.attrs["model." + name]) for name in ("rho", "alpha", "c", "r", "d", "tau0", "tau", "hbar")}
    x = f["mesh/x"][:]
    u, v, th, p, q, eta = (f["snapshots/" + n][k, :] for n in ("u", "v", "theta", "P", "q", "eta"))
    ux = np.diff(u) / np.diff(x)
    law = f.attrs["contact.law"]
    law = law.decode() if isinstance(law, bytes) else str(law)
    if law == "penalty":
        gap = max(u[-1] - float(f.attrs["contact.g"]), 0.0)
        contact = 0.5 / float(f.attrs["contact.eps"]) * gap**2
    elif law == "signorini":
        contact = 0.0
    else:
        raise SystemExit(f"energy_parts.py: contact law '{law}' has no independent energy here")
    return {
        "kinetic": 0.5 * m["rho"] * mass_product(x, v, v),
        "strain": 0.5 * m["alpha"] * np.sum(ux**2 * np.diff(x)),
        "thermal": 0.5 * m["c"] * mass_product(x, th, th),
        "chemical": 0.5 * m["r"] * mass_product(x, p, p),
        "coupling": m["d"] * mass_product(x, p, th),
        "heat_flux": 0.5 * m["tau0"] * mass_product(x, q, q),
        "mass_flux": 0.5 * m["tau"] * m["hbar"] * mass_product(x, eta, eta),
        "contact": contact,
    }


def check_file(path, seen):
    failures = 0
    with h5py.File(path, "r") as f:
        mass = f.attrs["contact.mass"]
        mass = mass.decode() if isinstance(mass, bytes) else str(mass)
        if mass != "consistent" or "snapshots/native" in f:
            raise SystemExit(f"energy_parts.py: {path}: needs the consistent mass on a fixed mesh")
        ts, te = f["snapshots/t"][:], f["series/t"][:]
        energy = f["series/energy"][:]
        scale = np.max(np.abs(energy))
        for k, t in enumerate(ts):
            j = int(np.argmin(np.abs(te - t)))
            if abs(te[j] - t) > 1e-12 * max(1.0, abs(t)):
                raise SystemExit(f"energy_parts.py: {path}: no series entry at the snapshot t = {t}")
            mine = parts_of(f, k)
            stored = {name: float(f["series/energy_" + name][j]) for name in PARTS}
            for name in PARTS:
                seen[name] = max(seen[name], abs(mine[name]) / scale)
                if abs(mine[name] - stored[name]) > RTOL * scale:
                    failures += 1
                    print(f"{path}: t = {t:.6g}: energy_{name} {stored[name]:.15e}, from the fields "
                          f"{mine[name]:.15e} (tolerance {RTOL * scale:.3e})")
            total = sum(stored.values())
            if abs(total - energy[j]) > RTOL * scale:
                failures += 1
                print(f"{path}: t = {t:.6g}: energy {energy[j]:.15e}, sum of its parts {total:.15e}")
        print(f"{path}: {len(ts)} snapshots, largest |E| {scale:.6e}, {failures} disagreements")
    return failures


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    seen = {name: 0.0 for name in PARTS}
    failures = sum(check_file(path, seen) for path in sys.argv[1:])
    for name in PARTS:
        if seen[name] < 1e-6:
            failures += 1
            print(f"energy_{name} is never above 1e-6 of E^n in these runs: nothing checks it")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
