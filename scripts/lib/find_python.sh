#!/usr/bin/env bash
# Print the path of a Python interpreter that can import h5py and numpy, or explain
# on stderr and exit 1. The python3 first on PATH may be a pyenv/conda interpreter
# that cannot see Debian's python3-h5py, hence the fallback to /usr/bin/python3.
#
#   PY=$(scripts/lib/find_python.sh) || exit 1

set -uo pipefail

for candidate in python3 /usr/bin/python3; do
    path="$(command -v "$candidate" 2>/dev/null)" || continue
    if "$path" -c 'import h5py, numpy' >/dev/null 2>&1; then
        echo "$path"
        exit 0
    fi
done

cat >&2 <<'MSG'
no Python with h5py found: install python3-h5py (Debian/Ubuntu: apt-get install -y python3-h5py python3-numpy),
or `pip install h5py numpy` into the python3 on your PATH. Tried: python3, /usr/bin/python3.
MSG
exit 1
