"""The type stubs (python/rigid/*.pyi, from scripts/make_stubs.py): current with the module,
shipped next to it with py.typed, accepted by mypy's stubtest, and listing every public name
with the parameters of the module's signatures."""
import ast
import inspect
import os
import pathlib
import re
import subprocess
import sys
import types

import pytest

import rigid

ROOT = pathlib.Path(__file__).resolve().parents[2]
SOURCE_STUBS = ROOT / "python" / "rigid"
PACKAGE = pathlib.Path(rigid.__file__).parent  # the built (or installed) package
MYPY_MISSING = ("mypy is not installed for {python}: the type stubs are checked with "
                "mypy.stubtest; install it with `apt install python3-mypy` "
                "(scripts/install-deps.sh does)")


def require_mypy():
    try:
        import mypy.stubtest  # noqa: F401
    except ImportError:
        pytest.fail(MYPY_MISSING.format(python=sys.executable))


def run(args, cwd):
    env = dict(os.environ, MYPYPATH=str(PACKAGE.parent), PYTHONPATH=str(PACKAGE.parent))
    return subprocess.run([sys.executable, *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=300)


def test_stubs_are_current_with_the_module(tmp_path):
    out = run([str(ROOT / "scripts" / "make_stubs.py"), "--check", "--out", str(SOURCE_STUBS)],
              tmp_path)
    assert out.returncode == 0, out.stderr


def test_stubs_and_py_typed_ship_next_to_the_module():
    stubs = sorted(p.name for p in SOURCE_STUBS.glob("*.pyi"))
    assert "__init__.pyi" in stubs and "mass.pyi" in stubs
    for name in stubs + ["py.typed"]:
        assert (PACKAGE / name).is_file(), f"{name} is not in {PACKAGE}"
        assert (PACKAGE / name).read_bytes() == (SOURCE_STUBS / name).read_bytes(), name


def test_stubtest_finds_no_difference(tmp_path):
    require_mypy()
    # run outside the source tree, so that mypy sees only the package next to the module
    out = run(["-m", "mypy.stubtest", "rigid"], tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "Success" in out.stdout


def test_mypy_checks_code_using_rigid(tmp_path):
    require_mypy()
    (tmp_path / "use.py").write_text(
        "import numpy as np\n"
        "import rigid\n"
        "R = rigid.SO3.exp([0.1, 0.2, 0.3])\n"
        "M: np.ndarray = R.matrix()\n"
        "mp = rigid.mass.cylinder(mass=2.0, radius=0.1, height=0.5)\n"
        "m: float = mp.mass\n"
        "out = rigid.integrate.solve(lambda t, y: -y, [1.0], 1.0)\n"
        "angle: str = R.angle()\n"  # wrong: a float
        "R.log(1)\n")  # wrong: log takes no argument
    out = run(["-m", "mypy", "--no-incremental", "use.py"], tmp_path)
    errors = [line for line in out.stdout.splitlines() if ": error:" in line]
    assert [e.split(":")[1] for e in errors] == ["8", "9"], out.stdout + out.stderr


def stub_functions():
    """{qualified name: [parameter names]} of every def in the stubs."""
    found = {}
    for path in SOURCE_STUBS.glob("*.pyi"):
        module = "rigid" if path.stem == "__init__" else f"rigid.{path.stem}"
        tree = ast.parse(path.read_text(encoding="utf-8"))

        def visit(body, prefix):
            for node in body:
                if isinstance(node, ast.ClassDef):
                    found[f"{prefix}.{node.name}"] = None
                    visit(node.body, f"{prefix}.{node.name}")
                elif isinstance(node, ast.FunctionDef):
                    a = node.args
                    names = [x.arg for x in a.posonlyargs + a.args]
                    names += [a.vararg.arg] if a.vararg else []
                    names += [x.arg for x in a.kwonlyargs] + ([a.kwarg.arg] if a.kwarg else [])
                    found.setdefault(f"{prefix}.{node.name}", names)
                elif isinstance(node, ast.AnnAssign):
                    found[f"{prefix}.{node.target.id}"] = None

        visit(tree.body, module)
    return found


def runtime_signatures():
    """{qualified name: [parameter names] or None} of the public API, from the docstrings."""
    found = {}
    seen = set()

    def names(f):
        first = (getattr(f, "__doc__", None) or "").split("\n", 1)[0]
        m = re.fullmatch(r"\w*\((.*)\)(?: -> .*)?", first.strip())
        if not m:
            return None
        params, depth, cur = [], 0, ""
        for c in m.group(1) + ",":
            depth += c in "[(" and 1 or (-1 if c in "])" else 0)
            if c == "," and depth == 0:
                p = cur.strip().split(":")[0].split("=")[0].strip().lstrip("*")
                if p and p not in ("/",) and p != "":
                    params.append(p)
                cur = ""
            else:
                cur += c
        return params

    def walk(module, prefix):
        for name, value in vars(module).items():
            if name.startswith("_"):
                continue
            q = f"{prefix}.{name}"
            if isinstance(value, types.ModuleType):
                if value.__name__.startswith("rigid.") and id(value) not in seen:
                    seen.add(id(value))
                    walk(value, f"rigid.{value.__name__.split('.', 1)[1]}")
            elif inspect.isclass(value):
                if value.__module__ != prefix or issubclass(value, BaseException):
                    continue
                found[q] = None
                for member, attr in vars(value).items():
                    if member.startswith("_") and member not in ("__init__", "__mul__"):
                        continue
                    f = attr.__func__ if isinstance(attr, staticmethod) else attr
                    if isinstance(attr, property) or type(attr).__name__ == "pybind11_static_property":
                        found[f"{q}.{member}"] = None
                    elif callable(f):
                        found[f"{q}.{member}"] = names(getattr(f, "__func__", f))
            elif callable(value):
                found[q] = names(value)

    walk(rigid, "rigid")
    return found


def test_stubs_list_every_public_name_with_the_modules_parameters():
    stubs, runtime = stub_functions(), runtime_signatures()
    missing = sorted(set(runtime) - set(stubs))
    assert not missing, "public names without a stub: " + ", ".join(missing)
    differ = [f"{name}: stub {stubs[name]}, module {params}" for name, params in runtime.items()
              if params is not None and stubs[name] != params]
    assert not differ, "parameters differ:\n" + "\n".join(differ)
