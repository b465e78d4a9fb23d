"""Makes the freshly built module importable: RIGID_PYTHON_DIR points at build/<preset>/python."""
import os
import sys

_dir = os.environ.get("RIGID_PYTHON_DIR")
if _dir:
    sys.path.insert(0, _dir)
