"""Every scene in examples/ run through `rigid run`, checked against the closed form in its
comments (computed here independently, with SciPy where an elliptic integral is needed);
then the errors and outputs of `rigid run`, `rigid check` and `rigid eom`."""
import csv
import json
import math
import pathlib

import numpy as np
import pytest
import sympy
from scipy.special import ellipk

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
G = 9.81


def simulate(run, tmp_path, name, *extra):
    out = tmp_path / name
    run("run", EXAMPLES / f"{name}.toml", "-o", out, "--quiet", *extra, check=True)
    with open(out / "trajectory.csv", newline="") as f:
        rows = list(csv.reader(f))
    data = np.array(rows[1:], dtype=float)
    columns = {c: data[:, i] for i, c in enumerate(rows[0])}
    summary = json.loads((out / "summary.json").read_text())
    return columns, summary


def zero_crossings(t, f):
    """Times where f changes sign, by linear interpolation between samples."""
    i = np.nonzero(np.signbit(f[:-1]) != np.signbit(f[1:]))[0]
    return t[i] + (t[i + 1] - t[i]) * f[i] / (f[i] - f[i + 1])


@pytest.mark.parametrize("name, a", [
    # s_ddot = g sin(alpha) / (1 + I/(m r^2)) with I/(m r^2) = 1/2, 2/5, (r1^2 + r2^2)/(2 r2^2)
    ("rolling_cylinder", G * math.sin(0.5) / 1.5),
    ("rolling_sphere", G * math.sin(0.5) / 1.4),
    ("rolling_tube", G * math.sin(0.5) / (1 + (0.03**2 + 0.05**2) / (2 * 0.05**2))),
])
def test_rolling_down_an_incline(run, tmp_path, name, a):
    c, summary = simulate(run, tmp_path, name)
    t = c["t"]
    # RK4 integrates s_ddot = const exactly (a quadratic): only round-off remains
    np.testing.assert_allclose(c["s"], a * t**2 / 2, rtol=0, atol=1e-11)
    np.testing.assert_allclose(c["s_dot"], a * t, rtol=0, atol=1e-11)
    assert t[-1] == 2.0 and len(t) == 201
    # energy is conserved (rolling without slipping does no work); round-off of ~|V| = 10 J
    assert summary["diagnostics"]["energy_max_change"] < 1e-9


def test_rolling_cylinder_pose_columns_follow_the_coordinate(run, tmp_path):
    c, _ = simulate(run, tmp_path, "rolling_cylinder")
    s, alpha, r = c["s"], 0.5, 0.1
    np.testing.assert_allclose(c["cylinder.x"], s * math.cos(alpha), atol=1e-14)
    np.testing.assert_allclose(c["cylinder.z"], -s * math.sin(alpha), atol=1e-14)
    # R_WB = Rx(pi/2) Rz(-s/r): the quaternion of the product, up to sign
    qw, qx, qy, qz = (c[f"cylinder.q{k}"] for k in "wxyz")
    h = -s / r / 2
    c0, s0 = math.cos(math.pi / 4), math.sin(math.pi / 4)
    expected = np.array([c0 * np.cos(h), s0 * np.cos(h), -s0 * np.sin(h), c0 * np.sin(h)])
    dot = np.abs(qw * expected[0] + qx * expected[1] + qy * expected[2] + qz * expected[3])
    np.testing.assert_allclose(dot, 1.0, atol=1e-12)


def test_atwood_machine_acceleration_and_rope_tensions(run, tmp_path):
    c, summary = simulate(run, tmp_path, "atwood")
    m1, m2, M = 3.0, 2.0, 2.0
    a = (m1 - m2) * G / (m1 + m2 + M / 2)
    t = c["t"]
    np.testing.assert_allclose(c["y1"], a * t**2 / 2, atol=1e-11)
    np.testing.assert_allclose(c["y2"], -a * t**2 / 2, atol=1e-11)
    np.testing.assert_allclose(c["phi"], a * t**2 / 2 / 0.1, atol=1e-10)
    # The multiplier of g1 = y1 - R phi enters y1's equation m1 y1_dd = m1 g + lambda1: the
    # rope pulls weight 1 up with T1 = -lambda1 = m1 (g - a); likewise T2 = -lambda2 = m2 (g + a)
    np.testing.assert_allclose(-c["lambda_rope1"], m1 * (G - a), rtol=1e-12)
    np.testing.assert_allclose(-c["lambda_rope2"], m2 * (G + a), rtol=1e-12)
    assert summary["diagnostics"]["constraint_residual_max"] < 1e-12


