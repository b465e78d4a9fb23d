"""rigid plot DIR --column NAME... -o FILE.svg: the SVG's points mapped back through the transform
written on its <svg> element equal the run's trajectory and the sweep's runs.csv values."""
import csv
import json
import math
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PENDULUM = os.path.join(ROOT, "examples", "physical_pendulum.toml")
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def dirs(tmp_path_factory, rigid_exe):
    base = tmp_path_factory.mktemp("plot")
    run_dir, sweep_dir, kept_dir = base / "run", base / "sweep", base / "kept"

    def rigid(*args):
        proc = subprocess.run([rigid_exe, *map(str, args)], capture_output=True, text=True,
                              timeout=120)
        assert proc.returncode == 0, proc.stderr

    # 0.5 s at the scene's 5 ms output spacing: 101 rows
    rigid("run", PENDULUM, "--set", "simulation.t_end=0.5", "-o", run_dir, "-q")
    # m = 1, 0.5, 0, -0.5: run 0 is valid, the runs of m <= 0 fail (a mass must be positive)
    rigid("sweep", PENDULUM, "--grid", "m=1:-0.5:4", "--grid", "L=0.5:2:3", "--set",
          "simulation.t_end=0.2", "-o", sweep_dir, "-q")
    rigid("sweep", PENDULUM, "--grid", "L=0.5:2:4", "--set", "simulation.t_end=0.2",
          "--keep-trajectories", "-o", kept_dir, "-q")
    return run_dir, sweep_dir, kept_dir


def plot(run, *args, check=True):
    proc = run("plot", *args)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


def parse(path):
    root = ET.parse(path).getroot()
    assert root.tag == f"{SVG}svg"
    x0, x1 = map(float, root.get("data-x-domain").split())
    y0, y1 = map(float, root.get("data-y-domain").split())
    left, top, width, height = map(float, root.get("data-plot-box").split())
    # the documented transform, inverted (docs/report.md, include/rigid/report/svg_plot.hpp)
    def to_data(px, py):
        return (x0 + (px - left) / width * (x1 - x0), y1 - (py - top) / height * (y1 - y0))
    # printed with 2 decimals: 0.005 units of round-off, and a little for the doubles' own
    tol = (0.0051 / width * (x1 - x0), 0.0051 / height * (y1 - y0))
    return root, to_data, tol


def series(root):
    return {g.get("data-label"): g for g in root.iter(f"{SVG}g") if g.get("class") == "series"}


def text_of(root, cls):
    return [t.text for t in root.iter(f"{SVG}text") if t.get("class") == cls]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_run_columns_map_back_to_the_trajectory(run, dirs, tmp_path):
    run_dir = dirs[0]
    out = tmp_path / "fig.svg"
    proc = plot(run, run_dir, "--column", "theta", "--column", "theta_dot", "-o", out)
    assert proc.stdout == f"wrote {out}\n"
    text = out.read_text()
    assert text.startswith('<?xml version="1.0"')
    root, to_data, (tol_x, tol_y) = parse(out)
    assert root.get("width") == "800" and root.get("height") == "500"
    assert root.get("viewBox") == "0 0 800 500"
    rows = read_csv(run_dir / "trajectory.csv")
    assert len(rows) == 101
    got = series(root)
    assert list(got) == ["theta", "theta_dot"]  # the schema states no unit for a coordinate
    for name, g in got.items():
        lines = g.findall(f"{SVG}polyline")
        assert len(lines) == 1
        points = [tuple(map(float, p.split(","))) for p in lines[0].get("points").split()]
        # 101 samples about 6 units apart: none is closer than half a unit to the one before
        assert len(points) == len(rows)
        for (px, py), row in zip(points, rows):
            x, y = to_data(px, py)
            assert abs(x - float(row["t"])) <= tol_x
            assert abs(y - float(row[name])) <= tol_y
    assert text_of(root, "x-label") == ["t (s)"]
    assert text_of(root, "y-label") == ["theta, theta_dot"]
    legend = [g.get("data-label") for g in root.iter(f"{SVG}g") if g.get("class") == "legend"]
    assert legend == ["theta", "theta_dot"]


