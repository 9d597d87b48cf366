"""Accuracy and cost of fixed and adaptive time steps on experiment 1 (bench/adaptive_steps.sh).

Needs h5py and numpy: run it with the interpreter of scripts/lib/find_python.sh.

    PY adaptive_steps.py points RAW REF.h5 SPEC
        every line of SPEC is one point, "LABEL SCHEME MODE PARAM T_END RUN.h5 [RUN.h5 ...]",
        the RUN.h5 repeats of the same run (identical results, only the wall time differs);
        appends one JSON line per point to RAW with the median wall time (root attribute
        wall_seconds; /usr/bin/time's elapsed from RUN.time where present), the counters, the
        max over the run's series times t <= T_END of |u(1,t) - reference| (the reference's
        /series/u_end linearly interpolated at the run's /series/t; also over t <= T_SPLIT and
        t > T_SPLIT, the contact phase and the decay), and the errors of the contact event
        times (/events) against the reference's.
    PY adaptive_steps.py refcheck RAW REF.h5 CHECK.h5 [COARSE.h5]
        the reference's own accuracy: CHECK (twice the reference's dt) and COARSE (four times)
        compared with it at their own series times, which are reference times (no interpolation);
        and the linear interpolation error of the reference's series (second differences / 8).
    PY adaptive_steps.py report OUTDIR
        reads OUTDIR/work_precision_adaptive.raw, .refcheck and .meta; writes
        OUTDIR/work_precision_adaptive.dat (gnuplot, one block per scheme/mode),
        OUTDIR/work_precision_adaptive_params.gp, OUTDIR/work_precision_adaptive.md (the section of
        docs/performance.md) and OUTDIR/work_precision_adaptive_targets.txt (rows of its Targets table).
    PY adaptive_steps.py splice OUTDIR DOC
        replaces that section and those target rows in DOC (docs/performance.md).
"""

import json
import math
import os
import statistics
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'scripts', 'lib'))
import rodrun  # noqa: E402
from textfiles import read_meta, spec_lines  # noqa: E402

T_SPLIT = 2.0              # contact phase [0, 2] (release at t ~ 1.45) and decay (2, t_end]
TARGET_A_RATIO = 20.0      # issue 12: max|du| <= 1e-5, events within 1e-5, >= 20x less wall time
TARGET_A_ERROR = 1e-5
TARGET_B_RATIO = 5.0       # issue 12: to t = 10 at fixed Euler dt = 1e-4's accuracy, >= 5x less wall time
TARGET_C_SECONDS = 0.12    # issue 24: max|du| <= 1e-5 on the dense grid (the interpolant), events within 1e-5
SEQUENCES = [("fixed", "euler", "Euler, fixed dt"), ("fixed", "bdf2", "BDF2, fixed dt"),
             ("adaptive", "euler", "Euler, adaptive"), ("adaptive", "bdf2", "BDF2, adaptive"),
             ("adaptive", "midpoint", "midpoint, adaptive")]
STYLE = {("fixed", "euler"): ("#c0392b", 7, 1), ("fixed", "bdf2"): ("#1f5fa8", 5, 1),
         ("adaptive", "euler"): ("#e67e22", 9, 2), ("adaptive", "bdf2"): ("#16a085", 11, 2),
         ("adaptive", "midpoint"): ("#5b2c83", 13, 2)}


def read_run(path):
    with rodrun.open_run(path) as f:
        d = {"t": rodrun.series(f, "t"), "u": rodrun.series(f, "u_end")}
        d["ev_t"], d["ev_kind"] = rodrun.events(f)
        for k in ("wall_seconds", "steps", "time_steps_rejected", "step_control_error_sum",
                  "step_control_error_sum_relative", "time_steps_at_dt_min", "status", "t_final"):
            d[k] = rodrun.attr(f, k)
        d["dt_series"] = rodrun.series(f, "dt")
    return d


def events(d, t_end):
    """(onset, release) times: the first +1 event and the first -1 event after it (None if absent)."""
    onset = release = None
    for t, k in zip(d["ev_t"], d["ev_kind"]):
        if t > t_end + 1e-12:
            break
        if k > 0 and onset is None:
            onset = float(t)
        elif k < 0 and onset is not None and release is None:
            release = float(t)
    return onset, release


def n_events(d, t_end):
    return int(np.sum(d["ev_t"] <= t_end + 1e-12))


