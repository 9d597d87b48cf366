#!/usr/bin/env python3
"""Benchmark of the impact case against its exact solution (tests/tools/exact_impact.py): every
time scheme x contact law x velocity mass (&contact mass) on input/impact.nml and two other
(g, A) pairs, at S = 1000 (dt = 2.5e-4), with S = 500 and 2000 (dt = S^-1/4) on impact.nml's
pair for the order; adaptive midpoint/Signorini runs on every pair, and on impact.nml the time error
of fixed and adaptive steps against a fixed-step reference (time accuracy at equal work). Writes the section between
<!-- impact-bench:begin --> and <!-- impact-bench:end --> of docs/performance.md, the raw
measures (OUT/impact.json) and figures/impact_sigma.png (sigma(1,t) of each scheme against the
exact one). Called by bench/impact.sh (which builds first).

    bench/impact.py EXE REPO OUT [--quick]
"""
import json
import math
import os
import signal
import subprocess
import sys
import time

REPO = None
QUICK_PAIRS = [(0.05, 1.0)]
PAIRS = [(0.05, 1.0), (0.1, 0.5), (0.02, 1.5)]
SCHEMES = ["euler", "bdf2", "midpoint"]
LAWS = ["signorini", "penalty"]
MASSES = ["consistent", "redistributed"]
BEGIN, END = "<!-- impact-bench:begin -->", "<!-- impact-bench:end -->"
TIME_LIMIT = 60.0   # seconds of wall time per run; a run that takes longer is stopped and reported
TARGET = dict(u_err=2.4e-3, sigma_rel=3e-2, tv=0.10, drift=1e-4)
ADAPTIVE_TOLS = (1e-4, 1e-5, 1e-6, 1e-7)
#: the first step of the adaptive runs (&time dt): the midpoint rule's first two steps are damped Euler
#: steps (time_scheme_m), which lose about dt^2 of the energy (3.75e-7 of E(0) at dt = 2.5e-4)
ADAPTIVE_FIRST_DT = 1e-6
FIXED_REPEATS = 3            # the fixed-step run each adaptive wall time is divided by: median of this many
#: time accuracy at equal work (impact.nml): fixed steps of these sizes and a reference of REF_DT, with
#: snapshots every WP_SNAPSHOT_DT (both step kinds land on them)
WP_DTS = (2.5e-4, 1.25e-4, 5e-5, 2.5e-5)
REF_DT = 2.5e-4 / 32
WP_SNAPSHOT_DT = 0.5


def run(exe, out, g, A, scheme, law, mass, S, extra=(), keep=False, dt=None, snapshots=False, repeat=0):
    """One run's measures (exact_impact.compare_run, the steps rejected); snapshots: also the
    snapshots' t, u and v (key "snap", not written to impact.json)."""
    dt = 0.25 / S if dt is None else dt
    tag = f"{scheme}_{law}_{mass}_g{g}_A{A}_S{S}_dt{dt:g}_r{repeat}" + "".join("_" + e.split("=")[0].split(".")[-1] + e.split("=")[1]
                                                          for e in extra)
    prefix = os.path.join(out, tag)
    cmd = [exe, os.path.join(REPO, "input", "impact.nml"), "--set", f"time.scheme='{scheme}'",
           "--set", f"contact.law='{law}'", "--set", f"contact.mass='{mass}'", "--set", f"contact.g={g}",
           "--set", f"initial.u1_poly=0,{A}", "--set", f"mesh.n_elements={S}", "--set", f"time.dt={dt}",
           "--set", f"output.prefix='{prefix}'", "--set", "output.quiet=.true.",
           "--set", "output.snapshot_every=1000000000"]
    for e in extra:
        cmd += ["--set", e]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL)
    try:
        proc.wait(timeout=TIME_LIMIT)
    except subprocess.TimeoutExpired:
        proc.send_signal(signal.SIGTERM)     # rodcontact stops cleanly and leaves PREFIX.h5.part
        proc.wait()
        import h5py
        with h5py.File(prefix + ".h5.part", "r") as f:
            t_reached, steps = float(f["series/t"][-1]), int(f["series/t"].shape[0]) - 1
        os.remove(prefix + ".h5.part")
        return dict(scheme=scheme, law=law, mass=mass, S=S, dt=dt, extra=list(extra), unfinished=True,
                    t_reached=t_reached, steps=steps, wall=float(TIME_LIMIT))
    if proc.returncode != 0:
        raise SystemExit(f"impact: {' '.join(cmd)}: exit {proc.returncode}")
    m = exact_impact.compare_run(prefix + ".h5")
    m.update(scheme=scheme, law=law, mass=mass, S=S, dt=dt, file=prefix + ".h5", extra=list(extra))
    import h5py
    with h5py.File(prefix + ".h5", "r") as f:
        m["rejected"] = int(f.attrs.get("time_steps_rejected", 0))
        if snapshots:
            m["snap"] = dict(t=f["snapshots/t"][:], u=f["snapshots/u"][:], v=f["snapshots/v"][:], x=f["mesh/x"][:])
    if not keep:
        os.remove(prefix + ".h5")
    return m


