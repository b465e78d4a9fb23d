"""`rigid inertia PRIMITIVE`: the hoop, placed primitives (--axis/--origin/--rpy, --about with
every format), pseudo-inertia and log-Cholesky output, and --tolerance; each compared with a
closed form and with the Python module (the same input gives the same numbers)."""
import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

rigid = pytest.importorskip("rigid")

# closed forms are a few flops: 1e-12 relative is the project's bar for them
REL = 1e-12


def test_hoop_acceptance_numbers(run):
    j = json.loads(run("inertia", "hoop", "--radius", 0.5, "--mass", 2, "--format", "json",
                       check=True).stdout)
    # I = (m r²/2, m r²/2, m r²) with m = 2, r = 0.5
    assert np.diag(j["inertia"]) == pytest.approx([0.25, 0.25, 0.5], rel=REL)
    # independent: the line integral over the circle by an N-point rule, exact for the
    # trigonometric polynomials of degree 2 here (N > 2), so equal to round-off
    n = 64
    th = 2 * np.pi * np.arange(n) / n
    p = np.stack([0.5 * np.cos(th), 0.5 * np.sin(th), 0 * th], axis=1)
    dm = 2.0 / n
    I = dm * sum(p_i @ p_i * np.eye(3) - np.outer(p_i, p_i) for p_i in p)
    assert np.array(j["inertia"]) == pytest.approx(I, rel=1e-14, abs=1e-15)
    # every alias and the Python factory say the same
    for name in ("ring", "thin-ring", "thin_hoop"):
        k = json.loads(run("inertia", name, "--radius", 0.5, "--mass", 2, "--format", "json",
                           check=True).stdout)
        assert k["inertia"] == j["inertia"]
    py = rigid.mass.hoop(mass=2.0, radius=0.5)
    assert py.inertia_com.tolist() == j["inertia"]
    assert rigid.mass.thin_ring_with_density(1.0, 0.5).mass == pytest.approx(math.pi, rel=REL)


CYL = ("inertia", "cylinder", "--radius", 0.05, "--height", 0.4, "--mass", 2)


def test_cylinder_along_x_at_an_offset_is_the_parallel_axis_closed_form(run):
    m, r, h, d = 2.0, 0.05, 0.4, 0.1
    j = json.loads(run(*CYL, "--axis", "x", "--origin", "0.1,0,0", "--about", "origin",
                       "--format", "json", check=True).stdout)
    axial, transverse = m * r * r / 2, m * (3 * r * r + h * h) / 12
    expected = np.diag([axial, transverse + m * d * d, transverse + m * d * d])
    assert j["com"] == pytest.approx([d, 0, 0], rel=REL)
    assert np.array(j["inertia"]) == pytest.approx(expected, rel=REL, abs=1e-16)
    # Python: the same factory with axis=, origin= gives the same doubles
    py = rigid.mass.cylinder(mass=m, radius=r, height=h, axis="x", origin=(d, 0, 0))
    assert py.inertia_about(np.zeros(3)).tolist() == j["inertia"]
    assert py.com.tolist() == j["com"]


@pytest.mark.parametrize("fmt", ["urdf", "sdf", "mjcf"])
def test_rpy_round_trip_through_the_robot_formats(run, tmp_path, fmt):
    rpy = (0.1, 0.2, 0.3)
    args = (*CYL, "--axis", "z", "--rpy", "0.1,0.2,0.3", "--origin", "0.1,0,0.05")
    out = tmp_path / f"placed.{fmt}"
    run(*args, "--frame", "principal", "--format", fmt, "-o", out, check=True)
    text = out.read_text()
    if fmt == "urdf":
        origin = ET.fromstring(text).find("link/inertial/origin")
        # R → quaternion → rpy: a few ε
        assert [float(v) for v in origin.get("rpy").split()] == pytest.approx(rpy, abs=1e-15)
    # read back: `rigid inertia check` accepts it and read_inertials gives the placed body
    assert "0 invalid" in run("inertia", "check", out, check=True).stdout
    (entry,) = rigid.mass.read_inertials(text=text)
    placed = rigid.mass.cylinder(mass=2.0, radius=0.05, height=0.4, rpy=rpy, origin=(0.1, 0, 0.05))
    assert entry["com"] == pytest.approx(placed.com, rel=REL)
    # the principal frame goes through rpy/quaternion and back: a few hundred ε of tr I
    assert entry["inertia_com"] == pytest.approx(placed.inertia_com, abs=1e-14)
    # independent: R = Rz(y) Ry(p) Rx(r) by hand, the tensor diag(t, t, a) rotated
    cr, sr, cp, sp, cy, sy = (f(a) for a in rpy for f in (math.cos, math.sin))
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    Ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    R = Rz @ Ry @ Rx
    t, a = 2.0 * (3 * 0.05**2 + 0.4**2) / 12, 2.0 * 0.05**2 / 2
    assert entry["inertia_com"] == pytest.approx(R @ np.diag([t, t, a]) @ R.T, abs=1e-14)


