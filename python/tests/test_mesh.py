"""rigid.mesh: arrays in and out, repair, exact moments of a box, errors."""
import numpy as np
import pytest

import rigid


def box(a, b, c):
    v = np.array([[(i & 1) * a, ((i >> 1) & 1) * b, ((i >> 2) & 1) * c] for i in range(8)], float)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    f = [t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
    return v, np.array(f)


def test_box_closed_form():
    a, b, c, rho = 0.3, 0.5, 0.7, 2700.0
    mesh = rigid.mesh.TriangleMesh(*box(a, b, c))
    mp, warnings = rigid.mesh.mass_properties(mesh, density=rho)
    m = rho * a * b * c
    assert warnings == []
    assert mp.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(mp.com, [a / 2, b / 2, c / 2], rtol=1e-12)
    expected = m / 12 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    np.testing.assert_allclose(mp.inertia_com, expected, rtol=0, atol=1e-12 * m)


def test_reversed_box_is_repaired():
    v, f = box(1, 2, 3)
    mesh = rigid.mesh.TriangleMesh(v, f[:, ::-1])
    report = rigid.mesh.repair(mesh)
    assert report.closed and report.inverted_components == 1
    assert report.components[0].volume == pytest.approx(6.0, rel=1e-12)
    assert "inward normals" in report.warnings[0]
    assert len(mesh) == 12 and mesh.vertices.shape == (8, 3)


def test_open_mesh_and_bad_input_errors(tmp_path):
    v, f = box(1, 1, 1)
    with pytest.raises(rigid.Error, match="3 boundary edges"):
        rigid.mesh.mass_properties(rigid.mesh.TriangleMesh(v, f[:-1]), density=1.0)
    with pytest.raises(rigid.Error, match="triangle 0 uses vertex 9"):
        rigid.mesh.TriangleMesh(v, np.array([[0, 1, 9]]))
    p = tmp_path / "empty.stl"
    p.write_bytes(b"")
    with pytest.raises(rigid.Error, match="empty.stl: the file is empty"):
        rigid.mesh.read(str(p))
    assert rigid.mesh.unit_scale("mm") == 0.001


def test_fill_holes_closes_a_missing_face_exactly():
    v, f = box(1, 2, 3)
    mesh = rigid.mesh.TriangleMesh(v, f[2:])  # without the face z = 0 (triangles 0 and 1)
    assert rigid.mesh.repair(mesh).boundary_edges == 4
    fill = rigid.mesh.fill_holes(mesh)
    assert len(fill.holes) == 1 and fill.holes[0].boundary_edges == 4
    assert fill.area == pytest.approx(2.0, rel=1e-12)  # the 1 × 2 face
    assert rigid.mesh.repair(mesh).closed
    mp, _ = rigid.mesh.mass_properties(mesh, density=1.0)
    assert mp.mass == pytest.approx(6.0, rel=1e-12)
    np.testing.assert_allclose(np.diag(mp.inertia_com), [6.5, 5.0, 2.5], rtol=1e-12)


def test_unrepaired_flipped_triangle_is_refused_with_the_remedy():
    # 0.2 × 0.3 × 0.1 m of aluminium is 16.2 kg; with one triangle flipped and no repair the
    # sum gave 13.5 kg without a word. Now refused, naming rigid.mesh.repair.
    v, f = box(0.2, 0.3, 0.1)
    f = f.copy()
    f[4] = f[4][[0, 2, 1]]
    mesh = rigid.mesh.TriangleMesh(v, f)
    with pytest.raises(rigid.Error, match=r"not consistently oriented \(3 edges.*run "
                                          r"rigid\.mesh\.repair\(mesh\) first"):
        rigid.mesh.mass_properties(mesh, density=2700)
    rigid.mesh.repair(mesh)
    mp, warnings = rigid.mesh.mass_properties(mesh, density=2700)
    assert mp.mass == pytest.approx(16.2, rel=1e-12)  # closed form, a few dozen terms of round-off
    assert warnings == []


def test_fill_holes_before_repair_is_an_error_not_an_assertion():
    # a box without one triangle plus a triangle that repeats a vertex (repair would drop it)
    v, f = box(1, 1, 1)
    mesh = rigid.mesh.TriangleMesh(v, np.vstack([f[1:], [[1, 1, 2]]]))
    with pytest.raises(rigid.Error, match=r"repeats a vertex: holes can be filled only in a "
                                          r"repaired mesh; run rigid\.mesh\.repair\(mesh\) first"):
        rigid.mesh.fill_holes(mesh)


@pytest.mark.parametrize("bad", ["nan", "-1", "inf"])
def test_weld_tolerance_must_be_a_fraction(bad):
    # the same refusal as `rigid mesh check --weld-tolerance` (tests/cli/test_cli_mesh.py)
    mesh = rigid.mesh.TriangleMesh(*box(1, 1, 1))
    with pytest.raises(rigid.Error, match=rf"^weld tolerance {bad}: expected a "
                                          r"finite number from 0 up to \(not including\) 1"):
        rigid.mesh.repair(mesh, weld_tolerance=float(bad))
    assert len(mesh.vertices) == 8  # unchanged


def test_repair_true_measures_a_repaired_copy_and_says_so():
    # the same box with one flipped triangle: refused as it is; repair=True gives the exact
    # 0.2 × 0.3 × 0.1 m aluminium box, says what it flipped, and leaves the mesh as it was
    a, b, c, rho = 0.2, 0.3, 0.1, 2700.0
    v, f = box(a, b, c)
    f = f.copy()
    f[4] = f[4][[0, 2, 1]]
    mesh = rigid.mesh.TriangleMesh(v, f)
    with pytest.raises(rigid.Error, match=r"not consistently oriented"):
        rigid.mesh.mass_properties(mesh, density=rho)
    mp, warnings = rigid.mesh.mass_properties(mesh, density=rho, repair=True)
    m = rho * a * b * c
    assert mp.mass == pytest.approx(m, rel=1e-12)  # 16.2 kg, a few dozen terms of round-off
    np.testing.assert_allclose(mp.com, [a / 2, b / 2, c / 2], rtol=1e-12)
    np.testing.assert_allclose(mp.inertia_com, m / 12 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b]),
                               rtol=0, atol=1e-12 * m)
    assert warnings == ["flipped 1 triangle whose winding disagreed with their neighbours"]
    np.testing.assert_array_equal(mesh.triangles, f)  # the caller's mesh is unchanged
    # an open mesh stays refused with repair=True: repair cannot invent the missing face
    with pytest.raises(rigid.Error, match=r"shell=True.*fill_holes=True"):
        rigid.mesh.mass_properties(rigid.mesh.TriangleMesh(v, f[:-1]), density=rho, repair=True)


