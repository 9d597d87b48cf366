#!/usr/bin/env python3
"""Text export of rodcontact HDF5 files for gnuplot and other tools (any run file: complete,
failed, interrupted or still running), and the data of the paper's Figures 2-7.

    <python with h5py> scripts/h5extract.py series   RUN.h5 [--datasets t,energy,...] [--every K] [UNITS]
    <python with h5py> scripts/h5extract.py snapshot RUN.h5 --time T [--fields u,theta,...] [UNITS]
    <python with h5py> scripts/h5extract.py events   RUN.h5 [UNITS]
    <python with h5py> scripts/h5extract.py matrix   RUN.h5 --field F [--format columns|nonuniform]
                                                     [--t-max T] [UNITS]
    <python with h5py> scripts/h5extract.py figures  OUT_DIR DATA_DIR
    <python with h5py> scripts/h5extract.py OUT_DIR DATA_DIR          (the same as figures)

series    the /series datasets as columns (all, in the file's order with t first, or the
          chosen ones), one row per entry; --every K keeps every K-th row (and the last).
snapshot  the snapshot nearest to time T (in the output's units: seconds for a run with
          &material): x, then one column per field (all of /snapshots, or the chosen ones).
          The header and stderr say which time was taken.
events    the contact events (/events): t and kind (+1 onset, -1 release), one row each.
matrix    one field over (x, t), for gnuplot's splot. --format columns (default): lines
          'x t value', one block per snapshot, blocks separated by a blank line:
              splot 'theta.dat' using 1:2:3 with pm3d
          --format nonuniform: gnuplot's nonuniform matrix (first line: the number of nodes
          and x; then one line per snapshot: t and the values):
              splot 'theta.mat' nonuniform matrix using 1:2:3 with pm3d
          --t-max T keeps the snapshots at t <= T (in the output's units).
UNITS     the values in the units of the run's input, by default: SI for a run with
          &material (si_factor and si_units of each dataset), else nondimensional.
          --nondimensional: the file's own (nondimensional) values; --si: SI, refused for a
          file without SI scales.
-o FILE   write to FILE instead of standard output.

The text modes start with comment lines ('#': gnuplot and numpy.loadtxt skip them): the
file, its status, each column's long_name and one line naming every column with its units,
e.g. (a run without &material; with it: # t [s] energy [J/m^2] u_end [m])
    # t [1] energy [1] u_end [1]
('1': nondimensional; the long_name says which scale of docs/output.md it is measured in).

figures   OUT_DIR holds exp1.h5, exp1_varpi05.h5, exp1_varpi1.h5, exp2.h5, exp3.h5 (as
written by scripts/paper/figures.sh). DATA_DIR receives

    <run>.<set>.<field>.dat   x and one column per marked time: the profiles field(x, t_k)
                              ('set' is 'all' for experiment 1, 'early' and 'late' for
                              experiments 2 and 3); first line: column titles
    <run>.series.dat          t, energy E, u(1,t), then the parts of the energy when the
                              file has them (/series/energy_<part>; thinned to at most
                              4000 rows)
    params.gp                 gnuplot assignments: obstacle g, wave speeds (7.4), the
                              marked times and their colours, contact intervals, ...

Marked times that the run does not reach (shortened --quick runs) are left out; when
fewer than three remain, evenly spaced snapshots are used instead.

Run it directly (scripts/h5extract.py ...): when the python3 on PATH cannot import h5py, it
runs itself again with the Python of scripts/lib/find_python.sh (/usr/bin/python3 on Debian),
and when there is none it says which packages to install (python3-h5py, python3-numpy) and
exits 1. Exit status: 0 written; 1 (figures) a file is missing,
incomplete or unreadable; 2 usage: unknown mode or option, a missing or unreadable file,
a file that is not a rodcontact output file, an unknown dataset or field, a bad time
(message on stderr).
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'lib'))
import interpreter  # noqa: E402

interpreter.ensure_h5py(__file__)
import numpy as np  # noqa: E402

# curve colours, early to late: plotdata.py's hue ramp (nine times differ in hue, not only
# in lightness; the viridis ramp used before made t >= 0.5 hard to tell apart)
from plotdata import colours  # noqa: E402
import rodrun  # noqa: E402
from textfiles import fmt_time, gnuplot_assignment, write_columns  # noqa: E402

MODES = ("series", "snapshot", "events", "matrix", "figures")


class UsageError(Exception):
    """A usage error: message on stderr, exit status 2."""


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def open_any(path):
    """Open a rodcontact output file for reading, or raise UsageError saying why not."""
    try:
        return rodrun.open_run(path)
    except rodrun.RunFileError as exc:
        raise UsageError(str(exc))


def units_of(d, si):
    """Factor and units of dataset d: (1, its units) or, with si, (si_factor, si_units)."""
    try:
        return rodrun.units(d, si)
    except rodrun.RunFileError as exc:
        raise UsageError(f"--si: {exc}")


def in_si(f, a):
    """Whether the values go out in SI: --si, --nondimensional, else the run's input units."""
    if a.si and a.nondimensional:
        raise UsageError("--si and --nondimensional exclude each other")
    return a.si or (not a.nondimensional and rodrun.in_si(f))


