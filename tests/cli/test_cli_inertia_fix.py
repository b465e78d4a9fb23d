"""`rigid inertia fix MODEL`: inertials recomputed from a model's geometry, through the command
line and Python (the same answer and the same refusal)."""
import json
import math
import os
import re
import subprocess

import pytest

HUMANOID = "/usr/share/mujoco/model/humanoid/humanoid.xml"

# a unit cube with a corner at the origin, outward faces
CUBE_OBJ = ("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
            "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
            "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n")

ROBOT = """<?xml version="1.0"?>
<!-- wrong inertials on purpose -->
<robot name="r">
  <link name="base">
    <inertial>
      <mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><box size="0.2 0.3 0.4"/></geometry></collision>
  </link>
  <link name="arm">
    <collision>
      <origin xyz="0 0 0.25" rpy="1.5707963267948966 0 0"/>
      <geometry><cylinder radius="0.05" length="0.5"/></geometry>
    </collision>
    <collision>
      <geometry><mesh filename="package://parts/cube.obj" scale="0.1 0.2 0.3"/></geometry>
    </collision>
  </link>
</robot>
"""


def without_inertials(text):
    """The text with every <inertial> element (and the blank line it sits on) removed."""
    return re.sub(r"\n[ \t]*<inertial\b(?:[^>]*/>|.*?</inertial>)", "", text, flags=re.S)


@pytest.fixture
def robot(tmp_path):
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "cube.obj").write_text(CUBE_OBJ)
    model = tmp_path / "robot.urdf"
    model.write_text(ROBOT)
    return model


def test_humanoid_is_fixed_and_only_inertials_change(run, tmp_path):
    out = tmp_path / "out.xml"
    proc = run("inertia", "fix", HUMANOID, "-o", out, check=True)
    rows = [l for l in proc.stdout.splitlines() if " missing " in l]
    assert len(rows) == 16  # every body of the humanoid has geoms and no <inertial>
    text = out.read_text()
    assert text.count("<inertial ") == 16
    assert without_inertials(text) == open(HUMANOID).read()


def test_urdf_fixed_then_check_passes(run, robot, tmp_path):
    out = tmp_path / "fixed.urdf"
    proc = run("inertia", "fix", robot, "--density", 2700, "--package-path",
               f"parts={tmp_path / 'parts'}", "--format", "json", "-o", out, check=True)
    report = json.loads(proc.stdout)
    assert [l["reason"] for l in report["links"]] == ["placeholder", "missing"]
    # the box, 0.2 × 0.3 × 0.4 m at 2700 kg/m³: m = 64.8 kg, I_xx = m (0.3² + 0.4²)/12
    base = report["links"][0]["new"]
    assert base["mass"] == pytest.approx(2700 * 0.024, rel=1e-14)
    assert base["inertia_com"][0][0] == pytest.approx(64.8 * 0.25 / 12, rel=1e-14)
    # the arm: cylinder (ρ π r² l) + the cube scaled to 0.1 × 0.2 × 0.3 m (ρ · 0.006)
    arm = report["links"][1]["new"]
    assert arm["mass"] == pytest.approx(2700 * (math.pi * 0.05**2 * 0.5 + 0.006), rel=1e-13)
    run("inertia", "check", out, check=True)
    assert without_inertials(out.read_text()) == without_inertials(ROBOT)


def test_assumed_density_is_said_in_cli_terms(run, robot, tmp_path):
    proc = run("inertia", "fix", robot, "--package-path", f"parts={tmp_path / 'parts'}",
               check=True)
    assert "1000 kg/m³ (water) assumed" in proc.stdout
    assert "--density RHO" in proc.stdout and "--keep-mass" in proc.stdout


