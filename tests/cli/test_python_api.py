"""Python and the command line agree: a step taken from Python is the step `rigid run` takes
(a scene's trajectory rebuilt bit for bit from single steps), the same bad input is refused
with the same message, and a mesh measured by `rigid inertia FILE` and by
rigid.mesh.mass_properties(repair=True) gives the same numbers and says the same."""
import csv
import json
import math

import numpy as np
import pytest

import rigid

from test_surfaces import EXAMPLES

ROUND_OFF = 1e-12  # rigid::integrate::TimeGrid::kRoundOff


def read_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return {name: np.array([float(r[k]) for r in rows[1:]]) for k, name in enumerate(rows[0])}


def march(t_end, output_dt, h_max):
    """(t0, n, h) of every output interval, as rigid::integrate::march steps: the fewest equal
    steps no longer than h_max (include/rigid/integrate/march.hpp)."""
    whole = math.floor(t_end / output_dt * (1 + ROUND_OFF))
    grid = [min(t_end, k * output_dt) for k in range(whole + 1)]
    if grid[-1] < t_end:
        grid.append(t_end)
    for t0, t1 in zip(grid, grid[1:]):
        n = max(1, math.ceil((t1 - t0) / h_max * (1 - ROUND_OFF)))
        yield t0, n, (t1 - t0) / n


TOP = """gravity = [0, 0, -9.81]
[[bodies]]
name = "top"
free = true
inertia = {mass = 1.5, ixx = 0.04, iyy = 0.05, izz = 0.06}
initial_rotation = {axis = [0, 1, 0], angle = 0.3}
pivot = [0.2, 0, 0]
angular_velocity = [50, 0, 0]

[simulation]
t_end = 0.01
dt = 1e-4
output_dt = 0.002
"""


def test_heavy_top_steps_from_python_are_rigid_run_bit_for_bit(run, tmp_path):
    # a top whose moments about the pivot (0.04, 0.11, 0.12 kg·m²) ascend along x, y, z: its
    # principal frame is its body frame, where the scene steps it
    scene = tmp_path / "top.toml"
    scene.write_text(TOP)
    out = tmp_path / "out"
    run("run", scene, "-o", out, "--format", "csv", "--format", "json", "-q", check=True)
    cols = read_columns(out / "trajectory.csv")
    summary = json.loads((out / "summary.json").read_text())
    top = rigid.body.HeavyTop(rigid.Scene(scene).bodies["top"], [0.2, 0, 0], [0, 0, -9.81])
    np.testing.assert_array_equal(top.principal_axes, np.eye(3))
    # the first row is the initial state, printed in shortest round-trip form (exact)
    q = np.array([cols[f"top.q{c}"][0] for c in "wxyz"])
    w = np.array([cols[f"top.w{c}"][0] for c in "xyz"])
    k = 0
    for _t0, n, h in march(0.01, 0.002, summary["dt"]):
        for _ in range(n):
            q, w = top.step(q, w, h, summary["integrator"])
        k += 1
        # the file holds the quaternion with w ≥ 0 (q and −q are one rotation; negation is exact)
        row = np.array([cols[f"top.q{c}"][k] for c in "wxyz"])
        assert np.array_equal(q, row) or np.array_equal(-q, row)
        np.testing.assert_array_equal(w, [cols[f"top.w{c}"][k] for c in "xyz"])
    assert k == len(cols["t"]) - 1


def test_free_body_steps_from_python_are_rigid_run_bit_for_bit(run, tmp_path):
    scene = EXAMPLES / "tennis_racket.toml"
    run("run", scene, "--set", "simulation.t_end=0.2", "-o", tmp_path, "--format", "csv", "--format", "json",
        "-q", check=True)
    cols = read_columns(tmp_path / "trajectory.csv")
    summary = json.loads((tmp_path / "summary.json").read_text())
    body = rigid.body.RigidBody(rigid.Scene(scene).bodies["racket"])
    s = {"q_wxyz": np.array([1.0, 0, 0, 0]), "omega_body": np.array([0.01, 1, 0.01]), "p_world": np.zeros(3),
         "v_world": np.zeros(3)}
    k = 0
    for t0, n, h in march(0.2, 0.05, summary["dt"]):
        for j in range(n):
            s = body.step("splitting2", t0 + j * h, h=h, free_method=summary["integrator"], **s)
        k += 1
        np.testing.assert_array_equal(s["q_wxyz"], [cols[f"racket.q{c}"][k] for c in "wxyz"])
        np.testing.assert_array_equal(s["omega_body"], [cols[f"racket.w{c}"][k] for c in "xyz"])