def elapsed(path):
    tpath = path[:-3] + ".time" if path.endswith(".h5") else path + ".time"
    try:
        return float(open(tpath).read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def cmd_points(args):
    raw, ref_path, spec = args
    ref = read_run(ref_path)
    for words in spec_lines(spec):
        point(raw, ref, *words)


def window_max(t, x):
    """max of x over t <= T_SPLIT and over t > T_SPLIT (None where empty)."""
    early, late = x[t <= T_SPLIT], x[t > T_SPLIT]
    return (float(early.max()) if early.size else None), (float(late.max()) if late.size else None)


def dense_grid(t_end):
    """The grid the errors between the steps are taken on: every 1e-4 to t = 1, every 1e-3 after."""
    g = np.arange(1, int(round(min(t_end, 1.0) / 1e-4)) + 1) * 1e-4
    if t_end > 1.0:
        g = np.concatenate([g, 1.0 + np.arange(1, int(round((t_end - 1.0) / 1e-3)) + 1) * 1e-3])
    return g[g <= t_end * (1 + 1e-12)]


def interpolant(t, u, ev_t, order, grid):
    """u(1,t) on the grid from the scheme's interpolant (src/numerics/dense_output_m.f90, as the
    code's &output series_dt writes it): the polynomial through the last order+1 levels since the
    last contact event; the straight line in the step across an event and the one after it.
    t, u: every step's level (the run's series, every step written)."""
    n = np.clip(np.searchsorted(t, grid), 1, t.size - 1)      # t[n-1] < grid <= t[n]
    step_of_event = np.searchsorted(t, ev_t)                   # the step across each event
    first = np.zeros(t.size, dtype=int)                        # the first level since the last event
    for m in step_of_event:
        if m < t.size:
            first[m:] = m
    levels = n - first[n] + 1
    quad = (order >= 2) & (levels >= 3)
    out = np.empty(grid.size)
    lin = ~quad
    t0, t1 = t[n - 1], t[n]
    out[lin] = (u[n - 1] + (u[n] - u[n - 1]) * (grid - t0) / (t1 - t0))[lin]
    q = np.where(quad)[0]
    if q.size:
        a, b, c = t[n[q] - 2], t[n[q] - 1], t[n[q]]
        x = grid[q]
        out[q] = (u[n[q] - 2] * (x - b) * (x - c) / ((a - b) * (a - c))
                  + u[n[q] - 1] * (x - a) * (x - c) / ((b - a) * (b - c))
                  + u[n[q]] * (x - a) * (x - b) / ((c - a) * (c - b)))
    return out


def point(raw, ref, label, scheme, mode, param, t_end, *runs):
    t_end = float(t_end)
    d = read_run(runs[0])
    if d["status"] != "complete":
        sys.exit("adaptive_accuracy: %s: status %r" % (runs[0], d["status"]))
    walls = [d["wall_seconds"]] + [read_run(p)["wall_seconds"] for p in runs[1:]]
    times = [x for x in (elapsed(p) for p in runs) if x is not None]
    keep = d["t"] <= t_end * (1 + 1e-12)
    t, u = d["t"][keep], d["u"][keep]
    du = np.abs(u - np.interp(t, ref["t"], ref["u"]))
    i = int(np.argmax(du))
    ro, rr = events(ref, t_end)
    o, r = events(d, t_end)
    big = d["dt_series"][1:] if d["dt_series"] is not None else np.zeros(0)
    du_early, du_late = window_max(t, du)
    grid = dense_grid(t_end)
    ref_grid = np.interp(grid, ref["t"], ref["u"])
    du_dense = float(np.max(np.abs(interpolant(t, u, d["ev_t"], 1 if scheme == "euler" else 2, grid) - ref_grid)))
    du_line = float(np.max(np.abs(np.interp(grid, t, u) - ref_grid)))
    row = {"label": label, "scheme": scheme, "mode": mode, "param": float(param), "param_text": param, "t_end": t_end,
           "steps": int(d["steps"]), "rejected": d["time_steps_rejected"],
           "at_dt_min": d["time_steps_at_dt_min"],
           "wall": statistics.median(walls), "walls": walls,
           "elapsed": statistics.median(times) if times else None, "runs": len(runs),
           "max_du": float(du[i]), "t_max_du": float(t[i]), "n_series": int(t.size),
           "max_du_dense": du_dense, "max_du_line": du_line, "n_grid": int(grid.size),
           "max_du_early": du_early, "max_du_late": du_late,
           "onset": o, "release": r, "onset_ref": ro, "release_ref": rr,
           "onset_err": abs(o - ro) if o is not None and ro is not None else None,
           "release_err": abs(r - rr) if r is not None and rr is not None else None,
           "n_events": n_events(d, t_end), "n_events_ref": n_events(ref, t_end),
           "est": d["step_control_error_sum"], "est_rel": d["step_control_error_sum_relative"],
           "dt_max_used": float(big.max()) if big.size else None,
           "dt_min_used": float(big[big > 0].min()) if big.size and (big > 0).any() else None}
    with open(raw, "a") as f:
        f.write(json.dumps(row) + "\n")
    ev = max(x for x in (row["onset_err"], row["release_err"], 0.0) if x is not None)
    print("  %-28s steps %8d  wall %7.3f s  max|du| %.2e (t = %.3g), dense grid %.2e (straight line %.2e)  "
          "events %d (ref %d), max event error %.2e"
          % (label, row["steps"], row["wall"], row["max_du"], row["t_max_du"], du_dense, du_line, row["n_events"],
             row["n_events_ref"], ev), file=sys.stderr)


def cmd_refcheck(args):
    raw, ref_path = args[0], args[1]
    ref = read_run(ref_path)
    out = {"ref_steps": int(ref["steps"]), "ref_wall": ref["wall_seconds"], "ref_t_end": float(ref["t_final"]),
           "ref_onset": events(ref, 1e300)[0], "ref_release": events(ref, 1e300)[1],
           "ref_n_events": n_events(ref, 1e300), "ref_elapsed": elapsed(ref_path)}
    u = ref["u"]
    with rodrun.open_run(ref_path) as f:
        energy = rodrun.series(f, "energy")
    out["energy"] = [(float(ref["t"][i]), float(energy[i])) for i in
                     sorted({int(np.searchsorted(ref["t"], x)) for x in (0, 2, 10, 20, 40)} & set(range(energy.size)))]
    out["energy_max"] = float(energy.max())
    for key in ("ref_onset", "ref_release"):           # du(1)/dt where u(1,t) crosses g
        if out[key] is not None:
            i = int(np.clip(np.searchsorted(ref["t"], out[key]), 2, u.size - 2))
            before = (u[i - 1] - u[i - 2]) / (ref["t"][i - 1] - ref["t"][i - 2])
            after = (u[i + 1] - u[i]) / (ref["t"][i + 1] - ref["t"][i])
            out[key + "_slope"] = (float(before), float(after))
    out["interp_error"] = float(np.max(np.abs(u[2:] - 2 * u[1:-1] + u[:-2])) / 8) if u.size > 2 else 0.0
    for key, path in zip(("check", "coarse"), args[2:4]):
        c = read_run(path)
        idx = np.searchsorted(ref["t"], c["t"])
        idx = np.clip(idx, 0, ref["t"].size - 1)
        exact = np.abs(ref["t"][idx] - c["t"]) <= 1e-9 * np.maximum(1.0, c["t"])
        diff = np.abs(c["u"] - np.interp(c["t"], ref["t"], ref["u"]))
        co, cr = events(c, 1e300)
        early, late = window_max(c["t"], diff)
        out[key] = {"steps": int(c["steps"]), "wall": c["wall_seconds"], "max_diff": float(diff.max()),
                    "t_max_diff": float(c["t"][int(np.argmax(diff))]), "max_diff_early": early, "max_diff_late": late,
                    "all_on_reference_times": bool(exact.all()),
                    "onset_diff": abs(co - out["ref_onset"]) if co is not None and out["ref_onset"] else None,
                    "release_diff": abs(cr - out["ref_release"]) if cr is not None and out["ref_release"] else None}
    with open(raw, "w") as f:
        f.write(json.dumps(out) + "\n")
    print("  reference check: %s" % json.dumps(out), file=sys.stderr)


# ------------------------------------------------------------------------------------ report
def e(x, fmt="%.2e"):
    return "–" if x is None else fmt % x


def ev_err(r):
    vals = [x for x in (r["onset_err"], r["release_err"]) if x is not None]
    if r["n_events"] != r["n_events_ref"] or len(vals) < 2:
        return None
    return max(vals)


def meets_a(r):
    ev = ev_err(r)
    return r["max_du"] <= TARGET_A_ERROR and ev is not None and ev <= TARGET_A_ERROR


def param_str(r):
    return ("dt = %s" % r["param_text"]) if r["mode"] == "fixed" else ("tol = %s" % r["param_text"])


def table(rows):
    md = ["| scheme | dt or error_tol | steps | rejected | largest dt | wall [s] (runs) | max\\|du\\| | at t | "
          "dense grid: interpolant | straight line | "
          "onset error | release error | events (ref) | step_control_error_sum_relative |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for mode, scheme, name in SEQUENCES:
        for r in sorted((r for r in rows if r["mode"] == mode and r["scheme"] == scheme),
                        key=lambda r: -r["param"]):
            md.append("| %s | %s | %d | %s | %s | %.3g (%d) | %.2e | %.3g | %s | %s | %s | %s | %d (%d) | %s |" % (
                name + (" (check)" if r["label"].endswith("_check") else ""), param_str(r), r["steps"],
                "–" if r["rejected"] is None else r["rejected"],
                r["param_text"] if r["mode"] == "fixed" else e(r["dt_max_used"], "%.3g"), r["wall"],
                r["runs"], r["max_du"], r["t_max_du"], e(r.get("max_du_dense")), e(r.get("max_du_line")),
                e(r["onset_err"]), e(r["release_err"]), r["n_events"],
                r["n_events_ref"], e(r["est_rel"], "%.2e")))
    return md


def cmd_report(args):
    outdir = args[0]
    rows = [json.loads(l) for l in open(os.path.join(outdir, "work_precision_adaptive.raw")) if l.strip()]
    rc = json.loads(open(os.path.join(outdir, "work_precision_adaptive.refcheck")).read())
    meta = read_meta(os.path.join(outdir, "work_precision_adaptive.meta"))
    t_long = float(meta["t_end"])
    t_short = float(meta["t_end_short"])
    long_rows = [r for r in rows if r["t_end"] == t_long]
    short_rows = [r for r in rows if r["t_end"] == t_short]
    base = next((r for r in rows if r["label"] == "base_euler_long"), None)
    base_short = next((r for r in rows if r["label"] == "base_euler_short"), None)

    # --- gnuplot data: one block per sequence, t = t_long (index 0-4) then t = t_short (index 5-9)
    with open(os.path.join(outdir, "work_precision_adaptive.dat"), "w") as f:
        for tag, rs in (("long", long_rows), ("short", short_rows)):
            for mode, scheme, name in SEQUENCES:
                f.write("# %s: %s\n# param wall max_du max_event_error steps param_text\n" % (tag, name))
                block = sorted((r for r in rs if r["mode"] == mode and r["scheme"] == scheme), key=lambda r: r["wall"])
                if not block:       # gnuplot drops an empty block from the index count: keep a line
                    f.write("NaN NaN NaN NaN 0 -\n")
                for r in block:
                    ev = ev_err(r)
                    f.write("%g %.6g %.6g %.6g %d %s\n" % (r["param"], r["wall"], r["max_du"],
                                                            ev if ev is not None else float("nan"), r["steps"],
                                                            r["param_text"]))
                f.write("\n\n")
    with open(os.path.join(outdir, "work_precision_adaptive_params.gp"), "w") as f:
        f.write("wpa_n = %d\n" % len(SEQUENCES))
        for arr in ("title", "colour", "pt", "dash", "lx", "ly"):
            f.write("array wpa_%s[%d]\n" % (arr, len(SEQUENCES)))
        for i, (mode, scheme, name) in enumerate(SEQUENCES, 1):
            colour, pt, dash = STYLE[(mode, scheme)]
            lx, ly = (0.7, -0.8) if (mode, scheme) == ("adaptive", "bdf2") else (0.3, 0.75)
            f.write('wpa_title[%d] = "%s"\nwpa_colour[%d] = "%s"\nwpa_pt[%d] = %d\nwpa_dash[%d] = %d\n'
                    'wpa_lx[%d] = %g\nwpa_ly[%d] = %g\n' % (i, name, i, colour, i, pt, i, dash, i, lx, i, ly))
        f.write("wpa_t_long = '%g'\nwpa_t_short = '%g'\nwpa_target_a = %g\n" % (t_long, t_short, TARGET_A_ERROR))
        ref_error = rc["check"]["max_diff"] / 3
        ev_check = [x for x in (rc["check"]["onset_diff"], rc["check"]["release_diff"]) if x is not None]
        ref_ev_error = max(ev_check) / 3 if ev_check else None
        f.write("wpa_ref_error = %g\n" % ref_error)
        f.write("wpa_ref_dt = '%s'\n" % meta.get("ref_dt", "?"))
        # y ranges that show the reference's accuracy lines with the data
        errs = [r["max_du"] for r in rows if r["t_end"] == t_long] + [ref_error]
        f.write("wpa_ymin_u = %g\nwpa_ymax_u = %g\n" % (10 ** math.floor(math.log10(min(errs) / 1.5)),
                                                         10 ** math.ceil(math.log10(max(errs)))))
        evs = [x for x in (ev_err(r) for r in rows if r["t_end"] == t_long) if x is not None]
        if ref_ev_error:
            f.write("wpa_ref_ev_error = %g\n" % ref_ev_error)
            evs.append(ref_ev_error)
        if evs:
            f.write("wpa_ymin_ev = %g\nwpa_ymax_ev = %g\n" % (10 ** math.floor(math.log10(min(evs) / 1.5)),
                                                               10 ** math.ceil(math.log10(max(evs)))))
        if base_short:
            f.write("wpa_base_short_error = %g\n" % base_short["max_du"])

    # --- the targets
    targets = []
    a_ok = sorted((r for r in long_rows if meets_a(r) and r["mode"] == "adaptive"), key=lambda r: r["wall"])
    a_fixed = sorted((r for r in long_rows if meets_a(r) and r["mode"] == "fixed"), key=lambda r: r["wall"])
    if base:
        if a_ok:
            best = a_ok[0]
            ratio = base["wall"] / best["wall"]
            targets.append("| exp1 to t = %g with max\\|u(1,t) - ref\\| <= 1e-5 and onset, release within 1e-5: wall "
                           "time >= %.0fx below fixed Euler dt = 1e-4 | %.0fx (%s adaptive, %s: %.3g s against %.3g s)"
                           " | %s |" % (t_long, TARGET_A_RATIO, ratio, best["scheme"], param_str(best), best["wall"],
                                        base["wall"], "yes" if ratio >= TARGET_A_RATIO else "**no**"))
        else:
            targets.append("| exp1 to t = %g with max\\|u(1,t) - ref\\| <= 1e-5 and events within 1e-5: >= %.0fx "
                           "below fixed Euler dt = 1e-4 | no adaptive run meets the accuracy | **no** |"
                           % (t_long, TARGET_A_RATIO))
    b_best = None
    if base_short:
        level = base_short["max_du"]
        cands = sorted((r for r in short_rows if r["mode"] == "adaptive" and r["max_du"] <= level),
                       key=lambda r: r["wall"])
        if cands:
            b_best = cands[0]
            ratio = base_short["wall"] / b_best["wall"]
            targets.append("| exp1 to t = %g at the accuracy of fixed Euler dt = 1e-4 (max\\|du\\| <= %.2e): wall "
                           "time >= %.0fx below it | %.0fx (%s adaptive, %s: %.3g s against %.3g s) | %s |"
                           % (t_short, level, TARGET_B_RATIO, ratio, b_best["scheme"], param_str(b_best),
                              b_best["wall"], base_short["wall"], "yes" if ratio >= TARGET_B_RATIO else "**no**"))
        else:
            targets.append("| exp1 to t = %g at the accuracy of fixed Euler dt = 1e-4: >= %.0fx | no adaptive run "
                           "reaches it | **no** |" % (t_short, TARGET_B_RATIO))
    c_ok = sorted((r for r in long_rows if r["mode"] == "adaptive" and r.get("max_du_dense") is not None
                   and r["max_du_dense"] <= TARGET_A_ERROR and ev_err(r) is not None and ev_err(r) <= TARGET_A_ERROR),
                  key=lambda r: r["wall"])
    if c_ok:
        best = c_ok[0]
        targets.append("| exp1 to t = %g with max\\|u(1,t) - ref\\| <= 1e-5 on the dense grid (every 1e-4 to t = 1, "
                       "1e-3 after; the scheme's interpolant) and events within 1e-5: wall time <= %.2f s | %.3g s "
                       "(%s adaptive, %s; %d steps) | %s |" % (t_long, TARGET_C_SECONDS, best["wall"], best["scheme"],
                                                            param_str(best), best["steps"],
                                                            "yes" if best["wall"] <= TARGET_C_SECONDS else "**no**"))
    else:
        targets.append("| exp1 to t = %g with max\\|u(1,t) - ref\\| <= 1e-5 on the dense grid and events within "
                       "1e-5: <= %.2f s | no adaptive run meets the accuracy | **no** |" % (t_long, TARGET_C_SECONDS))
    with open(os.path.join(outdir, "work_precision_adaptive_targets.txt"), "w") as f:
        f.write("\n".join(targets) + ("\n" if targets else ""))

    # --- the section
    md = []
    w = md.append
    w("## Adaptive time steps: work and precision on experiment 1")
    w("")
    w("Command: `bench/adaptive_steps.sh` (also run by `bench.sh`; helper "
      "`bench/adaptive_steps.py`). ![work-precision, adaptive time steps]"
      "(../figures/work_precision_adaptive.png)")
    w("")
    w("Experiment 1 (`input/exp1.nml`, h = 1/500) to t = %g, every run with" % t_long)
    w("")
    w("    LD_LIBRARY_PATH=%s build/rodcontact input/exp1.nml --set time.t_end=%g \\" % (meta.get("ld_library_path", "?"), t_long))
    w("        --set output.snapshot_every=1000000000 --set output.quiet=.true. --set output.prefix=<tmp> \\")
    w("        --set time.scheme=<scheme> --set time.dt=<dt>                      # fixed steps")
    w("        --set time.scheme=<scheme> --set time.adaptive=.true. --set time.error_tol=<tol>   # adaptive")
    w("")
    w("(adaptive: first step dt = 1e-4 of the input, `dt_min`, `dt_max` at their defaults 1e-10 and 1). "
      "Error: the largest |u(1,t) - reference| over the run's own series times t (`/series/t`, "
      "`/series/u_end`; every step is written), the reference's `/series/u_end` linearly interpolated there; "
      "and on the dense grid (every 1e-4 to t = 1, every 1e-3 after), the run's u(1,t) from the scheme's "
      "interpolant (`&output series_dt` writes the same values; `adaptive_steps.py`'s `interpolant`) and "
      "from the straight line between the steps (for comparison). Onset and release: `/events/t` (kind +1, then -1) "
      "against the reference's. Wall time: the root attribute `wall_seconds` (the whole run, set-up and "
      "HDF5 output included, without process start-up), median of %s runs for runs under %s s and for "
      "the fixed Euler baseline to t = %g, one run for the longer ones (the `(runs)` column; the repeats are "
      "round robin over all such runs, so that a burst of load from other jobs hits one round); `/usr/bin/time` elapsed is in the raw data. "
      "Load average %s at the start of this section, %s at its end (2 shared cores); BLAS/LAPACK resolved "
      "as: %s (a time step calls neither). Raw data: `%s/work_precision_adaptive.raw` (JSON lines)."
      % (meta.get("repeats", "?"), meta.get("repeat_below", "?"), t_short, meta.get("load_start", "?"),
         meta.get("load_end", "?"), meta.get("blas", "?"), meta.get("outdir_rel", "out/bench")))
    w("")
    w("### The reference and its accuracy")
    w("")
    ch, co = rc["check"], rc.get("coarse")
    points = [r for r in long_rows if not r["label"].endswith("_check")]     # the check is not a point
    ref_err = ch["max_diff"] / 3
    w("Reference: fixed-step BDF2 with dt = %s to t = %g, every step in the series (%d steps, %.0f s; events: "
      "onset t = %.8f, release t = %.8f). Checked against the same with dt = %s (%d steps; the row marked "
      "*check* below), at the check's own series times, which are reference times (no interpolation): max over "
      "t of the |u(1,t)| difference %.2e (at t = %.3g), onset and release %s and %s apart. For a second-order "
      "scheme the reference's own error is about the difference / (2^2 - 1): **%.1e** in u(1,t), %s and %s in "
      "the onset and release times." % (
          meta.get("ref_dt"), t_long, rc["ref_steps"], rc["ref_wall"], rc["ref_onset"] or float("nan"),
          rc["ref_release"] or float("nan"), meta.get("check_dt"), ch["steps"], ch["max_diff"], ch["t_max_diff"],
          e(ch["onset_diff"]), e(ch["release_diff"]), ref_err, e(ch["onset_diff"] and ch["onset_diff"] / 3, "%.1e"),
          e(ch["release_diff"] and ch["release_diff"] / 3, "%.1e")))
    if co:
        ratio = co["max_diff"] / ch["max_diff"] if ch["max_diff"] > 0 else float("nan")
        p = math.log(ratio - 1) / math.log(2) if ratio > 1 else float("nan")
        w("Is it second order here? The fixed BDF2 run with dt = %s differs from the reference by %.2e, %.2f "
          "times the dt = %s difference; order p gives (4^p - 1)/(2^p - 1) (5 for p = 2, 3 for p = 1): observed "
          "p = %.2f (%swith p = %.2f the reference's error would be the difference / %.2f = %.1e)." % (
              meta.get("coarse_dt"), co["max_diff"], ratio, meta.get("check_dt"), p,
              "both largest differences are at t = %.4g, next to the contact onset, where [u(1) - g]_+ has a kink "
              "in time; " % ch["t_max_diff"] if rc["ref_onset"] and abs(ch["t_max_diff"] - rc["ref_onset"]) < 0.01
              and abs(co["t_max_diff"] - rc["ref_onset"]) < 0.01 else "", p, 2 ** p - 1,
              ch["max_diff"] / (2 ** p - 1)))
    w("Linear interpolation of the reference between its steps adds at most about %.1e (largest second "
      "difference of its u(1,t) / 8)." % rc["interp_error"])
    w("")
    if points:
        best = min(points, key=lambda r: r["max_du"])
        ok = 10 * ref_err <= best["max_du"]
        w("| t | check - reference, max | reference error (/3) | most accurate point (%s %s, %s): max\\|du\\| | "
          "ratio |" % (best["scheme"], best["mode"], param_str(best)))
        w("|---|---:|---:|---:|---:|")
        for name, dk, pk in (("0 ≤ t ≤ %g (contact)" % T_SPLIT, "max_diff_early", "max_du_early"),
                             ("%g < t ≤ %g (decay)" % (T_SPLIT, t_long), "max_diff_late", "max_du_late"),
                             ("all t", "max_diff", "max_du")):
            if ch.get(dk) is not None and best.get(pk) is not None:
                w("| %s | %.2e | %.1e | %.2e | %.2g |" % (name, ch[dk], ch[dk] / 3, best[pk],
                                                          best[pk] / (ch[dk] / 3) if ch[dk] > 0 else float("inf")))
        w("")
        late = best["t_max_du"] > T_SPLIT
        dk, pk = ("max_diff_late", "max_du_late") if late else ("max_diff_early", "max_du_early")
        rwin = best[pk] / (ch[dk] / 3) if ch.get(dk) else float("inf")
        if ok:
            w("Requirement, the reference's error at least 10x below the most accurate point's max|du|: **met** "
              "(%.0fx)." % (best["max_du"] / ref_err))
        else:
            w("Requirement, the reference's error at least 10x below the most accurate point's max|du|: **not met** "
              "in the max over all t (%.1fx; the reference's largest difference to the check is at t = %.3g). "
              "Where that point's own largest error lies (t = %.3g, %s) the ratio is %.0f%s. The points with max|du| "
              "below 10 x %.1e = %.1e (%s) are within 10x of the reference's own error near t = %.3g: "
              "their max|du| is uncertain by up to %.1e." % (
                  best["max_du"] / ref_err, ch["t_max_diff"], best["t_max_du"],
                  "the decay" if late else "the contact phase", rwin,
                  " (met there)" if rwin >= 10 else " (not met there either)", ref_err, 10 * ref_err,
                  ", ".join("%s %s %s" % (r["scheme"], r["mode"], param_str(r)) for r in points
                            if r["max_du"] < 10 * ref_err), ch["t_max_diff"], ref_err))
        w("")
    w("### Experiment 1 to t = %g" % t_long)
    w("")
    if base:
        w("Baseline: fixed Euler dt = 1e-4, %d steps, %.3g s (`wall_seconds`, %d run%s)." % (
            base["steps"], base["wall"], base["runs"], "s" if base["runs"] > 1 else ""))
        w("")
    md.extend(table(long_rows))
    w("")
    w("Columns: *rejected* = `time_steps_rejected` (adaptive runs; retried steps that locate a contact "
      "event are not counted); *step_control_error_sum_relative* = the sum of the local error estimates "
      "the controller accepted, relative to the largest energy norm of the solution (adaptive runs only: what "
      "the controller worked with, in the energy norm of all fields, not an error of u(1,t); the run's error is "
      "`&output error_estimate`); *events* = number of "
      "contact events in `/events` (reference in brackets).")
    w("")
    w("**Target (a)**: max|u(1,t) - ref| <= 1e-5 and onset and release within 1e-5 of the reference. "
      "Runs that meet it:")
    w("")
    for r in a_ok + a_fixed:
        ratio = base["wall"] / r["wall"] if base else float("nan")
        w("- %s %s, %s%s: %.3g s, max|du| %.2e, onset and release %.1e and %.1e off: wall time ratio fixed "
          "Euler dt = 1e-4 / this run = **%.2g**" % (r["scheme"], r["mode"], param_str(r),
                                                    " (the reference check)" if r["label"].endswith("_check") else "",
                                                    r["wall"], r["max_du"], r["onset_err"], r["release_err"], ratio))
    if not a_ok + a_fixed:
        w("- none")
    fails = [r for r in long_rows if r["mode"] == "adaptive" and not meets_a(r)]
    if fails:
        w("")
        w("Adaptive runs that miss it (max|du|, worse event error): %s." % "; ".join(
            "%s %s: %.1e, %s" % (r["scheme"], param_str(r), r["max_du"], e(ev_err(r), "%.1e")) for r in
            sorted(fails, key=lambda r: (r["scheme"], -r["param"]))))
    if base:
        w("")
        w("Fixed Euler dt = 1e-4 itself: max|du| %.2e, onset %s and release %s off." % (
            base["max_du"], e(base["onset_err"]), e(base["release_err"])))
    w("")
    w("What the table shows (numbers from this run):")
    w("")
    for scheme in ("euler", "bdf2", "midpoint"):
        rs = sorted((r for r in long_rows if r["mode"] == "adaptive" and r["scheme"] == scheme),
                    key=lambda r: r["param"])
        if len(rs) < 2:
            continue
        lt = [math.log(r["param"]) for r in rs]
        le = [math.log(r["max_du"]) for r in rs]
        mt, me = sum(lt) / len(lt), sum(le) / len(le)
        slope = sum((a - mt) * (b - me) for a, b in zip(lt, le)) / sum((a - mt) ** 2 for a in lt)
        late = [r for r in rs if r["t_max_du"] > T_SPLIT]
        w("- adaptive %s: max|du| ~ error_tol^%.2f over error_tol = %s–%s (least squares); %s; %.0f–%.0f µs per "
          "step (fixed Euler dt = 1e-4: %.0f)." % (
              scheme, slope, rs[0]["param_text"], rs[-1]["param_text"],
              ("the largest error is in the decay at every tolerance (t = %s), where the steps grow to %s" % (
                  ", ".join("%.3g" % r["t_max_du"] for r in rs),
                  "dt_max = %s" % e(rs[0]["dt_max_used"], "%.2g") if len({r["dt_max_used"] for r in rs}) == 1
                  else ", ".join(e(r["dt_max_used"], "%.2g") for r in rs)))
              if len(late) == len(rs) else "the largest error at t = %s" % ", ".join("%.3g" % r["t_max_du"] for r in rs),
              1e6 * min(r["wall"] / r["steps"] for r in rs), 1e6 * max(r["wall"] / r["steps"] for r in rs),
              1e6 * base["wall"] / base["steps"] if base else float("nan")))
    en = rc.get("energy", [])
    w("- error_tol bounds the local error of a step relative to the largest energy norm the solution has had "
      "(`src/adaptivity/step_control_m.f90`). In experiment 1 that is the initial one: the reference's energy is %s "
      "(largest %.3g), so in the decay, where only u(1,t) ~ e^{-t/6} is left, the energy norm sqrt(2E) of the "
      "solution is %s of the largest: there a step may make a local error of error_tol divided by that, "
      "relative to the solution itself. error_tol is not a bound on max|du|, and the schemes differ by large "
      "factors at equal error_tol." % (", ".join("E(%.3g) = %.2g" % tuple(x) for x in en), rc.get("energy_max", float("nan")),
                      ", ".join("%.1e at t = %.3g" % (math.sqrt(E / rc["energy_max"]), t) for t, E in en if t > 5)))
    w("- An adaptive step costs more than a fixed one: every new step size is a new assembly and factorisation "
      "of the band matrix (BDF2: of its variable-step matrix), and the step is retried where a contact event is "
      "located; the large steps of the decay more than make up for it.")
    good = [r for r in long_rows if r["mode"] == "adaptive" and r["scheme"] != "euler" and r["param"] <= 1e-5
            and r["onset_err"] is not None]
    slopes = (rc.get("ref_onset_slope"), rc.get("ref_release_slope"))
    w("- The event times follow the accuracy of u(1,t), not error_tol alone: an error δ in u(1) moves a "
      "crossing of g by about δ / |du(1)/dt|%s. %s" % (
          ", and in the reference du(1)/dt is %.3g before the onset but %.3g before the release: the release "
          "is the sensitive one" % (slopes[0][0], slopes[1][0]) if all(slopes) else "",
          "The onset is located within %.1e by every adaptive BDF2 and midpoint run at error_tol <= 1e-5." % max(
              r["onset_err"] for r in good) if good else ""))
    w("")
    w("### Experiment 1 to t = %g at the accuracy of fixed Euler dt = 1e-4" % t_short)
    w("")
    if base_short:
        w("Fixed Euler dt = 1e-4 to t = %g: %.3g s (median of %d), max|du| over [0, %g] = %.2e: the accuracy to "
          "reach. Adaptive runs to t = %g (medians of %d runs):" % (
              t_short, base_short["wall"], base_short["runs"], t_short, base_short["max_du"], t_short,
              max(r["runs"] for r in short_rows)))
        w("")
        md.extend(table(short_rows))
        w("")
        if b_best:
            w("**Target (b)**: the cheapest adaptive run at least as accurate is %s adaptive, %s: %.3g s, max|du| "
              "%.2e, **%.1fx** less wall time than fixed Euler dt = 1e-4 (%.3g s)." % (
                  b_best["scheme"], param_str(b_best), b_best["wall"], b_best["max_du"],
                  base_short["wall"] / b_best["wall"], base_short["wall"]))
        else:
            w("**Target (b)**: no adaptive run reaches that accuracy.")
        w("")
    with open(os.path.join(outdir, "work_precision_adaptive.md"), "w") as f:
        f.write("\n".join(md).rstrip() + "\n")


def cmd_splice(args):
    """The section and the target rows of OUTDIR into DOC (docs/performance.md): the section
    '## Adaptive time steps: ...' replaced, the Targets table's rows of this benchmark (those
    starting '| exp1 to t = ') replaced by work_precision_adaptive_targets.txt's."""
    outdir, doc = args
    section = open(os.path.join(outdir, "work_precision_adaptive.md")).read().rstrip("\n").split("\n")
    rows = [l.rstrip("\n") for l in open(os.path.join(outdir, "work_precision_adaptive_targets.txt")) if l.strip()]
    lines = open(doc).read().rstrip("\n").split("\n")
    start = next((i for i, l in enumerate(lines) if l.startswith("## Adaptive time steps")), None)
    if start is not None:
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
        lines[start:end] = section + ([""] if end < len(lines) else [])
    else:
        lines += [""] + section
    t0 = next(i for i, l in enumerate(lines) if l == "## Targets")
    t1 = next(i for i in range(t0 + 1, len(lines)) if lines[i].startswith("## "))
    old = [i for i in range(t0, t1) if lines[i].startswith("| exp1 to t = ")]
    at = old[0] if old else max(i for i in range(t0, t1) if lines[i].startswith("|")) + 1
    lines = [l for i, l in enumerate(lines) if i not in old]
    lines[at:at] = rows
    with open(doc + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(doc + ".tmp", doc)


def main():
    cmds = {"points": cmd_points, "refcheck": cmd_refcheck, "report": cmd_report, "splice": cmd_splice}
    if len(sys.argv) < 2 or sys.argv[1] not in cmds:
        sys.exit(__doc__)
    cmds[sys.argv[1]](sys.argv[2:])


if __name__ == "__main__":
    main()
