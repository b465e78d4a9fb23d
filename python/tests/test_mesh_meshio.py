"""rigid.mesh against meshio on mesh files this project did not write.

The files: Debian's assimp-testmodels (/usr/share/assimp/models, exporters' output, some broken
on purpose) and the CGAL demo data (libcgal-demo, data/meshes/* of data.tar.gz), STL / OBJ /
PLY / OFF, ASCII and binary; scripts/install-deps.sh installs both and python3-meshio.

Every file listed below is asserted one way or the other; none is skipped:
- READ_BY_BOTH: rigid and meshio read the same vertices and triangles — vertex count (for STL,
  which stores each triangle's corners, the number of distinct positions: meshio merges equal
  corners, rigid's ASCII reader keeps them), triangle count (meshio's quads and polygons
  count as n − 2 triangles, as rigid splits them), the area, and for closed meshes the volume
  and the centre of volume. The references are computed here with numpy from meshio's arrays
  (area Σ |(b − a) × (c − a)| / 2; divergence theorem V = Σ a · (b × c) / 6 and
  V c = Σ a·(b × c)/6 · (a + b + c)/4 over the triangles, polygons fanned from their first
  vertex), independently of rigid, which integrates with its own code after its repair
  (weld, orient outward). Tolerance: 1e-12 relative — both sum the same few thousand O(1)
  terms in different orders, round-off ≈ n ε ≈ 1e-13 relative at most.
  Open meshes: rigid refuses them as solids (asserted), and the area still compares.
- RIGID_ONLY: meshio (5.0, Debian 12) cannot read them (OFF with quads or comments, PLY with
  a uint8 list type or an edge element, OBJ with normals per corner); rigid's result is
  checked against the geometry the file states (a unit or 2 m cube, a unit tetrahedron).
- REFUSED: rigid refuses them with a message naming the file and the problem (asserted);
  meshio refuses them too, or reads no faces, or reads vertex indices out of range
  (malformed.obj), or (malformed2, box_longline, regr_3429812) reads what rigid refuses as an
  invalid face (stated per file).
"""
import os
import tarfile
import warnings

import numpy as np
import pytest
import meshio  # python3-meshio (scripts/install-deps.sh): a missing comparison fails, never skips

import rigid

ASSIMP = "/usr/share/assimp/models"
CGAL_ARCHIVE = "/usr/share/doc/libcgal-demo/data.tar.gz"
REL = 1e-12

# (file, closed)
READ_BY_BOTH = [
    ("cgal:cube.off", True),            # OFF ASCII, [-1, 1]³
    ("cgal:sphere.off", True),          # the same sphere in three formats
    ("cgal:sphere.ply", True),          # PLY ASCII
    ("cgal:sphere.stl", True),          # STL binary
    ("cgal:elephant.off", True),
    ("cgal:knot1.off", True),
    ("cgal:bones.off", True),
    ("cgal:tetrahedron.off", True),     # wound inward: rigid's repair turns it outward
    ("cgal:pig.stl", False),            # STL binary, open
    ("cgal:mushroom.off", False),
    ("cgal:blobby_3cc.off", False),
    ("PLY/cube_binary.ply", True),      # PLY binary little-endian
    ("PLY/cube_uv.ply", True),          # quads; corners repeated per face (uv seams)
    ("PLY/float-color.ply", False),
    ("OBJ/box.obj", True),              # quads
    ("OBJ/box_mat_with_spaces.obj", True),
    ("OBJ/box_without_lineending.obj", True),
    ("OBJ/testmixed.obj", True),
    ("OBJ/multiple_spaces.obj", False),
    ("OFF/Wuson.off", False),
    ("STL/Spider_ascii.stl", False),    # the same spider, ASCII and binary
    ("STL/Spider_binary.stl", False),
    ("STL/Wuson.stl", False),
    ("STL/3DSMaxExport.STL", False),    # closed but with non-manifold edges
    ("STL/sphereWithHole.stl", False),  # ASCII
    ("STL/triangle.stl", False),
    ("STL/triangle_with_two_solids.stl", False),
]

