"""rigid.so3 (batch) and rigid.SO3 (scalar) against scipy.spatial.transform.Rotation.

10⁴ Haar-random rotations drawn by SciPy (seeded), and random rotation vectors, vectors and
Euler angles drawn by numpy (seeded). Conventions mapped:
- quaternions: SciPy's as_quat/from_quat are scalar-last (x, y, z, w) = rigid's order='xyzw';
  q and −q are the same rotation, so quaternions are compared up to sign (per row);
- Euler: SciPy spells an intrinsic sequence in upper case ('ZYX') and an extrinsic one in
  lower case ('zyx'); rigid takes sequence='ZYX' with intrinsic=True/False. Both put the
  middle angle in [−π/2, π/2] (Tait–Bryan) or [0, π] (proper Euler) and the outer ones in
  [−π, π], so away from gimbal lock the angles themselves are compared (differences wrapped to
  (−π, π], as ±π are the same angle); at and near the lock only the rotation they produce is
  (there SciPy and rigid may split the locked sum differently, and both warn or choose a
  convention for the free angle);
- composition: SciPy's r1 * r2 applies r2 first, as rigid's compose(a, b) = a * b.

Tolerances: entries of rotation matrices and unit quaternions are O(1) and both libraries
compute them with a few dozen roundings, so they agree to ~1e-15; TOL = 1e-13 leaves a factor
≈ 50 for the longest chain (Euler: three axis rotations composed, then converted).
Rotation vectors have |ω| ≤ π: the same absolute 1e-13 (relative ~3e-14).
Euler angles: an angle recovered by atan2 from matrix entries of error ε has error
ε / (distance of the middle angle from the lock); rows within 1e-3 rad of the lock are
compared through their rotation only, the others to 1e-13 / 1e-3 = 1e-10 rad.
"""
import math
import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation  # python3-scipy: missing fails, never skips

import rigid

N = 10_000
TOL = 1e-13
EULER_TOL = 1e-10
LOCK_MARGIN = 1e-3


def same_quaternion(a, b):
    """max over rows of min(|a − b|, |a + b|): the distance between quaternions up to sign."""
    return np.minimum(np.abs(a - b).max(axis=-1), np.abs(a + b).max(axis=-1)).max()


def wrap(d):
    return (d + math.pi) % (2 * math.pi) - math.pi


@pytest.fixture(scope="module")
def sample():
    rng = np.random.default_rng(2019)
    r = Rotation.random(N, random_state=12345)  # SciPy's own Haar sampler
    omega = rng.normal(size=(N, 3)) * rng.uniform(0, math.pi, size=(N, 1))
    return {"r": r, "xyzw": r.as_quat(), "wxyz": r.as_quat()[:, [3, 0, 1, 2]],
            "matrix": r.as_matrix(), "omega": omega, "v": rng.normal(size=(N, 3)),
            "r2": Rotation.random(N, random_state=54321)}


def test_quaternion_orders_and_matrices(sample):
    # the same rotation read in both orders gives SciPy's matrix
    assert np.abs(rigid.so3.to_matrix(sample["wxyz"]) - sample["matrix"]).max() < TOL
    assert np.abs(rigid.so3.to_matrix(sample["xyzw"], order="xyzw") - sample["matrix"]).max() < TOL
    # and matrices convert back to SciPy's quaternion in both orders
    assert same_quaternion(rigid.so3.from_matrix(sample["matrix"], order="xyzw"), sample["xyzw"]) < TOL
    assert same_quaternion(rigid.so3.from_matrix(sample["matrix"]), sample["wxyz"]) < TOL
    # scalar forms
    for q, M in zip(sample["wxyz"][:2000], sample["matrix"][:2000]):
        assert np.abs(rigid.SO3.from_quaternion(*q).matrix() - M).max() < TOL
        assert same_quaternion(rigid.SO3.from_matrix(M).quaternion(), q) < TOL


def test_rotation_vectors_exp_and_log(sample):
    w = sample["omega"]
    ref = Rotation.from_rotvec(w)
    assert same_quaternion(rigid.so3.exp(w, order="xyzw"), ref.as_quat()) < TOL
    assert np.abs(rigid.so3.exp(w, output="matrix") - ref.as_matrix()).max() < TOL
    # log of SciPy's rotations: SciPy's rotvec, angle in [0, π] on both sides
    assert np.abs(rigid.so3.log(sample["xyzw"], order="xyzw") - sample["r"].as_rotvec()).max() < TOL
    for x, q in zip(w[:2000], sample["wxyz"][:2000]):
        assert np.abs(rigid.SO3.exp(x).matrix() - Rotation.from_rotvec(x).as_matrix()).max() < TOL
        assert np.abs(rigid.SO3.from_quaternion(*q).log() - Rotation.from_quat(q[[1, 2, 3, 0]]).as_rotvec()).max() < TOL


