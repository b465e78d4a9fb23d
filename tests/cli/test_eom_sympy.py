"""`rigid eom --format json` against SymPy's LagrangesMethod: for every coordinate example, the
Lagrangian is written here by hand from the example's physics (the textbook kinetic and
potential energies, not rigid's output), SymPy derives M and f, and rigid's printed M and f,
read back with sympify, must equal them symbolically: simplify(a - b) == 0."""
import json
from pathlib import Path

import pytest

sympy = pytest.importorskip("sympy")
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
S = sympy.Symbol
t = sympy.Symbol("t")


def double_pendulum(q, qd, p):
    th1, th2 = q
    x1, z1 = p["l1"] * sympy.sin(th1), -p["l1"] * sympy.cos(th1)
    x2, z2 = x1 + p["l2"] * sympy.sin(th2), z1 - p["l2"] * sympy.cos(th2)
    v2 = lambda x, z: sympy.diff(x, t) ** 2 + sympy.diff(z, t) ** 2  # noqa: E731
    T = p["m1"] / 2 * v2(x1, z1) + p["m2"] / 2 * v2(x2, z2)
    V = p["g"] * (p["m1"] * z1 + p["m2"] * z2)
    return T - V, []


def atwood(q, qd, p):
    # two weights hanging at z = -1 - y; a pulley (solid cylinder, I = M R²/2 about its axis)
    y1, y2, phi = q
    T = p["m1"] / 2 * qd[0] ** 2 + p["m2"] / 2 * qd[1] ** 2 + p["M"] * p["R"] ** 2 / 4 * qd[2] ** 2
    V = p["g"] * (p["m1"] * (-1 - y1) + p["m2"] * (-1 - y2))
    return T - V, [y1 - p["R"] * phi, y2 + p["R"] * phi]


def physical_pendulum(q, qd, p):
    # thin rod about one end: COM at L/2, I_COM = m L²/12
    (th,) = q
    m, L, g = p["m"], p["L"], p["g"]
    T = m / 2 * (L / 2) ** 2 * qd[0] ** 2 + m * L**2 / 24 * qd[0] ** 2
    V = -m * g * L / 2 * sympy.cos(th)
    return T - V, []


def graded_rod_pendulum(q, qd, p):
    # a body measured from its density field: its mass, COM c and inertia are the named
    # constants rod_*; the body frame's origin at −(h/2)(sin θ, 0, cos θ), turned by θ about y
    (th,) = q
    m, h, g = p["rod_mass"], p["h"], p["g"]
    # (a COM component within the cubature's error of zero is 0 and named by no constant)
    c = sympy.Matrix([p.get("rod_com_x", 0), p.get("rod_com_y", 0), p.get("rod_com_z", 0)])
    R = sympy.Matrix([[sympy.cos(th), 0, sympy.sin(th)], [0, 1, 0], [-sympy.sin(th), 0, sympy.cos(th)]])
    r = sympy.Matrix([-(h / 2) * sympy.sin(th), 0, -(h / 2) * sympy.cos(th)]) + R * c
    v = r.diff(t)
    T = m / 2 * (v.T * v)[0, 0] + p["rod_iyy"] / 2 * qd[0] ** 2  # ω = θ̇ e_y in the body frame too
    return T - m * g * r[2], []


def cone_pendulum(q, qd, p):
    # solid cone from its apex: COM at 3h/4 from the apex, I_perp(COM) = m (3/20 r² + 3/80 h²)
    (th,) = q
    m, r, h, g = p["m"], p["r"], p["h"], p["g"]
    d = sympy.Rational(3, 4) * h
    I = m * (sympy.Rational(3, 20) * r**2 + sympy.Rational(3, 80) * h**2)
    T = m / 2 * d**2 * qd[0] ** 2 + I / 2 * qd[0] ** 2
    return T + m * g * d * sympy.cos(th), []


def rolling(I_over_m):
    # rolling without slipping down an incline: T = m ṡ²/2 + I (ṡ/R)²/2, V = −m g s sin α
    def lagrangian(q, qd, p):
        (s,) = q
        m, g, alpha = p["m"], p["g"], p["alpha"]
        I, R = I_over_m(p)
        T = m / 2 * qd[0] ** 2 + m * I / 2 * (qd[0] / R) ** 2
        return T + m * g * s * sympy.sin(alpha), []
    return lagrangian


