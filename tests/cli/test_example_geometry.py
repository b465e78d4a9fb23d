"""The example pendulums hang as drawn: a rod or cone that swings about a pivot at the world
origin has its body z axis along the line from the pivot to its centre at every output time
(the run's quaternion against its position). A rotation with the wrong sign keeps the period
(the inertia is symmetric about the swing axis) but draws the body crossing its own pivot line
and turns ω and L the wrong way, which only this test sees."""
import csv
import pathlib

import numpy as np
import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("scene, body", [
    ("physical_pendulum.toml", "rod"),
    ("graded_rod_pendulum.toml", "rod"),
    ("cone_pendulum.toml", "cone"),
])
def test_the_body_axis_points_at_the_pivot(run, tmp_path, scene, body):
    proc = run("run", EXAMPLES / scene, "-o", tmp_path / "out", "-q", "--set", "simulation.t_end=1")
    assert proc.returncode == 0, proc.stderr
    with open(tmp_path / "out" / "trajectory.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) > 10
    worst = 0.0
    for r in rows:
        w, x, y, z = (float(r[f"{body}.q{k}"]) for k in "wxyz")
        # R e_z of the unit quaternion (w, x, y, z)
        axis = np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
        p = np.array([float(r[f"{body}.{k}"]) for k in "xyz"])
        worst = max(worst, np.linalg.norm(np.cross(axis, p / np.linalg.norm(p))))
    # both are evaluated from the same angle in double precision: parallel to round-off
    assert worst < 1e-12, f"{scene}: the body axis is {worst} (sine of the angle) off the pivot line"
