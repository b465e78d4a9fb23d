"""`rigid rotation` against closed forms computed here with numpy."""
import math
import re

import numpy as np
import pytest


def numbers(line):
    return np.array([float(x) for x in re.findall(r"-?[0-9.]+(?:e-?[0-9]+)?|nan", line.split(":", 1)[1])])


def parse(out):
    lines = out.splitlines()
    res = {}
    for i, line in enumerate(lines):
        if line.startswith("quaternion"):
            res["quaternion_label"] = line.split(":")[0]
            res["quaternion"] = numbers(line)
        elif line.startswith("matrix:"):
            res["matrix"] = np.array([numbers(":" + lines[i + k]) for k in (1, 2, 3)])
        elif line.startswith("euler"):
            res["euler_label"] = line.split(":")[0]
            res["euler"] = numbers(line)
        elif line.startswith("rotation vector"):
            res["rotvec"] = numbers(line)
    return res


def rot(axis, t):
    c, s = math.cos(t), math.sin(t)
    return {"x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
            "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis]


# Printed with shortest round-trip doubles: agreement to 1e-14 leaves ~50 ulps for the
# chain of products.
TOL = 1e-14


def test_euler_zyx_degrees_to_matrix_and_quaternion(run):
    r = parse(run("rotation", "--euler", "30,20,10", check=True).stdout)
    expected = rot("z", math.radians(30)) @ rot("y", math.radians(20)) @ rot("x", math.radians(10))
    assert np.abs(r["matrix"] - expected).max() < TOL
    assert r["quaternion_label"] == "quaternion (w, x, y, z)"
    w, x, y, z = r["quaternion"]
    assert w >= 0
    assert abs(w - math.sqrt(1 + np.trace(expected)) / 2) < TOL
    assert r["euler_label"] == "euler ZYX intrinsic (deg)"
    assert np.abs(r["euler"] - [30, 20, 10]).max() < 1e-12


def test_extrinsic_xyz_equals_intrinsic_zyx_reversed(run):
    r = parse(run("rotation", "--euler", "10,20,30", "--convention", "xyz", "--extrinsic", check=True).stdout)
    expected = rot("z", math.radians(30)) @ rot("y", math.radians(20)) @ rot("x", math.radians(10))
    assert np.abs(r["matrix"] - expected).max() < TOL
    assert r["euler_label"] == "euler XYZ extrinsic (deg)"


def test_quaternion_xyzw_order_is_stated(run):
    # 180 deg about z: (x, y, z, w) = (0, 0, 1, 0).
    r = parse(run("rotation", "--quaternion", "0,0,1,0", "--order", "xyzw", "--unit", "rad", check=True).stdout)
    assert r["quaternion_label"] == "quaternion (x, y, z, w)"
    assert np.abs(r["matrix"] - np.diag([-1.0, -1.0, 1.0])).max() < TOL
    assert abs(np.linalg.norm(r["rotvec"]) - math.pi) < TOL


def test_axis_angle_radians_and_proper_euler_output(run):
    r = parse(run("rotation", "--axis-angle", "0,0,2,1.5", "--unit", "rad", "--out-convention", "ZXZ",
                  check=True).stdout)
    assert np.abs(r["matrix"] - rot("z", 1.5)).max() < TOL
    assert np.abs(r["rotvec"] - [0, 0, 1.5]).max() < TOL
    # A pure z rotation is the gimbal-locked case of ZXZ: third angle 0 by convention.
    assert r["euler_label"] == "euler ZXZ intrinsic (rad)"
    assert np.abs(r["euler"] - [1.5, 0, 0]).max() < TOL


def test_matrix_input_round_trips(run):
    M = rot("x", 0.3) @ rot("y", -1.1) @ rot("z", 2.0)
    r = parse(run("rotation", "--matrix", ",".join(repr(float(v)) for v in M.ravel()), check=True).stdout)
    assert np.abs(r["matrix"] - M).max() < TOL


# exit status: 1 for a well-formed value the library refuses, 2 (usage) for a value that is none
# of the option's forms (not a number, a wrong count, an unknown name)
@pytest.mark.parametrize("args, message, status", [
    (["--axis-angle", "0,0,0,10"], "axis [0, 0, 0] has norm 0, expected a nonzero axis", 1),
    (["--matrix", "1,0.001,0,0,1,0,0,0,1"],
     "is not a rotation: orthonormality defect max|RᵀR − I| = 0.001 (tolerance 1e-09)", 1),
    (["--matrix", "1,0,0,0,1,0,0,0,-1"], "determinant -1 (expected +1)", 1),
    (["--euler", "1,2,nan"], "--euler: value nan is not finite", 2),
    (["--euler", "1,2"], "--euler takes 3 comma-separated numbers, got 2", 2),
    (["--euler", "1,2,3", "--convention", "XXY"],
     "unknown Euler sequence 'XXY', expected one of XYZ, XZY, YXZ, YZX, ZXY, ZYX, XYX, XZX, YXY, YZY, ZXZ, ZYZ", 2),
    (["--quaternion", "0,0,0,0"], "has norm 0, expected a nonzero quaternion", 1),
    (["--euler", "1,2,3", "--unit", "grad"], "--unit is 'grad', expected deg or rad", 2),
    (["--euler", "1,2,3", "--unit", "degs"], "--unit is 'degs', expected deg or rad; did you mean 'deg'?", 2),
    (["--quaternion", "1,0,0,0", "--order", "wzyx"], "--order is 'wzyx', expected wxyz or xyzw", 2),
])
def test_bad_input(run, args, message, status):
    proc = run("rotation", *args, check=False)
    assert proc.returncode == status
    assert proc.stderr.startswith("rigid: error: ")
    assert message in proc.stderr


def test_exactly_one_input_form(run):
    proc = run("rotation", "--euler", "1,2,3", "--quaternion", "1,0,0,0", check=False)
    assert "Exactly 1 option" in proc.stderr


def test_demo_is_computed(run):
    out = run("demo", check=True).stdout
    # The 120 deg composition of two quarter turns about x and z.
    m = re.search(r"angle\(Rz\*Rx\)\s+= ([0-9.e-]+) deg", out)
    assert m and abs(float(m.group(1)) - 120) < 1e-12
