#!/usr/bin/env bash
# A reduced stress table (tests/tools/stress.sh --quick, 12 short runs): extreme eps, varpi,
# tau0 = tau, dt, n_elements, g, initial velocity and rho around experiments 1 and 2. Every
# run must complete with finite values and no energy rise above 1e-12, or stop with exit 3,
# status 'failed: ...' and one message naming the step (the paper's iteration at eps = 1e-4).
#
#   bash tests/test_stress_quick.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 passed, 1 a run with verdict PROBLEM, 77 skipped (no program or no h5py).
set -u

prog=${1:-}
source_dir=${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
scratch=${3:-$(mktemp -d)}
if [[ -z "$prog" || ! -x "$prog" ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
if ! "$source_dir/scripts/lib/find_python.sh" > /dev/null; then
    echo "SKIP: no Python with h5py"
    exit 77
fi
bash "$source_dir/tests/tools/stress.sh" --quick --program "$prog" --scratch "$scratch" --output - 2>&1
status=$?
if [[ $status -ne 0 ]]; then
    echo "FAIL: tests/tools/stress.sh --quick: expected every verdict ok, got exit status $status (table above)"
    exit 1
fi
echo "test_stress_quick: every run ok"