def tv_cell(m):
    if not m["tv"]:
        return "–"
    return ", ".join(f"{100 * (r / e - 1):+.0f} %" if e > 0 else "–" for _, _, r, e in m["tv"])


def row(m):
    return (f"| {m['scheme']} | {m['law']} | {m['mass']} | {m['S']} | {m['u_err']:.2e} | {m['u_max_minus_g']:+.1e} | "
            f"{m['sigma_err_rel']:.2e} | {tv_cell(m)} | {m['events']} ({m['events_exact']}) | "
            f"{m['energy_drift']:+.2e} | {m['energy_max_rise']:+.1e} | {m['wall']:.2f} |")


HEADER = ("| scheme | law | mass | S | max abs u(1,t) error | max u(1,t) - g | sigma L2 error / norm | "
          "sigma TV vs exact, per contact interval | events (exact) | E(4)/E(0) - 1 | largest one-step rise of E/E(0) | wall s |\n"
          "|---|---|---|---:|---:|---:|---:|---|---:|---:|---:|---:|")


def meets(m):
    fails = []
    if m["events"] != m["events_exact"]:
        fails.append("events")
    if any(abs(r / e - 1) > TARGET["tv"] for _, _, r, e in m["tv"] if e > 0):
        fails.append("TV")
    if m["sigma_err_rel"] > TARGET["sigma_rel"]:
        fails.append("sigma L2")
    if m["u_max_minus_g"] > 0:
        fails.append("u > g")
    if m["energy_max_rise"] > 1e-13 or abs(m["energy_drift"]) > TARGET["drift"]:
        fails.append("energy")
    if m["u_err"] > TARGET["u_err"]:
        fails.append("u error")
    return fails


