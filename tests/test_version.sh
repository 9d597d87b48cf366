#!/usr/bin/env bash
# One version (issue 37): CITATION.cff parses as YAML with the keys CFF 1.2.0 requires
# (cff-version, message, title, authors, version) and the paper under references; its
# version is CMake's project(VERSION) and the one `rodcontact --version` prints; --version
# names the commit the program was built from (`git rev-parse --short HEAD` of the source
# tree, '-dirty' aside; 'unknown' outside a git checkout); a run's `version` attribute is
# --version's version. A stale binary (built before the last commit) fails: rebuild.
# Usage: bash test_version.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
"$py" -c 'import yaml' 2> /dev/null || { echo "SKIP: $py cannot import yaml (Debian: python3-yaml)"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"

line=$("$exe" --version)
check "--version exits 0" equals 0 "$?"
pattern='^rodcontact ([0-9]+\.[0-9]+\.[0-9]+) \(commit ([0-9a-f]{4,40}(-dirty)?|unknown)\)$'
[[ $line =~ $pattern ]]
check "--version prints 'rodcontact X.Y.Z (commit HASH)': '$line'" equals 0 "$?"
version=${BASH_REMATCH[1]:-} commit=${BASH_REMATCH[2]:-}

cmake_version=$(sed -n 's/^project(rodcontact VERSION \([0-9][0-9.]*\) .*/\1/p' "$src/CMakeLists.txt")
check "--version's version is CMakeLists.txt's project(VERSION)" equals "$cmake_version" "$version"

if git -C "$src" rev-parse --git-dir > /dev/null 2>&1; then
    check "--version names the commit of the source tree (rebuild after a commit)" \
        equals "$(git -C "$src" rev-parse --short HEAD)" "${commit%-dirty}"
else
    check "--version outside a git checkout says 'unknown'" equals unknown "$commit"
fi

cff=$("$py" - "$src/CITATION.cff" <<'PY'
import sys, yaml
with open(sys.argv[1], encoding="utf-8") as f:
    d = yaml.safe_load(f)
bad = [f"no {k}" for k in ("cff-version", "message", "title", "authors", "version") if not d.get(k)]
if d.get("cff-version") != "1.2.0":
    bad.append(f"cff-version {d.get('cff-version')!r}, not '1.2.0'")
if not all(isinstance(a, dict) and (a.get("name") or a.get("family-names")) for a in d.get("authors") or []):
    bad.append("an author without name or family-names")
if d.get("license") != "BSD-3-Clause":
    bad.append(f"license {d.get('license')!r}")
refs = [r for r in d.get("references") or [] if "thermoviscoelastic diffusion" in r.get("title", "")]
if not refs or [a.get("family-names") for a in refs[0].get("authors", [])] != ["Aouadi", "Copetti", "Fernández"] \
        or refs[0].get("year") != 2017:
    bad.append("references: no Aouadi, Copetti, Fernández 2017")
print("; ".join(bad) if bad else str(d["version"]))
PY
)
check "CITATION.cff is CFF 1.2.0 with its required keys and the paper: $cff" equals "$cmake_version" "$cff"

"$exe" "$src/input/exp1.nml" --set mesh.n_elements=20 --set time.t_end=0.01 --set output.prefix=run \
    --set output.quiet=.true. > /dev/null
check "a short run exits 0" equals 0 "$?"
check "the file's version attribute is --version's version" \
    equals "$version" "$("$py" "$src/scripts/lib/rodrun.py" attr run.h5 version)"

echo "test_version: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
