"""Every primitive of the catalogue (rigid.mass.primitives(), the list `rigid inertia` offers)
against SymPy integrating its uniform density exactly.

Each body is described here independently of rigid: a parametrisation of its volume (or
surface, or curve) by coordinates with constant or linear limits, and the Jacobian of that
parametrisation. SymPy integrates the ten moments ∫ρ·{1, x, y, z, x², y², z², xy, xz, yz}
exactly (rational sizes, 1/4 to 5/4 m, all exact in binary, and density 3/2), from which
mass = ∫ρ, COM = ∫ρ r / m and the inertia about the COM,
    I_C = ∫ρ (|r|² 1 − r rᵀ) − m (|c|² 1 − c cᵀ),
follow exactly; only then are they rounded to double (30 digits first).

Tolerance: 1e-13 relative (mass; inertia entries against the largest moment; COM against the
body's largest size). rigid evaluates closed forms with π and a handful of products (≈ 10–30
roundings; the largest difference seen is 6.5e-16 relative, the frustum's inertia); the
margin covers the cancelling sums (capped shell, capsule, frustum) without hiding a wrong
coefficient, which changes a moment by ≥ 1e-3 relative.

Every catalogue name must have a model here, so a new primitive fails this test until one is
written (test_every_primitive_has_a_model).
"""
import functools

import numpy as np
import pytest
import sympy as sp  # python3-sympy: missing fails, never skips

import rigid

REL = 1e-13
RHO = sp.Rational(3, 2)

s, t, u, w = sp.symbols("s t u w", real=True)
pi = sp.pi
half, quarter = sp.Rational(1, 2), sp.Rational(1, 4)
three_q, five_q = sp.Rational(3, 4), sp.Rational(5, 4)


def ball(r0, r1, centre_z=0, theta=(0, pi)):
    """Spherical coordinates (s = radius, t = polar angle, u = azimuth), radius r0..r1."""
    return ((s * sp.sin(t) * sp.cos(u), s * sp.sin(t) * sp.sin(u), centre_z + s * sp.cos(t)),
            s**2 * sp.sin(t), [(s, r0, r1), (t, *theta), (u, 0, 2 * pi)])


def cylinder(r0, r1, z0, z1):
    """Cylindrical coordinates (s = radius, u = azimuth, w = z)."""
    return ((s * sp.cos(u), s * sp.sin(u), w), s, [(s, r0, r1), (u, 0, 2 * pi), (w, z0, z1)])


def cone(r_bottom, r_top, h):
    """Solid of revolution with radius linear in z: s = radius fraction (0..1) times r(z)."""
    rz = r_bottom + (r_top - r_bottom) * w / h
    return ((s * rz * sp.cos(u), s * rz * sp.sin(u), w), s * rz**2, [(s, 0, 1), (u, 0, 2 * pi), (w, 0, h)])


# name → (catalogue keywords, the pieces of the body: (coordinates, Jacobian, limits))
MODELS = {
    "solid_sphere": ({"radius": half}, [ball(0, half)]),
    "thick_spherical_shell": ({"inner_radius": quarter, "outer_radius": half}, [ball(quarter, half)]),
    "thin_spherical_shell": ({"radius": three_q}, [
        ((three_q * sp.sin(t) * sp.cos(u), three_q * sp.sin(t) * sp.sin(u), three_q * sp.cos(t)),
         three_q**2 * sp.sin(t), [(t, 0, pi), (u, 0, 2 * pi)])]),
    "solid_ellipsoid": ({"semi_x": half, "semi_y": three_q, "semi_z": five_q}, [
        ((half * s * sp.sin(t) * sp.cos(u), three_q * s * sp.sin(t) * sp.sin(u), five_q * s * sp.cos(t)),
         half * three_q * five_q * s**2 * sp.sin(t), [(s, 0, 1), (t, 0, pi), (u, 0, 2 * pi)])]),
    "solid_box": ({"lx": half, "ly": three_q, "lz": five_q}, [
        ((s, t, u), 1, [(s, -quarter, quarter), (t, -three_q / 2, three_q / 2), (u, -five_q / 2, five_q / 2)])]),
    "solid_cylinder": ({"radius": half, "height": five_q}, [cylinder(0, half, -five_q / 2, five_q / 2)]),
    "thick_tube": ({"inner_radius": quarter, "outer_radius": half, "height": five_q},
                   [cylinder(quarter, half, -five_q / 2, five_q / 2)]),
    "thin_cylindrical_shell": ({"radius": half, "height": five_q}, [
        ((half * sp.cos(u), half * sp.sin(u), w), half, [(u, 0, 2 * pi), (w, -five_q / 2, five_q / 2)])]),
    "capped_cylindrical_shell": ({"radius": half, "height": five_q}, [
        ((half * sp.cos(u), half * sp.sin(u), w), half, [(u, 0, 2 * pi), (w, -five_q / 2, five_q / 2)]),
        ((s * sp.cos(u), s * sp.sin(u), five_q / 2), s, [(s, 0, half), (u, 0, 2 * pi)]),
        ((s * sp.cos(u), s * sp.sin(u), -five_q / 2), s, [(s, 0, half), (u, 0, 2 * pi)])]),
    "solid_cone": ({"radius": half, "height": five_q}, [cone(half, 0, five_q)]),
    "solid_frustum": ({"bottom_radius": half, "top_radius": quarter, "height": three_q}, [cone(half, quarter, three_q)]),
    "solid_capsule": ({"radius": half, "length": three_q}, [
        cylinder(0, half, -three_q / 2, three_q / 2),
        ball(0, half, centre_z=three_q / 2, theta=(0, pi / 2)),       # the upper hemisphere
        ball(0, half, centre_z=-three_q / 2, theta=(pi / 2, pi))]),   # the lower one
    "solid_torus": ({"major_radius": three_q, "minor_radius": quarter}, [
        # s = distance from the centre circle, t = angle around the tube, u = azimuth
        (((three_q + s * sp.cos(t)) * sp.cos(u), (three_q + s * sp.cos(t)) * sp.sin(u), s * sp.sin(t)),
         s * (three_q + s * sp.cos(t)), [(s, 0, quarter), (t, 0, 2 * pi), (u, 0, 2 * pi)])]),
    "thin_rod": ({"length": five_q}, [((0, 0, w), 1, [(w, -five_q / 2, five_q / 2)])]),
    "thin_rectangular_plate": ({"lx": half, "ly": five_q}, [
        ((s, t, 0), 1, [(s, -quarter, quarter), (t, -five_q / 2, five_q / 2)])]),
    "thin_disk": ({"radius": three_q}, [((s * sp.cos(u), s * sp.sin(u), 0), s, [(s, 0, three_q), (u, 0, 2 * pi)])]),
    "thin_ring": ({"radius": three_q}, [((three_q * sp.cos(u), three_q * sp.sin(u), 0), three_q, [(u, 0, 2 * pi)])]),
}