def test_about_a_point_in_the_robot_formats_moves_the_link_origin(run):
    # URDF states the inertia about the COM and the COM from the link origin: about p the
    # link origin is at p, so the inertia about the file's link origin is the tensor about p
    p = np.array([0.2, -0.1, 0.3])
    j = json.loads(run(*CYL, "--axis", "y", "--about", "0.2,-0.1,0.3", "--format", "json",
                       check=True).stdout)
    for fmt in ("urdf", "sdf", "mjcf"):
        text = run(*CYL, "--axis", "y", "--about", "0.2,-0.1,0.3", "--format", fmt, check=True).stdout
        (entry,) = rigid.mass.read_inertials(text=text)
        c = np.array(entry["com"])
        assert c == pytest.approx(-p, rel=REL)
        # parallel axis from the file's numbers to its link origin
        I_link = np.array(entry["inertia_com"]) + 2.0 * (c @ c * np.eye(3) - np.outer(c, c))
        assert I_link == pytest.approx(np.array(j["inertia"]), rel=REL, abs=1e-16)
    # principal axes about a point are not what these formats state: refused, with the reason
    proc = run(*CYL, "--about", "0.2,-0.1,0.3", "--frame", "principal", "--format", "urdf", check=False)
    assert "principal axes of the inertia about the center of mass" in proc.stderr
    assert proc.stdout == ""


@pytest.mark.parametrize("args, message", [
    (("--axis", "0,0,0"), "--axis must be a non-zero direction, got '0,0,0'"),
    (("--axis", "w"), "--axis must be x, y, z, -x, -y, -z or a direction 'vx,vy,vz', got 'w'"),
    (("--rpy", "1,2"), "--rpy must be roll,pitch,yaw in radians 'r,p,y', got '1,2'"),
    (("--origin", "1,2,inf"), "--origin must be a point 'x,y,z' in metres, got '1,2,inf'"),
])
def test_bad_placements_are_refused(run, args, message):
    proc = run(*CYL, *args, check=False)
    assert proc.returncode == 2  # a value none of the option's forms: a usage error
    assert message in proc.stderr
    # the same input through Python: the same refusal
    with pytest.raises(rigid.Error):
        bad = {"--axis": "axis", "--rpy": "rpy", "--origin": "origin"}[args[0]]
        value = args[1]
        if bad == "axis" and "," not in value:
            rigid.mass.cylinder(mass=2, radius=0.05, height=0.4, axis=value)
        else:
            vec = [float(v) for v in value.split(",")]
            rigid.mass.cylinder(mass=2, radius=0.05, height=0.4, **{bad: vec})


BOX = ("inertia", "box", "--lx", 0.2, "--ly", 0.4, "--lz", 0.6, "--mass", 3, "--origin", "0.1,-0.2,0.3")


