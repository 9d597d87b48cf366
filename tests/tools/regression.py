"""Regression references (tests/test_regression.sh): make a compact copy of a run file, or
compare a run file with its reference.

    regression.py store RUN.h5 REF.h5      # /mesh, /series, /snapshots, /events and the status, gzip
    regression.py compare RUN.h5 REF.h5    # exit 1 (with what differs) beyond the tolerances
    regression.py same A.h5 B.h5           # exit 1 unless every dataset and every attribute is
                                           # equal bit for bit, provenance aside (restarts)
    regression.py same A.h5 B.h5 --ignore ATTR[,ATTR...]   # the same, without those root attributes

Tolerances: every value within RTOL * (largest |value| of that dataset in the reference) of
the reference, integer datasets equal, same shapes, same status. RTOL = 1e-8: a Debug build
(-O0) rounds differently from Release, and the Signorini multiplier (a gap divided by
dt^2 z_s) amplifies that to ~2e-10 of its scale; a change of the scheme moves results far more
(a 1e-6 relative change of the penalty fails 7 cases). A change meant to alter
results regenerates the references (tests/test_regression.sh --update) and says why in the
commit.
"""
import os
import sys

import h5py
import numpy as np

_repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(_repo, 'scripts', 'lib'))
import rodrun  # noqa: E402

RTOL = 1e-8
GROUPS = ("mesh", "series", "snapshots", "events")


def store(run, ref):
    with rodrun.open_run(run, checked=False) as src, h5py.File(ref, "w") as dst:
        for group in GROUPS:
            for name, dset in src[group].items():
                if isinstance(dset, h5py.Dataset):
                    data = dset[()]
                    packed = {"compression": "gzip", "compression_opts": 9} if data.size else {}
                    dst.create_dataset(f"{group}/{name}", data=data, **packed)
        dst.attrs["status"] = src.attrs["status"]


def compare(run, ref):
    problems = []
    with rodrun.open_run(run, checked=False) as got, rodrun.open_run(ref, checked=False) as want:
        if rodrun.status(got) != rodrun.status(want):
            problems.append(f"status {rodrun.status(got)!r}, reference {rodrun.status(want)!r}")
        for group in GROUPS:
            if group not in want:
                problems.append(f"/{group} not in the reference (store it: test_regression.sh --update)")
                continue
            for name, dset in want[group].items():
                path = f"{group}/{name}"
                if path not in got:
                    problems.append(f"/{path} missing")
                    continue
                a, b = got[path][()], dset[()]
                if a.shape != b.shape:
                    problems.append(f"/{path}: shape {a.shape}, reference {b.shape}")
                    continue
                if np.issubdtype(b.dtype, np.integer):
                    if not np.array_equal(a, b):
                        problems.append(f"/{path}: integers differ at {int(np.sum(a != b))} places")
                    continue
                scale = float(np.max(np.abs(b))) if b.size else 0.0
                diff = float(np.max(np.abs(a - b))) if b.size else 0.0
                if not diff <= RTOL * max(scale, np.finfo(float).tiny):
                    problems.append(f"/{path}: max |got - reference| = {diff:.3e} > {RTOL:g} * {scale:.3e}")
    for p in problems:
        print(f"  {run}: {p}")
    return 1 if problems else 0


#: Attributes that say where, when and how a file was made, not what the run computed: the
#: clock, the machine and build, the command and input file, the output's name and layout
#: (compression changes the layout, never the values), and what a restart was started from.
PROVENANCE_ATTRIBUTES = ("wall_seconds", "created", "host", "command_line", "input.overrides", "input.source",
                         "compiler_version", "hdf5_version", "source_version", "version", "output.prefix",
                         "output.compression", "time.restart_from", "restart_step")


def _objects(f):
    """Every group and dataset of f by path (visititems stops at a callback that returns
    something, so this one returns None)."""
    found = {}

    def keep(name, obj):
        found[name] = obj

    f.visititems(keep)
    return found


def _equal(x, y):
    x, y = np.asarray(x), np.asarray(y)
    if x.dtype.kind in "SUO" or y.dtype.kind in "SUO":
        return x.shape == y.shape and x.tolist() == y.tolist()
    return x.shape == y.shape and x.dtype == y.dtype and x.tobytes() == y.tobytes()


