#!/usr/bin/env bash
# Build rodcontact (scripts/setup.sh) and run the test suite with CTest.
#
#   scripts/test.sh                     # every test
#   scripts/test.sh -L fast             # extra arguments go to ctest
#   scripts/test.sh -R test_progress_m
#   scripts/test.sh --debug             # then again in a Debug build (see below)
#
# With --debug, or when the environment variable CI is set (continuous integration, .ci/run),
# the suite runs a second time in a Debug build (build-debug/, or DEBUG_BUILD_DIR):
# -fcheck=all (bounds, allocation, pointer checks) and -ffpe-trap=invalid,zero,overflow, so
# that an out-of-bounds access or a NaN/Inf produced anywhere stops the test that caused
# it. The Release run comes first; both always run. The Debug run leaves out the tests
# labelled slurm (tests/test_slurm.sh: a Slurm cluster running scan scripts, nothing that
# the Debug build checks) and extension (tests/test_new_contact_law.sh: builds a Release
# copy of its own) when it is given no ctest arguments.
#
# Both builds treat compiler warnings on the project's sources as errors (WERROR=ON for
# scripts/setup.sh): the code compiles warning-free with -Wall -Wextra, and stays so.
#
# Exit status: 0 when every test passed in every build; otherwise that of the failing ctest
# (the Release one if both failed), or 1 when a setup fails.
# Environment: BUILD_TYPE, BUILD_DIR as for scripts/setup.sh (the first run); DEBUG_BUILD_DIR
# (default build-debug) for the Debug run; CI.

set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

debug=no
[[ -n "${CI:-}" ]] && debug=yes
ctest_args=()
for arg in "$@"; do
    if [[ "$arg" == --debug ]]; then
        debug=yes
    else
        ctest_args+=("$arg")
    fi
done

build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"

export WERROR=ON   # a compiler warning on the project's sources fails the build (and the suite)
"$repo_root/scripts/setup.sh" || exit 1
ctest --test-dir "$build_dir" --output-on-failure -j 2 "${ctest_args[@]}"
status=$?

if [[ $debug == yes ]]; then
    debug_dir="${DEBUG_BUILD_DIR:-build-debug}"
    [[ "$debug_dir" = /* ]] || debug_dir="$repo_root/$debug_dir"
    echo "test.sh: running the suite again in a Debug build (-fcheck=all, floating-point traps) in $debug_dir/" >&2
    BUILD_TYPE=Debug BUILD_DIR="$debug_dir" "$repo_root/scripts/setup.sh" || exit 1
    debug_args=("${ctest_args[@]}")
    ((${#ctest_args[@]} == 0)) && debug_args=(-LE '^(slurm|extension)$')
    ctest --test-dir "$debug_dir" --output-on-failure -j 2 "${debug_args[@]}"
    debug_status=$?
    if [[ $status -eq 0 && $debug_status -ne 0 ]]; then
        echo "test.sh: the Release suite passed, the Debug suite failed" >&2
        status=$debug_status
    fi
fi
exit $status
