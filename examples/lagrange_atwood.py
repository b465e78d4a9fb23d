#!/usr/bin/env python3
"""Atwood machine with a heavy pulley, from bodies and two rope constraints.

Closed form (pulley a solid cylinder of mass M): a = (m2 - m1) g / (m1 + m2 + M/2),
T1 = m1 (g + a), T2 = m2 (g - a). The rope tensions are the Lagrange multipliers.
Run after `make demo` (or with rigid installed):
    PYTHONPATH=build/ci/python /usr/bin/python3 examples/lagrange_atwood.py
"""
import numpy as np

import rigid

# With these numbers: a = 0.5 g / 2.9 = 1.69138 m/s^2, y1(1 s) = a/2, and the tensions.
# check: y1(1 s) = 0.845690 m (rel 1e-5; run rel 1e-5)
# check: T1 = 11.5014 N (rel 1e-5; run rel 1e-5)
# check: T2 = 12.1779 N (rel 1e-5; run rel 1e-5)

m1, m2, M, R, g = 1.0, 1.5, 0.8, 0.1, 9.81
point = lambda m: rigid.MassProperties(m, np.zeros(3), np.zeros((3, 3)))
pulley = rigid.MassProperties(M, np.zeros(3), np.diag([0.01, 0.01, 0.5 * M * R * R]))

atwood = rigid.lagrange.System(
    coordinates=[("y1", 0.0, 0.0), ("y2", 0.0, 0.0), ("phi", 0.0, 0.0)],
    parameters={"R": R},
    bodies=[
        {"name": "left", "mass": point(m1), "position": ["-R", "y1", "0"]},
        {"name": "right", "mass": point(m2), "position": ["R", "y2", "0"]},
        {"name": "pulley", "mass": pulley, "rotations": [([0, 0, 1], "phi")]},
    ],
    gravity=[0, -g, 0],
    constraints=[("left_rope", "y1 + R*phi"), ("right_rope", "y2 - R*phi")],
)
for line in atwood.equations()["text"]:
    print(line)
out = atwood.simulate(1.0, output_dt=0.5)
a = (m2 - m1) * g / (m1 + m2 + M / 2)
print(f"y1(1 s) = {out['q'][-1, 0]:.12f} m   closed form {a / 2:.12f} m")
print(f"tensions {out['lambda'][-1]} N   closed form [{m1 * (g + a):.12f} {m2 * (g - a):.12f}] N")
