#!/usr/bin/env bash
# The docs against the tree: every repository path that README.md, docs/*.md and the
# folders' READMEs name exists, every script has its line in scripts/README.md
# (tests/tools/doc_paths.py), and docs/uses.dot, the use graph of docs/architecture.md, is
# the one the sources give today (tests/tools/layers.py dot src; regenerate it with that
# command when a `use` changes) and docs/uses.svg its drawing (Graphviz, installed by
# scripts/setup.sh). The path check is shown to fail on a copy of the README
# that names a missing script.
# Usage: bash test_docs.sh <rodcontact> <source dir> <scratch dir>
set -u
src=$2; scratch=$3
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"

python3 "$src/tests/tools/doc_paths.py" "$src" > paths.out 2> paths.err
status=$?  # taken at once: the $(head) of the message below would reset $?
check "every path the docs name exists, every script is indexed ($(head -c 600 paths.err))" equals 0 "$status"

python3 "$src/tests/tools/layers.py" dot "$src/src" > uses.dot
check "docs/uses.dot is the use graph of the sources (regenerate: python3 tests/tools/layers.py dot src > docs/uses.dot)" \
    cmp -s uses.dot "$src/docs/uses.dot"

dot -Tsvg uses.dot > uses.svg 2> dot.err
check "docs/uses.svg is docs/uses.dot drawn by Graphviz (regenerate: dot -Tsvg docs/uses.dot -o docs/uses.svg)" \
    cmp -s uses.svg "$src/docs/uses.svg"

mkdir -p copy/docs copy/scripts copy/src
cp "$src/README.md" copy/ && cp "$src/scripts/README.md" copy/scripts/
echo 'Run `scripts/no_such_tool.sh` to see.' >> copy/README.md
python3 "$src/tests/tools/doc_paths.py" copy > broken.out 2> broken.err
check "a README naming a missing script fails the check" equals 1 "$?"
check "the message names the file, line and path" grep -q "README.md:[0-9]*: names 'scripts/no_such_tool.sh'" broken.err

echo "test_docs: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
