"""`rigid inertia` refuses mass properties whose output would overflow a double (inf, nan)."""
import struct

import pytest

QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def write_unit_cube_stl(path):
    # the closed unit cube [0, 1]³ as a binary STL (12 outward triangles)
    v = [((i & 1) * 1.0, ((i >> 1) & 1) * 1.0, ((i >> 2) & 1) * 1.0) for i in range(8)]
    tris = [(v[q[0]], v[q[1]], v[q[2]]) for q in QUADS] + [(v[q[0]], v[q[2]], v[q[3]]) for q in QUADS]
    data = b"cube".ljust(80, b" ") + struct.pack("<I", len(tris))
    for t in tris:
        data += struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0)
    path.write_bytes(data)
    return path


def assert_refused_without_inf_or_nan(proc, wanted):
    assert proc.returncode == 1, proc.stdout
    assert proc.stdout == ""
    assert wanted in proc.stderr
    assert "internal error" not in proc.stderr
    # no inf or nan anywhere: not printed, nor quoted in the message
    for stream in (proc.stdout, proc.stderr):
        assert "nan" not in stream and "inf" not in stream.replace("information", "")


@pytest.mark.parametrize("fmt", ["pseudo", "log-cholesky"])
def test_a_cube_of_1e308_kg_is_refused_not_printed_as_inf(run, tmp_path, fmt):
    # the unit cube with its COM at (½, ½, ½): ½ tr(I_O) = 2e308 overflows (printed inf and -nan
    # with exit 0 before; log-cholesky reached an internal error)
    cube = write_unit_cube_stl(tmp_path / "cube.stl")
    proc = run("inertia", cube, "--mass", 1e308, "--format", fmt)
    assert_refused_without_inf_or_nan(proc, "the pseudo-inertia of the body (mass 1e+308 kg")
    assert "overflows a double" in proc.stderr
    # a mass that fits is printed
    proc = run("inertia", cube, "--mass", 1.0, "--format", fmt, check=True)
    assert "inf" not in proc.stdout and "nan" not in proc.stdout


@pytest.mark.parametrize("fmt", ["pseudo", "log-cholesky"])
def test_a_catalogue_box_about_a_far_point_is_refused(run, fmt):
    # a 1 kg box stated about a point 1e200 m away: m |d|² = 1e400
    proc = run("inertia", "box", "--lx", 1, "--ly", 1, "--lz", 1, "--mass", 1, "--about", "1e200,0,0",
               "--format", fmt)
    assert_refused_without_inf_or_nan(proc, "overflows a double")
