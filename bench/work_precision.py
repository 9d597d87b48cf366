"""Post-processing of bench/work_precision.sh (plain text; any python3 will do).

    python3 bench/work_precision.py OUTDIR EXP2_T_END [DT_T_END ...]

Reads OUTDIR/work_precision_{mms,exp2}.raw (output of rodcontact_work_precision) and the
matching .labels files (the sequence of each point, in the same order), and for each
DT_T_END OUTDIR/work_precision_exp2dt_<DT_T_END>.{raw,labels} (time error alone); writes
  OUTDIR/work_precision_{mms,exp2}.dat   one gnuplot data block per sequence (index i),
  OUTDIR/work_precision_params.gp        the sequence names and styles for gnuplot,
  OUTDIR/work_precision.md               tables and the speed-up at equal error.
Speed-up at an error level E: along each sequence, the wall time at which the error
crosses E (log-log interpolation between the two bracketing points); for each scheme the
smallest such time over its sequences (its best pairing of h and dt); the speed-up is
Euler's time over BDF2's.
"""

import math
import os
import sys

ERRORS = [("e_theta_L2", "L2 theta"), ("e_u_H1", "H1 u"), ("e_P_L2", "L2 P")]
ALL_ERRORS = [("e_theta_L2", "L2 theta"), ("e_u_H1", "H1 u"), ("e_v_L2", "L2 v"), ("e_P_L2", "L2 P")]


def parse(outdir, problem):
    raw = open(os.path.join(outdir, "work_precision_%s.raw" % problem)).read().splitlines()
    labels = open(os.path.join(outdir, "work_precision_%s.labels" % problem)).read().split()
    points, extra = [], []
    for line in raw:
        words = line.split()
        if not words:
            continue
        fields = dict(w.split("=", 1) for w in words[1:] if "=" in w)
        if words[0] == "point":
            points.append(fields)
        else:
            extra.append((words[0], fields))
    if len(points) != len(labels):
        sys.exit("work_precision.py: %d points but %d labels for %s" % (len(points), len(labels), problem))
    for p, label in zip(points, labels):
        p["label"] = label
        for k in ("dt", "seconds", "init_seconds") + tuple(e for e, _ in ALL_ERRORS):
            p[k] = float(p[k])
        p["s"], p["steps"] = int(p["s"]), int(p["steps"])
    return points, extra


def sequences(points):
    order = []
    for p in points:
        if p["label"] not in order:
            order.append(p["label"])
    return [(label, sorted((p for p in points if p["label"] == label), key=lambda p: p["seconds"]))
            for label in order]


def time_at(seq, key, level):
    """Wall time at which the error `key` reaches `level` along seq (sorted by time), or None."""
    for a, b in zip(seq, seq[1:]):
        ea, eb = a[key], b[key]
        if ea >= level >= eb and ea > eb:
            w = math.log(ea / level) / math.log(ea / eb)
            return math.exp((1 - w) * math.log(a["seconds"]) + w * math.log(b["seconds"]))
    if seq and seq[0][key] <= level:        # the cheapest point is already below the level
        return seq[0]["seconds"]
    return None


def best_time(seqs, scheme, key, level):
    best = None
    for label, seq in seqs:
        if not label.startswith(scheme + "_"):
            continue
        t = time_at(seq, key, level)
        if t is not None and (best is None or t < best[0]):
            best = (t, label)
    return best


def style(label, counts):
    """Title (gnuplot enhanced text), colour, point type and dash type of a sequence:
    Euler in reds, BDF2 in blues, the pairings told apart by shade and point type."""
    scheme, pairing = label.split("_", 1)
    k = counts[scheme]
    counts[scheme] += 1
    pretty = (pairing.replace("dt", "{/:Italic dt}").replace("h", "{/:Italic h}")
              .replace("sqrt({/:Italic h})", "\u221a{/:Italic h}").replace("^2", "^2"))
    name = "Euler" if scheme == "euler" else "BDF2"
    colours = {"euler": ["#c0392b", "#e67e22", "#7b241c"], "bdf2": ["#1f5fa8", "#16a085", "#5b2c83"]}
    points = {"euler": [7, 5, 9], "bdf2": [6, 4, 8]}
    return "%s, %s" % (name, pretty), colours[scheme][k % 3], points[scheme][k % 3], 1 + k


