"""Run metrics ([[output.metrics]]) and `--set` for settings and initial conditions, through the
command line and Python: the same scene and overrides give the same numbers and the same
refusals on both surfaces."""
import json
import math
import pathlib
import tomllib

import pytest
from scipy.special import ellipk

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
PENDULUM = EXAMPLES / "physical_pendulum.toml"


def pendulum_period(theta0):
    """4 K(m) sqrt(2L/(3g)) with m = k² = sin²(θ0/2) (scipy's ellipk takes m), L and g read from
    the example itself (a thin rod about its end: θ̈ = −(3g/2L) sin θ)."""
    doc = tomllib.loads(PENDULUM.read_text())
    L, g = doc["parameters"]["L"], doc["parameters"]["g"]
    return 4 * ellipk(math.sin(theta0 / 2) ** 2) * math.sqrt(2 * L / (3 * g))


def run_summary(run, tmp_path, scene, *extra):
    out = tmp_path / "out"
    p = run("run", scene, "-o", out, *extra, check=True)
    return json.loads((out / "summary.json").read_text()), p.stdout


# The acceptance: the period metric of the example, at several amplitudes set from the
# command line, matches the elliptic integral to 1e-8 relative (dopri5 at the example's 1e-12,
# crossings located on its dense output; measured ~1e-11).
@pytest.mark.parametrize("theta0", [0.1, 0.8, 1.6, 2.2, 2.5])
def test_pendulum_period_metric_is_the_elliptic_integral(run, tmp_path, theta0):
    summary, stdout = run_summary(run, tmp_path, PENDULUM, "--set", f"theta.initial={theta0}")
    period = summary["metrics"]["period"]
    assert period["unit"] == "s"
    expected = pendulum_period(theta0)
    assert abs(period["value"] - expected) <= 1e-8 * expected
    assert summary["parameters"]["L"] == 1.0
    # the printed summary has it with its unit, to 10 digits
    line = next(l for l in stdout.splitlines() if l.split()[:1] == ["period"])
    assert line.split()[2] == "s" and abs(float(line.split()[1]) - expected) <= 1e-8 * expected


def test_python_gives_the_same_metrics_as_the_command_line(run, tmp_path):
    summary, _ = run_summary(run, tmp_path, PENDULUM, "--set", "theta.initial=2.0",
                             "--set", "simulation.t_end=4")
    py = rigid.Scene(str(PENDULUM), set=["theta.initial=2.0", "simulation.t_end=4"]).run()
    assert py["summary"]["t_end"] == 4.0 == summary["t_end"]
    # the same run on both surfaces: the same double
    assert py["summary"]["metrics"]["period"]["value"] == summary["metrics"]["period"]["value"]
    assert py["summary"]["metrics"]["period"]["unit"] == "s"


def test_a_coordinate_named_alone_says_how_to_set_it_on_every_surface(run):
    p = run("run", PENDULUM, "--set", "theta=0.2", check=False)
    expected = "override 'theta=0.2': 'theta' is a coordinate: set 'theta.initial' or 'theta.velocity'"
    assert p.returncode == 1 and f"rigid: error: --set: {expected}" in p.stderr
    for command in ("check", "eom"):
        assert expected in run(command, PENDULUM, "--set", "theta=0.2", check=False).stderr
    with pytest.raises(rigid.Error, match=r"'theta' is a coordinate: set 'theta.initial'"):
        rigid.Scene(str(PENDULUM), set=["theta=0.2"])
    p = run("check", PENDULUM, "--set", "simulation.t_edn=3", check=False)
    assert "did you mean 'simulation.t_end'?" in p.stderr


def test_settings_from_the_command_line_are_checked_like_the_file(run):
    p = run("check", PENDULUM, "--set", "simulation.t_end=-1", check=False)
    assert p.returncode == 1
    assert "override 'simulation.t_end=-1'" in p.stderr and "t_end must be positive" in p.stderr


