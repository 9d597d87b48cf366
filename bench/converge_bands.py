"""How well do the GCI bands of scripts/converge.sh bracket the true error? The comparison
behind docs/verification.md's table (bench/converge_bands.sh) and tests/test_converge.sh.

    <python with h5py, scipy> bench/converge_bands.py compare DIR [--truth RUN.h5] [--exact]
                              [--csv OUT.csv] [--case NAME] [--modes K]
        DIR is a converge.sh output directory (converge.csv, level_<k>/point_0000.h5). Each
        row of converge.csv gets its true error: |fine - truth| for a scalar, and for a field
        ||f_fine - f|| / ||f_fine|| on the coarsest level's grid (as converge.sh measures it),
        the truth from RUN.h5 (a much finer run of the same input) and/or from the exact
        solution of the contact-free problem (tests/tools/exact_linear.py; it takes over the
        field rows before the first contact). Prints one line per row and the summary; --csv writes the rows
        (case,quantity,status,band,true,inside,ratio).
    <python> bench/converge_bands.py report [A.csv ...] [--group NAME A.csv ...] ... [--md OUT.md]
        The table of docs/verification.md: per case, the rows compared, the share whose true
        error lies inside the band, the share with band <= 10 x true, the median band/true;
        a total line per --group (its cases together) and one over all cases.
Rows left out: the snapshot at t = 0 (every level starts from the same data) and rows whose
true error and band are both at round-off (1e-12 of the value).
Exit status: 0; 2 usage or unreadable files.
"""

import argparse
import csv
import glob
import math
import os
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "scripts", "lib"))
sys.path.insert(0, os.path.join(here, "..", "tests", "tools"))
import converge  # noqa: E402
import converge_gci  # noqa: E402
import rodrun  # noqa: E402

ROUNDOFF = 1e-12


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for c in converge.COLUMNS[1:-2]:     # the numbers: not status, units
            r[c] = float(r[c])
    return rows


def levels_of(directory):
    """The level files of a converge.sh directory, coarsest first."""
    files = glob.glob(os.path.join(directory, "level_*", "point_0000.h5"))
    files.sort(key=lambda p: int(os.path.basename(os.path.dirname(p))[6:]))
    return files


def exact_stress(attrs, x, fields):
    """sigma = alpha u_x + varpi v_x - gamma1 theta - gamma2 P of the exact fields on the
    fine grid x (derivatives by central differences there: far below the errors compared)."""
    m = {k: float(attrs["model." + k]) for k in ("alpha", "varpi", "gamma1", "gamma2")}
    return (m["alpha"] * np.gradient(fields["u"], x) + m["varpi"] * np.gradient(fields["v"], x)
            - m["gamma1"] * fields["theta"] - m["gamma2"] * fields["P"])


def truths(directory, truth=None, exact=False, modes=2**18):
    """{quantity: (true value or None, true error)} for the rows of DIR/converge.csv."""
    files = levels_of(directory)
    coarse, fine = converge.Level(files[0]), converge.Level(files[-1])
    out = {}
    ref = converge.Level(truth) if truth else None
    if ref is not None:
        for name, value in ref.scalars().items():
            out[name] = (value, None)
    ex = None
    t_contact = math.inf
    if exact:
        import exact_linear
        ex = exact_linear.ExactLinear.from_attrs(fine.attrs, modes)
        on = np.nonzero(fine.pen > 0)[0]
        with rodrun.open_run(files[-1]) as f:
            t_series = f["series/t"][:]
        t_contact = float(t_series[on[0]]) if on.size else math.inf
    for k, t in enumerate(coarse.ts):
        kf = converge.match_time(fine.ts, t)
        if kf is None or t <= 0:
            continue
        if ex is not None and t < t_contact:
            exact_fields = ex.fields(float(t))
        elif ref is not None:
            kr = converge.match_time(ref.ts, t)
            if kr is None:
                continue
            exact_fields = None
        else:
            continue
        for field in coarse.fields:
            f1 = fine.snapshot_on(field, kf, coarse.x)
            if exact_fields is not None:
                if field == "sigma" and "sigma" not in exact_fields:
                    exact_fields["sigma"] = exact_stress(fine.attrs, ex.x, exact_fields)
                f = np.interp(coarse.x, ex.x, exact_fields[field])
            else:
                f = ref.snapshot_on(field, kr, coarse.x)
            norm = converge_gci.l2(f1, coarse.x)
            err = converge_gci.l2(f1 - f, coarse.x) / norm if norm > 0 else math.nan
            out[f"error_{field}@{t:.10g}"] = (None, err)
    return out


