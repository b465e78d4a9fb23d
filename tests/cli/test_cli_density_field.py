"""`rigid inertia box|cylinder|sphere --density-field EXPR`: a density ρ(x, y, z) (kg/m³, x, y, z
in m in the shape's own frame) integrated by adaptive cubature, against closed forms; the
cubature's error estimate is printed, and a field it cannot integrate is refused."""
import json
import math
import re

import pytest


def inertia(run, *args):
    proc = run("inertia", *args, "--format", "json", check=True)
    return json.loads(proc.stdout), proc.stderr


def test_a_constant_field_is_the_constant_density(run):
    field, note = inertia(run, "box", "--lx", 0.2, "--ly", 0.3, "--lz", 1.0, "--density-field", "7800")
    plain, _ = inertia(run, "box", "--lx", 0.2, "--ly", 0.3, "--lz", 1.0, "--density", 7800)
    # the cubature of a constant is exact to round-off (its error estimate says ~1e-15)
    assert field["mass"] == pytest.approx(plain["mass"], rel=1e-13)
    for row_f, row_p in zip(field["inertia"], plain["inertia"]):
        assert row_f == pytest.approx(row_p, rel=1e-12, abs=1e-12)
    assert "density field: 1 cell of 15³ points; estimated errors: mass" in note


def test_a_rod_denser_towards_one_end(run):
    # cylinder r = 0.05, h = 2 with ρ = ρ0 (1 + z/h): m = ρ0 π r² h, z_c = h/12 (∫ z²/h dz over
    # [−h/2, h/2] is h³/(12 h)), I_zz about the axis = m r²/2 (the z term integrates out)
    rho0, r, h = 2700.0, 0.05, 2.0
    got, _ = inertia(run, "cylinder", "--radius", r, "--height", h, "--density-field", f"{rho0}*(1 + z/{h})")
    m = rho0 * math.pi * r * r * h
    assert got["mass"] == pytest.approx(m, rel=1e-10)
    assert got["com"][2] == pytest.approx(h / 12, rel=1e-10)
    assert got["inertia"][2][2] == pytest.approx(m * r * r / 2, rel=1e-9)


def test_a_ball_denser_outwards(run):
    # ρ = ρ0 (1 + s²/R²): m = ρ0 π R³ (4/3 + 4/5), I = (2/3) ∫ ρ s² dV = (32/35) π ρ0 R⁵
    rho0, R = 100.0, 0.5
    got, _ = inertia(run, "sphere", "--radius", R, "--density-field", f"{rho0}*(1 + (x^2 + y^2 + z^2)/{R * R})")
    assert got["mass"] == pytest.approx(rho0 * math.pi * R ** 3 * (4 / 3 + 4 / 5), rel=1e-10)
    for k in range(3):
        assert got["inertia"][k][k] == pytest.approx(32 / 35 * math.pi * rho0 * R ** 5, rel=1e-9)


@pytest.mark.parametrize("args, status, message", [
    (["--density-field", "1000*x"], 1, "--density-field '1000*x': "),        # negative where x < 0
    (["--density-field", "1/sqrt(abs(x))"], 1, "got inf kg/m³ at [0, 0, 0] m"),  # infinite at x = 0
    (["--density-field", "1000*w"], 1, "undefined symbol 'w'; known names: x, y, z"),
    (["--density-field", "1000*(1+x"], 1, "missing ')'"),
    (["--density-field", "1000", "--mass", "3"], 2, "--density-field gives the density"),
])
def test_fields_that_cannot_be_integrated_are_refused(run, args, status, message):
    proc = run("inertia", "box", "--lx", 1, "--ly", 1, "--lz", 1, *args)
    assert proc.returncode == status, proc.stderr
    assert message in proc.stderr, proc.stderr


def test_only_the_shapes_with_a_cubature_take_a_field(run):
    proc = run("inertia", "cone", "--radius", 1, "--height", 1, "--density-field", "3")
    assert proc.returncode == 2, proc.stderr


# ---- scenes: `density_field = "…"` on a box, cylinder or sphere --------------------------

EXAMPLE = __import__("pathlib").Path(__file__).resolve().parents[2] / "examples" / "graded_rod_pendulum.toml"


