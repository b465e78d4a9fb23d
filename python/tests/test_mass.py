"""rigid.MassProperties and rigid.mass: closed forms, identities, errors, XML round trip."""
import math

import numpy as np
import pytest

import rigid

EPS = np.finfo(float).eps


def test_cone_closed_form():
    m, r, h = 2.5, 0.3, 1.2
    cone = rigid.mass.solid_cone_with_mass(m, r, h)
    assert cone.mass == m
    np.testing.assert_allclose(cone.com, [0, 0, h / 4], rtol=0, atol=16 * EPS)
    ixx = m * (3 * r * r / 20 + 3 * h * h / 80)
    np.testing.assert_allclose(np.diag(cone.inertia_com), [ixx, ixx, 0.3 * m * r * r], rtol=1e-12)


def test_parallel_axis_and_axis_moment():
    s = rigid.mass.solid_sphere_with_mass(2.0, 0.5)
    I_q = s.inertia_about(np.array([0.0, 0.0, 1.0]))
    # 2/5 m r² + m d² about x and y, unchanged about z
    np.testing.assert_allclose(np.diag(I_q), [0.2 + 2, 0.2 + 2, 0.2], rtol=1e-14)
    assert s.inertia_about_axis([1.0, 0, 0], [0, 0, 1.0]) == pytest.approx(0.2 + 2, rel=1e-14)


def test_tube_is_cylinder_minus_cylinder():
    tube = rigid.mass.thick_tube_with_density(800, 0.02, 0.06, 0.3)
    diff = rigid.subtract(rigid.mass.solid_cylinder_with_density(800, 0.06, 0.3),
                          rigid.mass.solid_cylinder_with_density(800, 0.02, 0.3))
    assert diff.mass == pytest.approx(tube.mass, rel=1e-13)
    np.testing.assert_allclose(diff.inertia_com, tube.inertia_com, rtol=1e-12, atol=1e-18)


def test_principal_axes_right_handed_and_rotation_invariant():
    box = rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7)
    c, s = math.cos(0.4), math.sin(0.4)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    moments, R_BP = box.rotated(R).principal_axes()
    np.testing.assert_allclose(moments, np.sort(np.diag(box.inertia_com)), rtol=1e-13)
    assert np.linalg.det(R_BP) == pytest.approx(1.0, abs=1e-14)


def test_combine_point_masses_and_numpy_shapes():
    pts = np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]])  # one point per row
    mp = rigid.mass.point_masses([1.0, 1.0], pts)
    np.testing.assert_allclose(mp.inertia_com, np.diag([0.0, 2.0, 2.0]), atol=8 * EPS)
    both = rigid.combine([mp, rigid.mass.point_mass(2.0, [0.0, 0.0, 1.0])])
    assert both.mass == 4.0
    assert both.inertia_com.shape == (3, 3)


def test_second_moments_and_laminae():
    ball = rigid.mass.n_ball_with_mass(1.0, 1.0, 4)
    np.testing.assert_allclose(ball.J_com, np.eye(4) / 6, rtol=1e-15)
    Omega = np.zeros((4, 4))
    Omega[0, 1], Omega[1, 0] = 1.0, -1.0
    np.testing.assert_allclose(ball.apply(Omega), Omega / 3, rtol=1e-15)
    sq = rigid.mass.polygon_lamina_with_mass(1.0, np.array([[0, 0], [1, 0], [1, 1], [0, 1.0]]))
    assert sq.moment_com == pytest.approx(1 / 6, rel=1e-14)  # m (a² + b²)/12


def test_density_cubature_linear_density():
    # ρ = 1 + x on the unit cube centred at 0: m = 1, x_C = 1/12
    res = rigid.mass.integrate_density_over_box(lambda p: 1.0 + p[0], 1.0, 1.0, 1.0)
    assert res.converged
    assert res.mass_properties.mass == pytest.approx(1.0, abs=res.mass_error + 1e-14)
    assert res.mass_properties.com[0] == pytest.approx(1 / 12, abs=res.com_error + 1e-14)


def test_xml_round_trip_with_rotated_frame():
    c, s = math.cos(0.7), math.sin(0.7)
    R = np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])
    mp = rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7).transformed(R, np.array([0.1, 0.2, 0.3]))
    for fmt in ("urdf", "mjcf", "sdf"):
        doc = rigid.mass.write_inertial_document(mp, fmt, name="link", principal=True)
        (entry,) = rigid.mass.read_inertials(text=doc)
        assert entry["name"] == "link" and entry["problem"] is None
        np.testing.assert_allclose(entry["inertia_com"], mp.inertia_com, rtol=0, atol=1e-15)


