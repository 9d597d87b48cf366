"""Extract what scripts/plot.sh (and the surface forms of scripts/paper/figures.sh) draw from ONE
rodcontact HDF5 file into text files for gnuplot (scripts/gnuplot/run_*.gp).

    <python with h5py> scripts/lib/plotdata.py RUN.h5 DATA_DIR [--fields u,P,theta] [--t-max T]
                                           [--times t1,t2,...] [--units auto|si|nondimensional]

DATA_DIR receives
    surf.<field>.dat   the field over (x, t), sampled to at most 61 x 61 points (every k-th
                       node and snapshot; t <= T), as gnuplot grid blocks: x t value; when
                       max|f| at t = 0 is more than 3 times max|f| at t > 0 (the pulses of
                       experiments 2 and 3), the surface starts at the first t > 0 (params.gp
                       says so) so that the later values are not flattened
    prof.<field>.dat   x and one column per profile time (at most 9, evenly spaced over
                       [0, T], or --times); first line: column titles
    series.dat         t, E, u(1,t), penetration, contact stress, then the parts of the
                       energy when the file has them (/series/energy_<part>), thinned to
                       at most 4000 rows
    params.gp          gnuplot assignments: fields, labels, times, colours, status, g, ...

Units: with --units si (the default 'auto' when the file has SI scales, i.e. a run with
&material) every value is written in SI units (the si_factor of its dataset) and params.gp
holds the units for the axis labels ('[m]', '[s]', ...); a dataset without si_factor stays
nondimensional and its label says so. --units nondimensional (the default without scales)
writes the file's values and labels the axes '(nondimensional)'; --units paper: the file's
values, no units in the labels (the paper's figures, in its variables). Times given with --t-max and
--times are in the file's own (nondimensional) time.

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
OFF_SCALE = 3.0          # t = 0 is left out of a surface when it is this much larger than t > 0
MAX_SERIES_ROWS = 4000
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
        snaps = f["snapshots"]
        if a.fields:
            fields = [s.strip() for s in a.fields.split(",") if s.strip()]
            bad = [s for s in fields if s not in ALL_FIELDS]
            if bad:
                sys.stderr.write(f"plotdata.py: unknown field(s) {', '.join(bad)}; known: {', '.join(ALL_FIELDS)}\n")
                return 2
            absent = [s for s in fields if s not in snaps]
            if absent:
                sys.stderr.write(f"plotdata.py: {a.run} has no /snapshots/{absent[0]}"
                                 f"{' (not written by this version of rodcontact)' if absent[0] == 'sigma' else ''}\n")
                return 2
        else:
            fields = [s for s in ["u", "P", "theta", "q", "eta", "sigma"] if s in snaps]
        os.makedirs(a.data_dir, exist_ok=True)
        has_scales = "si_factor" in f["mesh/x"].attrs
        if a.units == "si" and not has_scales:
            sys.stderr.write(f"plotdata.py: --si: {a.run} has no SI scales (only runs with &material have them)\n")
            return 2
        si = a.units == "si" or (a.units == "auto" and has_scales)

        def scale(d):
            """(factor, label suffix) of dataset d in the units chosen."""
            if a.units == "paper":
                return 1.0, ""
            if not si:
                return 1.0, " (nondimensional)"
            if "si_factor" not in d.attrs:
                return 1.0, " (nondimensional: no SI scale in the file)"
            return float(d.attrs["si_factor"]), " [%s]" % rodrun.text(d.attrs.get("si_units", "?"))

        fx, x_unit = scale(f["mesh/x"])
        ft, t_unit = scale(f["snapshots/t"])
        x = f["mesh/x"][:]
        ts = f["snapshots/t"][:]
        status = rodrun.status(f)
        t_max = a.t_max if a.t_max is not None else float(ts[-1])
        in_range = np.nonzero(ts <= t_max * (1 + 1e-12))[0]
        if in_range.size == 0:
            sys.stderr.write(f"plotdata.py: no snapshot at t <= {t_max:g} in {a.run}\n")
            return 2
        t_max = float(ts[in_range[-1]])
        ix = sample(x.size, SURF_SAMPLES)
        # profile times
        if a.times:
            wanted = [float(s) for s in a.times.split(",")]
            ip = sorted(set(int(np.argmin(np.abs(ts - t))) for t in wanted if t <= t_max * (1 + 1e-12)))
        else:
            n = min(9, in_range.size)
            ip = sorted(set(int(in_range[int(round(i))]) for i in np.linspace(0, in_range.size - 1, n)))
        tp = [float(ts[k]) for k in ip]
        t_min_of = {}
        unit_of = {}
        for fld in fields:
            data = snaps[fld]
            first = in_range
            if in_range.size > 2 and ts[in_range[0]] == 0.0:
                m0 = float(np.abs(data[in_range[0], :]).max())
                m1 = float(np.abs(data[in_range[1]:in_range[-1] + 1, :]).max())
                if m0 > OFF_SCALE * m1:
                    first = in_range[1:]
            it = first[sample(first.size, SURF_SAMPLES)]
            t_min_of[fld] = float(ts[first[0]])
            ff, unit_of[fld] = scale(data)
            # surface: blocks of constant t
            with open(os.path.join(a.data_dir, f"surf.{fld}.dat"), "w", encoding="utf-8") as out:
                rows = data[it, :][:, ix]
                for k, row in zip(it, rows):
                    np.savetxt(out, np.column_stack([fx * x[ix], np.full(ix.size, ft * ts[k]), ff * row]), fmt="%.7g")
                    out.write("\n")
            prof = ff * data[ip, :]
            write_columns(os.path.join(a.data_dir, f"prof.{fld}.dat"),
                          ["x"] + ["t = " + fmt_time(ft * t, 3) for t in tp], [fx * x] + [r for r in prof])
        # series
        ser = f["series"]
        t = ser["t"][:]
        keep = np.unique(np.r_[np.arange(0, t.size, max(1, math.ceil(t.size / MAX_SERIES_ROWS))), t.size - 1])
        fts, _ = scale(ser["t"])
        fe, e_unit = scale(ser["energy"])
        cols = [fts * t, fe * ser["energy"][:]]
        titles = ["t", "E"]
        fu, u_unit = 1.0, " (nondimensional)"
        for name in ("u_end", "penetration", "contact_stress"):
            if name in ser:
                factor, unit = scale(ser[name])
                if name == "u_end":
                    fu, u_unit = factor, unit
                cols.append(factor * ser[name][:])
            else:
                cols.append(np.full(t.size, np.nan))
            titles.append(name)
        parts = rodrun.energy_parts(f)
        for k in parts:
            # the parts in the energy's units (their own si_factor when they have one)
            factor = scale(ser[k])[0] if "si_factor" in ser[k].attrs or not si else fe
            cols.append(factor * ser[k][:])
            titles.append(k[len("energy_"):])
        write_columns(os.path.join(a.data_dir, "series.dat"), titles, [c[keep] for c in cols])
        t_on, t_off = rodrun.contact_interval(fts * t, rodrun.series(f, "penetration", np.zeros(t.size)))
        at = f.attrs
        params = {
            "fields": " ".join(fields),
            "symbols": " ".join(SYMBOL[s] for s in fields),
            "n_fields": len(fields),
            "n_prof": len(tp),
            "prof_times": " ".join(fmt_time(ft * t, 3) for t in tp),
            "prof_colours": " ".join(colours(len(tp))),
            "t_max": ft * t_max,
            "t_end_series": float(fts * t[-1]),
            "x_max": float(fx * x[-1]),
            "x_unit": x_unit,
            "t_unit": t_unit,
            "e_unit": e_unit,
            "u_unit": u_unit,
            "units_note": "SI units" if si else ("" if a.units == "paper" else "nondimensional variables (2.10)"),
            "status": status.replace('"', "'"),
            "failed": 0 if status == "complete" else 1,
            "run_name": os.path.basename(a.run).replace('"', "'"),
            "g": fu * float(at["contact.g"]) if "contact.g" in at else math.nan,
            "varpi": float(at["model.varpi"]),
            "t_on": t_on,
            "t_off": t_off,
            "u_end_min": float(np.nanmin(cols[2])) if t.size else 0.0,
            "u_end_max": float(np.nanmax(cols[2])) if t.size else 1.0,
            "e_positive": int(bool(np.any(cols[1] > 0))),
            "n_parts": len(parts),
            "part_names": " ".join(k[len("energy_"):] for k in parts),
        }
        for fld in fields:   # colour range of each surface; symmetric when the field changes sign
            i0 = int(np.nonzero(ts == t_min_of[fld])[0][0])
            v = snaps[fld][i0:in_range[-1] + 1, :]
            params[f"t_min_{fld}"] = ft * t_min_of[fld]
            params[f"unit_{fld}"] = unit_of[fld]
            v = scale(snaps[fld])[0] * v
            lo, hi = float(np.nanmin(v)), float(np.nanmax(v))
            signed = lo < 0 < hi and min(-lo, hi) > 0.05 * max(-lo, hi)
            m = max(abs(lo), abs(hi)) or 1.0
            params[f"cb_lo_{fld}"], params[f"cb_hi_{fld}"] = ((-m, m) if signed else (lo, hi if hi > lo else lo + 1))
            params[f"z_lo_{fld}"], params[f"z_hi_{fld}"] = (lo, hi if hi > lo else lo + 1)
            params[f"signed_{fld}"] = int(signed)
    with open(os.path.join(a.data_dir, "params.gp"), "w", encoding="utf-8") as out:
        out.write("# written by scripts/lib/plotdata.py from %s\n" % a.run)
        for k, v in params.items():
            out.write(gnuplot_assignment(k, v) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
