"""The report page (docs/report.md): `rigid run --report`, `rigid report DIR`, `rigid demo` and
Python's Scene.run(report=...) write one self-contained page whose data are the run's numbers."""
import base64
import json
import pathlib
import re
import struct

import numpy as np
import pytest

import rigid

ROOT = pathlib.Path(__file__).resolve().parents[2]
RACKET = ROOT / "examples" / "tennis_racket.toml"

# float32 rounding to nearest changes a value by at most 2^-24 of it; 2^-23 leaves one bit for
# the values computed in double before the rounding (a COM from a pose)
F32 = 2.0 ** -23


def page_data(path):
    text = pathlib.Path(path).read_text(encoding="utf-8")
    m = re.search(r'<script type="application/json" id="rigid-report-data">(.*?)</script>', text, re.S)
    assert m, "the page has no data element"
    return json.loads(m.group(1))


def floats(value):
    """A schema-v1 numeric array: a plain list, or "f32:BASE64" (little-endian float32)."""
    if isinstance(value, list):
        return np.array(value, dtype=float)
    assert value.startswith("f32:")
    raw = base64.b64decode(value[4:])
    return np.array(struct.unpack(f"<{len(raw) // 4}f", raw), dtype=float)


def trajectory(directory):
    csv = pathlib.Path(directory) / "trajectory.csv"
    names = csv.read_text().splitlines()[0].split(",")
    return names, np.loadtxt(csv, delimiter=",", skiprows=1, ndmin=2)


