"""Make sure numpy and scipy are importable.

The project uses Debian's python3-numpy and python3-scipy. A `python3` found first on PATH may be another
interpreter (pyenv, a virtualenv) without them; then the script is run again under /usr/bin/python3.
"""
import os
import sys

SYSTEM_PYTHON = "/usr/bin/python3"


def ensure_numpy():
    try:
        import numpy  # noqa: F401
        import scipy  # noqa: F401
        return
    except ImportError as error:
        missing = error
    if os.path.realpath(sys.executable) != os.path.realpath(SYSTEM_PYTHON) and os.path.exists(SYSTEM_PYTHON) \
            and not os.environ.get("TRUTHGEN_REEXEC"):
        os.environ["TRUTHGEN_REEXEC"] = "1"
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON] + sys.argv)
    sys.stderr.write("truthgen: error: numpy/scipy not importable (%s); install python3-numpy python3-scipy\n"
                     % missing)
    sys.exit(1)
