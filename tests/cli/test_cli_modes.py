"""`rigid modes` and Scene.modes(): the closed forms (the double pendulum's ω² = g(2 ∓ √2)/l,
the physical pendulum's ω0² = m g d / I_p, the sleeping top's threshold ω3² = 4 m g d I1 / I3²),
the same numbers and refusals through the command line, a scene and Python, and the `lagrangian`
key of a scene against the string API."""
import json
import math
import pathlib
import tomllib

import numpy as np
import pytest

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"

# ω² to 1e-10 relative: the acceptance bound (the symmetric eigenproblem of a 2 × 2
# pencil gives a few ulps)
REL = 1e-10


def parameters(path):
    with open(path, "rb") as f:
        doc = tomllib.load(f)
    return {k: float(v) for k, v in doc["parameters"].items() if not isinstance(v, str)}


def modes_json(run, tmp_path, *args):
    out = tmp_path / "modes.json"
    proc = run("modes", *args, "-o", out)
    assert proc.returncode == 0, proc.stderr
    return json.loads(out.read_text()), proc.stdout


def test_double_pendulum_frequencies(run, tmp_path):
    # started with both rods horizontal (the example's initial state): the search finds θ = 0
    path = EXAMPLES / "double_pendulum.toml"
    p = parameters(path)
    assert p["m1"] == p["m2"] and p["l1"] == p["l2"], "the closed form is for equal masses and lengths"
    doc, text = modes_json(run, tmp_path, path)
    assert doc["stability"] == "stable" and not doc["gyroscopic"]
    assert abs(doc["point"]["q"]["theta1"]) < 1e-12 and abs(doc["point"]["q"]["theta2"]) < 1e-12
    expected = [p["g"] * (2 - math.sqrt(2)) / p["l1"], p["g"] * (2 + math.sqrt(2)) / p["l1"]]
    for mode, w2 in zip(doc["modes"], expected):
        assert mode["omega_squared"] == pytest.approx(w2, rel=REL)
        assert mode["omega"] == pytest.approx(math.sqrt(w2), rel=REL)
        assert mode["hz"] == pytest.approx(math.sqrt(w2) / (2 * math.pi), rel=REL)
        assert mode["stability"] == "stable"
    # shapes θ2/θ1 = ±√2; 1e-12: eigenvector round-off (ε times the pencil's condition)
    s0, s1 = ({k: v["re"] for k, v in m["shape"].items()} for m in doc["modes"])
    assert s0["theta2"] / s0["theta1"] == pytest.approx(math.sqrt(2), abs=1e-12)
    assert s1["theta2"] / s1["theta1"] == pytest.approx(-math.sqrt(2), abs=1e-12)
    assert "stability: stable" in text and "mode 1: oscillating, omega = " in text


def test_physical_pendulum(run, tmp_path):
    # thin rod about its end: I_p = m L²/3, d = L/2, so ω0² = m g d / I_p = 3 g / (2 L)
    path = EXAMPLES / "physical_pendulum.toml"
    p = parameters(path)
    doc, _ = modes_json(run, tmp_path, path)
    (mode,) = doc["modes"]
    assert mode["omega_squared"] == pytest.approx(3 * p["g"] / (2 * p["L"]), rel=REL)


def test_sleeping_top_flips_at_the_threshold(run, tmp_path):
    path = EXAMPLES / "sleeping_top.toml"
    p = parameters(path)
    m, r, h, d, g = (p[k] for k in ("m", "r", "h", "d", "g"))
    I1, I3 = m * (3 * r * r + h * h) / 12 + m * d * d, m * r * r / 2
    critical = 2 * math.sqrt(m * g * d * I1) / I3
    doc, _ = modes_json(run, tmp_path, path)  # the scene's own spin, w3 = 100 rad/s
    assert doc["stability"] == "stable" and doc["gyroscopic"] and doc["ignorable"] == ["psi"]
    for factor, expected in ((1.001, "stable"), (0.999, "unstable")):
        doc, _ = modes_json(run, tmp_path, path, "--at", f"psi_dot={factor * critical!r}")
        assert doc["stability"] == expected, (factor, doc["eigenvalues"])
        assert doc["point"]["q_dot"]["psi"] == pytest.approx(factor * critical, rel=1e-15)
    # the rate may be an expression of the parameters
    doc, _ = modes_json(run, tmp_path, path, "--at", "psi_dot=2*w3")
    assert doc["point"]["q_dot"]["psi"] == 2 * p["w3"]


def test_cli_and_python_write_the_same_document(run, tmp_path):
    path = EXAMPLES / "sleeping_top.toml"
    out = tmp_path / "modes.json"
    assert run("modes", path, "--at", "a=0", "--at", "psi_dot=60", "-o", out, "--json").returncode == 0
    python = rigid.Scene(path).modes(at={"a": 0.0, "psi_dot": "60"})
    assert out.read_text() == python.json()
    assert python.stability == "stable" and python.ignorable == ["psi"]
    assert "<NormalModes stable at (a=0, b=0, psi=0): omega = [" in repr(python)
    assert repr(python.modes[0]).startswith("<Mode stable: omega = ")
    assert "stability: stable" in str(python)


