#!/usr/bin/env bash
# Make sure the Debian packages rodcontact needs are installed, then configure and
# build it. Called by scripts/run.sh and scripts/test.sh; safe to call directly, from
# any directory, as often as you like: when everything is present and up to date it
# prints nothing.
#
#   scripts/setup.sh                    # Release build in <repo>/build
#   BUILD_TYPE=Debug BUILD_DIR=build-debug scripts/setup.sh
#   scripts/setup.sh --build-only       # no package step: configure and build with the
#                                       # libraries that are there (no root needed; clusters)
#
# Packages: only the missing ones are installed (apt-get install --no-upgrade: installed
# packages are not upgraded; apt upgrades a dependency only when a new package requires it),
# with root or sudo. Without either, when the build's own packages (BUILD_PACKAGES) are there,
# it says which tool packages are missing (plots, tests) and builds anyway.
#
# Environment: BUILD_TYPE (default Release), BUILD_DIR (default build; relative paths
# are taken from the repository root), JOBS (parallel build jobs, default 2), WERROR
# (ON: compiler warnings on the project's sources are errors, as scripts/test.sh builds;
# OFF: not; unset: as the build directory was configured, OFF for a new one, so that
# scripts/run.sh after scripts/test.sh reuses its build instead of rebuilding everything).
# Exit status: 0 ready; 1 missing packages that could not be installed, or the
# configure/build failed.

set -euo pipefail

# graphviz: draws docs/uses.svg, the use graph of docs/architecture.md (tests/test_docs.sh).
# parallel: GNU parallel, which runs the points of scripts/scan.sh (with moreutils installed
# too, Debian moves moreutils' own 'parallel' aside to parallel.moreutils). The test-only
# Slurm packages (slurm-wlm, munge) are installed by tests/test_slurm.sh itself.
BUILD_PACKAGES=(gfortran cmake make liblapack-dev libblas-dev libhdf5-dev)
REQUIRED_PACKAGES=(gfortran cmake make liblapack-dev libblas-dev libhdf5-dev
                   gnuplot-nox fonts-dejavu-core python3-h5py python3-numpy python3-scipy python3-matplotlib
                   python3-xarray python3-h5netcdf netcdf-bin
                   valgrind parallel graphviz)

# poppler-utils: pdftotext, with which tests/test_plot.sh reads the title of a figure and
# tests/test_figure_layout.sh the text boxes of every figure (tests/tools/figure_layout.py)
REQUIRED_PACKAGES+=(poppler-utils)
# python3-yaml: tests/test_version.sh reads CITATION.cff
REQUIRED_PACKAGES+=(python3-yaml)

build_only=0
case "${1:-}" in
    --build-only) build_only=1 ;;
    "") ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup: unknown option '$1' (--build-only, --help)" >&2; exit 2 ;;
esac

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

build_type="${BUILD_TYPE:-Release}"
werror="${WERROR:-}"
build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
jobs="${JOBS:-2}"

say() { echo "setup: $*" >&2; }

# --- 1. Debian packages --------------------------------------------------------------
missing=()
if ((build_only)); then
    :   # the libraries are wherever the system (or 'module load') put them: CMake finds them
elif command -v dpkg-query >/dev/null 2>&1; then
    for pkg in "${REQUIRED_PACKAGES[@]}"; do
        status="$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)"
        if [[ "$status" != "install ok installed" ]]; then
            missing+=("$pkg")
        fi
    done
else
    say "dpkg-query not found (not Debian/Ubuntu?): not checking packages."
    say "rodcontact needs: a Fortran compiler, CMake >= 3.20, make, LAPACK/BLAS, HDF5 with Fortran bindings."
fi

if ((${#missing[@]} > 0)); then
    install_cmd="apt-get install -y --no-upgrade ${missing[*]}"
    say "missing Debian packages: ${missing[*]}"
    sudo_cmd=()
    if [[ "$(id -u)" -ne 0 ]]; then
        if command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
            sudo_cmd=(sudo)
        else
            missing_build=()
            for pkg in "${missing[@]}"; do
                [[ " ${BUILD_PACKAGES[*]} " == *" $pkg "* ]] && missing_build+=("$pkg")
            done
            say "not root and no sudo: cannot install them. As root: apt-get update && $install_cmd"
            if ((${#missing_build[@]} > 0)); then
                say "the build needs ${missing_build[*]}: install them (or 'module load' the compiler,"
                say "CMake, HDF5 and LAPACK and run scripts/setup.sh --build-only; README 'Building')"
                exit 1
            fi
            say "building without them (they are for plots, scans and tests)"
            missing=()
        fi
    fi
fi
if ((${#missing[@]} > 0)); then
    say "installing${sudo_cmd[*]:+ with sudo}: apt-get update && $install_cmd"
    if ! { "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q &&
           "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-upgrade "${missing[@]}"; }; then
        say "package installation failed. Install them yourself, as root:"
        echo "    apt-get update && $install_cmd" >&2
        exit 1
    fi
    say "packages installed."
fi

# --- 2. configure ----------------------------------------------------------------------
# Configure when there is no complete configuration yet (none, or an earlier one that
# failed), when it was made for another build type, or when packages were just installed.
cache="$build_dir/CMakeCache.txt"
cached_type="" cached_werror=""
if [[ -f "$cache" ]]; then
    cached_type="$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$cache")"
    cached_werror="$(sed -n 's/^RODCONTACT_WERROR:[A-Z]*=//p' "$cache")"
fi
[[ -n $werror ]] || werror="${cached_werror:-OFF}"
if [[ ! -f "$cache" || "$cached_type" != "$build_type" || "$cached_werror" != "$werror" || ${#missing[@]} -gt 0 ||
      ( ! -f "$build_dir/Makefile" && ! -f "$build_dir/build.ninja" ) ]]; then
    say "configuring $build_type build in $build_dir/"
    mkdir -p "$build_dir"
    log="$build_dir/setup-configure.log"
    if ! cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" -DRODCONTACT_WERROR="$werror" >"$log" 2>&1; then
        cat "$log" >&2
        say "configure failed (log: $log)"
        exit 1
    fi
fi

# --- 3. build --------------------------------------------------------------------------
# The build log is kept out of sight unless something was rebuilt or it failed.
log="$build_dir/setup-build.log"
if ! cmake --build "$build_dir" -j "$jobs" >"$log" 2>&1; then
    cat "$log" >&2
    say "build failed (log: $log)"
    exit 1
fi
if grep -q -E 'Building|Linking' "$log"; then
    say "built $build_type in $build_dir/"
fi
if grep -q -i -E '(^|[^a-z])warning:' "$log"; then
    say "the build printed warnings: see $log"
fi
