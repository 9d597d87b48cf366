#!/usr/bin/env bash
# Tables of &initial (*_file: rows of position and value, docs/input.md "Tables"):
#  1. a table of theta0 = 40 x (x - 1)^2 at the nodes of s = 100 (with comments, a blank line,
#     commas, tabs and blanks between the columns) gives the run of theta0_poly = 0, 40, -80,
#     40 (experiment 1) to round-off: every /snapshots field within 1e-12 of its largest value;
#  2. between its rows a table is interpolated linearly onto the nodes: the two rows (0, 2),
#     (1, 0) for p0 give P(x, 0) = 2 (1 - x) at every node;
#  3. the output records the table's contents (root attribute initial.theta0_table:
#     positions, then values) beside its name (initial.theta0_file);
#  4. a restart from a checkpoint of a run with a table continues it (exit 0) while the
#     table is unchanged, and refuses it (exit 2, naming initial.theta0_table) once the
#     file's contents have changed under the same name.
# Tables that are refused: tests/test_bad_input.sh.
#
#   bash tests/test_initial_table.sh <path to rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
. "$src/tests/lib/checks.sh"
cd "$scratch" && rm -rf ./* || exit 1

common=(--set mesh.n_elements=100 --set time.dt=1e-3 --set output.snapshot_every=10 --set output.quiet=.true.)
"$py" - > theta.txt <<'PY'
print("# theta0 = 40 x (x - 1)^2 at the nodes i/100\n#  x    theta0")
for i in range(101):
    x = i / 100
    sep = (",", "\t", "   ")[i % 3]
    print(f"  {x!r}{sep}{40 * x * (x - 1) ** 2!r}" + ("   # a comment" if i % 10 == 0 else ""))
    if i == 50:
        print("")
PY
printf '0 2\n1 0\n' > p.txt
"$exe" "$src/input/exp1.nml" "${common[@]}" --set time.t_end=0.05 --set output.prefix="'poly'" || echo "FAIL: the polynomial run"
"$exe" "$src/input/exp1.nml" "${common[@]}" --set time.t_end=0.05 --set initial.theta0_poly=0,0,0,0 \
    --set initial.theta0_file="'theta.txt'" --set output.prefix="'table'" || echo "FAIL: the table run"
"$exe" "$src/input/exp1.nml" "${common[@]}" --set time.t_end=0.05 --set initial.p0_poly=0,0,0,0,0 \
    --set initial.p0_file="'p.txt'" \
    --set output.prefix="'linear'" || echo "FAIL: the two-row table run"

check "a table of theta0 at the nodes gives the polynomial's run (every field within 1e-12)" \
    "$py" - poly.h5 table.h5 <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
worst = max(np.abs(a["snapshots"][k][()] - b["snapshots"][k][()]).max() / max(np.abs(a["snapshots"][k][()]).max(), 1e-300)
            for k in ("u", "v", "theta", "P", "q", "eta"))
print("  largest relative difference %.2e" % worst)
sys.exit(0 if worst <= 1e-12 else 1)
PY
check "a two-row table is interpolated linearly: P(x, 0) = 2 (1 - x)" "$py" - linear.h5 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
x, p = f["mesh/x"][()], f["snapshots/P"][0]
print("  max |P(x, 0) - 2 (1 - x)| = %.1e" % np.abs(p - 2 * (1 - x)).max())
sys.exit(0 if np.abs(p - 2 * (1 - x)).max() <= 1e-14 else 1)
PY
check "the output records the table's contents and its file" "$py" - table.h5 theta.txt <<'PY'
import sys, h5py, numpy as np
a = h5py.File(sys.argv[1], "r").attrs
rows = np.array([[float(v) for v in line.split("#")[0].replace(",", " ").split()]
                 for line in open(sys.argv[2]) if line.split("#")[0].strip()])
table = a["initial.theta0_table"]
ok = a["initial.theta0_file"] == "theta.txt" and np.array_equal(table, np.concatenate([rows[:, 0], rows[:, 1]]))
print("  initial.theta0_file = %r, initial.theta0_table: %d values" % (a["initial.theta0_file"], table.size))
sys.exit(0 if ok else 1)
PY

# 4. restarts
restart=(--set initial.theta0_poly=0,0,0,0 --set initial.theta0_file="'theta.txt'")
"$exe" "$src/input/exp1.nml" "${common[@]}" "${restart[@]}" --set time.t_end=0.05 --set output.checkpoint_every=20 \
    --set output.prefix="'ckpt'" || echo "FAIL: the run with checkpoints"
"$exe" "$src/input/exp1.nml" "${common[@]}" "${restart[@]}" --set time.t_end=0.08 \
    --set time.restart_from="'ckpt.h5'" --set output.prefix="'same'" > same.log 2>&1
check "a restart with the same table continues (exit 0)" equals 0 $?
sed -i '5s/^\(  [^ ,\t]*[ ,\t]*\).*/\10.5/' theta.txt
"$exe" "$src/input/exp1.nml" "${common[@]}" "${restart[@]}" --set time.t_end=0.08 \
    --set time.restart_from="'ckpt.h5'" --set output.prefix="'changed'" > changed.log 2>&1
status=$?
cat changed.log
check "a restart with the table changed under the same name exits 2" equals 2 $status
check "... naming initial.theta0_table" grep -q "initial.theta0_table" changed.log

echo "$n_checks checks, $n_failed failed"
((n_failed == 0))