def test_a_sweep_of_the_density_scale_leaves_the_period(run, tmp_path):
    # ρ0 scales m and I_p alike, so the period of examples/graded_rod_pendulum.toml is the same
    # for every ρ0 (the closed form 1.80796 s is checked by test_example_comments.py); a run's
    # density field is integrated with that run's parameters
    run("sweep", EXAMPLE, "--grid", "rho0=1000:3000:3", "--set", "simulation.t_end=4", "-o",
        tmp_path / "sweep", "-q", check=True)
    rows = (tmp_path / "sweep" / "runs.csv").read_text().splitlines()[1:]
    periods = [float(r.split(",")[2]) for r in rows]
    assert len(periods) == 3
    assert max(periods) - min(periods) <= 1e-9 * periods[0], periods
    # and h, which the field names, changes it as the closed form says (T ∝ sqrt(h) for r ≪ h)
    run("sweep", EXAMPLE, "--grid", "h=2:2:1", "--set", "simulation.t_end=5", "-o",
        tmp_path / "long", "-q", check=True)
    long = float((tmp_path / "long" / "runs.csv").read_text().splitlines()[1].split(",")[2])
    h, r, g = 2.0, 0.01, 9.81
    tau = math.sqrt((5 * h * h / 12 + r * r / 4) / (g * 7 * h / 12))
    from scipy.special import ellipk
    assert long == pytest.approx(4 * ellipk(math.sin(0.5) ** 2) * tau, rel=1e-9)


SCENE = """\
[parameters]
rho0 = 1000
[[bodies]]
name = "brick"
free = true
angular_velocity = [0.01, 1, 0.01]
{body}
[simulation]
t_end = 0.1
"""


@pytest.mark.parametrize("body, message", [
    ('primitive = "cone"\nradius = 1\nheight = 1\ndensity_field = "rho0"',
     "density_field is integrated over a box, a cylinder, a sphere or a closed mesh, not a "
     "solid_cone"),
    ('primitive = "box"\nlx = 1\nly = 1\nlz = 1\ndensity_field = "rho0"\nmass = 2',
     "density_field gives the mass; it takes no 'mass' or 'density'"),
    ('mesh = "part.stl"\ndensity_field = "rho0"\nshell = true',
     "density_field is the density of a solid; a mesh with 'shell' is a shell"),
    ('point_masses = [{ mass = 1, position = [0, 0, 0] }]\ndensity_field = "rho0"',
     "density_field goes with 'primitive' (box, cylinder or sphere) or 'mesh' (a closed one)"),
    ('primitive = "box"\nlx = 1\nly = 1\nlz = 1\ndensity_field = "rho0*q"',
     "undefined symbol 'q'"),
    ('primitive = "box"\nlx = 1\nly = 1\nlz = 1\ndensity_field = 1000',
     "density_field must be an expression string of x, y, z"),
    ('primitive = "box"\nlx = 1\nly = 1\nlz = 1\ndensity_field = "rho0*x"',
     "density must be non-negative and finite"),
])
def test_a_scene_field_is_refused_where_it_is_written(run, tmp_path, body, message):
    path = tmp_path / "brick.toml"
    path.write_text(SCENE.format(body=body))
    proc = run("check", path)
    assert proc.returncode == 1, proc.stderr
    assert message in proc.stderr, proc.stderr
    assert "brick.toml:" in proc.stderr, proc.stderr  # located in the file


def test_check_prints_the_cubature_error_estimate_as_inertia_does(run):
    # `rigid check` of a scene with a density field: the body's line is followed by the field's
    # cubature and estimated errors, the line `rigid inertia --density-field` prints for the same
    # shape and field (parameters written out: the same numbers at the same points, so the same
    # line to the digit)
    proc = run("check", EXAMPLE, check=True)
    _, note = inertia(run, "cylinder", "--radius", 0.01, "--height", 1.0, "--density-field",
                      "2700*(1 - z/1.0)")
    line = next(l for l in note.splitlines() if l.startswith("density field: "))
    lines = proc.stdout.splitlines()
    rod = next(i for i, l in enumerate(lines) if l.startswith("  rod "))
    assert lines[rod + 1] == "    " + line, proc.stdout
    # the estimate bounds the actual error of the mass against its closed form, rho0 pi r^2 h
    # (the body line prints 6 digits, so the comparison allows that rounding too)
    estimate = float(re.search(r"estimated errors: mass (\S+) kg", line).group(1))
    printed = float(re.search(r"  rod +mass (\S+) kg", lines[rod]).group(1))
    exact = 2700 * math.pi * 0.01 ** 2 * 1.0
    assert abs(printed - exact) <= estimate + 5e-6 * exact
    # a scene without a density field prints no such line
    plain = run("check", EXAMPLE.parent / "physical_pendulum.toml", check=True).stdout
    assert "density field" not in plain
