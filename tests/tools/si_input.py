#!/usr/bin/env python3
"""The hand conversion of an input between the two unit systems (docs/input.md), computed
here from the paper's formulas (2.10)-(2.11), independently of rodcontact's material_m.

    si_input.py INPUT.nml [name=value ...] > SI.nml
        INPUT.nml nondimensional; the same run in SI units: &model dropped, &material with
        units='SI' and the given Table 1 values (the others Table 1's), g, eps, the times and
        &initial multiplied by their scales (a table file T: its SI copy T.si)
    si_input.py INPUT.nml [name=value ...] --model > ND.nml
        INPUT.nml as it is, with &model the coefficients (2.11) of that material

The two outputs describe the same run (tests/test_units.sh). INPUT.nml: one assignment
`name = value[, value ...]` or `name(k) = value` at a time, groups `&name ... /`.
"""
import math
import re
import sys

TABLE1 = dict(T0=293.0, rho0=8954.0, cE=383.1, kappa=386.0, **{"lambda": 7.76e10}, mu=3.86e10, alpha_t=1.78e-5,
              alpha_c=1.98e-4, D=0.85e-8, nu=1.2e4, varrho=0.9e6, ell=1.0, tau0=0.0, tau=0.0, lambda_v=0.0, mu_v=0.0)


def scales(m):
    """The SI value of one nondimensional unit of each quantity, by (2.10); u* = u/(delta ell),
    and the code's sigma of (2.11) is a-check times that of (2.10)."""
    L = m["lambda"] + 2 * m["mu"]
    beta1 = (3 * m["lambda"] + 2 * m["mu"]) * m["alpha_t"]
    beta2 = (3 * m["lambda"] + 2 * m["mu"]) * m["alpha_c"]
    omega = m["rho0"] * m["cE"] * m["ell"] ** 2 / m["kappa"]
    delta = math.sqrt(L / (m["rho0"] * m["cE"] * m["T0"]))
    a = m["T0"] * beta1 ** 2 / (m["rho0"] * m["cE"] * L)
    s = dict(t=omega, x=m["ell"], u=m["ell"] * delta, v=m["ell"] * delta / omega, theta=L * delta / beta1,
             P=beta2 * delta, sigma=L * delta / a, q=m["rho0"] * m["cE"] * delta * m["ell"] * L / (omega * beta1),
             eta=m["D"] * beta2 * delta / m["ell"])
    a1, a2, a3 = L * m["nu"] / (beta1 * beta2), L * m["ell"] ** 2 / (m["D"] * beta2 ** 2 * omega), L * m["varrho"] / beta2 ** 2
    zeta = (m["lambda_v"] + 2 * m["mu_v"]) / (omega * L)
    model = dict(rho=a * m["rho0"] * m["ell"] ** 2 / (omega ** 2 * L), alpha=a * (1 - 1 / a3), varpi=zeta * a,
                 gamma1=a * (1 + a1 / a3), gamma2=a / a3, c=1 + a * a1 ** 2 / a3, d=a1 * a / a3, r=a / a3,
                 hbar=a / a2, tau0=m["tau0"] / omega, tau=m["tau"] / omega)
    return s, model


#: the scale of each input that has a unit: (group, name) -> the scale's key (steps: per element)
SCALED = {("contact", "g"): "u", ("time", "dt"): "t", ("time", "t_end"): "t", ("time", "dt_min"): "t",
          ("time", "dt_max"): "t", ("output", "snapshot_dt"): "t", ("output", "series_dt"): "t",
          ("initial", "u0_poly"): "u", ("initial", "u1_poly"): "v", ("initial", "theta0_poly"): "theta",
          ("initial", "p0_poly"): "P", ("initial", "q0_poly"): "q", ("initial", "eta0_poly"): "eta",
          ("initial", "theta0_step"): ("theta", "x"), ("initial", "p0_step"): ("P", "x")}


def parse(text):
    """[(group, [(lhs, [values as text])])] of a namelist text in the simple form above
    (comments after '!', quoted strings kept whole)."""
    groups, quote, comment, buf = [], "", False, ""
    for ch in text:
        if comment:
            comment = ch != "\n"
            if comment:
                continue
        elif quote:
            quote = "" if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch == "!":
            comment = True
            continue
        elif ch == "/" and buf.lstrip().startswith("&"):
            name, _, body = buf.strip()[1:].partition(" ")
            parts = re.split(r"\s*([A-Za-z_]\w*(?:\(\s*\d+\s*\))?)\s*=\s*", " " + body.replace("\n", " "))
            groups.append((name.lower().strip(), [(parts[k], [v for v in re.split(r"[\s,]+", parts[k + 1].strip()) if v])
                                                  for k in range(1, len(parts) - 1, 2)]))
            buf = ""
            continue
        buf += ch
    return groups


def table_si(path, s, key):
    """A copy of table file `path` in SI units (path.si): positions times ell, values times s[key]."""
    rows = [line.split("#")[0].replace(",", " ").split() for line in open(path)]
    with open(path + ".si", "w") as out:
        for row in (r for r in rows if r):
            out.write(f"{float(row[0]) * s['x']!r} {float(row[1]) * s[key]!r}\n")
    return f"'{path}.si'"


def write(groups, material, model=None, s=None):
    """The input text: &model `model` (nondimensional), or &material `material` and every
    value with a unit times its scale in s (SI)."""
    out = []
    if model is not None:
        out.append("&model " + " ".join(f"{k}={v!r}" for k, v in model.items()) + " /")
    else:
        out.append("&material units='SI' " + " ".join(f"{k}={v!r}" for k, v in material.items()) + " /")
    for group, assignments in groups:
        if group in ("model", "material"):
            continue
        items = []
        for lhs, values in assignments:
            name, _, sub = lhs.lower().partition("(")
            key = SCALED.get((group, name)) if s is not None else None
            if key is not None:
                first = int(sub.rstrip(")")) if sub else 1
                values = [repr(float(v.lower().replace("d", "e")) * s[key if isinstance(key, str) else key[first + k - 1]])
                          for k, v in enumerate(values)]
            if s is not None and group == "initial" and name.endswith("_file"):   # a table: a converted copy
                values = [table_si(values[0].strip("'\""), s, SCALED[("initial", name[:-5] + "_poly")])]
            if s is not None and (group, name) == ("contact", "eps"):   # (3.4): u - g = -eps sigma
                values = [repr(float(values[0].lower().replace("d", "e")) * s["u"] / s["sigma"])]
            items.append(f"{lhs} = {', '.join(values)}")
        out.append(f"&{group} " + "\n    ".join(items) + " /")
    return "\n".join(out) + "\n"


def main(argv):
    args = [a for a in argv[1:] if a != "--model"]
    if not args or args[0].startswith("-"):
        sys.exit(__doc__)
    given = dict(a.split("=", 1) for a in args[1:])
    material = dict(TABLE1)
    material.update({k: float(v) for k, v in given.items()})
    s, model = scales(material)
    groups = parse(open(args[0]).read())
    if "--model" in argv:
        sys.stdout.write(write(groups, material, model=model))
    else:
        sys.stdout.write(write(groups, {k: material[k] for k in TABLE1}, s=s))


if __name__ == "__main__":
    main(sys.argv)
