#!/usr/bin/env python3
"""Is a figure legible? Reads the text boxes of a PDF figure (`pdftotext -bbox`, Debian
poppler-utils) and reports

  - a text box that is not inside the page (a colour-bar label cut at the edge: poppler keeps
    the characters that start on the page, so a cut word still ends past the edge);
  - two text boxes that overlap (tick labels run together, a label over a tick label);
  - a y label (rotated text) that lies over another panel: inside the span of the nearest row
    of x tick labels below it that is not its own (a row of ticks is one panel's x axis);
  - an expected word (--expect, e.g. 'q(x,': the label of a panel) that is not on the page.

    python3 tests/tools/figure_layout.py FIGURE.pdf [--expect WORD ...] [--tolerance PT]

Prints one line per problem. Exit status: 0 legible; 1 a problem; 2 usage, or pdftotext
missing or failing.
"""

import argparse
import html
import re
import shutil
import subprocess
import sys

WORD = re.compile(r'<word xMin="([-0-9.e]+)" yMin="([-0-9.e]+)" xMax="([-0-9.e]+)" yMax="([-0-9.e]+)">(.*?)</word>')
PAGE = re.compile(r'<page width="([0-9.]+)" height="([0-9.]+)">')
NUMBER = re.compile(r"^[-−+]?[0-9]+(\.[0-9]*)?$")


def boxes(pdf):
    """(width, height, [(x0, y0, x1, y1, text)]) of the first page of pdf."""
    out = subprocess.run(["pdftotext", "-bbox", "-f", "1", "-l", "1", pdf, "-"],
                         capture_output=True, text=True, check=True).stdout
    w, h = (float(v) for v in PAGE.search(out).groups())
    return w, h, [(float(a), float(b), float(c), float(d), html.unescape(t)) for a, b, c, d, t in WORD.findall(out)]


def overlap(p, q, tol):
    return min(p[2], q[2]) - max(p[0], q[0]) > tol and min(p[3], q[3]) - max(p[1], q[1]) > tol


def tick_rows(words):
    """The x axes: runs of at least four numbers on one line, evenly spaced (a row across
    several panels splits where the spacing changes; the lowest y tick labels of panels side
    by side make runs of three); [(first, last centre, y)]."""
    rows = {}
    for w in words:
        if NUMBER.match(w[4]):
            rows.setdefault(round(w[1], 1), []).append((w[0] + w[2]) / 2)
    axes = []
    for y, centres in rows.items():
        centres.sort()
        run = [centres[0]]
        for c in centres[1:]:
            if len(run) >= 2 and abs((c - run[-1]) - (run[-1] - run[-2])) > 0.05 * (run[-1] - run[-2]):
                if len(run) >= 4:
                    axes.append((run[0], run[-1], y))
                run = [c]
            else:
                run.append(c)
        if len(run) >= 4:
            axes.append((run[0], run[-1], y))
    return axes


def problems(pdf, expect, tol):
    w, h, words = boxes(pdf)
    out = []
    for b in words:
        if b[0] < 0 or b[1] < 0 or b[2] > w or b[3] > h:
            out.append(f"'{b[4]}' is not inside the page ({b[0]:.1f}, {b[1]:.1f})-({b[2]:.1f}, {b[3]:.1f}), page {w:g} x {h:g}")
    for i, p in enumerate(words):
        for q in words[i + 1:]:
            if overlap(p, q, tol):
                out.append(f"'{p[4]}' and '{q[4]}' overlap at ({max(p[0], q[0]):.1f}, {max(p[1], q[1]):.1f})")
    axes = tick_rows(words)
    for r in words:   # rotated text: taller than wide, more than two characters
        if len(r[4]) <= 2 or r[3] - r[1] <= r[2] - r[0]:
            continue
        below = [a for a in axes if a[2] >= r[3]]
        if not below:
            continue
        y = min(a[2] for a in below)
        for a in below:
            if a[2] == y and a[0] < r[2] and r[0] < a[1]:
                out.append(f"the y label '{r[4]}' lies over the panel of the x axis at y = {y:.1f} "
                           f"({a[0]:.1f} to {a[1]:.1f})")
    texts = {b[4] for b in words}
    out += [f"'{e}' is not on the page" for e in expect if e not in texts]
    return out


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("pdf")
    p.add_argument("--expect", nargs="*", default=[], help="words that must be on the page")
    p.add_argument("--tolerance", type=float, default=0.5, help="overlap ignored below this (points)")
    a = p.parse_args(argv[1:])
    if shutil.which("pdftotext") is None:
        sys.stderr.write("figure_layout.py: pdftotext not found (Debian: poppler-utils)\n")
        return 2
    try:
        found = problems(a.pdf, a.expect, a.tolerance)
    except (subprocess.CalledProcessError, AttributeError) as exc:
        sys.stderr.write(f"figure_layout.py: cannot read the text of {a.pdf}: {exc}\n")
        return 2
    for line in found:
        print(f"{a.pdf}: {line}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
