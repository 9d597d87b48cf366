"""Post-processing of bench/work_precision_schemes.sh (plain text; any python3 will do).

    python3 bench/work_precision_schemes.py OUTDIR

Reads OUTDIR/wps_exp1.raw, wps_impact_{penalty,signorini}.raw, wps_impact_floor.raw (output
of rodcontact_work_precision uend/impact) and wps_meta.txt; writes
  OUTDIR/wps_{exp1,impact}.dat               one gnuplot data block per scheme (and law),
  OUTDIR/wps_params.gp                       the reference check, for the figure,
  OUTDIR/work_precision_schemes.md           the section of docs/performance.md.
Speed-up at an error level E: along each scheme's points, the stepping time at which the
error crosses E (log-log interpolation, work_precision.py's time_at); when a scheme's
cheapest point is already below E its time is an upper bound (ratio marked >=); when a
scheme never reaches E, its most expensive point's time is a lower bound (ratio marked >).
"""

import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'scripts', 'lib'))
import textfiles  # noqa: E402
from work_precision import time_at  # noqa: E402

SCHEMES = [("euler", "Euler"), ("bdf2", "BDF2"), ("midpoint", "midpoint")]
EXP1_ERRORS = [("e_uend_max", "max error of u(1,t), t in [0, T]"), ("e_uend_pre", "the same before contact"),
               ("e_theta_L2", "L2 theta at T (rel.)"), ("e_u_H1", "H1 u at T (rel.)")]


def read_lines(path):
    rows = []
    for line in open(path):
        words = line.split()
        if not words:
            continue
        d = dict(w.split("=", 1) for w in words[1:] if "=" in w)
        d["kind"] = words[0]
        for k, v in d.items():
            try:
                d[k] = float(v) if k not in ("scheme", "law", "problem", "kind", "s", "steps", "repeats") else v
            except ValueError:
                pass
        rows.append(d)
    return rows


def by_scheme(rows, scheme):
    return sorted((r for r in rows if r["kind"] == "point" and r["scheme"] == scheme), key=lambda r: -r["dt"])


def order(a, b, key):
    """observed order between two points (dt halved or so)"""
    if a[key] > 0 and b[key] > 0:
        return math.log(a[key] / b[key]) / math.log(a["dt"] / b["dt"])
    return None


def cell(seq, i, key):
    x = seq[i][key]
    o = order(seq[i - 1], seq[i], key) if i > 0 else None
    return "%.2e" % x + (" (%.2f)" % o if o is not None else "")


def time_bound(seq, key, level):
    """(time, kind): kind '=' interpolated, '<=' cheapest point already below, '>' never reached."""
    by_time = sorted(seq, key=lambda p: p["seconds"])
    if by_time and by_time[0][key] <= level:
        return by_time[0]["seconds"], "<="
    t = time_at(by_time, key, level)
    if t is not None:
        return t, "="
    return max(p["seconds"] for p in seq), ">"


def speedup(slow, fast, key, level):
    """'N', '>= N', '> N' or None (no bound): the time ratio slow/fast at error `level`."""
    ts, ks = time_bound(slow, key, level)
    tf, kf = time_bound(fast, key, level)
    ratio = ts / tf
    if ks == "=" and kf == "=":
        return "%.2g" % ratio
    if ks in ("=", ">") and kf in ("=", "<=") and ratio >= 1:     # a bound below 1 says nothing
        return ("> %.2g" if ks == ">" else "≥ %.2g") % ratio
    return None


