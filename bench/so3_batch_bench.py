#!/usr/bin/env python3
"""rigid.so3 (batch SO(3), looped in C++) against scipy.spatial.transform.Rotation, in one run.

  RIGID_PYTHON_DIR=build/bench/python /usr/bin/python3 bench/so3_batch_bench.py [N]

Prints, per operation on N = 10⁶ elements (default), the median of 5 runs: rigid on one thread
(the same call on chunks of 16384 rows, below the threading threshold) and SciPy (1.10,
Cython, one thread) in CPU time, and rigid on all cores (rows split over the threads from
32768 on) against SciPy in wall time, in ns per element, with the ratios SciPy / rigid. Then
the per-call cost of scalar calls.

What each side does:
- exp: rigid.so3.exp(omega) → (N, 4) | Rotation.from_rotvec(omega).as_quat()
- log: rigid.so3.log(q) → (N, 3) | r.as_rotvec() on a Rotation built beforehand; and
  Rotation.from_quat(q).as_rotvec() (from the same array as rigid: SciPy normalises there)
- exp fast, log fast: the same with fast=True (the vectorised loops, within 4 ε of the default)
- compose: rigid.so3.compose(q, p) | r1 * r2 (built beforehand); and from the arrays
- act: rigid.so3.act(q, v) | r.apply(v) (built beforehand); and from the arrays
rigid always starts from arrays and normalises every input quaternion (as SO3.from_quaternion).
"""
import functools
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
    """(wall, CPU) seconds, the medians of `repeat` runs. CPU time (this process, all its
    threads) is what a single-threaded run costs even when the shared machine is loaded; wall
    time is what a multi-threaded run gains."""
    walls, cpus = [], []
    for _ in range(repeat):
        s, c = time.perf_counter(), time.process_time()
        f()
        walls.append(time.perf_counter() - s)
        cpus.append(time.process_time() - c)
    return float(np.median(walls)), float(np.median(cpus))


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
    exp_fast = functools.partial(rigid.so3.exp, fast=True)
    log_fast = functools.partial(rigid.so3.log, fast=True)

    rows = [
        ("exp", lambda: rigid.so3.exp(omega), one_thread(rigid.so3.exp, omega),
         lambda: Rotation.from_rotvec(omega).as_quat(), None),
        ("log", lambda: rigid.so3.log(q), one_thread(rigid.so3.log, q),
         lambda: r1.as_rotvec(), lambda: Rotation.from_quat(q_xyzw).as_rotvec()),
        ("exp fast", lambda: rigid.so3.exp(omega, fast=True), one_thread(exp_fast, omega),
         lambda: Rotation.from_rotvec(omega).as_quat(), None),
        ("log fast", lambda: rigid.so3.log(q, fast=True), one_thread(log_fast, q),
         lambda: r1.as_rotvec(), lambda: Rotation.from_quat(q_xyzw).as_rotvec()),
        ("compose", lambda: rigid.so3.compose(q, p), one_thread(rigid.so3.compose, q, p),
         lambda: r1 * r2, lambda: (Rotation.from_quat(q_xyzw) * Rotation.from_quat(p_xyzw)).as_quat()),
        ("act", lambda: rigid.so3.act(q, v), one_thread(rigid.so3.act, q, v),
         lambda: r1.apply(v), lambda: Rotation.from_quat(q_xyzw).apply(v)),
    ]
    print(f"rigid {rigid.__version__}, numpy {np.__version__}, scipy {__import__('scipy').__version__}, "
          f"N = {n}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    print("ns per element. CPU: one thread, CPU time (robust to the load of a shared machine); "
          "wall: rigid on all cores vs SciPy (one thread). ratio = SciPy / rigid; 'arrays': SciPy "
          "starting from the same arrays as rigid (Rotation.from_quat included).")
    print(f"{'operation':<9} {'rigid CPU':>10} {'SciPy CPU':>10} {'arrays CPU':>11} {'ratio CPU':>10} "
          f"{'ratio arrays':>13} {'rigid wall':>11} {'SciPy wall':>11} {'ratio wall':>11}")
    for name, mine, mine1, ref, ref_arrays in rows:
        (wm, _), (_, c1), (wr, cr) = best(mine), best(mine1), best(ref)
        ca = best(ref_arrays)[1] if ref_arrays else cr
        ns = 1e9 / n
        print(f"{name:<9} {c1 * ns:10.1f} {cr * ns:10.1f} {ca * ns:11.1f} {cr / c1:10.1f} {ca / c1:13.1f} "
              f"{wm * ns:11.1f} {wr * ns:11.1f} {wr / wm:11.1f}")

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
