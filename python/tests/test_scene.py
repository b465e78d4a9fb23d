"""rigid.Scene: the scene files of examples/ from Python, against closed forms."""
import math
import pathlib

import numpy as np
import pytest

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def test_rolling_cylinder_from_python():
    s = rigid.Scene(str(EXAMPLES / "rolling_cylinder.toml"))
    assert s.kind == "coordinates" and s.integrator() == "rk4"
    assert s.parameters == {"g": 9.81, "alpha": 0.5, "m": 2.0, "r": 0.1}
    out = s.run()
    t, x = out["columns"]["t"], out["columns"]["s"]
    a = 2 / 3 * 9.81 * math.sin(0.5)
    # RK4 is exact on the quadratic s(t): round-off only
    np.testing.assert_allclose(x, a * t**2 / 2, atol=1e-11)
    assert out["summary"]["steps"] == 2000


def test_overrides_and_integrator():
    s = rigid.Scene(str(EXAMPLES / "atwood.toml"), set=["m2=3"])
    out = s.run(integrator="dopri5")
    assert out["summary"]["integrator"] == "dopri5"
    np.testing.assert_allclose(out["columns"]["y1"], 0, atol=1e-9)  # balanced machine


def test_free_body_scene_and_equations():
    s = rigid.Scene(str(EXAMPLES / "tennis_racket.toml"))
    assert s.kind == "free_bodies"
    assert "w1_dot" in s.equations()
    s.check()


def test_errors_carry_the_file_position(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text('[[coordinates]]\nname = "x"\n[[bodies]]\npoint_masses = [{mass = 1, position = [0, 0, 0]}]\n'
                 'position = ["y", 0, 0]\n[simulation]\nt_end = 1\n')
    with pytest.raises(rigid.Error, match=r"bad.toml:5:14: .*undefined symbol 'y'"):
        rigid.Scene(str(p))
    with pytest.raises(rigid.Error, match="has no parameter, setting or initial condition 'q'; did you mean 'g'"):
        rigid.Scene(str(EXAMPLES / "atwood.toml"), set=["q=1"])


LONG_RUN = """
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = 2, izz = 3}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 1e5
integrator = "splitting6"
dt = 1e-3
output_dt = 10
"""


def test_a_run_releases_the_gil(tmp_path):
    # while one thread runs a scene, another Python thread keeps running: the counter moves
    import threading
    import time

    scene = tmp_path / "long.toml"
    scene.write_text(LONG_RUN.replace("t_end = 1e5", "t_end = 3000"))  # ≈ 1 s of stepping
    model = rigid.Scene(scene)
    done = threading.Event()
    counts = []

    def count():
        n = 0
        while not done.is_set():
            n += 1
            time.sleep(0.001)
        counts.append(n)

    t = threading.Thread(target=count)
    t.start()
    start = time.monotonic()
    model.run()
    elapsed = time.monotonic() - start
    done.set()
    t.join()
    # with the GIL held the counter could not move during the run; released, it ticks about
    # once per millisecond (a loaded machine may slow it tenfold, not stop it)
    assert elapsed > 0.1 and counts[0] >= 20, (counts, elapsed)


def test_ctrl_c_stops_a_run_with_keyboard_interrupt_and_writes_nothing(tmp_path):
    import os
    import signal
    import threading

    scene = tmp_path / "long.toml"
    scene.write_text(LONG_RUN)
    model = rigid.Scene(scene)
    out = tmp_path / "out"
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt, match="cancelled at t = "):
            model.run(output=out)
    finally:
        timer.cancel()
    assert not out.exists()


def test_a_scene_from_text_and_a_path_that_is_never_parsed(tmp_path):
    text = (EXAMPLES / "atwood.toml").read_text()
    from_file = rigid.Scene(EXAMPLES / "atwood.toml").run()
    from_text = rigid.Scene.from_string(text).run()
    for name, column in from_file["columns"].items():
        np.testing.assert_array_equal(from_text["columns"][name], column)
    # overrides and errors: messages start with the name given (default <string>)
    assert rigid.Scene.from_string(text, set=["m2=3"]).parameters["m2"] == 3.0
    with pytest.raises(rigid.Error, match=r"^mine\.toml:1:"):
        rigid.Scene.from_string("[[coordinates]\n", name="mine.toml")
    with pytest.raises(rigid.Error, match=r"^<string>:1:"):
        rigid.Scene.from_string("[[coordinates]\n")
    # a str is a path: text passed as a path is refused with the remedy, not parsed
    with pytest.raises(rigid.Error, match=r"looks like TOML text: .*rigid\.Scene\.from_string\(text\)"):
        rigid.Scene(text)
    with pytest.raises(rigid.Error, match="missing.toml"):
        rigid.Scene(tmp_path / "missing.toml")
    with pytest.raises(TypeError, match=r"rigid\.Scene\(\): argument 'path' must be a path"):
        rigid.Scene(12)


def test_run_carries_the_scene_metrics():
    # [[output.metrics]] of tennis_racket.toml: the first zero crossing of ω_y (the flip) and the
    # energy drift. The flip from the closed form (rigid.body.FreeBodyExact, Jacobi elliptic
    # functions) by SciPy's brentq: independent of the run's splitting4 steps
    from scipy.optimize import brentq
    out = rigid.Scene(EXAMPLES / "tennis_racket.toml").run()
    metrics = out["summary"]["metrics"]
    assert set(metrics) == {"first_flip", "energy_drift"}
    exact = rigid.body.FreeBodyExact([1.0, 2.0, 3.0], [0.01, 1.0, 0.01])
    ts = np.linspace(0, 20, 2001)
    k = int(np.argmax([exact.omega_body(t)[1] < 0 for t in ts]))
    flip = brentq(lambda t: exact.omega_body(t)[1], ts[k - 1], ts[k], xtol=1e-14)
    assert metrics["first_flip"]["unit"] == "s"
    # the run's order-4 steps and its event interpolation: agreement to 1e-8 of the time
    assert metrics["first_flip"]["value"] == pytest.approx(flip, rel=1e-8)
    # the relative energy drift of a free body under splitting4: each sub-flow is an exact
    # rotation that keeps its axis' share of the energy, so only round-off remains (~1e-14)
    assert abs(metrics["energy_drift"]["value"]) < 1e-12
