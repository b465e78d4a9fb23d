"""`rigid inertia box|cylinder|sphere --density-field EXPR`: a density ρ(x, y, z) (kg/m³, x, y, z
in m in the shape's own frame) integrated by adaptive cubature, against closed forms; the
cubature's error estimate is printed, and a field it cannot integrate is refused."""
import json
import math

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
