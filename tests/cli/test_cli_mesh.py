"""`rigid mesh check FILE` and `rigid inertia FILE` for mesh files."""
import json
import struct

import pytest

QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def box_triangles(a, b, c):
    v = [((i & 1) * a, ((i >> 1) & 1) * b, ((i >> 2) & 1) * c) for i in range(8)]
    return [(v[q[0]], v[q[1]], v[q[2]]) for q in QUADS] + [(v[q[0]], v[q[2]], v[q[3]]) for q in QUADS]


def write_binary_stl(path, triangles, header=b"rigid test"):
    data = header.ljust(80, b" ") + struct.pack("<I", len(triangles))
    for t in triangles:
        data += struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0)
    path.write_bytes(data)
    return path


def test_check_closed_box(run, tmp_path):
    p = write_binary_stl(tmp_path / "box.stl", box_triangles(1, 2, 3), header=b"solid box")
    out = run("mesh", "check", p, check=True).stdout
    # the reader shares the float32-identical copies of the 8 corners (36 in the file)
    assert "vertices: 8 read, 8 after welding" in out
    assert "volume: 6 m³" in out
    assert "mass properties: trustworthy as a solid" in out


def test_check_open_mesh_fails(run, tmp_path):
    p = write_binary_stl(tmp_path / "open.stl", box_triangles(1, 1, 1)[:-1])
    proc = run("mesh", "check", p, check=False)
    assert proc.returncode == 1
    assert "mass properties: NOT trustworthy as a solid" in proc.stdout
    assert "open.stl: the mesh is not closed (3 boundary edges, 0 non-manifold edges)" in proc.stderr
    assert "--shell" in proc.stderr


def test_check_bad_file(run, tmp_path):
    p = tmp_path / "bad.stl"
    p.write_bytes(b"\0" * 100)
    proc = run("mesh", "check", p, check=False)
    assert "bad.stl: byte 80: binary STL triangle count 0 needs 84 bytes but the file has 100" in proc.stderr


def test_inertia_of_a_mesh_in_millimetres(run, tmp_path):
    # 100 × 200 × 300 mm box of density 1000: m = 6 kg, I_xx = m (0.2² + 0.3²)/12 = 0.065 kg·m².
    p = write_binary_stl(tmp_path / "box_mm.stl", box_triangles(100, 200, 300))
    proc = run("inertia", p, "--density", 1000, "--units", "mm", "--format", "json", check=True)
    d = json.loads(proc.stdout)
    assert d["mass"] == pytest.approx(6.0, rel=1e-12)
    assert d["inertia"][0][0] == pytest.approx(0.065, rel=1e-12)
    # the size with its unit, and no warning
    assert proc.stderr == f"rigid: {p}: size 0.1 × 0.2 × 0.3 m (file read in mm)\n"
    # Forgetting --units mm: 10⁹ times the mass, and a warning naming the fix.
    proc = run("inertia", p, "--mass", 6, check=True)
    assert "implied density 1e-06 kg/m³" in proc.stderr and "--units mm" in proc.stderr


def test_inertia_shell_and_open_solid(run, tmp_path):
    p = write_binary_stl(tmp_path / "open.stl", box_triangles(1, 1, 1)[:-1])
    proc = run("inertia", p, "--density", 1000, check=False)
    assert "3 boundary edges" in proc.stderr and "use --shell" in proc.stderr
    proc = run("inertia", p, "--shell", "--thickness", 0.001, "--density", 1000,
               "--format", "json", check=True)
    assert json.loads(proc.stdout)["mass"] == pytest.approx(5.5, rel=1e-12)  # 5.5 m² × 1 kg/m²


def test_fill_holes_closes_a_missing_face(run, tmp_path):
    # The unit box without its face z = 0 (triangles 0 and 6): a planar square hole,
    # closed exactly by the fan around its centre, so m = 1000 kg and I_xx = m (1 + 1)/12.
    tris = box_triangles(1, 1, 1)  # the first of each quad's two triangles, then the second
    p = write_binary_stl(tmp_path / "no_bottom.stl", [t for i, t in enumerate(tris) if i not in (0, 6)])
    proc = run("mesh", "check", p, check=False)
    assert proc.returncode == 1 and "--fill-holes" in proc.stderr
    out = run("mesh", "check", p, "--fill-holes", check=True).stdout
    assert "filled 1 hole (4 triangles added, patch area 1 m²): 4 edges/1 m²" in out
    assert "after filling:" in out and "boundary edges: 0" in out
    assert "mass properties: trustworthy as a solid" in out
    proc = run("inertia", p, "--density", 1000, "--fill-holes", "--format", "json", check=True)
    d = json.loads(proc.stdout)
    assert d["mass"] == pytest.approx(1000.0, rel=1e-12)
    assert d["inertia"][0][0] == pytest.approx(1000 * 2 / 12, rel=1e-12)
    assert "filled 1 hole" in proc.stderr and "the mesh is open" not in proc.stderr
    proc = run("inertia", p, "--density", 1000, check=False)
    assert proc.returncode != 0 and "--fill-holes" in proc.stderr


def test_fill_holes_refuses_holes_touching_at_a_vertex(run, tmp_path):
    # Triangles (0,2,3) and (0,5,4) of the box removed: two holes meeting at the origin.
    tris = box_triangles(1, 1, 1)
    p = write_binary_stl(tmp_path / "touching.stl", [t for i, t in enumerate(tris) if i not in (0, 8)])
    proc = run("inertia", p, "--density", 1000, "--fill-holes", check=False)
    assert proc.returncode != 0
    assert "boundary loop through vertex" in proc.stderr and "at (0, 0, 0) m is not simple" in proc.stderr