def header(out, f, path, what, names, units, long_names):
    out.write(f"# rodcontact {what} of {path} (status: {rodrun.status(f)})\n")
    for k, (n, ln) in enumerate(zip(names, long_names), 1):
        out.write(f"#   column {k}: {n}: {ln}\n")
    out.write("# " + " ".join(f"{n} [{u}]" for n, u in zip(names, units)) + "\n")


def chosen(listing, available, kind, path):
    """The comma-separated names in listing (all available ones when None), checked."""
    if listing is None:
        return list(available)
    names = [s.strip() for s in listing.split(",") if s.strip()]
    if not names:
        raise UsageError(f"no {kind} given")
    bad = [n for n in names if n not in available]
    if bad:
        raise UsageError(f"{path} has no {kind} {', '.join(bad)}; it has: {', '.join(available)}")
    return names


def parse_time(text, what):
    try:
        t = float(text)
    except ValueError:
        raise UsageError(f"{what}: got '{text}'; must be a number")
    if not math.isfinite(t):
        raise UsageError(f"{what}: got '{text}'; must be a finite number")
    return t


def fmt_row(values):
    return " ".join("%.17g" % (v + 0.0) for v in values) + "\n"     # + 0.0: no '-0'


def write_series(f, path, a, out):
    series = f["series"]
    names = chosen(a.datasets, rodrun.series_names(f), "series dataset(s)", path)
    if a.every < 1:
        raise UsageError(f"--every: got {a.every}; must be an integer >= 1")
    n = series["t"].shape[0]
    keep = np.unique(np.r_[np.arange(0, n, a.every), n - 1]) if n > 0 else np.arange(0)
    cols, units, si = [], [], in_si(f, a)
    for k in names:
        factor, u = units_of(series[k], si)
        cols.append(series[k][:][keep] * factor if factor != 1.0 else series[k][:][keep])
        units.append(u)
    header(out, f, path, "series", names, units, [rodrun.describe(series[k], k, si) for k in names])
    for row in zip(*cols):
        out.write(fmt_row(row))


def write_snapshot(f, path, a, out):
    t_req = parse_time(a.time, "--time")
    si = in_si(f, a)
    ft, ut = units_of(f["snapshots/t"], si)
    ts = f["snapshots/t"][:] * ft             # --time is in the output's units
    if ts.size == 0:
        raise UsageError(f"{path} holds no snapshot")
    tol = 1e-9 * max(abs(ts[-1]), abs(t_req))
    if t_req < ts[0] - tol or t_req > ts[-1] + tol:
        raise UsageError(f"--time: got {t_req:g} [{ut}]; the snapshots of {path} are at "
                         f"{ts[0]:g} <= t <= {ts[-1]:g} [{ut}]")
    k = rodrun.nearest(ts, t_req)
    fields = chosen(a.fields, rodrun.snapshot_fields(f), "field(s)", path)
    x = f["mesh/x"]
    fx, ux = units_of(x, si)
    cols, units = [x[:] * fx], [ux]
    for name in fields:
        d = f["snapshots/" + name]
        factor, u = units_of(d, si)
        cols.append(d[k, :] * factor)
        units.append(u)
    note = f"snapshot {k} of {ts.size} at t = {ts[k]:.17g} [{ut}] (nearest to the requested t = {t_req:g} [{ut}])"
    sys.stderr.write(f"h5extract.py: {note}\n")
    header(out, f, path, note, ["x"] + fields, units,
           [rodrun.describe(x, "x", si)] + [rodrun.describe(f["snapshots/" + n], n, si) for n in fields])
    for row in zip(*cols):
        out.write(fmt_row(row))


def write_events(f, path, a, out):
    if "events/t" not in f:
        raise UsageError(f"{path} has no /events (a run still going, or of an older version)")
    si = in_si(f, a)
    ft, ut = units_of(f["events/t"], si)
    t, kind = rodrun.events(f)
    header(out, f, path, "contact events", ["t", "kind"], [ut, "1"],
           [rodrun.describe(f["events/t"], "t", si), "+1 onset, -1 release"])
    for row in zip(t * ft, kind):
        out.write(fmt_row(row))


