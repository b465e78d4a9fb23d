#!/usr/bin/env python3
"""Writes the type stubs of the Python package rigid (python/rigid/*.pyi) from the built module.

pybind11 starts every function's docstring with its signature, `name(arg: type = default, ...)
-> type`, in the types of the binding (`numpy.ndarray[numpy.float64[3, 1]]`, `List[str]`,
`rigid.MassProperties`). This script imports the built package, walks it (the package, its
submodules, their classes: methods, static methods, properties, class attributes), turns each
signature into a stub declaration in Python's typing (numpy.typing.NDArray, list[...], X | None,
Any for what no type names) and keeps the docstring, so that IDEs and mypy see the parameters
instead of `(*args, **kwargs)`. One stub per module: rigid/__init__.pyi for `rigid`,
rigid/mass.pyi for `rigid.mass`, and so on; each class goes where its __module__ says.

    PYTHONPATH=build/ci/python /usr/bin/python3 scripts/make_stubs.py            # writes python/rigid/
    PYTHONPATH=build/ci/python /usr/bin/python3 scripts/make_stubs.py --check    # exit 1 if stale

--check compares instead of writing and names the stubs that differ from the module (the test
python/tests/test_stubs.py runs it, so a binding changed without regenerating the stubs fails).
Nothing is fetched; only the standard library and the built module are used.
"""
import argparse
import ast
import importlib
import inspect
import os
import re
import sys
import types

HEADER = ("# Type stubs of {module}, generated from the built module's signatures by "
          "scripts/make_stubs.py:\n# do not edit; rerun the script after changing a binding.\n")

# pybind11's names for Python types, and what a stub writes for them
SIMPLE = {
    "float": "float", "int": "int", "str": "str", "bool": "bool", "None": "None",
    "object": "object", "dict": "dict[str, Any]", "tuple": "tuple[Any, ...]",
    "list": "list[Any]", "function": "Callable[..., Any]", "os.PathLike": "os.PathLike[str]",
    "numpy.ndarray": "NDArray[Any]", "Any": "Any", "bytes": "bytes",
}
GENERIC = {"List": "list", "Tuple": "tuple", "Dict": "dict", "Set": "set", "Sequence": "Sequence",
           "Iterator": "Iterator", "Iterable": "Iterable"}


class Unknown(Exception):
    """A type text this script cannot translate: the stub says Any."""


def split_top(text, sep=","):
    """Splits at `sep` outside brackets and parentheses."""
    parts, depth, start = [], 0, 0
    for k, c in enumerate(text):
        if c in "[(":
            depth += 1
        elif c in "])":
            depth -= 1
        elif c == sep and depth == 0:
            parts.append(text[start:k].strip())
            start = k + 1
    tail = text[start:].strip()
    if tail or parts:
        parts.append(tail)
    return parts


class Namer:
    """Writes a type for use inside the stub of `module`, collecting the imports it needs."""

    def __init__(self, module, classes):
        self.module = module
        self.classes = classes  # qualified name -> defining module, of every class found
        self.imports = set()

    def cls(self, qualified):
        owner = self.classes.get(qualified)
        if owner is None:
            raise Unknown(qualified)
        name = qualified[len(owner) + 1:]
        if owner == self.module:
            return name
        if self.module == "rigid":  # the package stub imports its submodules by name
            return f"{owner[len('rigid.'):]}.{name}"
        self.imports.add(f"import {owner}")
        return qualified

    def type(self, text):
        text = text.strip()
        if text in SIMPLE:
            return SIMPLE[text]
        if text.startswith("numpy.ndarray["):
            return "NDArray[numpy.float64]" if "numpy.float64" in text else "NDArray[Any]"
        m = re.fullmatch(r"(\w+)\[(.*)\]", text)
        if m:
            head, inner = m.group(1), m.group(2)
            if head == "Optional":
                return f"{self.type(inner)} | None"
            if head == "Union":
                return " | ".join(self.type(a) for a in split_top(inner))
            if head == "Callable":
                return "Callable[..., Any]"
            if head in GENERIC:
                args = [self.type(a) for a in split_top(inner)]
                return f"{GENERIC[head]}[{', '.join(args)}]"
            raise Unknown(text)
        if text.startswith("rigid."):
            return self.cls(text)
        raise Unknown(text)

    def safe(self, text, fallback="Any"):
        try:
            return self.type(text)
        except Unknown:
            return fallback


