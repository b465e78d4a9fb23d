import math
import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk

import rigid

I = np.array([1.0, 2.0, 3.0])
W0 = np.array([0.01, 1.0, 0.01])
EPS = np.finfo(float).eps


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


# ---- single steps, the heavy top, Euler's equations and Euler–Arnold on SO(n) ----

def matrix_of(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def hat(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0.0]])


def spinning_top():
    # a solid cone (m = 1 kg, r = 5 cm, h = 20 cm) on its apex, tilted 0.3 rad, spinning at 200 rad/s
    cone = rigid.mass.solid_cone_with_mass(1.0, 0.05, 0.2)
    top = rigid.body.HeavyTop(cone, [0, 0, 0.2])
    q0 = np.array([math.cos(0.15), math.sin(0.15), 0, 0])
    return top, q0, np.array([0, 0, 200.0])


def test_heavy_top_keeps_energy_and_both_momenta():
    top, q, w = spinning_top()
    E0 = top.energy(q, w)
    Lz0 = top.angular_momentum_world(q, w)[2]
    L3_0 = (top.inertia_about_pivot @ w)[2]
    scale = np.linalg.norm(top.angular_momentum_world(q, w))
    for _ in range(2000):
        q, w = top.step(q, w, 1e-4, "splitting4")
    # the vertical world momentum is kept by every sub-step exactly (the kick's ΔL ⟂ g, the free
    # flow keeps L_W): round-off of 2000 steps, a few ε each
    assert abs(top.angular_momentum_world(q, w)[2] - Lz0) < 2000 * 8 * EPS * scale
    # the spin I₃ω₃ of a symmetric top (pivot on the axis): kept by the exact flow; the gravity
    # torque has no axial part, the free sub-flows of an axisymmetric body keep it up to round-off
    assert abs((top.inertia_about_pivot @ w)[2] - L3_0) < 1e-10 * scale
    # energy: a symplectic order-2 method keeps it to O(h²) without drift; (hω)² = 4e-4 bounds it
    assert abs(top.energy(q, w) - E0) < 4e-4 * abs(E0)


def test_heavy_top_step_converges_at_order_two_to_the_euler_poisson_equations():
    # independent reference: SciPy's DOP853 on Euler–Poisson, I ω̇ = Iω × ω + p_PC × (m Γ),
    # Γ̇ = Γ × ω with Γ = R_WBᵀ g the gravity in the body
    from scipy.integrate import solve_ivp
    top, q0, w0 = spinning_top()
    I_P, p, g = top.inertia_about_pivot, top.com_from_pivot, top.gravity
    rhs = lambda _t, y: np.concatenate([np.linalg.solve(I_P, np.cross(I_P @ y[:3], y[:3]) + np.cross(p, top.mass * y[3:])),
                                        np.cross(y[3:], y[:3])])
    ref = solve_ivp(rhs, (0, 0.2), np.concatenate([w0, matrix_of(q0).T @ g]), rtol=3e-14, atol=1e-14,
                    method="DOP853").y[3:, -1]
    errors = []
    for n in (500, 1000, 2000):
        q, w = q0, w0
        for _ in range(n):
            q, w = top.step(q, w, 0.2 / n, "splitting4")
        errors.append(np.max(np.abs(matrix_of(q).T @ g - ref)))
    # the kick–drift–kick splitting is order 2 whatever the free flow: error ratio 2² within ±10%
    for coarse, fine in zip(errors, errors[1:]):
        assert 4 * 0.9 < coarse / fine < 4 * 1.1


def test_free_body_steps_reproduce_simulate_bitwise():
    q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
    out = rigid.body.simulate_free_body("splitting4", I, q0, W0, 0.01, [0.25])
    # march: ceil(0.25 / 0.01) = 25 equal steps of 0.25/25
    q, w = q0, W0
    for _ in range(25):
        q, w = rigid.body.step_free_body("splitting4", I, q, w, 0.25 / 25)
    np.testing.assert_array_equal(q, out["q_wxyz"][0])
    np.testing.assert_array_equal(w, out["omega_body"][0])
    # the batch form is bitwise the scalar form, body by body
    qs = np.array([q0, [1.0, 0, 0, 0]])
    ws = np.array([W0, [0.3, -0.2, 0.1]])
    Is = np.array([I, [2.0, 2.0, 3.0]])
    qb, wb = rigid.body.step_free_bodies("splitting6", Is, qs, ws, 0.01)
    for k in range(2):
        qk, wk = rigid.body.step_free_body("splitting6", Is[k], qs[k], ws[k], 0.01)
        np.testing.assert_array_equal(qb[k], qk)
        np.testing.assert_array_equal(wb[k], wk)


