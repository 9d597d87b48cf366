#!/usr/bin/env bash
# scripts/h5extract.py on any run file (issue 14, deliverable 4): the series, snapshot and
# matrix modes (columns and gnuplot's nonuniform matrix), checked against the file's values
# with h5py; --si on a run with &material; a complete run and the .h5.part of a stopped one
# alike; every usage error exits 2 with a message on stderr and nothing on stdout; run
# directly, it finds a Python with h5py itself or names the packages to install.
# Usage: bash test_h5extract.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"
x() { "$py" "$src/scripts/h5extract.py" "$@"; }

"$exe" "$src/input/exp1.nml" --set mesh.n_elements=20 --set time.t_end=0.05 --set output.snapshot_every=100 \
    --set output.prefix=run --set output.quiet=.true. || { echo "FAIL: the run failed"; exit 1; }

# series: all datasets, header naming columns and units, values as in the file
x series run.h5 > series.txt 2> series.err
check "series: exit 0" equals 0 "$?"
check "series: header line names every dataset with its units" equals \
    "# t [1] contact_stress [1] dt [1] energy [1] energy_chemical [1] energy_contact [1] energy_coupling [1] energy_heat_flux [1] energy_kinetic [1] energy_mass_flux [1] energy_strain [1] energy_thermal [1] iterations [1] n_elements [1] penetration [1] u_end [1]" "$(grep -v '^#  ' series.txt | sed -n 2p)"
check "series: the columns are the file's datasets" "$py" -c "
import h5py, numpy as np, sys
f = h5py.File('run.h5', 'r'); d = np.loadtxt('series.txt')
names = ['t', 'contact_stress', 'dt', 'energy'] + sorted(k for k in f['series'] if k.startswith('energy_')) + \
    ['iterations', 'n_elements', 'penetration', 'u_end']
sys.exit(0 if d.shape == (f['series/t'].size, 16) and all(np.array_equal(d[:, k], f['series/' + n][:]) for k, n in enumerate(names)) else 1)"
x series run.h5 --datasets t,u_end --every 100 > some.txt
check "series --datasets t,u_end --every 100: rows 0, 100, ..., last; two columns" "$py" -c "
import h5py, numpy as np, sys
f = h5py.File('run.h5', 'r'); d = np.loadtxt('some.txt'); n = f['series/t'].size
keep = np.unique(np.r_[np.arange(0, n, 100), n - 1])
sys.exit(0 if np.array_equal(d, np.column_stack([f['series/t'][:][keep], f['series/u_end'][:][keep]])) else 1)"

# snapshot: the nearest one, said on stderr and in the header
x snapshot run.h5 --time 0.012 --fields u,theta > snap.txt 2> snap.err
check "snapshot: exit 0" equals 0 "$?"
check "snapshot: stderr says which time was taken (t = 0.01)" grep -q "at t = 0.01[0-9]* \[1\] (nearest to the requested t = 0.012 \[1\])" snap.err
check "snapshot: x, u, theta of snapshot 1" "$py" -c "
import h5py, numpy as np, sys
f = h5py.File('run.h5', 'r'); d = np.loadtxt('snap.txt')
sys.exit(0 if np.array_equal(d, np.column_stack([f['mesh/x'][:], f['snapshots/u'][1], f['snapshots/theta'][1]])) else 1)"
x snapshot run.h5 --time 0 > snap0.txt 2> /dev/null
check "snapshot without --fields: x, every field and sigma (8 columns)" equals 8 "$(grep -v '^#' snap0.txt | head -n 1 | wc -w)"

# matrix: blocks 'x t value' separated by blank lines; nonuniform matrix
x matrix run.h5 --field theta > theta.dat
check "matrix (columns): exit 0" equals 0 "$?"
check "matrix (columns): one block of s+1 lines per snapshot, blank lines between" "$py" -c "
import h5py, numpy as np, sys
f = h5py.File('run.h5', 'r')
blocks = [b for b in open('theta.dat').read().split('\n\n')]
rows = [np.loadtxt(b.splitlines()) for b in blocks]
ok = len(rows) == f['snapshots/t'].size and all(
    np.array_equal(r, np.column_stack([f['mesh/x'][:], np.full(21, f['snapshots/t'][k]), f['snapshots/theta'][k]]))
    for k, r in enumerate(rows))
sys.exit(0 if ok else 1)"
x matrix run.h5 --field P --format nonuniform --t-max 0.02 > P.mat
check "matrix (nonuniform): first row N x..., then t and the values, t <= 0.02" "$py" -c "
import h5py, numpy as np, sys
f = h5py.File('run.h5', 'r'); m = np.loadtxt('P.mat'); ts = f['snapshots/t'][:]; k = ts <= 0.02
ok = m[0, 0] == 21 and np.array_equal(m[0, 1:], f['mesh/x'][:]) and np.array_equal(m[1:, 0], ts[k]) \
    and np.array_equal(m[1:, 1:], f['snapshots/P'][:][k])
sys.exit(0 if ok else 1)"
if command -v gnuplot > /dev/null; then
    gnuplot -e "set terminal dumb; splot 'theta.dat' using 1:2:3 with lines; splot 'P.mat' nonuniform matrix using 1:2:3 with lines" > /dev/null 2> gp.err
    check "gnuplot reads both forms (splot, the commands of docs/output.md)" test ! -s gp.err
fi

