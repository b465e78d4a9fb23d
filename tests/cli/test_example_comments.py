"""The numbers the examples' comments state are true.

Every example file states at least one number in a machine-readable comment line

    # check: <name> = <value> [unit] (<rel|abs> <tolerance>[; run <rel|abs> <tolerance>])

and this test compares each stated value
  (a) with a closed form computed here, independently of rigid, from the parameters the
      example itself gives (read from its TOML, or the script's constants), within the first
      tolerance (the precision the comment claims), and
  (b) when the line has a `run` tolerance, with what running the example gives (`rigid run` of
      a scene, the printed output of a script), within the run tolerance (what the example's
      integrator and output spacing can resolve; each example's comment says why).
A check whose name has no closed form here fails, so a new claim needs its derivation too.
"""
import csv
import math
import os
import pathlib
import re
import subprocess
import sys
import tomllib

import numpy as np
import pytest
from scipy.special import ellipk, ellipkinc

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
FILES = sorted(p for p in EXAMPLES.iterdir() if p.suffix in (".toml", ".py"))

CHECK = re.compile(
    r"^\s*#\s*check:\s*(?P<name>.+?)\s*=\s*(?P<value>[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"
    r"\s*(?P<unit>[^(]*?)\s*\((?P<kind>rel|abs) (?P<tol>[0-9.eE+-]+)"
    r"(?:;\s*run (?P<run_kind>rel|abs) (?P<run_tol>[0-9.eE+-]+))?\)\s*$")


def checks(path):
    """The check lines of an example: [(name, value, kind, tol, run_kind, run_tol)]."""
    found = []
    for line in path.read_text().splitlines():
        if re.match(r"^\s*#\s*check:", line):
            m = CHECK.match(line)
            assert m, f"{path.name}: malformed check line: {line!r}"
            found.append((m["name"], float(m["value"]), m["kind"], float(m["tol"]),
                          m["run_kind"], float(m["run_tol"]) if m["run_tol"] else None))
    return found


def agree(stated, actual, kind, tol):
    return abs(stated - actual) <= (tol * abs(actual) if kind == "rel" else tol)


# ---- closed forms, from each example's own parameters -------------------------------------

def scene(path):
    with open(path, "rb") as f:
        return tomllib.load(f)


def parameters(doc):
    return {k: float(v) for k, v in doc.get("parameters", {}).items() if not isinstance(v, str)}


def coordinate(doc, name, key="initial"):
    return float(next(c for c in doc["coordinates"] if c["name"] == name).get(key, 0.0))


def rolling(doc, inertia_factor):
    # T = ½ m ṡ² + ½ I (ṡ/r)², V = −m g s sin α, I = c m r²  =>  s̈ = g sin α / (1 + c); s(t) = a t²/2
    p = parameters(doc)
    a = p["g"] * math.sin(p["alpha"]) / (1 + inertia_factor(p))
    t = float(doc["simulation"]["t_end"])
    return {"a": a, "s(2 s)": a * t * t / 2} if t == 2.0 else {"a": a}


def atwood(doc):
    # (m1 + m2 + M/2) a = (m1 − m2) g; the rope pulls each weight up: T1 = m1 (g − a), T2 = m2 (g + a)
    p = parameters(doc)
    a = (p["m1"] - p["m2"]) * p["g"] / (p["m1"] + p["m2"] + p["M"] / 2)
    return {"a": a, "T1": p["m1"] * (p["g"] - a), "T2": p["m2"] * (p["g"] + a)}


def cone_pendulum(doc):
    # solid cone about its apex: I = m (3/20 r² + 3/5 h²), COM at d = 3h/4 from the apex
    p = parameters(doc)
    I, d = p["m"] * (3 / 20 * p["r"] ** 2 + 3 / 5 * p["h"] ** 2), 3 * p["h"] / 4
    return {"T0": 2 * math.pi * math.sqrt(I / (p["m"] * p["g"] * d))}


def double_pendulum(doc):
    # at rest: E = V = −m1 g l1 cos θ1 − m2 g (l1 cos θ1 + l2 cos θ2)
    p = parameters(doc)
    c1, c2 = math.cos(coordinate(doc, "theta1")), math.cos(coordinate(doc, "theta2"))
    return {"E": -p["m1"] * p["g"] * p["l1"] * c1 - p["m2"] * p["g"] * (p["l1"] * c1 + p["l2"] * c2)}


