"""Make sure the running Python can import h5py and numpy, for the scripts that a user runs
directly (scripts/h5extract.py): the python3 first on PATH may be a pyenv or conda interpreter
that cannot see Debian's python3-h5py. When it cannot, the script is run again with the
interpreter that scripts/lib/find_python.sh finds (/usr/bin/python3 on Debian); when there is
none, a message says which packages to install and the script exits with status 1.

    import interpreter
    interpreter.ensure_h5py(__file__)      # before importing numpy, h5py or rodrun
"""

import os
import subprocess
import sys

_AGAIN = "RODCONTACT_PYTHON_RETRIED"


def ensure_h5py(script):
    """Return when h5py and numpy import; else re-execute SCRIPT with a Python that has them,
    or exit 1 with a message naming the Debian packages."""
    try:
        import h5py  # noqa: F401
        import numpy  # noqa: F401
        return
    except ImportError as exc:
        missing = exc.name or "h5py"
    name = os.path.basename(script)
    script = os.path.abspath(script)
    finder = os.path.join(os.path.dirname(script), "lib", "find_python.sh")
    if not os.environ.get(_AGAIN) and os.path.exists(finder):
        found = subprocess.run(["bash", finder], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                               universal_newlines=True)
        py = found.stdout.strip()
        if found.returncode == 0 and py:   # (the variable _AGAIN stops a second attempt)
            os.environ[_AGAIN] = "1"
            os.execv(py, [py, script] + sys.argv[1:])
    sys.stderr.write(
        f"{name}: this Python ({sys.executable}) cannot import {missing}, and no other Python here "
        "can: install the Debian packages python3-h5py and python3-numpy (as root: apt-get install "
        "python3-h5py python3-numpy; scripts/setup.sh installs them), or pip install h5py numpy "
        "into this Python\n")
    sys.exit(1)
