"""The Python examples in examples/ run against the module built next to the CLI and print what
their docstrings promise (each checks its own numbers against a closed form or prints them)."""
import os
import pathlib
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("script", sorted(EXAMPLES.glob("*.py")), ids=lambda p: p.stem)
def test_example_script_runs(script):
    env = dict(os.environ)
    assert env.get("RIGID_PYTHON_DIR"), "RIGID_PYTHON_DIR must name the built module's directory"
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [env["RIGID_PYTHON_DIR"], env.get("PYTHONPATH")]))
    proc = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip(), "an example prints its result"
