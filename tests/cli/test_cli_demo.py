"""`rigid demo` prints computed numbers; check them against independent closed forms."""
import csv
import json
import math
import pathlib
import re

import numpy as np

from scipy.special import ellipk


def _racket_period(I, w):
    # Free asymmetric body, Landau & Lifshitz §37, I1 < I2 < I3, 2E = Σ I_i w_i²,
    # L² = Σ I_i² w_i². The formulas below are the branch L² > 2E I2.
    I1, I2, I3 = I
    E2 = sum(i * x * x for i, x in zip(I, w))
    L2 = sum(i * i * x * x for i, x in zip(I, w))
    assert L2 > E2 * I2
    lam = math.sqrt((I3 - I2) * (L2 - E2 * I1) / (I1 * I2 * I3))
    m = (I2 - I1) * (E2 * I3 - L2) / ((I3 - I2) * (L2 - E2 * I1))
    return 4 * ellipk(m) / lam


def test_demo_tennis_racket_matches_elliptic_period(run, tmp_path):
    p = run("demo", check=True, cwd=tmp_path)
    period = float(re.search(r"4K\(k\)/lambda = ([0-9.]+) s", p.stdout).group(1))
    expected = _racket_period((1.0, 2.0, 3.0), (0.01, 1.0, 0.01))
    # printed with 6 decimals: half a unit in the last place
    assert abs(period - expected) <= 5e-7 + 1e-12 * expected
    flips = [float(x) for x in re.findall(r"t = +([0-9.]+) s +exact", p.stdout)]
    assert len(flips) == 3
    # successive flips are half a period apart (printed with 5 decimals)
    for a, b in zip(flips, flips[1:]):
        assert abs((b - a) - expected / 2) < 2e-5
    drift = re.search(r"energy drift (\S+) J, \|L\| drift (\S+) kg", p.stdout)
    # splitting4 at h = 0.01 s: |L| is kept to round-off (every sub-flow is a rotation),
    # the energy error is bounded at O(h^4) = 1e-8 times the energy (about 1 J)
    assert abs(float(drift.group(1))) < 1e-9 and abs(float(drift.group(2))) < 1e-12


def test_demo_writes_its_scene_and_outputs(run, tmp_path):
    run("demo", check=True, cwd=tmp_path)
    out = tmp_path / "rigid-demo"
    summary = json.loads((out / "summary.json").read_text())
    assert summary["integrator"] == "splitting4" and summary["t_end"] == 60.0
    with open(out / "trajectory.csv", newline="") as f:
        rows = list(csv.reader(f))
    data = np.array(rows[1:], dtype=float)
    assert np.array_equal(np.load(out / "trajectory.npy"), data)
    wy = data[:, rows[0].index("racket.wy")]
    assert np.count_nonzero(np.signbit(wy[:-1]) != np.signbit(wy[1:])) == 3
    # the scene written next to the outputs runs again to the same trajectory
    run("run", out / "tennis_racket.toml", "-o", tmp_path / "again", "-q", check=True, cwd=tmp_path)
    again = np.loadtxt(tmp_path / "again" / "trajectory.csv", delimiter=",", skiprows=1)
    assert np.array_equal(again, data)


def test_demo_from_the_build_directory_uses_the_source_trees_examples(run, tmp_path):
    # the rigid of a build directory has no <prefix>/share next to it: the source tree's
    # examples, and the command the tour suggests runs as printed
    examples = pathlib.Path(__file__).resolve().parents[2] / "examples"
    p = run("demo", "--no-report", check=True, cwd=tmp_path)
    assert f"Example scenes: {examples}\n" in p.stdout
    scene = re.search(r"Try: rigid run (\S+) -o out/atwood", p.stdout).group(1)
    assert pathlib.Path(scene) == examples / "atwood.toml"
    run("check", scene, check=True)