def test_errors_are_rigid_errors():
    with pytest.raises(rigid.Error, match="radius must be positive and finite, got -1 m"):
        rigid.mass.solid_sphere_with_mass(1.0, -1.0)
    with pytest.raises(ValueError, match=r"violate I₁ \+ I₂ ≥ I₃ by 1 kg·m²"):
        rigid.MassProperties(1.0, np.zeros(3), np.diag([1.0, 2.0, 4.0]))
    assert "violate" in rigid.MassProperties.check(1.0, np.zeros(3), np.diag([1.0, 2.0, 4.0]))
    with pytest.raises(rigid.Error, match="format must be 'urdf', 'mjcf' or 'sdf'"):
        rigid.mass.write_inertial_document(rigid.mass.point_mass(1.0, np.zeros(3)), "obj")


def test_catalogue_factories_take_mass_first_and_sizes_by_name():
    a = rigid.mass.solid_cylinder(mass=2.0, radius=0.1, height=0.5)
    b = rigid.mass.cylinder(mass=2.0, radius=0.1, height=0.5)
    c = rigid.mass.solid_cylinder_with_mass(2.0, 0.1, 0.5)
    np.testing.assert_array_equal(a.inertia_com, b.inertia_com)
    np.testing.assert_array_equal(a.inertia_com, c.inertia_com)
    # I_zz = m r²/2, I_xx = m (3r² + h²)/12 (closed form)
    assert a.inertia_com[2, 2] == pytest.approx(2.0 * 0.01 / 2, rel=1e-15)
    assert a.inertia_com[0, 0] == pytest.approx(2.0 * (0.03 + 0.25) / 12, rel=1e-15)
    names = {e["name"] for e in rigid.mass.primitives()}
    assert {"solid_cylinder", "thin_rod", "solid_tetrahedron"} <= names
    with pytest.raises(rigid.Error, match="give exactly one of mass= .* and density="):
        rigid.mass.rod(length=1.0)


def test_read_inertials_takes_a_path_or_text_never_a_file_name_as_xml(tmp_path):
    mp = rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7)
    doc = rigid.mass.write_inertial_document(mp, "urdf", name="link")
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(doc)
    for entries in (rigid.mass.read_inertials(urdf), rigid.mass.read_inertials(str(urdf)),
                    rigid.mass.read_inertials(text=doc)):
        (entry,) = entries
        assert entry["name"] == "link" and entry["mass"] == 2.0
        np.testing.assert_array_equal(entry["inertia_com"], mp.inertia_com)
    # a file name that does not exist is reported as a missing file, never parsed as XML
    with pytest.raises(rigid.Error, match=r"^rigid\.mass\.read_inertials\(\): 'nope\.urdf' is not a file \(no such file\)"):
        rigid.mass.read_inertials("nope.urdf")
    with pytest.raises(rigid.Error, match=r"looks like XML text: pass a document as read_inertials\(text=\.\.\.\)"):
        rigid.mass.read_inertials(doc)
    with pytest.raises(rigid.Error, match="give exactly one of path"):
        rigid.mass.read_inertials(urdf, text=doc)
    # errors inside a file name the file and the line; text names `source`
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot>\n<link>\n</robot>\n")
    with pytest.raises(rigid.Error, match=r"bad\.urdf:\d+"):
        rigid.mass.read_inertials(bad)
    with pytest.raises(rigid.Error, match=r"mine\.urdf:\d+"):
        rigid.mass.read_inertials(text="<robot>\n<link>\n</robot>\n", source="mine.urdf")


def test_factories_take_the_mass_first():
    # n-ball: J = m r²/(n + 2) · 1, here m = 2 kg, r = 0.5 m, n = 4 (closed form)
    ball = rigid.mass.n_ball_with_mass(2.0, 0.5, 4)
    np.testing.assert_allclose(ball.J_com, np.eye(4) * 2.0 * 0.25 / 6, rtol=4 * EPS)
    assert rigid.mass.n_ball_with_mass(m=2.0, r=0.5, n=4).mass == 2.0
    # ρ π^{n/2} rⁿ / Γ(n/2 + 1) for n = 2: a disk of mass ρ π r²
    assert rigid.mass.n_ball_with_density(3.0, 0.5, 2).mass == pytest.approx(3.0 * math.pi * 0.25, rel=4 * EPS)
    for name in dir(rigid.mass):
        if name.endswith("_with_mass") or name.endswith("_with_density"):
            doc = getattr(rigid.mass, name).__doc__
            first = doc.split("(", 2)[1].split(":")[0].split(",")[0].strip()
            assert first in ("m", "rho", "sigma", "lambda"), (name, doc.splitlines()[0])


