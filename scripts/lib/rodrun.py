"""Reading rodcontact run files (the HDF5 layout of docs/output.md): the one place where the
Python scripts open a run file, decode its attributes and take out its series, snapshots
(on the fixed grid /mesh/x and, for adaptive meshes, on each snapshot's own nodes under
/snapshots/native), contact events and SI scales.

    import rodrun
    with rodrun.open_run("out/exp1.h5") as f:            # RunFileError naming the file
        status = rodrun.status(f)                        # 'complete', 'failed: ...', ...
        a = rodrun.attributes(f)                         # {name: str, int, float or array}
        t, u_end = rodrun.series(f, "t"), rodrun.series(f, "u_end")
        x, fields = rodrun.native_snapshot(f, -1)        # own nodes (else /mesh/x)
    run = rodrun.Run("out/exp1.h5", complete=True)       # everything of a run, read once

From a shell script: `$PY scripts/lib/rodrun.py attr RUN.h5 NAME [DEFAULT]` prints one root
attribute (e.g. status, wall_seconds).

Scripts in other folders import it by putting the repository's scripts/lib first on
sys.path, relative to their own __file__. Needs h5py and numpy (scripts/lib/find_python.sh).
"""

import math
import os
import sys

import h5py
import numpy as np

REQUIRED = ("mesh/x", "snapshots/t", "series/t", "series/energy")
FIELDS = ("u", "v", "theta", "P", "q", "eta")        # the snapshot fields of every run


class RunFileError(OSError):
    """A file that cannot be read as a rodcontact run file; the message names the file."""


def value(v):
    """An attribute value as plain Python: bytes -> str, numpy scalars -> int, float, bool;
    arrays stay numpy arrays."""
    if isinstance(v, bytes):
        return v.decode("utf-8", errors="replace")
    if isinstance(v, np.generic) or (isinstance(v, np.ndarray) and v.ndim == 0):
        v = v.item()
        return v.decode("utf-8", errors="replace") if isinstance(v, bytes) else v
    return v


def text(v):
    """An attribute value as a string (bytes decoded)."""
    return str(value(v))


def check(f, path):
    """Raise RunFileError naming what makes the open HDF5 file f not a rodcontact run file."""
    missing = [p for p in REQUIRED if p not in f]
    if missing:
        raise RunFileError(f"{path} is not a rodcontact output file: no {', '.join('/' + m for m in missing)}")
    if "model.alpha" not in f.attrs or "status" not in f.attrs:
        raise RunFileError(f"{path} is not a rodcontact output file: no 'model.alpha'/'status' attributes on /")


def open_h5(path):
    """h5py.File(path, "r"); the .h5.part of a killed run is still marked as open by its
    writer (HDF5's SWMR mode, docs/output.md), which only a SWMR reader accepts: opened so."""
    try:
        return h5py.File(path, "r")
    except OSError as plain:
        try:
            return h5py.File(path, "r", swmr=True)
        except OSError:
            raise plain from None


def open_run(path, checked=True):
    """The HDF5 file at path, open for reading (use it in a `with`); RunFileError when it is
    missing, a directory, not HDF5, or (checked) not written by rodcontact."""
    if not os.path.exists(path):
        raise RunFileError(f"{path}: no such file")
    if os.path.isdir(path):
        raise RunFileError(f"{path} is a directory, not a rodcontact output file")
    try:
        f = open_h5(path)
    except OSError as exc:
        raise RunFileError(f"cannot open {path} as HDF5: {exc}") from exc
    if checked:
        try:
            check(f, path)
        except RunFileError:
            f.close()
            raise
    return f


def attr(f, name, default=None):
    """Root attribute name of f as plain Python (value()), default when it is absent."""
    return value(f.attrs[name]) if name in f.attrs else default


def attributes(f):
    """All root attributes of f, decoded (value())."""
    return {k: value(f.attrs[k]) for k in f.attrs.keys()}


def status(f):
    """The run's status: 'complete', 'incomplete', 'failed: ...' ('' when absent)."""
    return attr(f, "status", "")


def in_si(f):
    """Whether the run's input was in SI units (with &material), so that its tools show SI:
    the root attribute 'units' ('SI' or 'nondimensional'); a file without it (older
    versions): whether its datasets have si_factor."""
    u = attr(f, "units")
    if u is not None:
        return u == "SI"
    return "series/t" in f and "si_factor" in f["series/t"].attrs


def describe(d, default, si):
    """long_name of dataset d for a reader of its values in SI (si) or as stored: in SI,
    the '(nondimensional, scale: X)' it ends with says the scale applied instead."""
    name = long_name(d, default)
    return name.replace("(nondimensional, scale: ", "(SI: the stored value times scale.") if si else name


def units(d, si=False):
    """(factor, units) of dataset d: (1, its units), or with si (si_factor, si_units);
    RunFileError when d has no SI scale (runs without &material)."""
    if not si:
        return 1.0, text(d.attrs.get("units", "1"))
    if "si_factor" not in d.attrs:
        raise RunFileError(f"{d.name} has no si_factor (only runs with &material have SI units)")
    return float(d.attrs["si_factor"]), text(d.attrs["si_units"])


def long_name(d, default):
    """The long_name attribute of dataset d (default when absent)."""
    return text(d.attrs.get("long_name", default))


def series_names(f):
    """Names of the /series datasets, t first, the others in the file's order."""
    names = [k for k in f["series"] if isinstance(f["series"][k], h5py.Dataset)]
    return ["t"] + [k for k in names if k != "t"]


