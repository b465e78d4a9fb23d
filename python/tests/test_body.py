import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk

import rigid

I = np.array([1.0, 2.0, 3.0])
W0 = np.array([0.01, 1.0, 0.01])


def euler(_t, w):
    return [(I[1] - I[2]) * w[1] * w[2] / I[0], (I[2] - I[0]) * w[2] * w[0] / I[1],
            (I[0] - I[1]) * w[0] * w[1] / I[2]]


def test_exact_matches_scipy_and_elliptic_period():
    exact = rigid.body.FreeBodyExact(I, W0)
    ref = solve_ivp(euler, (0, 30), W0, rtol=1e-12, atol=1e-14, method="DOP853").y[:, -1]
    # DOP853 at rtol 1e-12 over a flip: agreement to ~1e-9 (amplified near the separatrix).
    assert np.max(np.abs(exact.omega_body(30.0) - ref)) < 1e-8
    # Landau-Lifshitz eq. 37.10 with scipy's K(m), m = k^2 (independent of Boost).
    E2 = np.sum(I * W0**2)
    L2 = np.sum(I**2 * W0**2)
    lam = math.sqrt((I[2] - I[1]) * (L2 - E2 * I[0]) / np.prod(I))
    m = (I[1] - I[0]) * (E2 * I[2] - L2) / ((I[2] - I[1]) * (L2 - E2 * I[0]))
    assert exact.period == pytest.approx(4 * ellipk(m) / lam, rel=1e-12)


def test_simulate_keeps_momentum_and_matches_exact():
    out = rigid.body.simulate_free_body("splitting6", I, [1, 0, 0, 0], W0, 0.01, [5.0, 10.0])
    L = out["L_world"]
    assert np.linalg.norm(L[1] - L[0]) < 1e-13 * np.linalg.norm(L[0])
    exact = rigid.body.FreeBodyExact(I, W0).omega_body(10.0)
    assert np.max(np.abs(out["omega_body"][1] - exact)) < 1e-9


def test_bad_method_raises():
    with pytest.raises(rigid.Error, match="unknown free-body method 'verlet'"):
        rigid.body.simulate_free_body("verlet", I, [1, 0, 0, 0], W0, 0.01, [1.0])


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def rotate(q, v):
    return quat_mul(quat_mul(q, np.concatenate([[0.0], v])), q * np.array([1, -1, -1, -1]))[1:]


def test_exact_orientation_keeps_world_momentum_and_matches_moser_veselov():
    q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
    motion = rigid.body.FreeBodyMotion(I, q0, W0)
    L0 = rotate(q0, I * W0)
    for t in (0.0, 3.3, 47.0, -12.0):
        q = motion.orientation(t)
        # L_W = R(t) I w(t) is constant: a handful of rounded products (1e-12 relative).
        assert np.linalg.norm(rotate(q, I * motion.omega_body(t)) - L0) < 1e-12 * np.linalg.norm(L0)
    # Second-order Moser-Veselov at h = 1e-3 over 10 s: error O(h^2) ~ 1e-6 rad.
    out = rigid.body.simulate_free_body("moser_veselov", I, q0, W0, 1e-3, [10.0])
    q_mv, q_ex = out["q_wxyz"][0], motion.orientation(10.0)
    assert 2 * math.acos(min(1.0, abs(float(np.dot(q_mv, q_ex))))) < 1e-4


def test_motion_rejects_non_unit_quaternion():
    with pytest.raises(rigid.Error, match=r"has norm 2; expected a unit quaternion \(norm within 1e-09 of 1\)"):
        rigid.body.FreeBodyMotion(I, [2, 0, 0, 0], W0)


def test_rigid_body_torque_about_a_principal_axis_and_load_at_a_point():
    # constant body torque tau about principal axis 3 from rest: w3 = tau t / I3 (closed form)
    b = rigid.body.RigidBody(2.0, np.diag([1.0, 2.0, 3.0]))
    b.add_load(lambda t, s: ((0, 0, 0), (0, 0, 0.6)), frame="body")
    out = b.simulate("splitting2", (1, 0, 0, 0), (0, 0, 0), (0, 0, 0), (0, 0, 0), 1e-3, [0.5, 1.0])
    np.testing.assert_allclose(out["omega_body"][:, 2], [0.1, 0.2], rtol=1e-12)
    # the rotation angle about z is tau t^2 / (2 I3): 0.1 rad at t = 1
    q = out["q_wxyz"][-1]
    assert abs(2 * math.atan2(q[3], q[0]) - 0.1) < 1e-12
    # a world force F = (0, 1, 0) at body point (1, 0, 0) also turns the body: r x F = (0, 0, 1)
    c = rigid.body.RigidBody(1.0, np.eye(3))
    c.add_load(lambda t, s: ((0, 1, 0), (0, 0, 0)), point=(1, 0, 0))
    out = c.simulate("rk4", (1, 0, 0, 0), (0, 0, 0), (0, 0, 0), (0, 0, 0), 1e-4, [1e-3])
    # after a short time the torque is still ~ (0, 0, 1): w3 ≈ t, v_y = t
    assert abs(out["omega_body"][-1, 2] - 1e-3) < 1e-8
    assert abs(out["v_world"][-1, 1] - 1e-3) < 1e-12
    with pytest.raises(rigid.Error, match="frame must be 'world' or 'body'"):
        c.add_load(lambda t, s: ((0, 0, 0), (0, 0, 0)), frame="space")
