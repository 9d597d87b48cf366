#!/usr/bin/env bash
# A new contact law touches only the files docs/architecture.md names ("A contact law"): in a
# scratch copy of the tree, the page's worked example, the toy law 'spring3'
# (lambda = (3/eps)[u(1) - g]_+), is added as the page says, taking its two Fortran blocks
# from the page itself: the new module, and the lines of the table contact_laws_m. The test
# then checks that no file changed but the ones the page's numbered list names, builds
# rodcontact (Release, warnings as errors), and runs the impact with contact.law =
# 'spring3' (implicit Euler): every series entry in contact must have the toy law's stress
# sigma(1,t) = -(3/eps)[u(1,t) - g]_+, and a misspelt law must be refused with 'spring3'
# among the allowed names. It builds the code: minutes under load (CTest label extension).
#
#   bash tests/test_new_contact_law.sh <path to rodcontact (unused)> <source dir> <scratch dir>
# Exit status: 0 passed, 1 failed, 77 skipped (no Python with h5py, or no cmake).
set -u
src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
command -v cmake > /dev/null || { echo "SKIP: no cmake"; exit 77; }
cd "$scratch" && rm -rf ./* || exit 1
. "$src/tests/lib/checks.sh"

mkdir tree && cp -r "$src/src" "$src/app" "$src/tests" "$src/bench" "$src/docs" "$src/input" \
    "$src/CMakeLists.txt" tree/ || exit 1
rm -rf tree/tests/reference   # large, and not needed to build

# --- the edits, as docs/architecture.md gives them ----------------------------------------
"$py" - "$src/docs/architecture.md" tree > edits.out 2>&1 <<'PY'
import re, sys
doc, tree = open(sys.argv[1], encoding="utf-8").read(), sys.argv[2]
section = doc[doc.index("**A contact law**"):doc.index("**A time scheme**")]
blocks = re.findall(r"```fortran\n(.*?)```", section, re.S)
if len(blocks) != 2:
    sys.exit(f"expected two fortran blocks in 'A contact law', found {len(blocks)}")
module, rows = blocks
name = re.search(r"^module (\w+)$", module, re.M).group(1)
open(f"{tree}/src/model/{name}.f90", "w").write(module)
table = f"{tree}/src/model/contact_laws_m.f90"
text = open(table).read().splitlines(keepends=True)
uses = [l for l in rows.splitlines(keepends=True) if l.lstrip().startswith("use ")]
case = [l for l in rows.splitlines(keepends=True) if not l.lstrip().startswith("use ")]
last_use = max(i for i, l in enumerate(text) if l.lstrip().startswith("use contact_"))
text[last_use + 1:last_use + 1] = uses
default = next(i for i, l in enumerate(text) if l.strip() == "case default")
text[default:default] = case
open(table, "w").write("".join(text))
# the files the page's numbered list names (<name>: the new module's)
listed = re.findall(r"^\d+\. `([^`]+)`", section, re.M)
print("\n".join(p.replace("contact_<name>_m", name) for p in listed))
PY
status=$?  # taken at once: the $(...) in the message below would reset $?
check "the page's two blocks applied to the scratch tree ($(tail -3 edits.out))" equals 0 "$status"
(cd tree && find . -type f | sort) > after.txt
(cd "$src" && find src app tests bench docs input CMakeLists.txt -type f ! -path 'tests/reference/*' \
    | sed 's|^|./|' | sort) > before.txt
changed=$(comm -13 before.txt after.txt | sed 's|^\./||')
for f in $(sed 's|^\./||' before.txt); do
    cmp -s "$src/$f" "tree/$f" || changed="$changed $f"
done
unlisted=""
for f in $changed; do grep -qxF "$f" edits.out || unlisted="$unlisted $f"; done
check "the files changed ($(echo $changed)) are all in the page's list" equals "" "$unlisted"

# --- build and run -----------------------------------------------------------------------
cmake -S tree -B build -DCMAKE_BUILD_TYPE=Release -DRODCONTACT_WERROR=ON > configure.log 2>&1 &&
    cmake --build build --target rodcontact -j 2 > build.log 2>&1
status=$?
check "rodcontact builds with the new law and no warning ($(grep -m3 -E 'Error|Warning' build.log))" \
    equals 0 "$status"
if [[ $status -ne 0 ]]; then
    echo "test_new_contact_law: $n_failed of $n_checks checks failed"
    exit 1
fi
exe=build/rodcontact
"$exe" "$src/input/impact.nml" --set contact.law="'spring3'" --set time.scheme="'euler'" \
    --set mesh.n_elements=100 --set time.t_end=0.3 --set output.prefix=spring3 --set output.quiet=.true. \
    > run.out 2> run.err
status=$?  # taken at once: the $(...) in the message below would reset $?
check "the impact runs with contact.law = 'spring3' ($(tail -2 run.err))" equals 0 "$status"
check "every series entry in contact has sigma(1,t) = -(3/eps)[u(1,t) - g]_+ (1e-10 relative)" \
    "$py" - spring3.h5 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
eps, law = float(f.attrs["contact.eps"]), f.attrs["contact.law"]
p, sigma = f["series/penetration"][:], f["series/contact_stress"][:]
want = -3.0 / eps * p
contact = p > 0
worst = np.max(np.abs(sigma[contact] - want[contact]) / np.abs(want[contact])) if contact.any() else np.inf
print(f"  law {law!r}: {contact.sum()} of {p.size} entries in contact, largest relative difference {worst:.2e}")
sys.exit(0 if contact.sum() >= 10 and worst <= 1e-10 and np.all(sigma[~contact] == 0) else 1)
PY
printf "&contact law = 'spring' /\n" > misspelt.nml
"$exe" misspelt.nml > misspelt.out 2>&1
check "a misspelt law is refused (exit 2)" equals 2 "$?"
check "the message lists 'spring3' among the allowed names: $(cat misspelt.out)" \
    grep -qF "must be one of 'penalty', 'signorini', 'spring3'" misspelt.out

echo "test_new_contact_law: $n_failed of $n_checks checks failed"
[ "$n_failed" -eq 0 ]