# --si with &material: si_factor times the value
sed -e 's/n_elements=500/n_elements=20/' -e 's/t_end=3.0/t_end=0.01/' -e "s|prefix='out/exp1'|prefix='mat' quiet=.true.|" \
    "$src/input/exp1.nml" > mat_nd.nml
"$py" "$src/tests/tools/si_input.py" mat_nd.nml ell=1.0 > mat.nml   # the same run in SI units
"$exe" mat.nml > /dev/null 2>&1
x series mat.h5 --datasets t,u_end --si > si.txt
check "series --si: units from si_units, values times si_factor" "$py" -c "
import h5py, numpy as np, sys
f = h5py.File('mat.h5', 'r'); d = np.loadtxt('si.txt'); a = f['series/u_end'].attrs
head = [l for l in open('si.txt') if l.startswith('# t [')][0]
ok = head.strip() == '# t [s] u_end [m]' and np.allclose(d[:, 1], a['si_factor'] * f['series/u_end'][:], rtol=1e-15, atol=0)
sys.exit(0 if ok else 1)"

# the .h5.part of a run stopped before its end (here: a full disk) works too
(ulimit -f 200; "$exe" "$src/input/exp1.nml" --set time.t_end=0.2 --set output.snapshot_every=10 \
    --set output.prefix=part --set output.quiet=.true. 2> /dev/null)
x series part.h5.part --datasets t > part.txt
check "series of an incomplete .h5.part: exit 0, its status in the header" grep -q "status: incomplete" part.txt

# usage errors: exit 2, a message on stderr, nothing on stdout
: > notrod.h5
"$py" -c "import h5py; h5py.File('foreign.h5', 'w')['a'] = [1.0]"
usage() {   # usage <description> <expected stderr text> <arguments ...>
    local what=$1 text=$2; shift 2
    x "$@" > usage.out 2> usage.err
    check "usage error, $what: exit 2" equals 2 "$?"
    check "usage error, $what: message on stderr ($(head -c 90 usage.err))" grep -q -- "$text" usage.err
    check "usage error, $what: nothing on stdout" test ! -s usage.out
}
usage "no arguments" "Text export" 
usage "unknown mode" "unknown mode 'bogus'" bogus run.h5
usage "missing file" "missing.h5: no such file" series missing.h5
usage "not an HDF5 file" "cannot open notrod.h5 as HDF5" series notrod.h5
usage "an HDF5 file not written by rodcontact" "foreign.h5 is not a rodcontact output file" snapshot foreign.h5 --time 0
usage "unknown field" "has no field bogus; it has: P, eta" matrix run.h5 --field bogus
usage "unknown field in --fields" "has no field(s) nope" snapshot run.h5 --time 0 --fields u,nope
usage "unknown series dataset" "has no series dataset(s) energyy" series run.h5 --datasets t,energyy
usage "time not a number" "got 'abc'; must be a number" snapshot run.h5 --time abc
usage "time not finite" "must be a finite number" snapshot run.h5 --time nan
usage "time after the last snapshot" "0 <= t <= 0.05" snapshot run.h5 --time 7
usage "time before the first snapshot" "got -1" snapshot run.h5 --time -1
usage "--t-max before the first snapshot" "--t-max: got -1" matrix run.h5 --field u --t-max -1
usage "missing --time" "required: --time" snapshot run.h5
usage "bad --format" "invalid choice" matrix run.h5 --field u --format grid
usage "--every 0" "--every: got 0" series run.h5 --every 0
usage "--si without &material" "only runs with &material" series run.h5 --si
usage "figures with a file as OUT_DIR" "is not a directory" figures run.h5 data

# run directly: executable (git mode 100755 when in a git checkout), and with a python3 first
# on PATH that cannot import h5py (here: Debian's own without its site packages, -S), it runs
# itself again with the Python of find_python.sh; with none, it names the packages, exit 1
for tool in h5extract.py h5layout.py; do   # the two Python tools of the index
    check "$tool is executable" test -x "$src/scripts/$tool"
    if git -C "$src" rev-parse --git-dir > /dev/null 2>&1; then
        check "$tool has git mode 100755" equals 100755 \
            "$(git -C "$src" ls-files -s scripts/$tool | cut -d' ' -f1)"
    fi
done
check "h5layout.py run directly lists the file" grep -q '^attr status = ' <("$src/scripts/h5layout.py" run.h5)
mkdir -p nopy
printf '#!/bin/sh\nexec %s -S "$@"\n' "$py" > nopy/python3
chmod +x nopy/python3
check "the stand-in python3 cannot import h5py" bash -c '! PATH=nopy:$PATH python3 -c "import h5py" 2> /dev/null'
PATH=$PWD/nopy:$PATH "$src/scripts/h5extract.py" series run.h5 --datasets t,energy > direct.txt 2> direct.err
check "run directly with a python3 without h5py: exit 0, the same output as with find_python's" \
    bash -c "[[ -s direct.txt ]] && cmp -s direct.txt <('$py' '$src/scripts/h5extract.py' series run.h5 --datasets t,energy)"
PATH=$PWD/nopy:$PATH RODCONTACT_PYTHON_RETRIED=1 "$src/scripts/h5extract.py" series run.h5 > /dev/null 2> nopy.err
check "no Python with h5py at all: exit 1" equals 1 "$?"
check "no Python with h5py at all: names the Debian packages, no traceback" \
    bash -c "grep -q 'install the Debian packages python3-h5py and python3-numpy' nopy.err && ! grep -q Traceback nopy.err"

echo "test_h5extract: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
