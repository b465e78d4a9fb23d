"""`rigid inertia`: primitives in every output format, and `rigid inertia check`."""
import json
import math
import xml.etree.ElementTree as ET

import pytest

# closed forms are a few flops: agreement to 1e-12 relative is the bar
REL = 1e-12


def cone_expected(m=2.5, r=0.3, h=1.2):
    ixx = m * (3 * r * r / 20 + 3 * h * h / 80)
    return ixx, ixx, 0.3 * m * r * r


def test_cone_urdf_matches_closed_form(run):
    out = run("inertia", "cone", "--radius", 0.3, "--height", 1.2, "--mass", 2.5,
              "--format", "urdf", check=True).stdout
    inertial = ET.fromstring(out).find("link/inertial")
    assert inertial.find("mass").get("value") == "2.5"
    xyz = [float(v) for v in inertial.find("origin").get("xyz").split()]
    assert xyz == pytest.approx([0, 0, 1.2 / 4], rel=REL, abs=0)
    inertia = inertial.find("inertia").attrib
    ixx, iyy, izz = cone_expected()
    assert float(inertia["ixx"]) == pytest.approx(ixx, rel=REL)
    assert float(inertia["iyy"]) == pytest.approx(iyy, rel=REL)
    assert float(inertia["izz"]) == pytest.approx(izz, rel=REL)
    assert float(inertia["ixy"]) == 0.0


def test_json_round_trips_the_same_doubles_as_urdf(run):
    args = ("inertia", "box", "--lx", 0.1, "--ly", 0.7, "--lz", 0.3, "--density", 1234.5)
    j = json.loads(run(*args, "--format", "json", check=True).stdout)
    urdf = ET.fromstring(run(*args, "--format", "urdf", check=True).stdout)
    # both print shortest round-trip doubles: the JSON value reprints as the URDF text
    assert repr(j["mass"]) == urdf.find("link/inertial/mass").get("value")
    assert repr(j["inertia"][0][0]) == urdf.find("link/inertial/inertia").get("ixx")
    m = 1234.5 * 0.1 * 0.7 * 0.3
    assert j["mass"] == pytest.approx(m, rel=REL)
    assert j["inertia"][2][2] == pytest.approx(m * (0.01 + 0.49) / 12, rel=REL)


def test_about_point_uses_parallel_axis(run):
    j = json.loads(run("inertia", "sphere", "--radius", 0.5, "--mass", 2, "--about", "0,0,1",
                       "--format", "json", check=True).stdout)
    # I_xx about (0, 0, 1) = 2/5 m r² + m·1²
    assert j["inertia"][0][0] == pytest.approx(0.4 * 2 * 0.25 + 2, rel=REL)
    assert j["inertia"][2][2] == pytest.approx(0.4 * 2 * 0.25, rel=REL)
    assert j["about"] == [0, 0, 1]


def test_tetrahedron_about_origin(run):
    # unit corner tetrahedron of mass 1: about the origin ∫x² dm = 1/10, ∫xy dm = 1/20
    j = json.loads(run("inertia", "tetrahedron", "--v0", "0,0,0", "--v1", "1,0,0", "--v2", "0,1,0",
                       "--v3", "0,0,1", "--mass", 1, "--about", "origin", "--format", "json",
                       check=True).stdout)
    assert j["com"] == pytest.approx([0.25] * 3, rel=REL)
    assert j["inertia"][0][0] == pytest.approx(0.2, rel=REL)
    assert j["inertia"][0][1] == pytest.approx(-0.05, rel=REL)


def test_principal_frame_json_and_mjcf(run):
    j = json.loads(run("inertia", "box", "--lx", 3, "--ly", 1, "--lz", 2, "--mass", 12,
                       "--frame", "principal", "--format", "json", check=True).stdout)
    # moments ascending: m(1+4)/12, m(9+1)/12, m(9+4)/12... sorted
    assert j["principal_moments"] == pytest.approx(sorted([5.0, 13.0, 10.0]), rel=REL)
    mjcf = ET.fromstring(run("inertia", "cone", "--radius", 0.3, "--height", 1.2, "--mass", 2.5,
                             "--frame", "principal", "--format", "mjcf", check=True).stdout)
    inertial = mjcf.find("worldbody/body/inertial")
    assert inertial.get("quat") is not None
    diag = [float(v) for v in inertial.get("diaginertia").split()]
    assert diag == pytest.approx(sorted(cone_expected()), rel=REL)


def test_text_output_for_people(run):
    out = run("inertia", "cylinder", "--radius", 0.1, "--height", 0.5, "--mass", 3,
              check=True).stdout
    assert "mass            3 kg" in out
    assert "center of mass  [0, 0, 0] m" in out
    assert "(kg·m²)" in out
    rows = [line for line in out.splitlines() if line.strip().startswith("[")]
    assert len(rows) == 3 and len({len(r) for r in rows}) == 1  # aligned columns


def test_sdf_output_parses(run):
    sdf = ET.fromstring(run("inertia", "torus", "--major-radius", 0.5, "--minor-radius", 0.1,
                            "--mass", 1, "--format", "sdf", check=True).stdout)
    izz = float(sdf.find("model/link/inertial/inertia/izz").text)
    assert izz == pytest.approx(0.25 + 0.75 * 0.01, rel=REL)


