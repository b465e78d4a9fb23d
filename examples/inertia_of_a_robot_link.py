"""Mass properties of a robot link built from primitives, written as a URDF inertial.

The link: an aluminium tube (the arm) with a steel box (the motor) at one end and a
bolt hole drilled through the box. Run after `make demo` (or with rigid installed):
    PYTHONPATH=build/ci/python /usr/bin/python3 examples/inertia_of_a_robot_link.py
"""
import numpy as np

import rigid

ALUMINIUM = 2700.0  # kg/m³
STEEL = 7850.0
# Mass: tube rho_Al pi (r2^2 - r1^2) L, plus box rho_St a b c, minus hole rho_St pi r^2 c; the
# COM is the mass-weighted mean of x = 0.2 m (tube) and x = 0.43 m (drilled box).
# check: mass = 2.14558 kg (rel 1e-5; run rel 1e-5)
# check: com x = 0.348165 m (rel 1e-5; run rel 1e-5)

# the arm: tube along x (the primitive's axis is z, so rotate z onto x), centred at x = 0.2
R_zx = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])
arm = rigid.mass.thick_tube_with_density(ALUMINIUM, 0.02, 0.025, 0.4).transformed(
    R_zx, np.array([0.2, 0.0, 0.0]))
# the motor: a steel box at the far end, with a 10 mm bolt hole along z through it
motor = rigid.mass.solid_box_with_density(STEEL, 0.06, 0.06, 0.05).shifted(np.array([0.43, 0, 0]))
hole = rigid.mass.solid_cylinder_with_density(STEEL, 0.005, 0.05).shifted(np.array([0.43, 0, 0]))
link = rigid.combine([arm, rigid.subtract(motor, hole)])

print(link)
moments, R_BP = link.principal_axes()
print("principal moments (kg·m²):", moments)
print(rigid.mass.write_inertial_document(link, "urdf", name="upper_arm"))