def signature_of(obj):
    """(parameters text, return text, rest of the docstring) of a pybind11 function, or None."""
    doc = getattr(obj, "__doc__", None) or ""
    first, _, rest = doc.partition("\n")
    m = re.fullmatch(r"(\w*)\((.*)\)(?: -> (.*))?", first.strip())
    if not m:
        return None
    return m.group(2), (m.group(3) or "None"), rest.strip()


def parameters(text, namer, method):
    """The stub's parameter list of pybind11's `text`; `method`: the first one is self."""
    out = []
    for k, p in enumerate(split_top(text)):
        if p in ("*", "/"):
            out.append(p)
            continue
        if p.startswith("*"):
            stars = "**" if p.startswith("**") else "*"
            out.append(f"{stars}{p.lstrip('*').split(':')[0].strip()}: Any")
            continue
        name, _, rest = p.partition(":")
        annotation, eq, _default = rest.partition("=")
        name = name.strip()
        if method and k == 0:
            out.append("self")
            continue
        written = f"{name}: {namer.safe(annotation, 'Any') if annotation.strip() else 'Any'}"
        out.append(written + (" = ..." if eq else ""))
    return out


def docstring(text, indent):
    if not text:
        return ""
    text = text.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    lines = text.splitlines()
    body = "\n".join((indent + line) if line.strip() else "" for line in lines)
    return f'{indent}"""{body.lstrip()}\n{indent}"""\n' if len(lines) > 1 else \
        f'{indent}"""{text}"""\n'


def function_stub(name, obj, namer, indent, kind):
    """`kind`: "function", "method" or "staticmethod"."""
    sig = signature_of(obj)
    head = ""
    if kind == "staticmethod":
        head = f"{indent}@staticmethod\n"
    if sig is None:
        params = "self, *args: Any, **kwargs: Any" if kind == "method" else "*args: Any, **kwargs: Any"
        return f"{head}{indent}def {name}({params}) -> Any: ...\n"
    params, ret, rest = sig
    plist = parameters(params, namer, kind == "method")
    returns = namer.safe(ret) if ret != "object" else "Any"
    if name == "__init__":
        returns = "None"
    doc = docstring(rest, indent + "    ")
    body = f"\n{doc}" if doc else " ...\n"
    return f"{head}{indent}def {name}({', '.join(plist)}) -> {returns}:{body}"


def property_stub(name, prop, namer, indent):
    sig = signature_of(prop.fget) if prop.fget else None
    returns = namer.safe(sig[1]) if sig and sig[1] != "object" else "Any"
    doc = docstring((prop.__doc__ or "").strip() if (prop.__doc__ or "") != (prop.fget.__doc__ or "")
                    else "", indent + "    ")
    out = f"{indent}@property\n{indent}def {name}(self) -> {returns}:" + (f"\n{doc}" if doc else " ...\n")
    if prop.fset is not None:
        out += f"{indent}@{name}.setter\n{indent}def {name}(self, value: {returns}) -> None: ...\n"
    return out


def value_type(value, namer):
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, (int, float, str)):
        return type(value).__name__
    if isinstance(value, tuple) and value and all(isinstance(v, str) for v in value):
        return "tuple[str, ...]"
    return "Any"


def class_stub(cls, namer):
    bases = [b for b in cls.__bases__ if b.__module__ != "pybind11_builtins" and b is not object]
    base_text = ", ".join(namer.safe(f"{b.__module__}.{b.__qualname__}", "object")
                          if b.__module__.startswith("rigid") else b.__qualname__ for b in bases)
    bases_text = ", ".join(([base_text] if base_text else []) + ["metaclass=_Pybind11Type"])
    out = f"class {cls.__name__}({bases_text}):\n"
    doc = docstring((cls.__doc__ or "").strip(), "    ")
    out += doc
    members = []
    if type(vars(cls).get("__init__")).__name__ != "instancemethod":
        # no constructor: instances come from the module's functions (calling the class raises
        # TypeError, as pybind11's object.__init__ takes anything and refuses it)
        members.append("    def __init__(self, *args: Any, **kwargs: Any) -> None: ...\n")
    for name, value in vars(cls).items():
        if name.startswith("_") and not (name.startswith("__") and name.endswith("__")):
            continue
        if name in ("__doc__", "__module__", "__dict__", "__weakref__", "__hash__"):
            continue
        if type(value).__name__ == "pybind11_static_property":
            members.append(f"    {name}: ClassVar[{value_type(getattr(cls, name), namer)}]\n")
        elif isinstance(value, property):
            members.append(property_stub(name, value, namer, "    "))
        elif isinstance(value, staticmethod):
            members.append(function_stub(name, value.__func__, namer, "    ", "staticmethod"))
        elif isinstance(value, types.BuiltinFunctionType) or type(value).__name__ == "instancemethod":
            func = getattr(value, "__func__", value)
            if signature_of(func) is None:
                continue  # a slot wrapper or descriptor of Python's own
            members.append(function_stub(name, func, namer, "    ", "method"))
    if not members and not doc:
        members.append("    ...\n")
    return out + "".join(members)


