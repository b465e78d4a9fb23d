"""rigid.lagrange.System.modes and rigid.lagrange.NormalModes: linearisation and normal modes
from Python, against closed forms."""
import math

import numpy as np
import pytest

import rigid

G = 9.81


def double_pendulum(m=0.7, l=1.3, theta=(math.pi / 2, math.pi / 2)):
    return rigid.lagrange.System(
        coordinates=[("theta1", theta[0], 0.0), ("theta2", theta[1], 0.0)],
        parameters={"m": m, "l": l, "g": G},
        lagrangian="m*l^2*theta1_dot^2 + m*l^2/2*theta2_dot^2"
                   " + m*l^2*theta1_dot*theta2_dot*cos(theta1 - theta2)"
                   " + 2*m*g*l*cos(theta1) + m*g*l*cos(theta2)")


def test_double_pendulum_frequencies_and_shapes():
    r = double_pendulum().modes()
    # ω² = g (2 ∓ √2)/l to 1e-10 relative (the acceptance bound; a few ulps expected)
    w2 = [G * (2 - math.sqrt(2)) / 1.3, G * (2 + math.sqrt(2)) / 1.3]
    assert [m.omega_squared for m in r.modes] == pytest.approx(w2, rel=1e-10)
    np.testing.assert_allclose(r.omega, np.sqrt(w2), rtol=1e-10)
    assert r.modes[0].hz == pytest.approx(math.sqrt(w2[0]) / (2 * math.pi), rel=1e-10)
    assert r.stability == "stable" and r.searched and not r.gyroscopic
    phi = r.modes[0].shape.real
    assert phi @ r.M @ phi == pytest.approx(1.0, abs=1e-13)  # M-normalised
    assert isinstance(r.modes[0].shape, np.ndarray) and r.modes[0].shape.dtype == complex
    assert repr(r).startswith("<NormalModes stable at (theta1=")
    assert "rad/s" in repr(r.modes[0]) and "mode 2: oscillating" in str(r)


def test_at_takes_a_dict_or_assignments_and_expressions():
    inverted = double_pendulum(theta=(0.0, 0.0)).modes(at={"theta1": "pi", "theta2": math.pi})
    assert inverted.stability == "unstable" and not inverted.searched
    same = double_pendulum(theta=(0.0, 0.0)).modes(at=["theta1=pi", "theta2=pi"])
    assert same.json() == inverted.json()
    # parameters for this call only
    light = double_pendulum().modes(parameters={"l": 2.6})
    assert light.modes[0].omega_squared == pytest.approx(G * (2 - math.sqrt(2)) / 2.6, rel=1e-10)


def test_damped_oscillator_uses_the_state_space_problem():
    s = rigid.lagrange.System(coordinates=[("x", 0.1, 0.0)], parameters={"m": 2.0, "k": 50.0, "c": 3.0},
                              lagrangian="m/2*x_dot^2 - k/2*x^2", forces=[("x", "-c*x_dot")])
    r = s.modes()
    assert r.gyroscopic and math.isnan(r.modes[0].omega_squared)
    # λ = −c/2m ± i √(k/m − c²/4m²)
    assert r.modes[0].eigenvalue == pytest.approx(complex(-0.75, math.sqrt(25 - 0.5625)), abs=1e-13)


def test_refusals_are_rigid_errors_worded_for_python():
    with pytest.raises(rigid.Error, match="unknown coordinate 'theta3'; did you mean"):
        double_pendulum().modes(at={"theta3": 0.0})
    falling = rigid.lagrange.System(coordinates=[("z", 0.0, 0.0)], lagrangian="z_dot^2/2 - 9.81*z")
    with pytest.raises(rigid.Error, match=r'no equilibrium found from \(z = 0\).*at="name=value"') as e:
        falling.modes()
    assert "normal_modes()" not in str(e.value)