def write_matrix(f, path, a, out):
    fields = rodrun.snapshot_fields(f)
    if a.field not in fields:
        raise UsageError(f"{path} has no field {a.field}; it has: {', '.join(fields)}")
    si = in_si(f, a)
    ft, ut = units_of(f["snapshots/t"], si)
    ts = f["snapshots/t"][:] * ft             # --t-max is in the output's units
    keep = np.arange(ts.size)
    if a.t_max is not None:
        t_max = parse_time(a.t_max, "--t-max")
        keep = np.nonzero(ts <= t_max * (1 + 1e-12) + 1e-300)[0]
        if keep.size == 0:
            raise UsageError(f"--t-max: got {t_max:g} [{ut}]; the first snapshot of {path} is at t = {ts[0]:g} [{ut}]")
    d, x = f["snapshots/" + a.field], f["mesh/x"]
    fv, uv = units_of(d, si)
    fx, ux = units_of(x, si)
    xs = x[:] * fx
    values = d[keep[0]:keep[-1] + 1, :] * fv
    times = ts[keep]
    names = ["x", "t", a.field]
    units = [ux, ut, uv]
    long_names = [rodrun.describe(x, "x", si), rodrun.describe(f["snapshots/t"], "t", si),
                  rodrun.describe(d, a.field, si)]
    if a.format == "columns":
        header(out, f, path, f"field {a.field} over (x, t): one block per snapshot "
               "(splot FILE using 1:2:3 with pm3d)", names, units, long_names)
        for j, t in enumerate(times):
            if j > 0:
                out.write("\n")
            for xv, v in zip(xs, values[j]):
                out.write(fmt_row((xv, t, v)))
    else:
        header(out, f, path, f"field {a.field} as a gnuplot nonuniform matrix: first line the number "
               "of nodes and x, then per snapshot t and the values "
               "(splot FILE nonuniform matrix using 1:2:3 with pm3d)", names, units, long_names)
        out.write(fmt_row([xs.size] + list(xs)))
        for j, t in enumerate(times):
            out.write(fmt_row([t] + list(values[j])))


def run_mode(argv):
    mode = argv[0]
    p = Parser(prog=f"h5extract.py {mode}", add_help=False)
    p.add_argument("run")
    p.add_argument("-o", "--output", default=None)
    p.add_argument("--si", action="store_true")
    p.add_argument("--nondimensional", action="store_true")
    if mode == "series":
        p.add_argument("--datasets", default=None)
        p.add_argument("--every", type=int, default=1)
    elif mode == "snapshot":
        p.add_argument("--time", required=True)
        p.add_argument("--fields", default=None)
    elif mode == "matrix":
        p.add_argument("--field", required=True)
        p.add_argument("--format", choices=("columns", "nonuniform"), default="columns")
        p.add_argument("--t-max", default=None)
    a = p.parse_args(argv[1:])
    with open_any(a.run) as f:
        target = open(a.output, "w", encoding="utf-8") if a.output else sys.stdout
        try:
            {"series": write_series, "snapshot": write_snapshot, "events": write_events,
             "matrix": write_matrix}[mode](f, a.run, a, target)
        finally:
            if a.output:
                target.close()
    return 0


def main(argv):
    args = argv[1:]
    if not args or args[0] in ("-h", "--help"):
        (sys.stdout if args else sys.stderr).write(__doc__)
        return 0 if args else 2
    try:
        if args[0] in ("series", "snapshot", "events", "matrix"):
            if any(x in ("-h", "--help") for x in args[1:]):
                sys.stdout.write(__doc__)
                return 0
            return run_mode(args)
        if args[0] == "figures":
            args = args[1:]
            if len(args) != 2:
                raise UsageError("figures needs OUT_DIR DATA_DIR")
        elif len(args) != 2 or not os.path.isdir(args[0]):
            # the older form OUT_DIR DATA_DIR (scripts/paper/figures.sh) starts with a directory
            raise UsageError(f"unknown mode '{args[0]}'; must be one of {', '.join(MODES)} "
                             "(or OUT_DIR DATA_DIR, a directory first, for the figures)")
        if not os.path.isdir(args[0]):
            raise UsageError(f"figures: OUT_DIR {args[0]} is not a directory")
        try:
            os.makedirs(args[1], exist_ok=True)
        except OSError as exc:
            raise UsageError(f"figures: cannot create DATA_DIR {args[1]}: {exc}")
        return figures_main(args[0], args[1])
    except UsageError as exc:
        sys.stderr.write(f"h5extract.py: {exc} (h5extract.py --help for the usage)\n")
        return 2
    except BrokenPipeError:
        return 0


