"""Velocity (nonholonomic) constraints through every surface: the rolling disk and the
Chaplygin sleigh through `rigid run`, rigid.Scene and rigid.lagrange.System give the same
trajectory, multipliers and residual, and the same refusals (file:line:col in scenes)."""
import csv
import json
import math
import pathlib

import numpy as np
import pytest

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}


def sleigh_closed_form(t, m=1.0, I=0.1, a=0.3, v0=0.5, w0=2.0):
    # v̇ = a ω², ω̇ = −(m a/J) v ω, J = I + m a² [Bloch2015, ch. 1]: v = V tanh s,
    # ω = ω0 cosh s0 / cosh s, s = (a m V/J) t + atanh(v0/V), V² = v0² + J ω0²/m
    J = I + m * a * a
    V = math.sqrt(v0 ** 2 + J * w0 ** 2 / m)
    s0 = math.atanh(v0 / V)
    s = a * m * V / J * np.asarray(t) + s0
    return V * np.tanh(s), w0 * math.cosh(s0) / np.cosh(s), m * I / J


@pytest.mark.parametrize("name", ["rolling_disk", "chaplygin_sleigh"])
def test_cli_and_python_scene_give_the_same_run(name, run, tmp_path):
    scene = EXAMPLES / f"{name}.toml"
    run("run", scene, "-o", tmp_path / "cli", "--format", "csv", "--format", "json", "-q", check=True)
    out = rigid.Scene(scene).run(output=tmp_path / "py", formats=["csv", "json"])
    assert (tmp_path / "cli" / "trajectory.csv").read_bytes() == (tmp_path / "py" / "trajectory.csv").read_bytes()
    summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    text = json.dumps(summary)
    # the residual is reported, at the integrator's tolerance (dopri5 at 1e-10)
    assert "velocity_constraint_residual_max" in text
    c = read_csv(tmp_path / "cli" / "trajectory.csv")
    assert c["velocity_constraint_residual"].max() <= 1e-9
    # energy: ideal rolling and blade forces do no work (relative drift at dopri5's 1e-10)
    e = c["energy"]
    assert np.abs(e - e[0]).max() <= 1e-8 * abs(e[0])
    assert out["written"]
    if name == "rolling_disk":
        # the steady motion: the lean stays 0.3 rad and the spin at the relation's value
        # (docs/lagrange.md: I1 Ω² sin θ cos θ − (I3 + m r²) w3 Ω cos θ = m g r sin θ), to the
        # 1e-10 of dopri5 amplified over two turns: 1e-7
        m, r, g, th, Om = 0.5, 0.1, 9.81, 0.3, -2.0
        w3 = (m * r * r / 4 * Om ** 2 * math.sin(th) * math.cos(th) - m * g * r * math.sin(th)) / (
            1.5 * m * r * r * Om * math.cos(th))
        np.testing.assert_allclose(c["theta"], th, atol=1e-7)
        np.testing.assert_allclose(c["phi_dot"], w3 - Om * math.sin(th), rtol=1e-7)
        np.testing.assert_allclose(np.hypot(c["mu_roll_x"], c["mu_roll_y"]), m * r * w3 * abs(Om), rtol=1e-7)


def test_sleigh_through_the_python_system_matches_its_closed_form():
    sys_ = rigid.lagrange.System(
        coordinates=[("x", 0.0, 0.5), ("y", 0.0, 0.0), ("theta", 0.0, 2.0)],
        parameters={"m": 1.0, "I": 0.1, "a": 0.3},
        lagrangian="m/2*((x_dot - a*sin(theta)*theta_dot)^2 + (y_dot + a*cos(theta)*theta_dot)^2)"
                   " + I/2*theta_dot^2",
        velocity_constraints=[{"name": "blade", "coefficients": {"x": "-sin(theta)", "y": "cos(theta)"}}])
    assert sys_.velocity_constraint_names == ["blade"]
    tr = sys_.simulate(t_end=1.5, tolerance=1e-12, output_dt=0.05)
    assert tr["velocity_constraint_names"] == ["blade"]
    th = tr["q"][:, 2]
    v = tr["q_dot"][:, 0] * np.cos(th) + tr["q_dot"][:, 1] * np.sin(th)
    v_exact, w_exact, force = sleigh_closed_form(tr["t"])
    # dopri5 at 1e-12 on O(1) values over 1.5 s: errors ≲ 1e-10
    np.testing.assert_allclose(v, v_exact, atol=1e-9)
    np.testing.assert_allclose(tr["q_dot"][:, 2], w_exact, atol=1e-9)
    np.testing.assert_allclose(tr["mu"][:, 0], force * v * tr["q_dot"][:, 2], atol=1e-9)
    assert tr["velocity_constraint_residual"].max() <= 1e-10
    # the example scene (the same sleigh as a body, not a Lagrangian string) runs the same
    # motion: its last row against this run's, at the scene's dopri5 tolerance 1e-10
    r = rigid.Scene(EXAMPLES / "chaplygin_sleigh.toml").run()
    c, d = r["columns"], r["summary"]["diagnostics"]
    assert d["velocity_constraint_residual_max"] <= 1e-9
    assert c["t"][-1] == tr["t"][-1] == 1.5
    np.testing.assert_allclose([c["x"][-1], c["y"][-1], c["theta"][-1], c["mu_blade"][-1]],
                               [*tr["q"][-1], tr["mu"][-1, 0]], atol=1e-8)


