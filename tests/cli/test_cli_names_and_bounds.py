"""Names and bounds at the edges: tolerances bounded above in every entry point, every error of
a sweep a rigid.Error, reserved names and file names of any bytes shown where they come from,
scene and sweep names that are identifiers."""
import pathlib

import pytest

import rigid

OSCILLATOR = """\
[parameters]
m = 1
[[coordinates]]
name = "x"
initial = 1.0
[[bodies]]
name = "b"
point_masses = [{mass = "m", position = [0, 0, 0]}]
position = ["x", 0, 0]
[[potentials]]
expression = "0.5*x^2"
[simulation]
t_end = 1
integrator = "dopri5"
tolerance = TOLERANCE
"""

BOUND = "is above 0.1, the loosest tolerance an error control honours"


def scene(tmp_path, text, name="s.toml"):
    path = tmp_path / name
    path.write_bytes(text.encode() if isinstance(text, str) else text)
    return path


def assert_refused(proc, *fragments):
    assert proc.returncode == 1, (proc.returncode, proc.stdout, proc.stderr)
    for f in fragments:
        assert f in proc.stderr, proc.stderr
    assert "(): " not in proc.stderr, proc.stderr  # no C++ function name


# A scene's tolerance = 1e300 was accepted (dopri5 then accepts any step the stability allows:
# 5.8e20 for a unit oscillator). Refused above 0.1 at the key, by check and run, in the file, by
# --set and by Python, in the same words as rigid.integrate.solve's rtol and atol.
def test_tolerances_are_bounded_above_everywhere(run, tmp_path):
    path = scene(tmp_path, OSCILLATOR.replace("TOLERANCE", "1e300"))
    for args in (["check"], ["run", "-o", tmp_path / "out"]):
        assert_refused(run(*args, path),
                       "s.toml:15:13: [simulation] tolerance = 1e+300 " + BOUND,
                       "expected [simulation] tolerance ≤ 0.1")
    assert not (tmp_path / "out").exists()
    ok = scene(tmp_path, OSCILLATOR.replace("TOLERANCE", "0.1"), "ok.toml")
    assert run("check", ok).returncode == 0  # the bound itself is accepted
    assert_refused(run("check", ok, "--set", "simulation.tolerance=0.5"),
                   "override 'simulation.tolerance=0.5'", "[simulation] tolerance = 0.5 " + BOUND)
    with pytest.raises(rigid.Error, match=r"\[simulation\] tolerance = 0\.2 is above 0\.1"):
        rigid.Scene(ok, ["simulation.tolerance=0.2"]).check()
    with pytest.raises(rigid.Error, match="rtol = 1e\\+300 " + BOUND):
        rigid.integrate.solve(lambda t, y: [y[1], -y[0]], [1.0, 0.0], 10.0, rtol=1e300)
    with pytest.raises(rigid.Error, match="atol = 0.5 " + BOUND):
        rigid.integrate.solve(lambda t, y: [y[1], -y[0]], [1.0, 0.0], 10.0, atol=0.5)


PENDULUM = OSCILLATOR.replace("tolerance = TOLERANCE\n", "")


# `parameter name 'sin' is reserved` came from inside the equations' builder, named
# "operator()()" and no place; the scene refuses it at the name's line, saying why.
@pytest.mark.parametrize("what, old, new, where", [
    ("parameter", "m = 1", "sin = 1", "s.toml:2:7: "),
    ("coordinate", 'name = "x"', 'name = "cos"', "s.toml:4:8: "),
])
def test_reserved_names_are_refused_where_they_are_declared(run, tmp_path, what, old, new, where):
    text = PENDULUM.replace(old, new).replace('"m"', '"sin"').replace("0.5*x^2", "0.5*cos^2" if what == "coordinate" else "0.5*x^2")
    proc = run("check", scene(tmp_path, text))
    name = new.split()[-1].strip('"') if what == "coordinate" else "sin"
    assert_refused(proc, f"{where}{what} may not be called '{name}': expressions reserve it")
    assert "operator()" not in proc.stderr


FREE_BODY = """\
[parameters]
NAME = 1
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = 2, izz = 3}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 1.0
output_dt = 0.05
"""


# A free-body scene took any quoted parameter name: ESC and BEL were echoed to the terminal
# by `rigid check`, a newline split runs.csv's header. Every scene kind's names are identifiers,
# and a refused name is shown escaped (no control byte reaches the terminal).
@pytest.mark.parametrize("key, shown", [('"a\\u001b[31mb"', "a\\x1b[31mb"), ('"r\\u0007"', "r\\x07"),
                                        ('"p\\nq"', "p\\x0aq"), ('"2x"', "2x")])
