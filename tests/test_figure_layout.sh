#!/usr/bin/env bash
# scripts/plot.sh's figures are legible in both unit systems: for a run with &material (SI axes,
# values of 10^6 K and 10^13 Pa), a nondimensional one (experiment 1) and experiment 2 with
# Signorini's law, every text box of every figure (surface, profiles, series; the PDFs) is
# inside the page, no two overlap, no y label lies over the next panel, and the label of every
# panel is there (tests/tools/figure_layout.py, with pdftotext -bbox). Signorini's contact
# interval is shaded (plotdata.py finds it from /events, and from the contact stress in a file
# without them: its penetration is always 0). A file still being written (.h5.part, status
# 'incomplete') is drawn as far as it goes, without a gnuplot warning: with one snapshot the
# profiles and the series (no surface, said so); with one series row no series (exit 3 when
# that is all that was asked for); the .h5.part of a run still going is drawn, and said to be.
#
#   bash tests/test_figure_layout.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 passed, 1 failed, 77 skipped (no gnuplot with cairo terminals, no h5py, or
# no pdftotext: Debian poppler-utils, which scripts/setup.sh installs).
set -u
prog=${1:-} src=${2:-} scratch=${3:-}
if [[ -z "$prog" || ! -x "$prog" || -z "$src" || -z "$scratch" ]]; then
    echo "usage: bash test_figure_layout.sh <rodcontact> <source dir> <scratch dir>"; exit 1
fi
command -v gnuplot >/dev/null 2>&1 || { echo "SKIP: gnuplot not found"; exit 77; }
gnuplot -e "set terminal pdfcairo" </dev/null >/dev/null 2>&1 || { echo "SKIP: no pdfcairo terminal"; exit 77; }
command -v pdftotext >/dev/null 2>&1 || { echo "SKIP: no pdftotext (Debian: poppler-utils)"; exit 77; }
py=$("$src/scripts/lib/find_python.sh" 2>/dev/null) || { echo "SKIP: no Python with h5py"; exit 77; }
dir="$scratch/figure_layout"
rm -rf "$dir"; mkdir -p "$dir"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
copy() { "$py" "$src/scripts/lib/nml_copy.py" "$@"; }

# 1. three short runs (a few tenths of a second each); the SI one is the README's rod of 1 cm, its
#    values far from 1 (10^6 K, 10^13 Pa: the nondimensional g = 0.5, eps = 0.01, dt = 2e-3,
#    t_end = 1, theta0 = 40 x (x-1)^2, u1 = 10 x in SI units, by tests/tools/si_input.py)
cat > "$dir/si.nml" <<EOF
&material units='SI' ell=0.01 /
&contact  g=0.06205218110031347 eps=1.0853251274570797e-17 /
&mesh     n_elements=40 /
&time     dt=0.0017773458031088085 t_end=0.8886729015544043 /
&initial  theta0_poly = 0, 13926317.701092463, -27852635.402184926, 13926317.701092463
          u1_poly = 0, 1.3965134076165966 /
&output   prefix='$dir/si' snapshot_every=25 quiet=.true. /
EOF
copy "$src/input/exp1.nml" "$dir/nd.nml" "output.prefix='$dir/nd'" output.quiet=.true. \
    mesh.n_elements=50 time.dt=2e-3 time.t_end=1 output.snapshot_every=25
copy "$src/input/exp2.nml" "$dir/sig.nml" "output.prefix='$dir/sig'" output.quiet=.true. \
    mesh.n_elements=100 time.dt=1e-3 time.t_end=0.6 output.snapshot_every=20 "contact.law='signorini'"
for r in si nd sig; do
    "$prog" "$dir/$r.nml" >"$dir/$r.log" 2>&1 || fail "the run $r failed: $(tail -n 3 "$dir/$r.log")"
done

# 2. every figure of each run: the text boxes
labels=(u P θ q η σ)
for r in si nd sig; do
    if ! "$src/scripts/plot.sh" "$dir/$r.h5" --style all --out "$dir/figs" >"$dir/plot_$r.log" 2>&1; then
        fail "plot.sh --style all on $r: $(cat "$dir/plot_$r.log")"; continue
    fi
    for st in surface profiles series; do
        expect=()
        # the panels' labels, and the x axis' label (a word of its own: 'x' or 'x [mm]')
        [[ $st == series ]] && expect=(obstacle contact t) || expect=("${labels[@]/%/(x,}" x)
        "$py" "$src/tests/tools/figure_layout.py" "$dir/figs/${r}_$st.pdf" --expect "${expect[@]}" \
            >"$dir/layout.out" 2>&1 || fail "$(cat "$dir/layout.out")"
    done
done