def series(f, name, default=None):
    """/series/<name> as an array; default when the file has none."""
    return f["series/" + name][:] if "series/" + name in f else default


def energy_parts(f):
    """Names of the parts of the energy in /series (energy_<part>), sorted."""
    n = f["series/t"].shape
    return sorted(k for k in f["series"].keys() if k.startswith("energy_") and f["series/" + k].shape == n)


def events(f):
    """The contact events (t, kind): kind +1 onset, -1 release; empty arrays when none."""
    if "events/t" not in f:
        return np.zeros(0), np.zeros(0, dtype=int)
    return f["events/t"][:], f["events/kind"][:]


def snapshot_fields(f):
    """Names of the /snapshots fields of f (2D, one row per snapshot, one column per node)."""
    n_snap, n_x = f["snapshots/t"].shape[0], f["mesh/x"].shape[0]
    return [k for k, d in f["snapshots"].items() if isinstance(d, h5py.Dataset) and d.shape == (n_snap, n_x)]


def nearest(times, t):
    """Index of the entry of times nearest to t."""
    return int(np.argmin(np.abs(times - t)))


def snapshot(f, k, names=FIELDS):
    """Snapshot k on the fixed grid: (x, {field: values})."""
    return f["mesh/x"][:], {n: f["snapshots/" + n][k, :] for n in names}


def has_native(f):
    """Whether f holds each snapshot on its own mesh (/snapshots/native: adaptive mesh)."""
    return "snapshots/native" in f


def native_snapshot(f, k, names=FIELDS):
    """Snapshot k on its own nodes: (x, {field: values}) from /snapshots/native (x[offset[k] :
    offset[k] + count[k]]); on /mesh/x when the file has no native snapshots."""
    if not has_native(f):
        return snapshot(f, k, names)
    g = f["snapshots/native"]
    k = k % g["offset"].shape[0]
    off, cnt = int(g["offset"][k]), int(g["count"][k])
    return g["x"][off:off + cnt], {n: g[n][off:off + cnt] for n in names}


def contact_interval(t, pen):
    """First and last series time with penetration > 0, (nan, nan) without contact."""
    on = np.nonzero(pen > 0.0)[0]
    if on.size == 0:
        return math.nan, math.nan
    return float(t[on[0]]), float(t[on[-1]])


class Run:
    """Everything of one run file that the paper's checks use, read once: decoded root
    attributes, the series t, energy, u_end, penetration, the snapshots of FIELDS on /mesh/x.
    complete: RunFileError unless the run's status is 'complete'."""

    def __init__(self, path, name=None, complete=False):
        self.path = path
        self.name = name or os.path.basename(path)[:-3]
        with open_run(path) as f:
            if complete and status(f) != "complete":
                raise RunFileError(f"{path}: status '{status(f)}', not 'complete'")
            self.attrs = attributes(f)
            self.x = f["mesh/x"][:]
            self.t = f["series/t"][:]
            self.energy = f["series/energy"][:]
            self.u_end = f["series/u_end"][:]
            self.pen = f["series/penetration"][:]
            self.ts = f["snapshots/t"][:]
            self.snap = {k: f["snapshots/" + k][:] for k in FIELDS}
        self.h = self.x[1] - self.x[0]
        self.t_end = float(self.t[-1])
        on = np.nonzero(self.pen > 0)[0]
        self.t_on = float(self.t[on[0]]) if on.size else math.inf               # first contact
        self.t_off = float(self.t[on[-1]]) if on.size and on[-1] < self.t.size - 1 else math.nan
        self.s = int(self.attrs["mesh.n_elements"])
        self.dt = float(self.attrs["time.dt"])

    def a(self, key):
        """Root attribute key as a float."""
        return float(self.attrs[key])

    def maxnorm(self, field):
        """max_x |field(x, t)| at every snapshot."""
        return np.abs(self.snap[field]).max(axis=1)

    def k_at(self, t, tol=1e-6):
        """Index of the snapshot at time t (within tol * max(1, t)), or None when there is none."""
        k = nearest(self.ts, t)
        return k if abs(self.ts[k] - t) <= tol * max(1.0, t) else None

    def at(self, t, tol=1e-6):
        """{field: values on /mesh/x} of the snapshot at time t (k_at), or None."""
        k = self.k_at(t, tol)
        return None if k is None else {n: self.snap[n][k] for n in FIELDS}

    def contact_intervals(self):
        """[(first, last)] series times of each stretch of steps with penetration > 0."""
        on = self.pen > 0.0
        out, k = [], 0
        while k < on.size:
            if on[k]:
                j = k
                while j + 1 < on.size and on[j + 1]:
                    j += 1
                out.append((float(self.t[k]), float(self.t[j])))
                k = j + 1
            else:
                k += 1
        return out


def main(argv):
    """rodrun.py attr RUN.h5 NAME [DEFAULT]: print one root attribute, decoded, for shell
    scripts (DEFAULT when it is absent). Exit 0; 1 no such attribute; 2 usage, unreadable file."""
    if len(argv) not in (4, 5) or argv[1] != "attr":
        sys.stderr.write("usage: rodrun.py attr RUN.h5 NAME [DEFAULT]\n")
        return 2
    try:
        with open_run(argv[2], checked=False) as f:
            v = attr(f, argv[3], argv[4] if len(argv) == 5 else None)
    except RunFileError as exc:
        sys.stderr.write(f"rodrun.py: {exc}\n")
        return 2
    if v is None:
        sys.stderr.write(f"rodrun.py: {argv[2]} has no root attribute {argv[3]}\n")
        return 1
    print(v)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
