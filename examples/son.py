#!/usr/bin/env python3
"""Rotations of R^n, SO(n), and the generalised rigid body of Euler and Arnold.

A rotation of R^n turns each of its n(n-1)/2 coordinate planes, so SO(n) has dimension
n(n-1)/2: 1 in the plane, 3 in space, 6 in R^4. exp maps so(n), the skew matrices, onto SO(n),
and log inverts it near the identity (here for n = 2 ... 6).

A rigid body in R^n with mass matrix J = diag(J_1, ..., J_n) (J = sum of m x x^T over its mass
in principal axes) has body angular momentum M in so(n) and angular velocity
Omega_ij = M_ij / (J_i + J_j). Its free motion is the Euler-Arnold equation dM/dt = [M, Omega]
[Arnold 1966; Ratiu 1980, rigid.body.euler_arnold_rhs]. It keeps the energy
E = 1/2 sum_{i<j} M_ij^2 / (J_i + J_j) and the Casimirs tr(M^2), tr(M^4) (M(t) is M(0) turned
by a rotation, so its spectrum stays). For n = 3, M = hat(L) and I_1 = J_2 + J_3 (cyclic), and
the equation is Euler's for a free body.

Run after `make demo` (or with rigid installed):
    PYTHONPATH=build/ci/python /usr/bin/python3 examples/son.py
"""
import numpy as np

import rigid

# The body in R^4 and its momentum, and what stays constant along its motion (closed forms of
# M(0)); the run integrates 10 s by RK4 at h = 1e-3 s (error O(h^4) ~ 1e-12 per unit time).
# check: dim SO(4) = 6 (abs 0; run abs 0)
# check: E = 0.138297619048 J (rel 1e-11; run rel 1e-9)
# check: tr(M^2) = -2.78 (rel 1e-12; run rel 1e-9)
# check: tr(M^4) = 3.8066 (rel 1e-12; run rel 1e-9)
# check: exp-log round trip = 0 (abs 1e-13; run abs 1e-13)
# check: Euler-Arnold minus Euler in R^3 = 0 (abs 1e-15; run abs 1e-14)

J = np.array([1.0, 2.0, 3.0, 4.0])  # kg m^2
upper = {(0, 1): 0.3, (0, 2): -0.5, (0, 3): 0.2, (1, 2): 0.7, (1, 3): -0.4, (2, 3): 0.6}  # kg m^2/s
M0 = np.zeros((4, 4))
for (i, j), v in upper.items():
    M0[i, j], M0[j, i] = v, -v


def energy(M):
    return 0.5 * sum(M[i, j] ** 2 / (J[i] + J[j]) for i in range(4) for j in range(i + 1, 4))


for n in range(2, 7):
    print(f"SO({n}): dimension {rigid.SOn.dimension_of(n)} = n(n-1)/2 = {n * (n - 1) // 2}")
print(f"dim SO(4) = {rigid.SOn.dimension_of(4)}")

# exp and log: random small so(n) coordinates (angles below pi) come back through exp then log
rng = np.random.default_rng(4)
worst = 0.0
for n in range(2, 7):
    for _ in range(20):
        xi = rng.uniform(-0.5, 0.5, n * (n - 1) // 2)
        R = rigid.SOn.exp(xi)
        assert np.allclose(R.matrix() @ R.matrix().T, np.eye(n), atol=1e-14)
        worst = max(worst, float(np.max(np.abs(R.log() - xi))))
print(f"exp-log round trip = {worst:.3e}")

# the motion of the body in R^4
M = M0.copy()
h, steps = 1e-3, 10_000
for _ in range(steps):
    M = rigid.body.euler_arnold_rk4_step(J, M, h)
print(f"E = {energy(M0):.12f} J at t = 0, E = {energy(M):.12f} J at t = 10 s")
print(f"tr(M^2) = {np.trace(M0 @ M0):.12f} at t = 0, tr(M^2) = {np.trace(M @ M):.12f} at t = 10 s")
M4_0, M4 = np.linalg.matrix_power(M0, 4), np.linalg.matrix_power(M, 4)
print(f"tr(M^4) = {np.trace(M4_0):.12f} at t = 0, tr(M^4) = {np.trace(M4):.12f} at t = 10 s")

# n = 3: the Euler-Arnold right-hand side is Euler's, with M = hat(L), L = (M_32, M_13, M_21),
# and I_1 = J_2 + J_3, I_2 = J_3 + J_1, I_3 = J_1 + J_2
J3 = np.array([1.0, 2.0, 3.0])
L = np.array([0.4, -0.9, 0.25])
M3 = np.array([[0, -L[2], L[1]], [L[2], 0, -L[0]], [-L[1], L[0], 0]])
I3 = np.array([J3[1] + J3[2], J3[2] + J3[0], J3[0] + J3[1]])
dM = rigid.body.euler_arnold_rhs(J3, M3)
dL = np.array([dM[2, 1], dM[0, 2], dM[1, 0]])
dL_euler = I3 * rigid.body.euler_rhs(I3, L / I3)
print(f"Euler-Arnold minus Euler in R^3 = {float(np.max(np.abs(dL - dL_euler))):.3e}")