# (file, volume, COM) from the file's own geometry
RIGID_ONLY = [
    ("cgal:cube-shuffled.off", 8.0, [0, 0, 0]),  # [-1, 1]³, windings shuffled, comments
    ("cgal:cube_quad.off", 8.0, [0, 0, 0]),
    ("cgal:cube_poly.off", 8.0, [0, 0, 0]),
    ("cgal:colored_tetra.ply", 1 / 6, [0.25, 0.25, 0.25]),  # the unit corner tetrahedron
    ("OFF/Cube.off", 1.0, None),
    ("PLY/cube.ply", 1.0, None),
    ("OBJ/cube_usemtl.obj", 1.0, None),
    ("OBJ/cube_mtllib_after_g.obj", 1.0, None),
    ("OBJ/cube_with_vertexcolors.obj", 1.0, None),
    ("OBJ/cube_with_vertexcolors_uni.obj", 1.0, None),
]

# (file, rigid's message, what meshio does: "refuses", "no faces" or "reads")
REFUSED = [
    ("cgal:b9.ply", "b9.ply:10: the PLY file has no faces", "no faces"),  # a point cloud
    ("PLY/points.ply", "points.ply:13: the PLY file has no faces", "no faces"),
    ("OBJ/point_cloud.obj", "no faces: not a mesh OBJ file (no 'f' records)", "no faces"),
    ("OBJ/testpoints.obj", "no faces: not a mesh OBJ file (no 'f' records)", "no faces"),
    ("OBJ/testline.obj", "no faces: not a mesh OBJ file (no 'f' records)", "no faces"),
    ("OBJ/box_UTF16BE.obj", "no faces: not a mesh OBJ file (no 'f' records)", "refuses"),
    ("OBJ/number_formats.obj", "number_formats.obj:11: '3.1+e2' is not a number", "refuses"),
    ("OFF/invalid.off", "invalid.off:3: '0.1' is not an integer", "refuses"),
    ("invalid/OutOfMemory.off", "OutOfMemory.off:2: the header declares 353535235358 vertices", "refuses"),
    ("PLY/pond.0.ply", "pond.0.ply:3: element vertex declares 70051 rows of at least 31 bytes each, but "
     "only 2171512 bytes of data follow the header: truncated or corrupt", "refuses"),
    ("PLY/issue623.ply", "issue623.ply:14: '7.941797' is not an integer: expected a list length", "refuses"),
    ("PLY/Wuson.ply", "Wuson.ply:3: unknown header keyword 'Created'", "refuses"),
    # meshio reads vertex index 0 of a 1-based format as the last vertex, and then 12 of 8
    ("invalid/malformed.obj", "malformed.obj:28: '0' is not a vertex reference", "out of range"),
    ("invalid/empty.obj", "empty.obj: the file is empty: expected a mesh", "no faces"),
    ("invalid/empty.off", "empty.off: the file is empty: expected a mesh", "refuses"),
    ("invalid/empty.ply", "empty.ply: the file is empty: expected a mesh", "refuses"),
    # meshio reads a face of 0 vertices as part of a polygon, a self-intersecting or
    # non-planar polygon as given; rigid refuses each, naming the face
    ("invalid/malformed2.obj", "malformed2.obj:23: face 1 with 0 vertices: expected at least 3", "reads"),
    ("OBJ/box_longline.obj", "box_longline.obj:24: face 1: the polygon of 936 vertices intersects itself", "reads"),
    ("OBJ/regr_3429812.obj", "regr_3429812.obj:8: face 1: the polygon of 4 vertices is not planar", "reads"),
    ("OBJ/concave_polygon.obj", "concave_polygon.obj:77: face 1: the polygon of 66 vertices intersects itself", "refuses"),
]


@pytest.fixture(scope="module")
def cgal_dir(tmp_path_factory):
    assert os.path.exists(CGAL_ARCHIVE), f"{CGAL_ARCHIVE} is missing: run scripts/install-deps.sh (libcgal-demo)"
    out = tmp_path_factory.mktemp("cgal")
    names = {f.split(":", 1)[1] for f, *_ in READ_BY_BOTH + RIGID_ONLY + REFUSED if f.startswith("cgal:")}
    with tarfile.open(CGAL_ARCHIVE) as tar:
        for n in names:
            member = tar.getmember(f"data/meshes/{n}")
            with tar.extractfile(member) as src, open(out / n, "wb") as dst:
                dst.write(src.read())
    return out


def path_of(name, cgal_dir):
    if name.startswith("cgal:"):
        return str(cgal_dir / name.split(":", 1)[1])
    path = os.path.join(ASSIMP, name)
    assert os.path.exists(path), f"{path} is missing: run scripts/install-deps.sh (assimp-testmodels)"
    return path


