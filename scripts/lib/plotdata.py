"""Extract what scripts/plot.sh (and the surface forms of scripts/paper/figures.sh) draw from ONE
rodcontact HDF5 file into text files for gnuplot (scripts/gnuplot/run_*.gp).

    <python with h5py> scripts/lib/plotdata.py RUN.h5 DATA_DIR [--fields u,P,theta] [--t-max T]
                                           [--times t1,t2,...] [--units auto|si|nondimensional]

DATA_DIR receives
    surf.<field>.dat   the field over (x, t), sampled to at most 61 x 61 points (every k-th
                       node and snapshot; t <= T), as gnuplot grid blocks: x t value; when the
                       state at t = 0 is off the scale of the later ones (see off_scale: the
                       pulses of experiments 2 and 3, the initial stress of a hot rod) the
                       surface starts at the first t > 0 (params.gp says so) so that the later
                       values are not flattened
    prof.<field>.dat   x and one column per profile time (at most 9, evenly spaced over
                       [0, T], or --times); first line: column titles. When t = 0 is off the
                       scale of the later profiles, params.gp says clip0_<field> = 1: it is drawn without setting
                       the y range (clipped at the frame), and the panel says so
    series.dat         t, E, u(1,t), penetration, contact stress, then the parts of the
                       energy when the file has them (/series/energy_<part>), thinned to
                       at most 4000 rows
    params.gp          gnuplot assignments: fields, labels, times, colours, status, g, the
                       contact intervals, ...

Units: with --units si (the default 'auto' when the run's input was in SI, rodrun.in_si: runs
with &material) every value is in SI units (the si_factor of its dataset); a dataset without
si_factor stays nondimensional and its label says so. --units nondimensional (the default
otherwise): the file's values, labelled '(nondimensional)'; --units paper: the file's values,
no units in the labels (the paper's figures, in its variables). Each quantity is drawn in a
power of ten of its unit chosen so that the tick labels have at most five characters
(power_of_ten): a 1 cm rod in mm, a temperature of 2e6 K as 2 in '[10^{6} K]', nondimensional
values as '(×10^{-3}, nondimensional)'; the data files hold the values so divided, and the
labels in params.gp name the power. Times given with --t-max and --times are in the units drawn
without that power (seconds for SI, the file's time otherwise).

A file still being written (a running or killed run's .h5.part, status 'incomplete') is read as
far as its datasets go: n_snap and n_series in params.gp say how many snapshots and series rows
it holds (scripts/plot.sh draws no surface from fewer than two snapshots, no series from fewer
than two rows).

Default fields: u P theta q eta, then sigma when /snapshots/sigma exists. Any file that
rodcontact wrote works, also a failed run (status 'failed: ...': everything up to the last
good step is there). Exit status: 0 written; 2 usage, or not a rodcontact output file
(with a message saying what is missing).
"""

import argparse
import math
import os
import sys

import numpy as np

import rodrun
from textfiles import fmt_time, gnuplot_assignment, write_columns

SYMBOL = {"u": "u", "v": "v", "theta": "θ", "P": "P", "q": "q", "eta": "η", "sigma": "σ"}
ALL_FIELDS = ["u", "v", "theta", "P", "q", "eta", "sigma"]
MAX_SAMPLES = 121        # profiles: nodes kept (every k-th)
SURF_SAMPLES = 61        # surfaces: nodes and snapshots kept, so that the mesh stays readable
OFF_SCALE = 0.5          # t = 0 is off the scale when t > 0 spans less than this part of the range
MAX_SERIES_ROWS = 4000
MAX_INTERVALS = 200      # contact intervals shaded (more are joined: a chattering contact)
PREFIXES = {-9: "n", -6: "µ", -3: "m", 3: "k", 6: "M", 9: "G", 12: "T"}
PREFIXED_UNITS = ("m", "s", "Pa")   # SI prefixes on these; other units get a power of ten
# Profile colours, early to late: dark blue, blue, cyan, green, gold, orange, red, dark red
# (a 'turbo'-like ramp without its pale middle): neighbouring times differ in hue, not
# only in lightness, so nine curves stay apart on white.
RAMP = ["#30123b", "#4145ab", "#2d9bd6", "#1bbc8f", "#67b51e", "#d9a800", "#f36a00", "#d0190f", "#7a0403"]


