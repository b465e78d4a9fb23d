"""rigid.so3 (batch SO(3)) against the scalar rigid.SO3 methods, element by element.

Where no quaternion is read (exp, from_matrix, from_euler), each batch element is computed by
the same compiled SO3d function as the scalar method, so the comparison is bitwise
(np.array_equal, no tolerance). Where a quaternion is read (log, inverse, to_matrix, compose,
act, to_euler), the batch normalises it by one Newton step (SO3d::from_integrated_quaternion)
where SO3.from_quaternion divides by its norm: each component differs by at most an ulp, which
the operation amplifies by a small factor (≤ 6 seen), so the comparison is at ULPS = 16 ε
times the scale of the result (1 for unit quaternions and matrices, π for rotation vectors,
|v| for rotated vectors); Euler angles near gimbal lock are ill-conditioned (an ε in the
matrix moves the angles by ε / distance to the lock), so their difference times
min(1, distance to the lock) is compared. Independent checks of the numbers themselves are in
test_so3_scipy.py. The vectorised exp and log (fast=True) are compared with the default to
their stated ulp bounds, on random rows and the edges, and refuse alike (at the end).
"""
import math

import numpy as np
import pytest

import rigid

N = 2000  # the scalar side loops in Python; 2000 rows cover all branches below in ~1 s
ULPS = 16 * np.finfo(float).eps