def test_pseudo_inertia_and_log_cholesky_match_the_closed_form_and_python(run):
    m, l, c = 3.0, np.array([0.2, 0.4, 0.6]), np.array([0.1, -0.2, 0.3])
    J = np.array(json.loads(run(*BOX, "--format", "pseudo", check=True).stdout)["pseudo_inertia"])
    # [Wensing2017]: Σ = ∫ r rᵀ dm = m diag(l²)/12 + m c cᵀ, h = m c; a few ε of round-off
    expected = np.zeros((4, 4))
    expected[:3, :3] = m * np.diag(l**2) / 12 + m * np.outer(c, c)
    expected[:3, 3] = expected[3, :3] = m * c
    expected[3, 3] = m
    assert J == pytest.approx(expected, abs=1e-15)
    body = rigid.mass.box(mass=m, lx=0.2, ly=0.4, lz=0.6, origin=c)
    assert rigid.mass.pseudo_inertia(body).tolist() == J.tolist()
    theta = json.loads(run(*BOX, "--format", "log-cholesky", check=True).stdout)["theta"]
    assert rigid.mass.log_cholesky(body).tolist() == theta
    # m = e^{2α}, and J = U Uᵀ rebuilt here from θ by [Rucker2022]'s U
    a, d1, d2, d3, s12, s23, s13, t1, t2, t3 = theta
    U = math.exp(a) * np.array([[math.exp(d1), s12, s13, t1], [0, math.exp(d2), s23, t2],
                                [0, 0, math.exp(d3), t3], [0, 0, 0, 1]])
    assert U @ U.T == pytest.approx(expected, abs=1e-14)
    back = rigid.mass.from_log_cholesky(np.array(theta))
    assert back.com == pytest.approx(c, abs=1e-15)
    # about a point: J about it (the link origin moved there)
    Jp = np.array(json.loads(run(*BOX, "--format", "pseudo", "--about", "0.1,-0.2,0.3",
                                 check=True).stdout)["pseudo_inertia"])
    assert Jp[:3, 3] == pytest.approx([0, 0, 0], abs=1e-15)


def test_singular_and_invalid_parameters_are_refused_on_every_surface(run):
    proc = run("inertia", "rod", "--length", 1, "--mass", 1, "--format", "log-cholesky", check=False)
    assert proc.returncode == 1
    assert "log-Cholesky parameters need a positive definite pseudo-inertia" in proc.stderr
    with pytest.raises(rigid.Error, match="positive definite pseudo-inertia"):
        rigid.mass.log_cholesky(rigid.mass.rod(mass=1, length=1))
    J = rigid.mass.pseudo_inertia(rigid.mass.box(mass=1, lx=1, ly=1, lz=1))
    J[2, 2] = -0.1
    with pytest.raises(rigid.Error, match="violate the triangle inequality"):
        rigid.mass.from_pseudo_inertia(J)
    proc = run(*BOX, "--format", "pseudo", "--frame", "principal", check=False)
    assert "--frame principal cannot be used with --format pseudo" in proc.stderr


def test_tolerance_agrees_with_monte_carlo_and_python(run):
    args = ("inertia", "cylinder", "--radius", 0.05, "--height", 0.4, "--density", 2700,
            "--rpy", "0.3,0.2,0.1", "--origin", "0.1,0,0", "--about", "origin")
    j = json.loads(run(*args, "--tolerance", "dims=±0.5mm,density=±2%", "--format", "json",
                       check=True).stdout)
    assert j["uncertain_inputs"] == ["radius", "height", "density"]
    py = rigid.mass.primitive_uncertainty("cylinder", "dims=±0.5mm,density=±2%", about=(0, 0, 0),
                                          density=2700, radius=0.05, height=0.4, rpy=(0.3, 0.2, 0.1),
                                          origin=(0.1, 0, 0))
    assert py["sigma"]["inertia"].tolist() == j["sigma"]["inertia"]
    assert py["sigma"]["mass"] == j["sigma"]["mass"]
    # Monte Carlo through the Python factories (not the propagation code): ± is 1σ of a normal
    n = 10_000
    rng = np.random.default_rng(18)
    r = 0.05 + 0.5e-3 * rng.standard_normal(n)
    h = 0.4 + 0.5e-3 * rng.standard_normal(n)
    rho = 2700 * (1 + 0.02 * rng.standard_normal(n))
    masses, tensors = [], []
    for rk, hk, rhok in zip(r, h, rho):
        b = rigid.mass.cylinder(density=rhok, radius=rk, height=hk, rpy=(0.3, 0.2, 0.1), origin=(0.1, 0, 0))
        masses.append(b.mass)
        tensors.append(b.inertia_about(np.zeros(3)))
    # an σ estimated from n normal samples has relative error 1/√(2(n − 1)) ≈ 0.71%: 5 of those
    # bound it (3.5%); first-order vs true σ differ by O((σ/x)²) ~ 1e-4 here
    bound = 5 / math.sqrt(2 * (n - 1))
    assert np.std(masses, ddof=1) == pytest.approx(j["sigma"]["mass"], rel=bound)
    sd = np.std(np.array(tensors), axis=0, ddof=1)
    assert sd == pytest.approx(np.array(j["sigma"]["inertia"]), rel=bound)
    # text output: value ± σ, and the refusals
    text = run(*args, "--tolerance", "dims=±0.5mm,density=±2%", check=True).stdout
    assert "± is 1 standard deviation" in text and f"{j['mass']:.10g} ± " in text
    proc = run(*args, "--tolerance", "dims=±0.5mm", "--format", "urdf", check=False)
    assert "urdf has no place for a standard deviation" in proc.stderr
    proc = run(*args, "--tolerance", "mass=±1%", check=False)
    assert "the solid_cylinder primitive is given by its density, so give density=±" in proc.stderr
    with pytest.raises(rigid.Error, match="so give density=±"):
        rigid.mass.primitive_uncertainty("cylinder", "mass=±1%", density=2700, radius=0.05, height=0.4)