def test_racket_first_flip_and_free_body_override(run, tmp_path):
    racket = EXAMPLES / "tennis_racket.toml"
    summary, stdout = run_summary(run, tmp_path, racket, "--set", "racket.omega=[0.01,1,0.01]",
                                  "--set", "simulation.t_end=20")
    # the closed form of the example's comment (ω_y = b sn(λt + u0 | k²), zero at λt + u0 = 2K)
    I1, I2, I3, w1, w2, w3 = 1, 2, 3, 0.01, 1, 0.01
    E2 = I1 * w1 ** 2 + I2 * w2 ** 2 + I3 * w3 ** 2
    L2 = (I1 * w1) ** 2 + (I2 * w2) ** 2 + (I3 * w3) ** 2
    lam = math.sqrt((I3 - I2) * (L2 - E2 * I1) / (I1 * I2 * I3))
    k2 = (I2 - I1) * (E2 * I3 - L2) / ((I3 - I2) * (L2 - E2 * I1))
    b = math.sqrt((E2 * I3 - L2) / (I2 * (I3 - I2)))
    from scipy.special import ellipkinc
    u0 = ellipkinc(math.asin(w2 / b), k2)
    expected = (2 * ellipk(k2) - u0) / lam
    # splitting4 at h = 1e-3 s and the cubic between steps: ~1e-11 relative; 1e-8 asserted
    assert abs(summary["metrics"]["first_flip"]["value"] - expected) <= 1e-8 * expected
    assert "first_flip" in stdout and "energy_drift" in stdout
    # a free body's vector of the wrong size
    p = run("check", racket, "--set", "racket.omega=[1,2]", check=False)
    assert "racket.angular_velocity has 2 elements; expected 3 numbers" in p.stderr


def test_an_event_that_did_not_happen_is_nan_with_a_note(run, tmp_path):
    scene = tmp_path / "p.toml"
    scene.write_text(PENDULUM.read_text() + """
[[output.metrics]]
name = "tenth_zero"
kind = "crossing"
column = "theta"
k = 10
""")
    summary, stdout = run_summary(run, tmp_path, scene, "--set", "simulation.t_end=1")
    m = summary["metrics"]["tenth_zero"]
    assert m["value"] is None and "crossing 10 did not happen" in m["note"]
    assert "tenth_zero" in stdout and "nan (" in stdout
    py = rigid.Scene(str(scene), set=["simulation.t_end=1"]).run()["summary"]["metrics"]["tenth_zero"]
    assert math.isnan(py["value"]) and py["note"] == m["note"]


def test_a_metric_on_a_column_that_does_not_exist_is_refused_with_its_place(run, tmp_path):
    scene = tmp_path / "p.toml"
    text = PENDULUM.read_text() + '\n[[output.metrics]]\nname = "bad"\nkind = "max"\ncolumn = "thetta"\n'
    scene.write_text(text)
    line = text.splitlines().index('column = "thetta"') + 1
    p = run("check", scene, check=False)
    assert p.returncode == 1
    assert f"p.toml:{line}:10: [[output.metrics]] 'bad': the run has no column 'thetta'; did you mean 'theta'?" in p.stderr
    with pytest.raises(rigid.Error, match="the run has no column 'thetta'"):
        rigid.Scene(str(scene))
    scene.write_text(PENDULUM.read_text() + '\n[[output.metrics]]\nname = "bad"\nkind = "peroid"\ncolumn = "theta"\n')
    assert "unknown kind 'peroid'; did you mean 'period'?" in run("check", scene, check=False).stderr


# The double pendulum starts at the potential's zero at rest: E(0) is the round-off of 0 (cos of
# the double nearest π/2 is 6e-17), and a relative drift would divide by it. The metric is then
# the absolute change, in J, with a note; its value is recomputed here from trajectory.csv's
# energy column (the same samples), so the test fails if the rule divides by E(0).
def test_drift_of_an_energy_that_starts_at_zero_is_absolute(run, tmp_path):
    scene = tmp_path / "double_pendulum.toml"
    scene.write_text((EXAMPLES / "double_pendulum.toml").read_text()
                     + '\n[[output.metrics]]\nname = "e_drift"\nkind = "drift"\ncolumn = "energy"\n')
    summary, _ = run_summary(run, tmp_path, scene, "--set", "simulation.t_end=2")
    m = summary["metrics"]["e_drift"]
    assert m["unit"] == "J" and "absolute change" in m["note"]
    rows = (tmp_path / "out" / "trajectory.csv").read_text().splitlines()
    col = rows[0].split(",").index("energy")
    e = [float(r.split(",")[col]) for r in rows[1:]]
    assert abs(e[0]) < 1e-12  # the premise: E(0) is round-off
    # the same samples: the same max, to the csv's shortest round-trip printing (exact)
    assert m["value"] == max(abs(x - e[0]) for x in e)
    assert 1e-6 < m["value"] < 1e-2  # implicit midpoint at dt = 1e-3: a bounded error ~6e-4 J
