"""Every single-file output (`-o` of `rigid inertia --format urdf`, `inertia fix`, `eom --emit`,
`modes`, `report`, `plot`; Python's `report=` and `fix_inertials(output=)`) goes through one
writer, io::write_file_atomically, which renames a temporary over the name. A rename replaced a
FIFO, a socket or a device with a regular file (run as root, `-o /dev/null` replaced /dev/null)
and a symbolic link with a file. Now such a file is refused before anything is written, naming
it and what was expected, and a link is written through: the file it names is replaced, the
link stays (docs/reliability.md, "Single files")."""
import os
import socket
import stat
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PENDULUM = ROOT / "examples" / "physical_pendulum.toml"
TIMEOUT = 60  # s: a writer that opened the FIFO and waited would be stopped here

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="base">
    <collision><geometry><box size="0.2 0.3 0.4"/></geometry></collision>
  </link>
</robot>
"""

REFUSED = "not a regular file; expected a regular file to replace or a new name"


@pytest.fixture(scope="module")
def inputs(tmp_path_factory, rigid_exe):
    base = tmp_path_factory.mktemp("special_inputs")
    run_dir = base / "run"
    proc = subprocess.run([rigid_exe, "run", str(PENDULUM), "--set", "simulation.t_end=0.2", "-q",
                           "-o", str(run_dir)], capture_output=True, text=True, timeout=TIMEOUT)
    assert proc.returncode == 0, proc.stderr
    model = base / "robot.urdf"
    model.write_text(URDF)
    return {"run": run_dir, "model": model}


# each writer's command line, the output's name last; what it writes starts with `head`
COMMANDS = {
    "inertia --format urdf": (lambda i: ["inertia", "box", "--lx", "1", "--ly", "2", "--lz", "3",
                                         "--mass", "4", "--format", "urdf", "-o"], "<?xml"),
    "inertia fix": (lambda i: ["inertia", "fix", str(i["model"]), "--density", "1000", "-o"],
                    "<?xml"),
    "eom --emit": (lambda i: ["eom", str(PENDULUM), "--emit", "python", "-o"], None),
    "modes": (lambda i: ["modes", str(PENDULUM), "-o"], "{"),
    "report": (lambda i: ["report", str(i["run"]), "-o"], "<!doctype html>"),
    "plot": (lambda i: ["plot", str(i["run"]), "--column", "theta", "-o"], "<?xml"),
}


NO_REPORT = "built without the report page"  # a build without node (RIGID_REPORT=OFF)


def rigid(rigid_exe, argv):
    proc = subprocess.run([rigid_exe, *argv], capture_output=True, text=True, timeout=TIMEOUT)
    if NO_REPORT in proc.stderr:
        pytest.skip("this rigid has no report page")
    return proc


def name_for(command):
    # plot writes .svg only; the others take any name
    return "out.svg" if command == "plot" else "out.txt"


@pytest.mark.parametrize("command", COMMANDS)
def test_a_fifo_is_refused_and_kept(rigid_exe, inputs, tmp_path, command):
    argv, _ = COMMANDS[command]
    fifo = tmp_path / name_for(command)
    os.mkfifo(fifo)
    # a reader that never blocks: a writer that opened the FIFO would not wait for one either,
    # so a regression shows as a wrong answer, not a hang
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
    try:
        proc = rigid(rigid_exe, argv(inputs) + [str(fifo)])
        assert proc.returncode == 1, (proc.returncode, proc.stdout, proc.stderr)
        assert f"cannot write '{fifo}': it is a FIFO (named pipe), {REFUSED}" in proc.stderr
        assert "Traceback" not in proc.stderr
        assert os.read(reader, 100) == b""  # nothing was written into it either
    finally:
        os.close(reader)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert sorted(os.listdir(tmp_path)) == [fifo.name]  # no temporary left


@pytest.mark.parametrize("command", COMMANDS)
def test_a_socket_is_refused_and_kept(rigid_exe, inputs, tmp_path, command):
    argv, _ = COMMANDS[command]
    path = tmp_path / name_for(command)
    with socket.socket(socket.AF_UNIX) as server:
        server.bind(str(path))
        proc = rigid(rigid_exe, argv(inputs) + [str(path)])
    assert proc.returncode == 1, (proc.returncode, proc.stderr)
    assert f"cannot write '{path}': it is a socket, {REFUSED}" in proc.stderr
    assert stat.S_ISSOCK(os.lstat(path).st_mode)


@pytest.mark.parametrize("command", COMMANDS)
def test_a_symbolic_link_is_written_through(rigid_exe, inputs, tmp_path, command):
    argv, head = COMMANDS[command]
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / name_for(command)
    target.write_text("old contents\n")
    link = tmp_path / name_for(command)
    link.symlink_to(Path("real") / name_for(command))  # relative, as `ln -s` makes them
    proc = rigid(rigid_exe, argv(inputs) + [str(link)])
    assert proc.returncode == 0, proc.stderr
    assert link.is_symlink() and os.readlink(link) == str(Path("real") / name_for(command))
    text = target.read_text()
    assert text != "old contents\n" and (head is None or text.startswith(head)), text[:80]
    # the temporary was made next to the target and renamed there: nothing else is left
    assert sorted(os.listdir(tmp_path / "real")) == [target.name]
    assert sorted(os.listdir(tmp_path)) == sorted([link.name, "real"])


@pytest.mark.parametrize("command", ["inertia --format urdf", "plot"])
def test_a_link_to_a_special_file_is_refused_naming_both(rigid_exe, inputs, tmp_path, command):
    argv, _ = COMMANDS[command]
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    link = tmp_path / name_for(command)
    link.symlink_to(fifo)
    proc = rigid(rigid_exe, argv(inputs) + [str(link)])
    assert proc.returncode == 1, proc.stderr
    assert f"cannot write '{link}' (a symbolic link to '{fifo}'): it is a FIFO" in proc.stderr
    assert link.is_symlink() and stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_a_character_device_is_refused(rigid_exe, tmp_path):
    # /dev/null for a user; as root (where the rename would have succeeded) a null device of
    # our own (1, 3), so that a regression cannot replace the system's
    device = Path("/dev/null")
    if os.geteuid() == 0:
        device = tmp_path / "null"
        os.mknod(device, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
    proc = rigid(rigid_exe, COMMANDS["inertia --format urdf"][0]({}) + [str(device)])
    assert proc.returncode == 1, proc.stderr
    assert f"cannot write '{device}': it is a character device, {REFUSED}" in proc.stderr
    assert stat.S_ISCHR(os.lstat(device).st_mode)


def test_python_outputs_refuse_a_fifo_and_write_through_a_link(inputs, tmp_path):
    rigid = pytest.importorskip("rigid")
    fifo = tmp_path / "fixed.urdf"
    os.mkfifo(fifo)
    with pytest.raises(rigid.Error, match="it is a FIFO"):
        rigid.mass.fix_inertials(str(inputs["model"]), output=str(fifo), density=1000)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    (tmp_path / "pages").mkdir()
    page = tmp_path / "pages" / "page.html"
    page.write_text("old")
    link = tmp_path / "page.html"
    link.symlink_to(page)
    scene = rigid.Scene(str(PENDULUM), set=["simulation.t_end=0.1"])
    report_fifo = tmp_path / "report.html"
    os.mkfifo(report_fifo)
    with pytest.raises(rigid.Error, match="it is a FIFO|" + NO_REPORT) as refused:
        scene.run(report=str(report_fifo))
    if NO_REPORT in str(refused.value):
        pytest.skip("this rigid has no report page")
    assert stat.S_ISFIFO(os.lstat(report_fifo).st_mode)
    scene.run(report=str(link))
    assert link.is_symlink() and page.read_text().lower().startswith("<!doctype html>")


def test_python_write_stl_refuses_a_fifo_and_writes_through_a_link(tmp_path):
    """rigid.mesh.write_stl goes through the same atomic writer: a FIFO is refused and kept, a
    link's target is replaced, and the file written reads back as the mesh (84 + 50 bytes a
    triangle)."""
    rigid = pytest.importorskip("rigid")
    np = pytest.importorskip("numpy")
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    mesh = rigid.mesh.TriangleMesh(vertices, np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    fifo = tmp_path / "out.stl"
    os.mkfifo(fifo)
    with pytest.raises(rigid.Error, match="it is a FIFO"):
        rigid.mesh.write_stl(mesh, fifo)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    (tmp_path / "meshes").mkdir()
    target = tmp_path / "meshes" / "cube.stl"
    target.write_text("old")
    link = tmp_path / "cube.stl"
    link.symlink_to(target)
    rigid.mesh.write_stl(mesh, link)
    assert link.is_symlink()
    assert target.stat().st_size == 84 + 50 * len(mesh.triangles)
    back = rigid.mesh.read(str(target))
    assert np.allclose(back.vertices[back.triangles], mesh.vertices[mesh.triangles], atol=1e-6)
