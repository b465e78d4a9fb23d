"""No pybind11 message reaches a user: every public function, method, static method, property
setter and constructor of rigid (walked with inspect) called with arguments of the wrong type,
too many arguments or an unknown keyword raises TypeError or rigid.Error in rigid's words,
never pybind11's "incompatible function arguments" with its list of overloads."""
import inspect
import types

import pytest

import rigid

PYBIND11_WORDS = ("incompatible function arguments", "incompatible constructor arguments",
                  "The following argument types are supported", "Invoked with",
                  "Unable to cast", "C++ type", "PYBIND11_")


def public_callables():
    """(name, callable) of every public function, class and class member of rigid."""
    seen, out = set(), []

    def walk(module, prefix):
        for name, value in inspect.getmembers(module):
            if name.startswith("_"):
                continue
            if isinstance(value, types.ModuleType):
                if value.__name__.startswith("rigid.") and id(value) not in seen:
                    seen.add(id(value))
                    walk(value, f"{prefix}.{name}")
            elif inspect.isclass(value) and not issubclass(value, BaseException):
                if id(value) in seen:
                    continue
                seen.add(id(value))
                out.append((f"{prefix}.{name}", value))
                for member, attr in vars(value).items():
                    if member.startswith("_") and member not in ("__init__", "__mul__", "__setstate__"):
                        continue
                    qualified = f"{prefix}.{name}.{member}"
                    if isinstance(attr, staticmethod):
                        out.append((qualified, attr.__func__))
                    elif isinstance(attr, property):
                        if attr.fset is not None:
                            out.append((qualified + ".fset", attr.fset))
                        out.append((qualified + ".fget", attr.fget))
                    elif callable(attr) and type(attr).__name__ != "wrapper_descriptor":
                        # an unbound method: the first argument is self, here of a wrong type
                        out.append((qualified, getattr(value, member)))
            elif callable(value):
                out.append((f"{prefix}.{name}", value))

    walk(rigid, "rigid")
    return out


CALLABLES = public_callables()
WRONG_CALLS = {
    "a string": (("x",), {}),
    "too many arguments": (("x",) * 12, {}),
    "an unknown keyword": ((), {"no_such_argument": 1}),
    "None": ((None,), {}),
}


def test_the_walk_finds_the_whole_api():
    names = {n for n, _ in CALLABLES}
    # a few from each corner: the walk must not silently stop at the package's top level
    for expected in ("rigid.SO3.exp", "rigid.MassProperties.shifted", "rigid.mass.cylinder",
                     "rigid.body.HeavyTop.step", "rigid.integrate.solve", "rigid.Scene.run",
                     "rigid.lagrange.System.simulate", "rigid.so3.exp", "rigid.mesh.TriangleMesh"):
        assert expected in names, expected
    assert len(CALLABLES) > 300


@pytest.mark.parametrize("how", sorted(WRONG_CALLS))
def test_wrong_arguments_get_rigids_words(how, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a path argument "x" is never written next to the tests
    args, kwargs = WRONG_CALLS[how]
    leaks, other = [], []
    for name, f in CALLABLES:
        try:
            f(*args, **kwargs)
        except (TypeError, rigid.Error) as e:
            if any(w in str(e) for w in PYBIND11_WORDS):
                leaks.append(f"{name}: {str(e).splitlines()[0]}")
        except Exception as e:  # noqa: BLE001 - any other type is a finding
            other.append(f"{name}: {type(e).__name__}: {e}")
    assert not leaks, f"{len(leaks)} calls with {how} got pybind11's message:\n" + "\n".join(leaks)
    assert not other, f"calls with {how} raised neither TypeError nor rigid.Error:\n" + "\n".join(other)


def test_the_message_names_the_function_what_came_and_what_is_expected():
    with pytest.raises(TypeError) as e:
        rigid.mass.solid_box_with_mass("heavy", 1.0, 2.0, 3.0)
    text = str(e.value)
    assert text.startswith("rigid.mass.solid_box_with_mass(): got (str, float, float, float); expected (")
    assert "-> rigid.MassProperties" in text and "\n" not in text
    with pytest.raises(TypeError, match=r"^rigid.SO3.log\(\): got \(rigid.SO3, int\); expected \(self"):
        rigid.SO3.identity().log(1)
    # a constructor: the instance being built is not among the arguments
    with pytest.raises(TypeError, match=r"^rigid.SE3.__init__\(\): got \(str\); expected "):
        rigid.SE3("x")
    with pytest.raises(TypeError, match=r"got \(mass=str\)"):
        rigid.body.RigidBody(mass="x")
