"""Accuracy and cost of uniform, time-adaptive and space-time-adaptive runs of experiment 2
against the exact pre-contact solution (bench/adaptive_mesh.sh; issue 13).

Needs h5py, numpy, scipy (and matplotlib for `report`): run it with the interpreter of
scripts/lib/find_python.sh.

    PY adaptive_mesh.py points RAW SPEC
        every line of SPEC is one point, "LABEL SERIES T RUN.h5 [RUN.h5 ...]", the RUN.h5
        repeats of the same run (identical results, only the wall time differs). Appends one
        JSON line per point to RAW: the median wall time (root attribute wall_seconds), steps,
        the relative L2 errors of u, v, theta, P, q, eta at the last snapshot (t = T) against
        tests/tools/exact_linear.py (2^18 modes). A run with /snapshots/native (adaptive mesh) is
        measured as the P1 function on its own final mesh (/snapshots/native/x, offset,
        count); a run without it as the P1 function on /mesh/x. For native runs the error of
        the interpolated /snapshots/<field> on /mesh/x is recorded as well (err_grid).
    PY adaptive_mesh.py after RAW SPEC
        runs after contact, no exact solution: every line "LABEL GROUP ROLE T RUN.h5", ROLE
        'ref' (one per group: the tightest setting) or 'point'. Appends one JSON line per
        point: the relative L2 difference of u, theta, P, eta at t = T to its group's ref.
    PY adaptive_mesh.py report OUTDIR FIGURE
        reads OUTDIR/work_precision_mesh.{raw,after,meta}; writes the figure (matplotlib),
        OUTDIR/work_precision_mesh.md (the section "Adaptive mesh" of docs/performance.md)
        and OUTDIR/work_precision_mesh_targets.txt (rows of its Targets table).
    PY adaptive_mesh.py splice OUTDIR DOC
        puts that section and those rows into DOC (an existing docs/performance.md) in place
        of earlier versions: the section replaces the one headed '## Adaptive mesh' (or goes
        at the end), the rows replace the Targets rows that start with '| exp2 adaptive mesh'
        (or go after the table's last row). For a run of adaptive_mesh.sh on its own;
        scripts/bench.sh writes the whole page through bench/report.py instead.
"""

import json
import math
import os
import statistics
import sys

import numpy as np

_repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(_repo, 'tests', 'tools'))  # exact_linear
sys.path.insert(0, os.path.join(_repo, 'scripts', 'lib'))  # rodrun, textfiles
import exact_linear  # noqa: E402
import rodrun  # noqa: E402
import textfiles  # noqa: E402
from rodrun import attr  # noqa: E402

FIELDS = exact_linear.FIELDS
SHOWN = ["u", "theta", "P", "eta"]
SYM = {"u": "u", "v": "v", "theta": "θ", "P": "P", "q": "q", "eta": "η"}
N_MODES = 2**18
T1_ERROR, T1_RATIO = 1e-2, 5.0          # issue 13: P, eta within 1 % at >= 5x less than BDF2 s = 8000
T2_ERROR, T2_RATIO = 5e-3, 10.0         # P, eta within 0.5 % at <= 1/10 of BDF2 s = 32000
TARGET_PREFIX = "| exp2 adaptive mesh"


