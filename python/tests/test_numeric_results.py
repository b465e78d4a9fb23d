"""Every numeric result is a numpy array: no list of floats comes out of a representative call
of each function that returns sample times, energies or other series."""
import math
import pathlib

import numpy as np

import rigid

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "physical_pendulum.toml"


def lists_of_numbers(value, path="result"):
    """Where `value` (a result: dicts, tuples, lists nested) holds a list or tuple of numbers."""
    found = []
    if isinstance(value, dict):
        for k, v in value.items():
            found += lists_of_numbers(v, f"{path}[{k!r}]")
    elif isinstance(value, (list, tuple)):
        if value and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in value):
            found.append(path)
        for k, v in enumerate(value):
            found += lists_of_numbers(v, f"{path}[{k}]")
    return found


def results():
    box = rigid.mass.box(mass=2.0, lx=0.3, ly=0.5, lz=0.7)
    I = np.array([1.0, 2.0, 3.0])
    top = rigid.body.HeavyTop(rigid.mass.solid_cone_with_mass(1.0, 0.05, 0.2), [0, 0, 0.2])
    q0 = np.array([math.cos(0.15), math.sin(0.15), 0, 0])
    net = rigid.spring.network_with_inertia(box, 1e4)
    pendulum = rigid.lagrange.System(coordinates=[("theta", 0.5, 0.0)],
                                     parameters={"m": 2.0, "l": 0.5, "g": 9.81},
                                     lagrangian="m*l^2/2*theta_dot^2 + m*g*l*cos(theta)")
    yield "integrate.solve", rigid.integrate.solve(lambda t, y: [y[1], -y[0]], [1.0, 0.0], 0.1,
                                                   method="rk4", dt=0.01)
    yield "integrate.solve dopri5", rigid.integrate.solve(lambda t, y: -y, [1.0], 0.1)
    yield "body.simulate_free_body", rigid.body.simulate_free_body("splitting4", I, [1, 0, 0, 0],
                                                                   [0.1, 1.0, 0.1], 0.01, [0.05, 0.1])
    yield "body.RigidBody.simulate", rigid.body.RigidBody(box).simulate(
        "splitting2", (1, 0, 0, 0), (0, 0, 1), (0, 0, 0), (0, 0, 0), 1e-3, [0.01, 0.02])
    yield "body.HeavyTop.simulate", top.simulate(q0, [0, 0, 200.0], 1e-4, [0.001, 0.002])
    yield "body.HeavyTop.step", top.step(q0, np.array([0, 0, 200.0]), 1e-4, "splitting4")
    yield "spring.Network.simulate", net.simulate(1e-4, [1e-3, 2e-3])
    yield "lagrange.System.simulate", pendulum.simulate(0.1, output_dt=0.05)
    yield "MassProperties.principal_axes", box.principal_axes()
    yield "Scene.run", rigid.Scene(EXAMPLE).run()
    yield "sweep", rigid.sweep(str(EXAMPLE), grid=["L=0.5:2:2"])


def test_every_numeric_result_is_an_array():
    offenders = []
    for name, value in results():
        offenders += [f"{name}: {where}" for where in lists_of_numbers(value)]
    assert not offenders, "lists of numbers where numpy arrays belong:\n" + "\n".join(offenders)


def test_solve_times_are_a_float_array():
    out = rigid.integrate.solve(lambda t, y: [y[1], -y[0]], [1.0, 0.0], 0.1, method="rk4", dt=0.01)
    assert isinstance(out["t"], np.ndarray) and out["t"].dtype == np.float64
    assert out["t"].shape == (out["y"].shape[0],)
    # rk4 with dt = 0.01 to 0.1: eleven samples at k·0.01 (the grid t0 + k·dt, to rounding)
    assert np.allclose(out["t"], np.linspace(0, 0.1, 11), rtol=0, atol=1e-15)
