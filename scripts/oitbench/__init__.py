"""oitbench's Python library: the scripts' one reader, case key, techniques, statistics, paper tables,
figures and result store. The programs in scripts/ are thin command lines on top of it; no script
imports another script."""
import os
import sys

FAILED = 1  # a script that could not do its work for a reason other than its input (exit status)

# The Debian package of each third-party module the library and scripts import (scripts/deps.sh installs them).
DEBIAN_PACKAGES = {"matplotlib": "python3-matplotlib", "numpy": "python3-numpy", "psycopg": "python3-psycopg",
                   "yaml": "python3-yaml"}


def missing_module_message(error):
    """The one line a script prints when this Python cannot import a third-party module (`error`, a
    ModuleNotFoundError): the module, its Debian package and the interpreter that missed it."""
    name = (error.name or "?").split(".")[0]
    package = DEBIAN_PACKAGES.get(name, f"python3-{name}")
    prog = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "oitbench"
    return (f"{prog}: this Python ({sys.executable}) cannot import {name}: install {package} (scripts/deps.sh "
            f"does), or run the script with /usr/bin/python3 if another Python comes first in PATH")


def _missing_module_hook(kind, value, tb, default=sys.excepthook):
    """A module missing at import time (before cli.run guards main) ends in the same line, exit 1."""
    if isinstance(value, ModuleNotFoundError) and value.name:
        print(missing_module_message(value), file=sys.stderr)
        return
    default(kind, value, tb)


sys.excepthook = _missing_module_hook
