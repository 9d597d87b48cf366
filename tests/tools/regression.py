"""Regression references (tests/test_regression.sh): make a compact copy of a run file, or
compare a run file with its reference.

    regression.py store RUN.h5 REF.h5      # /mesh, /series, /snapshots and the status, gzip
    regression.py compare RUN.h5 REF.h5    # exit 1 (with what differs) beyond the tolerances
    regression.py same A.h5 B.h5           # exit 1 unless /series and /snapshots are equal bit
                                           # for bit, with the same run counters (restarts)

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
GROUPS = ("mesh", "series", "snapshots")


def store(run, ref):
    with rodrun.open_run(run, checked=False) as src, h5py.File(ref, "w") as dst:
        for group in GROUPS:
            for name, dset in src[group].items():
                if isinstance(dset, h5py.Dataset):
                    dst.create_dataset(f"{group}/{name}", data=dset[()], compression="gzip", compression_opts=9)
        dst.attrs["status"] = src.attrs["status"]


def compare(run, ref):
    problems = []
    with rodrun.open_run(run, checked=False) as got, rodrun.open_run(ref, checked=False) as want:
        if rodrun.status(got) != rodrun.status(want):
            problems.append(f"status {rodrun.status(got)!r}, reference {rodrun.status(want)!r}")
        for group in GROUPS:
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


SAME_ATTRIBUTES = ("status", "steps", "energy_max_relative_rise", "solver.linear_solves", "solver.contact_steps")


def same(first, second):
    """Bit-for-bit equality of two runs (a restarted and an uninterrupted one): the same
    /series and /snapshots datasets (with /snapshots/native of an adaptive mesh) with the
    same bytes, and the same run counters."""
    bad = []
    with rodrun.open_run(first, checked=False) as a, rodrun.open_run(second, checked=False) as b:
        groups = ["series", "snapshots"] + (["snapshots/native"] if "snapshots/native" in a or "snapshots/native" in b else [])
        for g in groups:
            if g not in a or g not in b:
                bad.append(f"/{g}: only in one file")
                continue
            if set(a[g]) != set(b[g]):
                bad.append(f"/{g}: datasets {sorted(a[g])} vs {sorted(b[g])}")
            for k in a[g]:
                if k not in b[g] or not isinstance(a[g][k], h5py.Dataset):
                    continue
                x, y = a[g][k][()], b[g][k][()]
                if x.shape != y.shape or x.tobytes() != y.tobytes():
                    diff = float(np.max(np.abs(x - y))) if x.shape == y.shape else "n/a"
                    bad.append(f"/{g}/{k}: shapes {x.shape} vs {y.shape}, max diff {diff}")
        for k in SAME_ATTRIBUTES:
            va, vb = rodrun.value(a.attrs[k]), rodrun.value(b.attrs[k])
            if va != vb:
                bad.append(f"attribute {k}: {va} vs {vb}")
    print("\n".join(bad) if bad else "identical")
    return 1 if bad else 0


def main(argv):
    if len(argv) != 4 or argv[1] not in ("store", "compare", "same"):
        sys.exit(__doc__)
    try:
        if argv[1] == "store":
            store(argv[2], argv[3])
            return 0
        return (same if argv[1] == "same" else compare)(argv[2], argv[3])
    except rodrun.RunFileError as exc:
        sys.stderr.write(f"regression.py: {exc}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