def figure(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    ex = exact_impact.ExactImpact(0.05, 1.0, 4.0)
    fig, axes = plt.subplots(len(SCHEMES), 2, figsize=(13, 10), sharex="col")
    tt = np.linspace(0, 4, 4001)
    for i, scheme in enumerate(SCHEMES):
        for j, (lo, hi) in enumerate([(0.0, 1.1), (3.3, 4.0)]):
            ax = axes[i][j]
            for mass, style in (("consistent", dict(color="tab:red", lw=0.6, alpha=0.7)),
                                ("redistributed", dict(color="tab:blue", lw=1.4))):
                m = results[(scheme, mass)]
                import h5py
                with h5py.File(m["file"], "r") as f:
                    t, cs = f["series/t"][:], f["series/contact_stress"][:]
                k = (t >= lo) & (t <= hi)
                ax.plot(t[k], cs[k], label=f"{mass} mass", **style)
            k = (tt >= lo) & (tt <= hi)
            ax.plot(tt[k], ex.sigma_end(tt[k]), "k--", lw=1.2, label="exact")
            ax.set_ylim(-1.6, 0.2)
            ax.grid(alpha=0.3)
            ax.set_title(f"{scheme}, Signorini, S = 1000, dt = 2.5e-4: t in [{lo}, {hi}]", fontsize=10)
            if j == 0:
                ax.set_ylabel("sigma(1, t)")
            if i == len(SCHEMES) - 1:
                ax.set_xlabel("t")
            if i == 0 and j == 0:
                ax.legend(loc="lower right", fontsize=9)
    fig.suptitle("Impact case (input/impact.nml, g = 0.05, A = 1): /series/contact_stress against the exact sigma(1, t)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def main():
    global REPO, exact_impact
    exe, REPO, out = sys.argv[1], sys.argv[2], sys.argv[3]
    quick = "--quick" in sys.argv[4:]
    sys.path.insert(0, os.path.join(REPO, "tests", "tools"))
    import exact_impact as ei
    exact_impact = ei
    os.makedirs(out, exist_ok=True)
    pairs = QUICK_PAIRS if quick else PAIRS
    t0 = time.time()
    results, fig_runs = [], {}
    for g, A in pairs:
        for scheme in SCHEMES:
            for law in LAWS:
                for mass in MASSES:
                    drawn = (g, A) == (0.05, 1.0) and law == "signorini"
                    m = run(exe, out, g, A, scheme, law, mass, 1000, keep=drawn)
                    results.append(m)
                    if drawn:
                        fig_runs[(scheme, mass)] = m
    refine = []
    if not quick:
        for S in (500, 2000):
            for scheme in SCHEMES:
                for mass in MASSES:
                    refine.append(run(exe, out, 0.05, 1.0, scheme, "signorini", mass, S))
    adaptive, fixed_walls = [], {}
    for g, A in pairs:
        fixed_walls[(g, A)] = [m["wall"] for m in results if (m["g"], m["A"]) == (g, A) and m["scheme"] == "midpoint"
                               and m["law"] == "signorini" and m["mass"] == "redistributed"]
        # on impact.nml, snapshots for the time accuracy (work_precision; the steps land on them)
        snap = not quick and (g, A) == (0.05, 1.0)
        for tol in ((1e-5,) if quick else ADAPTIVE_TOLS):
            extra = ("time.adaptive=.true.", f"time.error_tol={tol}") + \
                ((f"output.snapshot_dt={WP_SNAPSHOT_DT}",) if snap else ())
            adaptive.append(run(exe, out, g, A, "midpoint", "signorini", "redistributed", 1000, extra,
                                dt=ADAPTIVE_FIRST_DT, snapshots=snap))
            # the fixed-step run again, next to the adaptive ones (the median of FIXED_REPEATS)
            if len(fixed_walls[(g, A)]) < FIXED_REPEATS:
                fixed_walls[(g, A)].append(run(exe, out, g, A, "midpoint", "signorini", "redistributed", 1000,
                                               repeat=len(fixed_walls[(g, A)]))["wall"])
    precision = [] if quick else work_precision(exe, out, adaptive)
    figpath = os.path.join(out, "impact_sigma_quick.png") if quick else os.path.join(REPO, "figures", "impact_sigma.png")
    figure(fig_runs, figpath)
    for m in list(fig_runs.values()):
        if os.path.exists(m["file"]):
            os.remove(m["file"])
    with open(os.path.join(out, "impact.json"), "w") as f:
        json.dump(dict(results=results, refine=refine, adaptive=[{k: v for k, v in m.items() if k != "snap"}
                                                                  for m in adaptive],
                       fixed_walls={f"{g},{A}": w for (g, A), w in fixed_walls.items()}, precision=precision),
                  f, indent=1, default=str)
    md = section(results, refine, adaptive, time.time() - t0, quick, fixed_walls, precision)
    if quick:
        print(md)
        return 0
    doc = os.path.join(REPO, "docs", "performance.md")
    text = open(doc).read()
    a, b = text.find(BEGIN), text.find(END)
    if a < 0 or b < 0:
        raise SystemExit(f"{doc}: no {BEGIN} ... {END} markers")
    text = text[:a + len(BEGIN)] + "\n" + md + "\n" + text[b:]
    open(doc, "w").write(text)
    print(f"impact: wrote the impact section of {doc} and {figpath}", file=sys.stderr)
    return 0


def energy_distance(a, b):
    """max over the snapshots of sqrt(int (v_a - v_b)^2 + int ((u_a - u_b)_x)^2) (rho = alpha = 1;
    trapezoidal v, exact for the piecewise linear u), and its value at the last snapshot."""
    import numpy as np
    h = np.diff(a["x"])
    du, dv = a["u"] - b["u"], a["v"] - b["v"]
    kinetic = np.sum(0.5 * (dv[:, 1:] ** 2 + dv[:, :-1] ** 2) * h, axis=1)
    strain = np.sum((np.diff(du, axis=1) / h) ** 2 * h, axis=1)
    d = np.sqrt(kinetic + strain)
    return float(d.max()), float(d[-1])


def work_precision(exe, out, adaptive):
    """Time error at equal work on impact.nml (S = 1000): fixed steps of WP_DTS and the adaptive
    runs against a fixed-step reference of REF_DT, in the energy norm over the snapshots (every
    WP_SNAPSHOT_DT; the adaptive steps land on them), relative to |X(0)|_E = sqrt(2 E(0))."""
    import numpy as np
    snap = (f"output.snapshot_dt={WP_SNAPSHOT_DT}",)
    ref = run(exe, out, 0.05, 1.0, "midpoint", "signorini", "redistributed", 1000, snap, dt=REF_DT, snapshots=True)
    scale = math.sqrt(2.0 / 6.0)     # |X(0)|_E = sqrt(2 E(0)), E(0) = A^2/6 with A = 1
    rows = []
    for dt in WP_DTS:
        m = run(exe, out, 0.05, 1.0, "midpoint", "signorini", "redistributed", 1000, snap, dt=dt, snapshots=True)
        worst, last = energy_distance(m["snap"], ref["snap"])
        rows.append(dict(kind="fixed", dt=dt, steps=m["steps"], err=worst / scale, err_end=last / scale,
                         wall=m["wall"]))
    for m in adaptive:
        if "snap" not in m or m.get("unfinished"):
            continue
        tol = [e.split("=")[1] for e in m["extra"] if "error_tol" in e][0]
        worst, last = energy_distance(m["snap"], ref["snap"])
        rows.append(dict(kind="adaptive", tol=tol, steps=m["steps"], err=worst / scale, err_end=last / scale,
                         wall=m["wall"]))
    fixed = [r for r in rows if r["kind"] == "fixed"]
    le, lw = np.log([r["err"] for r in fixed]), np.log([r["wall"] for r in fixed])
    for r in rows:
        if r["kind"] == "adaptive":
            # the wall time of a fixed-step run of the same time error: log-log interpolation (extrapolated
            # beyond the rows with the last two rows' slope)
            order = np.argsort(le)
            x, y = le[order], lw[order]
            if math.log(r["err"]) <= x[0]:
                slope = (y[1] - y[0]) / (x[1] - x[0])
                r["fixed_wall_same_err"] = float(math.exp(y[0] + slope * (math.log(r["err"]) - x[0])))
                r["extrapolated"] = True
            else:
                r["fixed_wall_same_err"] = float(math.exp(np.interp(math.log(r["err"]), x, y)))
                r["extrapolated"] = False
    ref_row = dict(kind="reference", dt=REF_DT, steps=ref["steps"], wall=ref["wall"])
    return [ref_row] + rows


def section(results, refine, adaptive, seconds, quick, fixed_walls, precision):
    L = []
    w = L.append
    load = os.getloadavg()[0]
    w(f"Written by `bench/impact.sh` ({seconds:.0f} s, load average {load:.1f} on 2 cores at the end; wall times are "
      "one run each, noisy). Exact solution: `tests/tools/exact_impact.py` (characteristics). Measures: max over the "
      "steps of abs(u(1,t_n) - exact); sigma: `/series/contact_stress` of step n against the exact mean "
      "(1/dt) int sigma(1,t) dt over the step, L2 in time, divided by the exact norm of sigma (0.767 for impact.nml); "
      "TV: total variation of the step values over the steps at least 0.02 inside each exact contact interval, against "
      "the exact step means' TV on the same steps; events: `/events` (exact: onset, release, onset). Penalty: eps = 1e-4.")
    w("")
    for pair in sorted({(m["g"], m["A"]) for m in results}, key=lambda p: (p != (0.05, 1.0), p)):
        g, A = pair
        ex = exact_impact.ExactImpact(g, A, 4.0)
        ev = ", ".join(f"{t:.4f}" for t, _ in ex.events)
        w(f"**g = {g}, A = {A}**{' (input/impact.nml)' if pair == (0.05, 1.0) else ''}: exact events at t = {ev}; "
          f"norm of sigma {ex.sigma_l2():.3f}. S = 1000, dt = 2.5e-4.")
        w("")
        w(HEADER)
        for m in results:
            if (m["g"], m["A"]) == pair:
                w(row(m))
        w("")
    if refine:
        w("**Refinement** (impact.nml, Signorini, dt = S^-1/4):")
        w("")
        w(HEADER)
        for m in sorted(refine + [r for r in results if (r["g"], r["A"]) == (0.05, 1.0) and r["law"] == "signorini"],
                        key=lambda r: (r["scheme"], r["mass"], r["S"])):
            w(row(m))
        w("")
    w("**Adaptive steps** (midpoint, Signorini, redistributed mass, S = 1000; a contact event is located and "
      "stepped over: the step that changes the contact state is cut to end at the event, docs/scheme.md; first "
      f"step &time dt = {ADAPTIVE_FIRST_DT:g}, as the midpoint rule's two damped Euler start-up steps lose about "
      "dt^2 of the energy, 3.75e-7 of E(0) at dt = 2.5e-4; on impact.nml snapshots every "
      f"{WP_SNAPSHOT_DT:g}, which the steps land on, for the time accuracy below). Wall / fixed: the run's wall time over the median of "
      f"{FIXED_REPEATS} runs of the fixed-step row above (dt = 2.5e-4), run in the same loop:")
    w("")
    w("| g, A | error_tol | steps | rejected | max abs u(1,t) error | sigma L2 error / norm | sigma TV vs exact | "
      "events (exact) | E(4)/E(0) - 1 | wall s | wall / fixed |")
    w("|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|")
    import statistics
    for m in adaptive:
        tol = [e.split("=")[1] for e in m["extra"] if "error_tol" in e][0]
        if m.get("unfinished"):
            w(f"| {m.get('g', '')}, {m.get('A', '')} | {tol} | {m['steps']} | – | did not finish: stopped after "
              f"{TIME_LIMIT:.0f} s at t = {m['t_reached']:.6g} | – | – | – | – | – | – |")
            continue
        fixed = statistics.median(fixed_walls[(m["g"], m["A"])])
        w(f"| {m['g']}, {m['A']} | {tol} | {m['steps']} | {m['rejected']} | {m['u_err']:.2e} | "
          f"{m['sigma_err_rel']:.2e} | {tv_cell(m)} | {m['events']} ({m['events_exact']}) | "
          f"{m['energy_drift']:+.2e} | {m['wall']:.2f} | {m['wall'] / fixed:.1f} |")
    w("")
    if precision:
        ref = precision[0]
        w(f"**Time accuracy at equal work** (impact.nml, S = 1000): the time error of each run against a fixed-step "
          f"reference (dt = {ref['dt']:.4g}, {ref['steps']} steps, {ref['wall']:.1f} s), in the energy norm "
          "sqrt(int v^2 + int u_x^2) of the difference at the snapshots t = 0.5, 1, ..., 4 (both step kinds land on "
          "them), relative to sqrt(2 E(0)); the largest over the snapshots. For an adaptive run, the wall time a "
          "fixed-step run of the same time error takes (log-log interpolation between the fixed rows; * extrapolated "
          "beyond the finest):")
        w("")
        w("| run | steps | time error (max over snapshots) | at t = 4 | wall s | fixed-step wall s at the same error | "
          "ratio |")
        w("|---|---:|---:|---:|---:|---:|---:|")
        for r in precision[1:]:
            if r["kind"] == "fixed":
                w(f"| fixed dt = {r['dt']:g} | {r['steps']} | {r['err']:.2e} | {r['err_end']:.2e} | {r['wall']:.2f} | "
                  "– | – |")
            else:
                star = "*" if r["extrapolated"] else ""
                w(f"| adaptive error_tol = {r['tol']} | {r['steps']} | {r['err']:.2e} | {r['err_end']:.2e} | "
                  f"{r['wall']:.2f} | {r['fixed_wall_same_err']:.2f}{star} | "
                  f"{r['wall'] / r['fixed_wall_same_err']:.2f} |")
        w("")
    w("**Targets** (issue 27; midpoint, Signorini, redistributed mass, S = 1000, dt = 2.5e-4): exact event count, "
      "TV within 10 % on every contact interval, sigma L2 error at most 3e-2 of its norm, u(1,t) <= g exactly, "
      "E^n never rises (round-off: 1e-13 of E(0)) and abs(E(4)/E(0) - 1) <= 1e-4, max abs u error <= 2.4e-3:")
    w("")
    for m in results:
        if m["scheme"] == "midpoint" and m["law"] == "signorini" and m["mass"] == "redistributed":
            f = meets(m)
            w(f"- g = {m['g']}, A = {m['A']}: " + ("all met" if not f else "not met: " + ", ".join(f)))
    w("")
    w("![sigma(1,t) against the exact one](../figures/impact_sigma.png)")
    return "\n".join(L)


if __name__ == "__main__":
    sys.exit(main())
