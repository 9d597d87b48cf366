#!/usr/bin/env bash
# The mutation check (not part of CI: about half an hour on 2 cores): every mutant of
# tests/mutation/mutants.txt applied in turn to a scratch copy of this tree, built, and the
# suite run until a test fails (killed) or all pass (then survived, or equivalent when no
# output of a set of fixed runs changes). Details: tests/mutation/mutation.py; the last
# result: docs/verification.md, "Mutation check".
#
#   tests/mutation/run.sh                     # every mutant (a baseline suite run first)
#   tests/mutation/run.sh --only ID,ID        # some of them
#   tests/mutation/run.sh --list              # which mutants still apply to the tree
#   tests/mutation/run.sh --keep              # keep the scratch copy and the test logs
#   tests/mutation/run.sh --mutants FILE      # another list, in the format of mutants.txt
# Exit status: 0 every counted mutant killed, 1 some survived, 2 setup error.
set -u
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
py=$("$root/scripts/lib/find_python.sh") || exit 2
exec "$py" "$root/tests/mutation/mutation.py" "$root" "$@"
