"""rigid: rigid-body mechanics from isometries and inertia tensors to Euler's equations.

Classes and functions live in the compiled extension rigid._rigid; this package checks that
the Python importing it can load that extension (the version it was built for, numpy), says
what to do when it cannot, and re-exports everything: rigid.SO3, rigid.MassProperties,
rigid.Error, and the submodules rigid.mass, rigid.mesh, rigid.body, rigid.lagrange, rigid.so3,
rigid.spring, rigid.integrate
(also importable as `import rigid.mass`).
"""
import os as _os
import sys as _sys

try:
    from . import _built_for
except ImportError:  # python/rigid/ in the source tree: CMake writes _built_for.py into the build's copy
    raise ImportError("this is rigid's source directory, which holds no extension: import the built "
                      "package (PYTHONPATH=build/ci/python after `make demo`) or an installed one") from None


def _this_python():
    return f"Python {_sys.version.split()[0]} ({_sys.executable or 'unknown path'})"


def _built_python():
    return f"Python {_built_for.VERSION} ({_built_for.EXECUTABLE})"


def _check_python():
    # the extension's ABI is the minor version: 3.11.2 and 3.11.7 load the same module
    built = tuple(int(x) for x in _built_for.VERSION.split(".")[:2])
    if _sys.version_info[:2] != built or _sys.implementation.name != "cpython":
        raise ImportError(
            f"rigid was built for {_built_python()} and cannot be imported by {_this_python()}: "
            f"run it with {_built_for.EXECUTABLE}, or rebuild rigid for this Python "
            f"(cmake -DPython3_EXECUTABLE={_sys.executable or 'python3'}, or `python3 -m pip install .`)")


def _check_numpy():
    try:
        import numpy  # noqa: F401
    except ImportError:
        if _os.path.realpath(_sys.executable or "") == _os.path.realpath(_built_for.EXECUTABLE):
            remedy = "install it with `apt install python3-numpy` (or `python3 -m pip install numpy` in a venv)"
        else:
            remedy = (f"run rigid with the Python it was built for, {_built_python()}, or install numpy "
                      f"into this one (`apt install python3-numpy` for Debian's python3, "
                      f"`python3 -m pip install numpy` for others)")
        raise ImportError(f"rigid needs numpy, which {_this_python()} cannot import: {remedy}") from None


_check_python()
_check_numpy()
try:
    from . import _rigid
except ImportError as _e:
    raise ImportError(
        f"rigid's extension module could not be loaded by {_this_python()} ({_e}); it was built for "
        f"{_built_python()}: run it with {_built_for.EXECUTABLE}, or rebuild rigid") from _e

from ._rigid import *  # noqa: E402,F401,F403
from ._rigid import __version__, Error  # noqa: E402,F401


def _adopt(module, name):
    # the extension names its classes and submodules after the package (rigid.SO3, rigid.mass);
    # registering the submodules makes `import rigid.mass` work wherever the package lives
    for attr, value in list(vars(module).items()):
        if isinstance(value, type(_sys)) and not attr.startswith("_"):
            sub = f"{name}.{attr}"
            value.__name__ = sub
            _sys.modules[sub] = value
            _adopt(value, sub)


_adopt(_rigid, __name__)
