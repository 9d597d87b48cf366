#!/usr/bin/env bash
# scripts/plot.sh draws any run file: a short complete run (every style, PNG and PDF), a
# failed run (status 'failed: ...', exit 3 of rodcontact), a file with the optional
# /snapshots/sigma and /series/energy_<part> datasets (added to a copy here, as a later
# rodcontact will write them: sigma must be drawn by default, the parts read); and it must
# refuse, with exit 2 and a message, an HDF5 file that is not a rodcontact output, a file
# that is not HDF5, an unknown style and an absent field. From another working directory on
# relative paths it writes only beside the run (or in --out), names are drawn literally, and
# a run with &material is drawn in SI units (otherwise the labels say nondimensional).
#
#   bash tests/test_plot.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 passed, 1 failed, 77 skipped (no gnuplot with cairo terminals or no h5py).
set -u
prog=${1:-} src=${2:-} scratch=${3:-}
if [[ -z "$prog" || ! -x "$prog" || -z "$src" || -z "$scratch" ]]; then
    echo "usage: bash test_plot.sh <rodcontact> <source dir> <scratch dir>"; exit 1
fi
command -v gnuplot >/dev/null 2>&1 || { echo "SKIP: gnuplot not found"; exit 77; }
for term in pngcairo pdfcairo; do
    gnuplot -e "set terminal $term" </dev/null >/dev/null 2>&1 || { echo "SKIP: no $term terminal"; exit 77; }