def test_small_and_near_pi_rotation_vectors():
    rng = np.random.default_rng(3)
    u = rng.normal(size=(1000, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    for scale in [1e-12, 1e-7, 1e-3, math.pi - 1e-7]:
        w = u * scale
        assert np.abs(rigid.so3.exp(w, output="matrix") - Rotation.from_rotvec(w).as_matrix()).max() < TOL
        # the angle is recovered with relative accuracy (SciPy's as_rotvec is accurate there too)
        got = rigid.so3.log(rigid.so3.exp(w))
        assert np.abs(got - Rotation.from_rotvec(w).as_rotvec()).max() < TOL * max(scale, 1e-3)


def test_composition_and_action(sample):
    a, b = sample["r"], sample["r2"]
    got = rigid.so3.compose(a.as_quat(), b.as_quat(), order="xyzw")
    assert same_quaternion(got, (a * b).as_quat()) < TOL
    v = sample["v"]
    # |v| is ~√3 on average, ≤ ~6: the same O(1) entries, so the same tolerance times |v|
    scale = np.linalg.norm(v, axis=1).max()
    assert np.abs(rigid.so3.act(sample["wxyz"], v) - a.apply(v)).max() < TOL * scale
    assert same_quaternion(rigid.so3.inverse(sample["wxyz"]), a.inv().as_quat()[:, [3, 0, 1, 2]]) < TOL
    # scalar forms: SO3 * SO3 and SO3 * vector
    qa, qb = sample["wxyz"], b.as_quat()[:, [3, 0, 1, 2]]
    for i in range(2000):
        A, B = rigid.SO3.from_quaternion(*qa[i]), rigid.SO3.from_quaternion(*qb[i])
        assert np.abs((A * B).matrix() - (a[i] * b[i]).as_matrix()).max() < TOL
        assert np.abs(A * v[i] - a[i].apply(v[i])).max() < TOL * scale


CONVENTIONS = [(s, intrinsic) for s in ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX",
                                        "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"]
               for intrinsic in (True, False)]


def scipy_seq(sequence, intrinsic):
    return sequence.upper() if intrinsic else sequence.lower()


def lock_distance(sequence, middle):
    """Distance of the middle angle from gimbal lock: ±π/2 (Tait–Bryan), 0 or π (proper)."""
    if sequence[0] == sequence[2]:
        return np.minimum(np.abs(middle), np.abs(math.pi - middle))
    return math.pi / 2 - np.abs(middle)


@pytest.mark.parametrize("sequence, intrinsic", CONVENTIONS)
def test_euler_every_convention(sample, sequence, intrinsic):
    seq = scipy_seq(sequence, intrinsic)
    rng = np.random.default_rng(CONVENTIONS.index((sequence, intrinsic)))
    angles = rng.uniform(-math.pi, math.pi, size=(N, 3))
    angles[:, 1] = rng.uniform(-math.pi / 2, math.pi / 2, N) if sequence[0] != sequence[2] else rng.uniform(0, math.pi, N)
    # angles → rotation: SciPy's matrix, in both quaternion orders
    M_ref = Rotation.from_euler(seq, angles).as_matrix()
    q = rigid.so3.from_euler(angles, sequence, intrinsic=intrinsic)
    assert np.abs(rigid.so3.to_matrix(q) - M_ref).max() < TOL
    q_xyzw = rigid.so3.from_euler(angles, sequence, intrinsic=intrinsic, order="xyzw")
    assert same_quaternion(q_xyzw, Rotation.from_euler(seq, angles).as_quat()) < TOL

    # rotation → angles: SciPy's random rotations
    e = rigid.so3.to_euler(sample["xyzw"], sequence, intrinsic=intrinsic, order="xyzw")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # SciPy's "Gimbal lock detected"
        e_ref = sample["r"].as_euler(seq)
    # both conventions' ranges for the middle angle
    if sequence[0] == sequence[2]:
        assert e[:, 1].min() >= 0 and e[:, 1].max() <= math.pi
    else:
        assert np.abs(e[:, 1]).max() <= math.pi / 2
    assert np.abs(e).max() <= math.pi
    away = lock_distance(sequence, e[:, 1]) > LOCK_MARGIN
    assert away.sum() > 0.99 * N  # the lock region is a small fraction of SO(3)
    assert np.abs(wrap(e[away] - e_ref[away])).max() < EULER_TOL
    # every row, near the lock too: the angles produce SciPy's rotation
    assert np.abs(Rotation.from_euler(seq, e).as_matrix() - sample["matrix"]).max() < TOL
    # scalar forms agree with SciPy on the same rows
    for i in range(0, N, 20):
        R = rigid.SO3.from_quaternion(*sample["wxyz"][i])
        ei = R.to_euler(sequence, intrinsic)
        if away[i]:
            assert np.abs(wrap(ei - e_ref[i])).max() < EULER_TOL
        assert np.abs(rigid.SO3.from_euler(angles[i], sequence, intrinsic).matrix() - M_ref[i]).max() < TOL


@pytest.mark.parametrize("sequence, intrinsic", CONVENTIONS)
def test_euler_at_gimbal_lock_produces_the_rotation(sequence, intrinsic):
    seq = scipy_seq(sequence, intrinsic)
    proper = sequence[0] == sequence[2]
    rng = np.random.default_rng(5)
    locks = [0.0, math.pi] if proper else [math.pi / 2, -math.pi / 2]
    angles = np.array([[a, b, c] for b in locks for a, c in rng.uniform(-math.pi, math.pi, size=(50, 2))])
    M_ref = Rotation.from_euler(seq, angles).as_matrix()
    e = rigid.so3.to_euler(rigid.so3.from_euler(angles, sequence, intrinsic=intrinsic), sequence, intrinsic=intrinsic)
    # the free angle is fixed by rigid's convention: third intrinsic angle / first extrinsic one 0
    free = 2 if intrinsic else 0
    assert np.all(e[:, free] == 0.0)
    assert np.abs(Rotation.from_euler(seq, e).as_matrix() - M_ref).max() < TOL