def test_many_steps_of_many_bodies_are_the_single_steps_bitwise():
    """step_free_bodies(..., steps=k) is k calls of step_free_body on each body, bit for bit, for
    the splittings (four bodies at a time in vector registers, 7 bodies: a block of four and one
    of three) and a method stepped body by body; steps below 1 are refused."""
    rng = np.random.default_rng(7)
    sides = rng.uniform(0.1, 1.0, (7, 3))
    Is = np.stack([(sides[:, 1] ** 2 + sides[:, 2] ** 2) / 12, (sides[:, 0] ** 2 + sides[:, 2] ** 2) / 12,
                   (sides[:, 0] ** 2 + sides[:, 1] ** 2) / 12], axis=1)
    qs = rng.normal(size=(7, 4))
    qs /= np.linalg.norm(qs, axis=1, keepdims=True)
    ws = rng.uniform(-30.0, 30.0, (7, 3))  # some sub-flows turn by more than the series' 0.5 rad
    for method in ("splitting2", "splitting4", "splitting6", "rk4"):
        qb, wb = rigid.body.step_free_bodies(method, Is, qs, ws, 0.05, steps=9)
        for k in range(7):
            q, w = qs[k], ws[k]
            for _ in range(9):
                q, w = rigid.body.step_free_body(method, Is[k], q, w, 0.05)
            np.testing.assert_array_equal(qb[k], q, err_msg=f"{method} body {k}")
            np.testing.assert_array_equal(wb[k], w, err_msg=f"{method} body {k}")
    with pytest.raises(rigid.Error, match=re.escape("rigid.body.step_free_bodies(): steps is 0, expected a count "
                                                    "of at least 1")):
        rigid.body.step_free_bodies("splitting2", Is, qs, ws, 0.01, steps=0)


def test_rigid_body_step_keeps_momenta_and_follows_the_parabola():
    box = rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7)
    free = rigid.body.RigidBody(box)
    s = {"q_wxyz": np.array([1.0, 0, 0, 0]), "omega_body": np.array([0.3, 2.0, 0.1]),
         "p_world": np.array([1.0, 2.0, 3.0]), "v_world": np.array([0.5, 0, -1.0])}
    d0 = free.diagnose(**s)
    for k in range(100):
        s = free.step("splitting2", 0.01 * k, h=0.01, **s)
    d1 = free.diagnose(**s)
    # no load, no gravity: P and L are kept by each exact sub-flow, to round-off
    np.testing.assert_allclose(d1["momentum_world"], d0["momentum_world"], rtol=0, atol=16 * EPS)
    np.testing.assert_allclose(d1["angular_momentum_world"], d0["angular_momentum_world"], rtol=0,
                               atol=100 * 16 * EPS * np.linalg.norm(d0["angular_momentum_world"]))
    # uniform gravity: the kick is exact, so the COM follows p0 + v0 t + ½ g t² to round-off
    g = np.array([0, 0, -9.81])
    falling = rigid.body.RigidBody(box, g)
    s = {"q_wxyz": np.array([1.0, 0, 0, 0]), "omega_body": np.zeros(3), "p_world": np.zeros(3),
         "v_world": np.array([1.0, 0, 2.0])}
    for k in range(50):
        s = falling.step("splitting2", 0.02 * k, h=0.02, **s)
    t = 1.0
    np.testing.assert_allclose(s["p_world"], np.array([1.0, 0, 2.0]) * t + 0.5 * g * t * t, rtol=0, atol=1e-13)
    a, alpha = falling.acceleration(0.0, **s)
    np.testing.assert_array_equal(a, g)
    np.testing.assert_array_equal(alpha, np.zeros(3))


