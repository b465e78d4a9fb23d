"""Every public class of the package prints readably and every public function, method and
property says what it computes: a walk over rigid and all its submodules that fails listing
every offender by its full name (so a new binding without a docstring or a repr is named)."""
import pathlib
import re
import types

import numpy as np

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"

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


def unit_cube_without_bottom():
    v = np.array([[(i & 1), (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], float)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    f = [t for q in quads[1:] for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
    return rigid.mesh.TriangleMesh(v, np.array(f))


def samples():
    """(instance, substrings its repr must hold): values chosen so the expected text is known
    without the code under test (cos 45° = 0.7071..., a 2 kg body, a 1 m box...)."""
    r = np.sqrt(0.5)
    mp = rigid.MassProperties(2.0, np.array([0.0, 0.0, 0.5]), np.diag([1.0, 2.0, 2.5]))
    mesh = unit_cube_without_bottom()
    report = rigid.mesh.repair(mesh)
    fill = rigid.mesh.fill_holes(mesh)
    pendulum = rigid.lagrange.System(coordinates=[("theta", 0.1, 0.0)], parameters={"g": 9.81, "L": 1.0},
                                     lagrangian="0.5*L**2*theta_dot**2 + g*L*cos(theta)")
    out = [
        (rigid.SO2.from_angle(np.pi / 2), ["SO2(", "1.5707963"]),
        (rigid.SE2(rigid.SO2.from_angle(0.0), np.array([3.0, 4.0])), ["SE2(", "3", "4"]),
        (rigid.SO3.exp(np.array([0.0, 0.0, np.pi / 2])), ["SO3(", "0.7071067"]),
        (rigid.SE3(rigid.SO3.identity(), np.array([1.0, 2.0, 3.0])), ["SE3(", "1", "2", "3"]),
        (rigid.SOn.identity(4), ["SOn(", "n=4"]),
        (rigid.SEn.identity(4), ["SEn(", "n=4"]),
        (rigid.check_orthogonal(np.diag([1.0, 1.0, -1.0])), ["OrthogonalityReport(", "determinant=-1",
                                                            "orthogonal=True", "rotation=False"]),
        (mp, ["2 kg", "0.5"]),
        (rigid.MassProperties2(3.0, np.array([0.0, 1.0]), 0.25), ["3 kg", "0.25"]),
        (rigid.SecondMoments.from_mass_properties(mp), ["SecondMoments(", "n=3", "mass=2 kg"]),
        (rigid.mass.integrate_density_over_box(lambda p: 1.0, 1.0, 1.0, 1.0),
         ["DensityIntegration(", "MassProperties{mass: ", "converged=True"]),
        (unit_cube_without_bottom(), ["TriangleMesh(", "8 vertices", "10 triangles"]),
        (report, ["RepairReport(", "closed=False", "boundary_edges=4"]),
        (report.components[0], ["ComponentReport(", "triangles=10", "boundary_edges=4"]),
        (fill, ["HoleFillReport(", "area=1 m²"]),
        (fill.holes[0], ["FilledHole(", "boundary_edges=4", "area=1 m²"]),
        (rigid.body.FreeBodyExact(np.array([1.0, 2.0, 3.0]), np.array([0.0, 0.0, 1.0])),
         ["FreeBodyExact(", "energy=1.5 J", "angular_momentum_norm=3"]),
        (rigid.body.FreeBodyMotion(np.array([1.0, 2.0, 3.0]), np.array([1.0, 0, 0, 0]), np.array([0, 0, 1.0])),
         ["FreeBodyMotion(", "angular_momentum_world"]),
        (rigid.body.HeavyTop(mp, np.zeros(3)), ["HeavyTop(", "mass=2 kg", "0.5"]),
        (rigid.body.RigidBody(mp), ["RigidBody(", "mass=2 kg", "loads=0"]),
        (pendulum, ["System(", "theta"]),
        (pendulum.equations(), ["Equations("]),
        (pendulum.equations().lagrangian, ["Printed(", "cos(theta)"]),
        # omega = sqrt(g / L) = 3.1320919527... rad/s
        (pendulum.modes(), ["NormalModes", "theta", "3.13209"]),
        (rigid.Scene(str(EXAMPLES / "atwood.toml")), ["Scene(", "atwood.toml", "coordinates"]),
    ]
    out.append((out[-2][0].modes[0], ["Mode", "3.13209", "Hz"]))
    # the open cube: its 4 bottom edges are used by one triangle each
    out.append((rigid.mesh.count_edges(unit_cube_without_bottom()), ["EdgeCounts(", "boundary=4", "non_manifold=0"]))
    # two 1 kg particles 1 m apart, one spring
    out.append((rigid.spring.Network([1.0, 1.0], [[0, 0, 0], [1, 0, 0]], np.zeros((2, 3)), [(0, 1, 10.0, 1.0)]),
                ["Network(", "particles=2", "springs=1", "mass=2 kg"]))
    out.append((rigid.robot.Robot(EXAMPLES / "arm7.urdf"), ["Robot(", "arm7.urdf", "dof=7"]))
    # arm7: 8 links with an inertial (10 parameters each) and 7 joints (3 each): 101
    out.append((rigid.robot.Robot(EXAMPLES / "arm7.urdf").base_parameters(), ["BaseParameters(", "standard=101"]))
    return out


def test_reprs_show_the_main_values():
    wrong = []
    covered = set()
    for obj, parts in samples():
        text = repr(obj)
        covered.add(type(obj).__name__)
        if " object at 0x" in text or not all(p in text for p in parts):
            wrong.append(f"{type(obj).__name__}: {text!r} lacks {[p for p in parts if p not in text]}")
    assert not wrong, "\n".join(wrong)
    # the samples cover every class the walk finds (a new class needs a sample here)
    classes = {obj.__name__ for name, obj, owner in walk()
               if isinstance(obj, type) and not issubclass(obj, BaseException)}
    assert classes <= covered, sorted(classes - covered)
