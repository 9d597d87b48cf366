#!/usr/bin/env bash
# The shape of src/ and app/: no module over 450 lines, no procedure over 60 lines
# (tests/tools/shape.py names each file and procedure over its limit), except the excesses
# not yet cut that tests/shape_known.txt lists, each at its present length: they may not
# grow, and one that is cut below the limit must leave the list. The test also proves
# the check can fail: in a scratch copy, a module grows past 450 lines and a procedure past
# 60, and the check must exit 1 and name both.
# Usage: bash test_shape.sh <rodcontact> <source dir> <scratch dir>
set -u
src=$2; scratch=$3
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"
py=$("$src/scripts/lib/find_python.sh") || py=python3
shape() { "$py" "$src/tests/tools/shape.py" check "$@"; }

(cd "$src" && "$py" tests/tools/shape.py check --known tests/shape_known.txt src app) > real.out 2> real.err
status=$?   # taken at once: the $(...) in the message below would reset $?
check "src/ and app/ keep modules <= 450 and procedures <= 60 lines (or the known list's): $(cat real.out)" \
    equals 0 "$status"

mkdir copy && cp -r "$src/src" "$src/app" copy/
# a procedure of 61 lines and a module of 451 lines
{ echo 'module grown_m'; echo 'contains'; echo '    subroutine long_one()'
  for i in $(seq 1 59); do echo "        ! line $i"; done
  echo '    end subroutine long_one'
  for i in $(seq 1 387); do echo "    ! filler $i"; done
  echo 'end module grown_m'; } > copy/src/base/grown_m.f90
check "the scratch module has 451 lines" equals 451 "$(wc -l < copy/src/base/grown_m.f90)"
mkdir copy/tests && cp "$src/tests/shape_known.txt" copy/tests/
(cd copy && "$py" "$src/tests/tools/shape.py" check --known tests/shape_known.txt src app) > broken.out 2> broken.err
check "a long module and procedure fail the check" equals 1 "$?"
check "the message names the module and its length" grep -q 'grown_m.f90: 451 lines' broken.out
check "the message names the procedure and its length" grep -q 'procedure long_one is 61 lines' broken.out

# a module of the known list may not grow (when the list still has one)
known_module=$(grep -v '^#' "$src/tests/shape_known.txt" | awk '$1 !~ /:/ {print $1; exit}')
if [[ -n "$known_module" ]]; then
    echo '! one more line' >> "copy/$known_module"
    (cd copy && "$py" "$src/tests/tools/shape.py" check --known tests/shape_known.txt src app) > grown.out 2> grown.err
    check "a known module that grows fails the check" equals 1 "$?"
    check "the message says it may not grow" grep -q "$known_module: .*may not grow" grown.out
fi

echo "test_shape: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