def stiff_dumbbell(q, qd, p):
    # two particles on a spring of rest length 2 r0
    x1, y1, x2, y2 = q
    m, k, r0 = p["m"], p["k"], p["r0"]
    T = m / 2 * sum(v**2 for v in qd)
    V = k / 2 * (sympy.sqrt((x1 - x2) ** 2 + (y1 - y2) ** 2) - 2 * r0) ** 2
    return T - V, []


def rot(axis, angle):
    c, s_ = sympy.cos(angle), sympy.sin(angle)
    if axis == "x":
        return sympy.Matrix([[1, 0, 0], [0, c, -s_], [0, s_, c]])
    if axis == "y":
        return sympy.Matrix([[c, 0, s_], [0, 1, 0], [-s_, 0, c]])
    return sympy.Matrix([[c, -s_, 0], [s_, c, 0], [0, 0, 1]])


def rigid_body_energy(R, p_WB, com_B, m, I_C, g):
    # T = ½ m |ċ|² + ½ ω_Bᵀ I_C ω_B with c = p_WB + R com_B and [ω_B]ₓ = Rᵀ Ṙ; V = m g c_z
    c = p_WB + R * com_B
    W = sympy.simplify(R.T * sympy.diff(R, t))
    w = sympy.Matrix([W[2, 1], W[0, 2], W[1, 0]])
    cd = sympy.diff(c, t)
    T = m / 2 * (cd.T * cd)[0] + (w.T * I_C * w)[0] / 2
    return T, m * g * c[2]


def sleeping_top(q, qd, p):
    # a solid cylinder (radius r, height h) turned by Rx(a) Ry(b) Rz(psi), its COM at d on its axis
    a, b, psi = q
    m, r, h, d = p["m"], p["r"], p["h"], p["d"]
    R = rot("x", a) * rot("y", b) * rot("z", psi)
    I_C = sympy.diag(m * (3 * r**2 + h**2) / 12, m * (3 * r**2 + h**2) / 12, m * r**2 / 2)
    T, V = rigid_body_energy(R, R * sympy.Matrix([0, 0, d]), sympy.zeros(3, 1), m, I_C, p["g"])
    return T - V, []


def chaplygin_sleigh(q, qd, p):
    # a flat body turned by theta about z, its COM at (a, 0) ahead of the contact point (x, y);
    # the blade: -sin(theta) x_dot + cos(theta) y_dot = 0 (a velocity constraint)
    x, y, th = q
    I_C = sympy.diag(sympy.Rational(5, 100), sympy.Rational(7, 100), p["I"])
    T, _ = rigid_body_energy(rot("z", th), sympy.Matrix([x, y, 0]), sympy.Matrix([p["a"], 0, 0]),
                             p["m"], I_C, 0)
    return T, [], [[-sympy.sin(th), sympy.cos(th), 0]]


def rolling_disk(q, qd, p):
    # a thin disk (I = m r²/4 about a diameter, m r²/2 about its axis): heading psi, lean
    # theta - pi/2 about x, spin phi; rolling: x_dot = r cos(psi) phi_dot, y_dot = r sin(psi) phi_dot
    x, y, psi, th, phi = q
    m, r = p["m"], p["r"]
    R = rot("z", psi) * rot("x", th - sympy.pi / 2) * rot("z", phi)
    p_WB = sympy.Matrix([x + r * sympy.sin(psi) * sympy.sin(th), y - r * sympy.cos(psi) * sympy.sin(th),
                         r * sympy.cos(th)])
    I_C = sympy.diag(m * r**2 / 4, m * r**2 / 4, m * r**2 / 2)
    T, V = rigid_body_energy(R, p_WB, sympy.zeros(3, 1), m, I_C, p["g"])
    return T - V, [], [[1, 0, 0, 0, -r * sympy.cos(psi)], [0, 1, 0, 0, -r * sympy.sin(psi)]]


