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


def write_ascii_stl(path, solids):
    """solids: {name: triangles}; one `solid … endsolid` block each."""
    text = ""
    for name, tris in solids.items():
        text += f"solid {name}\n"
        for t in tris:
            text += "facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {x!r} {y!r} {z!r}\n" for x, y, z in t)
            text += "endloop\nendfacet\n"
        text += f"endsolid {name}\n"
    path.write_text(text)
    return path


def moved(tris, dx):
    return [tuple((x + dx, y, z) for x, y, z in t) for t in tris]


def test_every_solid_of_an_ascii_stl_is_read(run, tmp_path):
    # two closed unit cubes in two blocks: volume 2 (only the first block was read: 1)
    cube = box_triangles(1.0, 1.0, 1.0)
    p = write_ascii_stl(tmp_path / "two.stl", {"first": cube, "second": moved(cube, 3.0)})
    out = run("mesh", "check", p, check=True).stdout
    assert "volume: 2 m³" in out and "mass properties: trustworthy as a solid" in out
    d = json.loads(run("inertia", p, "--density", 1, "--format", "json", check=True).stdout)
    assert d["mass"] == pytest.approx(2.0, rel=1e-15)


def test_obj_far_from_the_origin_keeps_its_size(run, tmp_path):
    # 0.2 × 0.3 × 0.1 m, 2700 kg/m³, 1000 km from the origin: 16.2 kg (float32 made it 20.25);
    # coordinates 1e6 + 0.2 are off by ≤ 5.8e-11 m in double: 1e-9 relative bounds the mass
    corners = [(1e6 + (i & 1) * 0.2, ((i >> 1) & 1) * 0.3, ((i >> 2) & 1) * 0.1) for i in range(8)]
    p = tmp_path / "far.obj"
    p.write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in corners)
                 + "".join(f"f {q[0] + 1} {q[1] + 1} {q[2] + 1} {q[3] + 1}\n" for q in QUADS))
    proc = run("inertia", p, "--density", 2700, "--format", "json", check=True)
    assert json.loads(proc.stdout)["mass"] == pytest.approx(16.2, rel=1e-9)
    mp, _ = rigid_module().mesh.mass_from_file(p, density=2700)
    assert mp.mass == pytest.approx(16.2, rel=1e-9)


def rigid_module():
    import rigid
    return rigid


def test_nan_vertex_is_refused_with_its_line(run, tmp_path):
    p = tmp_path / "nan.obj"
    p.write_text("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")
    proc = run("inertia", p, "--density", 1, check=False)
    assert f"{p}:2: a coordinate of vertex 2 is nan: expected a finite number" in proc.stderr


def test_a_20_mm_part_read_as_metres_is_flagged_everywhere(run, tmp_path):
    # 20 × 30 × 10 mm of aluminium read as metres: 20 × 30 × 10 m, 16 200 t
    p = write_binary_stl(tmp_path / "part.stl", box_triangles(20, 30, 10))
    proc = run("inertia", p, "--density", 2700, "--format", "json", check=True)
    assert f"rigid: {p}: size 20 × 30 × 10 m (file read in m)" in proc.stderr
    assert "the part is 20 × 30 × 10 m, more than 10 m long: if the file's numbers are " \
           "millimetres, use --units mm" in proc.stderr
    assert "the implied mass 1.62e+04 t is more than 1000 t" in proc.stderr
    out = run("mesh", "check", p, check=True).stdout
    assert "size: 20 × 30 × 10 m (file read in m)" in out
    assert "use --units mm" in out and "trustworthy as a solid" not in out
    assert "its size is implausible for the unit" in out
    # with the unit: no warning, 16.2 g
    proc = run("inertia", p, "--density", 2700, "--units", "mm", "--format", "json", check=True)
    assert "warning" not in proc.stderr
    assert json.loads(proc.stdout)["mass"] == pytest.approx(0.0162, rel=1e-12)
    # Python and a scene carry the same warnings, worded for each
    rigid = rigid_module()
    _, warnings = rigid.mesh.mass_from_file(p, density=2700)
    assert any('use units="mm"' in w for w in warnings)
    scene = tmp_path / "s.toml"
    scene.write_text(f'[[coordinates]]\nname = "x"\n[[bodies]]\nmesh = "{p.name}"\ndensity = 2700\n'
                     'position = ["x", 0, 0]\n[simulation]\nt_end = 1\n')
    assert any("use 'units = \"mm\"'" in w for w in rigid.Scene(scene).warnings)


def test_unsupported_extension_is_named(run, tmp_path):
    p = tmp_path / "part.step"
    p.write_text("ISO-10303-21;\n")
    proc = run("inertia", p, "--density", 1, check=False)
    assert proc.returncode != 0 and "unknown primitive" not in proc.stderr
    assert f"{p}: '.step' is not a supported mesh format: the supported extensions are .stl, " \
           ".obj, .ply and .off" in proc.stderr


@pytest.mark.parametrize("bad", ["nan", "-1", "inf"])
def test_weld_tolerance_is_checked(run, tmp_path, bad):
    p = write_binary_stl(tmp_path / "box.stl", box_triangles(1, 1, 1))
    proc = run("mesh", "check", p, "--weld-tolerance", bad, check=False)
    assert proc.returncode != 0
    # the library's function name stays out of what a user reads
    assert f"error: weld tolerance {bad}: expected a finite number from 0 up to (not including) 1" \
        in proc.stderr
    assert "repair_mesh" not in proc.stderr


def test_files_that_never_end_are_refused_at_once(rigid_exe, tmp_path):
    # a directory, /dev/zero, a FIFO, a PLY of 10¹² empty rows, an OBJ whose mtllib is
    # /dev/zero: each ends within 2 s (a generous bound on milliseconds) with a clear error,
    # or, for the OBJ (materials are never read), with its mass
    import os
    import subprocess
    folder = tmp_path / "folder.stl"
    folder.mkdir()
    zero = tmp_path / "zero.ply"
    zero.symlink_to("/dev/zero")
    fifo = tmp_path / "pipe.off"
    os.mkfifo(fifo)
    ply = tmp_path / "empty_element.ply"
    ply.write_text("ply\nformat ascii 1.0\nelement nothing 1000000000000\nelement vertex 3\n"
                   "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                   "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    (tmp_path / "zero.mtl").symlink_to("/dev/zero")
    obj = tmp_path / "mtl.obj"
    obj.write_text("mtllib zero.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                   "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
    expected = {folder: "is a directory: expected a mesh file",
                zero: "is not a regular file (a device, FIFO or socket)",
                fifo: "is not a regular file (a device, FIFO or socket)",
                ply: ":3: element nothing declares 1000000000000 rows but no properties"}
    for path, message in expected.items():
        proc = subprocess.run([rigid_exe, "inertia", str(path), "--density", "1"],
                              capture_output=True, text=True, timeout=2)
        assert proc.returncode == 1 and f"{path}{'' if message.startswith(':') else ': '}{message}" \
            in proc.stderr
    proc = subprocess.run([rigid_exe, "inertia", str(obj), "--density", "6", "--format", "json"],
                          capture_output=True, text=True, timeout=2)
    assert proc.returncode == 0 and json.loads(proc.stdout)["mass"] == pytest.approx(1.0, rel=1e-15)
