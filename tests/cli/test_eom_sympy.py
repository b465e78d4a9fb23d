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


CASES = {
    "double_pendulum": double_pendulum,
    "atwood": atwood,
    "physical_pendulum": physical_pendulum,
    "cone_pendulum": cone_pendulum,
    "rolling_cylinder": rolling(lambda p: (p["r"] ** 2 / 2, p["r"])),
    "rolling_sphere": rolling(lambda p: (sympy.Rational(2, 5) * p["r"] ** 2, p["r"])),
    "rolling_tube": rolling(lambda p: ((p["r1"] ** 2 + p["r2"] ** 2) / 2, p["r2"])),
    "stiff_dumbbell": stiff_dumbbell,
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
    L, constraints = CASES[name](q, qd, p)
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


@pytest.mark.parametrize("name", sorted(CASES))
def test_parts_of_the_forcing_add_up(run, name):
    doc = json.loads(run("eom", EXAMPLES / f"{name}.toml", "--format", "json", check=True).stdout)
    local = {s["name"]: S(s["name"]) for s in doc["symbols"]}
    read = lambda text: sympy.sympify(text, locals=local)  # noqa: E731
    for i in range(len(doc["coordinates"])):
        parts = sum(read(doc[k]["text"][i]) for k in ("forcing_inertial", "forcing_potential", "forcing_generalized"))
        assert sympy.simplify(parts - read(doc["forcing"]["text"][i])) == 0
