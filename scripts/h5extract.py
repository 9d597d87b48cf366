"""Extract the data of the paper's Figures 2-7 from rodcontact HDF5 files into
whitespace-separated text files that gnuplot reads (scripts/gnuplot/fig*.gp).

    <python with h5py> scripts/h5extract.py OUT_DIR DATA_DIR

OUT_DIR holds exp1.h5, exp1_varpi05.h5, exp1_varpi1.h5, exp2.h5, exp3.h5 (as written by
scripts/figures.sh). DATA_DIR receives

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
The script does not choose an interpreter (no shebang): run it with one that can import
h5py (scripts/find_python.sh). Exit status: 0 written, 1 a file is missing, incomplete
or unreadable, 2 usage.
"""

import math
import os
import sys

import h5py
import numpy as np

# curve colours, early to late: plotdata.py's hue ramp (nine times differ in hue, not only
# in lightness; the viridis ramp used before made t >= 0.5 hard to tell apart)
from plotdata import colours

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

def fmt_time(t):
    return ("%.2f" % t).rstrip("0").rstrip(".") if t != 0 else "0"


def open_run(out_dir, run):
    path = os.path.join(out_dir, run + ".h5")
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        raise RuntimeError(f"cannot open {path}: {exc} (run scripts/figures.sh to make it)")
    status = f.attrs.get("status", b"")
    status = status.decode() if isinstance(status, bytes) else str(status)
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


def write_columns(path, titles, columns):
    with open(path, "w", encoding="utf-8") as out:
        out.write(" ".join('"%s"' % s for s in titles) + "\n")
        np.savetxt(out, np.column_stack(columns), fmt="%.9g")


def contact_interval(t, pen):
    on = np.nonzero(pen > 0.0)[0]
    if on.size == 0:
        return float("nan"), float("nan")
    return float(t[on[0]]), float(t[on[-1]])


def main(argv):
    if len(argv) != 3 or argv[1] in ("-h", "--help"):
        sys.stderr.write(__doc__)
        return 2
    out_dir, data_dir = argv[1], argv[2]
    os.makedirs(data_dir, exist_ok=True)
    params = []

    def param(name, value):
        if isinstance(value, str):
            params.append('%s = "%s"' % (name, value))
        elif isinstance(value, float) and math.isnan(value):
            params.append("%s = NaN" % name)
        else:
            params.append("%s = %.10g" % (name, value))

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
                                      ["x"] + ["t = " + fmt_time(t) for t in times],
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
                parts = sorted(k for k in f["series"].keys()
                               if k.startswith("energy_") and f["series/" + k].shape == t.shape)
                write_columns(os.path.join(data_dir, f"{run}.series.dat"),
                              ["t", "E", "u(1,t)"] + [k[7:] for k in parts],
                              [t[keep], energy[keep], u_end[keep]] + [f["series/" + k][:][keep] for k in parts])
                if run == "exp1":     # Fig. 4 gets a panel with the parts when they exist
                    param("n_parts", len(parts))
                    param("part_names", " ".join(k[7:] for k in parts))
                on, off = contact_interval(t, pen)
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
