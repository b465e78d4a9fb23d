"""Writes the meshes of examples/docs/ (ASCII STL, outward-facing triangles):

  bracket.stl             an L bracket in millimetres: legs 40 mm, 5 mm thick, 30 mm wide
                          (a closed solid; volume (40*5 + 35*5) * 30 = 11250 mm^3)
  scan.stl                a scanned cup in millimetres: a 24-sided prism of radius 30 mm and
                          height 80 mm without its top face (open: one hole, 24 edges)
  cover.stl               a sheet-metal cover in millimetres: the top (200 x 100 mm) and four
                          sides 20 mm deep of a box, open below (a surface: area 32000 mm^2)
  meshes/upper_arm.stl    robot.urdf's upper arm in metres: a 12-sided prism of radius 0.04 m
                          and length 0.3 m along z, from z = 0 (a closed solid)

Run from anywhere: /usr/bin/python3 examples/docs/make_files.py (the files are rewritten
byte for byte the same)."""
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent


def write_stl(path, name, triangles):
    lines = [f"solid {name}"]
    for a, b, c in triangles:
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        length = math.sqrt(sum(x * x for x in n))
        n = [x / length for x in n]
        lines.append("  facet normal " + " ".join(f"{x:.6g}" for x in n))
        lines.append("    outer loop")
        for p in (a, b, c):
            lines.append("      vertex " + " ".join(f"{x:.9g}" for x in p))
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append(f"endsolid {name}")
    path.write_text("\n".join(lines) + "\n")


def prism(radius, height, sides, top=True, bottom=True):
    """A regular prism about z from z = 0 to height, counter-clockwise seen from outside."""
    ring = [(radius * math.cos(2 * math.pi * k / sides), radius * math.sin(2 * math.pi * k / sides))
            for k in range(sides)]
    out = []
    for k in range(sides):
        (x0, y0), (x1, y1) = ring[k], ring[(k + 1) % sides]
        out.append(((x0, y0, 0.0), (x1, y1, 0.0), (x1, y1, height)))
        out.append(((x0, y0, 0.0), (x1, y1, height), (x0, y0, height)))
        if bottom:
            out.append(((0.0, 0.0, 0.0), (x1, y1, 0.0), (x0, y0, 0.0)))
        if top:
            out.append(((0.0, 0.0, height), (x0, y0, height), (x1, y1, height)))
    return out


def extrude(polygon, fan_from, width):
    """The polygon (x, z), counter-clockwise in the x-z plane (seen from +y), extruded along
    +y by width; the caps are fans from the vertex fan_from (which sees every other vertex)."""
    n = len(polygon)
    out = []
    for k in range(n):
        (x0, z0), (x1, z1) = polygon[k], polygon[(k + 1) % n]
        out.append(((x0, 0.0, z0), (x1, width, z1), (x1, 0.0, z1)))
        out.append(((x0, 0.0, z0), (x0, width, z0), (x1, width, z1)))
    for k in range(1, n - 1):
        i, j = (fan_from + k) % n, (fan_from + k + 1) % n
        a, b, c = polygon[fan_from], polygon[i], polygon[j]
        out.append(((a[0], 0.0, a[1]), (b[0], 0.0, b[1]), (c[0], 0.0, c[1])))
        out.append(((a[0], width, a[1]), (c[0], width, c[1]), (b[0], width, b[1])))
    return out


def open_box(lx, ly, depth):
    """The top (z = 0) and four sides (down to z = -depth) of a box, normals outward."""
    top = [(0, 0), (lx, 0), (lx, ly), (0, ly)]
    out = [((0.0, 0.0, 0.0), (lx, 0.0, 0.0), (lx, ly, 0.0)), ((0.0, 0.0, 0.0), (lx, ly, 0.0), (0.0, ly, 0.0))]
    for k in range(4):
        (x0, y0), (x1, y1) = top[k], top[(k + 1) % 4]
        out.append(((x0, y0, 0.0), (x0, y0, -depth), (x1, y1, -depth)))
        out.append(((x0, y0, 0.0), (x1, y1, -depth), (x1, y1, 0.0)))
    return out


def main():
    # L profile in the x-z plane; vertex 3 = (5, 5) is the inner corner, seen from every vertex
    l_profile = [(0, 0), (40, 0), (40, 5), (5, 5), (5, 40), (0, 40)]
    write_stl(HERE / "bracket.stl", "bracket", extrude(l_profile, 3, 30.0))
    write_stl(HERE / "scan.stl", "scan", prism(30.0, 80.0, 24, top=False))
    write_stl(HERE / "cover.stl", "cover", open_box(200.0, 100.0, 20.0))
    (HERE / "meshes").mkdir(exist_ok=True)
    write_stl(HERE / "meshes" / "upper_arm.stl", "upper_arm", prism(0.04, 0.3, 12))


if __name__ == "__main__":
    main()