@pytest.mark.parametrize("cli, python", [
    (["inertia", "cylinder", "--mass", "-1", "--radius", "0.1", "--height", "0.5"],
     lambda: rigid.mass.cylinder(mass=-1, radius=0.1, height=0.5)),
    (["inertia", "cylinder", "--mass", "2", "--radius", "nan", "--height", "0.5"],
     lambda: rigid.mass.solid_cylinder_with_mass(2.0, float("nan"), 0.5)),
    (["inertia", "box", "--density", "0", "--lx", "1", "--ly", "1", "--lz", "1"],
     lambda: rigid.mass.box(density=0.0, lx=1.0, ly=1.0, lz=1.0)),
])
def test_the_same_bad_input_gets_the_same_message(run, cli, python):
    err = run(*cli, check=False).stderr.strip()
    assert err.startswith("rigid: error: ")
    with pytest.raises(rigid.Error) as refused:
        python()
    assert str(refused.value) == err[len("rigid: error: "):]


def test_a_mesh_measured_by_the_cli_and_by_python_with_repair(run, tmp_path):
    # 0.2 × 0.3 × 0.1 m box with one triangle flipped: `rigid inertia FILE` repairs every file it
    # reads; Python refuses the mesh as it is and, with repair=True, gives the same numbers and
    # the same warning
    a, b, c = 0.2, 0.3, 0.1
    v = np.array([[(i & 1) * a, ((i >> 1) & 1) * b, ((i >> 2) & 1) * c] for i in range(8)])
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    f = np.array([t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))])
    f[4] = f[4][[0, 2, 1]]
    off = tmp_path / "flipped.off"
    off.write_text("OFF\n8 12 0\n" + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in v)
                   + "".join(f"3 {i} {j} {k}\n" for i, j, k in f))
    proc = run("inertia", off, "--density", 2700, "--format", "json", check=True)
    cli = json.loads(proc.stdout)
    mesh = rigid.mesh.read(off)
    with pytest.raises(rigid.Error, match=r"not consistently oriented .*rigid\.mesh\.repair\(mesh\)"):
        rigid.mesh.mass_properties(mesh, density=2700)
    mp, warnings = rigid.mesh.mass_properties(mesh, density=2700, repair=True)
    assert mp.mass == pytest.approx(2700 * a * b * c, rel=1e-12)  # 16.2 kg
    np.testing.assert_array_equal(np.array(cli["inertia"]), mp.inertia_com)
    np.testing.assert_array_equal(np.array(cli["com"]), mp.com)
    assert cli["mass"] == mp.mass
    assert warnings == ["flipped 1 triangle whose winding disagreed with their neighbours"]
    assert f"{off}: {warnings[0]}" in proc.stderr


def test_a_python_sweep_writes_what_rigid_sweep_writes(run, tmp_path):
    from scipy.special import ellipk
    pendulum = EXAMPLES / "physical_pendulum.toml"
    run("sweep", pendulum, "--grid", "L=0.5:2:4", "-o", tmp_path / "cli", "-q", check=True)
    out = rigid.sweep(pendulum, grid=["L=0.5:2:4"], threads=2, output=tmp_path / "py")
    for name in ("runs.csv", "runs.npy", "summary.json"):
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "py" / name).read_bytes(), name
    cols = out["columns"]
    np.testing.assert_array_equal(cols["L"], [0.5, 1.0, 1.5, 2.0])
    assert out["errors"] == [""] * 4
    # the period metric against the closed form of the rod swinging from one end (amplitude of
    # the scene's theta.initial): T = 4 K(sin²(θ₀/2)) √(2L/(3g)); dopri5's tolerance: 1e-8
    theta0 = rigid.Scene(pendulum).system.initial_q[0]
    for L, T in zip(cols["L"], cols["period"]):
        assert T == pytest.approx(4 * ellipk(math.sin(theta0 / 2) ** 2) * math.sqrt(2 * L / (3 * 9.81)), rel=1e-8)
    assert out["summary"] == json.loads((tmp_path / "cli" / "summary.json").read_text())
    with pytest.raises(rigid.Error, match=r"rigid\.sweep\(\): grid: .*L=0\.5:2"):
        rigid.sweep(pendulum, grid=["L=0.5:2"])
    with pytest.raises(rigid.Error, match="did you mean 'L'"):
        rigid.sweep(pendulum, grid=["LL=0.5:2:2"])


def test_docs_python_examples_run_and_its_table_names_exist(monkeypatch):
    import pathlib
    import re as _re
    root = EXAMPLES.parent
    text = (root / "docs" / "python-api.md").read_text()
    monkeypatch.chdir(root)
    for block in _re.findall(r"```python\n(.*?)```", text, flags=_re.S):
        exec(compile(block, "docs/python-api.md", "exec"), {"__name__": "docs"})
    # every Python name of the table "What is reachable" exists
    table = text[text.index("## What is reachable"):text.index("Left out")]
    rows = [r for r in table.splitlines()[3:] if r.startswith("| ")]
    assert len(rows) > 20
    for row in rows:
        for name in _re.findall(r"`(rigid\.[A-Za-z0-9_.]+)", row.split("|")[2]):
            obj = rigid
            for part in name.rstrip(".").split(".")[1:]:
                obj = getattr(obj, part)