def test_euler_rhs_is_eulers_equations():
    w = np.array([0.3, -1.2, 0.7])
    tau = np.array([0.1, 0.2, -0.4])
    # I ω̇ = (I ω) × ω + τ, componentwise (Landau–Lifshitz §36)
    expected = (np.cross(I * w, w) + tau) / I
    np.testing.assert_allclose(rigid.body.euler_rhs(I, w, tau), expected, rtol=4 * EPS, atol=4 * EPS)
    assert rigid.body.rotational_energy(I, w) == pytest.approx(0.5 * np.sum(I * w * w), rel=4 * EPS)


def test_euler_arnold_on_so3_is_eulers_equations():
    # J = diag(J1, J2, J3) with I_1 = J_2 + J_3 (cyclic); M = hat(L), L = I ω
    J = np.array([0.5, 1.5, 2.5])
    I3 = np.array([J[1] + J[2], J[2] + J[0], J[0] + J[1]])
    w = np.array([0.3, -1.2, 0.7])
    M = hat(I3 * w)
    np.testing.assert_allclose(rigid.body.euler_arnold_velocity(J, M), hat(w), rtol=0, atol=4 * EPS)
    # Ṁ = [M, Ω] = hat(L × ω) = hat(I ω̇), with ω̇ from Euler's equations
    np.testing.assert_allclose(rigid.body.euler_arnold_rhs(J, M), hat(I3 * rigid.body.euler_rhs(I3, w)),
                               rtol=0, atol=16 * EPS)


def test_euler_arnold_so4_keeps_casimirs_and_matches_scipy():
    from scipy.integrate import solve_ivp
    J = np.array([1.0, 2.0, 3.0, 5.0])
    rng = np.random.default_rng(7)
    A = rng.normal(size=(4, 4))
    M0 = A - A.T

    def rhs(_t, y):  # the equations written out independently: Ω_ij = M_ij/(J_i + J_j), Ṁ = MΩ − ΩM
        M = y.reshape(4, 4)
        Om = M / (J[:, None] + J[None, :])
        return (M @ Om - Om @ M).ravel()

    ref = solve_ivp(rhs, (0, 1.0), M0.ravel(), rtol=1e-13, atol=1e-13, method="DOP853").y[:, -1].reshape(4, 4)
    M = M0
    for _ in range(1000):
        M = rigid.body.euler_arnold_rk4_step(J, M, 1e-3)
    # RK4 at h = 1e-3 over 1 s: global error O(h⁴) ~ 1e-12 of |M|
    np.testing.assert_allclose(M, ref, rtol=0, atol=1e-10 * np.abs(M0).max())
    # isospectral flow: tr(M²) and tr(M⁴) are Casimirs, kept to the same O(h⁴)
    for k in (2, 4):
        c0 = np.trace(np.linalg.matrix_power(M0, k))
        assert abs(np.trace(np.linalg.matrix_power(M, k)) - c0) < 1e-10 * abs(c0)
    np.testing.assert_allclose(M, -M.T, rtol=0, atol=1e-14 * np.abs(M0).max() * 1000)


def test_step_arguments_are_checked():
    with pytest.raises(rigid.Error, match=r"rigid\.body\.step_free_body\(\): step h must be positive and finite, got -0\.1 s"):
        rigid.body.step_free_body("rk4", I, [1, 0, 0, 0], W0, -0.1)
    with pytest.raises(rigid.Error, match=r"argument 'principal_moments': principal moments \(1, 2, 4\) kg·m² violate"):
        rigid.body.step_free_body("rk4", [1, 2, 4], [1, 0, 0, 0], W0, 0.1)
    top, q, w = spinning_top()
    with pytest.raises(rigid.Error, match=r"HeavyTop\.step\(\): step h must be positive and finite, got nan s"):
        top.step(q, w, float("nan"))
    with pytest.raises(rigid.Error, match="splitting2, splitting4 or splitting6|splitting"):
        top.step(q, w, 1e-3, "rk4")
    with pytest.raises(rigid.Error, match=r"rigid\.body\.euler_arnold_rk4_step\(\): step h must be positive"):
        rigid.body.euler_arnold_rk4_step([1.0, 2, 3], np.zeros((3, 3)), 0.0)
    assert rigid.body.method_order("splitting4") == 4
    with pytest.raises(rigid.Error, match=r"rigid\.body\.euler_arnold_rhs\(\): argument 'J' must have n ≥ 2 entries"):
        rigid.body.euler_arnold_rhs([1.0], [[0.0]])


