#!/usr/bin/env bash
# A bounded fuzz run of the namelist reader (tests/tools/fuzz.sh): 300 random mutations of the
# shipped inputs, each run by the real program with a 5 s limit. Every outcome must be
# exit 0 (valid), 2 (bad input, one message, no file) or 3 (numerically bad valid input);
# a crash, runtime error, hang or stray file fails the test, and the input is kept under
# <scratch>/findings/. The seed is fixed (FUZZ_SEED to change it) so a failure reproduces.
#
#   bash tests/test_fuzz.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 passed, 1 a finding, 77 skipped (no program).
set -u

prog=${1:-}
source_dir=${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
scratch=${3:-$(mktemp -d)}
if [[ -z "$prog" || ! -x "$prog" ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
rm -rf "$scratch/fuzz"
bash "$source_dir/tests/tools/fuzz.sh" --program "$prog" --count "${FUZZ_COUNT:-300}" --seed "${FUZZ_SEED:-20261123}" \
    --scratch "$scratch/fuzz" --quiet 2>&1
status=$?
if [[ $status -ne 0 ]]; then
    echo "FAIL: tests/tools/fuzz.sh found crashes, hangs or bad outcomes (above); inputs in $scratch/fuzz/findings/"
    exit 1
fi
echo "test_fuzz: no finding"