def heavy_top(doc):
    # solid cone on its apex: I3 = 3/10 m r², I1 = m (3/20 r² + 3/80 h²) + m d², d = 3h/4; the body
    # axis is turned by the initial rotation angle, so the tilt from the vertical is π − angle.
    b = doc["bodies"][0]
    m, r, h, w3 = b["mass"], b["radius"], b["height"], b["angular_velocity"][2]
    g, theta = -doc["gravity"][2], math.pi - b["initial_rotation"]["angle"]
    d = 3 * h / 4
    assert b["pivot"] == [0, 0, h], "the closed form is for a top on its apex"
    I3, I1 = 0.3 * m * r * r, m * (3 / 20 * r * r + 3 / 80 * h * h) + m * d * d
    disc = (I3 * w3) ** 2 - 4 * I1 * m * g * d * math.cos(theta)
    return {"Omega_p": m * g * d / (I3 * w3),
            "W": (I3 * w3 - math.sqrt(disc)) / (2 * I1 * math.cos(theta))}


def physical_pendulum(doc):
    # thin rod about one end: θ̈ = −(3g/2L) sin θ; T = 4 K(sin²(θ0/2)) sqrt(2L/3g), K(m) with m = k²
    p = parameters(doc)
    tau = math.sqrt(2 * p["L"] / (3 * p["g"]))
    theta0 = coordinate(doc, "theta")
    return {"T0": 2 * math.pi * tau, "T": 4 * ellipk(math.sin(theta0 / 2) ** 2) * tau}


def graded_rod_pendulum(doc):
    # a rod (radius r, length h) hanging from its top end with ρ = ρ0 (1/2 + u/h), u the distance
    # from the pivot: m = ρ0 π r² h, COM at d = 7h/12, I_p = m (5h²/12 + r²/4);
    # T = 4 K(sin²(θ0/2)) sqrt(I_p / (m g d))
    p = parameters(doc)
    h, r, g = p["h"], p["r"], p["g"]
    tau = math.sqrt((5 * h * h / 12 + r * r / 4) / (g * 7 * h / 12))
    theta0 = coordinate(doc, "theta")
    return {"T0": 2 * math.pi * tau, "T": 4 * ellipk(math.sin(theta0 / 2) ** 2) * tau}


def sleeping_top(doc):
    # disk (m, r, h) with its COM at d above the pivot: I3 = m r²/2, I1 = m (3r² + h²)/12 + m d²;
    # u = a + i b ∝ e^{iωt} with I1 ω² − I3 w3 ω + m g d = 0: real roots iff w3² > 4 m g d I1 / I3²
    p = parameters(doc)
    m, r, h, d, g, w3 = (p[k] for k in ("m", "r", "h", "d", "g", "w3"))
    I1, I3 = m * (3 * r * r + h * h) / 12 + m * d * d, m * r * r / 2
    return {"omega3_min": 2 * math.sqrt(m * g * d * I1) / I3,
            "w_slow": (I3 * w3 - math.sqrt((I3 * w3) ** 2 - 4 * I1 * m * g * d)) / (2 * I1)}


def stiff_dumbbell(doc):
    # m w² r = k (2r − 2r0)  =>  r = k r0 / (k − m w²/2)
    p = parameters(doc)
    return {"r": p["k"] * p["r0"] / (p["k"] - p["m"] * p["w"] ** 2 / 2)}


def tennis_racket(doc):
    # Euler's equations with 2E I2 < L²: ω2 = b sn(λ t + u0 | k²), λ and k² as the comment says;
    # ω2 changes sign at λ t + u0 = 2K, 4K, …; at t = 0, sn(u0) = ω2(0)/b with u0 < K (ω̇2 > 0)
    b = doc["bodies"][0]
    I1, I2, I3 = (b["inertia"][k] for k in ("ixx", "iyy", "izz"))
    w1, w2, w3 = b["angular_velocity"]
    E2 = I1 * w1 ** 2 + I2 * w2 ** 2 + I3 * w3 ** 2
    L2 = (I1 * w1) ** 2 + (I2 * w2) ** 2 + (I3 * w3) ** 2
    assert E2 * I2 < L2 and (I3 - I1) * w3 * w1 > 0, "the closed form below is for this regime"
    lam = math.sqrt((I3 - I2) * (L2 - E2 * I1) / (I1 * I2 * I3))
    k2 = (I2 - I1) * (E2 * I3 - L2) / ((I3 - I2) * (L2 - E2 * I1))
    w2_max = math.sqrt((E2 * I3 - L2) / (I2 * (I3 - I2)))  # ω2 where ω1 = 0
    K = ellipk(k2)
    u0 = ellipkinc(math.asin(w2 / w2_max), k2)
    return {"T": 4 * K / lam, "T/2": 2 * K / lam, "first flip": (2 * K - u0) / lam}