CASES = {
    "double_pendulum": double_pendulum,
    "atwood": atwood,
    "physical_pendulum": physical_pendulum,
    "graded_rod_pendulum": graded_rod_pendulum,
    "cone_pendulum": cone_pendulum,
    "rolling_cylinder": rolling(lambda p: (p["r"] ** 2 / 2, p["r"])),
    "rolling_sphere": rolling(lambda p: (sympy.Rational(2, 5) * p["r"] ** 2, p["r"])),
    "rolling_tube": rolling(lambda p: ((p["r1"] ** 2 + p["r2"] ** 2) / 2, p["r2"])),
    "stiff_dumbbell": stiff_dumbbell,
    "sleeping_top": sleeping_top,
    "chaplygin_sleigh": chaplygin_sleigh,
    "rolling_disk": rolling_disk,
}


def test_every_coordinate_example_is_covered(run):
    coordinate_examples = set()
    for scene in EXAMPLES.glob("*.toml"):
        if json.loads(run("eom", scene, "--format", "json", check=True).stdout)["kind"] == "coordinates":
            coordinate_examples.add(scene.stem)
    assert coordinate_examples == set(CASES)


@pytest.mark.parametrize("name", sorted(CASES))
def test_mass_matrix_and_forcing_equal_sympys(run, name):
    doc = json.loads(run("eom", EXAMPLES / f"{name}.toml", "--format", "json", check=True).stdout)
    names = [s["name"] for s in doc["symbols"]]
    local = {n: S(n) for n in names}
    read = lambda text: sympy.sympify(text, locals=local)  # noqa: E731
    coords = doc["coordinates"]
    n = len(coords)
    q = dynamicsymbols(" ".join(coords)) if n > 1 else [dynamicsymbols(coords[0])]
    qd = [sympy.diff(x, t) for x in q]
    p = {d["name"]: S(d["name"]) for d in doc["parameters"]}
    L, constraints, *velocity_rows = CASES[name](q, qd, p)
    # velocity constraints enter through their matrix A (checked below); M and f come from L
    lm = LagrangesMethod(L, q, hol_coneqs=constraints or None)
    lm.form_lagranges_equations()
    # SymPy's time functions → rigid's names: q → q, q̇ → q_dot
    plain = {**{sympy.diff(x, t): S(c + "_dot") for x, c in zip(q, coords)},
             **{x: S(c) for x, c in zip(q, coords)}}
    M = lm.mass_matrix.subs(plain)
    f = lm.forcing.subs(plain)
    for i in range(n):
        for j in range(n):
            diff = read(doc["mass_matrix"]["text"][i][j]) - M[i, j]
            assert sympy.simplify(diff) == 0, (name, i, j, doc["mass_matrix"]["text"][i][j], M[i, j])
        diff = read(doc["forcing"]["text"][i]) - f[i]
        assert sympy.simplify(diff) == 0, (name, i, doc["forcing"]["text"][i], f[i])
    # the multipliers' columns: SymPy writes M q̈ − Gᵀλ... as [M | −Gᵀ] (same λ), rigid
    # M q̈ = f + Gᵀ λ: the columns are −G transposed
    for k in range(len(constraints)):
        for i in range(n):
            diff = read(doc["constraint_jacobian"]["text"][k][i]) + lm.mass_matrix[i, n + k].subs(plain)
            assert sympy.simplify(diff) == 0, (name, k, i)
    # the velocity constraints' matrix A, row by row, against the rows written above
    for k, row in enumerate(velocity_rows[0] if velocity_rows else []):
        for i in range(n):
            diff = read(doc["velocity_constraint_matrix"]["text"][k][i]) - sympy.sympify(row[i]).subs(plain)
            assert sympy.simplify(diff) == 0, (name, k, i)


@pytest.mark.parametrize("name", sorted(CASES))
def test_parts_of_the_forcing_add_up(run, name):
    doc = json.loads(run("eom", EXAMPLES / f"{name}.toml", "--format", "json", check=True).stdout)
    local = {s["name"]: S(s["name"]) for s in doc["symbols"]}
    read = lambda text: sympy.sympify(text, locals=local)  # noqa: E731
    for i in range(len(doc["coordinates"])):
        parts = sum(read(doc[k]["text"][i]) for k in ("forcing_inertial", "forcing_potential", "forcing_generalized"))
        assert sympy.simplify(parts - read(doc["forcing"]["text"][i])) == 0
