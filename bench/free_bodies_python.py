#!/usr/bin/env python3
"""rigid.body.step_free_bodies from Python: the cost per body-step of a call that takes k steps.

  PYTHONPATH=build/bench/python /usr/bin/python3 bench/free_bodies_python.py [N]

N free bodies (default 10⁵; principal moments uniform in [1, 2] kg·m², sorted; random unit
quaternions and body rates), splitting2 and splitting4 at h = 1e-3 s, one thread. For
steps = 1, 10 and 100 per call, the best of 3 calls in CPU time (time.process_time), in ns per
body-step, and its ratio to steps = 100 (where the arguments' reading and checking, once per
call, is spread over 100 steps: the C++ kernel's own cost plus 1 %)."""
import sys
import time

import numpy as np

import rigid


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
    rng = np.random.default_rng(1)
    moments = np.sort(rng.uniform(1.0, 2.0, (n, 3)), axis=1)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    w = rng.normal(size=(n, 3))
    print(f"step_free_bodies, {n} bodies, h = 1e-3 s, CPU ns per body-step (best of 3)")
    for method in ("splitting2", "splitting4"):
        cost = {}
        for steps in (1, 10, 100):
            best = float("inf")
            for _ in range(3):
                t = time.process_time()
                rigid.body.step_free_bodies(method, moments, q, w, 1e-3, steps=steps)
                best = min(best, time.process_time() - t)
            cost[steps] = best / (n * steps) * 1e9
        print(f"  {method}: " + ", ".join(
            f"steps={k} {c:.1f} ns ({c / cost[100]:.2f}x steps=100)" for k, c in cost.items()))


if __name__ == "__main__":
    main()
