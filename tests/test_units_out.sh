#!/usr/bin/env bash
# One run with &material read by every tool (issue 36, "every output in the units of the
# input"): the end-of-run line, rodcontact --summary and --events, scripts/h5extract.py
# (SI by default), scripts/scan.sh's summary.csv and scripts/converge.sh all give the first
# contact onset in seconds, name the unit, and agree to 1e-9 relative. --nondimensional gives
# the file's own values (the onset / scale.time); h5extract's --time is in seconds; one
# --summary of an SI and a nondimensional file is refused.
# The run is the finest level of the converge.sh ladder (level 1 of 2: twice the elements,
# half the step of the input), run again by itself for its end-of-run line.
#   bash tests/test_units_out.sh <rodcontact> <source dir> <scratch dir>
# Exit status: 0 all passed, 1 a check failed, 77 skipped (no program, no GNU parallel
# outside CI, no Python with h5py).
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
PY=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"
export RODCONTACT=$prog

# A copper rod 1 cm long, heated inside; the gap is reached a few steps in and left again.
# In SI units (nondimensional g = 0.3785, eps = 0.01, dt = 2e-4, t_end = 0.02, theta0 =
# 4 x (x-1)^2, converted by tests/tools/si_input.py; the time scale is 0.8886729 s).
cat > rod.nml << 'EOF'
&material units='SI' ell=0.01 /
&contact  g=0.0469735010929373 eps=1.0853251274570797e-17 /
&mesh     n_elements=50 /
&time     dt=0.00017773458031088087 t_end=0.017773458031088086 /
&initial  theta0_poly = 0, 1392631.7701092463, -2785263.5402184925, 1392631.7701092463 /
&output   prefix='rod' snapshot_every=10 /
EOF

# --- converge.sh: two levels, the finest n = 100, dt = 1e-4
bash "$src/scripts/converge.sh" rod.nml --levels 2 --out conv -j 2 > conv.out 2> conv.err
status=$?
check "converge.sh runs (exit 0): $(tail -n 2 conv.err)" equals 0 "$status"
# --- the same run as converge.sh's finest level, by itself
"$prog" rod.nml --set output.prefix=run --set mesh.n_elements=100 --set time.dt=8.886729015544043e-05 \
    --set output.series_every=1 > run.log 2> run.err
check "the run (exit 0)" equals 0 "$?"
end_line=$(tail -n 1 run.err)
echo "  end-of-run line: $end_line"

onset_end=$(sed -n 's/.*contact: 1 onset (first t = \([^ ]*\) s).*/\1/p' <<< "$end_line")
"$prog" --summary-header run.h5 > summary.csv && "$prog" --summary run.h5 >> summary.csv
"$prog" --events run.h5 > events.csv
"$PY" "$src/scripts/h5extract.py" events run.h5 > events.txt 2> extract.err
status=$?   # taken at once: the $(...) in the message below would reset $?
check "h5extract.py events (exit 0): $(cat extract.err)" equals 0 "$status"

