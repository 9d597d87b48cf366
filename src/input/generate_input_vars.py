#!/usr/bin/env python3
"""Generate the input-variable table and the namelist plumbing from config_m's types.

    python3 src/input/generate_input_vars.py src/input/config_m.f90 OUT_DIR

The build runs it (CMakeLists.txt) whenever config_m.f90 changes. config_m's header says how
its types are the groups and variables and which declarations are inputs (anything else in a
group's type stops the generator with a message naming the line); from them this writes, into
OUT_DIR, two files that input_vars_m includes:

  input_vars_table.inc   GROUP_NAMES and INPUT_VARS (group, name, kind, keyword, unit)
  input_vars_access.inc  get_value (an input's value into an item) and read_namelist: one
                         local per variable named as in the input, the namelist statement of
                         each group, the copies between each local and its component
"""
import collections
import os
import re
import sys

# The lengths of input_var_t's components (input_vars_m) and of GROUP_NAMES' elements.
LEN_GROUP, LEN_VAR_NAME, LEN_UNIT = 8, 16, 24
# Names the generated read_namelist uses itself: no input variable may be called so.
RESERVED = {"cfg", "group", "text", "ios", "msg", "keyword", "read_namelist"}

TYPE_START = re.compile(r"^\s*type\s*::\s*(\w+)\s*$", re.I)
TYPE_END = re.compile(r"^\s*end\s+type\b", re.I)
GROUP = re.compile(r"^\s*type\((\w+)\)\s*::\s*(\w+)\s*(?:!.*)?$", re.I)
COMPONENT = re.compile(
    r"^\s*(?P<type>real\(dp\)|integer|logical|character\(len=(?P<len>\w+)\))\s*::\s*"
    r"(?P<name>\w+)\s*(?P<dims>\([^)]*\))?\s*(?:=\s*(?P<default>.*?))?\s*(?:!<\s*(?P<doc>.*))?$", re.I)
UNIT = re.compile(r"\[([^\[\]]*)\]\s*$")
NESTED = re.compile(r"\([^()]*\)|\[[^\[\]]*\]")   # an innermost (...) or [...]


Var = collections.namedtuple("Var", "group name kind keyword unit local")


def fail(path, number, message):
    raise SystemExit(f"{path}:{number}: generate_input_vars.py: {message}")


def read_types(path):
    """{type name: [(line number, line)]} of every `type :: name ... end type` block."""
    types, current = {}, None
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if current is None:
                m = TYPE_START.match(line)
                if m:
                    current = m.group(1).lower()
                    types[current] = []
            elif TYPE_END.match(line):
                current = None
            else:
                types[current].append((number, line.rstrip("\n")))
    return types


def variable(path, number, group, line):
    """The input variable declared by `line` of group's type, or None (not an input)."""
    if re.search(r"!<\s*not an input", line, re.I):
        return None
    m = COMPONENT.match(line)
    if not m:
        fail(path, number, f"cannot read this component of &{group} (one component per line, declared as "
                           "real(dp), integer, logical or character(len=LEN_NAME|LEN_PATH)): " + line.strip())
    doc = (m.group("doc") or "").strip()
    name, kind_text, dims = m.group("name"), m.group("type").lower(), (m.group("dims") or "").replace(" ", "")
    keyword = False
    if kind_text == "real(dp)":
        kind = {"": "KIND_REAL", "(0:MAX_POLY_DEGREE)": "KIND_COEFFS", "(2)": "KIND_PAIR"}.get(dims)
        if kind is None:
            fail(path, number, f"{group}.{name}: a real input is a scalar, (0:MAX_POLY_DEGREE) or (2), not {dims}")
        local = "real(dp) :: " + name + dims
    elif dims:
        fail(path, number, f"{group}.{name}: only real inputs may be arrays")
    elif kind_text == "integer":
        kind, local = "KIND_INTEGER", "integer :: " + name
    elif kind_text == "logical":
        kind, local = "KIND_LOGICAL", "logical :: " + name
    else:
        length = m.group("len")
        if length not in ("LEN_NAME", "LEN_PATH"):
            fail(path, number, f"{group}.{name}: a string input has len=LEN_NAME (a keyword) or len=LEN_PATH")
        kind, keyword, local = "KIND_STRING", length == "LEN_NAME", f"character(len={length}) :: {name}"
    u = UNIT.search(doc)
    unit = u.group(1) if u else ""
    if m.group("default") is None:
        fail(path, number, f"{group}.{name}: an input variable needs a default value in its type")
    if top_level_comma(m.group("default")):
        fail(path, number, f"cannot read this component of &{group} (one component per line): " + line.strip())
    if name.lower() in RESERVED:
        fail(path, number, f"{group}.{name}: the name is used by the generated code; choose another")
    if len(name) > LEN_VAR_NAME or len(unit) > LEN_UNIT:
        fail(path, number, f"{group}.{name}: names have at most {LEN_VAR_NAME} characters, units {LEN_UNIT}")
    return Var(group, name, kind, keyword, unit, local)


def top_level_comma(text):
    """Whether text has a comma outside quotes, parentheses and brackets."""
    text = re.sub(r"'[^']*'|\"[^\"]*\"", "", text)
    while re.search(NESTED, text):
        text = re.sub(NESTED, "", text)
    return "," in text