def test_python_system_refusals_name_what_and_where():
    base = dict(coordinates=[("x", 0.0, 0.0), ("y", 0.0, 0.0)], lagrangian="x_dot^2/2 + y_dot^2/2")
    with pytest.raises(rigid.Error, match=r"coefficient of 'xx': no coordinate of that name; did you mean 'x'\?"):
        rigid.lagrange.System(**base, velocity_constraints=[{"name": "k", "coefficients": {"xx": 1}}])
    with pytest.raises(rigid.Error, match="depends on the velocity 'y_dot', so the constraint is not linear"):
        rigid.lagrange.System(**base, velocity_constraints=[{"name": "k", "coefficients": {"x": "y_dot"}}])
    with pytest.raises(rigid.Error, match="term: is not linear in the velocities"):
        rigid.lagrange.System(**base, velocity_constraints=[{"name": "k", "term": "x_dot*y_dot"}])
    with pytest.raises(rigid.Error, match="velocity constraints 'a', 'b' are dependent for every q"):
        rigid.lagrange.System(**base, velocity_constraints=[{"name": "a", "coefficients": {"x": 1}},
                                                            {"name": "b", "coefficients": {"x": 2}}])
    with pytest.raises(rigid.Error, match="unknown velocity constraint key 'coefficient'"):
        rigid.lagrange.System(**base, velocity_constraints=[{"name": "a", "coefficient": {"x": 1}}])


def bad_scene(tmp_path, coefficient):
    text = (EXAMPLES / "chaplygin_sleigh.toml").read_text()
    text = text.replace('coefficients = { x = "-sin(theta)"', f'coefficients = {{ x = "{coefficient}"')
    path = tmp_path / "bad.toml"
    path.write_text(text)
    line = next(i for i, l in enumerate(text.splitlines(), 1) if l.startswith("coefficients"))
    return path, line


@pytest.mark.parametrize("coefficient,message", [
    ("-theta_dot", "depends on the velocity 'theta_dot', so the constraint is not linear"),
    ("-sin(thet)", "thet"),
])
def test_cli_and_python_refuse_a_scene_alike(coefficient, message, run, tmp_path):
    path, line = bad_scene(tmp_path, coefficient)
    p = run("run", path, "-o", tmp_path / "out", check=False)
    assert p.returncode == 1
    assert f"{path}:{line}:" in p.stderr and message in p.stderr
    with pytest.raises(rigid.Error) as e:
        rigid.Scene(path)
    assert str(e.value) in p.stderr
    assert not (tmp_path / "out").exists()


def test_unknown_coordinate_in_a_scene_is_refused_at_its_key(run, tmp_path):
    text = (EXAMPLES / "chaplygin_sleigh.toml").read_text().replace("{ x = ", "{ X = ")
    path = tmp_path / "bad.toml"
    path.write_text(text)
    line = next(i for i, l in enumerate(text.splitlines(), 1) if l.startswith("coefficients"))
    p = run("check", path, check=False)
    assert p.returncode == 1
    assert f"{path}:{line}:18: [[velocity_constraints]] entry 1 coefficients: 'X' is not a coordinate" in p.stderr


def test_a_scene_without_coordinates_says_so_instead_of_an_empty_list(run, tmp_path):
    # a free body has no coordinates: the message listed "expected one of: " and nothing
    path = tmp_path / "free.toml"
    path.write_text('[[bodies]]\nname = "b"\nfree = true\nprimitive = "sphere"\nradius = 0.1\n'
                    'mass = 1\n\n[[velocity_constraints]]\ncoefficients = { x = "1" }\n\n'
                    '[simulation]\nt_end = 1\n')
    p = run("check", path, check=False)
    assert p.returncode == 1
    assert (f"{path}:9:18: [[velocity_constraints]] entry 1 coefficients: 'x' is not a coordinate: "
            "the scene has no coordinates; velocity constraints act on the generalized coordinates "
            "of a scene posed by [[coordinates]] or a robot [model]") in p.stderr
    assert "expected one of" not in p.stderr
    with pytest.raises(rigid.Error, match="the scene has no coordinates"):
        rigid.Scene(path)
