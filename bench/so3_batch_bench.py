#!/usr/bin/env python3
"""rigid.so3 (batch SO(3), looped in C++) against scipy.spatial.transform.Rotation, in one run.

  RIGID_PYTHON_DIR=build/bench/python /usr/bin/python3 bench/so3_batch_bench.py [N]

Prints, per operation on N = 10⁶ elements (default): the best of 5 runs for rigid with all
cores (rows split over the threads from 32768 on), rigid on one thread (the same call on
chunks of 16384 rows, below the threading threshold), and SciPy (1.10, Cython, one thread),
in ns per element, with the ratios SciPy / rigid. Then the per-call cost of a scalar call.

What each side does:
- exp: rigid.so3.exp(omega) → (N, 4) | Rotation.from_rotvec(omega).as_quat()
- log: rigid.so3.log(q) → (N, 3) | r.as_rotvec() on a Rotation built beforehand; and
  Rotation.from_quat(q).as_rotvec() (from the same array as rigid: SciPy normalises there)
- compose: rigid.so3.compose(q, p) | r1 * r2 (built beforehand); and from the arrays
- act: rigid.so3.act(q, v) | r.apply(v) (built beforehand); and from the arrays
rigid always starts from arrays and normalises every input quaternion (as SO3.from_quaternion).
"""
import os
import sys
import time
import timeit

_dir = os.environ.get("RIGID_PYTHON_DIR")
if _dir:
    sys.path.insert(0, _dir)

import numpy as np  # noqa: E402

import rigid  # noqa: E402

try:
    from scipy.spatial.transform import Rotation  # noqa: E402
except ImportError:  # pragma: no cover
    sys.exit("so3_batch_bench: SciPy is needed (Debian python3-scipy; scripts/install-deps.sh)")

CHUNK = 16384


def best(f, repeat=5):
    t = float("inf")
    for _ in range(repeat):
        s = time.perf_counter()
        f()
        t = min(t, time.perf_counter() - s)
    return t


def one_thread(f, *arrays):
    n = len(arrays[0])
    return lambda: [f(*(a[i:i + CHUNK] for a in arrays)) for i in range(0, n, CHUNK)]


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    rng = np.random.default_rng(2019)
    omega = rng.normal(size=(n, 3))
    v = rng.normal(size=(n, 3))
    q = rigid.so3.exp(omega)
    p = rigid.so3.exp(v)
    q_xyzw, p_xyzw = q[:, [1, 2, 3, 0]].copy(), p[:, [1, 2, 3, 0]].copy()
    r1, r2 = Rotation.from_quat(q_xyzw), Rotation.from_quat(p_xyzw)

    rows = [
        ("exp", lambda: rigid.so3.exp(omega), one_thread(rigid.so3.exp, omega),
         lambda: Rotation.from_rotvec(omega).as_quat(), None),
        ("log", lambda: rigid.so3.log(q), one_thread(rigid.so3.log, q),
         lambda: r1.as_rotvec(), lambda: Rotation.from_quat(q_xyzw).as_rotvec()),
        ("compose", lambda: rigid.so3.compose(q, p), one_thread(rigid.so3.compose, q, p),
         lambda: r1 * r2, lambda: (Rotation.from_quat(q_xyzw) * Rotation.from_quat(p_xyzw)).as_quat()),
        ("act", lambda: rigid.so3.act(q, v), one_thread(rigid.so3.act, q, v),
         lambda: r1.apply(v), lambda: Rotation.from_quat(q_xyzw).apply(v)),
    ]
    print(f"rigid {rigid.__version__}, numpy {np.__version__}, scipy {__import__('scipy').__version__}, "
          f"N = {n}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    print(f"{'operation':<9} {'rigid':>9} {'rigid 1 thr':>12} {'SciPy':>9} {'SciPy arrays':>13} "
          f"{'ratio':>7} {'ratio 1 thr':>12} {'ratio arrays':>13}   (ns per element; ratio = SciPy / rigid)")
    for name, mine, mine1, ref, ref_arrays in rows:
        tm, t1, tr = best(mine), best(mine1), best(ref)
        ta = best(ref_arrays) if ref_arrays else tr
        ns = 1e9 / n
        print(f"{name:<9} {tm * ns:9.1f} {t1 * ns:12.1f} {tr * ns:9.1f} {ta * ns:13.1f} "
              f"{tr / tm:7.1f} {tr / t1:12.1f} {ta / tm:13.1f}")

    # per-call cost of scalar calls (timeit, best of 5 × 20000 calls)
    w = np.array([0.1, -0.2, 0.3])
    R = rigid.SO3.exp(w)
    x = np.array([1.0, 2.0, 3.0])
    calls = [
        ("rigid.SO3.identity()", lambda: rigid.SO3.identity()),
        ("rigid.SO3.exp(w)", lambda: rigid.SO3.exp(w)),
        ("R * x (SO3 * vector)", lambda: R * x),
        ("rigid.so3.exp(w) (batch of 1)", lambda: rigid.so3.exp(w)),
        ("Rotation.from_rotvec(w)", lambda: Rotation.from_rotvec(w)),
        ("r.apply(x)", (lambda r=Rotation.from_rotvec(w): r.apply(x))),
    ]
    print("\nscalar call                        ns per call")
    for label, f in calls:
        t = min(timeit.repeat(f, number=20000, repeat=5)) / 20000
        print(f"{label:<34} {t * 1e9:8.0f}")


if __name__ == "__main__":
    main()