def read_final(path):
    """The last snapshot of a run: {x, fields, t, native, wall, steps, ...}."""
    with rodrun.open_run(path) as f:
        d = {"path": path, "status": attr(f, "status"), "wall": attr(f, "wall_seconds"),
             "steps": attr(f, "steps"), "rejected": attr(f, "time_steps_rejected"),
             "attrs": rodrun.attributes(f)}
        ts = f["snapshots/t"][:]
        k = ts.size - 1
        d["t"] = float(ts[k])
        d["x_grid"], d["grid"] = rodrun.snapshot(f, k, FIELDS)
        d["native"] = rodrun.has_native(f)
        d["x"], d["fields"] = rodrun.native_snapshot(f, k, FIELDS)
        if d["native"]:
            g = f["snapshots/native"]
            d["native_counts"] = [int(c) for c in g["count"][:]]
            d["native_checks"] = native_checks(g, ts)
        t_on = rodrun.contact_interval(rodrun.series(f, "t"), rodrun.series(f, "penetration"))[0]
        d["t_contact"] = None if math.isnan(t_on) else t_on
        for name in ("mesh.n_elements", "mesh.max_level", "mesh.error_tol", "time.error_tol", "time.dt"):
            d[name] = attr(f, name)
        d["dt_min_used"] = d["dt_max_used"] = None
        if "series/n_elements" in f:               # adaptive mesh: elements at every series entry
            ne = f["series/n_elements"][:]
            d["elements"] = {"first": int(ne[0]), "max": int(ne.max()), "mean": float(ne.mean()), "last": int(ne[-1])}
            for name in ("mesh.remeshes", "mesh.n_elements_max"):
                d[name] = attr(f, name)
        if "series/dt" in f:
            dt = f["series/dt"][1:]
            if dt.size and (dt > 0).any():
                d["dt_min_used"], d["dt_max_used"] = float(dt[dt > 0].min()), float(dt.max())
    return d


def native_checks(g, ts):
    """Consistency of /snapshots/native: offsets are the running sum of counts, every
    snapshot's x increases from 0 to 1. Returns a list of problems (empty: fine)."""
    problems = []
    off, cnt = g["offset"][:], g["count"][:]
    if off.size != ts.size or cnt.size != ts.size:
        problems.append("offset/count have %d/%d entries for %d snapshots" % (off.size, cnt.size, ts.size))
    expect = np.concatenate([[0], np.cumsum(cnt)[:-1]])
    if off.size == expect.size and not np.array_equal(off, expect):
        problems.append("offset is not the running sum of count")
    total = int(cnt.sum())
    for n in ["x"] + FIELDS:
        if n in g and g[n].shape[0] != total:
            problems.append("native/%s has %d values, sum(count) = %d" % (n, g[n].shape[0], total))
    x = g["x"][:]
    for k in range(min(off.size, cnt.size)):
        xs = x[int(off[k]):int(off[k]) + int(cnt[k])]
        if xs.size < 2 or xs[0] != 0.0 or xs[-1] != 1.0 or not np.all(np.diff(xs) > 0):
            problems.append("snapshot %d: x not increasing from 0 to 1" % k)
            break
    return problems


def rel_l2_between(xa, fa, xb, fb, n=2**18):
    """Relative L2 distance of P1 function a from P1 function b, both at n midpoints."""
    xm = (np.arange(n) + 0.5) / n
    a, b = np.interp(xm, xa, fa), np.interp(xm, xb, fb)
    nb = math.sqrt(np.mean(b * b))
    return math.sqrt(np.mean((a - b) ** 2)) / nb if nb > 0 else math.nan


def cmd_points(raw, spec):
    ex = exact_linear.Cache(N_MODES)
    for w in textfiles.spec_lines(spec):
        label, series, t_end, runs = w[0], w[1], float(w[2]), w[3:]
        d = read_final(runs[0])
        row = {"label": label, "series": series, "t_end": t_end, "status": d["status"]}
        if d["status"] != "complete" or abs(d["t"] - t_end) > 1e-9:
            row["failed"] = "status %r, last snapshot at t = %g" % (d["status"], d["t"])
        elif d["t_contact"] is not None and d["t_contact"] <= t_end:
            row["failed"] = "contact at t = %g, before t = %g: no exact solution" % (d["t_contact"], t_end)
        else:
            walls = [d["wall"]] + [read_final(p)["wall"] for p in runs[1:]]
            model, exact = ex.get(d["attrs"], d["t"])
            row.update({"wall": statistics.median(walls), "walls": walls, "runs": len(runs),
                        "steps": d["steps"], "rejected": d["rejected"], "native": d["native"],
                        "nodes": int(d["x"].size), "err": model.rel_l2(exact, d["x"], d["fields"]),
                        "s": d["mesh.n_elements"], "max_level": d["mesh.max_level"],
                        "mesh_tol": d["mesh.error_tol"], "time_tol": d["time.error_tol"], "dt": d["time.dt"],
                        "dt_min_used": d["dt_min_used"], "dt_max_used": d["dt_max_used"]})
            if d["native"]:
                row["err_grid"] = model.rel_l2(exact, d["x_grid"], d["grid"])
                row["grid_points"] = int(d["x_grid"].size)
                row["elements"] = d.get("elements")
                row["remeshes"] = d.get("mesh.remeshes")
                row["native_problems"] = d["native_checks"]
                h = np.diff(d["x"])
                row["h_min"], row["h_max"] = float(h.min()), float(h.max())
        with open(raw, "a") as f:
            f.write(json.dumps(row) + "\n")
        if "failed" in row:
            print("  %-34s FAILED: %s" % (label, row["failed"]), file=sys.stderr)
        else:
            print("  %-34s wall %8.3f s  steps %7d  nodes %6d  " % (label, row["wall"], row["steps"], row["nodes"])
                  + "  ".join("%s %.2e" % (k, row["err"][k]) for k in SHOWN), file=sys.stderr)


