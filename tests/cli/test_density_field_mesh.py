"""A density ρ(x, y, z) over a closed mesh: `rigid inertia MESH --density-field EXPR` and a
scene body with `mesh` and `density_field`. The references are independent: the uniform mesh's
own integrals (the divergence theorem of the mesh module, no cubature) for fields whose
integrals follow from them, and the box primitive's tensor Gauss–Kronrod cubature for a field
over a box-shaped mesh."""
import json
import pathlib

import numpy as np
import pytest

import rigid

ROOT = pathlib.Path(__file__).resolve().parents[2]
BRACKET = ROOT / "examples" / "docs" / "bracket.stl"  # a non-convex CAD part, in mm


def inertia(run, *args):
    proc = run("inertia", *args, "--format", "json", check=True)
    return json.loads(proc.stdout), proc.stderr


def box_stl(path, lo, hi):
    """An ASCII STL of the box [lo, hi] (m), outward normals."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
             (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    lines = ["solid box"]
    for f in faces:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += [f"vertex {v[k][0]!r} {v[k][1]!r} {v[k][2]!r}" for k in f]
        lines += ["endloop", "endfacet"]
    lines.append("endsolid box")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_field_over_a_box_mesh_is_the_box_primitives(run, tmp_path):
    """ρ = 1000 (1 + x/0.4) exp(z) over the box [0.1, 0.5] × [−0.1, 0.2] × [0, 0.3] as a mesh,
    and over the box primitive (its own frame at the centre, the field shifted): two cubatures
    (tetrahedra, Grundmann–Möller; a tensor Gauss–Kronrod box), each within 1e-8 of its estimate,
    agree to 1e-8 relative; the mesh's COM is the primitive's plus the centre."""
    lo, hi = np.array([0.1, -0.1, 0.0]), np.array([0.5, 0.2, 0.3])
    c = (lo + hi) / 2
    mesh, note = inertia(run, box_stl(tmp_path / "box.stl", lo, hi),
                         "--density-field", "1000*(1 + x/0.4)*exp(z)")
    shifted = f"1000*(1 + (x + {c[0]!r})/0.4)*exp(z + {c[2]!r})"
    size = hi - lo
    prim, _ = inertia(run, "box", "--lx", size[0], "--ly", size[1], "--lz", size[2],
                      "--density-field", shifted)
    assert mesh["mass"] == pytest.approx(prim["mass"], rel=1e-8)
    assert np.allclose(mesh["com"], np.array(prim["com"]) + c, rtol=0, atol=1e-8 * 0.5)
    assert np.allclose(mesh["inertia"], prim["inertia"], rtol=0,
                       atol=1e-8 * np.trace(prim["inertia"]))
    assert "density field: " in note and "tetrahedra of 105 points" in note


def test_a_linear_field_over_a_cad_bracket_follows_from_its_uniform_integrals(run):
    """The bracket (non-convex: tetrahedra from the centroid reach outside it). For ρ = ρ0 (1 + x/L):
    m = ρ0 (V + X/L) and ∫ρx = ρ0 (X + Sxx/L), with V, X = ∫x and Sxx = ∫x² from the uniform
    mesh's mass properties (divergence theorem, exact for a polyhedron). The cubature is exact for
    this field (degree 3 with the second moments), so only round-off and the 1e-8 bound remain."""
    rho0, L = 2700.0, 0.05
    uni, _ = inertia(run, BRACKET, "--units", "mm", "--density", rho0)
    m_u, com = uni["mass"], np.array(uni["com"])
    I = np.array(uni["inertia"])
    S_c = 0.5 * np.trace(I) * np.eye(3) - I          # ∫ρ (x − c)(x − c)ᵀ of the uniform body
    V, X = m_u / rho0, m_u / rho0 * com[0]
    Sxx = (S_c[0, 0] + m_u * com[0] ** 2) / rho0
    field, note = inertia(run, BRACKET, "--units", "mm", "--density-field", f"{rho0}*(1 + x/{L})")
    m = rho0 * (V + X / L)
    assert field["mass"] == pytest.approx(m, rel=1e-10)
    assert field["com"][0] == pytest.approx(rho0 * (X + Sxx / L) / m, rel=1e-9)
    # a constant field is the uniform solid itself
    const, _ = inertia(run, BRACKET, "--units", "mm", "--density-field", f"{rho0}")
    assert const["mass"] == pytest.approx(m_u, rel=1e-12)
    assert np.allclose(const["inertia"], I, rtol=0, atol=1e-11 * np.trace(I))


@pytest.mark.parametrize("args, status, message", [
    (["--density-field", "1000", "--mass", "2"], 2, "--density-field gives the density of a solid"),
    (["--density-field", "1000", "--shell"], 2, "takes no --mass, --density, --areal-density, --shell"),
    (["--density-field", "1000*(x - 0.3)"], 1, "--density-field '1000*(x - 0.3)': "),
    (["--density-field", "1000*w"], 1, "undefined symbol 'w'; known names: x, y, z"),
])
def test_refusals(run, tmp_path, args, status, message):
    proc = run("inertia", box_stl(tmp_path / "b.stl", (0, 0, 0), (1, 1, 1)), *args)
    assert proc.returncode == status, proc.stderr
    assert message in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr


def test_an_open_mesh_is_refused_as_for_a_uniform_solid(run, tmp_path):
    path = box_stl(tmp_path / "open.stl", (0, 0, 0), (1, 1, 1))
    text = path.read_text().split("facet normal")
    path.write_text("facet normal".join(text[:-1]) + "endsolid box\n")  # one triangle less
    field = run("inertia", path, "--density-field", "1000")
    uniform = run("inertia", path, "--density", "1000")
    assert field.returncode == uniform.returncode == 1
    assert uniform.stderr.splitlines()[-1] in field.stderr


SCENE = """
[[bodies]]
name = "block"
mesh = "box.stl"
density_field = "rho0*(1 + x/0.4)"
free = true
angular_velocity = [0.1, 2.0, 0.0]

