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


def rot2(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s], [s, c]])


def test_so2_and_se2_closed_forms():
    R = rigid.SO2.exp(0.7)
    # cos and sin are correctly rounded: exact agreement with numpy.
    assert np.array_equal(R.matrix(), rot2(0.7))
    assert R.log() == 0.7
    assert np.abs(R * np.array([1.0, 0.0]) - [math.cos(0.7), math.sin(0.7)]).max() < 1e-16
    assert rigid.SO2.from_complex(-1.0, 0.0).log() == math.pi
    assert rigid.SO2.dimension == 1 and rigid.SE2.dimension == 3
    # SE2: a rotation by t about c has rho = t (c_y, -c_x); it fixes c.
    c, t = np.array([0.4, -1.3]), 2.0
    X = rigid.SE2.exp(np.array([t * c[1], -t * c[0], t]))
    assert np.abs(X * c - c).max() < 1e-15
    assert np.abs(X.translation() - (c - rot2(t) @ c)).max() < 1e-15
    assert np.abs(rigid.SE2.exp(X.log()).matrix() - X.matrix()).max() < 1e-15
    J = rigid.SE2.left_jacobian(np.array([0.3, -0.2, 1.1]))
    Ji = rigid.SE2.left_jacobian_inverse(np.array([0.3, -0.2, 1.1]))
    assert np.abs(J @ Ji - np.eye(3)).max() < 1e-15


def expm_series(A, terms=40):
    """Independent matrix exponential: Taylor series with scaling and squaring."""
    k = max(0, int(math.ceil(math.log2(max(np.abs(A).sum(axis=1).max(), 1e-300)))) + 1)
    B = A / 2**k
    E, term = np.eye(A.shape[0]), np.eye(A.shape[0])
    for j in range(1, terms):
        term = term @ B / j
        E = E + term
    for _ in range(k):
        E = E @ E
    return E