def meshio_read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return meshio.read(path)


def triangles_of(mesh):
    """meshio's faces as triangles (polygons fanned from their first vertex), int (m, 3)."""
    out = []
    for block in mesh.cells:
        d = np.asarray(block.data)
        if block.type == "triangle" or block.type == "quad" or block.type.startswith("polygon"):
            for j in range(1, d.shape[1] - 1):
                out.append(d[:, [0, j, j + 1]])
    return np.concatenate(out) if out else np.zeros((0, 3), dtype=int)


def reference(points, tris):
    a, b, c = points[tris[:, 0]], points[tris[:, 1]], points[tris[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    dv = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0  # signed volumes of the tetrahedra (0, a, b, c)
    volume = dv.sum()
    com = (dv[:, None] * (a + b + c) / 4.0).sum(axis=0) / volume if volume != 0 else None
    return area, volume, com


@pytest.mark.parametrize("name, closed", READ_BY_BOTH)
def test_rigid_and_meshio_read_the_same_mesh(name, closed, cgal_dir):
    path = path_of(name, cgal_dir)
    ref = meshio_read(path)
    points = np.asarray(ref.points, dtype=float)
    tris = triangles_of(ref)
    mine = rigid.mesh.read(path)
    v = mine.vertices
    assert len(mine) == len(tris)
    if path.lower().endswith(".stl"):
        assert len(np.unique(v, axis=0)) == len(points)
        exact = np.array_equal(np.unique(v, axis=0), np.unique(points, axis=0))
    else:
        assert len(v) == len(points)
        exact = np.array_equal(v, points)
    # An ASCII file that declares float32 coordinates: meshio rounds the decimals to float32,
    # rigid parses them as doubles; the positions then differ by up to 2⁻²⁴ relative (asserted)
    # and so do the area and volume, to 1e-6 relative (a few such roundings per term).
    rel = REL if exact else 1e-6
    if not exact:
        assert ref.points.dtype == np.float32
        assert np.abs(v - points).max() <= 2.0**-24 * np.abs(points).max()
    area, volume, com = reference(points, tris)
    rigid.mesh.repair(mine)
    shell, _ = rigid.mesh.mass_properties(mine, density=1.0, shell=True)  # kg at 1 kg/m² = area
    assert shell.mass == pytest.approx(area, rel=rel)
    if closed:
        solid, _ = rigid.mesh.mass_properties(mine, density=1.0)
        # an inward-wound file has a negative divergence sum; rigid orients it outward first
        assert solid.mass == pytest.approx(abs(volume), rel=rel)
        scale = np.abs(points).max()
        assert np.abs(solid.com - com).max() < rel * scale
    else:
        with pytest.raises(rigid.Error, match="the mesh is not closed"):
            rigid.mesh.mass_properties(mine, density=1.0)


@pytest.mark.parametrize("name, volume, com", RIGID_ONLY)
def test_files_meshio_cannot_read(name, volume, com, cgal_dir):
    path = path_of(name, cgal_dir)
    with pytest.raises((Exception, SystemExit)):  # meshio 5.0 prints and exits on some of them
        meshio_read(path)
    mine = rigid.mesh.read(path)
    assert rigid.mesh.repair(mine).closed
    solid, _ = rigid.mesh.mass_properties(mine, density=1.0)
    # the volume of a cube or tetrahedron with exact corner coordinates: a few roundings
    assert solid.mass == pytest.approx(volume, rel=1e-14)
    if com is not None:
        assert np.abs(solid.com - com).max() < 1e-15


@pytest.mark.parametrize("name, message, meshio_does", REFUSED)
def test_broken_files_are_refused(name, message, meshio_does, cgal_dir):
    path = path_of(name, cgal_dir)
    with pytest.raises(rigid.Error) as e:
        rigid.mesh.read(path)
    assert str(e.value).startswith(path)
    assert message in str(e.value)
    if meshio_does == "refuses":
        with pytest.raises((Exception, SystemExit)):
            meshio_read(path)
    elif meshio_does == "out of range":
        m = meshio_read(path)
        assert max(int(np.max(c.data)) for c in m.cells) >= len(m.points)
    elif meshio_does == "no faces":
        assert len(triangles_of(meshio_read(path))) == 0
    else:
        assert len(triangles_of(meshio_read(path))) > 0
