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
