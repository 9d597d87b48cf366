#!/usr/bin/env bash
# Each term of the discrete energy E^n (/series/energy_<part>) against an independent computation
# from the snapshot fields (tests/tools/energy_parts.py: the exact P1 integrals of the
# paper's energy terms with the file's coefficients, and the stored E^n = the sum of its
# parts). The sum alone is checked elsewhere (test_energy_law, test_energy_monitor); a factor
# wrong in one part that keeps the sum would pass there and fails here: checked with
# energy_m's PART_THERMAL at c/6 instead of c/12 (thermal off by a factor 2, and E^n no
# longer the sum) and with its E_lin's coupling term d instead of 2 d (the mutant
# energy_cross_term: the parts right, E^n not their sum).
# Two runs of experiment 1 (50 elements, t = 0.5, penalty contact): as given, and with rho = 1,
# q0 and eta0 nonzero and g = 0.01 so that every part, the kinetic and the contact one
# included, is well above round-off at some snapshot (the tool fails if one never is).
# Usage: bash test_energy_parts.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
. "$src/tests/lib/checks.sh"
cd "$scratch" && rm -rf ./* || exit 1

common=(--set mesh.n_elements=50 --set time.t_end=0.5 --set output.quiet=.true.)
"$exe" "${common[@]}" --set output.prefix="'given'" <"$src/input/exp1.nml" \
    || { echo "FAIL: exp1 run"; exit 1; }
"$exe" "${common[@]}" --set output.prefix="'every_part'" --set model.rho=1 --set initial.q0_poly=0,1,-1 \
    --set initial.eta0_poly=0,1,-1 --set contact.g=0.01 <"$src/input/exp1.nml" \
    || { echo "FAIL: exp1 run with every part nonzero"; exit 1; }

check "each energy part equals its computation from the snapshot fields, E^n their sum" \
    "$py" "$src/tests/tools/energy_parts.py" given.h5 every_part.h5

echo "$n_checks checks, $n_failed failed"
((n_failed == 0))
