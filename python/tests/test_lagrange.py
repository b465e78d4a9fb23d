"""rigid.lagrange: derive, print and simulate from Python; numpy arrays out."""
import math

import numpy as np
import pytest

import rigid

G = 9.81


def pendulum(theta0=0.5):
    return rigid.lagrange.System(
        coordinates=[("theta", theta0, 0.0)],
        parameters={"m": 2.0, "l": 0.5, "g": G},
        lagrangian="m*l^2/2*theta_dot^2 + m*g*l*cos(theta)",
    )


def test_equations_print_as_text_and_latex():
    eq = pendulum().equations()
    assert "theta_ddot" in eq["text"][0]
    assert r"\ddot{\theta}" in eq["latex"][0]
    assert eq["cyclic"] == []


def test_simulate_returns_numpy_arrays_and_conserves_energy():
    out = pendulum().simulate(2.0, tolerance=1e-12, output_dt=0.1)
    assert isinstance(out["q"], np.ndarray) and out["q"].shape == (21, 1)
    assert out["t"][-1] == 2.0
    # dopri5 at 1e-12 over 2 s: energy constant to ~1e-10 relative
    assert np.ptp(out["energy"]) < 1e-9 * abs(out["energy"][0])


def test_small_angle_period_matches_two_pi_sqrt_l_over_g():
    theta0 = 1e-6
    period = 2 * math.pi * math.sqrt(0.5 / G)
    out = pendulum(theta0).simulate(period, tolerance=1e-13, output_dt=period / 2)
    # the amplitude correction θ0²/16 is 6e-14; the bound is the integration tolerance
    assert out["q"][1, 0] == pytest.approx(-theta0, rel=1e-6)
    assert out["q"][2, 0] == pytest.approx(theta0, rel=1e-6)


def test_atwood_tensions_from_multipliers():
    m1, m2, mp, r = 1.0, 3.0, 2.0, 0.2
    zero = np.zeros(3)
    bodies = [
        {"name": "a", "mass": rigid.MassProperties(m1, zero, np.zeros((3, 3))), "position": ["-R", "y1", "0"]},
        {"name": "b", "mass": rigid.MassProperties(m2, zero, np.zeros((3, 3))), "position": ["R", "y2", "0"]},
        {"name": "pulley", "mass": rigid.MassProperties(mp, zero, np.diag([1.0, 1.0, 0.5 * mp * r * r])),
         "rotations": [([0, 0, 1], "phi")]},
    ]
    sys_ = rigid.lagrange.System(
        coordinates=[("y1", 0, 0), ("y2", 0, 0), ("phi", 0, 0)], parameters={"R": r},
        bodies=bodies, gravity=[0, -G, 0],
        constraints=[("left", "y1 + R*phi"), ("right", "y2 - R*phi")])
    out = sys_.simulate(0.5, tolerance=1e-12, output_dt=0.5)
    a = (m2 - m1) * G / (m1 + m2 + mp / 2)
    np.testing.assert_allclose(out["lambda"][-1], [m1 * (G + a), m2 * (G - a)], rtol=1e-9)
    assert out["residual"].max() < 1e-12


def test_unnamed_bodies_and_duplicate_names():
    pm = rigid.MassProperties(1.0, np.zeros(3), np.zeros((3, 3)))
    two = [{"mass": pm, "position": ["x", "0", "0"]}, {"mass": pm, "position": ["0", "x", "0"]}]
    sys_ = rigid.lagrange.System(coordinates=[("x", 0, 0)], bodies=two)
    m, _ = sys_.mass_matrix_and_forces(0.0, np.zeros(1), np.zeros(1))
    assert m[0, 0] == 2.0  # two unit masses both moving with x
    with pytest.raises(rigid.Error, match="body name 'a' is used twice"):
        rigid.lagrange.System(coordinates=[("x", 0, 0)], bodies=[{"name": "a", **b} for b in two])


