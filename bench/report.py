"""Write docs/performance.md from the raw data of scripts/bench.sh (plain text; any python3).

    python3 bench/report.py OUTDIR DOC

OUTDIR holds meta.txt (key=value), kernels.raw (rodcontact_bench_kernels lines prefixed
with blas= run=), exp1.raw, alloc.raw, callgrind_<method>_<t_end>.txt (callgrind_annotate
--inclusive=yes), work_precision.md and work_precision_speedup.txt (bench/work_precision.sh),
work_precision_schemes.md (bench/work_precision_schemes.sh).
work_precision_adaptive.md and work_precision_adaptive_targets.txt (bench/adaptive_steps.sh,
whose helper bench/adaptive_steps.py writes that section's prose).
step_cost.md (bench/step_cost.sh: instructions per adaptive and fixed step).
work_precision_mesh.md and work_precision_mesh_targets.txt (bench/adaptive_mesh.sh, whose helper
bench/adaptive_mesh.py writes that section's prose).
Every number on the page comes from these files; the prose around them is here.
"""

import math
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'scripts', 'lib'))
import textfiles  # noqa: E402

TARGET_EXP1_SECONDS = 2.5
TARGET_RSS_MB = 50.0
TARGET_SPEEDUP = 5.0
STEPS_CASES = [("step_monolithic_euler", "monolithic, Euler"), ("step_monolithic_bdf2", "monolithic, BDF2"),
               ("step_paper_euler", "paper, Euler"), ("step_monolithic_midpoint", "monolithic, midpoint"),
               ("step_thermoelastic_euler", "Euler, thermoelastic (P, eta left out)")]


def kv(words):
    return dict(w.split("=", 1) for w in words if "=" in w)


def read_kernels(outdir):
    cases, setups = {}, {}
    for line in open(os.path.join(outdir, "kernels.raw")):
        words = line.split()
        d = kv(words)
        if "setup" in words:
            setups.setdefault((d["blas"], int(d["s"])), []).append(d)
        elif "case" in d:
            cases.setdefault((d["blas"], int(d["s"]), d["case"]), []).append(d)
    return cases, setups


def med(values):
    return statistics.median(values)


def fmt_us(x):
    return "%.0f" % x if x >= 100 else ("%.1f" % x if x >= 10 else "%.2f" % x)


def slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def callgrind(outdir, method, t):
    path = os.path.join(outdir, "callgrind_%s_%s.txt" % (method, t))
    if not os.path.exists(path):
        return None
    total, funcs = None, {}
    pat = re.compile(r"^\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+(.*?)(?:\s+\[(.*)\])?\s*$")
    for line in open(path):
        m = pat.match(line)
        if not m:
            continue
        ir = int(m.group(1).replace(",", ""))
        name = m.group(2)
        if name == "PROGRAM TOTALS":
            total = ir
            continue
        name = name.split(":")[-1] if not name.startswith("???:") else name[4:]
        funcs[name] = funcs.get(name, 0) + ir
    return total, funcs


def pretty_function(name):
    m = re.match(r"__(\w+?)_MOD_(\w+)$", name)
    return "%s::%s" % (m.group(1), m.group(2)) if m else name


