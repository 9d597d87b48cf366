"""The analysis of scripts/converge.sh: read the run files of a refinement ladder, compute for
each quantity the observed order, the Richardson extrapolate and the GCI of the finest level
(converge_gci.py), write converge.csv, print the table, draw converge.png.

    <python with h5py> scripts/lib/converge.py DIR --refine space|time|both LEVEL0.h5 LEVEL1.h5 ...

The files are given coarsest first. Quantities (docs/verification.md, "Checking convergence
with scripts/converge.sh"):
  onset_<i>, release_<i>      the i-th contact onset / release time (/events); when the
                              levels have different numbers of events, onset_1 only
  max_u_end                   max over the series of u(1, t)
  max_penetration             max over the series of [u(1, t) - g]_+
  energy_end                  the energy at t_end
  error_<field>@<t>           the field at snapshot time t: ||f_fine - f|| and its band
Fields are compared on the coarsest level's grid /mesh/x (the coarse nodes are nodes of every
finer uniform mesh when the ratio is an integer; otherwise the finer levels are interpolated
there, linearly: the P1 solution).
Units: those of the run's input (rodrun.in_si): SI for a run with &material (times in s,
lengths in m, each field in its SI unit, the L2 norms of fields in that unit times m^(1/2)),
else the files' own nondimensional values ('1'); --nondimensional: those always. The column
'units' of converge.csv and the table name them.
An event in the first time step of every level gets the status first_step (converge_gci.py).
Exit status: 0 written; 2 usage or a file that cannot be read.
"""

import argparse
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import converge_gci  # noqa: E402
import rodrun  # noqa: E402

COLUMNS = ("quantity", "fine", "extrapolated", "observed_order", "gci_abs", "gci_rel", "status", "units")
SCHEME_ORDER = {"euler": 1, "bdf2": 2, "midpoint": 2}   # time_scheme_m's SCHEMES(:)%order
SPACE_ORDER = 2                                          # P1 elements, L2 norm


class Level:
    """One level of the ladder: its h, dt, series maxima, events and snapshots, in SI (si)
    or nondimensional; units: {quantity or field: its unit}."""

    def __init__(self, path, nondimensional=False):
        with rodrun.open_run(path) as f:
            st = rodrun.status(f)
            if st != "complete":
                raise rodrun.RunFileError(f"{path}: status '{st}', not 'complete'")
            self.si = rodrun.in_si(f) and not nondimensional
            self.units = {}

            def read(path, name):
                factor, self.units[name] = rodrun.units(f[path], self.si)
                return f[path][:] * factor
            self.attrs = rodrun.attributes(f)
            self.x = read("mesh/x", "x")
            self.u_end = read("series/u_end", "max_u_end")
            self.pen = read("series/penetration", "max_penetration")
            self.energy = read("series/energy", "energy_end")
            t = read("series/t", "t")
            self.t_events, self.kinds = rodrun.events(f)
            if "events/t" in f:
                self.t_events = read("events/t", "t")
            self.ts = read("snapshots/t", "t")
            self.fields = rodrun.snapshot_fields(f)
            self.snap = {n: read("snapshots/" + n, n) for n in self.fields}
        self.h = (self.x[-1] - self.x[0]) / int(self.attrs["mesh.n_elements"])
        self.dt = float(t[1] - t[0])          # fixed steps, a series entry at every step
        self.scheme = str(self.attrs.get("time.scheme", "euler")).strip().lower()

    def scalars(self):
        """{quantity: value} of the scalar quantities."""
        q = {}
        for name, kind in (("onset", 1), ("release", -1)):
            for i, t in enumerate(self.t_events[self.kinds == kind]):
                q[f"{name}_{i + 1}"] = float(t)
                self.units[f"{name}_{i + 1}"] = self.units["t"]
        q["max_u_end"] = float(np.max(self.u_end))
        q["max_penetration"] = float(np.max(self.pen))
        q["energy_end"] = float(self.energy[-1])
        return q

    def snapshot_on(self, field, k, x):
        """Snapshot k of field on the grid x (linear interpolation: exact at shared nodes)."""
        values = self.snap[field][k]
        if values.shape == x.shape and np.array_equal(self.x, x):
            return values
        return np.interp(x, self.x, values)


def formal_order(refine, scheme):
    """The formal order of the ladder: the scheme's in time, 2 in space, the smaller of the two
    when both are refined together (the one that dominates as the steps shrink: before that,
    observed orders between the two are seen, and flagged not_asymptotic)."""
    pt = SCHEME_ORDER.get(scheme)
    if pt is None:
        raise ValueError(f"unknown time scheme '{scheme}'")
    return {"time": pt, "space": SPACE_ORDER, "both": min(pt, SPACE_ORDER)}[refine]


