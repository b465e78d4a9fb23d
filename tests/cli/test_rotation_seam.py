"""One rotation through every front end: `rigid rotation` (CLI), rigid.so3 (batch), rigid.SO3
(scalar) and scipy.spatial.transform.Rotation, on the same inputs.

The three rigid front ends call the same library functions on the same doubles (angles in
rad, so no unit conversion differs; the CLI prints shortest round-trip doubles, which parse
back exactly), so among themselves they agree bit for bit, except where one of them normalises
a quaternion that the other does not (or normalises it differently): there to a few ulps
(2e-15 allowed), as said at each such comparison. SciPy is an independent
implementation: matrices agree to 1e-12 (entries O(1), a few dozen roundings each side ≈
1e-15; the margin is the brief's), Euler angles away from gimbal lock to 1e-12 rad too (the
inputs below have middle angles ≥ 0.2 rad from the lock, so the condition factor is ≤ 5).

Refusals: where the front ends share a library check (unknown Euler sequence, a zero
quaternion, a matrix that is not a rotation) they give the same message after their own
prefix; a NaN angle is refused by all three, by the CLI already while parsing its option.
"""
import math
import re
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation  # python3-scipy: missing fails, never skips

import rigid

TOL = 1e-12


def cli(run, *args):
    out = run("rotation", *args, "--unit", "rad", check=True).stdout
    lines = out.splitlines()

    def nums(text):
        return np.array([float(x) for x in re.findall(r"-?[0-9.]+(?:e[-+]?[0-9]+)?", text)])

    res = {}
    for i, line in enumerate(lines):
        head, _, tail = line.partition(":")
        if head.startswith("quaternion"):
            res["quaternion"] = nums(tail)
            res["order"] = "xyzw" if "(x, y, z, w)" in head else "wxyz"
        elif head == "matrix":
            res["matrix"] = np.array([nums(lines[i + k]) for k in (1, 2, 3)])
        elif head.startswith("euler"):
            res["euler"] = nums(tail)
        elif head.startswith("rotation vector"):
            res["rotvec"] = nums(tail)
    return res


def arg(v):
    return ",".join(repr(float(x)) for x in np.ravel(v))


SEQUENCES = ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"]


@pytest.mark.parametrize("intrinsic", [True, False])
@pytest.mark.parametrize("sequence", SEQUENCES)
def test_euler_input_gives_one_rotation_everywhere(run, sequence, intrinsic):
    angles = np.array([0.7, 1.1 if sequence[0] == sequence[2] else -0.6, -2.3])
    flags = [] if intrinsic else ["--extrinsic"]
    c = cli(run, "--euler", arg(angles), "--convention", sequence, *flags)
    batch_q = rigid.so3.from_euler(angles[None, :], sequence, intrinsic=intrinsic)[0]
    scalar = rigid.SO3.from_euler(angles, sequence, intrinsic)
    M = c["matrix"]
    # rigid's three front ends: the same doubles
    assert np.array_equal(batch_q, scalar.quaternion())
    assert np.array_equal(M, scalar.matrix())
    assert np.array_equal(c["euler"], scalar.to_euler(sequence, intrinsic))
    assert np.array_equal(c["rotvec"], scalar.log())
    # rigid.so3 normalises the quaternions it is given (a Newton step; SO3.from_quaternion
    # divides by the norm): a quaternion of norm 1 ± 1 ulp moves by an ulp, so the matrix and
    # angles computed from batch_q agree to a few ulps (4e-16 seen; 2e-15 allowed), not bitwise
    assert np.abs(M - rigid.so3.to_matrix(batch_q)).max() < 2e-15
    assert np.abs(c["euler"] - rigid.so3.to_euler(batch_q, sequence, intrinsic=intrinsic)).max() < 2e-15
    # the CLI prints the quaternion with w ≥ 0; the same rotation up to sign
    q = scalar.quaternion()
    assert np.array_equal(c["quaternion"], q if q[0] >= 0 else -q)
    # SciPy: upper case intrinsic, lower case extrinsic
    ref = Rotation.from_euler(sequence.upper() if intrinsic else sequence.lower(), angles)
    assert np.abs(M - ref.as_matrix()).max() < TOL
    assert np.abs(c["euler"] - angles).max() < TOL  # inside the output ranges: the input back
    assert np.abs(c["euler"] - ref.as_euler(sequence.upper() if intrinsic else sequence.lower())).max() < TOL
    assert np.abs(c["rotvec"] - ref.as_rotvec()).max() < TOL


@pytest.mark.parametrize("order", ["wxyz", "xyzw"])
def test_quaternion_input_in_both_orders(run, order):
    rng = np.random.default_rng(11)
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    c = cli(run, "--quaternion", arg(q), "--order", order)
    assert c["order"] == order
    scalar = rigid.SO3.from_quaternion(*(q if order == "wxyz" else q[[3, 0, 1, 2]]))
    # the CLI first divides the four numbers by the largest (so that huge ones cannot overflow
    # the norm), a different rounding of the same normalisation: a few ulps apart
    assert np.abs(c["matrix"] - scalar.matrix()).max() < 2e-15
    # rigid.so3 normalises by a Newton step, SO3.from_quaternion by the norm: an ulp apart
    assert np.abs(scalar.matrix() - rigid.so3.to_matrix(q, order=order)).max() < 2e-15
    xyzw = q if order == "xyzw" else q[[1, 2, 3, 0]]
    ref = Rotation.from_quat(xyzw)
    assert np.abs(c["matrix"] - ref.as_matrix()).max() < TOL
    # printed with w ≥ 0 in the order asked for; SciPy's as_quat is xyzw
    ref_q = ref.as_quat()
    ref_q = ref_q if ref_q[3] >= 0 else -ref_q
    assert np.abs(c["quaternion"] - (ref_q if order == "xyzw" else ref_q[[3, 0, 1, 2]])).max() < TOL


