"""Turn the summary.csv of the contact-map scan (scripts/scans/contact_map.sh) into the
text files scripts/scans/contact_map.gp plots. Standard library only.

    python3 scripts/scans/contact_map_grid.py SUMMARY_CSV OUT_DIR

OUT_DIR receives
    contact_map.cells.dat   one row per point: varpi, A, the cell around it (varpi_lo,
                            varpi_hi: geometric midpoints; A_lo, A_hi), max u(1,t)/g,
                            contact time, contact (1/0), status (1 complete, 0 not)
    contact_map.grid.dat    log10(varpi), A, max u(1,t)/g in gnuplot grid blocks (one
                            block per varpi, blank line between), for the contour
    contact_map.params.gp   gnuplot assignments: ranges, counts, the boundary found
Exit status 0 written, 1 the CSV lacks a column or a point, 2 usage.
"""

import csv
import math
import sys

VARPI = "model.varpi"
AMP = "initial.theta0_step(1)"


def midpoints(values, geometric):
    """Cell edges around sorted values: midpoints between neighbours, mirrored at the ends."""
    if len(values) == 1:
        return [(values[0] * 0.9, values[0] * 1.1)] if geometric else [(values[0] - 1, values[0] + 1)]
    edges = []
    for i in range(len(values) - 1):
        a, b = values[i], values[i + 1]
        edges.append(math.sqrt(a * b) if geometric else 0.5 * (a + b))
    if geometric:
        first = values[0] ** 2 / edges[0]
        last = values[-1] ** 2 / edges[-1]
    else:
        first = 2 * values[0] - edges[0]
        last = 2 * values[-1] - edges[-1]
    edges = [first] + edges + [last]
    return [(edges[i], edges[i + 1]) for i in range(len(values))]


def number(text):
    return float(text) if text not in ("", None) else float("nan")


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    csv_path, out_dir = argv[1], argv[2]
    with open(csv_path, newline="") as f:
        # the columns by name without their unit ('first_contact_t [1]': first_contact_t)
        rows = [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(f)]
    for column in (VARPI, AMP, "status", "max_u_end_over_g", "contact_time", "contact", "first_contact_t"):
        if rows and column not in rows[0]:
            print(f"contact_map_grid: {csv_path} has no column '{column}'", file=sys.stderr)
            return 1
    varpis = sorted({float(r[VARPI]) for r in rows})
    amps = sorted({float(r[AMP]) for r in rows})
    by_point = {(float(r[VARPI]), float(r[AMP])): r for r in rows}
    if len(by_point) != len(varpis) * len(amps):
        print(f"contact_map_grid: {csv_path}: {len(by_point)} points, expected a full "
              f"{len(varpis)} x {len(amps)} grid", file=sys.stderr)
        return 1
    x_cells = midpoints(varpis, geometric=True)
    y_cells = midpoints(amps, geometric=False)

    n_complete = n_contact = 0
    first_contact_max = 0.0
    boundary = []   # per varpi: the smallest amplitude with contact (or None)
    with open(f"{out_dir}/contact_map.cells.dat", "w") as cells, \
            open(f"{out_dir}/contact_map.grid.dat", "w") as grid:
        cells.write("# varpi A varpi_lo varpi_hi A_lo A_hi max_u_over_g contact_time contact complete\n")
        grid.write("# log10(varpi) A max_u_over_g\n")
        for i, varpi in enumerate(varpis):
            smallest = None
            for j, amp in enumerate(amps):
                r = by_point[(varpi, amp)]
                complete = r["status"] == "complete"
                ratio = number(r["max_u_end_over_g"]) if complete else float("nan")
                ctime = number(r["contact_time"]) if complete else float("nan")
                contact = 1 if complete and r["contact"] == "yes" else 0
                n_complete += complete
                n_contact += contact
                if contact:
                    first_contact_max = max(first_contact_max, number(r["first_contact_t"]))
                    if smallest is None:
                        smallest = amp
                cells.write(f"{varpi:.10g} {amp:.10g} {x_cells[i][0]:.10g} {x_cells[i][1]:.10g} "
                            f"{y_cells[j][0]:.10g} {y_cells[j][1]:.10g} {ratio:.10g} {ctime:.10g} "
                            f"{contact} {int(complete)}\n")
                grid.write(f"{math.log10(varpi):.10g} {amp:.10g} {ratio:.10g}\n")
            grid.write("\n")
            boundary.append(smallest)

    with open(f"{out_dir}/contact_map.params.gp", "w") as p:
        p.write(f"varpi_min = {x_cells[0][0]:.10g}; varpi_max = {x_cells[-1][1]:.10g}\n")
        p.write(f"amp_min = {y_cells[0][0]:.10g}; amp_max = {y_cells[-1][1]:.10g}\n")
        p.write(f"n_points = {len(rows)}; n_complete = {n_complete}; n_contact = {n_contact}\n")
        p.write(f"first_contact_latest = {first_contact_max:.10g}\n")
    print(f"contact_map_grid: {len(rows)} points, {n_complete} complete, {n_contact} with contact; "
          f"latest first contact t = {first_contact_max:.4g}", file=sys.stderr)
    print("contact_map_grid: smallest amplitude with contact, per varpi:", file=sys.stderr)
    for varpi, smallest in zip(varpis, boundary):
        print(f"    varpi = {varpi:<10.4g} A >= {smallest if smallest is not None else '(none up to ' + format(amps[-1], 'g') + ')'}",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
