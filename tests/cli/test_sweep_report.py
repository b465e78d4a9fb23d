"""The page of a sweep (docs/report.md, "A sweep's page"): `rigid sweep --report`, `rigid report
SWEEP_DIR` and rigid.sweep(report=) write one self-contained page whose data are runs.csv's
numbers, exactly (float64), with each run's error, the grid's axes or a sample's inputs, and the
units of run 0's schema."""
import base64
import csv
import json
import math
import pathlib
import re
import struct
import time

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PENDULUM = ROOT / "examples" / "physical_pendulum.toml"
# a short run of the pendulum: one period metric needs none, the energy columns need two samples
SHORT = ["--set", "simulation.t_end=0.02", "--set", "simulation.output_dt=0.01",
         "--set", "simulation.tolerance=1e-6"]


def page_data(path):
    text = pathlib.Path(path).read_text(encoding="utf-8")
    m = re.search(r'<script type="application/json" id="rigid-report-data">(.*?)</script>', text, re.S)
    assert m, "the page has no data element"
    return json.loads(m.group(1))


def decode(value):
    tag, _, b64 = value.partition(":")
    raw = base64.b64decode(b64)
    fmt = {"f64": "d", "u32": "I"}[tag]
    return list(struct.unpack(f"<{len(raw) // struct.calcsize(fmt)}{fmt}", raw))