# The tetrahedron: affine image of the unit simplex, x = v0 + s e1 + t e2 + u e3, Jacobian |det|.
TETRA = [sp.Matrix([0, 0, 0]), sp.Matrix([1, quarter, 0]), sp.Matrix([half, 1, quarter]),
         sp.Matrix([quarter, half, three_q])]
_E = sp.Matrix.hstack(TETRA[1] - TETRA[0], TETRA[2] - TETRA[0], TETRA[3] - TETRA[0])
_X = TETRA[0] + _E * sp.Matrix([s, t, u])
MODELS["solid_tetrahedron"] = (
    {"v0": TETRA[0], "v1": TETRA[1], "v2": TETRA[2], "v3": TETRA[3]},
    [((_X[0], _X[1], _X[2]), abs(_E.det()), [(u, 0, 1 - s - t), (t, 0, 1 - s), (s, 0, 1)])])


@functools.lru_cache(maxsize=None)
def exact(name):
    """(mass, COM, inertia about the COM) of the model, exact SymPy numbers."""
    _, pieces = MODELS[name]
    m = [sp.Integer(0)] * 10
    for (X, Y, Z), jac, limits in pieces:
        X, Y, Z = sp.sympify(X), sp.sympify(Y), sp.sympify(Z)
        for k, f in enumerate([1, X, Y, Z, X * X, Y * Y, Z * Z, X * Y, X * Z, Y * Z]):
            m[k] += sp.integrate(sp.expand(f * jac), *limits)
    mass = RHO * m[0]
    c = sp.Matrix([m[1], m[2], m[3]]) / m[0]
    S = RHO * sp.Matrix([[m[4], m[7], m[8]], [m[7], m[5], m[9]], [m[8], m[9], m[6]]])  # ∫ρ r rᵀ
    I_origin = S.trace() * sp.eye(3) - S
    I_com = I_origin - mass * ((c.T * c)[0] * sp.eye(3) - c * c.T)
    return sp.simplify(mass), c.applyfunc(sp.simplify), I_com.applyfunc(sp.simplify)


def to_float(x):
    return float(sp.N(x, 30))


def test_every_primitive_has_a_model():
    names = [e["name"] for e in rigid.mass.primitives()]
    assert sorted(names) == sorted(MODELS)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_primitive_against_sympy(name):
    kwargs, _ = MODELS[name]
    args = {k: (np.array([float(x) for x in v]) if isinstance(v, sp.Matrix) else float(v)) for k, v in kwargs.items()}
    mp = rigid.mass.primitive(name, density=float(RHO), **args)
    mass, c, I = exact(name)
    assert mp.mass == pytest.approx(to_float(mass), rel=REL)
    size = max(abs(float(v)) for v in np.ravel(list(args.values())))
    com = np.array([to_float(x) for x in c])
    assert np.abs(mp.com - com).max() <= REL * size
    I_ref = np.array([[to_float(I[i, j]) for j in range(3)] for i in range(3)])
    assert np.abs(mp.inertia_com - I_ref).max() <= REL * np.abs(I_ref).max()
    # the aliases name the same body
    entry = next(e for e in rigid.mass.primitives() if e["name"] == name)
    for alias in entry["aliases"]:
        other = rigid.mass.primitive(alias, density=float(RHO), **args)
        assert other.mass == mp.mass and np.array_equal(other.inertia_com, mp.inertia_com)


def test_a_wrong_coefficient_would_be_seen():
    # The comparison can fail: the cylinder's I_xx = m(3r² + h²)/12 with h²/12 replaced by
    # h²/16 (a classic slip) differs from SymPy's by far more than the tolerance.
    mass, _, I = exact("solid_cylinder")
    r, h = 0.5, 1.25
    m = to_float(mass)
    wrong = m * (3 * r * r / 12 + h * h / 16)
    assert abs(wrong - to_float(I[0, 0])) > 1e3 * REL * to_float(I[0, 0])