def walk(package):
    """{module name: module} of the package and its submodules."""
    found = {package.__name__: package}
    for value in vars(package).values():
        if isinstance(value, types.ModuleType) and value.__name__.startswith(package.__name__ + "."):
            if not value.__name__.split(".")[-1].startswith("_"):
                found.update(walk(value))
    return found


def public(module):
    return [(n, v) for n, v in vars(module).items() if not n.startswith("_")]


def module_stub(name, module, modules, classes):
    namer = Namer(name, classes)
    parts = []
    submodules = []
    for attr, value in public(module):
        if isinstance(value, types.ModuleType):
            if value.__name__ in modules:
                submodules.append(attr)
            continue
        if isinstance(value, type):
            if issubclass(value, BaseException):
                base = value.__bases__[0].__name__
                parts.append(f"class {attr}({base}):\n{docstring((value.__doc__ or '').strip(), '    ') or '    ...'}\n")
            elif classes.get(f"{value.__module__}.{value.__qualname__}") == name:
                parts.append(class_stub(value, namer))
            continue
        if callable(value):
            parts.append(function_stub(attr, value, namer, "", "function"))
        else:
            parts.append(f"{attr}: {value_type(value, namer)}\n")
    if name == "rigid":
        parts.insert(0, "__version__: str\n")
    out = HEADER.format(module=name)
    out += "import os\nfrom typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence\n\n"
    out += "import numpy\nfrom numpy.typing import NDArray\n"
    imports = sorted(namer.imports - {f"import {name}"})
    if imports:
        out += "\n" + "\n".join(imports) + "\n"
    if submodules:
        out += "\n" + "".join(f"from . import {s} as {s}\n" for s in sorted(submodules))
    if any(isinstance(v, type) and not issubclass(v, BaseException) for _, v in public(module)):
        parts.insert(0, 'class _Pybind11Type(type):\n    """The metaclass of the classes (pybind11_builtins.pybind11_type)."""\n')
    out += "\n\n" + "\n\n".join(p.rstrip("\n") + "\n" for p in parts)
    ast.parse(out)  # a stub this script wrote must at least be Python
    return out


def stubs(package_name="rigid"):
    package = importlib.import_module(package_name)
    modules = walk(package)
    classes = {}
    for name, module in modules.items():
        for attr, value in public(module):
            if isinstance(value, type) and value.__module__ == name:
                classes[f"{name}.{value.__qualname__}"] = name
    out = {}
    for name, module in modules.items():
        file = "__init__.pyi" if name == package_name else name.split(".", 1)[1].replace(".", "/") + ".pyi"
        out[file] = module_stub(name, module, modules, classes)
    return out


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.normpath(os.path.join(here, "..", "python", "rigid"))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=default_out,
                        help="the directory of the stubs (default: python/rigid)")
    parser.add_argument("--check", action="store_true",
                        help="compare with the stubs there instead of writing; exit 1 if any differs")
    args = parser.parse_args()
    generated = stubs()
    stale = []
    for file, text in sorted(generated.items()):
        path = os.path.join(args.out, file)
        old = open(path, encoding="utf-8").read() if os.path.exists(path) else None
        if old == text:
            continue
        stale.append(file)
        if not args.check:
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
    if not args.check:
        marker = os.path.join(args.out, "py.typed")
        if not os.path.exists(marker):
            open(marker, "w").close()
        print(f"make_stubs: {len(stale)} of {len(generated)} stubs written to {args.out}")
        return 0
    if stale:
        print(f"make_stubs: stubs out of date with the module: {', '.join(stale)}; regenerate them "
              f"with `PYTHONPATH=<build>/python python3 scripts/make_stubs.py`", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