def test_kepler_reports_the_cyclic_momentum():
    sys_ = rigid.lagrange.System(coordinates=[("r", 1.0, 0.0), ("phi", 0.0, 1.1)],
                                 lagrangian="(r_dot^2 + r^2*phi_dot^2)/2 + 1/r")
    assert sys_.cyclic_coordinates == ["phi"]
    out = sys_.simulate(3.0, tolerance=1e-12, output_dt=0.5)
    np.testing.assert_allclose(out["cyclic_momenta"][:, 0], 1.1, rtol=1e-10)


def test_spring_oscillator_period():
    m, k = 0.5, 80.0
    bob = rigid.MassProperties(m, np.zeros(3), np.zeros((3, 3)))
    y_eq = -(0.3 + m * G / k)
    sys_ = rigid.lagrange.System(
        coordinates=[("y", y_eq + 0.01, 0.0)], bodies=[{"name": "bob", "mass": bob, "position": ["0", "y", "0"]}],
        gravity=[0, -G, 0], springs=[{"body_a": "bob", "stiffness": k, "rest_length": 0.3}])
    period = 2 * math.pi * math.sqrt(m / k)
    out = sys_.simulate(period, tolerance=1e-13, output_dt=period / 2)
    # linear oscillation about y_eq: half a period later at the other turning point
    assert out["q"][1, 0] == pytest.approx(y_eq - 0.01, abs=1e-9)
    assert out["q"][2, 0] == pytest.approx(y_eq + 0.01, abs=1e-9)


def test_errors_are_rigid_errors_with_positions():
    with pytest.raises(rigid.Error, match="undefined symbol 'thta'"):
        rigid.lagrange.System(coordinates=[("theta", 0, 0)], lagrangian="theta_dot^2 + cos(thta)")
    with pytest.raises(rigid.Error, match="unknown integrator 'euler'"):
        pendulum().simulate(1.0, method="euler")
    with pytest.raises(rigid.Error, match="unknown body key 'masss'"):
        rigid.lagrange.System(coordinates=[("x", 0, 0)], bodies=[{"masss": 1}])


def test_energy_poses_and_constraints_at_a_state():
    # a bob of 2 kg on a 0.5 m rod: T = ½ m l² θ̇², V = −m g l cos θ (closed forms)
    bob = rigid.mass.point_mass(2.0, [0.0, 0.0, 0.0])
    s = rigid.lagrange.System(
        coordinates=[("theta", 0.3, 0.0), ("x", 0.0, 0.0)],
        parameters={"l": 0.5},
        bodies=[{"name": "bob", "mass": bob, "position": ["l*sin(theta)", "0", "-l*cos(theta)"]}],
        gravity=[0, 0, -G],
        lagrangian="x_dot^2/2",
        constraints=[("tie", "x - theta")],
    )
    q, qd = np.array([0.3, 0.3]), np.array([1.5, 1.5])
    T = 0.5 * 2.0 * 0.25 * 1.5**2 + 0.5 * 1.5**2
    V = -2.0 * G * 0.5 * math.cos(0.3)
    assert s.energy(0.0, q, qd) == pytest.approx(T + V, rel=1e-14)
    assert s.jacobi_integral(0.0, q, qd) == pytest.approx(T + V, rel=1e-14)  # L has no t: h = T + V
    pose = s.body_poses(0.0, q)["bob"]
    np.testing.assert_allclose(pose["p_world"], [0.5 * math.sin(0.3), 0, -0.5 * math.cos(0.3)], rtol=0, atol=1e-16)
    np.testing.assert_array_equal(pose["q_wxyz"], [1.0, 0, 0, 0])
    np.testing.assert_allclose(s.constraint_residual(0.0, [0.3, 0.5]), [0.2], rtol=1e-15)
    assert s.body_names == ["bob"] and s.parameters == {"l": 0.5}
    np.testing.assert_array_equal(s.initial_q, [0.3, 0.0])
    # q of the wrong length is named, not read past its end
    with pytest.raises(rigid.Error, match=r"System\.energy\(\): argument 'q' must have shape \(2,\); got \(3,\)"):
        s.energy(0.0, [0.3, 0.3, 0.3], qd)