#: The attributes of HDF5 dimension scales (H5DS) that hold object references: compared by
#: the names the references resolve to (their addresses may differ between equal files).
REFERENCE_ATTRIBUTES = ("DIMENSION_LIST", "REFERENCE_LIST")


def _resolved(obj, name):
    """Attribute `name` (one of REFERENCE_ATTRIBUTES) of obj with every object reference
    replaced by the path it points to."""
    value = obj.attrs[name]
    if name == "DIMENSION_LIST":
        return [[obj.file[ref].name for ref in refs] for refs in value]
    return [(obj.file[ref].name, int(dim)) for ref, dim in value]


def _attribute_problems(where, a, b, skip=()):
    bad = []
    for k in sorted((set(a.attrs) | set(b.attrs)) - set(skip)):
        if k not in a.attrs or k not in b.attrs:
            bad.append(f"{where}attribute {k}: only in {'the first' if k in a.attrs else 'the second'} file")
        elif k in REFERENCE_ATTRIBUTES:
            if _resolved(a, k) != _resolved(b, k):
                bad.append(f"{where}attribute {k}: {_resolved(a, k)} vs {_resolved(b, k)}")
        elif not _equal(a.attrs[k], b.attrs[k]):
            bad.append(f"{where}attribute {k}: {a.attrs[k]} vs {b.attrs[k]}")
    return bad


def same(first, second, ignore=()):
    """Bit-for-bit equality of two runs (a restarted and an uninterrupted one, or two
    compression levels): every group and dataset of either file present in both with the
    same shape, type and bytes (/series, /snapshots with /snapshots/native, /events, /mesh;
    not /checkpoint, the restart data of the run's last checkpoints, which depend on where
    the run started and on checkpoint_every), and every attribute of the files and their
    datasets equal, except
    PROVENANCE_ATTRIBUTES (so the run counters, the energy and time-error bookkeeping and
    the remeshes are compared); `ignore`: more root attributes left out (a known defect,
    named where it is used)."""
    bad = []
    with rodrun.open_run(first, checked=False) as a, rodrun.open_run(second, checked=False) as b:
        objects_a, objects_b = _objects(a), _objects(b)
        for objects in (objects_a, objects_b):
            for name in [n for n in objects if n == "checkpoint" or n.startswith("checkpoint/")]:
                del objects[name]
        for name in sorted(set(objects_a) | set(objects_b)):
            if name not in objects_a or name not in objects_b:
                bad.append(f"/{name}: only in {'the first' if name in objects_a else 'the second'} file")
                continue
            x, y = objects_a[name], objects_b[name]
            if isinstance(x, h5py.Dataset) != isinstance(y, h5py.Dataset):
                bad.append(f"/{name}: a dataset in one file, a group in the other")
                continue
            if isinstance(x, h5py.Dataset):
                u, v = x[()], y[()]
                if not _equal(u, v):
                    diff = float(np.max(np.abs(u - v))) if u.shape == v.shape and u.dtype.kind in "fiu" else "n/a"
                    bad.append(f"/{name}: shapes {u.shape} vs {v.shape}, max diff {diff}")
            bad += _attribute_problems(f"/{name}: ", x, y)
        bad += _attribute_problems("", a, b, PROVENANCE_ATTRIBUTES + tuple(ignore))
    print("\n".join(bad) if bad else "identical")
    return 1 if bad else 0


def main(argv):
    if len(argv) < 4 or argv[1] not in ("store", "compare", "same") or \
            (len(argv) > 4 and (argv[1] != "same" or argv[4] != "--ignore" or len(argv) != 6)):
        sys.exit(__doc__)
    try:
        if argv[1] == "store":
            store(argv[2], argv[3])
            return 0
        if argv[1] == "same":
            return same(argv[2], argv[3], argv[5].split(",") if len(argv) > 4 else ())
        return compare(argv[2], argv[3])
    except rodrun.RunFileError as exc:
        sys.stderr.write(f"regression.py: {exc}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