def pendulum_period(I_pivot, m, d, theta0):
    """Period of a physical pendulum of amplitude theta0: 4 K(sin^2(theta0/2)) sqrt(I/(m g d))."""
    return 4 * ellipk(math.sin(theta0 / 2) ** 2) * math.sqrt(I_pivot / (m * G * d))


def measured_period(c, name):
    zeros = zero_crossings(c["t"], c[name])
    assert len(zeros) >= 3
    # successive zeros are half a period apart
    return 2 * np.mean(np.diff(zeros)), 2 * np.ptp(np.diff(zeros)) / 2


def test_physical_pendulum_period(run, tmp_path):
    c, summary = simulate(run, tmp_path, "physical_pendulum")
    m, L = 0.5, 1.0
    expected = pendulum_period(m * L**2 / 3, m, L / 2, 1.0)  # 1.7758 s
    period, spread = measured_period(c, "theta")
    # dopri5 at 1e-10 and interpolation between 5 ms samples at the zero (where theta'' = 0)
    # place each zero to better than 1e-6 s
    assert abs(period - expected) < 1e-5
    assert spread < 1e-5
    assert summary["diagnostics"]["energy_max_change"] < 1e-8 * abs(summary["diagnostics"]["energy_initial"])


def test_cone_pendulum_checks_the_cone_inertia(run, tmp_path):
    c, _ = simulate(run, tmp_path, "cone_pendulum")
    m, r, h = 1.2, 0.1, 0.4
    # cone about its COM: I_perp = m (3/20 r^2 + 3/80 h^2); apex -> COM: d = 3h/4
    d = 0.75 * h
    I_apex = m * (3 / 20 * r**2 + 3 / 80 * h**2) + m * d**2
    expected = pendulum_period(I_apex, m, d, 0.01)  # 1.1449 s
    period, _ = measured_period(c, "theta")
    assert abs(period - expected) < 1e-5
    # and the small-angle formula of the comment, within its O(theta0^2/16) = 6e-6 error
    assert abs(period / (2 * math.pi * math.sqrt(I_apex / (m * G * d))) - 1) < 1e-5


def test_double_pendulum_energy_bounded_and_poses(run, tmp_path):
    c, summary = simulate(run, tmp_path, "double_pendulum")
    # both rods horizontal at rest: E = 0. Implicit midpoint (symplectic, h = 1e-3) keeps
    # the energy error O(h^2 |q_ddot|^2)-bounded without drift: far below m g l = 9.81 J
    e = c["energy"]
    assert np.max(np.abs(e)) < 1e-3
    half = len(e) // 2
    assert np.max(np.abs(e[half:])) < 2 * np.max(np.abs(e[:half])) + 1e-4  # no growth
    th1, th2 = c["theta1"], c["theta2"]
    np.testing.assert_allclose(c["bob2.x"], np.sin(th1) + np.sin(th2), atol=1e-13)
    np.testing.assert_allclose(c["bob2.z"], -np.cos(th1) - np.cos(th2), atol=1e-13)
    assert summary["integrator"] == "implicit_midpoint"


