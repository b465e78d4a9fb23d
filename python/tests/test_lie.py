"""rigid.SO3 / rigid.SE3 / O(n) helpers against numpy closed forms."""
import math

import numpy as np
import pytest

import rigid


def rot_z(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_exp_matches_rodrigues_and_numpy_round_trip():
    w = np.array([0.3, -0.2, 0.9])
    t = np.linalg.norm(w)
    K = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]) / t
    expected = np.eye(3) + math.sin(t) * K + (1 - math.cos(t)) * K @ K  # Rodrigues
    R = rigid.SO3.exp(w)
    # ~50 ulps: a handful of products on both sides.
    assert np.abs(R.matrix() - expected).max() < 1e-14
    assert np.abs(R.log() - w).max() < 1e-14
    assert np.abs(rigid.SO3.hat(w) @ np.array([1.0, 2.0, 3.0]) - np.cross(w, [1.0, 2.0, 3.0])).max() < 1e-15


def test_compose_act_quaternion():
    A = rigid.SO3.from_axis_angle(np.array([0.0, 0.0, 1.0]), math.pi / 2)
    assert np.abs(A * np.array([1.0, 0.0, 0.0]) - [0, 1, 0]).max() < 1e-15
    B = rigid.SO3.from_quaternion(math.cos(0.2), 0.0, 0.0, math.sin(0.2))
    assert np.abs((A * B).matrix() - rot_z(math.pi / 2 + 0.4)).max() < 1e-15
    assert np.abs(B.quaternion() - [math.cos(0.2), 0, 0, math.sin(0.2)]).max() < 1e-16


def test_euler_and_samples():
    R = rigid.SO3.from_euler(np.radians([30.0, 20.0, 10.0]), "ZYX")
    assert np.abs(np.degrees(R.to_euler("ZYX")) - [30, 20, 10]).max() < 1e-12
    rs = rigid.SO3.sample(seed=5, n=2000)
    # Haar measure: E[cos θ] = −1/2; σ(cos θ) < 0.7 so 5σ/√n < 0.08.
    assert abs(np.mean([math.cos(r.angle()) for r in rs]) + 0.5) < 0.08


def test_se3_act_and_matrix():
    X = rigid.SE3(rigid.SO3.exp(np.array([0.0, 0.0, math.pi / 2])), np.array([1.0, 2.0, 3.0]))
    assert np.abs(X * np.array([1.0, 0.0, 0.0]) - [1, 3, 3]).max() < 1e-15
    T = X.matrix()
    assert np.abs(np.linalg.inv(T) - X.inverse().matrix()).max() < 1e-15
    assert np.abs(rigid.SE3.exp(X.log()).matrix() - T).max() < 1e-14


def test_orthogonal_and_nearest_rotation():
    r = rigid.check_orthogonal(np.diag([1.0, 1.0, 1.0, -1.0]))
    assert r.orthogonal and not r.rotation and r.determinant == -1.0
    M = rot_z(0.4) + 1e-3 * np.arange(9.0).reshape(3, 3)
    P = rigid.nearest_rotation(M)
    U, _, Vt = np.linalg.svd(M)  # independent: numpy's SVD polar factor
    assert np.abs(P - U @ Vt).max() < 1e-14


def test_errors():
    # Defect |0.5² − 1| = 0.75.
    with pytest.raises(rigid.Error, match=r"orthonormality defect max\|RᵀR − I\| = 0.75"):
        rigid.SO3.from_matrix(np.diag([1.0, 1.0, 0.5]))
    with pytest.raises(rigid.Error, match="expected a nonzero axis"):
        rigid.SO3.from_axis_angle(np.zeros(3), 1.0)
    with pytest.raises(rigid.Error, match="unknown Euler sequence 'ABC'"):
        rigid.SO3.from_euler(np.zeros(3), "ABC")