def test_a_load_that_returns_garbage_is_named():
    box = rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7)
    args = ("splitting2", [1, 0, 0, 0], [0, 0, 1.0], [0, 0, 0], [0, 0, 0], 0.01, [0.1])
    body = rigid.body.RigidBody(box)
    body.add_load(lambda t, s: [1.0, 2.0, 3.0])
    with pytest.raises(rigid.Error, match=r"RigidBody\.add_load\(\): the wrench function must return \(force, "
                                          r"torque\), two 3-vectors; got \[1\.0, 2\.0, 3\.0\] at t = 0 s"):
        body.simulate(*args)
    body = rigid.body.RigidBody(box)
    body.add_load(lambda t, s: ([1.0, 2.0], [0, 0, 0]))
    with pytest.raises(rigid.Error, match=r"argument 'force \(returned by wrench\)' must have shape \(3,\); got \(2,\)"):
        body.simulate(*args)
    body = rigid.body.RigidBody(box)
    body.add_load(lambda t, s: ([np.nan, 0, 0], [0, 0, 0]))
    with pytest.raises(rigid.Error, match=r"load 0"):  # the library names the load and t
        body.simulate(*args)
    # a load that works: a constant world force F on the COM gives a = F/m exactly (splitting2's
    # kick is exact for a load that does not depend on the velocity)
    body = rigid.body.RigidBody(box)
    body.add_load(lambda t, s: ([2.0, 0, 0], [0, 0, 0]))
    out = body.simulate(*args)
    np.testing.assert_allclose(out["p_world"][-1], [0.5 * 1.0 * 0.1**2, 0, 0], rtol=1e-13)


# Times that are not finite, or so far that the phase of the motion has lost its fraction of a
# turn (beyond 1e15 rad), are refused with rigid.Error naming the function and 't' (before:
# NaN, or an internal error on a NaN quaternion).
def test_free_body_motion_refuses_a_non_finite_or_too_distant_time():
    e = rigid.body.FreeBodyExact(I, W0)
    with pytest.raises(rigid.Error, match=r"rigid\.body\.FreeBodyExact\.omega_body\(\): argument 't' "
                       r"must be a finite time \(s\); got nan"):
        e.omega_body(math.nan)
    with pytest.raises(rigid.Error, match=r"argument 't': time t = 1e\+300 s is too far"):
        e.omega_body(1e300)
    assert np.all(np.isfinite(e.omega_body(0.5 * e.max_time)))
    m = rigid.body.FreeBodyMotion(I, [1.0, 0.0, 0.0, 0.0], W0)
    with pytest.raises(rigid.Error, match=r"rigid\.body\.FreeBodyMotion\.orientation\(\): argument 't': "
                       r"time t = 1e\+300 s is too far"):
        m.orientation(1e300)
    with pytest.raises(rigid.Error, match=r"FreeBodyMotion\.omega_body\(\): argument 't' must be a finite"):
        m.omega_body(math.inf)
    with pytest.raises(TypeError, match=r"FreeBodyMotion\.orientation\(\): argument 't' must be a number"):
        m.orientation("soon")


def test_free_body_exact_refuses_an_energy_that_overflows():
    with pytest.raises(rigid.Error, match=r"initial body angular velocity \[1e\+200, 0, 0\] rad/s .* overflows"):
        rigid.body.FreeBodyExact(I, [1e200, 0.0, 0.0])


def test_steps_refuse_a_step_that_diverges():
    # RK4 with h |ω| = 1e200 overflows in its stages: refused, not returned as NaN
    with pytest.raises(rigid.Error, match=r"step_free_body\(\): the step of h = 1e\+100 s diverged"):
        rigid.body.step_free_body("rk4", I, [1.0, 0, 0, 0], [1e100, 1e100, 1e100], 1e100)
    with pytest.raises(rigid.Error, match=r"body 0: the step of h = 1e\+100 s diverged"):
        rigid.body.step_free_bodies("rk4", [I], [[1.0, 0, 0, 0]], [[1e100, 1e100, 1e100]], 1e100)