def rolling_disk(doc):
    # steady motion of a thin disk (I1 = m r²/4, I3 = m r²/2) leaning by θ, heading rate Ω:
    # I1 Ω² sin θ cos θ − (I3 + m r²) w3 Ω cos θ = m g r sin θ  (angular momentum about the
    # centre against the contact force's torque, docs/lagrange.md); φ̇ = w3 − Ω sin θ
    p = parameters(doc)
    m, r, g, th, Om = p["m"], p["r"], p["g"], p["lean"], p["Omega"]
    s, c = math.sin(th), math.cos(th)
    I1, I3 = m * r * r / 4, m * r * r / 2
    w3 = (I1 * Om ** 2 * s * c - m * g * r * s) / ((I3 + m * r * r) * Om * c)
    phi_dot = w3 - Om * s
    return {"phi_dot": phi_dot, "rho": abs(r * phi_dot / Om), "|mu|": m * r * w3 * abs(Om),
            "E": 0.5 * m * (r * w3) ** 2 + 0.5 * (I1 * (Om * c) ** 2 + I3 * w3 ** 2) + m * g * r * c}


def chaplygin_sleigh(doc):
    # v̇ = a ω², ω̇ = −(m a / J) v ω, J = I + m a²: v = V tanh s, ω = ω0 cosh s0 / cosh s,
    # θ − θ0 = sgn(ω0) √(J/m)/a (gd s − gd s0), s = (a m V / J) t + atanh(v0/V), V² = v0² + J ω0²/m
    p = parameters(doc)
    m, I, a, v0, w0 = p["m"], p["I"], p["a"], p["v0"], p["w0"]
    t = float(doc["simulation"]["t_end"])
    J = I + m * a * a
    V = math.sqrt(v0 ** 2 + J * w0 ** 2 / m)
    s0 = math.atanh(v0 / V)
    s = a * m * V / J * t + s0
    gd = lambda x: 2 * math.atan(math.tanh(x / 2))  # noqa: E731
    return {f"v({t:g} s)": V * math.tanh(s), f"w({t:g} s)": w0 * math.cosh(s0) / math.cosh(s),
            f"theta({t:g} s)": math.copysign(1, w0) * math.sqrt(J / m) / a * (gd(s) - gd(s0)),
            "E": 0.5 * (m * v0 ** 2 + J * w0 ** 2)}


def lagrange_atwood(_):
    # the script's constants: m1, m2, M, g; a = (m2 − m1) g / (m1 + m2 + M/2), y1 = a t²/2 at t = 1 s
    m1, m2, M, g = 1.0, 1.5, 0.8, 9.81
    a = (m2 - m1) * g / (m1 + m2 + M / 2)
    return {"y1(1 s)": a / 2, "T1": m1 * (g + a), "T2": m2 * (g - a)}


def robot_link(_):
    # the script's parts: an aluminium tube (r 0.02–0.025 m, 0.4 m) centred at x = 0.2 m, a steel
    # box 0.06 × 0.06 × 0.05 m at x = 0.43 m with a steel cylinder (r 0.005 m, 0.05 m) removed
    tube = 2700.0 * math.pi * (0.025 ** 2 - 0.02 ** 2) * 0.4
    box = 7850.0 * (0.06 * 0.06 * 0.05 - math.pi * 0.005 ** 2 * 0.05)
    return {"mass": tube + box, "com x": (tube * 0.2 + box * 0.43) / (tube + box)}


def son(_):
    # the script's constants: J = diag(1, 2, 3, 4) kg m², the upper entries of M(0) in so(4);
    # E = ½ Σ_{i<j} M_ij²/(J_i + J_j), tr(M²) = −2 Σ_{i<j} M_ij², tr(M⁴) of the matrix;
    # dim SO(n) = n(n − 1)/2; the round trip and the n = 3 identity are exact (0)
    J = [1.0, 2.0, 3.0, 4.0]
    upper = {(0, 1): 0.3, (0, 2): -0.5, (0, 3): 0.2, (1, 2): 0.7, (1, 3): -0.4, (2, 3): 0.6}
    M = np.zeros((4, 4))
    for (i, j), v in upper.items():
        M[i, j], M[j, i] = v, -v
    return {"dim SO(4)": 4 * 3 / 2,
            "E": 0.5 * sum(v * v / (J[i] + J[j]) for (i, j), v in upper.items()),
            "tr(M^2)": -2 * sum(v * v for v in upper.values()),
            "tr(M^4)": float(np.trace(np.linalg.matrix_power(M, 4))),
            "exp-log round trip": 0.0, "Euler-Arnold minus Euler in R^3": 0.0}