def steps(levels, refine):
    """The refinement parameter of each level: h for space, dt for time, sqrt(h dt) for both
    (its ratio is R when both are refined by R, and stays > 1 when only one of them is)."""
    if refine == "space":
        return [lv.h for lv in levels]
    if refine == "time":
        return [lv.dt for lv in levels]
    return [math.sqrt(lv.h * lv.dt) for lv in levels]


def inconsistencies(levels, refine):
    """What makes the ladder other than the --refine it claims: a list of sentences (empty
    when consistent). Ratios are compared within 2 % (n_elements * R^k is rounded)."""
    out = []
    for k in range(1, len(levels)):
        a, b = levels[k - 1], levels[k]
        rh, rt = a.h / b.h, a.dt / b.dt
        if refine == "space" and abs(rt - 1) > 1e-9:
            out.append(f"level {k} has another dt ({b.dt:g}, level {k - 1}: {a.dt:g}) in a space ladder")
        if refine == "time" and abs(rh - 1) > 1e-9:
            out.append(f"level {k} has another mesh (h = {b.h:g}, level {k - 1}: {a.h:g}) in a time ladder")
        if refine == "both" and abs(rh / rt - 1) > 0.02:
            out.append(f"level {k} refines h by {rh:.4g} but dt by {rt:.4g}")
        if levels[k].scheme != levels[0].scheme:
            out.append(f"level {k} uses the scheme '{levels[k].scheme}', level 0 '{levels[0].scheme}'")
    return out


def match_time(ts, t):
    """Index of the snapshot of ts at time t, or None (tolerance 1e-9 of the time scale)."""
    k = rodrun.nearest(ts, t)
    return k if abs(ts[k] - t) <= 1e-9 * max(1.0, abs(t)) else None


def study(levels, refine, warn=print):
    """The rows of converge.csv (dicts with COLUMNS) and, for the figure, the per-level values
    of each scalar: (rows, series {quantity: [value per level]}, hs)."""
    hs = steps(levels, refine)
    for k in range(1, len(hs)):
        if not hs[k] < hs[k - 1] * (1 - 1e-9):
            raise ValueError(f"level {k} is not finer than level {k - 1} ({refine}: "
                             f"{hs[k]:g} against {hs[k - 1]:g}): nothing to extrapolate")
    p_formal = formal_order(refine, levels[-1].scheme)
    bad = inconsistencies(levels, refine)
    for sentence in bad:
        warn(f"converge: inconsistent ladder: {sentence}; no row is reported as asymptotic")
    scal = [lv.scalars() for lv in levels]
    counts = [len(lv.t_events) for lv in levels]
    if len(set(counts)) > 1:
        # the i-th event of one level is not the i-th of another (chattering contact, a
        # bounce resolved on one level only): only the first onset is the same event
        warn(f"converge: the levels have {', '.join(map(str, counts))} contact events: only the first "
             "onset is compared (the others are not the same events on every level; see /events)")
        for q in scal:
            for name in [n for n in q if n.startswith(("onset_", "release_")) and n != "onset_1"]:
                del q[name]
    names = list(scal[-1].keys())
    rows, values = [], {}
    units = levels[-1].units
    for name in names:
        if not all(name in q for q in scal):
            continue
        phis = [q[name] for q in scal]
        values[name] = phis
        row = converge_gci.scalar(phis, hs, p_formal, not bad)
        if name.startswith(("onset_", "release_")) and all(phi <= lv.dt * (1 + 1e-9) for phi, lv in zip(phis, levels)):
            row.update(extrapolated=math.nan, observed_order=math.nan, gci_abs=math.nan, gci_rel=math.nan,
                       status="first_step")     # the step's time, not the solution's: no band
        rows.append({"quantity": name, **row, "units": units[name]})
    coarse = levels[0]
    half = " m^(1/2)" if coarse.si else ""
    for k0, t in enumerate(coarse.ts):
        ks = [match_time(lv.ts, t) for lv in levels]
        if any(k is None for k in ks):
            continue
        for field in coarse.fields:
            fs = [lv.snapshot_on(field, k, coarse.x) for lv, k in zip(levels, ks)]
            row = converge_gci.field(fs, hs, coarse.x, p_formal, not bad)
            rows.append({"quantity": f"error_{field}@{t:.10g}", **row, "units": units[field] + half})
    return rows, values, hs, p_formal


def write_csv(path, rows):
    with open(path, "w", newline="") as out:
        w = csv.writer(out, lineterminator="\n")
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([r["quantity"]] + [f"{r[c]:.15g}" for c in COLUMNS[1:-2]] + [r["status"], r["units"]])