def us_per_step(seq):
    return 1e6 * sorted(p["seconds"] / int(p["steps"]) for p in seq)[len(seq) // 2]


def orders(seq, key):
    o = [order(a, b, key) for a, b in zip(seq, seq[1:])]
    return min(o), max(o)


def at_dt(seq, dt):
    return next((p for p in seq if abs(p["dt"] - dt) <= 1e-9 * dt), None)


def exp1_reading(seqs, check):
    eu, bd, mp = seqs["euler"], seqs["bdf2"], seqs["midpoint"]
    lines = []
    lines.append("Cost per step (median over the dt of this run): Euler %.1f µs, BDF2 %.1f µs, midpoint %.1f µs; the "
                 "midpoint step is one solve as Euler's (with dt/2, then the extrapolation 2Y - X^{n-1}) and the "
                 "scalar contact equation, BDF2 also forms its level (4X^{n-1} - X^{n-2})/3. The per-step table above "
                 "(all cases round robin in one process) compares the per-step cost better; differences here beyond "
                 "it are the load of the shared machine." % (
                     us_per_step(eu), us_per_step(bd), us_per_step(mp)))
    lo, hi = orders(mp, "e_uend_max")
    blo, bhi = orders(bd, "e_uend_max")
    elo, ehi = orders(eu, "e_uend_max")
    text = ("u(1,t) over the whole window, through the contact (penalty eps = 0.01): the midpoint rule converges "
            "at order %.2f-%.2f, BDF2 irregularly at %.2f-%.2f, Euler at %.2f-%.2f." % (lo, hi, blo, bhi, elo, ehi))
    p_e, p_b, p_m = at_dt(eu, 1e-4), at_dt(bd, 1e-4), at_dt(mp, 1e-4)
    if p_e and p_b and p_m:
        text += (" At the paper's dt = 1e-4 the midpoint error is %.1e against BDF2's %.1e and Euler's %.1e (%.0fx "
                 "and %.0fx smaller) for %.2fx and %.2fx their stepping time." % (
                     p_m["e_uend_max"], p_b["e_uend_max"], p_e["e_uend_max"], p_b["e_uend_max"] / p_m["e_uend_max"],
                     p_e["e_uend_max"] / p_m["e_uend_max"], p_m["seconds"] / p_b["seconds"],
                     p_m["seconds"] / p_e["seconds"]))
    lines.append(text)
    lo, hi = orders(mp, "e_uend_pre")
    blo, bhi = orders(bd, "e_uend_pre")
    lines.append("Before the contact both second-order schemes are second order (midpoint %.2f-%.2f, BDF2 %.2f-%.2f) "
                 "with similar errors (BDF2/midpoint %.1f-%.1f at equal dt): there the midpoint rule gains little over "
                 "BDF2; its advantage on exp1 comes from the contact phase." % (
                     lo, hi, blo, bhi, min(b["e_uend_pre"] / m["e_uend_pre"] for b, m in zip(bd, mp)),
                     max(b["e_uend_pre"] / m["e_uend_pre"] for b, m in zip(bd, mp))))
    lo, hi = orders(mp, "e_theta_L2")
    blo, bhi = orders(bd, "e_theta_L2")
    lines.append("Where it does not help: the temperature at t = T converges at first order with every scheme "
                 "(midpoint %.2f-%.2f, BDF2 %.2f-%.2f), also before the contact (a run of the same command to "
                 "T = 0.15 gave order 1.0 for theta with the midpoint rule and BDF2); the midpoint error in theta is "
                 "%.1f-%.1fx smaller than BDF2's and %.0f-%.0fx smaller than Euler's at equal dt, a constant, not an "
                 "order. The H1 error of u at T converges at order %.2f-%.2f (midpoint). The chemical potential P "
                 "is left out of the table: its relative L2 error at T is large for every scheme (%.1f%% for the "
                 "midpoint rule at dt = %.3g, %.1f%% for BDF2, %.0f%% for Euler; first order; the reference check "
                 "differs by %.2f%%; raw data in `out/bench/wps_exp1.raw`)." % (
                     lo, hi, blo, bhi, min(b["e_theta_L2"] / m["e_theta_L2"] for b, m in zip(bd, mp)),
                     max(b["e_theta_L2"] / m["e_theta_L2"] for b, m in zip(bd, mp)),
                     min(e["e_theta_L2"] / m["e_theta_L2"] for e, m in zip(eu, mp)),
                     max(e["e_theta_L2"] / m["e_theta_L2"] for e, m in zip(eu, mp)), *orders(mp, "e_u_H1"),
                     100 * mp[-1]["e_P_L2"], mp[-1]["dt"], 100 * bd[-1]["e_P_L2"], 100 * eu[-1]["e_P_L2"],
                     100 * check["e_P_L2"]))
    return lines


def impact_reading(seqs, floor):
    pen = {s: seqs[("penalty", s)] for s, _ in SCHEMES}
    sig = {s: seqs[("signorini", s)] for s, _ in SCHEMES}
    lines = []
    space = next(r for r in floor if r["s"] == "1000")["e_uend_pre"]
    elo, ehi = orders(pen["euler"], "e_uend_pre")
    lines.append("Pre-contact u(1,t): Euler is first order (%.2f-%.2f); BDF2 and the midpoint rule are second order "
                 "(their first orders: %.2f and %.2f) until they reach the space error of s = 1000 (%.1e) at "
                 "dt ~ 2.5e-4; below it the error is the mesh's (it even grows a little towards the semi-discrete "
                 "value as the time error that partly cancelled it vanishes) and says nothing about the schemes. "
                 "BDF2 and midpoint are equally accurate here (BDF2's error is %.2fx the midpoint's at dt = 1e-3)." % (
                     elo, ehi, order(pen["bdf2"][0], pen["bdf2"][1], "e_uend_pre"),
                     order(pen["midpoint"][0], pen["midpoint"][1], "e_uend_pre"), space,
                     pen["bdf2"][0]["e_uend_pre"] / pen["midpoint"][0]["e_uend_pre"]))
    mp = pen["midpoint"]
    rise = max(p["max_rise"] for p in mp)
    lines.append("Energy, penalty law: with the midpoint rule E^n %s (largest one-step change %+.0e of E(0), "
                 "round-off), and the drift E(T)/E(0) - 1 (%.1e at dt = %.3g to %.1e at dt = %.3g, order %.2f) is "
                 "what the two damped Euler start-up steps cost (docs/scheme.md). Euler loses %.0f-%.0f%% (order "
                 "%.2f: the numerical damping of the waves), BDF2 %.2f-%.1f%% (order %.2f). At its cheapest point "
                 "(%.2g s) the midpoint drift is %.0fx smaller than BDF2's most expensive point (%.2g s) and %.0fx "
                 "smaller than Euler's: at equal drift the ratio is beyond what these runs can measure." % (
                     "never rises" if rise < 1e-12 else "**rises**", rise, abs(mp[0]["drift"]), mp[0]["dt"],
                     abs(mp[-1]["drift"]), mp[-1]["dt"], orders(mp, "abs_drift")[0],
                     100 * abs(pen["euler"][-1]["drift"]), 100 * abs(pen["euler"][0]["drift"]),
                     orders(pen["euler"], "abs_drift")[0], 100 * abs(pen["bdf2"][-1]["drift"]),
                     100 * abs(pen["bdf2"][0]["drift"]), orders(pen["bdf2"], "abs_drift")[0], mp[0]["seconds"],
                     abs(pen["bdf2"][-1]["drift"]) / abs(mp[0]["drift"]), pen["bdf2"][-1]["seconds"],
                     abs(pen["euler"][-1]["drift"]) / abs(mp[0]["drift"])))
    ms = sig["midpoint"]
    drifts = [abs(p["drift"]) for p in ms]
    bdf2_rises = ", ".join("%+.1e (dt = %.3g)" % (p["max_rise"], p["dt"]) for p in sig["bdf2"] if p["max_rise"] > 1e-12)
    bdf2_pen_rises = ", ".join("%+.1e (dt = %.3g)" % (p["max_rise"], p["dt"]) for p in pen["bdf2"]
                               if p["max_rise"] > 1e-12)
    rises = [p["max_rise"] for p in sig["bdf2"]]
    growing = all(b > a for a, b in zip(rises, rises[1:]) if a > 1e-12)
    lines.append("Energy, Signorini law: here refining dt does not help the midpoint rule: its drift stays at "
                 "%.1e-%.1e of E(0) for every dt (not monotone in dt). It is the energy the impacts remove at the "
                 "contact node (the constraint is imposed at the end of the step, docs/scheme.md; the first impact "
                 "removes about half the node's kinetic energy (rho h/2) v^2/2, docs/verification.md), which depends "
                 "on the mesh, not on dt; at the finest dt BDF2's drift (%.1e) is within %.1fx of it. What the "
                 "midpoint rule keeps is the law: E^n %s (largest one-step change %+.0e), while BDF2's E^n rises at "
                 "impacts, %s%s%s." % (
                     min(drifts), max(drifts), abs(sig["bdf2"][-1]["drift"]),
                     abs(sig["bdf2"][-1]["drift"]) / abs(ms[-1]["drift"]),
                     "never rises" if max(p["max_rise"] for p in ms) < 1e-12 else "**rises**",
                     max(p["max_rise"] for p in ms), bdf2_rises or "never in these runs",
                     ", more as dt decreases" if bdf2_rises and growing else "",
                     ("; with the penalty law too: " + bdf2_pen_rises) if bdf2_pen_rises else ""))
    return lines


def main():
    outdir = sys.argv[1]
    meta = textfiles.read_meta(os.path.join(outdir, "wps_meta.txt"))
    exp1 = read_lines(os.path.join(outdir, "wps_exp1.raw"))
    impact = {law: read_lines(os.path.join(outdir, "wps_impact_%s.raw" % law)) for law in ("penalty", "signorini")}
    floor = read_lines(os.path.join(outdir, "wps_impact_floor.raw"))
    ref = next(r for r in exp1 if r["kind"] == "reference")
    check = next(r for r in exp1 if r["kind"] == "reference_check")
    exp1_seqs = {s: by_scheme(exp1, s) for s, _ in SCHEMES}
    imp_seqs = {(law, s): by_scheme(impact[law], s) for law in impact for s, _ in SCHEMES}
    for seq in imp_seqs.values():
        for p in seq:
            p["abs_drift"] = abs(p["drift"])

    # ---------------------------------------------------------------- gnuplot data
    with open(os.path.join(outdir, "wps_exp1.dat"), "w") as f:
        for i, (s, name) in enumerate(SCHEMES):
            f.write("# index %d: %s\n# dt steps seconds e_uend_max e_uend_pre e_theta_L2 e_u_H1\n" % (i, name))
            for p in exp1_seqs[s]:
                f.write("%.6g %s %.6g %.6g %.6g %.6g %.6g\n" % (p["dt"], p["steps"], p["seconds"], p["e_uend_max"],
                                                            p["e_uend_pre"], p["e_theta_L2"], p["e_u_H1"]))
            f.write("\n\n")
    with open(os.path.join(outdir, "wps_impact.dat"), "w") as f:
        i = 0
        for law in ("penalty", "signorini"):
            for s, name in SCHEMES:
                f.write("# index %d: %s, %s\n# dt steps seconds e_uend_pre abs_drift max_rise\n" % (i, name, law))
                for p in imp_seqs[(law, s)]:
                    f.write("%.6g %s %.6g %.6g %.6g %.6g\n" % (p["dt"], p["steps"], p["seconds"], p["e_uend_pre"],
                                                               p["abs_drift"], p["max_rise"]))
                f.write("\n\n")
                i += 1
    fine_floor = min(floor, key=lambda r: r["dt"])
    with open(os.path.join(outdir, "wps_params.gp"), "w") as f:
        f.write("exp1_refcheck = %.6g\n" % check["e_uend_max"])
        f.write("exp1_tend = '%s'\n" % meta.get("exp1_tend", "?"))
        f.write("impact_tend = '%s'\n" % meta.get("impact_tend", "?"))
        f.write("impact_floor = %.6g\n" % next(r for r in floor if r["s"] == "1000")["e_uend_pre"])

    # ---------------------------------------------------------------- Markdown
    md = []
    w = md.append
    tend = meta.get("exp1_tend", "?")
    w("## Work-precision of the time schemes: Euler, BDF2 and the midpoint rule")
    w("")
    w("Written by `bench/work_precision_schemes.sh` (run by `bench.sh`, section 5; alone: "
      "`bench/work_precision_schemes.sh`, about 2.5 minutes on 2 cores); program `bench/work_precision.f90`, "
      "modes `uend` and `impact`. ![work-precision of the time schemes](../figures/work_precision_schemes.png)")
    w("")
    w("Only the steps are timed: each `stepper%%advance` alone, summed over the run (the recording of u(1,t) and "
      "of E^n after each step is outside the clock); the points of one command were run round robin, %s rounds, "
      "and the median is given (the reference and its check once). "
      "Load average %s at the start, %s at the end (2 cores). BLAS/LAPACK loaded (ldd): %s (a step calls "
      "neither). Commit %s." % (
          "/".join(sorted({p["repeats"] for seq in exp1_seqs.values() for p in seq})),
          meta.get("load_start", "?"), meta.get("load_end", "?"), meta.get("blas", "?").strip(" ;"),
          meta.get("commit", "?")))
    w("")

    # exp1
    w("### (a) Experiment 1: the time error of u(1,t)")
    w("")
    w("    build/bench/rodcontact_work_precision uend input/exp1.nml %s %s:500:%s <scheme>:500:<dt> ..." % (
        tend, ref["scheme"], ref["dt"]))
    w("")
    w("input/exp1.nml (h = 1/500, eps = 0.01, the paper's dt is 1e-4), every run on the reference's mesh, so only "
      "the time error is measured, to T = %s: the contact lasts from t ~ 0.19 to t ~ 1.45. Errors against a "
      "%s run with dt = %.3g (%s steps, %.1f s of stepping): the largest abs(u(1,t_n) - u_ref(1,t_n)) over all steps "
      "t_n <= T, the same over the steps before the reference's first contact (t < %.4f), and the relative L2 "
      "error of theta and H1 error of u at t = T (the snapshot fields). In brackets the observed order between "
      "successive dt." % (tend, ref["scheme"], ref["dt"], ref["steps"], ref["seconds"], ref["t_contact"]))
    w("")
    best = {key: min(p[key] for seq in exp1_seqs.values() for p in seq) for key, _ in EXP1_ERRORS}
    w("**Reference check**: a %s run with dt = %.3g differs from the reference by %s. The reference's own error "
      "is at most this difference (about a third of it at order 2); the smallest error of any point below is %s: "
      "the reference is %s." % (
          check["scheme"], check["dt"],
          ", ".join("%.1e (%s)" % (check[k], n) for k, n in EXP1_ERRORS),
          ", ".join("%.1e" % best[k] for k, _ in EXP1_ERRORS),
          "; ".join("%.0fx more accurate for %s%s" % (best[k] / check[k], n,
                                                      "" if best[k] / check[k] >= 10 else " (**less than 10x**: "
                                                      "the smallest errors of this column are uncertain by up to "
                                                      "%.0f%%)" % (100 * check[k] / best[k]))
                    for k, n in EXP1_ERRORS)))
    w("")
    w("| scheme | dt | steps | stepping time [s] | " + " | ".join("%s (order)" % n for _, n in EXP1_ERRORS) + " |")
    w("|---|---:|---:|---:|" + "---:|" * len(EXP1_ERRORS))
    for s, name in SCHEMES:
        seq = exp1_seqs[s]
        for i, p in enumerate(seq):
            w("| %s | %.3g | %s | %.3g | %s |" % (name, p["dt"], p["steps"], p["seconds"],
                                                 " | ".join(cell(seq, i, k) for k, _ in EXP1_ERRORS)))
    w("")
    w("Time ratio at equal error (stepping time of the slower scheme / the faster one, log-log interpolation "
      "between points; ≥: the faster scheme's cheapest point is already below the level, so its time there is "
      "at most that point's; >: the slower scheme does not reach the level in these runs, its most expensive "
      "point's time is used; –: no bound, e.g. both schemes already below the level at their cheapest point):")
    w("")
    w("| error | level | Euler / midpoint | BDF2 / midpoint | Euler / BDF2 |")
    w("|---|---:|---:|---:|---:|")
    for key, name in EXP1_ERRORS[:2]:
        for level in (1e-5, 1e-6, 1e-7, 1e-8):
            cells = [speedup(exp1_seqs[a], exp1_seqs[b], key, level) for a, b in
                     (("euler", "midpoint"), ("bdf2", "midpoint"), ("euler", "bdf2"))]
            if any(cells):
                w("| %s | %.0e | %s |" % (name, level, " | ".join(c or "–" for c in cells)))
    w("")

    w("Reading:")
    w("")
    for line in exp1_reading(exp1_seqs, check):
        w("- " + line)
    w("")

    # impact
    itend = meta.get("impact_tend", "?")
    w("### (b) The impact case: exact pre-contact solution and energy")
    w("")
    w("    build/bench/rodcontact_work_precision impact input/impact.nml %s penalty|signorini <scheme>:1000:<dt> ..." %
      itend)
    w("")
    w("input/impact.nml (elastic bar, rho = alpha = 1, no dissipation, s = 1000, penalty eps = 1e-4 or the "
      "Signorini law) to t = %s. Pre-contact error: max over t_n < 1 - sqrt(0.9) = %.5f of "
      "abs(u(1,t_n) - (t_n - t_n^2/2)) against the exact solution, so it holds the space error too: its floor is the "
      "P1 error at s = 1000 (a midpoint run with s = 1000, dt = %.3g has %.1e; with s = %s, dt = %.3g, %.1e; "
      "`impact input/impact.nml 0.1 penalty ...`). The PDE conserves the energy: E(T)/E(0) - 1 is the scheme's "
      "drift, and the largest one-step change max_n (E^n - E^{n-1})/E(0) is negative when E^n never rises (round-off "
      "is ~1e-15). The pre-contact error is the same for both laws (listed once)." % (
          itend, floor[0]["t_onset"], floor[0]["dt"], floor[0]["e_uend_pre"], fine_floor["s"], fine_floor["dt"],
          fine_floor["e_uend_pre"]))
    w("")
    w("| scheme | dt | steps | stepping time, penalty [s] | pre-contact error (order) | penalty: E(T)/E(0) - 1 "
      "(order) | penalty: largest one-step change of E^n | Signorini: E(T)/E(0) - 1 | Signorini: largest "
      "one-step change of E^n |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for s, name in SCHEMES:
        pen, sig = imp_seqs[("penalty", s)], imp_seqs[("signorini", s)]
        for i, (p, q) in enumerate(zip(pen, sig)):
            w("| %s | %.3g | %s | %.3g | %s | %+.2e%s | %+.1e | %+.2e | %+.1e |" % (
                name, p["dt"], p["steps"], p["seconds"], cell(pen, i, "e_uend_pre"), p["drift"],
                " (%.2f)" % order(pen[i - 1], p, "abs_drift") if i > 0 else "", p["max_rise"], q["drift"],
                q["max_rise"]))
    w("")
    w("Time ratio at equal error (as in (a)):")
    w("")
    w("| error | level | Euler / midpoint | BDF2 / midpoint | Euler / BDF2 |")
    w("|---|---:|---:|---:|---:|")
    rows = [("pre-contact error of u(1,t)", "penalty", "e_uend_pre", (1e-5, 1e-6)),
            ("penalty: abs(E(T)/E(0) - 1)", "penalty", "abs_drift", (1e-1, 1e-2, 1e-3)),
            ("Signorini: abs(E(T)/E(0) - 1)", "signorini", "abs_drift", (1e-1, 1e-2, 3e-3))]
    for name, law, key, levels in rows:
        for level in levels:
            cells = [speedup(imp_seqs[(law, a)], imp_seqs[(law, b)], key, level) for a, b in
                     (("euler", "midpoint"), ("bdf2", "midpoint"), ("euler", "bdf2"))]
            if any(cells):
                w("| %s | %.0e | %s |" % (name, level, " | ".join(c or "–" for c in cells)))
    w("")
    w("Reading:")
    w("")
    for line in impact_reading(imp_seqs, floor):
        w("- " + line)
    w("")
    with open(os.path.join(outdir, "work_precision_schemes.md"), "w") as f:
        f.write("\n".join(md) + "\n")


if __name__ == "__main__":
    main()