def colour(frac, ramp=RAMP):
    pos = frac * (len(ramp) - 1)
    k = min(int(pos), len(ramp) - 2)
    w = pos - k
    a = [int(ramp[k][i:i + 2], 16) for i in (1, 3, 5)]
    b = [int(ramp[k + 1][i:i + 2], 16) for i in (1, 3, 5)]
    return "#" + "".join("%02x" % round((1 - w) * p + w * q) for p, q in zip(a, b))


def colours(n):
    return [colour(k / (n - 1) if n > 1 else 0.0) for k in range(n)]


def stride_for(n, m=MAX_SAMPLES):
    return max(1, math.ceil((n - 1) / (m - 1)))


def sample(n, m=MAX_SAMPLES):
    """Indices 0, k, 2k, ... and always the last one."""
    return np.unique(np.r_[np.arange(0, n, stride_for(n, m)), n - 1])


def power_of_ten(m):
    """The exponent (a multiple of 3) in which a quantity of largest magnitude m is drawn: 0
    when 0.1 <= m < 10^4, else the one that brings m into [1, 1000): tick labels of at most
    five characters ('1.5e+06' ran off the page beside the colour bars, '-0.035' into the
    next panel)."""
    if not (m > 0 and math.isfinite(m)) or 0.1 <= m < 1e4:
        return 0
    return 3 * math.floor(math.log10(m) / 3)


def nice_step(span, n, steps=(1, 2, 2.5, 5)):
    """A tick step of one of steps times a power of ten giving at most n intervals over span."""
    if not (span > 0 and math.isfinite(span)):
        return 1.0
    raw = span / n
    p = 10.0 ** math.floor(math.log10(raw))
    return min((s * p for s in steps + (10,) if s * p >= raw * 0.999), default=10 * p)


def off_scale(v0, later):
    """Whether the state at t = 0 (values v0) is off the scale of the later values: they
    span less than OFF_SCALE of the range that includes v0 (the pulse of experiment 2, the
    initial stress of a run that settles into contact: drawn with them, the later values lie
    flat along the axis)."""
    lo, hi = float(np.nanmin(later)), float(np.nanmax(later))
    full = max(hi, float(np.nanmax(v0))) - min(lo, float(np.nanmin(v0)))
    return full > 0 and hi - lo < OFF_SCALE * full


class Units:
    """The unit system drawn: 'si', 'nondimensional' or 'paper' (the file's values, no labels)."""

    def __init__(self, system):
        self.system = system

    def factor(self, d):
        """(factor, unit) of dataset d: the unit '' when nondimensional, None in SI when d
        has no SI scale."""
        if self.system != "si":
            return 1.0, ""
        if "si_factor" not in d.attrs:
            return 1.0, None
        return float(d.attrs["si_factor"]), rodrun.text(d.attrs.get("si_units", "?"))

    def drawn(self, unit, e):
        """(unit as drawn, long label suffix, short label suffix) for power of ten e. The
        short one leaves out '(nondimensional)', which the figure's title says once."""
        times = "×10^{%d}" % e if e else ""
        if unit is None:
            return "", " (%snondimensional: no SI scale in the file)" % (times + ", " if e else ""), \
                " (%s)" % times if e else ""
        if self.system == "si":
            if e and unit in PREFIXED_UNITS and e in PREFIXES:
                unit, e = PREFIXES[e] + unit, 0
            u = ("10^{%d} " % e if e else "") + unit
            return u, " [%s]" % u, " [%s]" % u
        if self.system == "paper":
            return times, " (%s)" % times if e else "", " (%s)" % times if e else ""
        return times, " (%snondimensional)" % (times + ", " if e else ""), " (%s)" % times if e else ""