CLOSED_FORMS = {
    "atwood": atwood,
    "cone_pendulum": cone_pendulum,
    "double_pendulum": double_pendulum,
    "heavy_top": heavy_top,
    "physical_pendulum": physical_pendulum,
    "graded_rod_pendulum": graded_rod_pendulum,
    "rolling_cylinder": lambda d: rolling(d, lambda p: 0.5),
    "rolling_sphere": lambda d: rolling(d, lambda p: 0.4),
    "rolling_tube": lambda d: rolling(d, lambda p: (p["r1"] ** 2 + p["r2"] ** 2) / (2 * p["r2"] ** 2)),
    "sleeping_top": sleeping_top,
    "stiff_dumbbell": stiff_dumbbell,
    "tennis_racket": tennis_racket,
    "rolling_disk": rolling_disk,
    "chaplygin_sleigh": chaplygin_sleigh,
    "lagrange_atwood": lagrange_atwood,
    "inertia_of_a_robot_link": robot_link,
    "son": son,
}


# ---- what a run gives ----------------------------------------------------------------------

def trajectory(run, path, tmp_path):
    run("run", path, "-o", tmp_path / "out", "--format", "csv", "-q", check=True)
    with open(tmp_path / "out" / "trajectory.csv") as f:
        rows = list(csv.reader(f))
    return {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}


def crossings(t, x, rising=None):
    """Times where x changes sign, by linear interpolation (x is odd about its crossings
    here — a pendulum angle, an Euler-equation sn — so the error is third order in the step)."""
    i = np.nonzero(np.sign(x[1:]) != np.sign(x[:-1]))[0]
    if rising is not None:
        i = i[(x[i + 1] > x[i]) == rising]
    return t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])


def period(t, x):
    up = crossings(t, x, rising=True)
    assert len(up) >= 2, "the run must show at least one full period"
    return float(np.mean(np.diff(up)))


def farthest(values, stated):
    """The sample farthest from the stated value (for quantities that must stay constant)."""
    return float(values[np.argmax(np.abs(values - stated))])


def run_scene(stem, name, stated, c):
    t = c["t"]
    if stem == "atwood":
        return {"a": 2 * c["y1"][-1] / t[-1] ** 2, "T1": -c["lambda_rope1"][-1],
                "T2": -c["lambda_rope2"][-1]}[name]
    if stem in ("rolling_cylinder", "rolling_sphere", "rolling_tube"):
        return {"a": 2 * c["s"][-1] / t[-1] ** 2, "s(2 s)": c["s"][-1]}[name]
    if stem in ("cone_pendulum", "physical_pendulum", "graded_rod_pendulum"):
        return period(t, c["theta"])
    if stem == "sleeping_top":
        # the tilt a = eps cos(w_slow t) of the slow circular mode
        return 2 * math.pi / period(t, c["a"])
    if stem == "double_pendulum":
        return farthest(c["energy"], stated)
    if stem == "stiff_dumbbell":
        return farthest(np.hypot(c["x1"], c["y1"]), stated)
    if stem == "heavy_top":
        # the body axis B z in the world (third column of R_WB from the quaternion), pointing
        # from the pivot to the COM (−z); the mean azimuth rate is the fitted slope (clockwise
        # precession: the azimuth decreases, so W is minus the slope)
        qw, qx, qy, qz = (c[f"top.q{k}"] for k in "wxyz")
        zx, zy = 2 * (qx * qz + qw * qy), 2 * (qy * qz - qw * qx)
        azimuth = np.unwrap(np.arctan2(-zy, -zx))
        return -float(np.polyfit(t, azimuth, 1)[0])
    if stem == "tennis_racket":
        flips = crossings(t, c["racket.wy"])
        return {"T/2": float(np.mean(np.diff(flips))), "first flip": float(flips[0])}[name]
    if stem == "rolling_disk":
        if name == "rho":
            # least-squares circle through the contact points: x² + y² = 2 x0 x + 2 y0 y + k
            x, y = c["x"], c["y"]
            (x0, y0, k), *_ = np.linalg.lstsq(np.column_stack([2 * x, 2 * y, np.ones_like(x)]),
                                             x * x + y * y, rcond=None)
            return farthest(np.hypot(x - x0, y - y0), stated)
        return farthest({"phi_dot": c["phi_dot"], "E": c["energy"],
                         "|mu|": np.hypot(c["mu_roll_x"], c["mu_roll_y"])}[name], stated)
    if stem == "chaplygin_sleigh":
        if name == "E":
            return farthest(c["energy"], stated)
        th = c["theta"][-1]
        v = c["x_dot"][-1] * math.cos(th) + c["y_dot"][-1] * math.sin(th)
        return {"v": v, "w": c["theta_dot"][-1], "theta": th}[name.split("(")[0]]
    raise AssertionError(f"{stem}: no run measurement for {name!r}")