def test_point_masses_take_one_point_per_row():
    pts = np.array([[1.0, 0, 0], [0, 2.0, 0], [0, 0, 3.0], [-1.0, -2.0, -3.0]])
    m = np.array([1.0, 2.0, 3.0, 4.0])
    mp = rigid.mass.point_masses(m, pts)
    # the definition: COM Σ m p / Σ m, inertia Σ m (|r|² 1 − r rᵀ) about it
    com = (m[:, None] * pts).sum(axis=0) / m.sum()
    r = pts - com
    I_C = sum(mi * (ri @ ri * np.eye(3) - np.outer(ri, ri)) for mi, ri in zip(m, r))
    np.testing.assert_allclose(mp.com, com, rtol=0, atol=8 * EPS)
    np.testing.assert_allclose(mp.inertia_com, I_C, rtol=0, atol=64 * EPS * np.trace(I_C))


def test_laminae_point_sets_and_polygon_moments():
    # a unit square lamina of 1 kg: moment about the COM m (a² + b²)/12 = 1/6 (closed form)
    sq = rigid.mass.polygon_lamina_with_mass(1.0, [[0, 0], [1, 0], [1, 1], [0, 1]])
    moved = sq.shifted([2.0, 0.0])
    np.testing.assert_array_equal(moved.com, [2.5, 0.5])
    assert moved.moment_com == sq.moment_com
    turned = sq.rotated(math.pi / 2)
    np.testing.assert_allclose(turned.com, [-0.5, 0.5], rtol=0, atol=4 * EPS)
    two = rigid.MassProperties2.combine(sq, moved)
    # parallel axis: 2 · 1/6 + 2 · 1 · 1² (each COM 1 m from the common one)
    assert two.moment_com == pytest.approx(2 / 6 + 2.0, rel=8 * EPS)
    area, centroid, J = rigid.mass.polygon_moments([[0, 0], [2, 0], [2, 1], [0, 1]])
    assert area == 2.0
    np.testing.assert_array_equal(centroid, [1.0, 0.5])
    np.testing.assert_allclose(J, np.diag([2 * 4 / 12, 2 * 1 / 12]), rtol=8 * EPS)  # ∫x² = A a²/12
    # 4-D point set: J_C = Σ m (p − c)(p − c)ᵀ, from the definition
    pts = np.array([[1.0, 0, 0, 0], [-1.0, 0, 0, 2.0]])
    J4 = rigid.mass.point_set_second_moments([1.0, 1.0], pts)
    c = pts.mean(axis=0)
    np.testing.assert_allclose(J4.J_com, sum(np.outer(p - c, p - c) for p in pts), rtol=0, atol=8 * EPS)
    assert J4.dimension == 4
    assert rigid.mass.check_rotational_moments([1.0, 2.0, 2.5]) is None
    assert "violate" in rigid.mass.check_rotational_moments([1.0, 2.0, 4.0])
    assert rigid.mass.check_rotational_moments([0.0, 1.0, 1.0]) is not None  # a thin rod does not turn


def test_pseudo_inertia_and_log_cholesky_refuse_a_body_that_overflows():
    # 1e308 kg with its COM 10 m from the origin: m |c|² = 1e310 overflows a double; refused
    # (rather than returned with inf and nan entries)
    heavy = rigid.MassProperties(1e308, [10.0, 0.0, 0.0], np.diag([1e308 / 6] * 3))
    with pytest.raises(rigid.Error, match=r"the pseudo-inertia of the body \(mass 1e\+308 kg, center "
                       r"of mass \[10, 0, 0\] m from the origin\) overflows a double"):
        rigid.mass.pseudo_inertia(heavy)
    with pytest.raises(rigid.Error, match="overflows a double"):
        rigid.mass.log_cholesky(heavy)
    with pytest.raises(rigid.Error, match=r"the inertia about the point \[-9, 0, 0\] m overflows"):
        heavy.inertia_about([-9.0, 0.0, 0.0])