def axis(units, params, keys, d, magnitude):
    """The factor of one quantity (dataset d, largest magnitude `magnitude` in the file's
    values) as drawn; its long label, short label and unit into params under keys."""
    f, unit = units.factor(d)
    e = power_of_ten(f * magnitude)
    drawn, long, short = units.drawn(unit, e)
    params.update(zip(keys, (long, short, drawn)))
    return f / 10.0 ** e


def contact_intervals(f, t, n):
    """[(on, off)] in the file's time: from /events when the file has them (written at the
    end of a run: onsets and releases located inside their steps), else from the first n
    series rows (penetration > 0, or a contact stress: with Signorini's law the penetration
    is always 0, its multiplier is the stress)."""
    te, kind = rodrun.events(f)
    out = []
    if te.size:
        on = None if kind[0] > 0 else float(t[0])
        for tk, k in zip(te, kind):
            if k > 0 and on is None:
                on = float(tk)
            elif k < 0 and on is not None:
                out.append((on, float(tk)))
                on = None
        if on is not None:
            out.append((on, float(t[n - 1])))
    else:
        touch = np.zeros(n, dtype=bool)
        for name in ("penetration", "contact_stress"):
            if "series/" + name in f:
                touch |= f["series/" + name][:n] != 0.0
        edges = np.flatnonzero(np.diff(np.r_[0, touch.astype(int), 0]))
        out = [(float(t[a]), float(t[b - 1])) for a, b in zip(edges[::2], edges[1::2])]
    while len(out) > MAX_INTERVALS:   # join the closest neighbours
        k = int(np.argmin([out[i + 1][0] - out[i][1] for i in range(len(out) - 1)]))
        out[k:k + 2] = [(out[k][0], out[k + 1][1])]
    return out


def choose_units(f, a):
    """The unit system drawn (Units), or an error message."""
    has_scales = "si_factor" in f["mesh/x"].attrs
    if a.units == "si" and not has_scales:
        return f"--si: {a.run} has no SI scales (only runs with &material have them)"
    if a.units != "auto":
        return Units(a.units)
    return Units("si" if rodrun.in_si(f) and has_scales else "nondimensional")


def choose_fields(f, a):
    """The fields drawn, or an error message."""
    snaps = f["snapshots"]
    if not a.fields:
        return [s for s in ["u", "P", "theta", "q", "eta", "sigma"] if s in snaps]
    fields = [s.strip() for s in a.fields.split(",") if s.strip()]
    bad = [s for s in fields if s not in ALL_FIELDS]
    if bad:
        return f"unknown field(s) {', '.join(bad)}; known: {', '.join(ALL_FIELDS)}"
    absent = [s for s in fields if s not in snaps]
    if absent:
        return f"{a.run} has no /snapshots/{absent[0]}" + \
            (" (not written by this version of rodcontact)" if absent[0] == "sigma" else "")
    return fields


