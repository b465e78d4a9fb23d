"""Installed like a tool: `cmake --install` of the build that made RIGID_EXE into a scratch prefix
puts the example scenes in <prefix>/share/rigid/examples; the installed rigid's demo finds them
there, and an example runs from there. A rigid with no examples next to it refuses the demo,
naming where it looked."""
import json
import pathlib
import re
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def prefix(rigid_exe, tmp_path_factory):
    build = pathlib.Path(rigid_exe).resolve().parent.parent
    assert (build / "cmake_install.cmake").is_file(), f"{build} is not the build directory of {rigid_exe}"
    cmake = shutil.which("cmake")
    assert cmake, "cmake is needed to install the build"
    prefix = tmp_path_factory.mktemp("install") / "prefix"
    p = subprocess.run([cmake, "--install", str(build), "--prefix", str(prefix)], capture_output=True,
                       text=True, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    return prefix


def test_the_examples_are_installed_under_share(prefix):
    examples = prefix / "share" / "rigid" / "examples"
    shipped = sorted(p.relative_to(ROOT / "examples") for p in (ROOT / "examples").rglob("*") if p.is_file()
                     and "__pycache__" not in p.parts)
    assert shipped, "the source tree has no examples"
    for rel in shipped:
        assert (examples / rel).read_bytes() == (ROOT / "examples" / rel).read_bytes(), rel


def test_the_installed_demo_finds_the_installed_examples_and_an_example_runs(prefix, tmp_path):
    rigid = prefix / "bin" / "rigid"
    examples = prefix / "share" / "rigid" / "examples"
    p = subprocess.run([str(rigid), "demo", "--no-report"], capture_output=True, text=True, cwd=tmp_path,
                       timeout=300)
    assert p.returncode == 0, p.stderr
    assert f"Example scenes: {examples}\n" in p.stdout
    # the command the tour suggests runs as printed
    suggested = re.search(r"Try: rigid run (\S+) -o out/atwood", p.stdout).group(1)
    assert pathlib.Path(suggested) == examples / "atwood.toml"
    p = subprocess.run([str(rigid), "check", str(examples / "tennis_racket.toml")], capture_output=True, text=True,
                       timeout=300)
    assert p.returncode == 0 and "is a valid scene" in p.stdout, p.stderr
    out = tmp_path / "racket"
    p = subprocess.run([str(rigid), "run", str(examples / "tennis_racket.toml"), "-o", str(out), "-q"],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    metrics = json.loads((out / "summary.json").read_text())["metrics"]
    first_flip = metrics["first_flip"]["value"]
    # the example's own check: first flip at 10.917 s from Jacobi elliptic functions, rel 5e-5
    assert first_flip == pytest.approx(10.917, rel=5e-5)


def test_a_rigid_without_examples_refuses_the_demo_naming_both_places(prefix, tmp_path):
    bare = tmp_path / "bare" / "bin"
    bare.mkdir(parents=True)
    shutil.copy2(prefix / "bin" / "rigid", bare / "rigid")
    work = tmp_path / "work"
    work.mkdir()
    p = subprocess.run([str(bare / "rigid"), "demo"], capture_output=True, text=True, cwd=work, timeout=300)
    assert p.returncode == 1, p.stdout
    assert "no example scenes for rigid demo" in p.stderr
    assert f"'{tmp_path / 'bare' / 'share' / 'rigid' / 'examples'}'" in p.stderr
    assert f"'{ROOT / 'examples'}'" in p.stderr  # the source tree: only for the rigid of its build
    assert "cmake --install" in p.stderr
    assert not any(work.iterdir())  # refused before anything was written
