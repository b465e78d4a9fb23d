"""Every public class of the package prints readably and every public function, method and
property says what it computes: a walk over rigid and all its submodules that fails listing
every offender by its full name (so a new binding without a docstring or a repr is named)."""
import re
import types

import numpy as np
import pytest

import rigid

# pybind11's callables and properties; other attributes (constants, slot wrappers) are not API docs
CALLABLE_TYPES = ("builtin_function_or_method", "instancemethod", "staticmethod")


def walk():
    """(full name, object, owning class or None) for every public member of rigid and its submodules."""
    seen, out = set(), []

    def visit_module(module, prefix):
        for name, value in sorted(vars(module).items()):
            if name.startswith("_"):
                continue
            full = f"{prefix}.{name}"
            if isinstance(value, types.ModuleType):
                if value.__name__.startswith("rigid.") and id(value) not in seen:
                    seen.add(id(value))
                    visit_module(value, full)
            elif isinstance(value, type):
                if id(value) in seen:
                    continue
                seen.add(id(value))
                out.append((full, value, None))
                for attr, member in sorted(vars(value).items()):
                    if attr.startswith("_") and attr != "__init__":
                        continue
                    out.append((f"{full}.{attr}", member, value))
            elif type(value).__name__ in CALLABLE_TYPES:
                out.append((full, value, None))

    visit_module(rigid, "rigid")
    return out


def described(name, doc):
    """True when each signature in a pybind11 docstring is followed by a description."""
    if not doc or not doc.strip():
        return False
    short = name.rsplit(".", 1)[-1]
    signature = re.compile(rf"^(\d+\. )?{re.escape(short)}\(.*\)( -> .*)?$")
    segments, current = [], None
    for line in doc.splitlines():
        if signature.match(line.strip()):
            current = [line, ""]
            segments.append(current)
        elif line.strip() == "Overloaded function.":
            segments.clear()  # the (*args, **kwargs) header; the numbered overloads follow
            current = None
        elif line.strip():
            if current is None:
                current = ["", ""]
                segments.append(current)
            current[1] += line
    return bool(segments) and all(text.strip() for _, text in segments)


def test_the_walk_sees_the_whole_package():
    names = {n for n, _, _ in walk()}
    # one of each kind the walk must reach: a class, a method, a static method, a property,
    # a function of the package and of a submodule, a class of a submodule
    for expected in ("rigid.SO3", "rigid.SO3.log", "rigid.SO3.exp", "rigid.MassProperties.mass",
                     "rigid.combine", "rigid.mass.solid_box_with_mass", "rigid.body.HeavyTop",
                     "rigid.lagrange.System.simulate", "rigid.MassProperties.__init__"):
        assert expected in names, expected


def test_described_needs_text_after_every_signature():
    assert not described("f", "f(x: float) -> float\n")
    assert described("f", "f(x: float) -> float\n\nThe square of x (m²).\n")
    overloaded = ("f(*args, **kwargs)\nOverloaded function.\n\n1. f(x: float) -> float\n\nDoc one.\n\n"
                  "2. f(x: int) -> int\n")
    assert not described("f", overloaded)
    assert described("f", overloaded + "\nDoc two.\n")


def test_every_public_function_method_and_property_has_a_docstring():
    missing = []
    for name, obj, owner in walk():
        if isinstance(obj, type):
            if not (obj.__doc__ or "").strip():
                missing.append(f"{name} (class)")
        elif type(obj).__name__ == "pybind11_static_property":
            continue  # a class constant (SO2.dimension); pybind11 2.10 drops the docstrings of these
        elif isinstance(obj, property):
            if not (obj.__doc__ or "").strip():
                missing.append(f"{name} (property)")
        elif type(obj).__name__ in CALLABLE_TYPES:
            doc = obj.__func__.__doc__ if isinstance(obj, staticmethod) else obj.__doc__
            if not described(name, doc):
                missing.append(name)
    assert not missing, (f"{len(missing)} public names have no docstring (say what it computes, units, "
                         "frames):\n  " + "\n  ".join(missing))


def test_every_public_class_defines_its_repr():
    plain = [name for name, obj, owner in walk()
             if isinstance(obj, type) and not issubclass(obj, BaseException) and "__repr__" not in vars(obj)]
    assert not plain, ("classes that print as <... object at 0x...> (bind __repr__ showing the main "
                       "values):\n  " + "\n  ".join(plain))