def write_fields(f, a, units, fields, n_snap, params):
    """surf.*.dat, prof.*.dat and the snapshot part of params; an error message or None."""
    snaps = f["snapshots"]
    x = f["mesh/x"][:]
    ts = snaps["t"][:n_snap]
    ft0 = units.factor(snaps["t"])[0]
    t_max = a.t_max / ft0 if a.t_max is not None else float(ts[-1])
    in_range = np.nonzero(ts <= t_max * (1 + 1e-12))[0]
    if in_range.size == 0:
        return f"no snapshot at t <= {a.t_max:g} in {a.run}"
    t_max = float(ts[in_range[-1]])
    ft = axis(units, params, ("t_unit", "t_short", "t_plain"), snaps["t"], t_max)
    fx = axis(units, params, ("x_unit", "x_short", "x_plain"), f["mesh/x"], float(np.abs(x).max()))
    ix = sample(x.size, SURF_SAMPLES)
    if a.times:
        wanted = [float(s) / ft0 for s in a.times.split(",")]
        ip = sorted(set(rodrun.nearest(ts, t) for t in wanted if t <= t_max * (1 + 1e-12)))
    else:
        n = min(9, in_range.size)
        ip = sorted(set(int(in_range[int(round(i))]) for i in np.linspace(0, in_range.size - 1, n)))
    tp = [float(ts[k]) for k in ip]
    params.update(n_snap=int(in_range.size), n_prof=len(tp), t_max=ft * t_max, x_max=fx * float(x[-1]),
                  # surfaces: about four ticks of 1, 2 or 5 (the slanted axes ran 0.25 into 0.5)
                  t_step=nice_step(ft * t_max, 4, (1, 2, 5)), xs_step=nice_step(fx * float(x[-1]), 4, (1, 2, 5)),
                  x_step=nice_step(fx * float(x[-1]), 5),
                  prof_times=" ".join(fmt_time(ft * t, 3) for t in tp), prof_colours=" ".join(colours(len(tp))))
    for fld in fields:
        data = snaps[fld][:in_range[-1] + 1, :]
        first = in_range
        if in_range.size > 2 and ts[0] == 0.0 and off_scale(data[0], data[1:]):
            first = in_range[1:]
        v = data[first[0]:, :]
        lo, hi = float(np.nanmin(v)), float(np.nanmax(v))
        ff = axis(units, params, (f"unit_{fld}", f"short_{fld}", f"plain_{fld}"), snaps[fld], max(abs(lo), abs(hi)))
        it = first[sample(first.size, SURF_SAMPLES)]
        with open(os.path.join(a.data_dir, f"surf.{fld}.dat"), "w", encoding="utf-8") as out:
            for k, row in zip(it, data[it, :][:, ix]):
                np.savetxt(out, np.column_stack([fx * x[ix], np.full(ix.size, ft * ts[k]), ff * row]), fmt="%.7g")
                out.write("\n")
        write_columns(os.path.join(a.data_dir, f"prof.{fld}.dat"),
                      ["x"] + ["t = " + fmt_time(ft * t, 3) for t in tp], [fx * x] + [r for r in ff * data[ip, :]])
        # colour range; symmetric when the field changes sign
        lo, hi = ff * lo, ff * hi
        signed = lo < 0 < hi and min(-lo, hi) > 0.05 * max(-lo, hi)
        m = max(abs(lo), abs(hi)) or 1.0
        params[f"t_min_{fld}"] = ft * float(ts[first[0]])
        # the profiles: t = 0 against the later profiles drawn (a fast transient between
        # snapshots keeps the surface from t = 0 but leaves the profiles flat)
        params[f"clip0_{fld}"] = int(len(ip) > 2 and tp[0] == 0.0 and off_scale(data[ip[0]], data[ip[1:]]))
        params[f"cb_lo_{fld}"], params[f"cb_hi_{fld}"] = ((-m, m) if signed else (lo, hi if hi > lo else lo + 1))
        params[f"z_lo_{fld}"], params[f"z_hi_{fld}"] = (lo, hi if hi > lo else lo + 1)
        params[f"signed_{fld}"] = int(signed)
        # the y range of the profiles when they are all one value (a run's first snapshot, u = 0):
        # gnuplot would warn of an empty range
        flat = ff * data[ip[1:] if params[f"clip0_{fld}"] else ip, :]
        params[f"flat_{fld}"] = float(flat.min()) if flat.min() == flat.max() else math.nan
    return None