def round_step(ticks):
    """The step of evenly spaced ticks, if it is 1, 2, 2.5 or 5 times a power of ten."""
    step = ticks[1] - ticks[0]
    for a, b in zip(ticks, ticks[1:]):
        assert b - a == pytest.approx(step, rel=1e-9)
    e = math.floor(math.log10(step))
    mantissa = step / 10 ** e
    assert any(mantissa == pytest.approx(m, rel=1e-9) for m in (1, 2, 2.5, 5, 10)), step
    return step


def test_axis_labels_carry_the_schema_units_and_ticks_are_round(run, dirs, tmp_path):
    run_dir = dirs[0]
    out = tmp_path / "pos.svg"
    plot(run, run_dir, "--column", "rod.x", "--column", "rod.z", "-o", out)
    root, _, _ = parse(out)
    assert text_of(root, "y-label") == ["rod.x, rod.z (m)"]
    assert text_of(root, "x-label") == ["t (s)"]
    assert list(series(root)) == ["rod.x (m)", "rod.z (m)"]
    summary = json.loads((run_dir / "summary.json").read_text())
    units = {c["name"]: c["unit"] for c in summary["schema"]["columns"]}
    assert units["rod.x"] == "m" and units["t"] == "s"
    rows = read_csv(run_dir / "trajectory.csv")
    x0, x1 = map(float, root.get("data-x-domain").split())
    y0, y1 = map(float, root.get("data-y-domain").split())
    for axis, lo, hi, values in (
            ("x-ticks", x0, x1, [float(r["t"]) for r in rows]),
            ("y-ticks", y0, y1, [float(r[c]) for r in rows for c in ("rod.x", "rod.z")])):
        g = next(g for g in root.iter(f"{SVG}g") if g.get("class") == axis)
        ticks = [float(t.get("data-value")) for t in g.iter(f"{SVG}text")]
        labels = [float(t.text) for t in g.iter(f"{SVG}text")]
        step = round_step(ticks)
        # every tick a multiple of the step, printed as its value, and the axis from the outer
        # ticks around all the data within one step
        for t, label in zip(ticks, labels):
            assert t / step == pytest.approx(round(t / step), abs=1e-9)
            assert label == pytest.approx(t, abs=step * 1e-9)
        assert (ticks[0], ticks[-1]) == (lo, hi)
        assert lo <= min(values) < lo + step and hi - step < max(values) <= hi
        assert 2 <= len(ticks) <= 9


def test_sweep_points_skip_failed_runs_and_say_so(run, dirs, tmp_path):
    sweep_dir = dirs[1]
    out = tmp_path / "sweep.svg"
    plot(run, sweep_dir, "--column", "energy_initial", "-o", out)
    root, to_data, (tol_x, tol_y) = parse(out)
    rows = read_csv(sweep_dir / "runs.csv")
    ok = [r for r in rows if not r["error"]]
    failed = len(rows) - len(ok)
    assert len(rows) == 12 and failed == 6  # m = 0 and m = -0.5, each with 3 lengths
    circles = series(root)["energy_initial (J)"].findall(f"{SVG}circle")  # summary.json's unit
    assert len(circles) == len(ok)
    for c, row in zip(circles, ok):
        x, y = to_data(float(c.get("cx")), float(c.get("cy")))
        assert abs(x - float(row["m"])) <= tol_x  # x: the first swept name
        assert abs(y - float(row["energy_initial"])) <= tol_y
    assert text_of(root, "x-label") == ["m"]
    assert f"{failed} of {len(rows)} runs failed (see runs.csv's error column), not shown" in \
        text_of(root, "note")
    # --x picks another swept name
    plot(run, sweep_dir, "--column", "energy_initial", "--x", "L", "-o", out)
    root, to_data, (tol_x, _) = parse(out)
    circles = series(root)["energy_initial (J)"].findall(f"{SVG}circle")  # summary.json's unit
    for c, row in zip(circles, ok):
        assert abs(to_data(float(c.get("cx")), 0)[0] - float(row["L"])) <= tol_x


