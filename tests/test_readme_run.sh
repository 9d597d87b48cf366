#!/usr/bin/env bash
# The README's section "Your own run" works as written: its ```sh blocks are taken from
# README.md (so that the test and the README cannot drift), run one after another in a
# scratch directory that looks like the repository root (build/rodcontact, scripts/ and
# input/ linked there), and every file that a command's comment names ('# -> FILE, FILE')
# must exist and not be empty afterwards; the figures the README states for its copper rod
# (peak temperature rise, contact onset and release, largest displacement) hold to 5 %, and
# the scan's points give different summary rows. The blocks with --slurm are left out: they need a
# Slurm cluster, and tests/test_slurm.sh checks scan.sh --slurm on one.
#
#   bash tests/test_readme_run.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 passed, 1 failed, 77 skipped (no gnuplot with cairo terminals, no Python
# with h5py, or no GNU parallel outside CI).
set -u
prog=${1:-} src=${2:-} scratch=${3:-}
if [[ -z "$prog" || ! -x "$prog" || -z "$src" || -z "$scratch" ]]; then
    echo "usage: bash test_readme_run.sh <rodcontact> <source dir> <scratch dir>"; exit 1
fi
skip() { [[ -n ${CI:-} ]] && { echo "FAIL (CI must run this test): $*"; exit 1; }; echo "SKIP: $*"; exit 77; }
command -v gnuplot > /dev/null 2>&1 || skip "gnuplot not found"
"$src/scripts/lib/find_python.sh" > /dev/null 2>&1 || skip "no Python with h5py"
parallel --version 2> /dev/null | grep -q '^GNU parallel' || skip "no GNU parallel (scripts/scan.sh)"

. "$src/tests/lib/checks.sh"   # check, equals, n_checks, n_failed

# the section's code blocks: from '## Your own run' to the next '## ' heading
script=$scratch/own_run.sh
awk '
    /^## / { inside = ($0 == "## Your own run") }
    inside && /^```sh$/ { block = ""; in_block = 1; next }
    inside && in_block && /^```$/ { in_block = 0; if (block !~ /--slurm/) printf "%s", block; next }
    in_block { block = block $0 "\n" }
' "$src/README.md" > "$script"
n_commands=$(grep -c -v -e '^[[:space:]]*$' -e '^[[:space:]]' -e '^&' -e '^EOF$' -e '^cat >' "$script")
check "README.md has a section 'Your own run' with commands ($n_commands)" test "$n_commands" -ge 8
check "the section's commands cover run, plot, h5extract --si, --summary, --events and scan.sh" \
    bash -c "grep -q '^build/rodcontact runs/' '$script' && grep -q '^scripts/plot.sh' '$script' &&
             grep -q '^scripts/h5extract.py .*--si' '$script' && grep -q -- '--summary ' '$script' &&
             grep -q -- '--events ' '$script' && grep -q '^scripts/scan.sh' '$script'"
check "the Slurm commands are in the README but not run here" grep -q -- '--slurm' "$src/README.md"

# the files the commands say they write
mapfile -t files < <(grep -o '# -> .*' "$script" | sed 's/^# -> //' | tr ',' '\n' | sed 's/^ *//; s/ *$//' | grep -v '^$')
check "the commands name the files they write (${#files[@]})" test "${#files[@]}" -ge 8

# a directory that looks like the repository root
work=$scratch/repo
rm -rf "$work"
mkdir -p "$work/build"
ln -s "$src/scripts" "$work/scripts"
ln -s "$src/input" "$work/input"
ln -s "$prog" "$work/build/rodcontact"
(cd "$work" && bash -e "$script") > "$scratch/own_run.log" 2>&1
status=$?
check "the commands of 'Your own run' run without an error (log: own_run.log)" equals 0 "$status"
for f in "${files[@]}"; do
    check "written: $f" test -s "$work/$f"
done
check "the SI series: t in s, u_end in m" grep -q '^# t \[s\] u_end \[m\]$' "$work/runs/mybar_u_end.txt"
check "the plot's axes are in SI units (PDF text)" \
    bash -c "! command -v pdftotext > /dev/null || pdftotext '$work/runs/mybar_series.pdf' - | grep -q 't \[s\]'"
check "the summary: a header and one row, in contact" equals "2 yes" \
    "$(wc -l < "$work/runs/mybar_summary.csv") $(tail -n 1 "$work/runs/mybar_summary.csv" | cut -d, -f3)"
# the figures the README states for the copper rod ("What it shows"), to 5 %
check "the README's figures: 10 K, onset 0.028 s, u(l,t) 0.53 um at 0.04 s, release 0.63 s" \
    "$("$src/scripts/lib/find_python.sh")" - "$work/runs/mybar.h5" << 'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
si = lambda d: f[d][()] * f[d].attrs["si_factor"]
t, u, kind, te = si("series/t"), si("series/u_end"), f["events/kind"][()], si("events/t")
got = [si("snapshots/theta").max(), te[kind == 1][0], u.max(), t[u.argmax()], te[kind != 1][0]]
want = [10.0, 0.028, 0.53e-6, 0.04, 0.63]
print("  got", got)
sys.exit(0 if len(te) == 2 and all(abs(g / w - 1) <= 0.05 for g, w in zip(got, want)) else 1)
PY
check "the scan's summary rows differ (g and ell change the run)" equals 4 \
    "$(tail -n +2 "$work/runs/myscan/summary.csv" | cut -d, -f4- | sort -u | wc -l)"
check "the scan: 4 points, all complete" equals "4" \
    "$(tail -n +2 "$work/runs/myscan/summary.csv" | grep -c ',complete,0,')"
check "nothing written outside the working directory's runs/" equals "build input runs scripts" \
    "$(ls "$work" | tr '\n' ' ' | sed 's/ $//')"

echo "test_readme_run: $n_checks checks, $n_failed failed"
if ((n_failed > 0)); then
    echo "--- the commands run:"; cat "$script"
    echo "--- their output:"; cat "$scratch/own_run.log"
    exit 1
fi
