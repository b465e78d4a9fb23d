"""The CLI tests run the built `rigid` executable named by RIGID_EXE; the tests that compare it
with the Python module import the one built next to it (RIGID_PYTHON_DIR)."""
import os
import subprocess
import sys

import pytest

_dir = os.environ.get("RIGID_PYTHON_DIR")
if _dir and _dir not in sys.path:
    sys.path.insert(0, _dir)


@pytest.fixture(scope="session")
def rigid_exe():
    exe = os.environ.get("RIGID_EXE")
    assert exe and os.path.exists(exe), "RIGID_EXE must name the built rigid executable"
    return exe


@pytest.fixture
def run(rigid_exe):
    def _run(*args, check=None, cwd=None):
        proc = subprocess.run([rigid_exe, *map(str, args)], capture_output=True, text=True,
                              cwd=cwd, timeout=600)
        if check is True:
            assert proc.returncode == 0, proc.stderr
        elif check is False:
            assert proc.returncode != 0, proc.stdout
        return proc
    return _run