def cmd_after(raw, spec):
    groups = {}
    for w in textfiles.spec_lines(spec):
        groups.setdefault(w[1], []).append((w[0], w[2], float(w[3]), w[4]))
    for group, rows in groups.items():
        refs = [r for r in rows if r[1] == "ref"]
        if len(refs) != 1:
            sys.exit("mesh_accuracy: group %s has %d ref lines" % (group, len(refs)))
        ref = read_final(refs[0][3])
        ref_ok = ref["status"] == "complete" and abs(ref["t"] - refs[0][2]) <= 1e-9
        for label, role, t, path in rows:
            d = ref if role == "ref" else read_final(path)
            row = {"label": label, "group": group, "role": role, "t_end": t, "status": d["status"],
                   "wall": d["wall"], "steps": d["steps"], "nodes": int(d["x"].size), "native": d["native"],
                   "contact": d["t_contact"]}
            if d["status"] != "complete" or abs(d["t"] - t) > 1e-9:
                row["failed"] = "status %r, last snapshot at t = %g" % (d["status"], d["t"])
            elif not ref_ok:
                row["failed"] = "the group's ref run failed"
            else:
                row["diff"] = {k: rel_l2_between(d["x"], d["fields"][k], ref["x"], ref["fields"][k]) for k in SHOWN}
            with open(raw, "a") as f:
                f.write(json.dumps(row) + "\n")
            print("  after contact, %-30s %s" % (label, row.get("failed") or "  ".join(
                "%s %.2e" % (k, row["diff"][k]) for k in SHOWN)), file=sys.stderr)


# ------------------------------------------------------------------------------------ report
def pct(e):
    return textfiles.pct(e, 3)


def describe(r):
    """A short description of a point's setting."""
    s = r["series"]
    if s.startswith("uniform"):
        return "s = %d, dt = %g" % (r["s"], r["dt"])
    if s.startswith("tadapt"):
        return "s = %d, error_tol = %g" % (r["s"], r["time_tol"])
    return "s₀ = %d, max_level = %d, mesh tol = %g, time tol = %g" % (r["s"], r["max_level"], r["mesh_tol"],
                                                                       r["time_tol"])


SERIES_TITLES = [("uniform_euler", "uniform, Euler"), ("uniform_bdf2", "uniform, BDF2"),
                 ("tadapt_bdf2_s2000", "adaptive dt, BDF2, s = 2000"),
                 ("tadapt_bdf2_s8000", "adaptive dt, BDF2, s = 8000"),
                 ("tadapt_midpoint_s2000", "adaptive dt, midpoint, s = 2000"),
                 ("tadapt_midpoint_s8000", "adaptive dt, midpoint, s = 8000")]


def series_title(name):
    for key, title in SERIES_TITLES:
        if key == name:
            return title
    if name.startswith("mesh_"):        # mesh_<scheme>_s<n0>_L<level>
        parts = name.split("_")
        return "adaptive mesh + dt, %s, s₀ = %s, max_level %s" % (parts[1], parts[2][1:], parts[3][1:])
    return name