def print_table(rows, t_unit, out=sys.stdout):
    """The scalar rows, then per field the largest relative band over the snapshots; the
    quantities' units in the last column, t_unit: that of the snapshot times."""
    fmt = "{:<22} {:>14} {:>14} {:>7} {:>11} {:>9}  {:<14} {}"
    print(fmt.format("quantity", "fine", "extrapolated", "order", "gci_abs", "gci_rel", "status", "units"), file=out)
    scalars = [r for r in rows if not r["quantity"].startswith("error_")]
    worst = {}
    for r in rows:
        if r["quantity"].startswith("error_"):
            field = r["quantity"][6:].split("@")[0]
            g = r["gci_rel"]
            if field not in worst or not (worst[field]["gci_rel"] >= g):
                worst[field] = r
    for r in scalars + [worst[f] for f in worst]:
        print(fmt.format(r["quantity"], f"{r['fine']:.7g}", f"{r['extrapolated']:.7g}",
                         f"{r['observed_order']:.2f}", f"{r['gci_abs']:.3g}",
                         f"{100 * r['gci_rel']:.3g}%", r["status"], r["units"]), file=out)
    statuses = [r["status"] for r in rows]
    counts = ", ".join(f"{statuses.count(s)} {s}" for s in converge_gci.STATUSES if statuses.count(s))
    print(f"({len(rows)} rows: {counts}; the field rows above are each field's largest band "
          f"over the snapshots, error_<field>@<t> at t in [{t_unit}])", file=out)


def draw(path, rows, values, hs, refine, p_formal, t_unit):
    """converge.png: each scalar against h or dt with the band of the finest level and the
    extrapolate; one panel of the fields' relative bands against the snapshot time."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    byname = {r["quantity"]: r for r in rows}
    names = list(values)
    n = len(names) + 1
    ncol = min(3, n)
    nrow = (n + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.3 * nrow), squeeze=False)
    axes = axes.ravel()
    x_unit = {"s": {"space": "m", "time": "s", "both": "(m s)^(1/2)"}[refine]}.get(t_unit, t_unit)
    label = {"space": "h", "time": "dt", "both": "sqrt(h dt)"}[refine] + f" [{x_unit}]"
    for ax, name in zip(axes, names):
        r = byname[name]
        ax.semilogx(hs, values[name], "o-", color="C0", label="levels")
        if math.isfinite(r["gci_abs"]):
            ax.errorbar([hs[-1]], [r["fine"]], yerr=[r["gci_abs"]], fmt="none", ecolor="C3",
                        capsize=5, lw=2, label="GCI band")
        if math.isfinite(r["extrapolated"]):
            ax.axhline(r["extrapolated"], color="C2", ls="--", lw=1, label="extrapolate")
        p = r["observed_order"]
        order = f"p = {p:.2f}" if math.isfinite(p) else {"first_step": "the first step's time",
                                                        "unchanged": "no change"}.get(r["status"], "p undefined")
        ax.set_title(f"{name} [{r['units']}]: {r['status']}, {order}", fontsize=9)
        ax.set_xlabel(label)
        ax.ticklabel_format(axis="y", useOffset=False)
        ax.tick_params(labelsize=8)
    axes[0].legend(fontsize=7)
    ax = axes[len(names)]
    fields = {}
    for r in rows:
        if r["quantity"].startswith("error_"):
            field, t = r["quantity"][6:].split("@")
            fields.setdefault(field, ([], []))
            if r["gci_rel"] > 0 and math.isfinite(r["gci_rel"]):
                fields[field][0].append(float(t))
                fields[field][1].append(r["gci_rel"])
    for field, (t, g) in fields.items():
        if t:
            ax.semilogy(t, g, ".-", ms=3, lw=1, label=field)
    ax.set_xlabel(f"t [{t_unit}]")
    ax.set_title(f"fields: band on ||f_fine - f|| / ||f_fine|| (formal order {p_formal:g})", fontsize=9)
    ax.legend(fontsize=7, ncol=2)
    ax.tick_params(labelsize=8)
    for ax in axes[n:]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="converge.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--refine", choices=("space", "time", "both"), required=True)
    ap.add_argument("--no-figure", action="store_true")
    ap.add_argument("--nondimensional", action="store_true")
    ap.add_argument("files", nargs="+")
    a = ap.parse_args(argv)
    if len(a.files) < 2:
        ap.error("at least two levels")
    try:
        levels = [Level(p, a.nondimensional) for p in a.files]
        if len({lv.si for lv in levels}) > 1:
            raise ValueError("the levels are in different unit systems (SI and nondimensional): "
                             "give --nondimensional")
        rows, values, hs, p_formal = study(levels, a.refine, warn=lambda m: print(m, file=sys.stderr))
    except (rodrun.RunFileError, ValueError, KeyError) as exc:
        print(f"converge: error: {exc}", file=sys.stderr)
        return 2
    csv_path = os.path.join(a.dir, "converge.csv")
    write_csv(csv_path, rows)
    print_table(rows, levels[0].units["t"])
    print(f"converge: {csv_path}", file=sys.stderr)
    if not a.no_figure:
        png = os.path.join(a.dir, "converge.png")
        draw(png, rows, values, hs, a.refine, p_formal, levels[0].units["t"])
        print(f"converge: {png}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
