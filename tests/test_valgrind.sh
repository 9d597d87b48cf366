#!/usr/bin/env bash
# valgrind memcheck on a short experiment 1 (h = 1/500, dt = 1e-4, 100 steps, with contact
# from the start: g is lowered to 0.001): no invalid read or write, no use of an
# uninitialised value, no bad free (any memcheck error fails), and no memory lost per time
# step. "Definitely lost" blocks are counted on runs of 10 and of 100 steps and must not
# grow with the number of steps: what is lost once at exit (allocatables of the main program
# that gfortran does not free) is reported, not failed. Still-reachable memory (HDF5 keeps
# some until exit) is fine.
#
#   bash tests/test_valgrind.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 passed, 1 failed, 77 skipped (no program or no valgrind).
set -u

prog=${1:-}
source_dir=${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
scratch=${3:-$(mktemp -d)}
if [[ -z "$prog" || ! -x "$prog" ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
if ! command -v valgrind > /dev/null; then
    echo "SKIP: valgrind not installed (Debian: apt-get install valgrind)"
    exit 77
fi
mkdir -p "$scratch" || exit 1

n_failed=0
declare -A lost=()
for t_end in 0.001 0.01; do
    # directory names of equal length: the input path is among what is lost at exit
    dir="$scratch/steps_$(printf '%03d' "$(awk -v t="$t_end" 'BEGIN { printf "%d", t / 1e-4 + 0.5 }')")"
    rm -rf "$dir" && mkdir -p "$dir"
    sed -e "s|^&output.*|\&output prefix='$dir/run' quiet=.true. snapshot_every=20 /|" \
        -e "s|^&time.*|\&time dt=1e-4 t_end=$t_end /|" \
        -e "s|^&contact.*|\&contact g=0.001 eps=0.01 /|" "$source_dir/input/exp1.nml" > "$dir/input.nml"
    valgrind --tool=memcheck --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=none \
        --show-leak-kinds=definite --track-origins=yes --log-file="$dir/valgrind.log" \
        "$prog" "$dir/input.nml" > "$dir/stdout" 2> "$dir/stderr" < /dev/null
    status=$?
    errors=$(sed -n 's/.*ERROR SUMMARY: \([0-9,]*\) errors.*/\1/p' "$dir/valgrind.log" | tr -d ,)
    definitely=$(sed -n 's/.*definitely lost: \([0-9,]*\) bytes.*/\1/p' "$dir/valgrind.log" | tr -d ,)
    lost[$t_end]=${definitely:-0}
    if [[ $status -ne 0 || "${errors:-x}" != 0 || ! -f "$dir/run.h5" ]]; then
        n_failed=$((n_failed + 1))
        echo "FAIL t_end=$t_end: expected exit 0, 0 memcheck errors and $dir/run.h5;" \
            "got exit $status, ${errors:-no} errors (log: $dir/valgrind.log)"
        grep -A12 -m 3 -E 'Invalid|uninitialised|Mismatched|free\(\)' "$dir/valgrind.log" | head -40
    else
        echo "PASS t_end=$t_end: exit 0, 0 memcheck errors, definitely lost ${lost[$t_end]} bytes"
    fi
done
if [[ "${lost[0.01]}" -gt "${lost[0.001]}" ]]; then
    n_failed=$((n_failed + 1))
    echo "FAIL leak per step: definitely lost ${lost[0.001]} bytes after 10 steps, ${lost[0.01]} after 100"
    grep -B2 -A10 'definitely lost in' "$scratch/steps_100/valgrind.log" | head -40
else
    echo "PASS no leak per step: definitely lost ${lost[0.001]} bytes after 10 steps, ${lost[0.01]} after 100" \
        "(lost once, at exit)"
fi
echo "test_valgrind: $n_failed failed"
[[ $n_failed -eq 0 ]]
