"""rigid.mesh.integrate_density: ρ(x, y, z) over the solid a closed mesh bounds, against the
box cubature of rigid.mass (an independent rule on the same box) and the CLI's
`rigid inertia MESH --density-field` (the same integration through another front end)."""
import json
import os
import subprocess

import numpy as np
import pytest

import rigid

VERTICES = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                     [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float) * [0.4, 0.3, 0.2]
TRIANGLES = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                      [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])


def rho(p):
    return 1000.0 * (1 + p[0] / 0.4) * np.exp(p[2])


def test_against_the_box_cubature():
    """Mass, COM and inertia of the box mesh equal the box cubature's (the field shifted to the
    box's centre) within the two error estimates and 1e-12 relative."""
    mesh = rigid.mesh.TriangleMesh(VERTICES, TRIANGLES)
    got = rigid.mesh.integrate_density(mesh, rho)
    c = np.array([0.2, 0.15, 0.1])
    ref = rigid.mass.integrate_density_over_box(lambda p: rho(np.asarray(p) + c), 0.4, 0.3, 0.2)
    assert got.converged and ref.converged
    m, mr = got.mass_properties, ref.mass_properties
    assert abs(m.mass - mr.mass) <= got.mass_error + ref.mass_error + 1e-12 * mr.mass
    assert np.max(np.abs(m.com - (mr.com + c))) <= got.com_error + ref.com_error + 1e-15
    assert np.max(np.abs(m.inertia_com - mr.inertia_com)) <= (
        got.inertia_error + ref.inertia_error + 1e-12 * np.trace(mr.inertia_com))


def test_the_same_as_the_cli(tmp_path):
    """The CLI's --density-field over the same box as an STL gives the same mass to 1e-13
    (the same rules on the same tetrahedra; the CLI's field is compiled, Python's a callable)."""
    lines = ["solid b"]
    for t in TRIANGLES:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += ["vertex {!r} {!r} {!r}".format(*VERTICES[k]) for k in t]
        lines += ["endloop", "endfacet"]
    stl = tmp_path / "b.stl"
    stl.write_text("\n".join(lines + ["endsolid b"]) + "\n")
    out = subprocess.run([os.environ.get("RIGID_EXE", "rigid"), "inertia", str(stl),
                          "--density-field", "1000*(1 + x/0.4)*exp(z)", "--format", "json"],
                         capture_output=True, text=True, check=True)
    cli = json.loads(out.stdout)
    got = rigid.mesh.integrate_density(rigid.mesh.TriangleMesh(VERTICES, TRIANGLES), rho)
    assert got.mass_properties.mass == pytest.approx(cli["mass"], rel=1e-13)


def test_an_open_mesh_is_refused():
    mesh = rigid.mesh.TriangleMesh(VERTICES, TRIANGLES[:-1])
    with pytest.raises(rigid.Error, match="not closed and consistently oriented"):
        rigid.mesh.integrate_density(mesh, rho)
