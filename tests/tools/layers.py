#!/usr/bin/env python3
"""The layers of src/: check that no module uses one of a later layer, or draw the use graph.

    python3 tests/tools/layers.py check SRC_DIR      # exit 1 naming every use that breaks the order
    python3 tests/tools/layers.py dot SRC_DIR        # the use graph in Graphviz's dot language

The layer order is declared once, in SRC_DIR/LAYERS (one folder name per line, lowest
first); a module's layer is the folder its file lives in. Intrinsic modules and the
libraries' (hdf5, h5lt, h5ds) are not the project's and are left out.
"""
import os
import re
import sys

MODULE = re.compile(r"^\s*module\s+(?!procedure\b)(\w+)\s*(?:!.*)?$", re.I)
SUBMODULE = re.compile(r"^\s*submodule\s*\(\s*(\w+)\s*\)\s*(\w+)", re.I)
USE = re.compile(r"^\s*use\s*(?:,\s*(intrinsic|non_intrinsic)\s*)?(?:::)?\s*(\w+)", re.I)


def read_layers(src):
    with open(os.path.join(src, "LAYERS"), encoding="utf-8") as f:
        return [line.strip() for line in f if line.strip() and not line.startswith("#")]


def scan(src):
    """Return {module: layer} and a list of (module, used module, file, line number)."""
    layers = read_layers(src)
    owner, uses = {}, []
    for layer in layers:
        folder = os.path.join(src, layer)
        if not os.path.isdir(folder):
            raise SystemExit(f"layers.py: {src}/LAYERS names '{layer}', which is not a folder of {src}")
    for root, _, files in os.walk(src):
        rel = os.path.relpath(root, src)
        for name in sorted(files):
            if not name.endswith((".f90", ".f90.in")):
                continue
            layer = rel.split(os.sep)[0]
            path = os.path.join(root, name)
            if layer not in layers:
                raise SystemExit(f"layers.py: {path} is in no layer of {src}/LAYERS")
            this = None
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    m = MODULE.match(line) or SUBMODULE.match(line)
                    if m and this is None:
                        this = m.group(m.lastindex).lower()
                        owner[this] = layer
                        if m.re is SUBMODULE:   # a submodule uses its parent's scope
                            uses.append((this, m.group(1).lower(), path, number))
                        continue
                    u = USE.match(line)
                    if u and this is not None and u.group(1) is None:
                        uses.append((this, u.group(2).lower(), path, number))
    return layers, owner, uses


def check(src):
    layers, owner, uses = scan(src)
    rank = {name: i for i, name in enumerate(layers)}
    broken = 0
    for user, used, path, number in uses:
        if used not in owner:
            continue  # a library's module (hdf5, lapack interfaces) or an intrinsic one
        if rank[owner[used]] > rank[owner[user]]:
            broken += 1
            print(f"{path}:{number}: {user} ({owner[user]}) uses {used} ({owner[used]}), "
                  f"a later layer (order: {' < '.join(layers)})", file=sys.stderr)
    if broken:
        print(f"layers.py: {broken} use(s) against the layer order of {src}/LAYERS", file=sys.stderr)
        return 1
    print(f"layers.py: {len(owner)} modules in {len(layers)} layers, "
          f"{sum(1 for u in uses if u[1] in owner)} uses, none against the order")
    return 0


def dot(src):
    """The use graph, one box per layer (drawn top to bottom from the driver). Uses of the
    first layer (base: kinds, errors, strings, files) are left out: every layer may use it,
    and its edges would hide the rest."""
    layers, owner, uses = scan(src)
    print("digraph uses {")
    print('  rankdir=TB; newrank=true; ranksep=0.35; nodesep=0.15;')
    print('  node [shape=box, fontsize=10, height=0.25]; edge [arrowsize=0.5, color="#555555"];')
    print(f'  label="use graph of src/ (tests/tools/layers.py dot src); uses of {layers[0]}/ left out"; fontsize=10;')
    for i, layer in reversed(list(enumerate(layers))):
        print(f'  subgraph cluster_{i} {{ label="{i + 1}. {layer}"; style=rounded; fontsize=10;')
        for module in sorted(m for m, l in owner.items() if l == layer):
            print(f"    {module};")
        print("  }")
    edges = sorted({(a, b) for a, b, _, _ in uses if b in owner and a != b and owner[b] != layers[0]})
    for a, b in edges:
        print(f"  {a} -> {b};")
    print("}")
    return 0


def main(argv):
    if len(argv) != 3 or argv[1] not in ("check", "dot"):
        print(__doc__, file=sys.stderr)
        return 2
    return check(argv[2]) if argv[1] == "check" else dot(argv[2])


if __name__ == "__main__":
    sys.exit(main(sys.argv))
