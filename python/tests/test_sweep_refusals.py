"""rigid.sweep refuses, before any run, what every run of the sweep would refuse: run 0 (the
`set` values and each axis's first value) is built and checked as its run would be, with the
sweep's integrator and the scene's metrics; and its summary groups the failed runs by message."""
import pathlib

import pytest

import rigid

PENDULUM = pathlib.Path(__file__).resolve().parents[2] / "examples" / "physical_pendulum.toml"


@pytest.mark.parametrize("kwargs, scene_edit, message", [
    (dict(grid=["L=0.5:2:3"], integrator="rk5"), None, "unknown integrator 'rk5'"),
    (dict(grid=["L=0.5:2:3"]), ('column = "theta"', 'column = "thetaa"'), "the run has no column 'thetaa'"),
    (dict(grid=["L=0.5:2:3"], set=["m=-1"]), None, "mass must be positive and finite, got -1 kg"),
    (dict(grid=["m=-1:1:3"]), None, "mass must be positive and finite, got -1 kg"),
    (dict(sample=["L=uniform(-2,-1)"], samples=4), None, "length must be positive"),
])
def test_what_every_run_would_refuse_raises_before_any_run(tmp_path, kwargs, scene_edit, message):
    scene = PENDULUM
    if scene_edit:
        scene = tmp_path / "edited.toml"
        scene.write_text(PENDULUM.read_text().replace(*scene_edit))
    out = tmp_path / "out"
    with pytest.raises(rigid.Error, match="run 0 of the sweep .* is refused, so no run was started") as e:
        rigid.sweep(str(scene), output=str(out), **kwargs)
    assert message in str(e.value)
    assert not (out / "runs.csv").exists()


def test_failed_runs_are_grouped_by_message_in_the_summary():
    # m runs down from 1 to -1: run 0 is valid, the runs with m = 0 and m = -1 are refused by
    # their models, each with its own value in its message
    out = rigid.sweep(str(PENDULUM), grid=["m=1:-1:3"], set=["simulation.t_end=0.5"])
    errors = out["errors"]
    assert errors[0] == "" and "got 0 kg" in errors[1] and "got -1 kg" in errors[2]
    summary = out["summary"]
    assert summary["failures"] == 2
    assert summary["failure_groups"] == [{"message": errors[1], "count": 1, "runs": [1]},
                                         {"message": errors[2], "count": 1, "runs": [2]}]


# Values that underflow (subnormal or to 0), as axes, `set` values, sample ranges and expressions:
# each is a rigid.Error (a ValueError) naming the value, never a RuntimeError or another
# library's exception, and no run starts.
@pytest.mark.parametrize("kwargs", [
    dict(grid=["theta.initial=1e-309:2e-309:2"]),
    dict(grid=["g=1e-320:2e-320:2"]),
    dict(grid=["theta.initial=0.1:0.2:2"], set=["g=2.2250738585072014e-309"]),
    dict(grid=["theta.initial=0.1:0.2:2"], set=["L=1e-400"]),
    dict(grid=["theta.initial=0.1:0.2:2"], set=["g=exp(-800)"]),
    dict(grid=["theta.initial=0.1:0.2:2"], set=["g=1e-300*1e-10"]),
    dict(grid=["theta.initial=0.1:0.2:2"], set=["simulation.t_end=1e-320"]),
    dict(grid=["theta.initial=0.1:0.2:2"], set=["simulation.dt=1e-320"]),
    dict(sample=["g=uniform(1e-320,2e-320)"], samples=3),
])
def test_an_underflowing_value_is_a_rigid_error(tmp_path, kwargs):
    out = tmp_path / "out"
    with pytest.raises(rigid.Error) as e:
        rigid.sweep(str(PENDULUM), output=str(out), **kwargs)
    assert type(e.value) is rigid.Error
    assert "underflow" in str(e.value) or "evaluates to" in str(e.value)
    assert not (out / "runs.csv").exists()


def test_ctrl_c_stops_a_sweep_of_short_runs_with_keyboard_interrupt(tmp_path):
    # 200,000 runs of ~0.24 ms (~25 s on two threads): Ctrl-C after 0.3 s stops it within a
    # second (the signal is looked for every 20 ms, not for every row) and writes no outputs
    import os
    import signal
    import threading
    import time

    out = tmp_path / "out"
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            rigid.sweep(str(PENDULUM), grid=["theta.initial=0.1:2.5:200000"], set=["simulation.t_end=0.5"],
                        threads=2, output=str(out))
    finally:
        timer.cancel()
    assert time.monotonic() - start < 5.0  # a loaded machine's margin over the ~0.3 s expected
    assert not (out / "runs.csv").exists()