@pytest.mark.parametrize("args,message", [
    (("cone", "--radius", 0.3, "--height", 1), "give exactly one of --mass (kg) and --density (kg/m³), got neither"),
    (("cone", "--radius", 0.3, "--height", 1, "--mass", 1, "--density", 2), "got both"),
    (("cone", "--radius", -0.3, "--height", 1, "--mass", 1), "radius must be positive and finite, got -0.3 m"),
    (("cone", "--radius", "nan", "--height", 1, "--mass", 1), "radius must be positive and finite, got nan m"),
    (("cone", "--radius", "inf", "--height", 1, "--mass", 1), "got inf m"),
    (("cone", "--radius", 0, "--height", 1, "--mass", 1), "got 0 m"),
    (("cone", "--height", 1, "--mass", 1), "cone needs --radius"),
    (("tube", "--inner-radius", 0.2, "--outer-radius", 0.1, "--height", 1, "--mass", 1), "inner radius must be less than outer radius"),
    (("disk", "--radius", 1, "--density", -1), "density must be positive and finite, got -1 kg/m²"),
    (("blob", "--radius", 1), "unknown primitive 'blob'; expected one of solid-sphere"),
        (("cylindr", "--radius", 1), "unknown primitive 'cylindr'; did you mean 'cylinder'?"),
    (("sphere", "--radius", 1, "--mass", 1, "--about", "1,2"), "--about must be a point 'x,y,z' in metres, got '1,2'"),
    (("sphere", "--radius", 1, "--mass", 1, "--about", "centre"), "--about must be 'com', 'origin' or a point 'x,y,z'"),
    (("tetrahedron", "--v0", "0,0,0", "--v1", "1,0,0", "--v2", "0,1,0", "--mass", 1), "tetrahedron needs --v3"),
    (("tetrahedron", "--v0", "0,0,0", "--v1", "1,0,0", "--v2", "0,1,0", "--v3", "1,1,0", "--mass", 1), "the tetrahedron is degenerate"),
    (("sphere", "--radius", 1, "--mass", 1, "--format", "yaml"), "--format must be one of text, json, urdf, mjcf, sdf, pseudo, log-cholesky; got 'yaml'"),
    (("sphere", "--radius", 1, "--mass", 1, "--frame", "world"), "--frame must be 'body' or 'principal'"),
    (("sphere", "--radius", 1, "--mass", 1, "--format", "urdf", "--about", "0,0,1", "--frame", "principal"),
     "urdf gives the principal axes of the inertia about the center of mass"),
])
def test_bad_input_messages(run, args, message):
    proc = run("inertia", *args, check=False)
    assert message in proc.stderr
    assert proc.stdout == ""


def test_unknown_option(run):
    proc = run("inertia", "cone", "--radiu", 0.3, "--height", 1, "--mass", 1, check=False)
    assert proc.returncode == 2
    assert "unknown option '--radiu' for `rigid inertia cone`; did you mean '--radius'?" in proc.stderr


BAD_URDF = """<robot name="r">
  <link name="good"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="flat">
    <inertial>
      <mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="4"/>
    </inertial>
  </link>
  <link name="signs"><inertial><mass value="1"/><inertia ixx="1" ixy="2" ixz="0" iyy="1" iyz="0" izz="2"/></inertial></link>
</robot>
"""


def test_check_lists_invalid_inertials_with_lines(run, tmp_path):
    f = tmp_path / "bad.urdf"
    f.write_text(BAD_URDF)
    proc = run("inertia", "check", f, check=False)
    assert proc.returncode == 1
    assert f"{f}:4: 'flat': principal moments (1, 2, 4) kg·m² violate I₁ + I₂ ≥ I₃ by 1 kg·m²" in proc.stdout
    assert f"{f}:8: 'signs': inertia tensor is not positive semidefinite" in proc.stdout
    assert "3 inertials, 2 invalid" in proc.stdout
    assert "2 of 3 inertials" in proc.stderr


def test_check_accepts_written_files_in_every_format(run, tmp_path):
    for fmt in ("urdf", "mjcf", "sdf"):
        for frame in ("body", "principal"):
            out = tmp_path / f"cone_{frame}.{fmt}"
            run("inertia", "cone", "--radius", 0.3, "--height", 1.2, "--mass", 2.5, "--format", fmt,
                "--frame", frame, "--name", "cone", "-o", out, check=True)
            proc = run("inertia", "check", out, check=True)
            assert "1 inertial, 0 invalid" in proc.stdout


def test_check_malformed_xml(run, tmp_path):
    f = tmp_path / "broken.urdf"
    f.write_text("<robot>\n  <link name='a'>\n</robot>\n")
    proc = run("inertia", "check", f, check=False)
    assert f"{f}:2: malformed XML" in proc.stderr
    proc = run("inertia", "check", tmp_path / "missing.urdf", check=False)
    assert "missing.urdf' does not exist" in proc.stderr
