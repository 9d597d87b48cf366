#!/usr/bin/env bash
# scripts/converge.sh on a case with an exact solution: experiment 1 before contact
# (t <= 0.1; the contact-free problem, tests/tools/exact_linear.py), 40 elements and
# dt = 1e-3 refined in time and space together over three levels (about 2 s). Checks: the
# table's columns; the GCI band of each field row contains the exact error of the finest
# level for >= 90 % of the rows and for every row of u, and is at most 10 x that error;
# a rerun reuses the levels; a deliberately inconsistent ladder (the finest level run with
# the middle level's dt) is warned about and no row of it is reported asymptotic; a ladder
# whose finest level is not finer is refused; bad options exit 2 with a message.
#   bash tests/test_converge.sh <rodcontact> <source dir> <scratch dir>
# Exit status: 0 all passed, 1 a check failed, 77 skipped (no program, no GNU parallel
# outside CI, no Python with h5py and scipy).
set -u
prog=${1:-}
src=${2:-}
scratch=${3:-}
if [[ -z "$prog" || ! -x "$prog" ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
if ! parallel --version 2> /dev/null | grep -q '^GNU parallel'; then
    [[ -n ${CI:-} ]] && { echo "FAIL: GNU parallel not found (scripts/setup.sh should have installed it)"; exit 1; }
    echo "SKIP: scripts/converge.sh needs GNU parallel (scripts/setup.sh installs it)"
    exit 77
fi
PY=$("$src/scripts/lib/find_python.sh") && "$PY" -c 'import scipy' 2> /dev/null ||
    { echo "SKIP: no Python with h5py and scipy"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"
export RODCONTACT=$prog
conv=$src/scripts/converge.sh
case_args=("$src/input/exp1.nml" --set mesh.n_elements=40 --set time.dt=1e-3 --set time.t_end=0.1
           --set output.snapshot_every=20)

# --- the exact case
bash "$conv" "${case_args[@]}" --out exact -j 2 > exact.out 2> exact.err
rc=$?
check "converge.sh runs (exit 0)" equals 0 "$rc"
((rc == 0)) || tail -n 5 exact.err
check "converge.csv has the columns of the issue" equals \
    "quantity,fine,extrapolated,observed_order,gci_abs,gci_rel,status,units" "$(head -n 1 exact/converge.csv)"
check "the scalar rows are there" grep -q '^energy_end,' exact/converge.csv
check "a field row per snapshot and field (7 fields with sigma x 6 snapshots)" equals 42 "$(grep -c '^error_' exact/converge.csv)"
check "the level files: n = 40, 80, 160" equals "40 80 160" \
    "$(for k in 0 1 2; do "$PY" "$src/scripts/lib/rodrun.py" attr exact/level_$k/point_0000.h5 mesh.n_elements; done | xargs)"
check "the level files: dt = 1e-3 / 2^k" equals "0.001 0.0005 0.00025" \
    "$(for k in 0 1 2; do "$PY" "$src/scripts/lib/rodrun.py" attr exact/level_$k/point_0000.h5 time.dt; done | xargs)"
check "the figure is written" test -s exact/converge.png
# 4096 modes: experiment 1's initial data are polynomials (the errors agree with 2^18 modes'
# within 0.4 %, at a tenth of the time)
"$PY" "$src/bench/converge_bands.py" compare exact --exact --modes 4096 --csv bands.csv > bands.out 2> bands.err
status=$?  # taken at once: the $(...) in the message below would reset $?
check "converge_bands.py compare (exit 0): $(cat bands.err)" equals 0 "$status"
read -r n inside within u_out <<< "$("$PY" -c '
import csv, sys
rows = list(csv.DictReader(open("bands.csv")))
inside = [r for r in rows if r["inside"] == "True"]
within = [r for r in inside if float(r["ratio"]) <= 10]
u_out = [r["quantity"] for r in rows if r["quantity"].startswith("error_u@") and r["inside"] != "True"]
print(len(rows), len(inside), len(within), len(u_out))')"
check "35 field rows compared with the exact solution (t > 0)" equals 35 "$n"
check "the exact error inside the band for >= 90 % of the rows ($inside of $n)" test "$((10 * inside))" -ge "$((9 * n))"
check "the band <= 10 x the exact error where it holds it ($within of $inside)" equals "$inside" "$within"
check "the exact error of u inside the band at every snapshot" equals 0 "$u_out"

# --- a rerun reuses the levels (scan.sh skips complete points)
before=$(stat -c %Y exact/level_2/point_0000.h5)
bash "$conv" "${case_args[@]}" --out exact -j 2 > rerun.out 2> rerun.err
check "a rerun succeeds and keeps the level files" equals "0 $before" "$? $(stat -c %Y exact/level_2/point_0000.h5)"

# --- a deliberately inconsistent ladder: the finest level with the middle level's dt
"$prog" "$src/input/exp1.nml" --set mesh.n_elements=160 --set time.dt=5e-4 --set time.t_end=0.1 \
    --set output.snapshot_every=40 --set output.series_every=1 --set output.prefix=bad_finest \
    --set output.quiet=.true. > /dev/null 2>&1
mkdir -p bad
"$PY" "$src/scripts/lib/converge.py" bad --refine both --no-figure exact/level_0/point_0000.h5 \
    exact/level_1/point_0000.h5 bad_finest.h5 > bad.out 2> bad.err
check "an inconsistent ladder is analysed (exit 0)" equals 0 "$?"
check "it is warned about" grep -q "inconsistent ladder: level 2 refines h by 2 but dt by 1" bad.err
check "no row of it is asymptotic" equals 0 "$(cut -d, -f7 bad/converge.csv | grep -c '^asymptotic$')"
"$PY" "$src/scripts/lib/converge.py" bad --refine time --no-figure exact/level_0/point_0000.h5 \
    exact/level_1/point_0000.h5 exact/level_0/point_0000.h5 > bad2.out 2> bad2.err
check "a finest level that is not finer: exit 2" equals 2 "$?"
check "... naming the level" grep -q "level 2 is not finer than level 1" bad2.err

# --- bad usage: exit 2 with a message, nothing run
refused() {   # refused <expected message part> <converge.sh arguments ...>
    local part=$1 status
    shift
    bash "$conv" "$@" > refused.out 2> refused.err
    status=$?
    [[ $status == 2 ]] || { echo "  exit status $status, expected 2"; return 1; }
    grep -q -F -- "$part" refused.err || { echo "  no '$part' in: $(cat refused.err)"; return 1; }
    [[ ! -e never ]] || { echo "  'never' was created"; return 1; }
}
e1=$src/input/exp1.nml
check "no input: exit 2" refused "no input file" --out never
check "missing input: exit 2" refused "cannot read input file 'nope.nml'" nope.nml --out never
check "unknown option: exit 2" refused "unknown option '--level'" "$e1" --level 3 --out never
check "--levels 1: exit 2" refused "--levels: at least 2 levels" "$e1" --levels 1 --out never
check "--levels x: exit 2" refused "--levels: expected an integer" "$e1" --levels x --out never
check "--ratio 1: exit 2" refused "--ratio: the refinement ratio must be > 1, got 1" "$e1" --ratio 1 --out never
check "--ratio -2: exit 2" refused "--ratio: expected a number > 1, got '-2'" "$e1" --ratio -2 --out never
check "--refine x: exit 2" refused "--refine: expected space, time or both, got 'x'" "$e1" --refine x --out never
check "-j 0: exit 2" refused "-j: expected a positive integer" "$e1" -j 0 --out never
check "--set output.prefix: exit 2" refused "converge.sh sets output.prefix itself" "$e1" --set output.prefix=a --out never
check "adaptive steps: exit 2" refused "adaptive steps and meshes are refused" "$e1" --set time.adaptive=.true. --out never
sed 's|^&time *dt=1e-4 t_end=3.0 /|\&time dt=1e-4 t_end=3.0 adaptive=.true. /|' "$e1" > adaptive.nml
check "an input with adaptive steps: exit 2" refused "refines fixed steps on uniform meshes" adaptive.nml --out never
bash "$conv" --help > help.out 2>&1
check "--help: exit 0 and the usage" equals "0 1" "$? $(grep -c '^ *scripts/converge.sh INPUT' help.out)"

echo "test_converge: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