def main():
    outdir, doc = sys.argv[1], sys.argv[2]
    meta = textfiles.read_meta(os.path.join(outdir, "meta.txt"))
    cases, setups = read_kernels(outdir)
    blases = [b for b in ("reference", "openblas") if any(k[0] == b for k in cases)]
    sizes = sorted({k[1] for k in cases})
    runs = meta.get("runs", "?")
    md = []
    w = md.append

    w("# Performance")
    w("")
    w("Written by `scripts/bench.sh` (a benchmark, not a test) on %s; do not edit by hand: rerun it "
      "(the sections from 'Impact against the exact solution' on are kept as they are: bench/impact.sh "
      "and bench/impact_pairs.sh rewrite that one, the later ones measure one change each, by hand). "
      "The raw data are in `out/bench/`. The machine is shared with other jobs, so wall times are "
      "noisy: every case was run %s times and the tables give medians; ratios are taken within one "
      "process (the kernel benchmark times all cases round robin); instruction counts "
      "(valgrind) are exact." % (meta.get("date", "?"), runs))
    w("")
    w("## Machine and build")
    w("")
    w("| | |")
    w("|---|---|")
    w("| CPU | %s, %s cores (%s) |" % (meta.get("cpu", "?"), meta.get("cores", "?"),
                                       meta.get("caches", "").strip(";").replace(";", ", ")))
    w("| OS | %s |" % meta.get("kernel", "?"))
    w("| load average (1, 5, 15 min) | %s at the start, %s at the end (2 cores: above 2 means waiting for a CPU) |"
      % (meta.get("load_start", "?"), meta.get("load_end", "?")))
    w("| compiler | %s |" % meta.get("compiler", "?"))
    w("| flags (rodcontact_lib) | `%s` |" % meta.get("flags", "?").strip())
    w("| commit | %s |" % meta.get("commit", "?"))
    w("| bench.sh run time | %s s |" % meta.get("bench_seconds", "?"))
    w("")
    w("### BLAS and LAPACK")
    w("")
    w("The binaries link `libblas.so.3` and `liblapack.so.3`; each run selects the implementation with "
      "`LD_LIBRARY_PATH`, and `bench.sh` checks with `ldd` that both resolve from that directory "
      "before it measures anything:")
    w("")
    w("| run | LD_LIBRARY_PATH | resolved by ldd (real file) |")
    w("|---|---|---|")
    for b in blases:
        libs = [x for x in meta.get("resolved." + b, "").split(";") if x and not x.startswith("libgfortran")]
        w("| %s | `%s` | %s |" % (b, meta.get("ld_library_path." + b, "?"), "<br>".join("`%s`" % x for x in libs)))
    libs = [x for x in meta.get("resolved.default", "").split(";") if x and not x.startswith("libgfortran")]
    w("| (none: the system's alternatives) | | %s |" % "<br>".join("`%s`" % x for x in libs))
    w("")
    w("OpenBLAS: %s. `OPENBLAS_NUM_THREADS`: %s. Installing `libopenblas0-pthread` makes Debian switch the "
      "system-wide alternatives `libblas.so.3` / `liblapack.so.3` to OpenBLAS (it has the higher "
      "priority), which would slow down every other program on this machine: `bench.sh` records both "
      "alternatives (`update-alternatives --query`), pins them to their current value with "
      "`update-alternatives --set` before `apt-get install`, and sets them again right after (also on an "
      "error exit). The groups are left in manual mode pointing where they pointed before "
      "(`update-alternatives --auto` would now select OpenBLAS)." %
      (meta.get("openblas_action", "?"), meta.get("openblas_num_threads", "unset")))
    w("")
    w("| alternative | before | after |")
    w("|---|---|---|")
    for alt in ("libblas.so.3-x86_64-linux-gnu", "liblapack.so.3-x86_64-linux-gnu"):
        w("| %s | `%s` | `%s` |" % (alt, meta.get("alternative_before." + alt, "?"),
                                     meta.get("alternative_after." + alt, "?")))
    w("")

    # ---------------------------------------------------------------- targets (filled below)
    targets = []
    targets_at = len(md)

    # ---------------------------------------------------------------- the band
    w("## The monolithic system and its band")
    w("")
    w("The five fields are interleaved per node in the order `q, theta, v, P, eta` (docs/scheme.md): "
      "n = 5 (s + 1) unknowns, and every coupled pair of fields is at most two slots apart, so the "
      "band has **kl = ku = 7** (5 + 2; an arbitrary order needs 9); `dgbtrf` stores it in "
      "2 kl + ku + 1 = 22 rows. The kernel benchmark prints kl and ku of the matrix it assembles: "
      "%s. The floor of the per-step cost is taken as one LAPACK `dgbtrs` (one right-hand side) on this "
      "factored matrix: a step that did nothing but LAPACK's banded solve. The ratio (step)/(dgbtrs) says how "
      "far above that floor a whole step is; it is below 1 where the step's own substitution (block-tridiagonal, "
      "or the band substitution as plain loops) is faster than `dgbtrs` itself."
      % ", ".join(sorted({"kl = %s, ku = %s" % (d["kl"], d["ku"]) for v in setups.values() for d in v})))
    w("")

    # ---------------------------------------------------------------- per-step cost
    w("## Per-step cost against the mesh size")
    w("")
    w("Command (run by `bench.sh` for each BLAS, s and run, %s runs): " % runs)
    w("")
    w("    LD_LIBRARY_PATH=<dir> build/bench/rodcontact_bench_kernels input/exp1.nml <s>")
    w("")
    w("`bench/bench_kernels.f90` reads exp1 (the paper's (7.1) model, dt = 1e-4), sets n_elements = s, "
      "assembles the monolithic matrix, factors it with `dgbtrf` (and the block-tridiagonal LU), and "
      "times in one process, round robin over 7 batches of about 20 ms each: one `dgbtrs` "
      "(`band%solve_lapack`), the same substitution as plain loops (`band%solve`), the block-tridiagonal "
      "substitution (`block_tridiagonal_t%solve`), and one whole time step `stepper%advance` of method "
      "`monolithic` (Euler and BDF2) and `paper` (Euler) from exp1's initial data (the state advances "
      "through the timed steps). The solves are timed on a fresh copy of the right-hand side, whose "
      "copy time is subtracted. Each cell: median over the runs of the per-run median; "
      "µs per call, and in brackets ns per unknown (n = 5(s+1)) and the ratio to one `dgbtrs` of the "
      "same run (median of the per-batch ratios).")
    w("")
    linear = {}
    for b in blases:
        w("### %s BLAS/LAPACK" % b)
        w("")
        w("| s | n | dgbtrs (floor) | own band substitution | block substitution | "
          + " | ".join("step: %s" % name for _, name in STEPS_CASES) + " | block LU used (Euler / BDF2) |")
        w("|---:|---:|---:|---:|---:|" + "---:|" * len(STEPS_CASES) + "---|")
        for s in sizes:
            row = ["%d" % s, "%d" % (5 * (s + 1))]
            for case in ("dgbtrs", "band_solve", "block_solve") + tuple(c for c, _ in STEPS_CASES):
                rs = cases.get((b, s, case))
                if not rs:
                    row.append("–")
                    continue
                us = med(float(r["us"]) for r in rs)
                ns = med(float(r["ns_per_unknown"]) for r in rs)
                ratio = med(float(r["ratio_dgbtrs"]) for r in rs)
                cell = "%s (%.1f ns, %.2f)" % (fmt_us(us), ns, ratio) if case != "dgbtrs" else "%s (%.1f ns)" % (
                    fmt_us(us), ns)
                if case == "step_paper_euler":
                    cell += " [%.1f it]" % med(float(r["iterations"]) for r in rs)
                row.append(cell)
            flags = []
            for key in ("stepper_uses_block_solver", "bdf2_stepper_uses_block_solver"):
                used = {d.get(key) for d in setups.get((b, s), [])}
                flags.append("yes" if used == {"T"} else ("**no**" if used == {"F"} else "?"))
            row.append(" / ".join(flags))
            w("| " + " | ".join(row) + " |")
        w("")
        # linearity
        for case, name in STEPS_CASES:
            pts = [(s, med(float(r["us"]) for r in cases[(b, s, case)])) for s in sizes if (b, s, case) in cases]
            if len(pts) >= 2:
                linear[(b, case)] = (slope([5 * (s + 1) for s, _ in pts], [u for _, u in pts]),
                                     [(pts[i][0], pts[i + 1][0],
                                       slope([5 * (pts[i][0] + 1), 5 * (pts[i + 1][0] + 1)], [pts[i][1], pts[i + 1][1]]))
                                      for i in range(len(pts) - 1)],
                                     max(u / (5 * (s + 1)) for s, u in pts) / min(u / (5 * (s + 1)) for s, u in pts))
        w("Growth with s (%s BLAS): least-squares exponent p of (time per step) ~ n^p over all s, the "
          "exponent between successive s, and the largest/smallest cost per unknown:" % b)
        w("")
        w("| step | p (all s) | p between successive s | max/min ns per unknown |")
        w("|---|---:|---|---:|")
        for case, name in STEPS_CASES:
            if (b, case) in linear:
                p, pieces, spread = linear[(b, case)]
                w("| %s | %.2f | %s | %.1f |" % (name, p, ", ".join("%d→%d: %.2f" % x for x in pieces), spread))
        w("")
        # run-to-run spread of the Euler step
        spreads = []
        for s in sizes:
            rs = cases.get((b, s, "step_monolithic_euler"), [])
            if len(rs) >= 2:
                us = [float(r["us"]) for r in rs]
                spreads.append("s = %d: %s–%s µs" % (s, fmt_us(min(us)), fmt_us(max(us))))
        if spreads:
            w("Run-to-run range of the monolithic Euler step (the noise of a shared machine): " + "; ".join(spreads)
              + ".")
            w("")

    ir_rows = []
    irpath = os.path.join(outdir, "ir_per_step.raw")
    if os.path.exists(irpath):
        for line in open(irpath):
            d = kv(line.split())
            try:
                s = int(d["s"])
                per_step = (int(d["ir2"]) - int(d["ir1"])) / (int(d["steps2"]) - int(d["steps1"]))
                ir_rows.append((s, per_step))
            except (KeyError, ValueError):
                pass
    if ir_rows:
        w("### The work per step: instructions")
        w("")
        w("Instructions are not disturbed by other jobs or by caches: `valgrind --tool=callgrind build/rodcontact "
          "input/exp1.nml --set mesh.n_elements=<s> --set output.snapshot_every=100000 ...` for two numbers of "
          "steps, the difference per step (everything a step of a real run does, monolithic Euler):")
        w("")
        w("| s | instructions per step | per unknown | block LU used (Euler) |")
        w("|---:|---:|---:|---|")
        for s, per_step in sorted(ir_rows):
            used = {d.get("stepper_uses_block_solver") for d in setups.get(("reference", s), [])}
            w("| %d | %.0f | %.1f | %s |" % (s, per_step, per_step / (5 * (s + 1)),
                                           "yes" if used == {"T"} else ("**no**" if used == {"F"} else "?")))
        w("")
        w("While the block LU is used, the work per unknown is constant: a step's work is linear in s. Where "
          "the stepper falls back to the `dgbtrf` factors (see below) the work per unknown more than doubles. "
          "The wall time per unknown also grows once the factors no longer fit in the caches (the block factors "
          "take 3 x 25 x 8 bytes = 600 bytes per node: 1.2 MB at s = 2000 against 1 MB of L2 per core, "
          "60 MB at s = 100000 against 32 MB of L3): the solve then streams its factors from memory.")
        w("")
    diffs = []
    for s in sizes:
        vals = [float(d["block_vs_dgbtrs"]) for b in blases for d in setups.get((b, s), []) if "block_vs_dgbtrs" in d]
        if vals:
            diffs.append("%.0e at s = %d" % (med(vals), s))
    w("**When the block LU is used.** It has no pivoting across nodes, so `stepper_m`'s `blocks_agree` checks it "
      "once per run against `dgbtrf` (partial pivoting): on the contact response and on a smooth right-hand side its "
      "residual |A x - b| must be at most 10 times dgbtrf's (or 1e-13 |b|). The two solutions themselves differ by "
      "about cond(A) x eps, which grows with s (relative difference on a smooth right-hand side, Euler matrix: %s) "
      "while both are backward stable to the same level; an earlier check on that difference (1e-9) made large "
      "meshes fall back to the 2-3 times slower band substitution. With the residual check the block LU is used at "
      "every s above (column 'block LU used')." % ", ".join(diffs))
    w("")
    if len(blases) == 2:
        w("### Reference BLAS against OpenBLAS")
        w("")
        w("| s | dgbtrs reference | dgbtrs OpenBLAS | OpenBLAS / reference | monolithic Euler step, reference | "
          "the same, OpenBLAS |")
        w("|---:|---:|---:|---:|---:|---:|")
        for s in sizes:
            try:
                r = med(float(x["us"]) for x in cases[("reference", s, "dgbtrs")])
                o = med(float(x["us"]) for x in cases[("openblas", s, "dgbtrs")])
                sr = med(float(x["us"]) for x in cases[("reference", s, "step_monolithic_euler")])
                so = med(float(x["us"]) for x in cases[("openblas", s, "step_monolithic_euler")])
            except KeyError:
                continue
            w("| %d | %s µs | %s µs | %.1f | %s µs | %s µs |" % (s, fmt_us(r), fmt_us(o), o / r, fmt_us(sr), fmt_us(so)))
        w("")
        w("A time step calls no BLAS or LAPACK routine (the substitutions are our own loops, see below), so "
          "its cost does not depend on the library; only the floor `dgbtrs` does (and the one-off `dgbtrf`, "
          "`dgetrf`/`dgetri` of the set-up). With OpenBLAS the floor is slower, which makes the ratio "
          "step/floor smaller without making anything faster.")
        w("")

    # ---------------------------------------------------------------- exp1
    exp1 = [kv(l.split()) for l in open(os.path.join(outdir, "exp1.raw")) if l.strip()]
    w("## Experiment 1 as the paper ran it")
    w("")
    w("Command (`bench.sh`, %s runs per BLAS; wall time and peak resident set size from "
      "`/usr/bin/time -f '%%e %%M'`):" % runs)
    w("")
    w("    LD_LIBRARY_PATH=<dir> /usr/bin/time -f '%e %M' build/rodcontact input/exp1.nml \\")
    w("        --set time.t_end=<T> --set output.prefix=<tmp> --set output.quiet=.true.")
    w("")
    w("h = 1/500, dt = 1e-4, monolithic Euler, default output (series every step, snapshot every "
      "100 steps, HDF5):")
    w("")
    w("| BLAS | t_end | steps | runs | wall time median [s] (min–max) | µs per step | peak RSS median [MB] | HDF5 file |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|")
    exp1_median, rss = None, {}
    for b in blases:
        for tend in sorted({float(d["t_end"]) for d in exp1}):
            rs = [d for d in exp1 if d["blas"] == b and float(d["t_end"]) == tend]
            if not rs:
                continue
            walls = [float(d["wall"]) for d in rs]
            rss_mb = [float(d["rss_kb"]) / 1024 for d in rs]
            steps = int(round(tend / 1e-4))
            w("| %s | %g | %d | %d | %.2f (%.2f–%.2f) | %.1f | %.1f | %.0f MB |" % (
                b, tend, steps, len(rs), med(walls), min(walls), max(walls), 1e6 * med(walls) / steps, med(rss_mb),
                float(rs[0]["h5_bytes"]) / 2 ** 20))
            if b == "reference":
                rss[tend] = med(rss_mb)
                if abs(tend - float(meta.get("exp1_tend", 10))) < 1e-9:
                    exp1_median = med(walls)
    w("")
    if len(rss) > 1:
        w("The peak RSS grows a little with t_end and levels off; it is not a per-step leak (memcheck finds no "
          "allocation per step, below). The output writer holds at most 4096 series entries in memory "
          "(192 KiB) and keeps no HDF5 chunk cache: each chunk (one snapshot row, 256 series entries) is "
          "written by the call that fills it (docs/output.md, \"Chunks and compression\"; before issue 14 "
          "HDF5's default cache of up to 1 MiB per dataset filled up over ~130,000 steps). The output "
          "file, not the memory, is what grows with t_end.")
        w("")

    # ---------------------------------------------------------------- energy with BDF2
    epath = os.path.join(outdir, "energy.raw")
    erows = [kv(l.split()) for l in open(epath) if l.strip()] if os.path.exists(epath) else []
    if erows:
        w("## BDF2 and the energy law during contact")
        w("")
        w("`src/numerics/energy_m.f90`: BDF2's G-energy (E_lin(X^n) + E_lin(2X^n - X^{n-1}))/2 never rises while the "
          "contact node is inactive; with an active penalty the nonlinear term is not G-stable, so there is "
          "no such law. Measured on exp1 (h = 1/500, dt = 1e-4) to t = 3, through the whole contact phase "
          "(t ~ 0.19 to 1.45): `build/rodcontact input/exp1.nml --set time.t_end=3 --set time.scheme=<scheme> "
          "--set output.snapshot_every=100000 ...`, then the root attribute `energy_max_relative_rise` (largest "
          "relative rise of the scheme's law energy) and, from `/series/energy`, the largest relative rise "
          "of E^n of Corollary 6.2 over a step in contact and out of contact:")
        w("")
        w("| scheme | steps | steps in contact | law energy: largest relative rise (0: never rises) | "
          "E^n: largest relative change over a step in contact (< 0: it always falls) | the same out of contact | "
          "steps where E^n rises (by > 1e-12) |")
        w("|---|---:|---:|---:|---:|---:|---:|")
        for d in erows:
            w("| %s | %s | %s | %.2e | %.2e | %.2e | %s |" % (
                d["scheme"], d["steps"], d["contact_steps"], float(d["law_max_rise"]),
                float(d["En_max_rise_contact"]), float(d["En_max_rise_free"]), d["En_rising_steps"]))
        w("")

    # ---------------------------------------------------------------- callgrind
    w("## Where the time of a step goes")
    w("")
    w("valgrind's callgrind counts instructions exactly, so the per-step cost can be split by function "
      "without timing noise. Command: `valgrind --tool=callgrind build/rodcontact input/exp1.nml --set "
      "time.t_end=T ...` for T = 0.1 and 0.2 (1000 and 2000 steps, s = 500), and the difference of the "
      "two runs divided by 1000 steps: that is everything a step costs in a real run (solve, right-hand "
      "side, energy, series output, snapshots every 100 steps, progress), without the set-up. "
      "Inclusive counts (a function includes what it calls); functions below 1% of a step are left out.")
    w("")
    for method, title in (("euler", "monolithic, Euler"), ("bdf2", "monolithic, BDF2"), ("paper", "paper, Euler")):
        a, b2 = callgrind(outdir, method, "0.1"), callgrind(outdir, method, "0.2")
        if not a or not b2 or a[0] is None or b2[0] is None:
            continue
        per_step = (b2[0] - a[0]) / 1000.0
        w("**%s**: %.0f instructions per step in all (%.1f per unknown)." % (title, per_step, per_step / 2505))
        w("")
        w("| function (inclusive) | instructions per step | share |")
        w("|---|---:|---:|")
        rows = []
        for name, ir in b2[1].items():
            d = (ir - a[1].get(name, 0)) / 1000.0
            if d >= 0.01 * per_step and not re.match(r"(main|MAIN__|\(below main\)|_start|__libc_start|0x)", name) \
                    and "libc_start" not in name and "run_simulation" not in name:
                rows.append((d, name))
        for d, name in sorted(rows, reverse=True)[:14]:
            w("| `%s` | %.0f | %.0f%% |" % (pretty_function(name), d, 100 * d / per_step))
        w("")

    cg_bdf2 = (callgrind(outdir, "bdf2", "0.1"), callgrind(outdir, "bdf2", "0.2"))
    if all(c and c[0] for c in cg_bdf2):
        (a_tot, a_f), (b_tot, b_f) = cg_bdf2
        per_step = (b_tot - a_tot) / 1000.0
        key = "__energy_m_MOD_discrete_energy"
        mon = [k for k in b_f if k.endswith("_MOD_monitor_observe")]
        if key in b_f and mon:
            energy = (b_f[key] - a_f.get(key, 0)) / 1000.0
            observe = (b_f[mon[0]] - a_f.get(mon[0], 0)) / 1000.0
            w("With BDF2 the energy monitor (`run_m`'s `monitor_observe`) takes %.0f%% of a step's instructions: "
              "`discrete_energy` twice per step (E_lin(X^n), reused for E^n, and E_lin(2X^n - X^{n-1}) for the "
              "G-energy), %.0f instructions of %.0f per step." % (100 * observe / per_step, energy, per_step))
            w("")

    # ---------------------------------------------------------------- allocations
    allocs = {}
    for line in open(os.path.join(outdir, "alloc.raw")):
        d = kv(line.split())
        if d.get("allocs", "?") != "?":
            allocs[(d["method"], d["t_end"], d["snapshot_every"])] = int(d["allocs"])
    per_step_allocs = {}
    per_snapshot_allocs = {}
    if allocs:
        w("## Heap allocations per step")
        w("")
        w("valgrind memcheck's heap summary (`total heap usage: N allocs`) of exp1 runs (s = 500) to t = 0.1 and "
          "0.2 without snapshots (`--set output.snapshot_every=100000`: only the first and last state), "
          "and to t = 0.2 with the default snapshot every 100 steps:")
        w("")
        w("| method | allocations, 1000 steps | 2000 steps | per step | 2000 steps with 21 snapshots | per snapshot |")
        w("|---|---:|---:|---:|---:|---:|")
        for method, title in (("euler", "monolithic, Euler"), ("bdf2", "monolithic, BDF2"), ("paper", "paper, Euler")):
            try:
                a1, a2, a3 = (allocs[(method, "0.1", "100000")], allocs[(method, "0.2", "100000")],
                              allocs[(method, "0.2", "100")])
            except KeyError:
                continue
            per_step_allocs[method] = (a2 - a1) / 1000.0
            per_snapshot_allocs[method] = (a3 - a2) / 19.0
            w("| %s | %d | %d | %.3f | %d | %.0f |" % (title, a1, a2, (a2 - a1) / 1000.0, a3, (a3 - a2) / 19.0))
        w("")

    # ---------------------------------------------------------------- what a step does not do
    w("## What a time step does not do")
    w("")
    w("Read in `src/numerics/stepper_m.f90` and `src/driver/run_m.f90`, and checked by the measurements above:")
    w("")
    w("- **No refactorisation.** `stepper%init` assembles and factors the matrices once: `dgbtrf` and the "
      "block-tridiagonal LU of the monolithic matrix (a second pair for BDF2's step 2dt/3), or the thermal "
      "and mechanical bands of the paper's method; the contact response z = A^{-1} e_s is solved once. "
      "`stepper%advance` only builds the right-hand side (`old_state_rhs`, O(s)), scatters it, substitutes "
      "(block substitution, or the band substitution with the `dgbtrf` factors), adds the closed-form "
      "contact correction `x - f z` and gathers the fields; the paper's method makes two substitutions (thermal "
      "and mechanical band) per iteration, with 2-4 iterations per step on exp1 (the 'it' in the tables). No BLAS/LAPACK call is made in a step (which is why the step cost does not depend on "
      "the BLAS library).")
    w("- **No allocation.** All work arrays of the stepper are allocated in `init`; BDF2's previous level "
      "(`state%%u_prev`, `w_prev`) is allocated on the first step only. Measured: %s allocations per step "
      "(the 2000-step run's allocations less the 1000-step run's, over 1000 steps; a snapshot allocates about %s "
      "times, inside HDF5 and for its dataset names)."
      % (", ".join("%.3f (%s)" % (v, k) for k, v in per_step_allocs.items()) or "not measured",
         "%.0f" % max(per_snapshot_allocs.values()) if per_snapshot_allocs else "?"))
    w("- **Output only on output steps.** `run_simulation` appends one series entry per step to a "
      "fixed-size buffer (`writer%append_series`: a few stores; written to the file when the buffer is "
      "full) and writes a snapshot (seven HDF5 hyperslab writes: t and six fields) only every `snapshot_every` "
      "steps, and a checkpoint only every `checkpoint_every` steps (default 0: never); the progress line reads the clock only at its next check step. The step does evaluate the discrete "
      "energy (Corollary 6.2, O(s)) every step, as the specification requires.")
    w("")

    # ---------------------------------------------------------------- work-precision
    w("## Work-precision: implicit Euler against BDF2")
    w("")
    w("Command: `bench/work_precision.sh` (also run by `bench.sh`); program `bench/work_precision.f90`. "
      "![work-precision diagram](../figures/work_precision.png)")
    w("")
    w("Only the time loop is timed (`stepper%advance`, N = t_end/dt steps); the error is evaluated once, "
      "at the final time, after the clock stops. For the manufactured solution a step also evaluates the "
      "source terms (3-point Gauss quadrature of `mms_m`'s analytic sources on every element), which "
      "costs more than the solve but scales the same way (O(s) per step, the same for both schemes), so "
      "the time ratios between the schemes are essentially ratios of (number of steps) x s; without sources a "
      "BDF2 step costs 10-20% more than an Euler step (per-step tables above), which would lower the ratios "
      "by as much. One point per (h, dt) pair; the pairings:")
    w("")
    w("- manufactured solution (`mms_no_contact` with the O(1) model of `tests/test_convergence.f90`, "
      "t_end = 1): Euler's error is about a h^2 + b dt in L2 and c h + b' dt in H1 (P1 elements), BDF2's "
      "a h^2 + e dt^2 and c h + e' dt^2. The balanced pairings are therefore dt ~ h^2 for Euler in L2, "
      "dt ~ h for Euler in H1 (the constants measured on the h = dt runs give dt = h/8), h = dt for BDF2 "
      "in L2 and dt ~ sqrt(h) for BDF2 in H1. Each is run as a sequence, and h = dt (Corollary 6.4's "
      "O(h + dt) coupling) for both; the speed-up at an error level compares each scheme's fastest "
      "sequence there (log-log interpolation along it).")
    w("- experiment 2 (t_end = 0.4, after the contact begins at t ~ 0.30 and while the P pulse front, "
      "decaying like exp(-t/(2 tau)), is still sharp; the theta front has decayed, exp(-t/(2 tau0))): "
      "dt = 0.05 h (the paper's ratio, h = 1/500 with dt = 1e-4) and dt = 0.4 h, s = 100 ... 1600, "
      "against a BDF2 reference with s = 8000, dt = 4e-5. Errors relative to the reference's norms.")
    w("")
    wp = os.path.join(outdir, "work_precision.md")
    if os.path.exists(wp):
        md.extend(open(wp).read().splitlines())
        w("")
    w("What this shows:")
    w("")
    w("- On the smooth manufactured solution the second-order scheme is much faster at equal error: see the "
      "time ratios under (a) (target: at least 5 at an error of 1e-4). In L2, Euler's best pairing needs "
      "dt ~ h^2 while BDF2 can take h = dt; in H1 the P1 space limits both to O(h), but Euler still needs "
      "dt ~ h/8 where BDF2 takes dt ~ sqrt(h)/4. (The stepping times of the manufactured solution are "
      "dominated by the evaluation of its source terms, the same per step for both schemes.)")
    w("- On experiment 2 at t = 0.4 it makes no difference for theta and u: their errors are set by the mesh "
      "(the discontinuous initial pulses leave rough fields; the errors fall like h), the two schemes are "
      "equally accurate at equal (h, dt), and dt = 0.4 h, eight times the paper's ratio, is as accurate as "
      "dt = 0.05 h for them. Where the time scheme matters is the P pulse front (third panel): there BDF2's "
      "error is several times smaller at equal cost. P errors below about the reference check's P difference "
      "(above) are at the reference's own accuracy and mean little.")
    w("- The time error alone (tables (c), s = 400 fixed): for u, Euler is first order and BDF2 has a much "
      "smaller error (8-30 times here) but not second order: before the contact (t = 0.2) its order in u is "
      "about 1.1-1.4, limited by the pulse fronts in theta and P that drive u through the coupling terms, "
      "and after the contact begins (t = 0.4) it is irregular (the contact force [u(1) - g]_+ has a kink in "
      "time). At the fronts (theta, P) both schemes converge at well below their order, because the fronts "
      "are discontinuities; BDF2 with the smaller error.")
    w("")

    # ---------------------------------------------------------------- work-precision of the schemes
    wps = os.path.join(outdir, "work_precision_schemes.md")
    if os.path.exists(wps):      # bench/work_precision_schemes.sh: the section, prose included
        md.extend(open(wps).read().splitlines())
    # ---------------------------------------------------------------- adaptive time steps (issue 12)
    wpa = os.path.join(outdir, "work_precision_adaptive.md")
    if os.path.exists(wpa):
        md.extend(open(wpa).read().splitlines())
        w("")
    sc = os.path.join(outdir, "step_cost.md")       # bench/step_cost.sh (issue 24)
    if os.path.exists(sc):
        md.extend(open(sc).read().splitlines())
        w("")
    # ---------------------------------------------------------------- adaptive mesh (issue 13)
    wpm = os.path.join(outdir, "work_precision_mesh.md")
    if os.path.exists(wpm):
        md.extend(open(wpm).read().splitlines())
        w("")
    eb = os.path.join(outdir, "error_budget.md")     # bench/error_budget.sh
    if os.path.exists(eb):
        md.extend(open(eb).read().splitlines())
        w("")

    # ---------------------------------------------------------------- targets
    t = []
    t.append("## Targets")
    t.append("")
    t.append("| target | measured | met |")
    t.append("|---|---|---|")
    if exp1_median is not None:
        t.append("| exp1 (h = 1/500, dt = 1e-4) to t_end = %s, median wall time <= %.1f s | %.2f s | %s |" % (
            meta.get("exp1_tend"), TARGET_EXP1_SECONDS, exp1_median,
            "yes" if exp1_median <= TARGET_EXP1_SECONDS else "**no**"))
    if rss:
        worst = max(rss.values())
        keys = sorted(rss)
        growth = [(keys[i], keys[i + 1], rss[keys[i + 1]] - rss[keys[i]]) for i in range(len(keys) - 1)]
        # bounded: below the target, and each tenfold / threefold longer run adds less than the one before
        saturating = all(g2 <= g1 + 0.5 for (_, _, g1), (_, _, g2) in zip(growth, growth[1:]))
        verdict = ("yes" if worst < TARGET_RSS_MB and (not growth or max(g for _, _, g in growth) < 1.0) else
                   "yes, bounded: it grows a little and levels off (HDF5's chunk caches fill up; see below)"
                   if worst < TARGET_RSS_MB and saturating else "**no**")
        t.append("| peak RSS < %.0f MB, not growing with t_end | %s | %s |" % (
            TARGET_RSS_MB, ", ".join("%.1f MB (t_end = %g)" % (rss[k], k) for k in keys), verdict))
    for b in blases:
        if (b, "step_monolithic_euler") in linear:
            p, pieces, spread = linear[(b, "step_monolithic_euler")]
            ok = 0.9 <= p <= 1.1 and spread < 2.0
            t.append("| per-step wall time linear in s (monolithic Euler, %s BLAS) | n^%.2f over s = %d–%d (%s); "
                     "time per unknown varies %.1fx | %s |" % (
                         b, p, sizes[0], sizes[-1], ", ".join("%d→%d: %.2f" % x for x in pieces), spread,
                         "yes" if ok else "**no** beyond the caches and at the block-LU fallback (see the "
                                          "instruction counts)"))
    if ir_rows:
        per_unknown = [(s, ir / (5 * (s + 1))) for s, ir in sorted(ir_rows)]
        blocks = [(s, x) for s, x in per_unknown
                  if {d.get("stepper_uses_block_solver") for d in setups.get(("reference", s), [])} == {"T"}]
        if blocks:
            lo, hi = min(x for _, x in blocks), max(x for _, x in blocks)
            t.append("| per-step work (instructions) linear in s | %s instructions per unknown | %s |" % (
                ", ".join("%.0f (s = %d)" % (x, s) for s, x in per_unknown),
                "yes while the block LU is used (s = %d–%d: %.0f–%.0f per unknown)%s" % (
                    blocks[0][0], blocks[-1][0], lo, hi,
                    "; **no** where it falls back" if len(blocks) < len(per_unknown) else "")))
    sp = os.path.join(outdir, "work_precision_speedup.txt")
    if os.path.exists(sp):
        for line in open(sp):
            key, val = line.split()
            name = {"e_theta_L2": "L2 error of theta", "e_u_H1": "H1 error of u", "e_P_L2": "L2 error of P"}[key]
            if val == "none":
                t.append("| BDF2 >= %.0fx faster than Euler at error 1e-4 (manufactured solution, %s) | not "
                         "reached in these runs | – |" % (TARGET_SPEEDUP, name))
            else:
                t.append("| BDF2 >= %.0fx faster than Euler at error 1e-4 (manufactured solution, %s) | %sx | %s |"
                         % (TARGET_SPEEDUP, name, val, "yes" if float(val) >= TARGET_SPEEDUP else "**no**"))
    wpa_targets = os.path.join(outdir, "work_precision_adaptive_targets.txt")
    if os.path.exists(wpa_targets):
        t.extend(line.rstrip("\n") for line in open(wpa_targets) if line.strip())
    wpm_targets = os.path.join(outdir, "work_precision_mesh_targets.txt")
    if os.path.exists(wpm_targets):
        t.extend(line.rstrip("\n") for line in open(wpm_targets) if line.strip())
    t.append("")
    md[targets_at:targets_at] = t

    md += kept_impact_section(doc)
    with open(doc, "w") as f:
        f.write("\n".join(md).rstrip() + "\n")
    # on stdout: the targets and the per-step tables (the medians), for whoever ran bench.sh
    keep, printing = [], False
    for line in md:
        if line.startswith("## "):
            printing = line in ("## Targets", "## Per-step cost against the mesh size",
                                "## Experiment 1 as the paper ran it")
        if printing and not (line and line[0].isalpha() or line.startswith("    ") or line.startswith("`")):
            keep.append(line)
    print(re.sub(r"\n{3,}", "\n\n", "\n".join(keep)))



def kept_impact_section(doc):
    """The page from the heading of the section that bench/impact.sh writes between its markers
    to the page's end, kept as it is: that section and bench/impact_pairs.sh's table are rewritten
    by those scripts, and the sections after them are written by hand (measurements of one
    change, with their commands), not by this script."""
    if not os.path.exists(doc):
        return []
    text = open(doc).read()
    a = text.find("<!-- impact-bench:begin -->")
    if a < 0:
        return []
    head = text.rfind("\n## ", 0, a)
    return [""] + text[head + 1:].rstrip("\n").split("\n")


if __name__ == "__main__":
    main()
