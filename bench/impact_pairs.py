#!/usr/bin/env python3
"""sigma's L2-in-time error of the impact case on four (g, A) pairs and four meshes, and where in
time it lies (called by bench/impact_pairs.sh, which builds first). Midpoint rule, Signorini,
&contact mass = 'redistributed', S elements, dt = S^-1/4, t_end = 4. The measure is bench/impact.py's:
/series/contact_stress of step n (the step's impulse over dt) against the exact mean of sigma(1, t)
over the step (tests/tools/exact_impact.py), L2 in time, over the exact norm of sigma on [0, 4].
Its square is split into the steps inside [t_on, t_on + 5 h] after each exact onset t_on, the
step that holds t_on, and the rest. Writes the section between <!-- impact-pairs:begin --> and
<!-- impact-pairs:end --> of docs/performance.md (--quick: prints it).

    bench/impact_pairs.py EXE REPO OUT [--quick]
"""
import math
import os
import subprocess
import sys
import time

import numpy as np

PAIRS = [(0.05, 1.0), (0.1, 0.5), (0.02, 1.5), (0.03, 0.8)]
BEGIN, END = "<!-- impact-pairs:begin -->", "<!-- impact-pairs:end -->"
ONSET_WINDOW = 5.0   # in units of h


def run(exe, repo, out, g, A, S):
    import h5py
    prefix = os.path.join(out, f"pairs_g{g}_A{A}_S{S}")
    cmd = [exe, os.path.join(repo, "input", "impact.nml"), "--set", "time.scheme='midpoint'",
           "--set", "contact.law='signorini'", "--set", "contact.mass='redistributed'", "--set", f"contact.g={g}",
           "--set", f"initial.u1_poly=0,{A}", "--set", f"mesh.n_elements={S}", "--set", f"time.dt={0.25 / S}",
           "--set", f"output.prefix='{prefix}'", "--set", "output.quiet=.true.",
           "--set", "output.snapshot_every=1000000000"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with h5py.File(prefix + ".h5", "r") as f:
        t, sig = f["series/t"][:], f["series/contact_stress"][:]
        u_end, energy = f["series/u_end"][:], f["series/energy"][:]
        n_events = len(f["events/t"]) if "events/t" in f else -1
    os.remove(prefix + ".h5")
    ex = exact_impact.ExactImpact(g, A, float(t[-1]))
    t0, t1 = t[:-1], t[1:]
    sq = (sig[1:] - ex.sigma_average(t0, t1)) ** 2 * (t1 - t0)
    norm = ex.sigma_l2()
    h = 1.0 / S
    onset, straddle = np.zeros_like(sq, dtype=bool), np.zeros_like(sq, dtype=bool)
    for t_on, kind in ex.events:
        if kind > 0:
            straddle |= (t0 < t_on) & (t1 > t_on)
            onset |= (t0 >= t_on) & (t1 <= t_on + ONSET_WINDOW * h + 1e-12)
    rest = ~(onset | straddle)
    jumps = [abs(float(ex.sigma_end(t_on + 1e-9))) for t_on, kind in ex.events if kind > 0]
    rel = lambda mask: math.sqrt(float(np.sum(sq[mask]))) / norm
    return dict(g=g, A=A, S=S, err=math.sqrt(float(np.sum(sq))) / norm, onset=rel(onset), straddle=rel(straddle),
                rest=rel(rest), norm=norm, jumps=math.sqrt(sum(j * j for j in jumps)) / norm, events=n_events, events_exact=len(ex.events),
                u_err=float(np.max(np.abs(u_end - ex.u_end(t)))), drift=float(energy[-1] / energy[0] - 1.0),
                rise=float(np.max(np.diff(energy)) / energy[0]))


def section(rows, seconds):
    L = []
    w = L.append
    w(f"Written by `bench/impact_pairs.sh` ({seconds:.0f} s, load average {os.getloadavg()[0]:.1f} on 2 cores at the "
      "end). Midpoint, Signorini, redistributed mass, dt = S^-1/4, t_end = 4. sigma error: as in the table above (the "
      "step's `/series/contact_stress` against the exact step mean, L2 in time, over the exact norm); its parts: the "
      f"steps within {ONSET_WINDOW:.0f} h after each exact onset, the step holding the onset, the rest "
      "(the squares add up). Onset jumps: sqrt(sum of J^2) / norm, J = abs(sigma(1, t_on+)) the exact stress "
      "jump at each onset. (g, A) = (0.03, 0.8) was used for no choice.")
    w("")
    w("| g, A | g/A | exact onsets, releases | norm of sigma | onset jumps / norm | S | sigma L2 error / norm | onset windows | onset steps | "
      "rest | events (exact) | max abs u(1,t) error | E(4)/E(0) - 1 | largest rise of E/E(0) |")
    w("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        ex = exact_impact.ExactImpact(r["g"], r["A"], 4.0)
        ev = ", ".join(f"{t:.4f}" for t, _ in ex.events)
        w(f"| {r['g']}, {r['A']} | {r['g'] / r['A']:.4g} | {ev} | {r['norm']:.3f} | {r['jumps']:.2f} | {r['S']} | {r['err']:.2e} | "
          f"{r['onset']:.2e} | {r['straddle']:.2e} | {r['rest']:.2e} | {r['events']} ({r['events_exact']}) | "
          f"{r['u_err']:.2e} | {r['drift']:+.2e} | {r['rise']:+.1e} |")
    return "\n".join(L)


def main():
    global exact_impact
    exe, repo, out = sys.argv[1], sys.argv[2], sys.argv[3]
    quick = "--quick" in sys.argv[4:]
    sys.path.insert(0, os.path.join(repo, "tests", "tools"))
    import exact_impact as ei
    exact_impact = ei
    os.makedirs(out, exist_ok=True)
    start = time.time()
    rows = [run(exe, repo, out, g, A, S) for g, A in PAIRS for S in ((500, 1000) if quick else (500, 1000, 2000, 4000))]
    md = section(rows, time.time() - start)
    if quick:
        print(md)
        return 0
    doc = os.path.join(repo, "docs", "performance.md")
    text = open(doc).read()
    a, b = text.find(BEGIN), text.find(END)
    if a < 0 or b < 0:
        raise SystemExit(f"{doc}: no {BEGIN} ... {END} markers")
    open(doc, "w").write(text[:a + len(BEGIN)] + "\n" + md + "\n" + text[b:])
    print(f"impact_pairs: wrote the impact-pairs section of {doc}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
