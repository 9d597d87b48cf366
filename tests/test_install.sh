#!/usr/bin/env bash
# cmake --install (issue 37). A scratch build directory is configured from the source tree (a
# clean configure, with the install rules); the build is installed into a temporary prefix P;
# from an unrelated temporary directory P/bin/rodcontact runs P/share/rodcontact/input/exp1.nml
# (short), then the installed plot.sh and h5extract.py work on its output and the installed
# scan.sh runs a point with P/bin/rodcontact, found by itself ($RODCONTACT unset): each exits 0
# and writes its files there; nothing is written into the source tree (`git status
# --porcelain` before and after).
# The build installed is the one of <rodcontact> (a fresh one takes minutes on a loaded
# machine); with RODCONTACT_INSTALL_FRESH=1 the scratch directory is built and installed.
# Usage: bash test_install.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"
# ran STATUS LOG: the command succeeded, else the end of its log
ran() { [[ $1 == 0 ]] && return 0; echo "  exit $1:"; tail -n 5 "$2" | sed 's/^/  /'; return 1; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rodcontact_install.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix share=$tmp/prefix/share/rodcontact
in_git=0
git -C "$src" rev-parse --git-dir > /dev/null 2>&1 && in_git=1
((in_git)) && status_before=$(git -C "$src" status --porcelain)

build=$(cd "$(dirname "$exe")" && pwd)
cmake -S "$src" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release > configure.log 2>&1
check "a clean configure of the source tree in a scratch directory" ran $? configure.log
check "its install rules put the program in bin and the tools in share/rodcontact" \
    grep -q 'share/rodcontact/scripts' "$scratch/build/cmake_install.cmake"
if [[ ${RODCONTACT_INSTALL_FRESH:-0} == 1 ]]; then
    cmake --build "$scratch/build" -j 2 --target rodcontact > build.log 2>&1
    check "the scratch build" ran $? build.log
    build=$scratch/build
fi
cmake --install "$build" --prefix "$prefix" > install.log 2>&1
check "cmake --install $build --prefix P" ran $? install.log
for f in bin/rodcontact share/rodcontact/scripts/plot.sh share/rodcontact/scripts/h5extract.py \
         share/rodcontact/scripts/h5layout.py share/rodcontact/scripts/scan.sh share/rodcontact/scripts/converge.sh \
         share/rodcontact/scripts/lib/find_rodcontact.sh share/rodcontact/scripts/lib/find_python.sh; do
    check "P/$f is installed, executable" test -x "$prefix/$f"
done
for f in scripts/lib/rodrun.py scripts/lib/plotdata.py scripts/lib/converge.py \
         scripts/gnuplot/run_surface.gp scripts/slurm/scan_array.sbatch input/exp1.nml input/impact.nml \
         docs/output.md README.md CHANGELOG.md LICENSE CITATION.cff; do
    check "P/share/rodcontact/$f is installed" test -s "$share/$f"
done
check "the installed program is the build's" equals "$("$build/rodcontact" --version)" "$("$prefix/bin/rodcontact" --version)"

# From an unrelated directory, with nothing of the source tree on the way
mkdir -p "$tmp/work" && cd "$tmp/work" || exit 1
unset RODCONTACT RODCONTACT_ROOT
"$prefix/bin/rodcontact" "$share/input/exp1.nml" --set time.t_end=0.05 --set mesh.n_elements=20 \
    --set output.snapshot_every=100 --set output.quiet=.true. > run.log 2>&1
check "P/bin/rodcontact on P/share/rodcontact/input/exp1.nml exits 0" ran $? run.log
check "it writes out/exp1.h5 in the working directory" test -s out/exp1.h5

"$share/scripts/h5extract.py" series out/exp1.h5 --datasets t,u_end > u_end.txt 2> extract.err
check "the installed h5extract.py exits 0" ran $? extract.err
check "and writes t, u_end: 501 rows of 2 columns" equals "501 2" \
    "$(grep -v '^#' u_end.txt | awk 'END { print NR, NF }')"

if command -v gnuplot > /dev/null && gnuplot -e 'set terminal pngcairo; set terminal pdfcairo' < /dev/null > /dev/null 2>&1; then
    "$share/scripts/plot.sh" out/exp1.h5 > plot.log 2>&1
    check "the installed plot.sh exits 0" ran $? plot.log
    check "and writes out/exp1_surface.png and .pdf" test -s out/exp1_surface.png -a -s out/exp1_surface.pdf
else
    echo "SKIP plot.sh: no gnuplot with pngcairo and pdfcairo"
fi

if parallel --version 2> /dev/null | grep -q '^GNU parallel'; then
    "$share/scripts/scan.sh" "$share/input/exp1.nml" --set time.t_end=0.01 --set mesh.n_elements=10 \
        --out scan -j 1 > scan.log 2>&1
    check "the installed scan.sh exits 0" ran $? scan.log
    check "its point is complete in scan/summary.csv" grep -q ',complete,' scan/summary.csv
    py=$("$share/scripts/lib/find_python.sh") &&
        check "and was run by P/bin/rodcontact" equals "$prefix/bin/rodcontact" \
            "$("$py" "$share/scripts/lib/rodrun.py" attr scan/point_0000.h5 command_line | cut -d' ' -f1)"
else
    echo "SKIP scan.sh: no GNU parallel"
fi

if ((in_git)); then
    check "nothing written into the source tree (git status --porcelain)" \
        equals "$status_before" "$(git -C "$src" status --porcelain)"
fi
echo "test_install: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