def worst_pe(r):
    return max(r["err"]["P"], r["err"]["eta"])


def cmd_report(outdir, figure):
    rows = [json.loads(l) for l in open(os.path.join(outdir, "work_precision_mesh.raw")) if l.strip()]
    after_path = os.path.join(outdir, "work_precision_mesh.after")
    after = [json.loads(l) for l in open(after_path) if l.strip()] if os.path.exists(after_path) else []
    meta = textfiles.read_meta(os.path.join(outdir, "work_precision_mesh.meta"))
    quick = meta.get("quick") == "1"
    main = [r for r in rows if not r["series"].startswith("pulse_") and "failed" not in r]
    failed = [r for r in rows if "failed" in r]
    series_names = []
    for r in main:
        if r["series"] not in series_names:
            series_names.append(r["series"])

    def find(series, s):
        return next((r for r in main if r["series"] == series and r["s"] == s), None)

    b8000, b32000 = find("uniform_bdf2", 8000), find("uniform_bdf2", 32000)
    mesh_rows = [r for r in main if r["series"].startswith("mesh_")]
    tadapt_rows = [r for r in main if r["series"].startswith("tadapt_")]

    # ------------------------------------------------------------------ figure
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    colours = {"uniform_euler": "#c0392b", "uniform_bdf2": "#1f5fa8", "tadapt_bdf2_s2000": "#16a085",
               "tadapt_bdf2_s8000": "#0b5345", "tadapt_midpoint_s2000": "#a569bd", "tadapt_midpoint_s8000": "#5b2c83"}
    mesh_palette = ["#e67e22", "#9a7d0a", "#6e2c00", "#f4d03f", "#ff66cc", "#17202a", "#a04000", "#7d3c98"]
    markers = {"uniform_euler": "s", "uniform_bdf2": "o", "tadapt_bdf2_s2000": "^", "tadapt_bdf2_s8000": "v",
               "tadapt_midpoint_s2000": "<", "tadapt_midpoint_s8000": ">"}
    mesh_series = [n for n in series_names if n.startswith("mesh_")]
    for ax, k in zip(axes.flat, SHOWN):
        for name in series_names:
            rs = sorted((r for r in main if r["series"] == name), key=lambda r: r["wall"])
            if name.startswith("mesh_"):
                c, m, ls = mesh_palette[mesh_series.index(name) % len(mesh_palette)], "D", "-"
            else:
                c, m = colours.get(name, "k"), markers.get(name, "x")
                ls = "-" if name.startswith("uniform") else "--"
            ax.plot([r["wall"] for r in rs], [100 * r["err"][k] for r in rs], ls, color=c, marker=m,
                    label=series_title(name), ms=5, lw=1.2)
        if k in ("P", "eta"):
            ax.axhline(100 * T1_ERROR, color="grey", lw=0.8, ls=":")
            ax.axhline(100 * T2_ERROR, color="grey", lw=0.8, ls=":")
            if b8000:
                ax.axvline(b8000["wall"] / T1_RATIO, color="#1f5fa8", lw=0.8, ls=":")
            if b32000:
                ax.axvline(b32000["wall"] / T2_RATIO, color="#1f5fa8", lw=0.8, ls="-.")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time [s] (wall_seconds)")
        ax.set_ylabel("relative L2 error of %s at t = %g [%%]" % (SYM[k], main[0]["t_end"] if main else 0.25))
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        ax.set_title(SYM[k])
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
    marks = ["dotted horizontal lines: 1 % and 0.5 %"]
    if b8000:
        marks.append("dotted vertical: BDF2 s = 8000 wall / %g" % T1_RATIO)
    if b32000:
        marks.append("dash-dot: BDF2 s = 32000 wall / %g" % T2_RATIO)
    fig.suptitle("Experiment 2 at t = 0.25 against the exact solution%s\nP and η panels: %s" % (
        " (QUICK MODE: a few cheap points)" if quick else "", "; ".join(marks)), fontsize=10)
    fig.tight_layout(rect=(0, 0.09, 1, 0.97))
    fig.savefig(figure, dpi=110)
    plt.close(fig)

    # ------------------------------------------------------------------ targets
    targets = []
    mesh_available = meta.get("mesh_adaptive") == "yes"

    def best_below(level, cands):
        ok = sorted((r for r in cands if worst_pe(r) <= level), key=lambda r: r["wall"])
        return ok[0] if ok else None

    t_info = []
    for (level, ratio, base, name) in ((T1_ERROR, T1_RATIO, b8000, "BDF2 s = 8000, dt = 6.25e-6"),
                                      (T2_ERROR, T2_RATIO, b32000, "BDF2 s = 32000, dt = 1.5625e-6")):
        head = "%s: P and η within %s of exact at t = 0.25, wall time <= 1/%g of uniform %s" % (
            TARGET_PREFIX[2:], pct(level), ratio, name)
        if base is None:
            targets.append("| %s | not measured (no uniform %s run%s) | – |" % (
                head, name, " in --quick mode" if quick else ""))
            t_info.append(None)
            continue
        if not mesh_available:
            targets.append("| %s | not measured: this build has no `mesh.adaptive` (%s) | – |" % (
                head, meta.get("mesh_adaptive_reason", "")))
            t_info.append(None)
            continue
        best = best_below(level, mesh_rows)
        if best is None:
            targets.append("| %s | no adaptive-mesh run reaches it (best P, η: %s) | **no** |" % (
                head, ", ".join("%s/%s" % (pct(r["err"]["P"]), pct(r["err"]["eta"]))
                                for r in sorted(mesh_rows, key=worst_pe)[:2]) or "none ran"))
            t_info.append(None)
            continue
        r = base["wall"] / best["wall"]
        targets.append("| %s | %.1fx (%s: %.3g s, P %s, η %s; uniform %.3g s, P %s, η %s) | %s |" % (
            head, r, describe(best), best["wall"], pct(best["err"]["P"]), pct(best["err"]["eta"]), base["wall"],
            pct(base["err"]["P"]), pct(base["err"]["eta"]), "yes" if r >= ratio else "**no**"))
        t_info.append((best, base, r))
    with open(os.path.join(outdir, "work_precision_mesh_targets.txt"), "w") as f:
        f.write("\n".join(targets) + "\n")

    # ------------------------------------------------------------------ the section
    md = []
    w = md.append
    w("## Adaptive mesh: work and precision on experiment 2 against the exact solution")
    w("")
    w("Command: `bench/adaptive_mesh.sh` (also run by `bench.sh`; helper `bench/adaptive_mesh.py`). "
      "![work-precision, adaptive mesh](../figures/work_precision_mesh.png)")
    w("")
    if quick:
        w("> **Quick mode (pipeline check): a handful of cheap points, one run each — the numbers mean little.**")
        w("")
    w("Experiment 2 (`input/exp2.nml`: pulses θ₀ = P₀ = 20 on [0, 0.1]) to t = %s, before the rod first touches "
      "the obstacle (t ≈ 0.30), where the model is linear and `tests/tools/exact_linear.py` gives the exact solution "
      "(%d modes; its own error at t = 0.25 is about 1e-4 relative in P and η and far below in the others: "
      "`exact_linear.py --self-check`). Every run:" % (meta.get("t_end", "0.25"), N_MODES))
    w("")
    w("    LD_LIBRARY_PATH=%s build/rodcontact input/exp2.nml --set time.t_end=%s \\"
      % (meta.get("ld_library_path", "?"), meta.get("t_end", "0.25")))
    w("        --set output.snapshot_every=100000000 --set output.quiet=.true. --set output.prefix=<tmp> \\")
    w("        --set mesh.n_elements=<s> --set time.scheme=<scheme> --set time.dt=<dt>            # uniform")
    w("        ... --set time.adaptive=.true. --set time.error_tol=<tol>                    # adaptive dt")
    w("        ... --set mesh.adaptive=.true. --set mesh.error_tol=<r> --set mesh.max_level=<L>   # adaptive mesh")
    w("")
    w("Error: relative L2 error ‖f_h − f‖/‖f‖ over (0, 1) at the last snapshot (t = t_end, the last step's), "
      "f_h the P1 function of the nodal values: on `/mesh/x` for uniform runs, on the run's own final mesh "
      "(`/snapshots/native/x`, `offset`, `count`) for adaptive-mesh runs. Wall time: the root attribute "
      "`wall_seconds` (whole run, set-up and output included), median of %s run(s) (round robin over all such runs) "
      "for runs under %s s, one run for the longer ones (the *runs* column). Load average %s at the start, %s at "
      "the end (2 shared cores). BLAS/LAPACK loaded (ldd under that LD_LIBRARY_PATH): %s. Raw data: "
      "`%s/work_precision_mesh.raw` (JSON lines); this section took %s s." % (
          meta.get("repeats", "?"), meta.get("repeat_below", "?"), meta.get("load_start", "?"),
          meta.get("load_end", "?"), meta.get("blas", "?"), meta.get("outdir_rel", "out/bench"),
          meta.get("seconds", "?")))
    w("")
    if not mesh_available:
        w("**The adaptive mesh (`&mesh adaptive`) is not in the build this section was measured with** (%s): only "
          "the uniform and time-adaptive series are here; the targets are not measured." %
          meta.get("mesh_adaptive_reason", "the option was rejected"))
        w("")
    w("| series | setting | steps | nodes (final) | wall [s] (runs) | " + " | ".join(SYM[k] for k in SHOWN) + " |")
    w("|---|---|---:|---:|---:|" + "---:|" * len(SHOWN))
    for name in series_names:
        for r in sorted((r for r in main if r["series"] == name), key=lambda r: r["wall"]):
            w("| %s | %s | %d | %d | %.3g (%d) | " % (series_title(name), describe(r), r["steps"], r["nodes"],
                                                      r["wall"], r["runs"]) +
              " | ".join(pct(r["err"][k]) for k in SHOWN) + " |")
    w("")
    if failed:
        w("Runs that failed or could not be measured: %s." % "; ".join(
            "%s (%s)" % (r["label"], r["failed"]) for r in failed))
        w("")

    # what the table shows
    w("What the table shows (numbers from this run):")
    w("")
    for name in ("uniform_euler", "uniform_bdf2"):
        rs = sorted((r for r in main if r["series"] == name), key=lambda r: r["s"])
        if len(rs) >= 2:
            orders = []
            for k in SHOWN:
                o = [math.log(a["err"][k] / b["err"][k]) / math.log(b["s"] / a["s"]) for a, b in zip(rs, rs[1:])]
                orders.append("%s %s" % (SYM[k], ", ".join("%.2f" % x for x in o)))
            w("- %s, h and dt refined together (s = %s): observed orders %s. u and θ converge at order 1; P and η, "
              "which carry the jump of the pulse as a front (Cattaneo's law damps it only as e^(−t/(2τ)), τ = 0.2), "
              "much more slowly." % (series_title(name), ", ".join(str(r["s"]) for r in rs), "; ".join(orders)))
    if tadapt_rows:
        for s in sorted({r["s"] for r in tadapt_rows}):
            ref = find("uniform_bdf2", s)
            rs = [r for r in tadapt_rows if r["s"] == s]
            if ref and rs:
                best = min(rs, key=worst_pe)
                w("- Adaptive time steps on s = %d: the smallest P/η error is %s/%s (%s, %s), against %s/%s for uniform "
                  "BDF2 on the same mesh with dt = %g; u and θ stay at the mesh's error (%s, %s) whatever the "
                  "tolerance. Adapting dt alone cannot remove the mesh error of the fronts." % (
                      s, pct(best["err"]["P"]), pct(best["err"]["eta"]), best["series"].split("_")[1],
                      "error_tol = %g" % best["time_tol"], pct(ref["err"]["P"]), pct(ref["err"]["eta"]), ref["dt"],
                      pct(best["err"]["u"]), pct(best["err"]["theta"])))
    if mesh_rows:
        nat = [r for r in mesh_rows if "err_grid" in r]
        if nat:
            worst_gap = max(nat, key=lambda r: r["err_grid"]["P"] / r["err"]["P"])
            w("- Adaptive mesh: the error on the run's own mesh (`/snapshots/native`) and that of the interpolated "
              "`/snapshots/P` on the fixed grid `/mesh/x` (%d points) differ by up to %.2fx in P (%s: %s native, "
              "%s interpolated); the tables use the native values." % (
                  worst_gap["grid_points"], worst_gap["err_grid"]["P"] / worst_gap["err"]["P"],
                  describe(worst_gap), pct(worst_gap["err"]["P"]), pct(worst_gap["err_grid"]["P"])))
            probs = [(r["label"], p) for r in nat for p in r.get("native_problems", [])]
            if probs:
                w("- **/snapshots/native inconsistencies**: %s." % "; ".join("%s: %s" % x for x in probs))
            w("- How the meshes evolved (elements from `/series/n_elements`: at t = 0, largest, mean over the series, "
              "at t = %s; the finest element of the final mesh; µs per step and per element-step, against %s for "
              "uniform BDF2): %s." % (
                  meta.get("t_end", "0.25"), ", ".join("%.0f ns (s = %d)" % (1e9 * r["wall"] / r["steps"] / r["s"], r["s"])
                                                       for r in main if r["series"] == "uniform_bdf2"),
                  "; ".join("%s: %s, h_min %.2g, %.0f µs per step, %.0f ns per element-step" % (
                      describe(r), "%d / %d / %.0f / %d" % (r["elements"]["first"], r["elements"]["max"],
                                                             r["elements"]["mean"], r["elements"]["last"])
                      if r.get("elements") else "?", r["h_min"], 1e6 * r["wall"] / r["steps"],
                      1e9 * r["wall"] / r["steps"] / r["elements"]["mean"] if r.get("elements") else float("nan"))
                      for r in sorted(nat, key=lambda r: r["wall"]))))
    w("")
    for info, (level, ratio, name) in zip(t_info, ((T1_ERROR, T1_RATIO, "T1"), (T2_ERROR, T2_RATIO, "T2"))):
        if info:
            best, base, r = info
            w("**Target %s** (P and η within %s, >= %gx less wall time than uniform BDF2 s = %d): the cheapest "
              "adaptive-mesh run there is %s, %.3g s against %.3g s: **%.1fx**, %s." % (
                  name, pct(level), ratio, base["s"], describe(best), best["wall"], base["wall"], r,
                  "met" if r >= ratio else "not met"))
            w("")
    if b8000:
        others = sorted((r for r in main if not r["series"].startswith("mesh_") and r is not b8000
                         and worst_pe(r) <= T1_ERROR), key=lambda r: r["wall"])
        if others:
            o = others[0]
            w("Without the adaptive mesh: the cheapest run with P and η within 1 %% is %s (%s; P %s, η %s) in "
              "%.3g s, %.1fx less wall time than uniform BDF2 s = 8000." % (
                  series_title(o["series"]).split(", s = ")[0], describe(o), pct(o["err"]["P"]), pct(o["err"]["eta"]), o["wall"],
                  b8000["wall"] / o["wall"]))
            w("")
    for base in (b8000, b32000):
        if base:
            w("Uniform BDF2 s = %d itself: P %s, η %s (%s within 1 %%, %s within 0.5 %%)." % (
                base["s"], pct(base["err"]["P"]), pct(base["err"]["eta"]),
                "is" if worst_pe(base) <= T1_ERROR else "is **not**", "is" if worst_pe(base) <= T2_ERROR else "is not"))
    w("")

    # other pulses
    pulses = [r for r in rows if r["series"].startswith("pulse_")]
    if pulses:
        w("### The same settings on other pulses")
        w("")
        w("The adaptive setting %s and uniform BDF2 (%s) on other initial pulses, each against its exact "
          "solution at a time before its first contact. Before contact the model is linear, so exp2_amp5 is "
          "exp2 scaled by 1/4: equal relative errors there only show that the settings are scale-invariant; "
          "the other widths change the shape of the fronts." % (
              "`%s` (`%s`)" % tuple((meta.get("pulse_setting", "?") + ": ").split(": ")[:2]), meta.get("pulse_base", "?")))
        w("")
        w("| input | t | run | steps | nodes | wall [s] | " + " | ".join(SYM[k] for k in SHOWN) + " |")
        w("|---|---:|---|---:|---:|---:|" + "---:|" * len(SHOWN))
        for r in pulses:
            variant, kind = r["series"][len("pulse_"):].rsplit("_", 1)
            what = meta.get("pulse." + variant, variant)
            if "failed" in r:
                w("| %s | %g | %s | – | – | – | failed: %s |" % (what, r["t_end"], kind, r["failed"]) + " |" * 3)
                continue
            w("| %s | %g | %s | %d | %d | %.3g | " % (what, r["t_end"], "adaptive" if kind == "adaptive" else
                                                      "uniform BDF2 s = %d" % r["s"], r["steps"], r["nodes"], r["wall"])
              + " | ".join(pct(r["err"][k]) for k in SHOWN) + " |")
        w("")

    # after contact
    if after:
        w("### After contact (t = %g): adaptive runs against each other" % after[0]["t_end"])
        w("")
        w("No exact solution once the rod has touched the obstacle. Within each group, the relative L2 difference "
          "of every run to the group's tightest setting (*ref*); a difference that shrinks as the tolerance "
          "tightens is consistent with convergence, not a proof of it.")
        w("")
        w("| group | run | role | steps | nodes | wall [s] | first contact | " +
          " | ".join("Δ" + SYM[k] for k in SHOWN) + " |")
        w("|---|---|---|---:|---:|---:|---:|" + "---:|" * len(SHOWN))
        for r in after:
            if "failed" in r:
                w("| %s | %s | %s | – | – | – | – | failed: %s | | | |" % (r["group"], r["label"], r["role"], r["failed"]))
                continue
            w("| %s | %s | %s | %d | %d | %.3g | %s | " % (
                r["group"], r["label"], r["role"], r["steps"], r["nodes"], r["wall"],
                "%.4f" % r["contact"] if r["contact"] is not None else "none") +
              " | ".join("–" if r["role"] == "ref" else pct(r["diff"][k]) for k in SHOWN) + " |")
        w("")
    with open(os.path.join(outdir, "work_precision_mesh.md"), "w") as f:
        f.write("\n".join(md).rstrip() + "\n")