def test_keep_mass_is_not_advised_to_who_gave_it(run, robot, tmp_path):
    # with --keep-mass the base keeps its stated 1 kg and only the arm, which states no mass,
    # gets water's density: the warning went on "or keep the stated masses with --keep-mass"
    proc = run("inertia", "fix", robot, "--keep-mass", "--package-path",
               f"parts={tmp_path / 'parts'}", check=True)
    assert ("no density given: 1000 kg/m³ (water) assumed for the geometry of every link without "
            "a valid stated mass to keep; give the material's with --density RHO") in proc.stdout
    assert "keep the stated masses" not in proc.stdout
    report = json.loads(run("inertia", "fix", robot, "--keep-mass", "--package-path",
                            f"parts={tmp_path / 'parts'}", "--format", "json", check=True).stdout)
    assert report["links"][0]["new"]["mass"] == pytest.approx(1, rel=1e-15)  # kept
    # the arm at 1000 kg/m³: cylinder π r² l and the scaled cube 0.1 × 0.2 × 0.3 m
    assert report["links"][1]["new"]["mass"] == pytest.approx(
        1000 * (math.pi * 0.05**2 * 0.5 + 0.006), rel=1e-13)
    # Python words the same warning with its keywords
    import rigid
    r = rigid.mass.fix_inertials(str(robot), keep_mass=True,
                                 package_path=f"parts={tmp_path / 'parts'}")
    assert any("without a valid stated mass to keep" in w for w in r["warnings"]), r["warnings"]
    assert not any("keep_mass=True" in w for w in r["warnings"]), r["warnings"]


def test_unfixable_links_exit_1_and_write_nothing(run, tmp_path):
    model = tmp_path / "bad.urdf"
    model.write_text('<robot name="b">\n  <link name="l">\n    <collision><geometry>'
                     '<mesh filename="missing.stl"/></geometry></collision>\n  </link>\n</robot>\n')
    out = tmp_path / "out.urdf"
    proc = run("inertia", "fix", model, "-o", out, check=False)
    assert proc.returncode == 1
    assert f"{model}:2: link 'l': <collision> mesh (line 3): mesh file" in proc.stderr
    assert "does not exist" in proc.stderr and "nothing was written" in proc.stderr
    assert "NOT FIXED" in proc.stdout
    assert not out.exists()
    assert os.listdir(tmp_path) == ["bad.urdf"]  # no temporary left behind either


def test_unknown_package_names_the_cli_option(run, robot):
    proc = run("inertia", "fix", robot, check=False)
    assert proc.returncode == 1
    assert "give it with --package-path parts=DIR" in proc.stderr


def test_python_gives_the_same_answer_and_refusal(run, robot, tmp_path):
    rigid = pytest.importorskip("rigid")
    package = f"parts={tmp_path / 'parts'}"
    out = tmp_path / "cli.urdf"
    cli = json.loads(run("inertia", "fix", robot, "--density", 2700, "--package-path", package,
                         "--format", "json", "-o", out, check=True).stdout)
    py = rigid.mass.fix_inertials(str(robot), output=str(tmp_path / "py.urdf"), density=2700,
                                  package_path=[package])
    assert py["links"] == cli["links"]  # bit for bit: the same doubles through JSON
    assert py["text"] == out.read_text() == (tmp_path / "py.urdf").read_text()
    # the same refusal, with the remedy in each surface's terms
    with pytest.raises(rigid.Error, match=r"give it with package_path=\"parts=DIR\""):
        rigid.mass.fix_inertials(str(robot))


def test_only_the_named_links_change(run, robot, tmp_path):
    out = tmp_path / "only.urdf"
    proc = run("inertia", "fix", robot, "--density", 1000, "--only", "base", "--format", "json",
               "-o", out, check=True)
    assert [l["name"] for l in json.loads(proc.stdout)["links"]] == ["base"]
    text = out.read_text()
    # base's placeholder replaced (0.024 m³ of water: 24 kg), arm left without an inertial
    assert '<mass value="24"/>' in text
    assert text.count("<inertial>") == 1
    assert text[text.index('<link name="arm">'):] == ROBOT[ROBOT.index('<link name="arm">'):]


# ---------------------------------------------------------------------------------------------
# MJCF <include>, malformed XML and files that are not regular: `check` and `fix` alike

HUMANOID100 = "/usr/share/mujoco/model/humanoid100/humanoid100.xml"

MAIN_XML = """<mujoco model="m">
  <worldbody>
    <body name="base">
      <geom type="sphere" size="0.1"/>
      <include file="parts/arm.xml"/>
    </body>
  </worldbody>
</mujoco>
"""

# line 3: diaginertia 1 2 4 violates I1 + I2 >= I3
ARM_XML = """<mujoco>
  <body name="arm">
    <inertial pos="0 0 0" mass="2" diaginertia="1 2 4"/>
    <geom type="box" size="0.1 0.2 0.3"/>
  </body>
</mujoco>
"""


@pytest.fixture
def included(tmp_path):
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "arm.xml").write_text(ARM_XML)
    main = tmp_path / "main.xml"
    main.write_text(MAIN_XML)
    return main, tmp_path / "parts" / "arm.xml"