def test_free_body_scene_names_are_identifiers(run, tmp_path, key, shown):
    proc = run("check", scene(tmp_path, FREE_BODY.replace("NAME", key)))
    assert_refused(proc, f"s.toml:2:{len(key) + 4}: parameter name '{shown}' is not a valid name")
    assert not any(ord(c) < 0x20 and c != "\n" for c in proc.stderr), repr(proc.stderr)
    body = FREE_BODY.replace("NAME", "w").replace('name = "racket"', f"name = {key}")
    proc = run("check", scene(tmp_path, body, "b.toml"))
    assert_refused(proc, f"b.toml:4:8: body name '{shown}' is not a valid name")
    assert not any(ord(c) < 0x20 and c != "\n" for c in proc.stderr), repr(proc.stderr)


# A sweep axis or --set name with a newline or ESC was echoed raw (and a newline in a swept
# name split runs.csv's header): such names are refused before anything runs, shown escaped,
# on the command line and in rigid.sweep alike.
@pytest.mark.parametrize("args, shown", [
    (["sweep", "--grid", "m\n=1:2:2"], "'m\\x0a' is not a valid name"),
    (["sweep", "--grid", "m=1:2:2", "--set", "x.initial\x1b=0.5"], "'x.initial\\x1b' is not a valid name"),
    (["run", "--set", "x.ini\x07tial=0.5"], "'x.ini\\x07tial' is not a valid name"),
])
def test_sweep_and_set_names_are_identifiers(run, tmp_path, args, shown):
    path = scene(tmp_path, PENDULUM)
    proc = run(*args[:1], path, *args[1:], "-o", tmp_path / "out")
    assert_refused(proc, shown)
    assert not any(ord(c) < 0x20 and c != "\n" for c in proc.stderr), repr(proc.stderr)
    assert not (tmp_path / "out").exists()
    with pytest.raises(rigid.Error, match="is not a valid name"):
        rigid.sweep(path, grid=["m\n=1:2:2"])


# A scene file named with the byte 0xff ran to the end and then failed in the JSON writer
# ("[json.exception.type_error.316] invalid UTF-8 byte"), writing nothing. The name is shown
# escaped (\xff) in summary.json, and the run writes its files.
def test_a_file_name_of_any_bytes_is_escaped_in_json(rigid_exe, tmp_path):
    import json
    import os
    import subprocess
    text = OSCILLATOR.replace("TOLERANCE", "1e-8")
    raw = os.path.join(os.fsencode(tmp_path), b"\xff\x1b.toml")
    with open(raw, "wb") as f:
        f.write(text.encode())
    out = tmp_path / "out"
    proc = subprocess.run([os.fsencode(rigid_exe), b"run", raw, b"-o", os.fsencode(out)],
                          capture_output=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert b"json.exception" not in proc.stderr
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["scene"].endswith("\\xff\\x1b.toml"), summary["scene"]
    assert (out / "trajectory.csv").exists()


# The same for the robot-model commands that write JSON: `eom --regressor --json` and
# `inertia fix --format json` name the model file, escaped; a link name with an invalid UTF-8
# byte (XML text is not checked) is replaced, never a json.exception.
def test_robot_model_json_names_a_file_of_any_bytes(rigid_exe, tmp_path):
    import json
    import os
    import subprocess
    examples = pathlib.Path(__file__).resolve().parents[2] / "examples"
    source = (examples / "cart_arm.urdf").read_bytes()
    raw = os.path.join(os.fsencode(tmp_path), b"\xff\x1barm.urdf")
    with open(raw, "wb") as f:
        f.write(source.replace(b'"cart"', b'"cart\xfe"'))
    exe = os.fsencode(rigid_exe)
    for args in ([b"eom", raw, b"--regressor", b"--json"],
                 [b"inertia", b"fix", raw, b"--format", b"json", b"-o",
                  os.fsencode(tmp_path / "fixed.urdf")]):
        proc = subprocess.run([exe, *args], capture_output=True, timeout=60)
        assert proc.returncode == 0, proc.stderr
        assert b"json.exception" not in proc.stderr
        doc = json.loads(proc.stdout.decode("utf-8"))
        assert doc.get("model", doc.get("file")).endswith("\\xff\\x1barm.urdf"), doc


# An error located in such a file (file:line:col) names it escaped too: no raw 0xff or ESC byte
# reaches the terminal.
def test_a_located_error_escapes_the_file_name(rigid_exe, tmp_path):
    import os
    import subprocess
    text = OSCILLATOR.replace("TOLERANCE", "1e-8").replace('name = "x"', 'name = "x"\nbogus = 1')
    raw = os.path.join(os.fsencode(tmp_path), b"\xff\x1bbad.toml")
    with open(raw, "wb") as f:
        f.write(text.encode())
    proc = subprocess.run([os.fsencode(rigid_exe), b"check", raw], capture_output=True, timeout=60)
    assert proc.returncode == 1, proc.stderr
    assert b"\\xff\\x1bbad.toml:" in proc.stderr, proc.stderr
    assert b"\xff" not in proc.stderr and b"\x1b" not in proc.stderr, proc.stderr