def test_heavy_top_precession(run, tmp_path):
    c, summary = simulate(run, tmp_path, "heavy_top")
    m, r, h, w3, theta = 1.0, 0.05, 0.2, 2000.0, 0.3
    I3 = 0.3 * m * r**2
    d = 0.75 * h
    I1 = m * (3 / 20 * r**2 + 3 / 80 * h**2) + m * d**2
    # azimuth of the body z axis (third column of R_WB) in the world
    qw, qx, qy, qz = (c[f"top.q{k}"] for k in "wxyz")
    zx, zy = 2 * (qx * qz + qw * qy), 2 * (qy * qz - qw * qx)
    phi = np.unwrap(np.arctan2(zy, zx))
    rate = np.polyfit(c["t"], phi, 1)[0]
    fast = m * G * d / (I3 * w3)
    steady = (I3 * w3 - math.sqrt((I3 * w3) ** 2 - 4 * I1 * m * G * d * math.cos(theta))) / (
        2 * I1 * math.cos(theta))
    eps = I1 * m * G * d / (I3 * w3) ** 2
    # clockwise seen from above; the fast-top formula holds to its order eps = 0.016
    assert rate < 0
    assert abs(-rate / fast - 1) < 2 * eps
    # the nutation (period 0.1 s, started from rest in azimuth) averages out of the
    # least-squares slope over 2 s to a few parts in 1e3 of the steady precession
    assert abs(-rate / steady - 1) < 3e-3
    # L_3 = I3 w3: the gravity torque has no component along the symmetry axis
    np.testing.assert_allclose(c["top.wz"], w3, rtol=1e-13)
    # the splitting keeps L_z to round-off
    assert summary["diagnostics"]["top.L_vertical_max_change"] < 1e-12


def racket_period(I, w):
    """Period of w(t) of the free asymmetric body (Landau & Lifshitz §37), L^2 > 2E I2."""
    I1, I2, I3 = I
    E2 = sum(i * x * x for i, x in zip(I, w))
    L2 = sum(i * i * x * x for i, x in zip(I, w))
    lam = math.sqrt((I3 - I2) * (L2 - E2 * I1) / (I1 * I2 * I3))
    k2 = (I2 - I1) * (E2 * I3 - L2) / ((I3 - I2) * (L2 - E2 * I1))
    return 4 * ellipk(k2) / lam, E2 / 2, math.sqrt(L2)


def test_tennis_racket_flips(run, tmp_path):
    c, summary = simulate(run, tmp_path, "tennis_racket")
    T, E, L = racket_period((1, 2, 3), (0.01, 1, 0.01))  # 39.106 s
    flips = zero_crossings(c["t"], c["racket.wy"])
    assert len(flips) == 5  # at 10.9, 30.5, 50.0, 69.6, 89.1 s
    # splitting4 at h = 1e-3 s; linear interpolation of w_y between 50 ms samples at its
    # zero (an inflection point) is accurate to ~1e-5 s
    np.testing.assert_allclose(np.diff(flips), T / 2, atol=1e-4)
    assert abs(flips[0] - 10.917) < 1e-3
    # energy and |L| from the initial state, conserved to round-off by the splitting
    assert abs(summary["diagnostics"]["energy_initial"] - E) < 1e-14
    assert summary["diagnostics"]["energy_max_change"] < 1e-11
    assert summary["diagnostics"]["racket.L_norm_max_change"] < 1e-11
    Lw = np.stack([c["racket.Lx"], c["racket.Ly"], c["racket.Lz"]])
    np.testing.assert_allclose(np.linalg.norm(Lw, axis=0), L, rtol=1e-12)


@pytest.mark.parametrize("k", [1e2, 1e4, 1e6])
def test_stiff_dumbbell_approaches_the_rigid_body(run, tmp_path, k):
    c, _ = simulate(run, tmp_path, "stiff_dumbbell", "--set", f"k={k}")
    m, r0, w = 1.0, 0.5, 2.0
    rk = k * r0 / (k - m * w**2 / 2)  # the stretched radius of the steady rotation
    t = c["t"]
    radius = np.hypot(c["x1"] - c["x2"], c["y1"] - c["y2"]) / 2
    # started on the steady rotation, the radius stays rk up to the midpoint rule's O(h^2)
    # modification of the orbit, (w h)^2 / 4 = 1e-8 relative
    np.testing.assert_allclose(radius, rk, rtol=2e-8)
    # phase error of implicit midpoint: w^3 h^2 t / 12 = 8e-8 * 3 / 12 rad
    np.testing.assert_allclose(c["x1"], rk * np.cos(w * t), atol=1e-7)
    np.testing.assert_allclose(c["y1"], rk * np.sin(w * t), atol=1e-7)
    # the distance to the rigid dumbbell shrinks as 1/k: (rk - r0) k -> m w^2 r0 / 2
    assert abs((rk - r0) * k / (m * w**2 * r0 / 2) - 1) < 2 * m * w**2 / k
    assert abs(np.mean(radius) - r0) < 1.01 * (rk - r0)