def read_variables(path):
    """The groups in the order of config_t and the variables of each, in order."""
    types = read_types(path)
    if "config_t" not in types:
        fail(path, 1, "no type config_t")
    groups, variables = [], []
    for _, line in types["config_t"]:
        m = GROUP.match(line)
        if not m:
            continue
        type_name, group = m.group(1).lower(), m.group(2)
        if type_name not in types:
            fail(path, 1, f"config_t's component {group} has type {type_name}, which config_m does not define")
        if len(group) > LEN_GROUP or group.lower() in RESERVED:
            fail(path, 1, f"group name {group}: at most {LEN_GROUP} characters, and not one of {sorted(RESERVED)}")
        groups.append(group)
        for number, text in types[type_name]:
            if not text.strip() or text.strip().startswith("!"):
                continue
            var = variable(path, number, group, text)
            if var is not None:
                variables.append(var)
    names = {g.lower() for g in groups}
    for var in variables:
        if var.name.lower() in names:
            fail(path, 1, f"{var.group}.{var.name}: a variable may not be named as a namelist group")
    return groups, variables


def wrap(items, indent, width):
    """The items separated by ', ', broken into Fortran continuation lines of about width."""
    lines, line = [], ""
    for item in items:
        if line and len(line) + len(item) + 2 > width:
            lines.append(line + ",")
            line = ""
        line = f"{line}, {item}" if line else item
    lines.append(line)
    return (" &\n" + indent).join(lines)


def table(groups, variables):
    out = ["! Generated by src/input/generate_input_vars.py from src/input/config_m.f90: do not edit.",
           "",
           "    !> Namelist groups (config_t's components), in the order validation checks them.",
           f"    character(len=*), parameter :: GROUP_NAMES({len(groups)}) = [character(len={LEN_GROUP}) :: &",
           "        " + wrap([f"'{g}'" for g in groups], "        ", 100) + "]",
           "",
           "    !> Every input variable, by group in the order of GROUP_NAMES; within a group in the",
           "    !> order of its type in config_m, which is the order of the messages, the echo and the file.",
           "    type(input_var_t), parameter :: INPUT_VARS(*) = [ &"]
    rows = []
    for var in variables:
        unit = var.unit.replace("'", "''")
        rows.append(f"        input_var_t('{var.group}', '{var.name}', {var.kind}, "
                    f"{'.true.' if var.keyword else '.false.'}, '{unit}')")
    out.append(", &\n".join(rows) + "]")
    return "\n".join(out) + "\n"


def access(groups, variables):
    # one local per name (Fortran is case-insensitive: &model d and &material D share one)
    locals_, seen = [], {}
    for var in variables:
        key = var.name.lower()
        if key in seen:
            if seen[key] != var.local.lower():
                raise SystemExit(f"generate_input_vars.py: {var.group}.{var.name} is declared as '{var.local}' "
                                 f"but another group's {var.name} as '{seen[key]}'; one name, one declaration")
            continue
        seen[key] = var.local.lower()
        locals_.append(var.local)
    value = {"KIND_REAL": "item%reals = [{}]", "KIND_COEFFS": "item%reals = {}", "KIND_PAIR": "item%reals = {}",
             "KIND_INTEGER": "item%int = {}", "KIND_STRING": "item%text = trim({})", "KIND_LOGICAL": "item%flag = {}"}
    out = ["! Generated by src/input/generate_input_vars.py from src/input/config_m.f90: do not edit.",
           "",
           "    !> item's value: that of INPUT_VARS(k) in cfg.",
           "    subroutine get_value(cfg, k, item)",
           "        type(config_t), intent(in) :: cfg",
           "        integer, intent(in) :: k",
           "        type(input_item_t), intent(inout) :: item",
           "",
           "        select case (k)"]
    for k, var in enumerate(variables, 1):
        out += [f"        case ({k})", "            " + value[var.kind].format(f"cfg%{var.group}%{var.name}")]
    out += ["        end select",
            "    end subroutine get_value",
            "",
            "    !> Read the namelist `text` ('&group ... /', assignments of variables of `group`) over",
            "    !> the values of the group in cfg (a keyword in lower case); ios and msg as from the read.",
            "    subroutine read_namelist(cfg, group, text, ios, msg)",
            "        type(config_t), intent(inout) :: cfg",
            "        character(len=*), intent(in) :: group, text",
            "        integer, intent(out) :: ios",
            "        character(len=*), intent(out) :: msg",
            "        ! The namelist objects: one local per input variable, named as in the input (groups",
            "        ! that share a name share its local; only one group is read at a time)."]
    out += ["        " + declaration for declaration in locals_]
    for group in groups:
        members = [v.name for v in variables if v.group == group]
        out.append(f"        namelist /{group}/ " + wrap(members, "            ", 80))
    out += ["", "        ios = 0", "        select case (group)"]
    for group in groups:
        members = [v for v in variables if v.group == group]
        out.append(f"        case ('{group}')")
        out += [f"            {v.name} = cfg%{group}%{v.name}" for v in members]
        out += [f"            read (text, nml={group}, iostat=ios, iomsg=msg)", "            if (ios /= 0) return"]
        out += [f"            cfg%{group}%{v.name} = " + (f"keyword({v.name})" if v.keyword else v.name)
                for v in members]
    out += ["        end select", "    end subroutine read_namelist"]
    return "\n".join(out) + "\n"


def write(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def main(argv):
    if len(argv) != 3:
        raise SystemExit(__doc__.split("\n\n")[1])
    groups, variables = read_variables(argv[1])
    os.makedirs(argv[2], exist_ok=True)
    write(os.path.join(argv[2], "input_vars_table.inc"), table(groups, variables))
    write(os.path.join(argv[2], "input_vars_access.inc"), access(groups, variables))


if __name__ == "__main__":
    main(sys.argv)