def test_read_takes_a_pathlib_path_and_names_the_file(tmp_path):
    v, f = box(1, 2, 3)
    off = tmp_path / "box.off"
    off.write_text("OFF\n8 12 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in v)
                   + "".join(f"3 {i} {j} {k}\n" for i, j, k in f))
    by_path = rigid.mesh.read(off)
    by_str = rigid.mesh.read(str(off))
    np.testing.assert_array_equal(by_path.vertices, v)
    np.testing.assert_array_equal(by_str.triangles, f)
    with pytest.raises(rigid.Error, match="missing.off"):
        rigid.mesh.read(tmp_path / "missing.off")
    with pytest.raises(TypeError, match=r"rigid\.mesh\.read\(\): argument 'path' must be a path \(str or "
                                        r"pathlib\.Path\); got int"):
        rigid.mesh.read(3)


def test_edge_counts_moments_and_stl_round_trip(tmp_path):
    a, b, c = 1.0, 2.0, 3.0
    v, f = box(a, b, c)
    mesh = rigid.mesh.TriangleMesh(v, f)
    e = rigid.mesh.count_edges(mesh)
    assert (e.boundary, e.non_manifold, e.misoriented) == (0, 0, 0)
    flipped = f.copy()
    flipped[4] = flipped[4][[0, 2, 1]]
    assert rigid.mesh.count_edges(rigid.mesh.TriangleMesh(v, flipped)).misoriented == 3  # its three edges
    # moments of the box about its corner (closed forms): V = abc, ∫x = a²bc/2, ∫x² = a³bc/3, ∫xy = a²b²c/4
    vm = rigid.mesh.volume_moments(mesh, about=[0, 0, 0])
    assert vm["measure"] == pytest.approx(a * b * c, rel=1e-14)
    np.testing.assert_allclose(vm["first"], [a * a * b * c / 2, a * b * b * c / 2, a * b * c * c / 2], rtol=1e-14)
    assert vm["second"][0, 0] == pytest.approx(a**3 * b * c / 3, rel=1e-14)
    assert vm["second"][0, 1] == pytest.approx(a * a * b * b * c / 4, rel=1e-14)
    sm = rigid.mesh.surface_moments(mesh)
    assert sm["measure"] == pytest.approx(2 * (a * b + b * c + a * c), rel=1e-14)
    np.testing.assert_array_equal(sm["about"], [a / 2, b / 2, c / 2])  # the bounding-box centre
    # in-place transforms: scale, translate, reverse (the volume's sign follows the winding)
    mesh.scale(0.5)
    mesh.translate([10.0, 0, 0])
    lo, hi = mesh.bounding_box
    np.testing.assert_array_equal(lo, [10.0, 0, 0])
    np.testing.assert_array_equal(hi, [10.5, 1.0, 1.5])
    mesh.reverse_winding()
    assert rigid.mesh.volume_moments(mesh)["measure"] == pytest.approx(-a * b * c / 8, rel=1e-14)
    # STL holds float32: coordinates that are exact in float32 come back exactly
    stl = tmp_path / "box.stl"
    rigid.mesh.write_stl(mesh, stl)
    back = rigid.mesh.read(stl)
    assert len(back) == 12
    np.testing.assert_array_equal(np.sort(back.vertices, axis=0), np.sort(mesh.vertices, axis=0))
