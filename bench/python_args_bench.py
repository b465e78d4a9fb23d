"""Per-call cost of array arguments in the Python module: a numpy array, a list, and a call with
scalars only (no conversion), each the best of 3 repeats of 200 000 calls. Run by `make bench`
(scripts/run-benchmarks.sh) with the module of the bench build:
    PYTHONPATH=build/bench/python /usr/bin/python3 bench/python_args_bench.py
Array arguments go through python/convert.hpp (shape, dtype and finiteness checks with messages
naming the argument); this measures what that costs per call."""
import timeit

import numpy as np

import rigid


def main():
    box = rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7)
    d = np.array([0.1, 0.2, 0.3])
    q, w, inertia = np.array([1.0, 0, 0, 0]), np.array([0.1, 1.0, 0.2]), np.array([1.0, 2.0, 3.0])
    rot, xi = rigid.SO3.exp(w), np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
    cases = [
        ("MassProperties.shifted(ndarray (3,))", lambda: box.shifted(d)),
        ("MassProperties.shifted(list of 3)", lambda: box.shifted([0.1, 0.2, 0.3])),
        ("mass.solid_box_with_mass(4 floats)", lambda: rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7)),
        ("body.step_free_body(3 arrays, splitting2)", lambda: rigid.body.step_free_body("splitting2", inertia, q, w, 0.01)),
        ("SO3.exp(ndarray (3,))", lambda: rigid.SO3.exp(w)),
        ("SO3.exp(list of 3)", lambda: rigid.SO3.exp([0.1, 1.0, 0.2])),
        ("SO3 * SO3", lambda: rot * rot),
        ("SO3 * ndarray (3,)", lambda: rot * d),
        ("SE3.exp(ndarray (6,))", lambda: rigid.SE3.exp(xi)),
    ]
    n = 200_000
    for name, call in cases:
        best = min(timeit.repeat(call, number=n, repeat=3)) / n
        print(f"{name:44s} {best * 1e6:6.2f} µs/call")


if __name__ == "__main__":
    main()