done
py=$("$src/scripts/lib/find_python.sh" 2>/dev/null) || { echo "SKIP: no Python with h5py"; exit 77; }
dir="$scratch/plot"
rm -rf "$dir"; mkdir -p "$dir"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
is_png() { [[ -s "$1" && "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]]; }
is_pdf() { [[ -s "$1" && "$(head -c 5 "$1")" == "%PDF-" ]]; }

# 1. a short complete run (experiment 2, coarse) in every style
"$py" "$src/scripts/lib/nml_copy.py" "$src/input/exp2.nml" "$dir/run.nml" "output.prefix='$dir/run'" \
    output.quiet=.true. mesh.n_elements=50 time.dt=1e-3 time.t_end=0.1 output.snapshot_every=5
"$prog" "$dir/run.nml" >/dev/null 2>&1 || fail "the short run failed"
if ! "$src/scripts/plot.sh" "$dir/run.h5" --style all --out "$dir/figs" >"$dir/plot.log" 2>&1; then
    fail "plot.sh --style all on a complete run: $(cat "$dir/plot.log")"
fi
grep -q 'gnuplot said' "$dir/plot.log" && fail "gnuplot warnings: $(cat "$dir/plot.log")"
for st in surface profiles series; do
    is_png "$dir/figs/run_$st.png" || fail "run_$st.png missing or not a PNG"
    is_pdf "$dir/figs/run_$st.pdf" || fail "run_$st.pdf missing or not a PDF"
done
"$src/scripts/plot.sh" "$dir/run.h5" --style profiles --fields u,v --out "$dir/figs2" >"$dir/p2.log" 2>&1 &&
    is_png "$dir/figs2/run_profiles.png" || fail "plot.sh --fields u,v: $(cat "$dir/p2.log")"

# 2. a failed run: the paper iteration stopped after 3 iterations at the first contact
"$py" "$src/scripts/lib/nml_copy.py" "$src/input/exp1.nml" "$dir/failed.nml" "output.prefix='$dir/failed'" \
    output.quiet=.true. mesh.n_elements=50 time.dt=1e-3 time.t_end=0.3 "solver.method='paper'" \
    solver.max_iter=3 output.snapshot_every=7
"$prog" "$dir/failed.nml" >/dev/null 2>&1
[[ $? -eq 3 ]] || fail "the run meant to fail did not exit 3"
[[ "$("$py" "$src/scripts/lib/rodrun.py" attr "$dir/failed.h5" status)" == failed* ]] ||
    fail "failed.h5 has no status 'failed: ...'"
if ! "$src/scripts/plot.sh" "$dir/failed.h5" --style all --out "$dir/figs" >"$dir/failed.log" 2>&1; then
    fail "plot.sh on a failed run: $(cat "$dir/failed.log")"
fi
for st in surface profiles series; do is_png "$dir/figs/failed_$st.png" || fail "failed_$st.png missing"; done

# 3. optional datasets: sigma and energy parts are drawn when present
cp "$dir/run.h5" "$dir/extra.h5"
"$py" - "$dir/extra.h5" <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r+") as f:
    # rodcontact writes sigma and eight energy parts: replaced by known ones here
    for name in ["snapshots/sigma"] + ["series/" + k for k in f["series"] if k.startswith("energy_")]:
        if name in f:
            del f[name]
    f["snapshots/sigma"] = 0.5 * f["snapshots/theta"][:] - 1.0
    e = f["series/energy"][:]
    f["series/energy_kinetic"] = 0.1 * e
    f["series/energy_thermal"] = 0.6 * e
PY
data="$dir/extra-data"
"$py" "$src/scripts/lib/plotdata.py" "$dir/extra.h5" "$data" >"$dir/extra.log" 2>&1 || fail "plotdata.py on extra.h5: $(cat "$dir/extra.log")"
grep -q '^fields = ".*sigma' "$data/params.gp" || fail "sigma not among the default fields: $(grep '^fields' "$data/params.gp")"
grep -q '^n_parts = 2$' "$data/params.gp" || fail "energy parts not found: $(grep '^n_parts' "$data/params.gp")"
"$src/scripts/plot.sh" "$dir/extra.h5" --style all --out "$dir/figs" >"$dir/extra2.log" 2>&1 ||
    fail "plot.sh on a file with sigma and energy parts: $(cat "$dir/extra2.log")"
grep -q 'gnuplot said' "$dir/extra2.log" && fail "gnuplot warnings: $(cat "$dir/extra2.log")"

# 4. refusals: exit 2 with a message
"$py" -c 'import sys, h5py; f = h5py.File(sys.argv[1], "w"); f["x"] = [1.0, 2.0]' "$dir/other.h5"
printf 'not an hdf5 file\n' >"$dir/text.h5"
check2() {   # check2 <what> <expected message pattern> <plot.sh args...>
    local what=$1 pat=$2; shift 2
    "$src/scripts/plot.sh" "$@" >"$dir/r.log" 2>&1
    local st=$?
    [[ $st -eq 2 ]] || fail "$what: expected exit 2, got $st ($(cat "$dir/r.log"))"
    grep -Eq -- "$pat" "$dir/r.log" || fail "$what: message does not match '$pat': $(cat "$dir/r.log")"
}
check2 "an HDF5 file that is not rodcontact's" "not a rodcontact output file" "$dir/other.h5" --out "$dir/figs"
check2 "a text file" "cannot open .* as HDF5" "$dir/text.h5" --out "$dir/figs"
check2 "an unknown style" "--style must be" "$dir/run.h5" --style heatmap
cp "$dir/run.h5" "$dir/nosigma.h5"   # a file of an older rodcontact, without sigma
"$py" -c 'import sys, h5py; del h5py.File(sys.argv[1], "r+")["snapshots/sigma"]' "$dir/nosigma.h5"
check2 "an absent field" "has no /snapshots/sigma" "$dir/nosigma.h5" --fields u,sigma --out "$dir/figs"
check2 "a missing file" "no such file" "$dir/nothing.h5"
ls "$dir/figs"/other_* >/dev/null 2>&1 && fail "figures written for a non-rodcontact file"

# 5. from another working directory, on relative paths: the figures beside the run file (or
#    in --out, relative to the current directory), nothing written in the source tree; a run
#    named point_0001 keeps its underscore (no gnuplot markup: the PDF's text says so)
src_state() { (cd "$src" && find . -path ./build -prune -o -path './build-*' -prune -o -path ./.git -prune -o -newer "$dir/stamp" -print); }
touch "$dir/stamp"; sleep 1
mkdir -p "$dir/cwd/runs"
cp "$dir/run.h5" "$dir/cwd/runs/point_0001.h5"
(cd "$dir/cwd" && "$src/scripts/plot.sh" runs/point_0001.h5 >"$dir/rel.log" 2>&1) ||
    fail "plot.sh on a relative path from another directory: $(cat "$dir/rel.log")"
is_png "$dir/cwd/runs/point_0001_surface.png" || fail "runs/point_0001_surface.png not written beside the run"
(cd "$dir/cwd" && "$src/scripts/plot.sh" runs/point_0001.h5 --style series --out figs/rel >"$dir/rel2.log" 2>&1) ||
    fail "plot.sh --out relative: $(cat "$dir/rel2.log")"
is_pdf "$dir/cwd/figs/rel/point_0001_series.pdf" || fail "--out figs/rel: point_0001_series.pdf not in figs/rel"
[[ -z $(src_state) ]] || fail "plot.sh wrote into the source tree: $(src_state)"
ls "$src"/scripts/gnuplot/*.tmp >/dev/null 2>&1 && fail "temporary files left in scripts/gnuplot"
[[ $(ls "$dir/cwd" | tr '\n' ' ') == "figs runs " ]] || fail "plot.sh wrote into the working directory: $(ls "$dir/cwd")"
if command -v pdftotext >/dev/null 2>&1; then
    pdftotext "$dir/cwd/figs/rel/point_0001_series.pdf" - | grep -q 'point_0001' ||
        fail "the title does not read point_0001: $(pdftotext "$dir/cwd/figs/rel/point_0001_series.pdf" - | head -n 3)"
fi

# 6. units: a run with &material is drawn in SI units by default (values times si_factor,
#    units in the labels); --nondimensional and a run without &material say 'nondimensional'
sed -e 's/n_elements=500/n_elements=20/' -e 's/t_end=3.0/t_end=0.05/' -e 's/snapshot_every=100/snapshot_every=10/' \
    -e "s|prefix='out/exp1'|prefix='$dir/alu' quiet=.true.|" "$src/input/exp1.nml" > "$dir/alu_nd.nml"
"$py" "$src/tests/tools/si_input.py" "$dir/alu_nd.nml" ell=1.0 > "$dir/alu.nml"   # the same run in SI units
"$prog" "$dir/alu.nml" >/dev/null 2>&1 || fail "the &material run failed"
"$py" "$src/scripts/lib/plotdata.py" "$dir/alu.h5" "$dir/si-data" >"$dir/si.log" 2>&1 || fail "plotdata.py on alu.h5: $(cat "$dir/si.log")"
grep -q '^x_unit = " \[m\]"$' "$dir/si-data/params.gp" && grep -Eq '^t_unit = " \[[mµ]?s\]"$' "$dir/si-data/params.gp" &&
    grep -Eq '^unit_theta = " \[(10\^\{[0-9]+\} )?K\]"$' "$dir/si-data/params.gp" || fail "SI units missing in params.gp: $(grep unit "$dir/si-data/params.gp")"
"$py" - "$dir/alu.h5" "$dir/si-data" <<'PY' || fail "the SI profiles are not si_factor times the file's values (in the power of ten of their label)"
import re, sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
p = np.loadtxt(sys.argv[2] + "/prof.theta.dat", skiprows=1)
label = re.search(r'^unit_theta = "(.*)"$', open(sys.argv[2] + "/params.gp").read(), re.M).group(1)
power = 10.0 ** int(re.search(r"10\^\{(-?[0-9]+)\}", label).group(1)) if "10^" in label else 1.0
th, x = f["snapshots/theta"], f["mesh/x"]
ok = np.allclose(p[:, 0], x.attrs["si_factor"] * x[:], rtol=1e-6) and \
     np.allclose(power * p[:, -1], th.attrs["si_factor"] * th[-1, :], rtol=1e-6, atol=1e-6 * abs(th.attrs["si_factor"] * th[-1, :]).max())
sys.exit(0 if ok else 1)
PY
"$src/scripts/plot.sh" "$dir/alu.h5" --style all --out "$dir/si-figs" >"$dir/si2.log" 2>&1 || fail "plot.sh on a &material run: $(cat "$dir/si2.log")"
"$py" "$src/scripts/lib/plotdata.py" "$dir/alu.h5" "$dir/nd-data" --units nondimensional >/dev/null 2>&1
grep -q '^x_unit = " (nondimensional)"$' "$dir/nd-data/params.gp" || fail "--units nondimensional: x not labelled nondimensional"
grep -q '^x_unit = " (nondimensional)"$' "$data/params.gp" || fail "a run without &material: x not labelled nondimensional"
check2 "--si on a run without &material" "has no SI scales" "$dir/run.h5" --si --out "$dir/figs"

if ((failures > 0)); then echo "test_plot: $failures failure(s)"; exit 1; fi
echo "test_plot: passed (complete, failed and extended run files drawn; relative paths from another directory, nothing in the source tree, literal names; SI and nondimensional units; bad files refused with exit 2)"
exit 0
