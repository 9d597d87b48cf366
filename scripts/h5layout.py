"""Print the layout of a rodcontact HDF5 file: every group, every dataset with its shape
and dtype, and every root attribute with its value, one per line, sorted by name.

    <python with h5py> scripts/h5layout.py out/run.h5

The script does not choose an interpreter (no shebang): run it with one that can import
h5py (on the project machine /usr/bin/python3). Output lines look like

    group /series
    dataset /series/t (10000,) float64
    attr model.rho = 1.2298e-17
    attr status = 'complete'

Exit status: 0 success, 1 file cannot be read, 2 usage error, 77 h5py not importable
(so that a shell test can report a skip).
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'lib'))


def format_value(value):
    """An attribute value decoded by rodrun.value on one line; arrays as Python lists."""
    return repr(value.tolist() if hasattr(value, "tolist") else value)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        sys.stderr.write("usage: python3 h5layout.py FILE.h5\n")
        return 2
    try:
        import h5py
        import rodrun
    except ImportError as exc:
        sys.stderr.write(f"h5layout.py: h5py cannot be imported by {sys.executable}: {exc}\n")
        return 77

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
