"""The small text formats the scripts share besides run files (those are scripts/lib/rodrun.py):
column files and assignments for gnuplot, the key=value files the benchmark scripts write next
to their raw data (meta files) and the spec files that list their points, and how times and
relative errors are printed. Plain Python: only write_columns needs numpy (the benchmark
reports run with any python3).
"""

import math


def write_columns(path, titles, columns):
    """A text file for gnuplot: a line of quoted column titles, then the columns (%.9g)."""
    import numpy as np
    with open(path, "w", encoding="utf-8") as out:
        out.write(" ".join('"%s"' % s for s in titles) + "\n")
        np.savetxt(out, np.column_stack(columns), fmt="%.9g")


def gnuplot_assignment(name, value):
    """A line `name = value` for a gnuplot script: strings quoted, NaN as NaN, numbers %.10g."""
    if isinstance(value, str):
        return '%s = "%s"' % (name, value)
    if isinstance(value, float) and math.isnan(value):
        return "%s = NaN" % name
    return "%s = %.10g" % (name, value)


def read_meta(path):
    """A meta file: one key=value per line (the value is the rest of the line); other lines
    are skipped. Returns {key: value}, both strings."""
    meta = {}
    with open(path) as f:
        for line in f:
            if "=" in line:
                k, v = line.rstrip("\n").split("=", 1)
                meta[k] = v
    return meta


def spec_lines(path):
    """The words of every non-blank line of a spec file (one benchmark point per line)."""
    with open(path) as f:
        return [line.split() for line in f if line.split()]


def fmt_time(t, decimals):
    """A time for a label: at most `decimals` decimals, trailing zeros dropped ('0' for 0)."""
    return ("%.*f" % (decimals, t)).rstrip("0").rstrip(".") if t != 0 else "0"


def pct(e, digits):
    """A relative error as a percentage with `digits` significant digits ('–' for None, NaN)."""
    if e is None or (isinstance(e, float) and math.isnan(e)):
        return "–"
    return ("%.*g %%" % (digits, 100 * e)) if 100 * e >= 0.01 else ("%.1e %%" % (100 * e))
