#!/usr/bin/env python3
"""Print the layout of a rodcontact HDF5 file: every group, every dataset with its shape
and dtype, and every root attribute with its value, one per line, sorted by name.

    scripts/h5layout.py out/run.h5

Run it directly, as scripts/h5extract.py: when the python3 on PATH cannot import h5py, it
runs itself again with the Python of scripts/lib/find_python.sh. Output lines look like

    group /series
    dataset /series/t (10000,) float64
    attr model.rho = 1.2298e-17
    attr status = 'complete'

Exit status: 0 success, 1 file cannot be read, or no Python here has h5py (the message
names the packages), 2 usage error.
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'lib'))
import interpreter  # noqa: E402

interpreter.ensure_h5py(__file__)


def format_value(value):
    """An attribute value decoded by rodrun.value on one line; arrays as Python lists."""
    return repr(value.tolist() if hasattr(value, "tolist") else value)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        sys.stderr.write("usage: scripts/h5layout.py FILE.h5\n")
        return 2
    import h5py
    import rodrun

    try:
        f = rodrun.open_run(argv[1], checked=False)
    except rodrun.RunFileError as exc:
        sys.stderr.write(f"h5layout.py: {exc}\n")
        return 1

    with f:
        lines = []

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                lines.append(f"dataset /{name} {obj.shape} {obj.dtype}")
            elif isinstance(obj, h5py.Group):
                lines.append(f"group /{name}")

        f.visititems(visit)
        for line in sorted(lines, key=lambda s: s.split()[1]):
            print(line)
        for name in sorted(f.attrs.keys()):
            try:
                value = format_value(rodrun.value(f.attrs[name]))
            except (OSError, TypeError) as exc:  # e.g. a type h5py cannot convert
                value = f"<unreadable: {exc}>"
            print(f"attr {name} = {value}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except BrokenPipeError:  # output piped into head: not an error
        sys.stderr.close()
        sys.exit(0)