def cmd_splice(outdir, doc):
    section = open(os.path.join(outdir, "work_precision_mesh.md")).read().rstrip("\n").split("\n")
    rows = [l.rstrip("\n") for l in open(os.path.join(outdir, "work_precision_mesh_targets.txt")) if l.strip()]
    lines = open(doc).read().rstrip("\n").split("\n")
    # the section
    start = next((i for i, l in enumerate(lines) if l.startswith("## Adaptive mesh")), None)
    if start is not None:
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
        lines[start:end] = section + ([""] if end < len(lines) else [])
    else:
        lines += [""] + section
    # the target rows
    lines = [l for l in lines if not l.startswith(TARGET_PREFIX)]
    t0 = next(i for i, l in enumerate(lines) if l == "## Targets")
    last = t0
    for i in range(t0 + 1, len(lines)):
        if lines[i].startswith("|"):
            last = i
        elif lines[i].startswith("## "):
            break
    lines[last + 1:last + 1] = rows
    with open(doc + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(doc + ".tmp", doc)


def main():
    cmds = {"points": (cmd_points, 2), "after": (cmd_after, 2), "report": (cmd_report, 2), "splice": (cmd_splice, 2)}
    if len(sys.argv) < 2 or sys.argv[1] not in cmds or len(sys.argv) != 2 + cmds[sys.argv[1]][1]:
        sys.exit(__doc__)
    cmds[sys.argv[1]][0](*sys.argv[2:])


if __name__ == "__main__":
    main()
