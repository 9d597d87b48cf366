#!/usr/bin/env bash
# Every claim of Section 7 of the paper holds on the full runs: scripts/paper/claims.sh runs every
# input/exp*.nml (paper's h and dt, the inputs' final times) and exp1_long (experiment 1 up to
# t = 60) with the rodcontact under test into the scratch directory (without the accuracy study
# of other resolutions: --no-accuracy), and must exit 0. Runs
# that are up to date in the scratch directory (newer than the binary) are reused.
# Takes about 35 s (the long run is about 20 s of it).
#
#   bash tests/test_claims_full.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 every claim holds, 1 a claim does not hold or the pipeline failed,
# 77 skipped (no Python with h5py).
set -u

prog=${1:-}
src=${2:-}
scratch=${3:-}
if [[ -z "$prog" || ! -x "$prog" || -z "$src" || -z "$scratch" ]]; then
    echo "usage: bash test_claims_full.sh <rodcontact> <source dir> <scratch dir>"
    exit 1
fi
if ! "$src/scripts/lib/find_python.sh" >/dev/null 2>&1; then
    echo "SKIP: no Python that can import h5py and numpy (Debian: python3-h5py)"
    exit 77
fi

mkdir -p "$scratch/out"
doc="$scratch/reproduction.md"
"$src/scripts/paper/claims.sh" --no-accuracy --exe "$prog" --out "$scratch/out" --doc "$doc" --figdir "$src/figures"
status=$?
if ((status != 0)); then
    echo "FAIL: scripts/paper/claims.sh exited with status $status (1: a claim does not hold; see the lines above"
    echo "      and the table in $doc)"
    exit 1
fi
echo "test_claims_full: every claim of Section 7 holds ($doc)"
exit 0