def compare(directory, truth=None, exact=False, case="", modes=2**18):
    """Rows (case, quantity, status, band, true, inside, ratio) for every row of converge.csv
    with a truth."""
    known = truths(directory, truth, exact, modes)
    result = []
    for r in read_rows(os.path.join(directory, "converge.csv")):
        q = r["quantity"]
        if q not in known:
            continue
        value, err = known[q]
        if q.startswith("error_"):
            band, true = r["gci_rel"], err
            scale = 1.0
        else:
            band, true = r["gci_abs"], abs(r["fine"] - value)
            scale = max(abs(value), abs(r["fine"]))
        if not (true > ROUNDOFF * scale) and not (band > ROUNDOFF * scale):
            continue
        inside = bool(band >= true)            # a nan band (diverging) is not inside
        ratio = band / true if true > 0 else math.inf
        result.append({"case": case, "quantity": q, "status": r["status"], "band": band,
                       "true": true, "inside": inside, "ratio": ratio})
    return result


def summary(rows):
    """(n, share inside, share with band <= 10 true, median band/true) of rows."""
    n = len(rows)
    if n == 0:
        return 0, math.nan, math.nan, math.nan
    inside = sum(r["inside"] for r in rows) / n
    within = sum(r["inside"] and r["ratio"] <= 10 for r in rows) / n
    ratios = [r["ratio"] for r in rows if math.isfinite(r["ratio"])]
    return n, inside, within, float(np.median(ratios)) if ratios else math.nan


def main_compare(a):
    rows = compare(a.dir, a.truth, a.exact, a.case, a.modes)
    for r in rows:
        print(f"{r['quantity']:<24} {r['status']:<15} band {r['band']:.3e} true {r['true']:.3e} "
              f"{'inside' if r['inside'] else 'OUTSIDE'} ratio {r['ratio']:.2f}")
    n, inside, within, med = summary(rows)
    print(f"{a.dir}: {n} rows, {100 * inside:.0f} % inside the band, "
          f"{100 * within:.0f} % inside and band <= 10 x true, median band/true {med:.2f}")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=["case", "quantity", "status", "band", "true", "inside", "ratio"],
                               lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
    return 0


def main_report(a):
    lines = ["| case | rows | true error inside the band | inside and band ≤ 10 × true | median band / true | statuses |",
             "|---|---:|---:|---:|---:|---|"]
    everything = []
    groups = [(None, a.csvs)] + [(g[0], g[1:]) for g in a.group]
    totals = []
    for name, paths in groups:
        subset = main_report_cases(paths, lines)
        everything += subset
        if name is not None:
            totals.append(table_line(f"**{name}**", subset))
    lines += totals
    lines.append(table_line("**all**", everything))
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if a.md:
        with open(a.md, "w") as f:
            f.write(text)
    return 0


def main_report_cases(paths, lines):
    """Append the lines of the cases in paths (scalars and fields apart) to lines; return
    their rows."""
    everything = []
    for path in paths:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        for r in rows:
            r["inside"] = r["inside"] == "True"
            r["band"], r["true"], r["ratio"] = float(r["band"]), float(r["true"]), float(r["ratio"])
        everything += rows
        for label, subset in (("scalars", [r for r in rows if not r["quantity"].startswith("error_")]),
                              ("fields", [r for r in rows if r["quantity"].startswith("error_")])):
            if not subset:
                continue
            lines.append(table_line(f"{rows[0]['case']}: {label}", subset))
    return everything


def table_line(label, rows):
    n, inside, within, med = summary(rows)
    statuses = ", ".join(f"{sum(r['status'] == s for r in rows)} {s}" for s in converge_gci.STATUSES
                         if any(r["status"] == s for r in rows))
    return f"| {label} | {n} | {100 * inside:.0f} % | {100 * within:.0f} % | {med:.2f} | {statuses} |"


def main(argv):
    ap = argparse.ArgumentParser(prog="converge_bands.py", description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("compare")
    c.add_argument("dir")
    c.add_argument("--truth")
    c.add_argument("--exact", action="store_true")
    c.add_argument("--csv")
    c.add_argument("--case", default="")
    c.add_argument("--modes", type=int, default=2**18,
                   help="modes of the exact solution (default 2^18; smooth initial data need far fewer)")
    r = sub.add_parser("report")
    r.add_argument("csvs", nargs="*")
    r.add_argument("--group", nargs="+", action="append", default=[], metavar=("NAME", "CSV"),
                   help="a group of cases with its own total line")
    r.add_argument("--md")
    a = ap.parse_args(argv)
    if a.cmd == "compare" and not (a.truth or a.exact):
        ap.error("compare needs --truth RUN.h5, --exact, or both")
    try:
        return main_compare(a) if a.cmd == "compare" else main_report(a)
    except (rodrun.RunFileError, OSError, ValueError, KeyError) as exc:
        print(f"converge_bands: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
