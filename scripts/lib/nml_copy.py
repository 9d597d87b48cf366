"""Copy a rodcontact namelist input with some scalar variables replaced.

    python3 scripts/lib/nml_copy.py SRC DST group.variable=value [group.variable=value ...]

    python3 scripts/lib/nml_copy.py input/exp1.nml /tmp/exp1.nml \
        "output.prefix='/tmp/exp1'" time.t_end=0.3 output.quiet=.true.

Inside each named group, every earlier assignment of a named variable is removed and the
new assignment is put just before the group's closing '/'; a group that is absent is
appended. A first comment line names the source and the changes. Everything else (comments, initial data, the other variables) is copied as it
is, so the copy still documents itself. Values are written verbatim (quote strings
yourself). Only scalar variables can be replaced (an array assignment such as
`theta0_poly = 0, 40, -80` would lose only its first element: refused).

Used by scripts/paper/figures.sh (output directory, shortened --quick runs, the long copy of
experiment 1). Exit status: 0 written, 2 usage or parse error. Any python3 will do.
"""

import re
import sys

ARRAY_VARIABLES = {"u0_poly", "u1_poly", "theta0_poly", "p0_poly", "q0_poly", "eta0_poly",
                   "theta0_step", "p0_step"}


def parse_overrides(args):
    overrides = {}
    for arg in args:
        m = re.fullmatch(r"(\w+)\.(\w+)=(.+)", arg, re.S)
        if not m:
            raise ValueError(f"override '{arg}' is not of the form group.variable=value")
        group, name, value = m.group(1).lower(), m.group(2).lower(), m.group(3)
        if name in ARRAY_VARIABLES:
            raise ValueError(f"{group}.{name} is an array: nml_copy.py replaces scalars only")
        overrides.setdefault(group, {})[name] = value
    return overrides


def rewrite(text, overrides):
    out, i, group, seen = [], 0, None, set()
    value = re.compile(r"\s*=\s*('[^']*'|\"[^\"]*\"|[^\s,/!]+)\s*,?", re.S)
    while i < len(text):
        ch = text[i]
        if ch in "'\"":                                   # quoted string: copy verbatim
            j = text.find(ch, i + 1)
            if j < 0:
                raise ValueError("unterminated string")
            out.append(text[i:j + 1])
            i = j + 1
            continue
        if ch == "!":                                     # comment to end of line
            j = text.find("\n", i)
            j = len(text) if j < 0 else j
            out.append(text[i:j])
            i = j
            continue
        if ch == "&" and group is None:                   # group start
            m = re.match(r"&(\w+)", text[i:])
            if not m:
                raise ValueError(f"'&' without a group name at offset {i}")
            group = m.group(1).lower()
            seen.add(group)
            out.append(m.group(0))
            i += len(m.group(0))
            continue
        if ch == "/" and group is not None:               # group end: add the new values
            for name, v in overrides.get(group, {}).items():
                out.append(f" {name}={v} ")
            out.append("/")
            group = None
            i += 1
            continue
        if group in overrides and ch.isalpha() and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r"\w+", text[i:])
            if m.group(0).lower() in overrides[group]:
                v = value.match(text, i + len(m.group(0)))
                if v:                                     # drop 'name = value,'
                    i = v.end()
                    continue
            out.append(m.group(0))
            i += len(m.group(0))
            continue
        out.append(ch)
        i += 1
    if group is not None:
        raise ValueError(f"group &{group} is not closed by '/'")
    for g, kv in overrides.items():
        if g not in seen:
            out.append("\n&%s %s /\n" % (g, " ".join("%s=%s" % x for x in kv.items())))
    return "".join(out)


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        sys.stderr.write(__doc__)
        return 2
    src, dst = argv[1], argv[2]
    try:
        overrides = parse_overrides(argv[3:])
        with open(src, encoding="utf-8") as f:
            text = rewrite(f.read(), overrides)
    except (OSError, ValueError) as exc:
        sys.stderr.write(f"nml_copy.py: {src}: {exc}\n")
        return 2
    header = "! Copy of %s made by scripts/lib/nml_copy.py with %s\n" % (src, " ".join(argv[3:]) or "no changes")
    with open(dst, "w", encoding="utf-8") as f:
        f.write(header + text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