def test_sweep_units_come_from_summary_json_or_a_kept_run_schema(run, dirs, tmp_path):
    # summary.json states the units of run 0's schema: no run needs to be kept
    out = tmp_path / "sweep.svg"
    plot(run, dirs[1], "--column", "energy_initial", "-o", out)
    assert text_of(parse(out)[0], "y-label") == ["energy_initial (J)"]
    # a summary.json without them (a sweep of an older rigid): the schema of a run it kept
    kept_dir = tmp_path / "kept"
    shutil.copytree(dirs[2], kept_dir)
    summary = json.loads((kept_dir / "summary.json").read_text())
    assert summary.pop("units")["energy_initial"] == "J"
    (kept_dir / "summary.json").write_text(json.dumps(summary))
    out = tmp_path / "kept.svg"
    plot(run, kept_dir, "--column", "energy_initial", "--column", "energy_final", "-o", out)
    root, _, _ = parse(out)
    assert text_of(root, "y-label") == ["energy_initial, energy_final (J)"]
    assert list(series(root)) == ["energy_initial (J)", "energy_final (J)"]
    # the period metric is NaN in runs of 0.2 s (no full swing): counted, not drawn
    plot(run, kept_dir, "--column", "period", "--column", "energy_initial", "-o", out)
    root, _, _ = parse(out)
    assert series(root)["period (s)"].findall(f"{SVG}circle") == []
    assert ("period: 4 of the 4 runs that succeeded have no finite value (NaN: e.g. an event "
            "that did not happen), not shown") in text_of(root, "note")


def test_unknown_column_is_refused_with_the_close_names(run, dirs, tmp_path):
    run_dir, sweep_dir, _ = dirs
    out = tmp_path / "x.svg"
    proc = plot(run, run_dir, "--column", "thet", "-o", out, check=False)
    assert proc.returncode == 1
    assert "--column 'thet': the run in" in proc.stderr
    assert "has no such column; did you mean 'theta', 'theta_dot'? Its columns are t, theta, " \
        "theta_dot, rod.x" in proc.stderr
    proc = plot(run, sweep_dir, "--column", "energy_intial", "-o", out, check=False)
    assert proc.returncode == 1
    assert "did you mean 'energy_initial'" in proc.stderr
    proc = plot(run, run_dir, "--column", "theta", "--x", "time", "-o", out, check=False)
    assert proc.returncode == 1
    # nothing close: the columns alone
    assert "--x 'time': the run in" in proc.stderr and "has no such column; its columns are t, " \
        "theta" in proc.stderr
    assert not out.exists()


def test_bad_outputs_and_directories_are_refused(run, rigid_exe, dirs, tmp_path):
    run_dir = dirs[0]
    proc = plot(run, run_dir, "--column", "theta", "-o", tmp_path / "fig.png", check=False)
    assert proc.returncode == 2 and "give a name ending in .svg" in proc.stderr
    proc = plot(run, run_dir, "-o", tmp_path / "fig.svg", check=False)
    assert proc.returncode == 2  # --column is required
    folder = tmp_path / "folder.svg"
    folder.mkdir()
    proc = plot(run, run_dir, "--column", "theta", "-o", folder, check=False)
    assert proc.returncode == 1 and "is a directory" in proc.stderr
    fifo = tmp_path / "pipe.svg"
    os.mkfifo(fifo)
    # opening a FIFO blocks until a reader comes: the timeout catches that
    proc = subprocess.run([rigid_exe, "plot", str(run_dir), "--column", "theta", "-o", str(fifo)],
                          capture_output=True, text=True, timeout=30)
    assert proc.returncode == 1 and "it is a FIFO (named pipe), not a regular file" in proc.stderr
    assert os.path.exists(fifo) and not os.path.isfile(fifo)
    empty = tmp_path / "empty"
    empty.mkdir()
    proc = plot(run, empty, "--column", "theta", "-o", tmp_path / "e.svg", check=False)
    assert proc.returncode == 1 and "is neither a run's directory" in proc.stderr
    # an existing SVG is replaced
    old = tmp_path / "old.svg"
    old.write_text("old")
    plot(run, run_dir, "--column", "theta", "-o", old)
    assert ET.parse(old).getroot().tag == f"{SVG}svg"
