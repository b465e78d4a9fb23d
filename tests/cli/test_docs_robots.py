"""docs/robots.md's C++ examples build and run as written, in a scratch directory that holds
the repository's examples/ (as the page's paths expect), with the built `rigid` first on PATH.
Its ```sh and ```python blocks run with every other page's in tests/cli/test_docs_blocks.py."""
import os
import pathlib
import re
import subprocess

import pytest


ROOT = pathlib.Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "robots.md"


def blocks(language):
    return re.findall(rf"```{language}\n(.*?)```", DOC.read_text(), re.S)


@pytest.fixture()
def scratch(tmp_path):
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    env = dict(os.environ)
    exe = pathlib.Path(os.environ.get("RIGID_EXE", ROOT / "build" / "ci" / "bin" / "rigid")).resolve()
    env["PATH"] = f"{exe.parent}{os.pathsep}{env.get('PATH', '')}"
    if "RIGID_PYTHON_DIR" in os.environ:
        env["PYTHONPATH"] = os.environ["RIGID_PYTHON_DIR"]
    return tmp_path, env


def test_every_cpp_block_builds_and_runs(scratch):
    """A ```cpp block starts `// FILE.cpp: build and run with` followed by `//   COMMAND` lines:
    the block is written to FILE.cpp and the commands run in order (the system's compiler)."""
    cwd, env = scratch
    for block in blocks("cpp"):
        lines = block.splitlines()
        head = re.match(r"// (\S+\.cpp): build and run with$", lines[0])
        if head is None:
            continue
        (cwd / head[1]).write_text(block)
        for line in lines[1:]:
            command = re.match(r"//   (.+)$", line)
            if command is None:
                break
            r = subprocess.run(command[1], shell=True, cwd=cwd, env=env, capture_output=True, text=True,
                               timeout=120)
            assert r.returncode == 0, f"{command[1]}\n{r.stdout}\n{r.stderr}"
    assert any(re.match(r"// \S+\.cpp: build and run with\n", b) for b in blocks("cpp"))
