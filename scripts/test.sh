#!/usr/bin/env bash
# Build rodcontact (scripts/setup.sh) and run the test suite with CTest.
#
#   scripts/test.sh                     # every test
#   scripts/test.sh -L fast             # extra arguments go to ctest
#   scripts/test.sh -R test_progress_m
#
# Exit status: that of ctest (0 when every test passed), or 1 when setup fails.
# Environment: BUILD_TYPE, BUILD_DIR as for scripts/setup.sh.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$repo_root/scripts/setup.sh"
cd "$repo_root"

build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"

exec ctest --test-dir "$build_dir" --output-on-failure -j 2 "$@"
