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

import sys


def format_value(value):
    """Attribute value on one line; bytes decoded, numpy scalars/arrays as plain Python."""
    if isinstance(value, bytes):
        return repr(value.decode("utf-8", errors="replace"))
    if isinstance(value, str):
        return repr(value)
    if hasattr(value, "tolist"):  # numpy scalar or array
        value = value.tolist()
        if isinstance(value, bytes):
            return repr(value.decode("utf-8", errors="replace"))
    return repr(value)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        sys.stderr.write("usage: python3 h5layout.py FILE.h5\n")
        return 2
    try:
        import h5py
    except ImportError as exc:
        sys.stderr.write(f"h5layout.py: h5py cannot be imported by {sys.executable}: {exc}\n")
        return 77

    path = argv[1]
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        sys.stderr.write(f"h5layout.py: cannot open '{path}': {exc}\n")
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
                value = format_value(f.attrs[name])
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