@pytest.fixture(scope="module")
def data():
    rng = np.random.default_rng(19)
    q = rng.normal(size=(N, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    q[:, 0] = np.where(np.arange(N) % 2 == 0, q[:, 0], -q[:, 0])  # both signs of w
    omega = rng.normal(size=(N, 3)) * rng.uniform(0, 2 * math.pi, size=(N, 1))
    # the series branches of exp and log (|ω| < 1e-5) and the neighbourhood of π
    omega[:20] *= 1e-7
    omega[20:40] = omega[20:40] / np.linalg.norm(omega[20:40], axis=1)[:, None] * (math.pi - 1e-9)
    omega[40] = 0.0
    v = rng.normal(size=(N, 3))
    angles = rng.uniform(-math.pi, math.pi, size=(N, 3))
    return {"q": q, "omega": omega, "v": v, "angles": angles}


def scalar(q):
    return rigid.SO3.from_quaternion(*q)


def test_exp_quaternion_and_matrix_bitwise(data):
    w = data["omega"]
    got_q = rigid.so3.exp(w)
    got_m = rigid.so3.exp(w, output="matrix")
    assert got_q.shape == (N, 4) and got_m.shape == (N, 3, 3)
    want_q = np.array([rigid.SO3.exp(x).quaternion() for x in w])
    want_m = np.array([rigid.SO3.exp(x).matrix() for x in w])
    assert np.array_equal(got_q, want_q)
    assert np.array_equal(got_m, want_m)
    xyzw = rigid.so3.exp(w, order="xyzw")
    assert np.array_equal(xyzw, want_q[:, [1, 2, 3, 0]])


def test_log_inverse_matrix_to_an_ulp(data):
    q = data["q"]
    assert np.abs(rigid.so3.log(q) - np.array([scalar(x).log() for x in q])).max() <= ULPS * math.pi
    assert np.abs(rigid.so3.inverse(q) - np.array([scalar(x).inverse().quaternion() for x in q])).max() <= ULPS
    assert np.abs(rigid.so3.to_matrix(q) - np.array([scalar(x).matrix() for x in q])).max() <= ULPS
    # xyzw in and out is the same computation on reordered columns: bitwise
    assert np.array_equal(rigid.so3.log(q[:, [1, 2, 3, 0]], order="xyzw"), rigid.so3.log(q))
    assert np.array_equal(rigid.so3.inverse(q[:, [1, 2, 3, 0]], order="xyzw"), rigid.so3.inverse(q)[:, [1, 2, 3, 0]])


def test_compose_and_act_to_an_ulp_with_broadcast(data):
    q, v = data["q"], data["v"]
    p = np.roll(q, 1, axis=0)
    scale = np.linalg.norm(v, axis=1).max()
    want = np.array([(scalar(a) * scalar(b)).quaternion() for a, b in zip(q, p)])
    assert np.abs(rigid.so3.compose(q, p) - want).max() <= ULPS
    want_act = np.array([scalar(a) * x for a, x in zip(q, v)])
    assert np.abs(rigid.so3.act(q, v) - want_act).max() <= ULPS * scale
    # one rotation against N, and N rotations against one vector
    single = np.array([(scalar(q[0]) * scalar(b)).quaternion() for b in p])
    assert np.abs(rigid.so3.compose(q[0], p) - single).max() <= ULPS
    assert np.abs(rigid.so3.act(q[0], v) - np.array([scalar(q[0]) * x for x in v])).max() <= ULPS * scale
    assert np.abs(rigid.so3.act(q, v[0]) - np.array([scalar(a) * v[0] for a in q])).max() <= ULPS * scale
    # a single element broadcast is the same computation as the row repeated: bitwise
    assert np.array_equal(rigid.so3.compose(q[0], p), rigid.so3.compose(np.repeat(q[:1], N, axis=0), p))
    # single with single gives a single element
    assert rigid.so3.compose(q[0], p[0]).shape == (4,)
    assert rigid.so3.act(q[0], v[0]).shape == (3,)


def test_exact_unit_quaternions_are_taken_as_they_are():
    # |q|² = 1 exactly: the Newton factor (3 − |q|²)/2 is exactly 1, as is SO3.from_quaternion's
    # norm, so both read the same quaternion and everything after is bitwise the same
    q = np.array([[1.0, 0.0, 0.0, 0.0], [0.5, 0.5, 0.5, 0.5], [0.5, -0.5, 0.5, -0.5], [0.0, 0.0, 0.0, 1.0],
                  [0.0, 0.6, 0.8, 0.0]])
    assert np.array_equal(rigid.so3.to_matrix(q), np.array([scalar(x).matrix() for x in q]))
    assert np.array_equal(rigid.so3.log(q), np.array([scalar(x).log() for x in q]))


def lock_distance(sequence, middle):
    if sequence[0] == sequence[2]:
        return np.minimum(np.abs(middle), np.abs(math.pi - middle))
    return math.pi / 2 - np.abs(middle)


def test_from_matrix_bitwise(data):
    M = np.array([scalar(x).matrix() for x in data["q"]])
    want = np.array([rigid.SO3.from_matrix(m).quaternion() for m in M])
    assert np.array_equal(rigid.so3.from_matrix(M), want)


@pytest.mark.parametrize("intrinsic", [True, False])
@pytest.mark.parametrize("sequence", rigid.so3.sequences)
def test_euler_every_convention(data, sequence, intrinsic):
    a, q = data["angles"][:300], data["q"][:300]
    want = np.array([rigid.SO3.from_euler(x, sequence, intrinsic).quaternion() for x in a])
    assert np.array_equal(rigid.so3.from_euler(a, sequence, intrinsic=intrinsic), want)
    want_e = np.array([scalar(x).to_euler(sequence, intrinsic) for x in q])
    e = rigid.so3.to_euler(q, sequence, intrinsic=intrinsic)
    d = np.abs((e - want_e + math.pi) % (2 * math.pi) - math.pi)  # ±π are the same angle
    assert (d * np.minimum(1.0, lock_distance(sequence, want_e[:, 1]))[:, None]).max() <= ULPS * math.pi


def test_sequences_are_the_twelve():
    assert sorted(rigid.so3.sequences) == sorted(
        ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"])


def test_large_batches_use_threads_with_the_same_numbers():
    # Above 32768 rows the loop is split over threads; each row is independent of the split,
    # so a large batch equals the concatenation of small (single-threaded) ones.
    rng = np.random.default_rng(7)
    w = rng.normal(size=(100_000, 3))
    big = rigid.so3.exp(w)
    small = np.concatenate([rigid.so3.exp(w[i:i + 1000]) for i in range(0, len(w), 1000)])
    assert np.array_equal(big, small)
    assert np.array_equal(rigid.so3.log(big), np.concatenate([rigid.so3.log(big[i:i + 1000])
                                                             for i in range(0, len(w), 1000)]))


def test_empty_single_list_and_dtype_inputs():
    assert rigid.so3.exp(np.zeros((0, 3))).shape == (0, 4)
    assert rigid.so3.exp(np.zeros(3)).shape == (4,)
    assert np.array_equal(rigid.so3.exp([[0, 0, 1]]), rigid.so3.exp(np.array([[0.0, 0.0, 1.0]])))
    # integers and float32 are converted to float64 (float32 0.5 is exact)
    assert np.array_equal(rigid.so3.exp(np.array([[0, 0, 1]], dtype=np.int32)), rigid.so3.exp([[0.0, 0.0, 1.0]]))
    assert np.array_equal(rigid.so3.exp(np.array([[0, 0, 0.5]], dtype=np.float32)), rigid.so3.exp([[0.0, 0.0, 0.5]]))


def test_non_contiguous_and_read_only_arrays(data):
    w = np.asfortranarray(data["omega"])
    strided = np.zeros((N, 6))
    strided[:, ::2] = data["omega"]
    ro = data["omega"].copy()
    ro.setflags(write=False)
    want = rigid.so3.exp(np.ascontiguousarray(data["omega"]))
    assert np.array_equal(rigid.so3.exp(w), want)
    assert np.array_equal(rigid.so3.exp(strided[:, ::2]), want)
    assert np.array_equal(rigid.so3.exp(ro), want)
    assert np.array_equal(rigid.so3.exp(data["omega"][::-1]), want[::-1])


def test_quaternions_are_normalised_like_from_quaternion():
    # far from unit: normalised by the norm; huge: scaled first, so that |q|² does not overflow
    for q in ([2.0, 0.0, 0.0, 2.0], [1e200, 0.0, 0.0, 1e200], [3e-10, 4e-10, 0.0, 0.0]):
        want = rigid.SO3.from_quaternion(*(np.array(q) / max(abs(x) for x in q))).matrix()
        assert np.abs(rigid.so3.to_matrix(np.array([q]))[0] - want).max() <= ULPS


@pytest.mark.parametrize("call, message", [
    (lambda: rigid.so3.exp(np.zeros((5, 4))),
     r"so3.exp\(\): argument 'omega' must have shape \(N, 3\) or \(3,\); got \(5, 4\)"),
    (lambda: rigid.so3.exp(np.zeros((2, 3, 1))),
     r"argument 'omega' must have shape \(N, 3\) or \(3,\); got \(2, 3, 1\)"),
    (lambda: rigid.so3.from_matrix(np.zeros((4, 3))),
     r"so3.from_matrix\(\): argument 'R' must have shape \(N, 3, 3\) or \(3, 3\); got \(4, 3\)"),
    (lambda: rigid.so3.log(np.zeros((3, 4), dtype=complex)),
     r"so3.log\(\): argument 'q' must hold real numbers .*of shape \(N, 4\) or \(4,\); got dtype complex128"),
    (lambda: rigid.so3.log(np.array([["a", "b", "c", "d"]])), r"argument 'q' must hold real numbers .*got dtype <U1"),
    (lambda: rigid.so3.log(np.ones((2, 4), dtype=bool)), r"argument 'q' must hold real numbers .*got dtype bool"),
    (lambda: rigid.so3.log([[1, 0, 0], [1, 0, 0, 0]]), r"argument 'q' must be an array of numbers of shape \(N, 4\) or \(4,\); got a list that is not rectangular"),
    (lambda: rigid.so3.exp([[0, 0, 1], [0, float("nan"), 0]]),
     r"so3.exp\(\): argument 'omega' row 1: rotation vector \[0, nan, 0\] has a non-finite component"),
    (lambda: rigid.so3.exp([0, 0, float("inf")]), r"so3.exp\(\): argument 'omega': rotation vector \[0, 0, inf\]"),
    (lambda: rigid.so3.exp([[1e200, 0, 0]]), r"argument 'omega' row 0: rotation vector \[1e\+200, 0, 0\] is too long"),
    (lambda: rigid.so3.log([[1, 0, 0, 0], [1, 0, 0, 0], [0, 0, 0, 0]]),
     r"so3.log\(\): argument 'q' row 2: quaternion \(w, x, y, z\) = \(0, 0, 0, 0\) has norm 0, expected a nonzero"),
    (lambda: rigid.so3.to_euler([[1, 0, float("nan"), 0]]),
     r"argument 'q' row 0: quaternion \(w, x, y, z\) = \(1, 0, nan, 0\) has a non-finite component"),
    (lambda: rigid.so3.compose([[1, 0, 0, 0]] * 3, [[1, 0, 0, 0]] * 2),
     r"so3.compose\(\): arguments 'a' and 'b' must have the same number of rows N .*got 3 and 2"),
    (lambda: rigid.so3.compose([[1, 0, 0, 0]] * 3, [[1, 0, 0, 0], [1, 0, 0, 0], [0, 0, 0, 0]]),
     r"so3.compose\(\): argument 'b' row 2: quaternion .* has norm 0"),
    (lambda: rigid.so3.compose([0, 0, 0, 0], [[1, 0, 0, 0]] * 2), r"so3.compose\(\): argument 'a': quaternion .* has norm 0"),
    (lambda: rigid.so3.act([[1, 0, 0, 0]] * 2, [[1, 2, 3], [1, float("nan"), 3]]),
     r"so3.act\(\): argument 'v' row 1: vector \[1, nan, 3\] has a non-finite component"),
    (lambda: rigid.so3.from_matrix([np.eye(3), np.diag([1.0, 1.0, -1.0])]),
     r"so3.from_matrix\(\): argument 'R' row 1: matrix .* is not a rotation: .*determinant -1 \(expected \+1\)"),
    (lambda: rigid.so3.from_matrix(np.eye(3), tol=-1.0), r"tol is -1, expected a tolerance >= 0"),
    (lambda: rigid.so3.from_euler([[0, 0, 0], [1, 2, float("nan")]], "ZYX"),
     r"so3.from_euler\(\): argument 'angles' row 1: Euler angles \[1, 2, nan\] have a non-finite component"),
    (lambda: rigid.so3.from_euler([[0, 0, 0]], "XXY"),
     r"unknown Euler sequence 'XXY', expected one of XYZ, XZY, YXZ, YZX, ZXY, ZYX, XYX, XZX, YXY, YZY, ZXZ, ZYZ"),
    (lambda: rigid.so3.log([[1, 0, 0, 0]], order="wzyx"), r"so3.log\(\): order is 'wzyx', expected wxyz or xyzw"),
    (lambda: rigid.so3.exp([[0, 0, 1]], output="euler"), r"output is 'euler', expected 'quaternion' or 'matrix'"),
])
def test_bad_input_names_the_argument(call, message):
    with pytest.raises(rigid.Error, match=message):
        call()


def test_refusal_in_a_threaded_batch_names_the_first_bad_row():
    w = np.zeros((200_000, 3))
    w[150_000, 1] = np.nan  # in the second thread's chunk
    w[199_999, 0] = np.inf
    with pytest.raises(rigid.Error, match=r"argument 'omega' row 150000: rotation vector \[0, nan, 0\]"):
        rigid.so3.exp(w)


def test_large_batches_release_the_gil():
    # A thread reads a counter, runs a large batch, reads it again; the main thread counts
    # meanwhile. With the switch interval at 1 s the interpreter does not hand the GIL over by
    # itself during the call (~0.1 s), so the main thread can only have counted if the batch
    # released the GIL.
    import sys
    import threading

    w = np.random.default_rng(1).normal(size=(2_000_000, 3))
    counter = [0]
    seen = {}

    def worker():
        seen["before"] = counter[0]
        rigid.so3.exp(w)
        seen["after"] = counter[0]

    old = sys.getswitchinterval()
    sys.setswitchinterval(1.0)
    try:
        t = threading.Thread(target=worker)
        t.start()
        while t.is_alive():
            counter[0] += 1
        t.join()
    finally:
        sys.setswitchinterval(old)
    assert seen["after"] - seen["before"] > 100


def test_ctrl_c_interrupts_a_large_batch():
    # SIGINT 20 ms into a batch of ~0.2–1 s (4·10⁶ Euler conversions on 2 loaded cores): the
    # loop asks Python for signals every 50 ms and raises KeyboardInterrupt.
    import os
    import signal
    import threading
    import time

    angles = np.random.default_rng(2).uniform(-1, 1, size=(4_000_000, 3))
    timer = threading.Timer(0.02, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    try:
        with pytest.raises(KeyboardInterrupt, match=r"so3.from_euler\(\): interrupted"):
            rigid.so3.from_euler(angles, "ZYX")
    finally:
        timer.cancel()
    # stopped well before the end: the whole batch takes ≥ 0.2 s even on an idle machine
    assert time.perf_counter() - start < 0.2


# --- the vectorised path (fast=True) against the default ---------------------------------------
# The default exp and log compute each row with SO3d's operations (bitwise SO3.exp above; log
# as the batch reader then SO3.log); fast=True replaces atan2, sin and cos by polynomials in a
# vectorised loop. Its stated bounds (the docstrings, python/so3_kernels.hpp): each component of
# log within FAST_LOG_ULPS · ε · |ω| of the default's (the error of an angle is relative to the
# angle: Cephes' atan is within 1 ulp, plus a few roundings of the reduction, of |v| and of the
# final scaling; 2.5 measured), each quaternion component of exp within FAST_EXP_ULPS · ε
# (|q| = 1; Cephes' sin/cos within 1 ulp after an exact Cody–Waite reduction; 1.0 measured).
EPS = np.finfo(float).eps
FAST_LOG_ULPS = 4.0
FAST_EXP_ULPS = 4.0


def norms(v):
    """|v| of each row without underflow (np.linalg.norm squares 1e-300 to 0)."""
    scale = np.abs(v).max(axis=1)
    return scale * np.linalg.norm(v / np.where(scale > 0, scale, 1.0)[:, None], axis=1)


def log_edges():
    """Quaternions (w, x, y, z) at the edges of log: angles near 0 (both branches of the series
    threshold |v| = 1e-5), near π (w → 0), exactly π (w = ±0), the identity, unnormalised."""
    rng = np.random.default_rng(5)
    axes = rng.normal(size=(64, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    rows = []
    for half in [0.0, 1e-300, 1e-160, 1e-12, 1e-8, 5e-6, 1e-5 * (1 - 1e-12), 1e-5, 1e-5 * (1 + 1e-12), 1e-3,
                 0.3, 0.66, math.pi / 4, 1.0, math.pi / 2 - 1e-9, math.pi / 2 - 1e-17, math.pi / 2]:
        for a in axes[:8]:
            rows.append(np.concatenate([[math.cos(half)], math.sin(half) * a]))
    for a in axes:
        rows.append(np.concatenate([[0.0], a]))    # exactly π
        rows.append(np.concatenate([[-0.0], a]))   # exactly π, w = −0
        rows.append(np.concatenate([[-1e-17], a]))  # π from the other side: the w ≥ 0 representative
    q = np.array(rows)
    q = np.concatenate([q, -q, q * 1e-11, q * 3.0, q * 1e100])  # both signs, unnormalised (|q|² ≥ 2e-24)
    return q[np.linalg.norm(q, axis=1) > 0]


def test_fast_log_within_the_stated_ulps_of_the_default():
    rng = np.random.default_rng(31)
    q = rng.normal(size=(200_000, 4))
    q[:100_000] /= np.linalg.norm(q[:100_000], axis=1)[:, None]
    q = np.concatenate([q, log_edges()])
    want = rigid.so3.log(q)
    got = rigid.so3.log(q, fast=True)
    angle = norms(want)
    err = np.abs(got - want).max(axis=1)
    assert np.all(err <= FAST_LOG_ULPS * EPS * angle), (err / (EPS * np.maximum(angle, 1e-300))).max()
    assert np.array_equal(got[angle == 0], want[angle == 0])  # the identity: exactly 0
    # the same representative (w ≥ 0, w = −0 as +0): near π the two ±ω never mix
    assert np.all(np.einsum("ij,ij->i", got, want) >= 0)
    # xyzw is the same computation on reordered columns
    assert np.array_equal(rigid.so3.log(q[:, [1, 2, 3, 0]], order="xyzw", fast=True), got)
    # and within the default's 16-ulp tolerance plus the fast bound of the scalar SO3.log
    small = log_edges()
    scalar_log = np.array([scalar(x).log() for x in small])
    bound = (ULPS * math.pi + FAST_LOG_ULPS * EPS * norms(scalar_log))[:, None]
    assert np.all(np.abs(rigid.so3.log(small, fast=True) - scalar_log) <= bound)


def test_fast_exp_within_the_stated_ulps_of_the_default():
    rng = np.random.default_rng(32)
    w = rng.normal(size=(200_000, 3)) * rng.uniform(0, 20, size=(200_000, 1))
    axes = w[:64] / np.linalg.norm(w[:64], axis=1)[:, None]
    # θ at 0, around the series threshold 1e-5, multiples of π/2 (where the reduction switches
    # quadrant) and large angles up to and beyond the fast domain (|ω| ≤ 1e6; beyond, the default)
    angles = [0.0, 1e-300, 1e-12, 1e-5 * (1 - 1e-12), 1e-5, 1e-5 * (1 + 1e-12), 1e-3]
    angles += [k * math.pi / 2 + d for k in range(1, 9) for d in (-1e-12, 0.0, 1e-12)]
    angles += [1e3, 12345.678, 2e4, 999_999.0, 1e6, 1.5e6, 1e9, 1e15]
    edges = np.array([t * a for t in angles for a in axes[:8]])
    w = np.concatenate([w, edges, -edges])
    want = rigid.so3.exp(w)
    got = rigid.so3.exp(w, fast=True)
    assert np.abs(got - want).max() <= FAST_EXP_ULPS * EPS
    assert np.array_equal(got[np.linalg.norm(w, axis=1) == 0], want[np.linalg.norm(w, axis=1) == 0])
    assert np.array_equal(rigid.so3.exp(w, fast=True, order="xyzw"), got[:, [1, 2, 3, 0]])
    # matrices from the fast quaternions: an entry is a sum of products 2 q_a q_b whose gradient in q
    # has 1-norm ≤ 4√2, so 4√2 · FAST_EXP_ULPS ε plus a few roundings: 24 ε, as the docstring says
    m = rigid.so3.exp(w[:20_000], fast=True, output="matrix")
    assert np.abs(m - rigid.so3.exp(w[:20_000], output="matrix")).max() <= 24 * EPS


def test_fast_bounds_are_the_documented_ones():
    assert "4 ε |ω|" in rigid.so3.log.__doc__
    assert "4 ε (ε = 2⁻⁵²)" in rigid.so3.exp.__doc__ and "24 ε" in rigid.so3.exp.__doc__


def test_default_log_blocks_are_bitwise_the_per_row_code():
    # A row the block loop does not take (|q|² overflows: scaled first) sends its whole block of
    # 4096 rows through read_rotation and SO3d::log one by one; every other row must come out
    # bitwise the same as from the block loop.
    rng = np.random.default_rng(33)
    q = rng.normal(size=(4096, 4))
    q[::2] /= np.linalg.norm(q[::2], axis=1)[:, None]
    q = np.concatenate([q, log_edges()[:300]])
    mixed = q.copy()
    mixed[7] = [1e200, 1e200, 0.0, 0.0]
    a, b = rigid.so3.log(q), rigid.so3.log(mixed)
    keep = np.arange(len(q)) != 7
    assert np.array_equal(a[keep], b[keep])
    assert np.allclose(b[7], [math.pi / 2, 0, 0], rtol=0, atol=4 * EPS)


BAD_LOG = [
    ([[1, 0, 0, 0], [0, 0, 0, 0]], r"argument 'q' row 1: quaternion \(w, x, y, z\) = \(0, 0, 0, 0\) has norm 0"),
    ([[1, 0, 0, 0], [1, float("nan"), 0, 0]], r"argument 'q' row 1: quaternion .* has a non-finite component"),
    ([1e-13, 0, 0, 0], r"argument 'q': quaternion .* has norm 1e-13"),
    ([[1, 0, 0, 0], [1, 0, float("inf"), 0]], r"argument 'q' row 1: quaternion .* has a non-finite component"),
]
BAD_EXP = [
    ([[0, 0, 1], [0, float("nan"), 0]], r"argument 'omega' row 1: rotation vector \[0, nan, 0\] has a non-finite"),
    ([[0, 0, 1], [2e15, 0, 0]], r"argument 'omega' row 1: rotation vector \[2000000000000000, 0, 0\] is too long: angle"),
    ([1e200, 0, 0], r"argument 'omega': rotation vector \[1e\+200, 0, 0\] is too long: \|ω\|² overflows"),
]


@pytest.mark.parametrize("function, argument, message",
                         [("log", a, m) for a, m in BAD_LOG] + [("exp", a, m) for a, m in BAD_EXP])
def test_fast_refuses_as_the_default(function, argument, message):
    f = getattr(rigid.so3, function)
    errors = []
    for fast in (False, True):
        with pytest.raises(rigid.Error, match=message) as e:
            f(argument, fast=fast)
        errors.append(str(e.value))
    assert errors[0] == errors[1]


def test_fast_refusal_in_a_threaded_batch_names_the_first_bad_row():
    q = np.tile([1.0, 0.0, 0.0, 0.0], (200_000, 1))
    q[150_001] = 0.0  # in the second thread's chunk
    q[199_999, 0] = np.nan
    for fast in (False, True):
        with pytest.raises(rigid.Error, match=r"so3.log\(\): argument 'q' row 150001: .* has norm 0"):
            rigid.so3.log(q, fast=fast)
