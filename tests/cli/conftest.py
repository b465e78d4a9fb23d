"""The CLI tests run the built `rigid` executable named by RIGID_EXE."""
import os
import subprocess

import pytest


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