def test_graded_rod_pendulum_period(run, tmp_path):
    # a rod (r = 0.01, h = 1) with ρ = ρ0 (1/2 + u/h), u from the pivot at its top: m = ρ0 π r² h,
    # COM at 7h/12, I_pivot = m (5h²/12 + r²/4); its mass properties come from the density field
    c, summary = simulate(run, tmp_path, "graded_rod_pendulum")
    rho0, r, h = 2700.0, 0.01, 1.0
    m = rho0 * math.pi * r * r * h
    expected = pendulum_period(m * (5 * h * h / 12 + r * r / 4), m, 7 * h / 12, 1.0)  # 1.80796 s
    period, spread = measured_period(c, "theta")
    # as the physical pendulum above: dopri5 at 1e-12 and interpolation at the zeros
    assert abs(period - expected) < 1e-5
    assert spread < 1e-5
    assert summary["metrics"]["period"]["value"] == pytest.approx(expected, rel=1e-9)


CHECKED = {"rolling_cylinder", "rolling_sphere", "rolling_tube", "atwood", "physical_pendulum",
           "graded_rod_pendulum",
           "cone_pendulum", "double_pendulum", "heavy_top", "tennis_racket", "stiff_dumbbell",
           "sleeping_top",  # tests/cli/test_cli_modes.py and test_example_comments.py
           "rolling_disk", "chaplygin_sleigh"}  # these two: tests/cli/test_nonholonomic.py


def test_every_example_scene_has_a_closed_form_check():
    # a new example must come with its check above
    assert {p.stem for p in EXAMPLES.glob("*.toml")} == CHECKED


def test_npy_equals_csv(run, tmp_path):
    out = tmp_path / "o"
    run("run", EXAMPLES / "atwood.toml", "-o", out, "--format", "csv", "--format", "npy", check=True)
    with open(out / "trajectory.csv", newline="") as f:
        rows = list(csv.reader(f))
    csv_data = np.array(rows[1:], dtype=float)
    npy = np.load(out / "trajectory.npy")
    assert npy.shape == csv_data.shape and npy.dtype == np.float64
    # the CSV prints each double in a form that reads back to the same bits
    assert np.array_equal(npy, csv_data)
    # trajectory.npy holds no column names: summary.json, which lists them, comes with it
    assert json.loads((out / "summary.json").read_text())["columns"] == rows[0]


def test_run_prints_a_summary(run, tmp_path):
    p = run("run", EXAMPLES / "atwood.toml", "-o", tmp_path / "o", check=True)
    assert "rk4 to t = 1 s: 1000 steps" in p.stdout
    assert "constraint_residual_max" in p.stdout
    assert "trajectory.csv" in p.stdout and "summary.json" in p.stdout
    # not a terminal: no progress bar
    assert "\r" not in p.stderr
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["parameters"] == {"g": 9.81, "m1": 3.0, "m2": 2.0, "M": 2.0, "R": 0.1}
    assert summary["steps"] == 1000 and summary["samples"] == 101
    assert summary["final"]["t"] == 1.0


def test_set_overrides_a_parameter(run, tmp_path):
    c, summary = simulate(run, tmp_path, "atwood", "--set", "m2=3")
    assert summary["parameters"]["m2"] == 3.0
    np.testing.assert_allclose(c["y1"], 0, atol=1e-12)  # balanced


