"""rigid.integrate.solve: the library's integrators on a right-hand side written in Python,
against the harmonic oscillator's closed form, with measured orders of convergence."""
import math
import re

import numpy as np
import pytest

import rigid


def oscillator(_t, y):  # q̈ = −q: q = cos t, q̇ = −sin t from (1, 0)
    return np.array([y[1], -y[0]])


def error_at(method, dt, t_end=2.0):
    out = rigid.integrate.solve(oscillator, [1.0, 0.0], t_end, method=method, dt=dt, output_dt=t_end)
    assert out["t"].tolist() == [0.0, t_end]
    return np.max(np.abs(out["y"][-1] - [math.cos(t_end), -math.sin(t_end)]))


@pytest.mark.parametrize("method, order", [("rk4", 4), ("implicit_midpoint", 2), ("stormer_verlet", 2)])
def test_fixed_step_methods_converge_at_their_order(method, order):
    # the error ratio between dt and dt/2 is 2^p within ±10% (measured, not assumed)
    coarse, fine = error_at(method, 0.02), error_at(method, 0.01)
    assert 2**order * 0.9 < coarse / fine < 2**order * 1.1


def test_dopri5_meets_its_tolerance_and_samples_the_grid():
    out = rigid.integrate.solve(oscillator, np.array([1.0, 0.0]), 10.0, rtol=1e-12, atol=1e-12, output_dt=0.5)
    t = np.array(out["t"])
    np.testing.assert_allclose(t, np.linspace(0, 10, 21), rtol=0, atol=1e-15 * 10)
    # local tolerance 1e-12 over ~10 s of steps: the global error stays below 1e-9
    np.testing.assert_allclose(out["y"][:, 0], np.cos(t), rtol=0, atol=1e-9)
    assert out["rhs_evaluations"] > out["steps"] > 0
    assert "dopri5" in rigid.integrate.methods()


def test_bad_right_hand_sides_are_named():
    with pytest.raises(rigid.Error, match=r"non-finite state at step 1, t = 0\.001 s: v = nan"):
        rigid.integrate.solve(lambda t, y: np.array([0.0, np.nan]), [1.0, 0.0], 1.0, method="rk4", names=["q", "v"])
    with pytest.raises(rigid.Error, match=re.escape("rigid.integrate.solve(): rhs(t, y) must return dy/dt of shape "
                                                    "(2,), like y0; got shape (1,) at t = 0 s")):
        rigid.integrate.solve(lambda t, y: [1.0], [1.0, 0.0], 1.0)
    with pytest.raises(ZeroDivisionError):  # the function's own exception comes through unchanged
        rigid.integrate.solve(lambda t, y: 1 / 0, [1.0, 0.0], 1.0)
    with pytest.raises(rigid.Error, match="unknown integrator 'euler'; expected one of rk4, dopri5"):
        rigid.integrate.solve(oscillator, [1.0, 0.0], 1.0, method="euler")
    with pytest.raises(rigid.Error, match=r"rigid\.integrate\.solve\(\): argument 'y0' must be finite"):
        rigid.integrate.solve(oscillator, [np.inf, 0.0], 1.0)