def run_script(path):
    env = dict(os.environ)
    assert env.get("RIGID_PYTHON_DIR"), "RIGID_PYTHON_DIR must name the built module's directory"
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [env["RIGID_PYTHON_DIR"], env.get("PYTHONPATH")]))
    proc = subprocess.run([sys.executable, str(path)], capture_output=True, text=True, env=env,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def script_values(stem, out):
    number = r"([-+0-9.eE]+)"
    if stem == "lagrange_atwood":
        y1 = float(re.search(r"y1\(1 s\) = " + number, out)[1])
        t1, t2 = map(float, re.search(r"tensions \[\s*" + number + r"\s+" + number, out).groups())
        # the multipliers act on y1 and y2, which point up: the tensions are their magnitudes
        return {"y1(1 s)": y1, "T1": abs(t1), "T2": abs(t2)}
    if stem == "inertia_of_a_robot_link":
        m = re.search(r"mass: " + number + r" kg, com: \[?\s*" + number, out)
        assert m, out
        return {"mass": float(m[1]), "com x": float(m[2])}
    if stem == "son":
        # the values after the 10 s run (the second number of each line), the printed identities
        late = lambda name: float(re.search(re.escape(name) + r" = " + number + r".*, "  # noqa: E731
                                            + re.escape(name) + r" = " + number, out)[2])
        return {"dim SO(4)": float(re.search(r"dim SO\(4\) = " + number, out)[1]),
                "E": late("E"), "tr(M^2)": late("tr(M^2)"), "tr(M^4)": late("tr(M^4)"),
                "exp-log round trip": float(re.search(r"exp-log round trip = " + number, out)[1]),
                "Euler-Arnold minus Euler in R^3":
                    float(re.search(r"Euler-Arnold minus Euler in R\^3 = " + number, out)[1])}
    raise AssertionError(f"{stem}: no output measurement")


# ---- the tests -----------------------------------------------------------------------------

def test_every_example_states_a_checked_number():
    for path in FILES:
        found = checks(path)
        assert found, f"{path.name} states no `# check:` number"
        assert any(c[4] for c in found), f"{path.name}: no stated number is compared with a run"
        assert path.stem in CLOSED_FORMS, f"{path.name}: no closed form in this test"


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_stated_numbers_match_closed_forms(path):
    closed = CLOSED_FORMS[path.stem](scene(path) if path.suffix == ".toml" else None)
    for name, value, kind, tol, _, _ in checks(path):
        assert name in closed, f"{path.name}: no closed form for {name!r} (known: {sorted(closed)})"
        assert agree(value, closed[name], kind, tol), (
            f"{path.name}: the comment states {name} = {value}, the closed form gives "
            f"{closed[name]!r} ({kind} tolerance {tol})")


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_stated_numbers_match_the_run(path, run, tmp_path):
    if path.suffix == ".toml":
        columns = trajectory(run, path, tmp_path)
        measured = lambda name, value: run_scene(path.stem, name, value, columns)  # noqa: E731
    else:
        values = script_values(path.stem, run_script(path))
        measured = lambda name, value: values[name]  # noqa: E731
    for name, value, _, _, run_kind, run_tol in checks(path):
        if run_kind is None:
            continue
        got = measured(name, value)
        assert agree(value, got, run_kind, run_tol), (
            f"{path.name}: the comment states {name} = {value}, the run gives {got!r} "
            f"({run_kind} tolerance {run_tol})")


def test_a_wrong_comment_fails():
    # the comment the physical pendulum had before (T = 1.7758 s) is refused by the closed form
    closed = physical_pendulum(scene(EXAMPLES / "physical_pendulum.toml"))
    assert not agree(1.7758, closed["T"], "rel", 1e-5)
    assert not agree(1.6383, closed["T0"], "rel", 1e-5)