# 3. Signorini: the contact interval from /events, and from the contact stress without them
"$py" "$src/scripts/lib/plotdata.py" "$dir/sig.h5" "$dir/sig-data" >/dev/null || fail "plotdata.py on sig.h5"
cp "$dir/sig.h5" "$dir/sig_noevents.h5"
"$py" -c 'import sys, h5py; del h5py.File(sys.argv[1], "r+")["events"]' "$dir/sig_noevents.h5"
"$py" "$src/scripts/lib/plotdata.py" "$dir/sig_noevents.h5" "$dir/sig-data2" >/dev/null || fail "plotdata.py on sig_noevents.h5"
"$py" - "$dir/sig.h5" "$dir/sig-data/params.gp" "$dir/sig-data2/params.gp" <<'PY' || fail "Signorini's contact interval is not shaded: $(grep contact_on "$dir"/sig-data*/params.gp)"
import re, sys, h5py
f = h5py.File(sys.argv[1], "r")
onset = float(f["events/t"][0])
assert f["series/penetration"][:].max() == 0.0      # why the penetration cannot say it
for path in sys.argv[2:]:
    p = dict(re.findall(r'^(\w+) = "?([^"\n]*)"?$', open(path).read(), re.M))
    assert int(p["n_contact"]) >= 1, path
    assert abs(float(p["contact_on"].split()[0]) - onset) < 2e-3, (path, p["contact_on"], onset)
PY

# 4. a file still being written: one snapshot so far, then one series row too
part() {   # part <name> <series rows kept>: a copy of nd.h5 cut to one snapshot, status 'incomplete'
    cp "$dir/nd.h5" "$dir/$1.h5.part"
    "$py" - "$dir/$1.h5.part" "$2" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    for name, d in list(f["snapshots"].items()):
        if isinstance(d, h5py.Dataset):
            data = d[:1]
            del f["snapshots/" + name]
            f["snapshots/" + name] = data
    n = int(sys.argv[2])
    for name in list(f["series"]):
        data = f["series/" + name][:n]
        del f["series/" + name]
        f["series/" + name] = data
    del f["events"]
    f.attrs["status"] = "incomplete"
PY
}
part running 200
"$src/scripts/plot.sh" "$dir/running.h5.part" --style all --out "$dir/part" >"$dir/part.log" 2>&1 ||
    fail "plot.sh on a .part with one snapshot: $(cat "$dir/part.log")"
grep -q "status 'incomplete'" "$dir/part.log" && grep -q "no surface" "$dir/part.log" ||
    fail "plot.sh on a .part does not say what it draws: $(cat "$dir/part.log")"
[[ -s "$dir/part/running_profiles.pdf" && -s "$dir/part/running_series.pdf" && ! -e "$dir/part/running_surface.pdf" ]] ||
    fail "a .part with one snapshot: expected the profiles and the series, got: $(ls "$dir/part")"
"$src/scripts/plot.sh" "$dir/running.h5.part" --out "$dir/part2" >"$dir/part2.log" 2>&1 &&
    [[ -s "$dir/part2/running_profiles.pdf" ]] || fail "--style surface on one snapshot: no profiles instead: $(cat "$dir/part2.log")"
part started 1
"$src/scripts/plot.sh" "$dir/started.h5.part" --style all --out "$dir/part3" >"$dir/part3.log" 2>&1 &&
    grep -q "no series" "$dir/part3.log" && [[ $(ls "$dir/part3" | tr '\n' ' ') == "started_profiles.pdf started_profiles.png " ]] ||
    fail "a .part with one snapshot and one series row: expected the profiles only, and 'no series': $(ls "$dir/part3"), $(cat "$dir/part3.log")"
"$src/scripts/plot.sh" "$dir/started.h5.part" --style series --out "$dir/part4" >"$dir/part4.log" 2>&1
st=$?
[[ $st -eq 3 ]] && grep -q "nothing to draw yet" "$dir/part4.log" ||
    fail "--style series on one series row: expected exit 3 and 'nothing to draw yet', got $st: $(cat "$dir/part4.log")"
grep -q "gnuplot said" "$dir"/part*.log && fail "gnuplot warnings on a .part: $(grep -h -A1 'gnuplot said' "$dir"/part*.log)"

# 5. a run still going: its .h5.part (opened by a SWMR reader) is drawn, and said to be incomplete
copy "$src/input/exp1.nml" "$dir/live.nml" "output.prefix='$dir/live'" output.quiet=.true. \
    mesh.n_elements=200 time.dt=1e-4 time.t_end=1000 output.snapshot_every=200
"$prog" "$dir/live.nml" >"$dir/live.log" 2>&1 &
live=$!
for _ in $(seq 50); do [[ -s "$dir/live.h5.part" ]] && break; sleep 0.1; done
sleep 1
"$src/scripts/plot.sh" "$dir/live.h5.part" --style all --out "$dir/live" >"$dir/live_plot.log" 2>&1 ||
    fail "plot.sh on a running run's .h5.part: $(cat "$dir/live_plot.log")"
kill -0 "$live" 2>/dev/null || fail "the live run ended before the end of the test: $(cat "$dir/live.log")"
kill -KILL "$live" 2>/dev/null; wait "$live" 2>/dev/null
grep -q "status 'incomplete'" "$dir/live_plot.log" || fail "plot.sh on a running run does not say so: $(cat "$dir/live_plot.log")"
grep -q "gnuplot said" "$dir/live_plot.log" && fail "gnuplot warnings on a running run: $(cat "$dir/live_plot.log")"

if ((failures > 0)); then echo "test_figure_layout: $failures failure(s)"; exit 1; fi
echo "test_figure_layout: passed (SI, nondimensional and Signorini figures: every text box inside the page, none overlapping, every panel labelled; Signorini contact shaded; .part drawn as far as it goes)"
exit 0
