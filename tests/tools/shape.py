"""The shape of src/ and app/ (tests/test_shape.sh): no module over MODULE_LINES lines, no
procedure over PROCEDURE_LINES lines.

    shape.py check DIR [DIR ...]     # exit 1, naming each file and procedure over its limit
    shape.py check --known FILE DIR [DIR ...]   # the same, with FILE's known excesses allowed
    shape.py report DIR [DIR ...]    # every file's length and its longest procedures
    shape.py count DIR [DIR ...]     # lines of every file but README.md and LAYERS, and the
                                     # mean length of a non-blank one

FILE (tests/shape_known.txt) lists excesses not yet cut, one a line: `PATH LINES` for a module
or `PATH:PROCEDURE LINES` for a procedure (PATH relative to the repository root); each may
not grow past LINES, and an entry that is no longer over the limit (or no longer exists) is
itself reported, so that the list only shrinks.

A module is a Fortran source file (one module or submodule a file); its length counts every
line. A procedure runs from its `subroutine`/`function` statement to the matching `end`,
both counted; a contained procedure counts in its host's length too (it is part of it).
"""
import os
import re
import sys

MODULE_LINES = 450
PROCEDURE_LINES = 60
FORTRAN = (".f90", ".F90", ".f90.in")
START = re.compile(
    r"^\s*(?:(?:pure|elemental|recursive|impure|module|non_recursive)\s+|"
    r"(?:integer|real|logical|character|complex|type|class)\s*(?:\([^)]*\))?\s+)*"
    r"(subroutine|function)\s+(\w+)", re.IGNORECASE)
END = re.compile(r"^\s*end\s+(subroutine|function)\b", re.IGNORECASE)
BARE_END = re.compile(r"^\s*end\s*(!.*)?$", re.IGNORECASE)


def files(dirs, fortran_only=True):
    for top in dirs:
        for root, _, names in os.walk(top):
            for name in sorted(names):
                if name in ("README.md", "LAYERS"):
                    continue
                if fortran_only and not name.endswith(FORTRAN):
                    continue
                yield os.path.join(root, name)


def procedures(path):
    """(name, first line, length) of every procedure of a Fortran file."""
    stack, found = [], []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, start=1):
            code = line.split("!", 1)[0]
            if re.match(r"^\s*end\b", code, re.IGNORECASE):
                if END.match(code) and stack:
                    name, first = stack.pop()
                    found.append((name, first, number - first + 1))
                continue
            match = START.match(code)
            if match and not re.match(r"^\s*(module\s+procedure|procedure)\b", code, re.IGNORECASE):
                stack.append((match.group(2), number))
    return found


def read_known(path):
    """{key: lines} of a known-excess file (key PATH or PATH:PROCEDURE)."""
    known = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                known[line[0]] = int(line[1])
    return known


def check(dirs, known=None, root="."):
    known = dict(known or {})
    problems = []
    for path in files(dirs):
        key = os.path.relpath(path, root)
        with open(path, encoding="utf-8") as f:
            n = sum(1 for _ in f)
        limit = known.pop(key, None)
        if n > MODULE_LINES and (limit is None or n > limit):
            allowed = f"known at {limit}, may not grow" if limit else f"at most {MODULE_LINES} a module"
            problems.append(f"{path}: {n} lines ({allowed})")
        elif limit is not None and n <= MODULE_LINES:
            problems.append(f"{key}: {n} lines, within the limit: remove it from the known list")
        for name, first, length in procedures(path):
            limit = known.pop(f"{key}:{name}", None)
            if length > PROCEDURE_LINES and (limit is None or length > limit):
                allowed = f"known at {limit}, may not grow" if limit else f"at most {PROCEDURE_LINES}"
                problems.append(f"{path}:{first}: procedure {name} is {length} lines ({allowed})")
            elif limit is not None and length <= PROCEDURE_LINES:
                problems.append(f"{key}:{name}: {length} lines, within the limit: "
                                "remove it from the known list")
    problems += [f"{key}: in the known list but not found" for key in known]
    return problems


def main(argv):
    if len(argv) < 3 or argv[1] not in ("check", "report", "count"):
        print(__doc__, file=sys.stderr)
        return 2
    dirs, known, root = argv[2:], None, "."
    if dirs[:1] == ["--known"]:
        known = read_known(dirs[1])
        root = os.path.dirname(os.path.dirname(os.path.abspath(dirs[1])))
        dirs = dirs[2:]
    if argv[1] == "check":
        problems = check(dirs, known, root)
        for p in problems:
            print(p)
        print(f"shape.py: {len(problems)} over the limits", file=sys.stderr)
        return 1 if problems else 0
    if argv[1] == "count":
        total, chars, nonblank = 0, 0, 0
        for path in files(dirs, fortran_only=False):
            with open(path, encoding="utf-8") as f:
                for line in f:
                    total += 1
                    if line.strip():
                        nonblank += 1
                        chars += len(line.rstrip("\n"))
        print(f"{total} lines, mean non-blank line {chars / max(nonblank, 1):.1f} characters")
        return 0
    for path in files(dirs):
        with open(path, encoding="utf-8") as f:
            n = sum(1 for _ in f)
        longest = sorted(procedures(path), key=lambda p: -p[2])[:3]
        print(f"{n:5d} {path}  " + ", ".join(f"{name} {length}" for name, _, length in longest))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
