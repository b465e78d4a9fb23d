"""rigid as a Python package: the build tree's package, `cmake --install` into a prefix, the
messages a Python that cannot load it prints, and `pip install .` offline.

RIGID_PYTHON_DIR names build/<preset>/python; the build tree is its parent directory."""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

import rigid

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "inertia_of_a_robot_link.py"


@pytest.fixture(scope="module")
def python_dir():
    d = os.environ.get("RIGID_PYTHON_DIR")
    assert d, "RIGID_PYTHON_DIR must name the built package's directory (build/<preset>/python)"
    return pathlib.Path(d).resolve()


@pytest.fixture(scope="module")
def build_dir(python_dir):
    b = python_dir.parent
    assert (b / "CMakeCache.txt").is_file(), f"{b} is not the CMake build tree of {python_dir}"
    return b


def clean_env(**extra):
    """The environment without any path to a rigid package, plus `extra`."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "RIGID_PYTHON_DIR")}
    env.update(extra)
    return env


def run_python(args, env, cwd):
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, env=env,
                          cwd=cwd, timeout=300)


def test_the_build_tree_holds_a_package_that_reexports_the_extension(python_dir):
    assert pathlib.Path(rigid.__file__).resolve() == python_dir / "rigid" / "__init__.py"
    assert rigid._rigid.__name__ == "rigid._rigid"
    # everything the extension defines is reachable from the package, submodules included
    public = {n for n in vars(rigid._rigid) if not n.startswith("_")}
    assert public <= set(vars(rigid)), sorted(public - set(vars(rigid)))
    assert {"SO3", "MassProperties", "Error", "Scene", "mass", "body", "lagrange", "mesh"} <= public
    for name in ("SO3", "MassProperties", "Scene", "Error"):
        assert getattr(rigid, name) is getattr(rigid._rigid, name)
    assert rigid.SO3.__module__ == "rigid"
    assert rigid.mass.__name__ == "rigid.mass"


def test_submodules_import_by_name():
    import rigid.mass
    from rigid.body import HeavyTop

    assert rigid.mass is sys.modules["rigid.mass"]
    assert HeavyTop is rigid.body.HeavyTop


def test_built_for_names_this_python():
    from rigid import _built_for

    assert _built_for.VERSION.split(".")[:2] == [str(v) for v in sys.version_info[:2]]
    assert os.path.isabs(_built_for.EXECUTABLE)
    assert pathlib.Path(rigid._rigid.__file__).name == "_rigid" + _built_for.EXT_SUFFIX


def test_cmake_install_puts_the_package_where_python_finds_it_and_an_example_runs(build_dir, python_dir,
                                                                                  tmp_path):
    prefix = tmp_path / "prefix"
    proc = subprocess.run(["cmake", "--install", str(build_dir), "--prefix", str(prefix), "--component",
                           "python"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    installed = sorted(prefix.rglob("rigid/__init__.py"))
    assert len(installed) == 1, installed
    site_dir = installed[0].parent.parent
    # the directory is one the installing Python itself searches under that prefix (Debian:
    # lib/python3/dist-packages), by site's own rule, not by the rule CMake used
    probe = run_python(["-c", "import site, sys; print('\\n'.join(site.getsitepackages([sys.argv[1]])))",
                        str(prefix)], clean_env(), tmp_path)
    assert str(site_dir) in probe.stdout.split("\n"), (site_dir, probe.stdout)

    env = clean_env(PYTHONPATH=str(site_dir))
    where = run_python(["-c", "import rigid; print(rigid.__file__); print(rigid.SO3.exp([0, 0, 1.0]))"], env,
                       tmp_path)
    assert where.returncode == 0, where.stderr
    assert where.stdout.splitlines()[0] == str(installed[0])
    # the example prints the same from the installed package as from the build tree
    from_install = run_python([str(EXAMPLE)], env, tmp_path)
    from_build = run_python([str(EXAMPLE)], clean_env(PYTHONPATH=str(python_dir)), tmp_path)
    assert from_install.returncode == 0, from_install.stderr
    assert from_build.returncode == 0, from_build.stderr
    assert "principal moments" in from_install.stdout
    assert from_install.stdout == from_build.stdout


NO_NUMPY = [
    # numpy made unimportable inside a Python that has it
    ["-c", "import sys; sys.modules['numpy'] = None; import rigid"],
    # a Python started without its site directories (where Debian keeps numpy)
    ["-S", "-c", "import rigid"],
]


@pytest.mark.parametrize("args", NO_NUMPY, ids=["numpy-blocked", "no-site"])
def test_a_python_without_numpy_is_told_so_in_one_sentence(python_dir, tmp_path, args):
    env = clean_env(PYTHONPATH=str(python_dir))
    if args[0] == "-S" and run_python(["-S", "-c", "import numpy"], env, tmp_path).returncode == 0:
        pytest.skip("this Python finds numpy without its site directories")
    proc = run_python(args, env, tmp_path)
    assert proc.returncode != 0
    last = proc.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: rigid needs numpy, which Python "), proc.stderr
    assert "apt install python3-numpy" in last
    assert ". " not in last, f"one sentence: {last}"
    # no chained traceback from inside the extension
    assert "initialization failed" not in proc.stderr
    assert "During handling" not in proc.stderr and "direct cause" not in proc.stderr


def fake_package(python_dir, tmp_path, version, executable):
    """The built package with its _built_for.py claiming another Python."""
    pkg = tmp_path / "site" / "rigid"
    pkg.mkdir(parents=True)
    for f in (python_dir / "rigid").iterdir():
        if f.name.startswith("_rigid"):
            (pkg / f.name).symlink_to(f)
        elif f.suffix == ".py" and f.name != "_built_for.py":
            shutil.copy(f, pkg / f.name)
    (pkg / "_built_for.py").write_text(
        f'VERSION = "{version}"\nEXECUTABLE = "{executable}"\nEXT_SUFFIX = ".cpython-399-x86_64-linux-gnu.so"\n')
    return pkg.parent


def test_another_python_is_told_which_python_the_package_was_built_for(python_dir, tmp_path):
    site_dir = fake_package(python_dir, tmp_path, "3.99.1", "/opt/python3.99/bin/python3")
    proc = run_python(["-c", "import rigid"], clean_env(PYTHONPATH=str(site_dir)), tmp_path)
    assert proc.returncode != 0
    last = proc.stderr.strip().splitlines()[-1]
    this = f"Python {sys.version.split()[0]} ({sys.executable})"
    assert last.startswith("ImportError: rigid was built for Python 3.99.1 (/opt/python3.99/bin/python3) "
                           f"and cannot be imported by {this}: run it with /opt/python3.99/bin/python3"), last
    assert f"-DPython3_EXECUTABLE={sys.executable}" in last
    assert "initialization failed" not in proc.stderr


def test_the_same_minor_version_loads(python_dir, tmp_path):
    # the extension's ABI is the minor version: another patch release loads it
    major, minor = sys.version_info[:2]
    site_dir = fake_package(python_dir, tmp_path, f"{major}.{minor}.99", "/opt/other/python3")
    proc = run_python(["-c", "import rigid; print(rigid.SO3.identity())"], clean_env(PYTHONPATH=str(site_dir)),
                      tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("SO3(")


def test_pip_installs_offline_into_a_venv(build_dir, tmp_path):
    """`pip install --no-index --no-build-isolation .` with Debian's pip, setuptools and wheel, into
    a venv that sees Debian's numpy. The project's setup.py, pyproject.toml and CMakeLists.txt are
    copied to a scratch directory (nothing is written into the source tree) and setup.py reuses
    this build tree (RIGID_CMAKE_BUILD_DIR), so no compiler runs: about 4 s. A build from
    scratch (no RIGID_CMAKE_BUILD_DIR) is the same code path plus a CMake configure and the
    compilation (773 s on 2 busy cores; docs/python.md), too long for every `make test`."""
    for module in ("pip", "setuptools", "wheel", "venv"):
        probe = subprocess.run([sys.executable, "-c", f"import {module}"], capture_output=True, text=True)
        assert probe.returncode == 0, f"{module} is missing: scripts/install-deps.sh installs python3-{module}"
    project = tmp_path / "clone"
    project.mkdir()
    for name in ("setup.py", "pyproject.toml", "CMakeLists.txt"):
        shutil.copy(ROOT / name, project / name)
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", str(venv)],
                   check=True, timeout=120)
    py = venv / "bin" / "python"
    env = clean_env(RIGID_CMAKE_BUILD_DIR=str(build_dir), PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    proc = subprocess.run([str(py), "-m", "pip", "install", "--no-index", "--no-build-isolation", "."],
                          cwd=project, capture_output=True, text=True, env=env, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    check = subprocess.run([str(py), "-c", "import rigid, sys; print(rigid.__file__); print(rigid.__version__)"],
                           capture_output=True, text=True, cwd=tmp_path, env=clean_env(), timeout=120)
    assert check.returncode == 0, check.stderr
    where, version = check.stdout.splitlines()
    assert pathlib.Path(where).is_relative_to(venv), where
    assert version == rigid.__version__
    shown = subprocess.run([str(py), "-m", "pip", "show", "rigid"], capture_output=True, text=True, env=env)
    assert f"Version: {rigid.__version__}" in shown.stdout, shown.stdout


def test_another_python_of_the_same_version_without_numpy_is_pointed_at_the_build_python(python_dir, tmp_path):
    major, minor = sys.version_info[:2]
    site_dir = fake_package(python_dir, tmp_path, f"{major}.{minor}.99", "/opt/other/python3")
    proc = run_python(["-c", "import sys; sys.modules['numpy'] = None; import rigid"],
                      clean_env(PYTHONPATH=str(site_dir)), tmp_path)
    assert proc.returncode != 0
    last = proc.stderr.strip().splitlines()[-1]
    assert last.startswith(f"ImportError: rigid needs numpy, which Python {sys.version.split()[0]} "
                           f"({sys.executable}) cannot import: run rigid with the Python it was built for, "
                           f"Python {major}.{minor}.99 (/opt/other/python3), or install numpy"), last
    assert "apt install python3-numpy" in last


def test_the_python3_first_on_path_gets_the_package_or_a_clear_message(python_dir, tmp_path):
    """The case users meet: a `python3` earlier on PATH (pyenv, conda) than the build's Python.
    It imports rigid, or is told what to do; never a bare `initialization failed`."""
    other = shutil.which("python3")
    if not other:
        pytest.skip("no python3 on PATH")
    probe = subprocess.run([other, "-c", "import sys; print(sys.executable)"], capture_output=True, text=True,
                           env=clean_env(), timeout=60)
    if probe.returncode != 0 or os.path.realpath(probe.stdout.strip()) == os.path.realpath(sys.executable):
        pytest.skip("the python3 on PATH is the build's own Python")
    proc = subprocess.run([other, "-c", "import rigid; print(rigid.SO3.identity())"], capture_output=True,
                          text=True, env=clean_env(PYTHONPATH=str(python_dir)), cwd=tmp_path, timeout=60)
    if proc.returncode == 0:
        assert proc.stdout.startswith("SO3(")
    else:
        last = proc.stderr.strip().splitlines()[-1]
        assert last.startswith(("ImportError: rigid needs numpy", "ImportError: rigid was built for")), last
        assert "initialization failed" not in proc.stderr