@pytest.mark.parametrize("args, message", [
    (["--at", "theta3=0"], "unknown coordinate 'theta3'; did you mean"),
    (["--at", "theta1"], "--at: point 'theta1' is not of the form name=value"),
    (["--at", "theta1_dot=1"], "'theta1' is not one (the system has no cyclic coordinates)"),
    (["--at", "theta1=0.5"], "is not an equilibrium: the generalized force on 'theta1'"),
    (["--at", "theta1=pj"], "point 'theta1=pj'"),
])
def test_refusals_through_cli_and_python(run, args, message):
    path = EXAMPLES / "double_pendulum.toml"
    proc = run("modes", path, *args)
    assert proc.returncode == 1 and message in proc.stderr, proc.stderr
    assert "normal_modes()" not in proc.stderr  # no C++ function names on the command line
    with pytest.raises(rigid.Error, match=message.replace("--at: ", "").replace("(", r"\(").replace(")", r"\)")):
        rigid.Scene(path).modes(at=[args[1]])


def test_a_free_body_scene_and_no_equilibrium_are_refused(run, tmp_path):
    proc = run("modes", EXAMPLES / "heavy_top.toml")
    assert proc.returncode == 1 and "normal modes are of a scene of [[coordinates]]" in proc.stderr
    scene = tmp_path / "falling.toml"
    scene.write_text('lagrangian = "z_dot^2/2 - 9.81*z"\n[[coordinates]]\nname = "z"\n[simulation]\nt_end = 1\n')
    proc = run("modes", scene)
    assert proc.returncode == 1
    assert "no equilibrium found from (z = 0)" in proc.stderr and "--at name=value" in proc.stderr
    with pytest.raises(rigid.Error, match='at="name=value"'):
        rigid.Scene(scene).modes()
    assert run("modes").returncode == 2  # the scene is required


def test_scene_lagrangian_matches_python_and_bodies(tmp_path):
    # the double pendulum three ways: a scene's lagrangian key, Python's string API and the
    # example's bodies give the same accelerations (1e-13: GiNaC may order a sum's terms
    # differently in separate derivations, a few ulps of |q̈| ≈ 10)
    L = ("(m1 + m2)/2*l1^2*theta1_dot^2 + m2/2*l2^2*theta2_dot^2"
         " + m2*l1*l2*theta1_dot*theta2_dot*cos(theta1 - theta2)"
         " + (m1 + m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)")
    scene = tmp_path / "dp.toml"
    scene.write_text(f'lagrangian = """\n{L}"""\n' + """
[parameters]
g = 9.81
m1 = 1.0
m2 = 1.0
l1 = 1.0
l2 = 1.0

[[coordinates]]
name = "theta1"
initial = 0.3
velocity = 0.5
[[coordinates]]
name = "theta2"
initial = -0.4
velocity = 1.5

[simulation]
t_end = 1.0
""")
    params = {"g": 9.81, "m1": 1.0, "m2": 1.0, "l1": 1.0, "l2": 1.0}
    system = rigid.lagrange.System([("theta1", 0.3, 0.5), ("theta2", -0.4, 1.5)], parameters=params,
                                   lagrangian=L)
    q, qd = np.array([0.3, -0.4]), np.array([0.5, 1.5])
    a_python, _ = system.accelerations(0.0, q, qd)
    a_scene, _ = rigid.Scene(scene).system.accelerations(0.0, q, qd)
    a_bodies, _ = rigid.Scene(EXAMPLES / "double_pendulum.toml").system.accelerations(0.0, q, qd)
    np.testing.assert_allclose(a_scene, a_python, rtol=0, atol=1e-13)
    np.testing.assert_allclose(a_bodies, a_python, rtol=0, atol=1e-13)
    # and the modes (the C++ side of the seam: tests/scene/lagrangian_test.cpp)
    w2 = [m.omega_squared for m in rigid.Scene(scene).modes(at=["theta1=0", "theta2=0"]).modes]
    assert w2 == pytest.approx([m.omega_squared for m in system.modes(at={"theta1": 0, "theta2": 0}).modes],
                               rel=1e-13)


@pytest.mark.parametrize("args", [["modes"], ["eom", "--emit", "c++"]])
def test_refusals_after_loading_name_the_scene_file(run, args):
    # a refusal that comes after the scene loaded (here: velocity constraints) starts with the
    # scene file, as the loader's own errors do, so a script running many scenes knows which one
    path = EXAMPLES / "rolling_disk.toml"
    proc = run(args[0], path, *args[1:])
    assert proc.returncode == 1
    assert proc.stderr.startswith(f"rigid: error: {path}: the system has velocity constraints"), proc.stderr