def test_mesh_vertex_noise_agrees_with_monte_carlo(run, tmp_path):
    # a box mesh [0, a]×[0, b]×[0, c] as OFF, 8 shared vertices
    a, b, c = 0.3, 0.2, 0.1
    V = np.array([((i & 1) * a, ((i >> 1) & 1) * b, ((i >> 2) & 1) * c) for i in range(8)])
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    T = np.array([(q[0], q[1], q[2]) for q in quads] + [(q[0], q[2], q[3]) for q in quads])
    path = tmp_path / "box.off"
    path.write_text("OFF\n8 12 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in V)
                    + "".join(f"3 {i} {j} {k}\n" for i, j, k in T))
    j = json.loads(run("inertia", path, "--density", 2700, "--tolerance", "vertices=±0.3mm,density=±2%",
                       "--format", "json", check=True).stdout)
    assert j["uncertain_inputs"] == ["vertices", "density"]
    assert j["mass"] == pytest.approx(2700 * a * b * c, rel=1e-12)
    # Monte Carlo, independent of the library: the divergence theorem in numpy on noisy vertices
    n = 10_000
    rng = np.random.default_rng(7)
    P = V[None, :, :] + 0.3e-3 * rng.standard_normal((n, 8, 3))
    rho = 2700 * (1 + 0.02 * rng.standard_normal(n))
    p0, p1, p2 = P[:, T[:, 0]], P[:, T[:, 1]], P[:, T[:, 2]]
    det = np.einsum("ntk,ntk->nt", p0, np.cross(p1, p2))
    vol = det.sum(axis=1) / 6
    com_x = (det * (p0 + p1 + p2)[:, :, 0]).sum(axis=1) / 24 / vol
    # σ from n samples: relative error 1/√(2(n − 1)); 5 of those bound it (3.5%)
    bound = 5 / math.sqrt(2 * (n - 1))
    assert np.std(rho * vol, ddof=1) == pytest.approx(j["sigma"]["mass"], rel=bound)
    assert np.std(com_x, ddof=1) == pytest.approx(j["sigma"]["com"][0], rel=bound)
    proc = run("inertia", path, "--density", 2700, "--tolerance", "dims=±1mm", check=False)
    assert "unknown tolerance 'dims' for a mesh; it takes vertices=±LENGTH and density=±…" in proc.stderr


def test_mesh_vertex_noise_is_the_same_in_python(run, tmp_path):
    a, b, c = 0.3, 0.2, 0.1
    V = np.array([((i & 1) * a, ((i >> 1) & 1) * b, ((i >> 2) & 1) * c) for i in range(8)])
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    T = np.array([(q[0], q[1], q[2]) for q in quads] + [(q[0], q[2], q[3]) for q in quads])
    path = tmp_path / "box.off"
    path.write_text("OFF\n8 12 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in V)
                    + "".join(f"3 {i} {j} {k}\n" for i, j, k in T))
    j = json.loads(run("inertia", path, "--mass", 2, "--tolerance", "vertices=±0.1mm", "--about", "origin",
                       "--format", "json", check=True).stdout)
    mesh = rigid.mesh.TriangleMesh(V, T)
    py = rigid.mesh.vertex_noise_uncertainty(mesh, 1e-4, mass=2.0, about=(0, 0, 0))
    # the same mesh and the same arithmetic: equal to round-off (the file's text repeats the doubles)
    assert py["sigma"]["inertia"] == pytest.approx(np.array(j["sigma"]["inertia"]), rel=1e-12, abs=1e-18)
    assert py["sigma"]["mass"] == j["sigma"]["mass"] == 0.0