# value COLUMN CSV: the value of the named column in the (last) row of a CSV file
value() {
    "$PY" -c 'import csv, sys
rows = list(csv.DictReader(open(sys.argv[2])))
print(rows[-1].get(sys.argv[1], "no column " + sys.argv[1]))' "$1" "$2"
}
onset_summary=$(value 'first_onset_t [s]' summary.csv)
onset_events=$("$PY" -c 'import csv, sys
print(next(r["t [s]"] for r in csv.DictReader(open("events.csv")) if r["kind"] == "onset"))' 2>&1)
check "h5extract.py events names its columns t [s] kind [1]" grep -qx '# t \[s\] kind \[1\]' events.txt
onset_extract=$(awk '!/^#/ && $2 == 1 { print $1; exit }' events.txt)
onset_scan=$(value 'first_onset_t [s]' conv/level_1/summary.csv)
onset_converge=$("$PY" -c 'import csv
r = next(r for r in csv.DictReader(open("conv/converge.csv")) if r["quantity"] == "onset_1")
print(r["fine"] if r["units"] == "s" else "units " + r["units"])' 2>&1)
check "converge.sh's table names the onset's unit" grep -Eq '^onset_1 .* s$' conv.out
echo "  first onset [s]: end line $onset_end, --summary $onset_summary, --events $onset_events," \
     "h5extract $onset_extract, scan.sh $onset_scan, converge.sh $onset_converge"
agree() {   # agree A B: both numbers, equal to 1e-9 relative
    "$PY" -c 'import sys
a, b = float(sys.argv[1]), float(sys.argv[2])
sys.exit(0 if a > 0 and abs(a - b) <= 1e-9 * abs(a) else 1)' "$1" "$2" 2> /dev/null
}
check "the onset is not in the first step (0.1 ms at most is 1 step): $onset_end s" \
    "$PY" -c "import sys; sys.exit(0 if float('$onset_end') > 3 * 1e-4 * 0.8886 else 1)"
check "--summary agrees with the end-of-run line" agree "$onset_end" "$onset_summary"
check "--events agrees" agree "$onset_end" "$onset_events"
check "h5extract.py events (SI by default) agrees" agree "$onset_end" "$onset_extract"
check "scan.sh's summary.csv (converge.sh's level 1) agrees" agree "$onset_end" "$onset_scan"
check "converge.sh's converge.csv (its finest level) agrees" agree "$onset_end" "$onset_converge"

# --- --nondimensional: the file's own values everywhere
scale=$("$PY" "$src/scripts/lib/rodrun.py" attr run.h5 scale.time)
"$prog" --summary-header run.h5 --nondimensional > nd.csv && "$prog" --summary --nondimensional run.h5 >> nd.csv
onset_nd=$(value 'first_onset_t [1]' nd.csv)
check "--summary --nondimensional: first_onset_t [1] = the onset / scale.time" \
    agree "$onset_nd" "$("$PY" -c "print(float('$onset_end') / float('$scale'))")"
check "--events --nondimensional: t [1]" equals "file,event,kind,t [1]" "$("$prog" --events run.h5 --nondimensional | head -n 1)"
"$PY" "$src/scripts/h5extract.py" events run.h5 --nondimensional > events_nd.txt 2> /dev/null
check "h5extract.py --nondimensional agrees" agree "$onset_nd" "$(awk '!/^#/ && $2 == 1 { print $1; exit }' events_nd.txt)"

# --- h5extract's --time in seconds: the run ends at 0.02 x 0.8886 s = 0.01777 s
"$PY" "$src/scripts/h5extract.py" snapshot run.h5 --time 0.0175 > snap.txt 2> snap.err
check "snapshot --time 0.0175 (s) is taken: $(cat snap.err)" grep -q 'at t = 0.0177[0-9]* \[s\]' snap.err
"$PY" "$src/scripts/h5extract.py" snapshot run.h5 --time 0.019 > /dev/null 2> late.err
check "snapshot --time 0.019 (s) is past the end: refused in seconds" \
    grep -q 'the snapshots of run.h5 are at 0 <= t <= 0.01777[0-9]* \[s\]' late.err
check "snapshot --time 0.019 --nondimensional is inside the run (t_end = 0.02)" \
    "$PY" "$src/scripts/h5extract.py" snapshot run.h5 --time 0.019 --nondimensional -o /dev/null
check "no '-0' in the exported columns" bash -c "! grep -Eq '(^| )-0( |$)' snap.txt"
check "the comment lines of SI columns do not say nondimensional" bash -c "! grep -q nondimensional snap.txt"

# --- one table, one unit system
"$prog" "$src/input/exp1.nml" --set output.prefix=plain --set time.t_end=0.01 --set output.quiet=.true.
"$prog" --summary run.h5 plain.h5 > /dev/null 2> mixed.err
status=$?
check "--summary of an SI and a nondimensional file: refused (exit 2), names both" \
    bash -c "[[ $status == 2 ]] && grep -q \"'plain.h5' is nondimensional, 'run.h5' SI\" mixed.err"
check "... and with --nondimensional: two rows" equals 2 "$("$prog" --summary --nondimensional run.h5 plain.h5 | wc -l)"

echo "test_units_out: $n_checks checks, $n_failed failed"
((n_failed == 0))
