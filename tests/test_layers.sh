#!/usr/bin/env bash
# The layers of src/ (src/LAYERS, lowest first): no module uses one of a later layer.
# tests/tools/layers.py reads every `use` statement of src/. The test also proves the check
# can fail: in a scratch copy of src/, base/kinds_m gains `use run_m` (the driver), and the
# check must exit 1 and name that use.
# Usage: bash test_layers.sh <rodcontact> <source dir> <scratch dir>
set -u
src=$2; scratch=$3
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"
layers() { python3 "$src/tests/tools/layers.py" check "$@"; }

layers "$src/src" > real.out 2> real.err
status=$?  # taken at once: the $(...) in the message below would reset $?
check "src/ keeps the layer order (stderr: $(cat real.err))" equals 0 "$status"

cp -r "$src/src" copy
sed -i 's/^\(\s*module kinds_m\s*\)$/\1\n  use run_m, only: run_simulation/' copy/base/kinds_m.f90
check "the scratch copy has the injected use" grep -q 'use run_m' copy/base/kinds_m.f90
layers copy > broken.out 2> broken.err
check "a low layer that uses the driver fails the check" equals 1 "$?"
check "the message names the module, the used module and both layers" \
    grep -q 'kinds_m (base) uses run_m (driver)' broken.err

mkdir copy/attic && cp copy/base/errors_m.f90 copy/attic/
layers copy > stray.out 2> stray.err
check "a source folder not in LAYERS is refused" equals 1 "$?"
check "the message names the stray file" grep -q "attic/errors_m.f90 is in no layer" stray.err

echo "test_layers: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