def kept_rows(n, max_frames):
    # the rule of docs/report.md: k = ceil((n-1)/(M-1)), rows 0, k, 2k, ... and the last
    k = 1 if n <= max_frames else -(-(n - 1) // (max_frames - 1))
    rows = list(range(0, n, k))
    if rows[-1] != n - 1:
        rows.append(n - 1)
    return rows


def test_racket_page_is_small_offline_and_holds_the_run(run, tmp_path):
    out = tmp_path / "racket"
    run("run", RACKET, "--report", "-o", out, "-q", check=True)
    page = out / "report.html"
    raw = page.read_bytes()
    assert len(raw) <= 2 * 1024 * 1024, f"{len(raw)} bytes"
    # the whole page, script and style included, names no network resource
    assert b"http://" not in raw and b"https://" not in raw
    assert raw.startswith(b'<!doctype html><html lang="en"><head><meta charset="utf-8"><title>rigid')
    d = page_data(page)
    assert d["rigid_report"] == 1 and d["kind"] == "free_bodies"
    assert d["scene"]["name"] == "tennis_racket"
    names, data = trajectory(out)
    rows = kept_rows(len(data), 2000)
    assert d["frames"]["count"] == len(rows) <= 2000
    t = data[rows, names.index("t")]
    assert np.allclose(floats(d["frames"]["t"]), t, rtol=F32, atol=0)
    # the racket's COM is its body origin (explicit inertia, com = 0): the pose columns
    pos = floats(d["frames"]["bodies"][0]["position"]).reshape(-1, 3)
    for k, c in enumerate(("racket.x", "racket.y", "racket.z")):
        assert np.allclose(pos[:, k], data[rows, names.index(c)], rtol=F32, atol=0)
    quat = floats(d["frames"]["bodies"][0]["quaternion"]).reshape(-1, 4)
    for k, c in enumerate(("racket.qw", "racket.qx", "racket.qy", "racket.qz")):
        assert np.allclose(quat[:, k], data[rows, names.index(c)], rtol=F32, atol=0)
    series = {s["name"]: s for s in d["series"]}
    for c in ("racket.wx", "racket.wy", "racket.wz", "energy"):
        assert np.allclose(floats(series[c]["values"]), data[rows, names.index(c)], rtol=F32, atol=0)
    # the relative energy error: |E - E0| / |E0| of the kept rows
    e = data[rows, names.index("energy")]
    rel = np.abs(e - e[0]) / abs(e[0])
    got = [s for s in d["series"] if s["group"] == "energy_error"][0]
    assert np.allclose(floats(got["values"]), rel, rtol=F32, atol=0)
    assert d["bodies"][0]["principal_moments"] == [1.0, 2.0, 3.0]


def test_report_of_an_earlier_run_is_the_same_page(run, tmp_path):
    out = tmp_path / "pend"
    scene = ROOT / "examples" / "double_pendulum.toml"
    run("run", scene, "--report", "-o", out, "-q", "--set", "m2=2", check=True)
    first = page_data(out / "report.html")
    p = run("report", out, "-o", tmp_path / "again.html", check=True)
    assert "again.html" in p.stdout
    again = page_data(tmp_path / "again.html")
    # the same data: the summary's numbers (wall time included) and the --set value
    assert again == first
    assert {"name": "m2", "value": 2.0, "unit": ""} in again["parameters"]
    assert again["kind"] == "coordinates" and again["frames"]["bodies"][0]["omega"] is None


def test_report_refuses_what_it_cannot_read(run, tmp_path):
    p = run("report", tmp_path / "nothing", check=False)
    assert p.returncode == 1 and "is not a directory" in p.stderr
    out = tmp_path / "run"
    run("run", RACKET, "-o", out, "-q", "--format", "json", check=True)
    p = run("report", out, check=False)
    assert p.returncode == 1 and "trajectory.csv' is missing" in p.stderr
    (out / "summary.json").unlink()
    p = run("report", out, check=False)
    assert p.returncode == 1 and "summary.json' is missing" in p.stderr


# A count in summary.json that is no whole number >= 0 (5.5e66 is a float to the JSON reader,
# and its conversion to a count was undefined behaviour; -1 became 2^64 - 1) is refused by name.
@pytest.mark.parametrize("steps", ["5.5e66", "-1", "2.5"])
def test_report_refuses_a_count_that_is_not_a_whole_number(run, tmp_path, steps):
    out = tmp_path / "run"
    run("run", RACKET, "-o", out, "-q", check=True)
    summary = out / "summary.json"
    text = summary.read_text()
    assert re.search(r'"steps": \d+', text)
    summary.write_text(re.sub(r'"steps": \d+', f'"steps": {steps}', text, count=1))
    p = run("report", out, check=False)
    assert p.returncode == 1, p.stderr
    assert '"steps" has the wrong type; expected the summary.json a run writes' in p.stderr, p.stderr


def test_report_frames_are_checked_and_obeyed(run, tmp_path):
    p = run("run", RACKET, "--report", "--report-frames", "1", "-o", tmp_path / "a", check=False)
    assert p.returncode == 2 and "--report-frames 1: expected a number of frames from 2 to 1000000" in p.stderr
    # 0 is no default in disguise, and −1 no longer wraps to 2^64 − 1
    p = run("run", RACKET, "--report", "--report-frames", "0", "-o", tmp_path / "a", check=False)
    assert p.returncode == 2 and "--report-frames 0: expected a number of frames from 2" in p.stderr
    for bad in ["-1", "abc", "2.5"]:
        p = run("run", RACKET, "--report", "--report-frames", bad, "-o", tmp_path / "a", check=False)
        assert p.returncode == 2 and f"--report-frames {bad}: the number of frames must be a whole number" in p.stderr
    p = run("run", RACKET, "--report-frames", "10", "-o", tmp_path / "b", check=False)
    assert p.returncode == 2 and "give --report with it" in p.stderr
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()
    run("run", RACKET, "--report", "--report-frames", "100", "-o", tmp_path / "c", "-q", check=True)
    d = page_data(tmp_path / "c" / "report.html")
    assert d["frames"]["count"] == len(kept_rows(2001, 100)) <= 100
    assert d["frames"]["rule"] == "every 21st of 2001 samples, and the last (at most 100 frames)"


def test_cli_and_python_write_the_same_report(run, tmp_path):
    scene = ROOT / "examples" / "heavy_top.toml"
    run("run", scene, "--report", "-o", tmp_path / "cli", "-q", check=True)
    r = rigid.Scene(scene).run(output=tmp_path / "py", report=True)
    assert r["report"] == str(tmp_path / "py" / "report.html")
    cli, py = page_data(tmp_path / "cli" / "report.html"), page_data(tmp_path / "py" / "report.html")
    cli["integrator"].pop("wall_time_s")
    py["integrator"].pop("wall_time_s")
    assert cli == py
    # the page alone, at a path of its own
    r = rigid.Scene(scene).run(report=tmp_path / "alone.html")
    alone = page_data(tmp_path / "alone.html")
    alone["integrator"].pop("wall_time_s")
    assert alone == cli
    with pytest.raises(rigid.Error, match="give output= too"):
        rigid.Scene(scene).run(report=True)
    with pytest.raises(rigid.Error, match="report_frames = 1: expected a number of frames from 2"):
        rigid.Scene(scene).run(report=tmp_path / "x.html", report_frames=1)


def sphere_stl(path, n):
    """A closed UV sphere of radius 0.1 m with 2 n (n - 1) triangles, as binary STL."""
    lat = np.linspace(0, np.pi, n + 1)
    lon = np.linspace(0, 2 * np.pi, n, endpoint=False)
    # the vertex of latitude ring i and meridian j (j mod n)
    def p(i, j):
        i, j = np.asarray(i), np.asarray(j) % n
        return np.stack([0.1 * np.sin(lat[i]) * np.cos(lon[j]), 0.1 * np.sin(lat[i]) * np.sin(lon[j]),
                         0.1 * np.cos(lat[i])], axis=-1)
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    i, j = i.ravel(), j.ravel()
    top = i > 0          # (a, b, d): not at the north pole, where a = d
    bottom = i < n - 1   # (b, c, d): not at the south pole, where b = c
    tris = np.concatenate([
        np.stack([p(i[top], j[top]), p(i[top] + 1, j[top]), p(i[top], j[top] + 1)], axis=1),
        np.stack([p(i[bottom] + 1, j[bottom]), p(i[bottom] + 1, j[bottom] + 1), p(i[bottom], j[bottom] + 1)], axis=1),
    ])
    record = np.zeros(len(tris), dtype=[("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    record["v"] = tris
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", len(tris)))
        f.write(record.tobytes())
    return len(tris)


def test_ten_bodies_with_a_large_mesh_stay_under_ten_megabytes(run, tmp_path):
    triangles = sphere_stl(tmp_path / "ball.stl", 225)
    assert triangles >= 100_000
    bodies = "".join(f"""
[[bodies]]
name = "b{i}"
free = true
mesh = "ball.stl"
density = 1000
initial_position = [{i}, 0, 0]
angular_velocity = [0.1, {1 + i / 10}, 0.1]
""" for i in range(10))
    scene = tmp_path / "ten.toml"
    # 10^5 steps (dt = 1 ms to 100 s), one output row per 50 ms: 2001 samples, all kept with
    # --report-frames 2001. The page's size depends on the frames it keeps, not on the steps or
    # the samples: a run with more samples keeps at most 2000 (the default), so this page is at
    # least as large as the default's of any run of these bodies (fewer samples keep the test
    # short: the trajectory.csv of 10^5 rows alone would take seconds to write)
    scene.write_text(bodies + "\n[simulation]\nt_end = 100.0\ndt = 0.001\noutput_dt = 0.05\n")
    run("run", scene, "--report", "--report-frames", "2001", "-o", tmp_path / "out", "-q", check=True)
    page = tmp_path / "out" / "report.html"
    size = page.stat().st_size
    assert size <= 10 * 1024 * 1024, f"{size} bytes"
    d = page_data(page)
    assert len(d["meshes"]) == 1 and d["meshes"][0]["triangles"] == triangles
    assert all(b["shape"]["mesh"] == 0 for b in d["bodies"])
    assert d["integrator"]["steps"] == 100_000 and d["frames"]["count"] == 2001


def test_demo_writes_a_report_and_says_where(run, tmp_path):
    p = run("demo", check=True, cwd=tmp_path)
    page = tmp_path / "rigid-demo" / "report.html"
    assert f"report: {page}" in p.stdout
    d = page_data(page)
    assert d["scene"]["name"] == "tennis_racket"
    run("demo", "--no-report", check=True, cwd=tmp_path / "rigid-demo" / "..")
    assert not page.exists()


def test_a_scene_that_drops_the_poses_has_no_report(run, tmp_path):
    scene = tmp_path / "racket.toml"
    scene.write_text(RACKET.read_text() + '\n[output]\nquantities = ["racket.w*"]\n')
    p = run("run", scene, "--report", "-o", tmp_path / "out", check=False)
    assert p.returncode == 1
    assert "the report needs the trajectory column 'racket.x'" in p.stderr
    assert "[output] quantities leaves it out" in p.stderr
    assert not (tmp_path / "out").exists()  # nothing of the run is written