def runs_csv(directory):
    with open(pathlib.Path(directory) / "runs.csv", newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def same(a, b):
    return (math.isnan(a) and math.isnan(b)) or a == b


def check_page_holds_runs_csv(page, directory):
    """The page's columns are runs.csv's, value for value (NaN where it says nan or nothing), and
    its errors are runs.csv's error column."""
    data = page_data(page)
    header, rows = runs_csv(directory)
    assert data["rigid_sweep_page"] == 1 and data["runs"] == len(rows)
    assert [c["name"] for c in data["columns"]] == header[:-1]
    for k, c in enumerate(data["columns"]):
        values = decode(c["values"])
        expected = [float(r[k]) if r[k] else math.nan for r in rows]
        assert all(same(a, b) for a, b in zip(values, expected)), c["name"]
        assert len(values) == len(rows)
    index = decode(data["error"])
    errors = [data["messages"][i - 1] if i else "" for i in index]
    assert errors == [r[-1] for r in rows]
    assert data["failures"] == sum(1 for r in rows if r[-1])
    return data


def test_a_one_axis_grid_with_failed_runs(run, tmp_path):
    # m from 1 down to -1: run 0 is valid, m = 0 and m < 0 fail ("mass must be positive")
    out = tmp_path / "g1"
    p = run("sweep", PENDULUM, "--grid", "m=1:-1:5", *SHORT, "-o", out, "--report", check=True)
    assert str(out / "report.html") in p.stdout
    raw = (out / "report.html").read_bytes()
    assert b"http://" not in raw and b"https://" not in raw
    data = check_page_holds_runs_csv(out / "report.html", out)
    assert data["layout"] == {"kind": "grid", "axes": [{"name": "m", "values": [1.0, 0.5, 0.0, -0.5, -1.0]}]}
    assert data["failures"] == 3 and len(data["messages"]) == 3
    assert all("mass must be positive" in m for m in data["messages"])
    units = {c["name"]: c["unit"] for c in data["columns"]}
    # run 0's schema: the energy in J, the period in s; the scene's parameter m has none
    assert units["energy_initial"] == "J" and units["period"] == "s" and units["m"] == ""
    summary = json.loads((out / "summary.json").read_text())
    assert data["failure_groups"] == summary["failure_groups"]
    assert data["statistics"] == summary["results"]
    # rigid report DIR writes the same numbers again
    again = tmp_path / "again.html"
    run("report", out, "-o", again, check=True)
    check_page_holds_runs_csv(again, out)


def test_a_two_axis_grid_is_a_grid_of_its_axes(run, tmp_path):
    out = tmp_path / "g2"
    run("sweep", PENDULUM, "--grid", "L=0.5:2:4", "--grid", "m=1:-0.5:4", *SHORT, "-o", out, "-q", check=True)
    assert not (out / "report.html").exists()
    p = run("report", out, check=True)
    assert p.stdout.strip() == f"wrote {out / 'report.html'}"
    data = check_page_holds_runs_csv(out / "report.html", out)
    assert data["layout"]["kind"] == "grid"
    assert [a["name"] for a in data["layout"]["axes"]] == ["L", "m"]
    assert data["layout"]["axes"][0]["values"] == [0.5, 1.0, 1.5, 2.0]
    assert data["layout"]["axes"][1]["values"] == [1.0, 0.5, 0.0, -0.5]
    # m = 0 and m = -0.5 fail for every L
    assert data["failures"] == 8
    # --report PATH, and --report-frames is a run page's
    page = tmp_path / "elsewhere.html"
    run("sweep", PENDULUM, "--grid", "L=0.5:2:4", "--grid", "m=1:-0.5:4", *SHORT, "-o", out, "-q",
        "--report", page, check=True)
    other = page_data(page)
    assert other["layout"] == data["layout"] and other["error"] == data["error"]
    assert [c["values"] for c in other["columns"]] == [c["values"] for c in data["columns"]]
    # the units of run 0's schema: the sweep that ran the scene knows them, and `rigid report DIR`
    # reads them from summary.json; a scene's own parameter has none
    for page_data_ in (other, data):
        units = {c["name"]: c["unit"] for c in page_data_["columns"]}
        assert units["energy_initial"] == "J" and units["period"] == "s" and units["L"] == ""
    p = run("report", out, "--report-frames", "10", check=False)
    assert p.returncode == 2 and "sweep's directory" in p.stderr


def test_a_sample_with_failed_runs(run, tmp_path):
    # m uniform on (-0.2, 1): about a sixth of the runs fail; with seed 3 run 0 is valid (a sweep
    # whose run 0 is refused stops before any run)
    out = tmp_path / "mc"
    p = run("sweep", PENDULUM, "--sample", "m=uniform(-0.2,1)", "--sample", "L=uniform(0.5,2)", "-n", "60",
            "--seed", "3", *SHORT, "-o", out, "--report")
    assert p.returncode == 0, p.stderr
    data = check_page_holds_runs_csv(out / "report.html", out)
    assert data["layout"] == {"kind": "sample"}
    assert data["swept"] == ["m", "L"]
    assert 0 < data["failures"] < 60


def test_a_one_axis_sample_is_not_taken_for_a_grid(run, tmp_path):
    # with no journal (rigid.sweep writes none) the layout is found from the values: one axis
    # is a grid only when its values are evenly spaced
    import rigid
    out = tmp_path / "py"
    r = rigid.sweep(PENDULUM, sample=["L=uniform(0.5,2)"], samples=20, seed=1, set=SHORT[1::2],
                    output=out, report=tmp_path / "py.html")
    assert r["report"] == str(tmp_path / "py.html")
    data = check_page_holds_runs_csv(tmp_path / "py.html", out)
    assert data["layout"] == {"kind": "sample"}
    assert {c["name"]: c["unit"] for c in data["columns"]}["period"] == "s"
    # and a Python grid is one
    r = rigid.sweep(PENDULUM, grid=["L=0.5:2:4"], set=SHORT[1::2], report=tmp_path / "grid.html")
    data = page_data(tmp_path / "grid.html")
    assert data["layout"]["kind"] == "grid" and data["failures"] == 0
    assert decode(data["columns"][1]["values"]) == list(r["columns"]["L"])


def test_rigid_report_takes_units_from_a_kept_run(run, tmp_path):
    out = tmp_path / "kept"
    run("sweep", PENDULUM, "--grid", "simulation.t_end=0.02:0.04:3", "--keep-trajectories", "-o", out, "-q",
        check=True)
    run("report", out, check=True)
    data = check_page_holds_runs_csv(out / "report.html", out)
    units = {c["name"]: c["unit"] for c in data["columns"]}
    assert units["simulation.t_end"] == "s" and units["energy_initial"] == "J" and units["period"] == "s"
    assert data["layout"]["axes"] == [{"name": "simulation.t_end", "values": [0.02, 0.03, 0.04]}]


def test_report_refuses_a_directory_that_is_neither(run, tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    p = run("report", empty, check=False)
    assert p.returncode == 1 and "is neither a run's directory" in p.stderr and "nor a sweep's" in p.stderr
    # a shard's directory: a journal and no runs.csv
    shard = tmp_path / "shard"
    run("sweep", PENDULUM, "--grid", "L=0.5:2:4", *SHORT, "--shard", "0/2", "-o", shard, "-q", check=True)
    p = run("report", shard, check=False)
    assert p.returncode == 1 and "sweep merge" in p.stderr
    p = run("sweep", PENDULUM, "--grid", "L=0.5:2:4", "--shard", "0/2", "--report", "-o", tmp_path / "s2", check=False)
    assert p.returncode == 2 and "--report with --shard" in p.stderr
    # a runs.csv that is not one
    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "runs.csv").write_text("a,b\n1,2\n")
    (bad / "summary.json").write_text("{}")
    p = run("report", bad, check=False)
    assert p.returncode == 1 and "no header line ending in 'error'" in p.stderr


def test_the_page_of_ten_thousand_runs_is_under_5_mb(run, tmp_path):
    out = tmp_path / "big"
    start = time.monotonic()
    run("sweep", PENDULUM, "--grid", "L=0.5:2:100", "--grid", "m=0.1:1:100", *SHORT, "-o", out, "-q",
        "--report", check=True)
    seconds = time.monotonic() - start
    size = (out / "report.html").stat().st_size
    assert size <= 5 * 1024 * 1024, f"{size} bytes"
    data = check_page_holds_runs_csv(out / "report.html", out)
    assert data["runs"] == 10000
    print(f"10^4-run sweep with its page: {seconds:.2f} s, page {size} bytes")