def write_dat(outdir, problem, seqs):
    with open(os.path.join(outdir, "work_precision_%s.dat" % problem), "w") as f:
        for i, (label, seq) in enumerate(seqs):
            f.write("# index %d: %s\n# s dt steps seconds e_theta_L2 e_u_H1 e_v_L2 e_P_L2\n" % (i, label))
            for p in sorted(seq, key=lambda p: p["s"]):
                f.write("%d %.6g %d %.6g %.6g %.6g %.6g %.6g\n" % (p["s"], p["dt"], p["steps"], p["seconds"],
                        p["e_theta_L2"], p["e_u_H1"], p["e_v_L2"], p["e_P_L2"]))
            f.write("\n\n")


def md_table(seqs):
    rows = ["| sequence | s | dt | steps | stepping time [s] | L2 theta | H1 u | L2 v | L2 P |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for label, seq in seqs:
        for p in sorted(seq, key=lambda p: p["s"]):
            rows.append("| %s | %d | %.4g | %d | %.3g | %.2e | %.2e | %.2e | %.2e |" % (
                label, p["s"], p["dt"], p["steps"], p["seconds"], p["e_theta_L2"], p["e_u_H1"],
                p["e_v_L2"], p["e_P_L2"]))
    return "\n".join(rows)


def speedup_lines(seqs, levels, absolute):
    """levels: {error key: level}"""
    lines = []
    result = {}
    for key, name in ERRORS:
        level = levels[key]
        e = best_time(seqs, "euler", key, level)
        b = best_time(seqs, "bdf2", key, level)
        what = "error" if absolute else "relative error"
        if e and b:
            result[key] = e[0] / b[0]
            lines.append("- %s %s = %.0e: Euler %.3g s (%s), BDF2 %.3g s (%s): time ratio Euler/BDF2 **%.3g**"
                         % (name, what, level, e[0], e[1], b[0], b[1], e[0] / b[0]))
        else:
            lines.append("- %s %s = %.0e: not reached by %s in these runs"
                         % (name, what, level, " and ".join(s for s, r in (("Euler", e), ("BDF2", b)) if not r)))
    return lines, result


def time_error_table(outdir, tend):
    """Observed orders in dt at fixed s (problem exp2dt_<tend>)."""
    points, extra = parse(outdir, "exp2dt_%s" % tend)
    md = []
    for kind, fields in extra:
        if kind == "reference":
            md.append("Reference: %s, s = %s, dt = %s (the same mesh as every run below, so only the time error "
                      "is measured). " % (fields["scheme"], fields["s"], fields["dt"]))
        elif kind == "reference_check":
            md.append("A run with dt = %s differs from it by L2 theta %.1e, H1 u %.1e, L2 v %.1e, "
                      "L2 P %.1e (relative; the reference's own time error is smaller by about 2^p - 1 for "
                      "order p)." % (fields["dt"], float(fields["e_theta_L2"]),
                                                 float(fields["e_u_H1"]), float(fields["e_v_L2"]),
                                                 float(fields["e_P_L2"])))
    md.append("")
    md.append("| scheme | dt | " + " | ".join("%s (order)" % name for _, name in ALL_ERRORS) + " |")
    md.append("|---|---:|" + "---:|" * len(ALL_ERRORS))
    for label, seq in sequences(points):
        seq = sorted(seq, key=lambda p: -p["dt"])
        for i, p in enumerate(seq):
            cells = []
            for key, _ in ALL_ERRORS:
                if i == 0:
                    cells.append("%.2e" % p[key])
                else:
                    q = seq[i - 1]
                    order = math.log(q[key] / p[key]) / math.log(q["dt"] / p["dt"])
                    cells.append("%.2e (%.2f)" % (p[key], order))
            md.append("| %s | %.3g | %s |" % (label.split("_")[0], p["dt"], " | ".join(cells)))
    return md


def main():
    outdir, exp2_tend, dt_tends = sys.argv[1], sys.argv[2], sys.argv[3:]
    mms, _ = parse(outdir, "mms")
    exp2, exp2_extra = parse(outdir, "exp2")
    mms_seqs, exp2_seqs = sequences(mms), sequences(exp2)
    write_dat(outdir, "mms", mms_seqs)
    write_dat(outdir, "exp2", exp2_seqs)
    with open(os.path.join(outdir, "work_precision_params.gp"), "w") as f:
        for problem, seqs in (("mms", mms_seqs), ("exp2", exp2_seqs)):
            n = len(seqs)
            f.write("%s_n = %d\n" % (problem, n))
            for arr in ("title", "colour", "pt", "dash"):
                f.write("array %s_%s[%d]\n" % (problem, arr, n))
            counts = {"euler": 0, "bdf2": 0}
            for i, (label, _) in enumerate(seqs, 1):
                title, colour, pt, dash = style(label, counts)
                f.write("%s_title[%d] = \"%s\"\n" % (problem, i, title))
                f.write("%s_colour[%d] = \"%s\"\n" % (problem, i, colour))
                f.write("%s_pt[%d] = %d\n" % (problem, i, pt))
                f.write("%s_dash[%d] = %d\n" % (problem, i, dash))
        f.write("exp2_tend = '%s'\n" % exp2_tend)
        for kind, fields in exp2_extra:
            if kind == "reference_check":
                f.write("exp2_refcheck_P = %s\n" % float(fields["e_P_L2"]))

    md = []
    md.append("#### (a) Manufactured solution (errors against the exact solution at t = 1)\n")
    lines, speed = speedup_lines(mms_seqs, {"e_theta_L2": 1e-4, "e_u_H1": 1e-4, "e_P_L2": 1e-4}, True)
    md += lines
    md.append("")
    md.append(md_table(mms_seqs))
    md.append("")
    md.append("#### (b) Experiment 2 (errors relative to the reference at t = %s)\n" % exp2_tend)
    for kind, fields in exp2_extra:
        if kind == "reference":
            md.append("- reference: %s, s = %s, dt = %s, %s steps, %.3g s of stepping"
                      % (fields["scheme"], fields["s"], fields["dt"], fields["steps"], float(fields["seconds"])))
        elif kind == "reference_check":
            md.append("- reference check: the same with s = %s, dt = %s differs from it by L2 theta %.2e, "
                      "H1 u %.2e, L2 v %.2e, L2 P %.2e (relative)"
                      % (fields["s"], fields["dt"], float(fields["e_theta_L2"]), float(fields["e_u_H1"]),
                         float(fields["e_v_L2"]), float(fields["e_P_L2"])))
    lines, _ = speedup_lines(exp2_seqs, {"e_theta_L2": 1e-2, "e_u_H1": 1e-2, "e_P_L2": 1e-1}, False)
    md += lines
    md.append("")
    md.append(md_table(exp2_seqs))
    md.append("")
    for tend in dt_tends:
        md.append("#### (c) Experiment 2, the time error alone at t = %s\n" % tend)
        md += time_error_table(outdir, tend)
        md.append("")
    with open(os.path.join(outdir, "work_precision.md"), "w") as f:
        f.write("\n".join(md))
    # one line per target for the caller (scripts/bench.sh)
    with open(os.path.join(outdir, "work_precision_speedup.txt"), "w") as f:
        for key, _ in ERRORS:
            f.write("%s %s\n" % (key, "%.1f" % speed[key] if key in speed else "none"))


if __name__ == "__main__":
    main()