def write_series(f, a, units, n_snap, params):
    """series.dat and the series part of params (contact intervals, g, ...)."""
    ser = f["series"]
    names = [k for k in ("u_end", "penetration", "contact_stress") if k in ser]
    parts = [k for k in sorted(ser) if k.startswith("energy_")]
    # a file being written: its datasets may hold one row more or less than t
    n = min(ser[k].shape[0] for k in ["t", "energy"] + names + parts)
    t = ser["t"][:n]
    keep = np.unique(np.r_[np.arange(0, n, max(1, math.ceil(n / MAX_SERIES_ROWS))), n - 1])
    fts = axis(units, params, ("ts_unit", "ts_short", "ts_plain"), ser["t"], float(t[-1]) if n else 1.0)
    fe, e_unit = units.factor(ser["energy"])
    params["e_unit"], params["e_short"] = units.drawn(e_unit, 0)[1:]   # a log axis: no power of ten
    g = float(f.attrs["contact.g"]) if "contact.g" in f.attrs else math.nan
    u_end = ser["u_end"][:n] if "u_end" in ser else np.full(n, np.nan)
    # u(1, t) in the power of ten of the field u (the same quantity in the same unit)
    u_max = float(np.nanmax(np.abs(np.r_[u_end, 0.0 if math.isnan(g) else g, f["snapshots/u"][:n_snap].ravel()])))
    fu = axis(units, params, ("u_unit", "u_short", "u_plain"), ser["u_end"] if "u_end" in ser else ser["t"], u_max)
    cols, titles = [fts * t, fe * ser["energy"][:n]], ["t", "E"]
    for name in ("u_end", "penetration", "contact_stress"):
        if name not in ser:
            cols.append(np.full(n, np.nan))
        else:   # the penetration in u's units, the stress in its own (unused by the figures)
            cols.append((fu if name != "contact_stress" else units.factor(ser[name])[0]) * ser[name][:n])
        titles.append(name)
    for k in parts:   # the parts in the energy's units (their own si_factor when they have one)
        cols.append((units.factor(ser[k])[0] if "si_factor" in ser[k].attrs else fe) * ser[k][:n])
        titles.append(k[len("energy_"):])
    write_columns(os.path.join(a.data_dir, "series.dat"), titles, [c[keep] for c in cols])
    spans = contact_intervals(f, t, n) if n else []
    params.update(
        n_series=n, t_end_series=float(fts * t[-1]) if n else 0.0, g=fu * g,
        n_contact=len(spans), contact_on=" ".join("%.9g" % (fts * s[0]) for s in spans),
        contact_off=" ".join("%.9g" % (fts * s[1]) for s in spans),
        t_on=fts * spans[0][0] if spans else math.nan, t_off=fts * spans[-1][1] if spans else math.nan,
        u_end_min=float(np.nanmin(cols[2])) if n else 0.0, u_end_max=float(np.nanmax(cols[2])) if n else 1.0,
        e_positive=int(bool(np.any(cols[1] > 0))), n_parts=len(parts),
        part_names=" ".join(k[len("energy_"):].replace("_", "-") for k in parts),
        x_end="ℓ" if units.system == "si" else "1")


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run")
    p.add_argument("data_dir")
    p.add_argument("--fields", default=None, help="comma-separated: u,v,theta,P,q,eta,sigma")
    p.add_argument("--t-max", type=float, default=None, help="last time drawn (default: the run's last)")
    p.add_argument("--times", default=None, help="comma-separated profile times")
    p.add_argument("--units", choices=("auto", "si", "nondimensional", "paper"), default="auto")
    a = p.parse_args(argv[1:])
    try:
        f = rodrun.open_run(a.run)
    except rodrun.RunFileError as exc:
        sys.stderr.write(f"plotdata.py: {exc}\n")
        return 2
    with f:
        units, fields = choose_units(f, a), choose_fields(f, a)
        error = units if isinstance(units, str) else fields if isinstance(fields, str) else None
        if error is None:
            os.makedirs(a.data_dir, exist_ok=True)
            status = rodrun.status(f)
            # a file being written: as many snapshots as every field drawn holds
            n_snap = min(f["snapshots/" + k].shape[0] for k in ["t"] + fields)
            params = {
                "fields": " ".join(fields), "symbols": " ".join(SYMBOL[s] for s in fields),
                "n_fields": len(fields),
                "units_note": {"si": "SI units", "paper": ""}.get(units.system, "nondimensional variables (2.10)"),
                "status": status.replace('"', "'"), "failed": 0 if status == "complete" else 1,
                "run_name": os.path.basename(a.run).replace('"', "'"),
                "varpi": float(f.attrs["model.varpi"]),
            }
            error = write_fields(f, a, units, fields, n_snap, params)
        if error is None:
            write_series(f, a, units, n_snap, params)
    if error is not None:
        sys.stderr.write(f"plotdata.py: {error}\n")
        return 2
    with open(os.path.join(a.data_dir, "params.gp"), "w", encoding="utf-8") as out:
        out.write("# written by scripts/lib/plotdata.py from %s\n" % a.run)
        for k, v in params.items():
            out.write(gnuplot_assignment(k, v) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