def write(tmp_path, text, name="scene.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


PENDULUM = """gravity = [0, 0, "-g"]
[parameters]
g = 9.81
l = 2.0
[[coordinates]]
name = "theta"
initial = 0.1
[[bodies]]
name = "bob"
point_masses = [{mass = 1, position = [0, 0, 0]}]
position = ["l*sin(theta)", 0, "-l*cos(thta)"]
[simulation]
t_end = 1
"""


def test_undefined_symbol_is_reported_at_its_column_and_nothing_is_written(run, tmp_path):
    scene = write(tmp_path, PENDULUM)
    out = tmp_path / "o"
    p = run("run", scene, "-o", out, check=False)
    assert p.returncode == 1
    # line 11: the third string opens at column 32, 'thta' starts 8 characters later
    assert f"{scene}:11:40: body 'bob' position[2]: undefined symbol 'thta'" in p.stderr
    assert "undefined symbol 'thta'" in p.stderr
    assert "Traceback" not in p.stderr and "terminate" not in p.stderr
    assert not out.exists()


def test_check_validates_without_running(run, tmp_path):
    p = run("check", EXAMPLES / "atwood.toml", check=True)
    assert "coordinates: y1, y2, phi" in p.stdout
    assert "constraints: rope1, rope2" in p.stdout
    assert "is a valid scene" in p.stdout
    bad = write(tmp_path, PENDULUM)
    p = run("check", bad, check=False)
    assert "undefined symbol 'thta'" in p.stderr


def test_check_refuses_inconsistent_initial_conditions(run, tmp_path):
    text = (EXAMPLES / "atwood.toml").read_text().replace(
        '[[coordinates]]\nname = "y1"', '[[coordinates]]\nname = "y1"\ninitial = 0.5')
    p = run("check", write(tmp_path, text), check=False)
    assert "initial conditions violate constraint 'rope1'" in p.stderr


def test_a_constraints_rope_names_its_bodies_and_keys(run, tmp_path):
    # the rope only draws the constraint; its bodies and keys are checked as a spring's are
    atwood = (EXAMPLES / "atwood.toml").read_text()
    lines = atwood.splitlines()
    row = next(i for i, line in enumerate(lines) if line.startswith('rope = {body_a = "weight1"')) + 1
    p = run("check", write(tmp_path, atwood.replace('body_a = "weight1"', 'body_a = "weigth1"')), check=False)
    assert p.returncode != 0
    assert f":{row}:8: rope of constraint 'rope1' attached to unknown body 'weigth1'; did you mean 'weight1'?" in p.stderr
    p = run("check", write(tmp_path, atwood.replace('body_a = "weight1",', 'body_a = "weight1", colour = 2,')), check=False)
    assert p.returncode != 0 and "unknown key 'colour' in [[constraints]] entry 1 rope" in p.stderr
    p = run("check", write(tmp_path, atwood.replace('rope = {body_a = "weight1", point_b = [-0.1, 0, 0]}', 'rope = "weight1"')), check=False)
    assert p.returncode != 0 and f":{row}:8:" in p.stderr and "rope" in p.stderr
    # a potential or a force has no rope
    text = atwood + '[[potentials]]\nexpression = "0"\nrope = {body_a = "weight1"}\n'
    p = run("check", write(tmp_path, text), check=False)
    assert p.returncode != 0 and "unknown key 'rope' in [[potentials]] entry 1" in p.stderr
    assert run("check", EXAMPLES / "atwood.toml").returncode == 0


def test_unknown_key_suggests_the_right_one(run, tmp_path):
    text = PENDULUM.replace("thta", "theta").replace("t_end = 1", "t_ned = 1")
    p = run("run", write(tmp_path, text), "-o", tmp_path / "o", check=False)
    assert ":13:1: unknown key 't_ned' in [simulation]; did you mean 't_end'?" in p.stderr


def test_physically_invalid_body_is_refused(run, tmp_path):
    text = (EXAMPLES / "rolling_cylinder.toml").read_text().replace('radius = "r"', 'radius = "-r"')
    p = run("run", write(tmp_path, text), "-o", tmp_path / "o", check=False)
    assert "body 'cylinder'" in p.stderr and "radius" in p.stderr and "-0.1" in p.stderr
    assert not (tmp_path / "o").exists()


def test_free_point_mass_has_no_defined_rotation(run, tmp_path):
    text = """[[bodies]]
name = "p"
free = true
point_masses = [{mass = 1, position = [0, 0, 0]}]
[simulation]
t_end = 1
"""
    p = run("run", write(tmp_path, text), "-o", tmp_path / "o", check=False)
    assert "zero moment" in p.stderr and "'p'" in p.stderr


def test_unknown_integrator_lists_the_choices(run, tmp_path):
    p = run("run", EXAMPLES / "tennis_racket.toml", "--integrator", "rk45", "-o", tmp_path / "o",
            check=False)
    assert "rk45" in p.stderr and "splitting4" in p.stderr
    p = run("run", EXAMPLES / "heavy_top.toml", "--integrator", "rk4", "-o", tmp_path / "o", check=False)
    assert "pivot" in p.stderr and "splitting2" in p.stderr


def test_eom_text_and_latex(run):
    p = run("eom", EXAMPLES / "physical_pendulum.toml", check=True)
    assert "theta" in p.stdout and "sin(theta)" in p.stdout
    p = run("eom", EXAMPLES / "physical_pendulum.toml", "--latex", check=True)
    assert "\\theta" in p.stdout
    p = run("eom", EXAMPLES / "tennis_racket.toml", check=True)
    # Euler's equations with the principal moments (1, 2, 3) [Landau1976, §36]:
    # I1 w1_dot = (I2 - I3) w2 w3 and cyclic; each printed line is read back by SymPy and
    # compared with the closed form (the order of the printed terms is free)
    w1, w2, w3, d1, d2, d3 = sympy.symbols("w1 w2 w3 w1_dot w2_dot w3_dot")
    expected = [1 * d1 - (2 - 3) * w2 * w3, 2 * d2 - (3 - 1) * w3 * w1, 3 * d3 - (1 - 2) * w1 * w2]
    lines = [l for l in p.stdout.splitlines() if "_dot = " in l and "R_WB" not in l and "c_ddot" not in l]
    assert len(lines) == 3, p.stdout
    for line, want in zip(lines, expected):
        lhs, rhs = line.split(" = ")
        assert sympy.simplify(sympy.sympify(lhs) - sympy.sympify(rhs) - want) == 0, line


def test_tennis_racket_exact_integrator_agrees_with_splitting(run, tmp_path):
    a, sa = simulate(run, tmp_path, "tennis_racket")
    b, sb = simulate(run, tmp_path / "exact", "tennis_racket", "--integrator", "exact")
    assert sb["integrator"] == "exact" and sb["steps"] == 0
    # splitting4 at h = 1e-3 s: a 4th-order error of ~1e-12 per unit time, amplified by the
    # motion's sensitivity near the separatrix (k = 0.9999) to ~1e-10 over 100 s
    for col in ("racket.wx", "racket.wy", "racket.wz", "racket.qw", "racket.qx", "racket.qy", "racket.qz"):
        np.testing.assert_allclose(a[col], b[col], rtol=0, atol=1e-8, err_msg=col)
    # the closed form conserves energy and |L| to round-off by construction
    assert sb["diagnostics"]["energy_max_change"] < 1e-13
    p = run("run", EXAMPLES / "heavy_top.toml", "--integrator", "exact", "-o", tmp_path / "o", check=False)
    assert "closed-form motion of the torque-free body" in p.stderr


def test_progress_bar_only_on_a_terminal(rigid_exe, tmp_path):
    import os
    import pty
    import subprocess
    # 5e6 splitting4 steps, a second or more: long enough for the bar (it waits half a second)
    scene = write(tmp_path, (EXAMPLES / "tennis_racket.toml").read_text()
                  .replace("t_end = 100.0", "t_end = 5000.0").replace("output_dt = 0.05", "output_dt = 1"))
    master, slave = pty.openpty()
    proc = subprocess.run([rigid_exe, "run", str(scene), "-o", str(tmp_path / "o")],
                          stdout=subprocess.PIPE, stderr=slave, timeout=120)
    os.close(slave)
    err = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:
            break
        if not chunk:
            break
        err += chunk
    os.close(master)
    assert proc.returncode == 0
    assert b"\r[#" in err and b"t = " in err
    assert err.endswith(b"\r\x1b[K")  # the bar is wiped before the summary
    assert b"splitting4 to t = 5000 s" in proc.stdout


def test_output_quantities_select_columns(run, tmp_path):
    text = (EXAMPLES / "atwood.toml").read_text() + '\n[output]\nquantities = ["y1", "lambda_*"]\n'
    out = tmp_path / "o"
    run("run", write(tmp_path, text), "-o", out, check=True)
    with open(out / "trajectory.csv", newline="") as f:
        header = next(csv.reader(f))
    assert header == ["t", "y1", "lambda_rope1", "lambda_rope2"]
    bad = text.replace('"lambda_*"', '"lamda_rope1"')
    p = run("run", write(tmp_path, bad, "bad.toml"), "-o", tmp_path / "b", check=False)
    assert "'lamda_rope1' matches no column; did you mean 'lambda_rope1'?" in p.stderr