def test_son_matches_numpy_and_so3():
    rng = np.random.default_rng(3)
    for n in range(2, 9):
        w = rng.standard_normal(n * (n - 1) // 2)
        W = rigid.SOn.hat(w)
        assert np.array_equal(W, -W.T)
        R = rigid.SOn.exp(w)
        # ~1e-14 from ||W|| ~ n and two independent exponentials.
        assert np.abs(R.matrix() - expm_series(W)).max() < 1e-12
        assert R.n == n and R.dimension == n * (n - 1) // 2
        g = rigid.SOn.sample(n, seed=n, count=1)[0]
        assert np.abs(rigid.SOn.exp(g.log()).matrix() - g.matrix()).max() < 1e-12
        v = rng.standard_normal(n)
        assert np.abs(g * v - g.matrix() @ v).max() < 1e-14
    w3 = np.array([0.3, -0.2, 0.9])
    assert np.array_equal(rigid.SOn.hat(w3), rigid.SO3.hat(w3))
    assert np.abs(rigid.SOn.exp(w3).matrix() - rigid.SO3.exp(w3).matrix()).max() < 1e-15
    assert np.abs(rigid.SOn.from_matrix(rigid.SO3.exp(w3).matrix()).log() - w3).max() < 1e-15


def test_sen_matches_se3():
    xi = np.array([0.5, -1.0, 2.0, 0.3, -0.2, 0.9])
    X = rigid.SEn.exp(xi)
    assert np.abs(X.matrix() - rigid.SE3.exp(xi).matrix()).max() < 1e-15
    assert np.abs(X.log() - xi).max() < 1e-14
    assert np.abs(X.adjoint() - rigid.SE3.exp(xi).adjoint()).max() < 1e-15
    Y = rigid.SEn.sample(5, seed=1, count=1)[0]
    p = np.arange(5.0)
    assert np.abs(Y * p - (Y.matrix() @ np.append(p, 1.0))[:5]).max() < 1e-14


def test_new_group_errors():
    with pytest.raises(rigid.Error, match=r"determinant -1 \(expected \+1\)"):
        rigid.SOn.from_matrix(np.diag([1.0, 1.0, 1.0, -1.0]))
    with pytest.raises(rigid.Error, match="tangent vector has 4 components"):
        rigid.SOn.exp(np.zeros(4))
    with pytest.raises(rigid.Error, match=r"SO\(3\) and SO\(4\) differ"):
        rigid.SOn.identity(3) * rigid.SOn.identity(4)
    with pytest.raises(rigid.Error, match="has norm 0, expected a nonzero number"):
        rigid.SO2.from_complex(0.0, 0.0)
    with pytest.raises(rigid.Error, match=r"last row of the homogeneous matrix is \[1, 0, 1\]"):
        rigid.SE2.from_matrix(np.array([[1.0, 0, 0], [0, 1, 0], [1, 0, 1]]))


def test_mul_composes_elements_and_acts_on_arrays():
    # one __mul__ per group, dispatching on its operand; compared with products of matrices.
    # Tolerance 1e-14: the quaternion (or complex) product and the matrix product round
    # differently, by a few ulps of |x| ≈ 3.7.
    x3 = np.array([1.0, 2.0, 3.0])
    R, S = rigid.SO3.exp([0.3, -0.2, 0.9]), rigid.SO3.exp([-1.0, 0.5, 0.1])
    assert isinstance(R * S, rigid.SO3)
    assert np.abs((R * S).matrix() - R.matrix() @ S.matrix()).max() < 1e-14
    for x in (x3, x3.tolist(), tuple(x3), x3.astype(np.int8), np.repeat(x3, 2)[::2]):
        assert np.abs(R * x - R.matrix() @ x3).max() < 1e-14
    X = rigid.SE3(R, [0.5, -1.0, 2.0])
    assert isinstance(X * X, rigid.SE3)
    assert np.abs((X * X).matrix() - X.matrix() @ X.matrix()).max() < 1e-14
    assert np.abs(X * [1, 2, 3] - (R.matrix() @ x3 + [0.5, -1.0, 2.0])).max() < 1e-14
    P = rigid.SO2.from_angle(0.4)
    assert isinstance(P * P, rigid.SO2)
    assert np.abs(P * [1, 2] - P.matrix() @ [1.0, 2.0]).max() < 1e-14
    Y = rigid.SE2(P, [1.0, -2.0])
    assert np.abs(Y * [1, 2] - (P.matrix() @ [1.0, 2.0] + [1.0, -2.0])).max() < 1e-14
    Q = rigid.SOn.exp([0.1, -0.2, 0.3, 0.4, -0.5, 0.6])
    assert isinstance(Q * Q, rigid.SOn)
    assert np.abs(Q * [1, 2, 3, 4] - Q.matrix() @ [1.0, 2, 3, 4]).max() < 1e-14
    Z = rigid.SEn(Q, [1, 2, 3, 4])
    assert isinstance(Z * Z, rigid.SEn)
    assert np.abs(Z * [1, 0, 0, 0] - (Q.matrix()[:, 0] + [1.0, 2, 3, 4])).max() < 1e-14


# Refusals of non-finite input and of angles beyond kMaxAngle = 1e15 rad (where the fraction
# of a turn is lost in rounding): rigid.Error naming the function and the argument, never a
# NaN result.
def test_so3_from_euler_refuses_an_angle_too_large_to_mean_a_rotation():
    with pytest.raises(rigid.Error, match=r"so3\.from_euler\(\): argument 'angles': Euler angles "
                       r"\[1e\+300, 0, 0\] rad: an angle is too large, expected \|angle\| <= "
                       r"kMaxAngle = 1e\+15 rad"):
        rigid.so3.from_euler([1e300, 0, 0], "ZYX")
    with pytest.raises(rigid.Error, match=r"an angle is too large"):
        rigid.SO3.from_euler([0.0, 2e15, 0.0], "XYZ")
    # the limit itself gives a unit quaternion
    assert np.linalg.norm(rigid.so3.from_euler([1e15, 0, 0], "ZYX")) == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("group, a, b", [
    ("SE3", rigid.SE3.identity(), rigid.SE3(rigid.SO3.exp([0.1, 0, 0]), [1.0, 2.0, 3.0])),
    ("SO3", rigid.SO3.identity(), rigid.SO3.exp([0.1, 0, 0])),
    ("SE2", rigid.SE2.identity(), rigid.SE2.exp([1.0, 2.0, 0.5])),
    ("SO2", rigid.SO2.identity(), rigid.SO2.exp(0.5)),
    ("SOn", rigid.SOn.identity(4), rigid.SOn.exp([0.1] * 6)),
    ("SEn", rigid.SEn.identity(3), rigid.SEn.exp([0.1] * 6)),
])
def test_interpolate_refuses_a_non_finite_or_huge_fraction(group, a, b):
    for s in (math.nan, math.inf):
        with pytest.raises(rigid.Error, match=rf"rigid\.{group}\.interpolate\(\): argument 's' "
                           rf"must be finite; got {s}"):
            a.interpolate(b, s)
    with pytest.raises(rigid.Error, match=rf"rigid\.{group}\.interpolate\(\): argument 's': "
                       r"fraction s = 1e\+300 gives the tangent"):
        a.interpolate(b, 1e300)
    # a string is no number: a TypeError naming the argument (not pybind11's overload list)
    with pytest.raises(TypeError, match=rf"rigid\.{group}\.interpolate\(\): argument 's' must be a number"):
        a.interpolate(b, "half")
    a.interpolate(b, 0.5)  # still works


def test_so3_exp_refuses_a_vector_longer_than_the_angle_limit():
    with pytest.raises(rigid.Error, match=r"rigid\.SO3\.exp\(\): argument 'omega': rotation vector "
                       r"\[2000000000000000, 0, 0\] is too long: angle \|ω\| = 2e\+15 rad"):
        rigid.SO3.exp([2e15, 0, 0])
    with pytest.raises(rigid.Error, match=r"argument 'angle'|angle 1e\+300 rad is too large"):
        rigid.SO3.from_axis_angle([0, 0, 1], 1e300)