def test_matrix_and_rotation_vector_inputs(run):
    w = np.array([0.4, -1.3, 2.2])
    c = cli(run, "--rotvec", arg(w))
    assert np.array_equal(c["matrix"], rigid.so3.exp(w, output="matrix"))
    assert np.array_equal(c["matrix"], rigid.SO3.exp(w).matrix())
    assert np.abs(c["matrix"] - Rotation.from_rotvec(w).as_matrix()).max() < TOL
    M = Rotation.from_rotvec(w).as_matrix()
    c2 = cli(run, "--matrix", arg(M))
    assert np.array_equal(c2["matrix"], rigid.so3.to_matrix(rigid.so3.from_matrix(M)))
    assert np.array_equal(c2["rotvec"], rigid.so3.log(rigid.so3.from_matrix(M)))
    assert np.abs(c2["rotvec"] - w).max() < TOL


def refusals(run, cli_args, batch_call, scalar_call, usage_or_input=1):
    proc = run("rotation", *cli_args, check=False)
    # a value none of the option's forms (an unknown sequence, not a number) is a usage error (2);
    # a well-formed value the library refuses, an input error (1)
    assert proc.returncode == usage_or_input and proc.stderr.startswith("rigid: error: ")
    with pytest.raises(rigid.Error) as b:
        batch_call()
    with pytest.raises(rigid.Error) as s:
        scalar_call()
    first_line = proc.stderr.splitlines()[0]
    return first_line.removeprefix("rigid: error: "), str(b.value), str(s.value)


def test_unknown_sequence_is_refused_alike(run):
    expected = ("unknown Euler sequence 'XXY', expected one of XYZ, XZY, YXZ, YZX, ZXY, ZYX, XYX, XZX, "
                "YXY, YZY, ZXZ, ZYZ; did you mean 'XZY'?")
    c, b, s = refusals(run, ["--euler", "1,2,3", "--convention", "XXY"],
                       lambda: rigid.so3.from_euler([[1.0, 2.0, 3.0]], "XXY"),
                       lambda: rigid.SO3.from_euler(np.array([1.0, 2.0, 3.0]), "XXY"), usage_or_input=2)
    assert c == b == s == expected
    with pytest.raises(ValueError):  # SciPy refuses too, in its own words
        Rotation.from_euler("XXY", [1.0, 2.0, 3.0])


def test_nan_angle_is_refused_by_every_rigid_front_end(run):
    c, b, s = refusals(run, ["--euler", "1,2,nan"],
                       lambda: rigid.so3.from_euler([[1.0, 2.0, math.nan]], "ZYX"),
                       lambda: rigid.SO3.from_euler(np.array([1.0, 2.0, math.nan]), "ZYX"), usage_or_input=2)
    # the CLI refuses while parsing its option; Python the library's check, with the argument
    assert c == "--euler: value nan is not finite"
    assert s == "Euler angles [1, 2, nan] have a non-finite component"
    assert b == "so3.from_euler(): argument 'angles' row 0: " + s


def test_zero_quaternion_and_non_rotation_matrix_are_refused_alike(run):
    c, b, s = refusals(run, ["--quaternion", "0,0,0,0"],
                       lambda: rigid.so3.to_matrix([[0.0, 0.0, 0.0, 0.0]]),
                       lambda: rigid.SO3.from_quaternion(0.0, 0.0, 0.0, 0.0))
    assert c == s and b == "so3.to_matrix(): argument 'q' row 0: " + s
    assert "has norm 0, expected a nonzero quaternion" in s
    M = np.diag([1.0, 1.0, -1.0])
    c, b, s = refusals(run, ["--matrix", arg(M)], lambda: rigid.so3.from_matrix(M[None]),
                       lambda: rigid.SO3.from_matrix(M))
    assert c == s and b == "so3.from_matrix(): argument 'R' row 0: " + s
    assert "determinant -1 (expected +1)" in s


def test_unknown_quaternion_order_is_refused_alike(run):
    proc = run("rotation", "--quaternion", "1,0,0,0", "--order", "wzyx", check=False)
    with pytest.raises(rigid.Error) as b:
        rigid.so3.log([1.0, 0.0, 0.0, 0.0], order="wzyx")
    tail = "is 'wzyx', expected wxyz or xyzw"
    assert proc.returncode == 2
    assert proc.stderr.splitlines()[0] == "rigid: error: --order " + tail
    assert str(b.value) == "so3.log(): order " + tail


if __name__ == "__main__":
    sys.exit(pytest.main([__file__]))