[parameters]
rho0 = 800.0

[simulation]
t_end = 0.2
dt = 0.01
"""


def test_a_scene_body_with_a_mesh_and_a_field(run, tmp_path):
    """The scene's body weighs what `rigid inertia` gives for the same mesh and field (the same
    integration), through the CLI's check and Python's Scene; `rigid check` prints the estimate;
    a shell with a field is refused at its line."""
    box_stl(tmp_path / "box.stl", (0.1, -0.1, 0.0), (0.5, 0.2, 0.3))
    scene = tmp_path / "block.toml"
    scene.write_text(SCENE)
    direct, _ = inertia(run, tmp_path / "box.stl", "--density-field", "800.0*(1 + x/0.4)")
    check = run("check", scene, check=True)
    assert "density field: " in check.stdout + check.stderr
    body = rigid.Scene(str(scene)).bodies["block"]
    assert body.mass == pytest.approx(direct["mass"], rel=1e-14)
    assert np.allclose(body.com, direct["com"], rtol=1e-14, atol=1e-15)
    run("run", scene, "-o", tmp_path / "out", "-q", check=True)
    scene.write_text(SCENE.replace('free = true', 'free = true\nshell = true'))
    proc = run("check", scene)
    assert proc.returncode == 1
    assert "block.toml:5:" in proc.stderr and "density_field is the density of a solid" in proc.stderr


def test_the_mean_density_is_checked_against_real_materials(run):
    """The plausibility warnings of a uniform solid apply to the field's size and mean density:
    the bracket in mm with aluminium's 2700 kg/m³ (±10%) draws none; read as metres, it is 40 m
    long and draws the size hint; a field in g/cm³ mistaken for kg/m³ ×1000 (2.7e6) draws the
    density warning."""
    ok = run("inertia", BRACKET, "--units", "mm", "--density-field", "2700*(1 + x/0.5)", check=True)
    assert "warning" not in ok.stderr, ok.stderr
    metres = run("inertia", BRACKET, "--density-field", "2700*(1 + x/500)", check=True)
    assert "more than 10 m long" in metres.stderr and "use --units mm" in metres.stderr
    assert "implied density" not in metres.stderr
    heavy = run("inertia", BRACKET, "--units", "mm", "--density-field", "2.7e6", check=True)
    assert "implied density 2.7e+06 kg/m³ is outside any real material" in heavy.stderr, heavy.stderr
