"""`rigid sweep`: runs.csv / runs.npy / summary.json, byte-identical whatever the threads, MPI
ranks or shards; resumable after SIGINT and SIGKILL; failing runs recorded; the closed forms of
the physical pendulum's period and the tennis racket's flip period over the swept values."""
import csv
import json
import math
import os
import pathlib
import shutil
import signal
import subprocess
import time

import numpy as np
import pytest
from scipy.special import ellipk

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
PENDULUM = EXAMPLES / "physical_pendulum.toml"

# The tennis racket of examples/tennis_racket.toml with I2 a parameter and I3 = 2.9 (the
# example's I3 = I1 + I2 is a flat plate, and any smaller I2 would be no body).
RACKET = """
[parameters]
I2 = 2
[[bodies]]
name = "racket"
free = true
inertia = {{mass = 0.35, ixx = 1, iyy = "I2", izz = 2.9}}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = {t_end}
output_dt = {output_dt}
"""


def racket(tmp_path, t_end=100.0, output_dt=0.05):
    p = tmp_path / "racket.toml"
    p.write_text(RACKET.format(t_end=t_end, output_dt=output_dt))
    return p


def read_runs(d):
    with open(d / "runs.csv", newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def same_outputs(a, b):
    for name in ("runs.csv", "runs.npy", "summary.json"):
        assert (a / name).read_bytes() == (b / name).read_bytes(), name


def journal_rows(d):
    p = d / ".journal.jsonl"
    if not p.exists():
        return 0
    return max(0, len([l for l in p.read_text().split("\n")[1:] if l]))


def test_grid_runs_csv_npy_and_summary_agree(run, tmp_path):
    out = tmp_path / "s"
    run("sweep", PENDULUM, "--grid", "L=0.5:2:4", "--grid", "m=1:2:2", "-o", out, "-q", check=True)
    header, rows = read_runs(out)
    assert header[:3] == ["run", "L", "m"] and header[-1] == "error"
    assert len(rows) == 8
    # the first axis slowest; both ends exact
    assert [(float(r[1]), float(r[2])) for r in rows[:3]] == [(0.5, 1.0), (0.5, 2.0), (1.0, 1.0)]
    assert float(rows[-1][1]) == 2.0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["count"] == 8 and summary["failures"] == 0
    npy = np.load(out / "runs.npy")
    assert npy.shape == (8, len(header) - 1)
    assert summary["columns"] == header[:-1]
    # the npy holds the csv's numbers, bit for bit
    np.testing.assert_array_equal(npy, np.array([r[:-1] for r in rows], dtype=float))
    # statistics of a column, against numpy over the same numbers
    k = header.index("energy_initial")
    x = npy[:, k]
    s = summary["results"]["energy_initial"]
    assert s["mean"] == pytest.approx(np.mean(x), rel=1e-15)  # sums of 8 terms: round-off only
    assert s["std"] == pytest.approx(np.std(x, ddof=1), rel=1e-13)
    assert s["quantiles"]["0.25"] == pytest.approx(np.quantile(x, 0.25), rel=1e-15)
    assert s["min"] == x.min() and s["max"] == x.max()


def test_a_row_is_the_run_of_rigid_run_with_that_override(run, tmp_path):
    # the seam: a sweep's run is `rigid run --set` with its value; the diagnostics agree bitwise
    out = tmp_path / "s"
    run("sweep", PENDULUM, "--grid", "L=0.5:2:3", "-o", out, "-q", check=True)
    header, rows = read_runs(out)
    run("run", PENDULUM, "--set", "L=1.25", "-o", tmp_path / "r", "-q", check=True)
    diag = json.loads((tmp_path / "r" / "summary.json").read_text())["diagnostics"]
    row = dict(zip(header, rows[1]))
    assert float(row["L"]) == 1.25
    for name, value in diag.items():
        assert float(row[name]) == value, name
    # and Python's Scene with the same override (the module built next to the executable)
    rigid = pytest.importorskip("rigid")
    summary = rigid.Scene(str(PENDULUM), set=["L=1.25"]).run()["summary"]
    for name, value in summary["diagnostics"].items():
        assert float(row[name]) == value, name


def test_summary_states_the_units_run_0s_schema_knows(run, tmp_path):
    # the seam: the units summary.json gives a sweep's columns are those `rigid run` states in its
    # own schema for the same scene; a scene's own parameter (L) and a coordinate the scene does not
    # say is an angle or a length have none
    out = tmp_path / "s"
    run("sweep", PENDULUM, "--grid", "L=0.5:2:3", "--grid", "simulation.t_end=0.5:1:2", "-o", out, "-q", check=True)
    summary = json.loads((out / "summary.json").read_text())
    run("run", PENDULUM, "--set", "simulation.t_end=0.5", "-o", tmp_path / "r", "-q", check=True)
    schema = json.loads((tmp_path / "r" / "summary.json").read_text())["schema"]
    expected = {n: u for group in ("diagnostics", "metrics") for n, u in schema[group].items() if u}
    expected["simulation.t_end"] = "s"
    assert set(summary["results"]) <= set(expected), "every result column has a unit here"
    assert summary["units"] == {c: expected[c] for c in summary["columns"] if c in expected}
    assert summary["units"]["period"] == "s" and summary["units"]["energy_initial"] == "J"
    assert "L" not in summary["units"] and "run" not in summary["units"]


def test_merged_shards_keep_the_units_and_refuse_other_units(run, tmp_path):
    args = ("sweep", PENDULUM, "--grid", "L=0.5:2:4", "--set", "simulation.t_end=0.5", "-q")
    for i in range(2):
        run(*args, "--shard", f"{i}/2", "-o", tmp_path / f"s{i}", check=True)
    run("sweep", "merge", tmp_path / "s0", tmp_path / "s1", "-o", tmp_path / "m", "-q", check=True)
    assert json.loads((tmp_path / "m" / "summary.json").read_text())["units"]["period"] == "s"
    # a shard whose journal states other units (its scene changed between the shards)
    journal = tmp_path / "s1" / ".journal.jsonl"
    lines = journal.read_text().split("\n")
    header = json.loads(lines[0])
    header["units"]["period"] = "min"
    journal.write_text("\n".join([json.dumps(header, separators=(",", ":"))] + lines[1:]))
    p = run("sweep", "merge", tmp_path / "s0", tmp_path / "s1", "-o", tmp_path / "m2", check=False)
    assert p.returncode == 1 and "states other units" in p.stderr and str(tmp_path / "s1") in p.stderr
    assert not (tmp_path / "m2" / "summary.json").exists()


def test_a_free_body_sweeps_batched_rows_are_the_runs_of_rigid_run(run, tmp_path):
    # a free-body sweep marches its runs four at a time (8 runs on 2 threads: two batches of
    # four); each row is still, bit for bit, `rigid run --set` and Python's run of its value
    scene = racket(tmp_path, t_end=20)
    out = tmp_path / "s"
    run("sweep", scene, "--grid", "I2=2:2.4:8", "--threads", "2", "-o", out, "-q", check=True)
    header, rows = read_runs(out)
    rigid = pytest.importorskip("rigid")
    for row in (rows[0], rows[5], rows[7]):
        row = dict(zip(header, row))
        value = row["I2"]
        run("run", scene, "--set", f"I2={value}", "-o", tmp_path / "r", "-q", check=True)
        diag = json.loads((tmp_path / "r" / "summary.json").read_text())["diagnostics"]
        assert diag and row["error"] == ""
        for name, v in diag.items():
            assert float(row[name]) == v, (value, name)
        summary = rigid.Scene(str(scene), set=[f"I2={value}"]).run()["summary"]
        for name, v in summary["diagnostics"].items():
            assert float(row[name]) == v, (value, name)
    # and one thread (batches of four taken in another order) gives the same bytes
    run("sweep", scene, "--grid", "I2=2:2.4:8", "--threads", "1", "-o", tmp_path / "one", "-q", check=True)
    same_outputs(out, tmp_path / "one")


def test_one_and_two_threads_give_the_same_bytes(run, tmp_path):
    scene = racket(tmp_path, t_end=20)
    args = ("sweep", scene, "--sample", "I2=uniform(1.98,2.02)", "-n", "12", "--seed", "5", "-q")
    run(*args, "--threads", "1", "-o", tmp_path / "a", check=True)
    run(*args, "--threads", "2", "-o", tmp_path / "b", check=True)
    same_outputs(tmp_path / "a", tmp_path / "b")
    # another seed draws other values
    run(*args[:-3], "--seed", "6", "-q", "-o", tmp_path / "c", check=True)
    assert read_runs(tmp_path / "a")[1][0][1] != read_runs(tmp_path / "c")[1][0][1]


def test_three_shards_merged_give_the_unsharded_bytes(run, tmp_path):
    args = ("sweep", PENDULUM, "--grid", "L=0.5:2:7", "-q")
    run(*args, "-o", tmp_path / "whole", check=True)
    for i in range(3):
        run(*args, "--shard", f"{i}/3", "-o", tmp_path / f"s{i}", check=True)
        assert not (tmp_path / f"s{i}" / "runs.csv").exists()  # a shard writes its journal only
    # a shard missing: refused, naming the runs
    p = run("sweep", "merge", tmp_path / "s0", tmp_path / "s2", "-o", tmp_path / "m", check=False)
    assert p.returncode == 1 and "2 of the sweep's 7 runs are missing (runs 1, 4)" in p.stderr
    run("sweep", "merge", tmp_path / "s0", tmp_path / "s1", tmp_path / "s2", "-o", tmp_path / "m", "-q", check=True)
    same_outputs(tmp_path / "whole", tmp_path / "m")
    # the shards of another sweep are not merged with these
    run("sweep", PENDULUM, "--grid", "L=0.5:2:6", "--shard", "0/3", "-o", tmp_path / "x", "-q", check=True)
    p = run("sweep", "merge", tmp_path / "s0", tmp_path / "x", "-o", tmp_path / "m2", check=False)
    assert p.returncode == 1 and "holds another sweep" in p.stderr


def test_two_mpi_ranks_give_the_same_bytes(rigid_exe, run, tmp_path):
    mpirun = shutil.which("mpirun")
    assert mpirun, "mpirun (Debian openmpi-bin) is a test dependency: scripts/install-deps.sh"
    args = ("sweep", PENDULUM, "--grid", "L=0.5:2:6", "--threads", "1", "-q")
    run(*args, "-o", tmp_path / "one", check=True)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    p = subprocess.run([mpirun, "--oversubscribe", "-n", "2", rigid_exe, *map(str, args), "-o",
                        str(tmp_path / "two")], capture_output=True, text=True, env=env, timeout=120)
    assert p.returncode == 0, p.stderr + p.stdout
    same_outputs(tmp_path / "one", tmp_path / "two")


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGKILL])
def test_an_interrupted_sweep_resumes_to_the_same_bytes(rigid_exe, run, tmp_path, sig):
    # 24 runs of ~10⁴ steps each on one thread: long enough to stop in the middle
    scene = racket(tmp_path, t_end=100, output_dt=1)
    args = [rigid_exe, "sweep", str(scene), "--grid", "I2=1.95:2.1:24", "--threads", "1", "-q"]
    d = tmp_path / "stopped"
    proc = subprocess.Popen(args + ["-o", str(d)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while journal_rows(d) < 3 and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)
    assert proc.poll() is None, "the sweep ended before it could be stopped; make its runs longer"
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    done = journal_rows(d)
    assert 3 <= done < 24
    if sig == signal.SIGINT:
        assert proc.returncode == 130, err
        assert "run the same command again" in err
    else:
        assert proc.returncode == -signal.SIGKILL
    assert not (d / "runs.csv").exists()
    p = subprocess.run(args + ["-o", str(d)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    subprocess.run(args + ["-o", str(tmp_path / "whole")], check=True, timeout=120)
    same_outputs(d, tmp_path / "whole")
    assert journal_rows(d) == 24  # the finished runs were not run again


def test_a_failing_run_is_a_row_and_the_others_go_on(run, tmp_path):
    # m runs down from 1 to -1: run 0 is valid (a refused run 0 stops the sweep, below)
    out = tmp_path / "s"
    p = run("sweep", PENDULUM, "--grid", "m=1:-1:3", "-o", out, check=True)
    assert "2 failed:" in p.stdout
    header, rows = read_runs(out)
    assert "mass must be positive and finite, got -1 kg" in rows[2][-1]
    assert "mass must be positive and finite, got 0 kg" in rows[1][-1]
    assert rows[0][-1] == "" and float(rows[0][header.index("energy_initial")]) < 0
    npy = np.load(out / "runs.npy")
    assert np.isnan(npy[2, 2:]).all() and np.isfinite(npy[0]).all()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["failures"] == 2
    # one group per message (each names its value), in order of their first run
    assert [(g["count"], g["runs"]) for g in summary["failure_groups"]] == [(1, [1]), (1, [2])]
    assert summary["failure_groups"][1]["message"] == rows[2][-1]
    assert f"  1 run: {rows[1][-1]} (run 1)" in p.stdout
    # some runs succeeded: -q prints nothing and the exit status is 0
    p = run("sweep", PENDULUM, "--grid", "m=1:-1:3", "-o", tmp_path / "q", "-q", check=True)
    assert p.stdout == "" and p.stderr == ""


# What every run would refuse is refused once, before any run and before the output directory is
# made: run 0 (the --set values and each axis's first value) is built and checked as its run
# would be, with the sweep's integrator and the scene's metrics.
@pytest.mark.parametrize("extra, scene_edit, message", [
    (("--grid", "L=0.5:2:3", "--integrator", "rk5"), None, "unknown integrator 'rk5'"),
    (("--grid", "L=0.5:2:3"), ('column = "theta"', 'column = "thetaa"'), "the run has no column 'thetaa'"),
    (("--grid", "L=0.5:2:3", "--set", "m=-1"), None, "mass must be positive and finite, got -1 kg"),
    (("--grid", "m=-1:1:3"), None, "mass must be positive and finite, got -1 kg"),
    (("--sample", "L=uniform(-2,-1)", "-n", "4"), None, "length must be positive"),
])
def test_what_every_run_would_refuse_stops_the_sweep_before_any_run(run, tmp_path, extra, scene_edit, message):
    scene = PENDULUM
    if scene_edit:
        scene = tmp_path / "edited.toml"
        scene.write_text(PENDULUM.read_text().replace(*scene_edit))
    out = tmp_path / "s"
    for quiet in ((), ("-q",)):
        p = run("sweep", scene, *extra, "-o", out, *quiet, check=False)
        assert p.returncode == 1, p.stderr
        assert p.stderr.startswith("rigid: error: run 0 of the sweep (") and message in p.stderr, p.stderr
        assert "no run was started" in p.stderr and p.stdout == ""
        assert not out.exists()  # no journal, no runs.csv


# x'' = c x'^2 with x(0) = 0, x'(0) = 1: x'(t) = 1/(1 - c t), infinite at t = 1/c. Run 0's check
# passes (its state at t = 0 is finite); with t_end = 1.5 s a run with c >= 1 diverges while it
# runs. The axis d changes nothing in the motion, so the runs of one c fail with one message.
BLOW_UP = """
lagrangian = "x_dot^2/2"
[parameters]
c = 1.0
d = 0.0
[[coordinates]]
name = "x"
initial = 0
velocity = 1
[[forces]]
coordinate = "x"
expression = "c*x_dot^2 + 0*d"
[simulation]
t_end = 1.5
integrator = "rk4"
dt = 1e-3
output_dt = 0.1
"""


def test_a_sweep_whose_every_run_failed_exits_1_and_groups_the_errors(run, tmp_path):
    scene = tmp_path / "blowup.toml"
    scene.write_text(BLOW_UP)
    args = ("sweep", scene, "--grid", "c=1:2:2", "--grid", "d=0:1:3")
    out = tmp_path / "all"
    p = run(*args, "-o", out, check=False)
    assert p.returncode == 1, p.stderr
    header, rows = read_runs(out)  # the outputs are written all the same
    assert len(rows) == 6 and all("diverged" in r[-1] for r in rows)
    # c = 1 are runs 0-2 (the first axis varies slowest), c = 2 runs 3-5: two messages
    assert rows[0][-1] == rows[2][-1] != rows[3][-1] == rows[5][-1]
    summary = json.loads((out / "summary.json").read_text())
    assert summary["failures"] == 6
    assert summary["failure_groups"] == [{"message": rows[0][-1], "count": 3, "runs": [0, 1, 2]},
                                         {"message": rows[3][-1], "count": 3, "runs": [3, 4, 5]}]
    assert "6 failed:" in p.stdout and f"  3 runs: {rows[3][-1]} (runs 3, 4, 5)" in p.stdout
    assert p.stderr.startswith("rigid: error: every one of the sweep's 6 runs failed:")
    assert f"  3 runs: {rows[0][-1]} (runs 0, 1, 2)" in p.stderr and str(out / "runs.csv") in p.stderr
    # said even with -q, on stderr; and by the merge of shards that all failed
    p = run(*args, "-o", tmp_path / "q", "-q", check=False)
    assert p.returncode == 1 and p.stdout == "" and "every one of the sweep's 6 runs failed" in p.stderr
    for i in range(2):
        run(*args, "--shard", f"{i}/2", "-o", tmp_path / f"s{i}", "-q", check=True)
    p = run("sweep", "merge", tmp_path / "s0", tmp_path / "s1", "-o", tmp_path / "m", "-q", check=False)
    assert p.returncode == 1 and "every one of the sweep's 6 runs failed" in p.stderr
    same_outputs(out, tmp_path / "m")
    # c = 0 runs to the end (x = t): one run of three succeeded, the exit status is 0
    p = run("sweep", scene, "--grid", "c=0:2:3", "-o", tmp_path / "some", check=True)
    assert "2 failed:" in p.stdout


def test_bad_commands_are_refused_with_a_reason(run, tmp_path):
    # a value that is none of --grid's/--sample's/--shard's forms, or a missing or conflicting
    # option, is usage (exit 2, as in every subcommand); a name the scene lacks is the input's (1)
    cases = [
        (("--grid", "x=0:1:3"), "--grid: ", 1),  # the override's own refusal follows, naming 'x'
        (("--grid", "x=0:1:3"), "'x", 1),
        (("--grid", "L=0:1"), "--grid: 'L=0:1' has 2 field(s) after '='", 2),
        (("--grid", "L=a:1:3"), "--grid: 'L=a:1:3': START and STOP must be finite numbers", 2),
        (("--grid", "L=0:1:0"), "COUNT must be a whole number from 1", 2),
        (("--grid", "L=0:1:2", "--grid", "L=1:2:2"), "--grid: 'L' is swept twice", 2),
        (("--grid", "L=0:1:65536", "--grid", "m=1:2:65536", "--grid", "c=0:1:2"),
         "--grid: the grid has more than 4294967296 runs", 2),
        (("--sample", "L=uniform(1,2)"), "--sample needs -n N", 2),
        (("--sample", "L=gauss(1,2)", "-n", "3"), "unknown distribution 'gauss'", 2),
        (("--sample", "L=uniform(2,1)", "-n", "3"), "--sample: 'L=uniform(2,1)': uniform(a, b) needs a < b", 2),
        (("--sample", "L=normal(1)", "-n", "3"), "--sample: 'L=normal(1)': expected two finite numbers", 2),
        (("--grid", "L=1:2:2", "--sample", "m=uniform(1,2)", "-n", "2"), "--grid and --sample: give one", 2),
        (("--grid", "L=1:2:2", "-n", "2"), "-n is for --sample", 2),
        ((), "give the runs: --grid", 2),
        (("--grid", "L=1:2:2", "--shard", "3/3"), "--shard: shard '3/3' is not I/N", 2),
    ]
    for extra, message, status in cases:
        p = run("sweep", PENDULUM, *extra, "-o", tmp_path / "s", check=False)
        assert p.returncode == status, (extra, p.returncode, p.stderr)
        assert message in p.stderr, (extra, p.stderr)
        assert not (tmp_path / "s").exists(), extra  # refused before the output directory is made
    # another sweep in the same directory is refused
    run("sweep", PENDULUM, "--grid", "L=1:2:2", "-o", tmp_path / "d", "-q", check=True)
    p = run("sweep", PENDULUM, "--grid", "L=1:2:3", "-o", tmp_path / "d", check=False)
    assert p.returncode == 1 and "holds another sweep" in p.stderr and "another output directory" in p.stderr


def test_racket_flip_period_over_a_monte_carlo_of_I2_matches_the_closed_form(run, tmp_path):
    # I2 uniform within ±1% of 2; each run's flip period T = 4K(k)/λ (examples/tennis_racket.toml)
    # from its own I2 (in runs.csv), against the sign changes of ω_y in its kept trajectory
    scene = racket(tmp_path)
    out = tmp_path / "mc"
    run("sweep", scene, "--sample", "I2=uniform(1.98,2.02)", "-n", "16", "--seed", "3", "--keep-trajectories",
        "-o", out, "-q", check=True)
    header, rows = read_runs(out)
    I1, I3, w = 1.0, 2.9, np.array([0.01, 1, 0.01])
    measured, closed = [], []
    for r in rows:
        I2 = float(r[header.index("I2")])
        I = np.array([I1, I2, I3])
        twoE, L2 = np.sum(I * w**2), np.sum(I**2 * w**2)
        lam = math.sqrt((I3 - I2) * (L2 - twoE * I1) / (I1 * I2 * I3))
        k2 = (I2 - I1) * (twoE * I3 - L2) / ((I3 - I2) * (L2 - twoE * I1))
        closed.append(4 * ellipk(k2) / lam)
        with open(out / "runs" / f"{int(r[0]):05d}" / "trajectory.csv", newline="") as f:
            data = list(csv.reader(f))
        t = np.array([float(x[0]) for x in data[1:]])
        wy = np.array([float(x[data[0].index("racket.wy")]) for x in data[1:]])
        i = np.nonzero(np.signbit(wy[:-1]) != np.signbit(wy[1:]))[0]
        crossings = t[i] + (t[i + 1] - t[i]) * wy[i] / (wy[i] - wy[i + 1])
        # successive sign changes are half a period apart
        measured.append(2 * np.mean(np.diff(crossings)))
    measured, closed = np.array(measured), np.array(closed)
    # the flip is a sign change of a cn-like ω_y at its inflection: linear interpolation between
    # samples 0.05 s apart errs by O(h³) (~1e-7 s); splitting4 at the scene's step has a relative
    # phase error of ~1e-6 over 100 s (the example's check holds to 2e-5): 2e-5 relative bounds both
    np.testing.assert_allclose(measured, closed, rtol=2e-5)
    assert np.mean(measured) == pytest.approx(np.mean(closed), rel=2e-5)
    # the spread comes from the ±1% of I2 (a few % of T); its error is at most the values' error
    assert np.std(measured, ddof=1) == pytest.approx(np.std(closed, ddof=1), abs=2 * 2e-5 * np.max(closed))
    assert np.std(closed, ddof=1) > 100 * 2e-5 * np.max(closed)  # the spread is resolved


def test_acceptance_pendulum_period_over_the_amplitude(run, tmp_path):
    # The acceptance of the sweep with run metrics: examples/physical_pendulum.toml defines a
    # metric `period` (successive crossings) and `theta.initial` is an override. It needs the run
    # metrics and initial-condition overrides of the same issue; without them the sweep is
    # refused ('theta.initial' is no parameter) and this test fails.
    out = tmp_path / "pendulum"
    run("sweep", PENDULUM, "--grid", "theta.initial=0.1:2.5:25", "-o", out, "-q", check=True)
    header, rows = read_runs(out)
    assert len(rows) == 25 and "theta.initial" in header and "period" in header
    L, g = 1.0, 9.81
    for r in rows:
        theta0 = float(r[header.index("theta.initial")])
        T = 4 * ellipk(math.sin(theta0 / 2) ** 2) * math.sqrt(2 * L / (3 * g))
        # the scene's dopri5 tolerance 1e-10, crossings located on its dense output: 1e-8 relative
        assert float(r[header.index("period")]) == pytest.approx(T, rel=1e-8), theta0