# Marked times of the profile families (see docs/reproduction.md, "Figures").
TIMES = {
    "all": [0.0, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 3.0],
    "early": [0.0, 0.01, 0.02, 0.03, 0.04, 0.05],
    "late": [0.1, 0.2, 0.3, 0.5, 1.0, 1.5, 2.0],
}
PROFILE_SETS = {           # run -> (sets, fields)
    "exp1": (["all"], ["u", "theta", "P", "q", "eta"]),
    "exp2": (["early", "late"], ["u", "theta", "P", "q", "eta"]),
    "exp3": (["early", "late"], ["u", "theta", "P"]),
}
SERIES_RUNS = ["exp1", "exp1_varpi05", "exp1_varpi1", "exp2"]
MAX_SERIES_ROWS = 4000

def open_run(out_dir, run):
    path = os.path.join(out_dir, run + ".h5")
    try:
        f = rodrun.open_run(path, checked=False)
    except rodrun.RunFileError as exc:
        raise RuntimeError(f"{exc} (run scripts/paper/figures.sh to make it)")
    status = rodrun.status(f)
    if status != "complete":
        f.close()
        raise RuntimeError(f"{path}: status '{status}', not 'complete'")
    return f


def pick_times(t_snap, wanted):
    """Indices of the snapshots at the wanted times (those the run reaches)."""
    idx = []
    for t in wanted:
        k = int(np.argmin(np.abs(t_snap - t)))
        if abs(t_snap[k] - t) <= 1e-6 * max(1.0, t):
            idx.append(k)
    if len(idx) < 3:                     # a shortened run: evenly spaced snapshots
        n = min(6, len(t_snap))
        idx = sorted(set(int(round(i)) for i in np.linspace(0, len(t_snap) - 1, n)))
    return idx


def figures_main(out_dir, data_dir):
    """The figures mode: see the module docstring."""
    os.makedirs(data_dir, exist_ok=True)
    params = []

    def param(name, value):
        params.append(gnuplot_assignment(name, value))

    try:
        for run, (sets, fields) in PROFILE_SETS.items():
            with open_run(out_dir, run) as f:
                x = f["mesh/x"][:]
                t_snap = f["snapshots/t"][:]
                for s in sets:
                    idx = pick_times(t_snap, TIMES[s])
                    times = [float(t_snap[k]) for k in idx]
                    n = len(idx)
                    cols = colours(n)
                    param(f"n_{run}_{s}", n)
                    param(f"times_{run}_{s}", " ".join("%.10g" % t for t in times))
                    param(f"colours_{run}_{s}", " ".join(cols))
                    for fld in fields:
                        data = f["snapshots/" + fld][idx, :]
                        write_columns(os.path.join(data_dir, f"{run}.{s}.{fld}.dat"),
                                      ["x"] + ["t = " + fmt_time(t, 2) for t in times],
                                      [x] + [row for row in data])
                if run == "exp2":
                    a = f.attrs
                    param("v_theta", 1.0 / math.sqrt(a["model.tau0"] * a["model.c"]))     # (7.4)
                    param("v_P", math.sqrt(a["model.hbar"] / (a["model.r"] * a["model.tau"])))
                    param("pulse_end", float(a["initial.theta0_step"][1]))
        t_max = 0.0
        for run in SERIES_RUNS:
            with open_run(out_dir, run) as f:
                t = f["series/t"][:]
                energy = f["series/energy"][:]
                u_end = f["series/u_end"][:]
                pen = f["series/penetration"][:]
                stride = max(1, math.ceil(t.size / MAX_SERIES_ROWS))
                keep = np.r_[np.arange(0, t.size, stride), t.size - 1]
                keep = np.unique(keep)
                parts = rodrun.energy_parts(f)
                write_columns(os.path.join(data_dir, f"{run}.series.dat"),
                              ["t", "E", "u(1,t)"] + [k[7:] for k in parts],
                              [t[keep], energy[keep], u_end[keep]] + [f["series/" + k][:][keep] for k in parts])
                if run == "exp1":     # Fig. 4 gets a panel with the parts when they exist
                    param("n_parts", len(parts))
                    param("part_names", " ".join(k[7:] for k in parts))
                on, off = rodrun.contact_interval(t, pen)
                param(f"t_on_{run}", on)
                param(f"t_off_{run}", off)
                param(f"t_end_{run}", float(t[-1]))
                param(f"varpi_{run}", float(f.attrs["model.varpi"]))
                t_max = max(t_max, float(t[-1]))
                if run == "exp1":
                    param("g", float(f.attrs["contact.g"]))
        param("t_end_series", t_max)
    except (RuntimeError, KeyError, OSError) as exc:
        sys.stderr.write(f"h5extract.py: {exc}\n")
        return 1
    with open(os.path.join(data_dir, "params.gp"), "w", encoding="utf-8") as out:
        out.write("# written by scripts/h5extract.py from %s\n" % out_dir)
        out.write("\n".join(params) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
