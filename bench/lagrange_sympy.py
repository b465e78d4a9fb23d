#!/usr/bin/env python3
"""SymPy's side of bench/lagrange_bench.cpp: the N-link planar pendulum (point masses 1 kg,
rods 1 m, g = 9.81). (a) time to derive the equations with sympy.physics.mechanics
LagrangesMethod; (b) time per right-hand-side call of the lambdified mass matrix and forcing
with numpy, including the mass-matrix solve. Usage: bench/lagrange_sympy.py [N ...]"""
import sys
import time
import timeit

import numpy as np
import sympy as sp
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols


def derive(n):
    t = sp.Symbol("t")
    q = dynamicsymbols(f"q1:{n + 1}")
    qd = [sp.diff(qi, t) for qi in q]
    l = sp.symbols(f"l1:{n + 1}")
    g = sp.Symbol("g")
    x = y = 0
    T = V = 0
    for k in range(n):
        x += l[k] * sp.sin(q[k])
        y -= l[k] * sp.cos(q[k])
        T += sp.Rational(1, 2) * (sp.diff(x, t) ** 2 + sp.diff(y, t) ** 2)
        V += g * y
    lm = LagrangesMethod(T - V, q)
    lm.form_lagranges_equations()
    return lm, q, qd, l, g


def compile_rhs(lm, q, qd, l, g):
    # replace the time functions by plain symbols for lambdify
    qs = sp.symbols(f"x1:{len(q) + 1}")
    vs = sp.symbols(f"v1:{len(q) + 1}")
    subs = {**dict(zip(qd, vs)), **dict(zip(q, qs))}
    M = lm.mass_matrix.subs(subs)
    F = lm.forcing.subs(subs)
    args = list(qs) + list(vs) + list(l) + [g]
    fM = sp.lambdify(args, M, "numpy")
    fF = sp.lambdify(args, F, "numpy")

    def rhs(qv, vv, lv, gv):
        a = (*qv, *vv, *lv, gv)
        return np.linalg.solve(fM(*a), np.asarray(fF(*a), dtype=float).ravel())

    return rhs


def main():
    sizes = [int(a) for a in sys.argv[1:]] or [2, 4, 8]
    print(f"sympy {sp.__version__}, numpy {np.__version__}")
    print(f"{'N':>3} {'derive (s)':>12} {'rhs (us/call)':>14}")
    for n in sizes:
        start = time.perf_counter()
        lm, q, qd, l, g = derive(n)
        derive_s = time.perf_counter() - start
        rhs = compile_rhs(lm, q, qd, l, g)
        qv = [0.3 * np.sin(1.7 * i + 0.4) for i in range(n)]
        vv = [0.5 * np.cos(2.3 * i) for i in range(n)]
        lv = [1.0] * n
        number = max(20, 20000 // (n * n))
        per_call = min(timeit.repeat(lambda: rhs(qv, vv, lv, 9.81), number=number, repeat=5)) / number
        print(f"{n:>3} {derive_s:>12.3f} {per_call * 1e6:>14.1f}")
        print(f"    qdd = {np.array2string(rhs(qv, vv, lv, 9.81), precision=12)}")


if __name__ == "__main__":
    main()