@pytest.mark.skipif(not os.path.exists(HUMANOID100), reason="MuJoCo's model directory is not installed")
def test_humanoid100_is_read_through_its_include(run, tmp_path):
    # no body of it states an <inertial>: check finds nothing wrong
    proc = run("inertia", "check", HUMANOID100, check=True)
    assert proc.stdout.endswith("humanoid100.xml: 0 inertials, 0 invalid\n"), proc.stdout
    # fix measures every body: the humanoid's 16 from humanoid_body.xml, then the 100 objects
    out = tmp_path / "humanoid100.xml"
    proc = run("inertia", "fix", HUMANOID100, "--format", "json", "-o", out, check=True)
    report = json.loads(proc.stdout)
    assert len(report["links"]) == 116
    files = [os.path.basename(l["file"]) for l in report["links"]]
    assert files == ["humanoid_body.xml"] * 16 + ["humanoid100.xml"] * 100
    assert all(l["reason"] == "missing" for l in report["links"])
    assert any('<include file="humanoid_body.xml">' in w for w in report["warnings"])
    # one self-contained file: no include left, every body with its inertial, and it fixes
    # again to the same numbers (its bodies now keep the written inertials: "auto")
    text = out.read_text()
    assert "<include" not in text and text.count("<inertial ") == 116
    again = json.loads(run("inertia", "fix", out, "--format", "json", check=True).stdout)
    assert [l["old"]["mass"] for l in again["links"]] == [l["new"]["mass"] for l in report["links"]]
    run("inertia", "check", out, check=True)


def test_check_reports_an_included_inertial_at_its_own_file_and_line(run, included):
    main, arm = included
    proc = run("inertia", "check", main, check=False)
    assert proc.returncode == 1
    assert f"{arm}:3: 'arm': " in proc.stdout
    assert "I₁ + I₂ ≥ I₃" in proc.stdout
    assert f"{main} (with {arm}): 1 inertial, 1 invalid" in proc.stdout
    # fix reports the body at its own file and line, and replaces its invalid inertial
    proc = run("inertia", "fix", main, "--format", "json", check=True)
    arm_row = json.loads(proc.stdout)["links"][1]
    assert (arm_row["name"], arm_row["file"], arm_row["line"], arm_row["reason"]) == \
        ("arm", str(arm), 2, "invalid")


def test_fix_writes_includes_inline_and_leaves_included_files_alone(run, included, tmp_path):
    main, arm = included
    out = tmp_path / "fixed.xml"
    run("inertia", "fix", main, "-o", out, check=True)
    text = out.read_text()
    assert "<include" not in text and '<body name="arm">' in text
    assert arm.read_text() == ARM_XML and main.read_text() == MAIN_XML
    proc = run("inertia", "check", out, check=True)
    assert "2 inertials, 0 invalid" in proc.stdout


def test_a_missing_include_is_refused_naming_it(run, included):
    main, arm = included
    arm.unlink()
    for command in ("check", "fix"):
        proc = run("inertia", command, main, check=False)
        assert proc.returncode == 1
        assert f"{main}:5: <include file=\"parts/arm.xml\">: '{arm}' does not exist" in proc.stderr


def test_truncated_xml_names_the_file_and_line_in_plain_words(run, tmp_path):
    f = tmp_path / "cut.xml"
    f.write_text('<mujoco>\n  <worldbody>\n    <body name="b">\n      <geom type="sph')
    for command in ("check", "fix"):
        proc = run("inertia", command, f, check=False)
        assert proc.returncode == 1
        assert (f"{f}:4: malformed XML: the file ends inside the element <body> of line 3, in the "
                f"middle of the start tag <geom: it is cut short, or </body> is missing") in proc.stderr
        for raw in ("XML_ERROR", "ErrorID", "Line number"):
            assert raw not in proc.stderr


def test_a_fifo_is_refused_without_waiting_for_a_writer(rigid_exe, tmp_path):
    fifo = tmp_path / "model.urdf"
    os.mkfifo(fifo)
    for command in ("check", "fix"):
        # opening a FIFO for reading blocks until a writer comes: the timeout catches that
        proc = subprocess.run([rigid_exe, "inertia", command, str(fifo)], capture_output=True,
                              text=True, timeout=30)
        assert proc.returncode == 1
        assert f"'{fifo}' is not a regular file (a directory, FIFO or device)" in proc.stderr
