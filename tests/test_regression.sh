#!/usr/bin/env bash
# Regression references: every case of tests/regression_cases.txt (the shipped inputs, BDF2,
# Signorini, the paper's iteration, a thermoelastic scene with fields left out, a checkpoint
# and its restart) is run shortened and its /series, /snapshots and /events compared with the stored
# reference tests/reference/<case>.h5 within tests/tools/regression.py's tolerance (1e-8 of each
# dataset's largest value). A change that is not meant to change results keeps this green.
#
#   bash test_regression.sh <rodcontact> <source dir> <scratch dir> [--update]
# --update rewrites the references from this build (say why in the commit).
set -u
exe=$1; src=$2; scratch=$3; update=${4:-}
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py to compare the files"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
failures=0
while read -r name input rest; do
    [[ -z "$name" || "$name" == \#* ]] && continue
    eval "overrides=($rest)"
    if ! "$exe" "$src/input/$input" --set mesh.n_elements=100 --set time.t_end=0.3 \
         --set output.snapshot_every=500 --set output.prefix="$name" --set output.quiet=.true. \
         "${overrides[@]}" > "$name.log" 2>&1; then
        echo "FAIL: case $name: rodcontact exited non-zero"; cat "$name.log"; failures=$((failures + 1)); continue
    fi
    if [[ "$update" == --update ]]; then
        "$py" "$src/tests/tools/regression.py" store "$name.h5" "$src/tests/reference/$name.h5" || exit 1
        echo "stored tests/reference/$name.h5"
    elif ! "$py" "$src/tests/tools/regression.py" compare "$name.h5" "$src/tests/reference/$name.h5"; then
        echo "FAIL: case $name differs from tests/reference/$name.h5"; failures=$((failures + 1))
    else
        echo "ok: $name"
    fi
done < "$src/tests/regression_cases.txt"
echo "$failures case(s) failed"
[[ $failures -eq 0 ]]
