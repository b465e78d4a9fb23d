"""Builds the Python package `rigid` with CMake, for `python3 -m pip install .` from a clone.

Offline with Debian's tools (python3-pip, python3-setuptools, python3-wheel and the build
dependencies of scripts/install-deps.sh), e.g. into a venv that sees Debian's numpy:
    python3 -m venv --system-site-packages venv
    venv/bin/python -m pip install --no-index --no-build-isolation .
CMake configures a Release build of the Python module alone for the Python running pip, under
build/pip/; CMAKE_ARGS adds options (e.g. CMAKE_ARGS=-DRIGID_REPORT=ON to embed the report
page, which needs node 20). RIGID_CMAKE_BUILD_DIR names an already configured build tree to
use instead (e.g. build/ci): only its module target is brought up to date.
"""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    found = re.search(r"project\(rigid VERSION ([0-9.]+)", text)
    if not found:
        raise RuntimeError("setup.py: no `project(rigid VERSION x.y.z)` in CMakeLists.txt")
    return found.group(1)


class CMakeExtension(Extension):
    def __init__(self):
        super().__init__("rigid._rigid", sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("RIGID_CMAKE_BUILD_DIR")
        build_dir = pathlib.Path(given).resolve() if given else ROOT / "build" / "pip"
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        if not given:
            configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                         f"-DPython3_EXECUTABLE={sys.executable}", "-DRIGID_BUILD_PYTHON=ON",
                         "-DRIGID_BUILD_TESTS=OFF", "-DRIGID_BUILD_APPS=OFF"]
            if shutil.which("ninja"):
                configure += ["-G", "Ninja"]
            configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
            subprocess.run(configure, check=True)
        elif not (build_dir / "CMakeCache.txt").is_file():
            raise RuntimeError(f"RIGID_CMAKE_BUILD_DIR={given} is not a configured CMake build tree")
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "rigid_python", "-j", jobs], check=True)
        # the package as `cmake --install` lays it out, copied to where setuptools collects it
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve().parent
        with tempfile.TemporaryDirectory() as staging:
            subprocess.run(["cmake", "--install", str(build_dir), "--component", "python",
                            "--prefix", staging], check=True)
            packages = list(pathlib.Path(staging).rglob("rigid/__init__.py"))
            if len(packages) != 1:
                raise RuntimeError(f"cmake --install put {len(packages)} rigid packages under {staging}")
            if target.exists():
                shutil.rmtree(target)
            shutil.copytree(packages[0].parent, target)


setup(
    name="rigid",
    version=project_version(),
    description="Rigid-body mechanics from isometries and inertia tensors to Euler's equations",
    python_requires=">=3.9",
    install_requires=["numpy"],
    ext_modules=[CMakeExtension()],
    cmdclass={"build_ext": CMakeBuild},
    packages=[],
    zip_safe=False,
)
