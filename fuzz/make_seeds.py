#!/usr/bin/env python3
"""Writes the seed corpus of every fuzz target into OUT/<target>/: small well-formed inputs
generated here (a tetrahedron and a cube in every mesh format and encoding, inertials in the
three XML formats, expressions, run schemas, sweep journals, CSV files, command lines), the
example scenes, and the smallest meshes of the CGAL demo
data set when it is installed (libcgal-demo). Nothing large is committed: the seeds are made
when `make fuzz` runs.  Usage: fuzz/make_seeds.py OUT"""
import json
import os
import shutil
import struct
import sys
import tarfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CGAL = "/usr/share/doc/libcgal-demo/data.tar.gz"

TET_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
CUBE_Q = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def tris(faces):
    return [t for f in faces for t in ([(f[0], f[k], f[k + 1]) for k in range(1, len(f) - 1)])]


def write(out, target, name, data):
    d = os.path.join(out, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def stl_ascii(v, f, name="s"):
    s = f"solid {name}\n"
    for t in f:
        s += " facet normal 0 0 0\n  outer loop\n"
        s += "".join(f"   vertex {v[i][0]} {v[i][1]} {v[i][2]}\n" for i in t)
        s += "  endloop\n endfacet\n"
    return s + f"endsolid {name}\n"


def stl_binary(v, f, header=b"binary"):
    b = header.ljust(80, b" ")[:80] + struct.pack("<I", len(f))
    for t in f:
        b += struct.pack("<3f", 0, 0, 0)
        for i in t:
            b += struct.pack("<3f", *v[i])
        b += struct.pack("<H", 0)
    return b


def obj(v, f, extras=False):
    s = "# seed\no body\n" + "".join(f"v {x} {y} {z}\n" for x, y, z in v)
    if extras:
        s += "vt 0 0\nvn 0 0 1\n"
        return s + "".join("f " + " ".join(f"{i + 1}/1/1" for i in face) + "\n" for face in f)
    return s + "".join("f " + " ".join(str(i - len(v)) for i in face) + "\n" for face in f)


def ply_ascii(v, f):
    s = ("ply\nformat ascii 1.0\ncomment seed\n"
         f"element vertex {len(v)}\nproperty float x\nproperty float y\nproperty float z\n"
         f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n")
    s += "".join(f"{x} {y} {z}\n" for x, y, z in v)
    return s + "".join(f"{len(face)} " + " ".join(map(str, face)) + "\n" for face in f)


def ply_binary(v, f, big):
    e = ">" if big else "<"
    s = (f"ply\nformat binary_{'big' if big else 'little'}_endian 1.0\n"
         f"element vertex {len(v)}\nproperty double x\nproperty double y\nproperty double z\n"
         "property uchar red\n"
         f"element face {len(f)}\nproperty list uchar uint vertex_indices\nend_header\n").encode()
    for p in v:
        s += struct.pack(e + "3dB", *p, 7)
    for face in f:
        s += struct.pack(e + "B" + "I" * len(face), len(face), *face)
    return s


def off(v, f):
    s = "OFF\n# seed\n" + f"{len(v)} {len(f)} 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in v)
    return s + "".join(f"{len(face)} " + " ".join(map(str, face)) + "\n" for face in f)


def meshes(out):
    write(out, "stl_ascii", "tet.stl", stl_ascii(TET_V, TET_F))
    write(out, "stl_ascii", "cube.stl", stl_ascii(CUBE_V, tris(CUBE_Q), "cube"))
    write(out, "stl_ascii", "two_solids.stl", stl_ascii(TET_V, TET_F, "a") + stl_ascii(TET_V, TET_F, "b"))
    write(out, "stl_binary", "tet.stl", stl_binary(TET_V, TET_F))
    write(out, "stl_binary", "cube.stl", stl_binary(CUBE_V, tris(CUBE_Q)))
    write(out, "stl_binary", "solid_header.stl", stl_binary(TET_V, TET_F, b"solid exported by a CAD tool"))
    write(out, "obj", "tet.obj", obj(TET_V, TET_F))
    write(out, "obj", "cube_quads.obj", obj(CUBE_V, CUBE_Q, extras=True))
    write(out, "ply", "tet_ascii.ply", ply_ascii(TET_V, TET_F))
    write(out, "ply", "cube_ascii.ply", ply_ascii(CUBE_V, CUBE_Q))
    write(out, "ply", "tet_le.ply", ply_binary(TET_V, TET_F, False))
    write(out, "ply", "cube_be.ply", ply_binary(CUBE_V, CUBE_Q, True))
    write(out, "off", "tet.off", off(TET_V, TET_F))
    write(out, "off", "cube.off", off(CUBE_V, CUBE_Q))
    if os.path.exists(CGAL):  # real files, the small ones only
        with tarfile.open(CGAL) as tar:
            for m in tar.getmembers():
                ext = os.path.splitext(m.name)[1].lower().lstrip(".")
                if m.isfile() and m.size <= 4096 and ext in ("off", "stl", "ply", "obj"):
                    data = tar.extractfile(m).read()
                    target = {"off": "off", "ply": "ply", "obj": "obj"}.get(ext)
                    if ext == "stl":
                        target = "stl_ascii" if data.lstrip().startswith(b"solid") else "stl_binary"
                    write(out, target, "cgal_" + os.path.basename(m.name), data)


def inertials(out):
    inertia = 'ixx="0.4" ixy="-0.01" ixz="0" iyy="0.5" iyz="0.02" izz="0.6"'
    write(out, "inertial_xml", "link.urdf",
          '<robot name="r"><link name="a"><inertial><origin xyz="0.1 0 0.2" rpy="0 0.3 0"/>'
          f'<mass value="2"/><inertia {inertia}/></inertial></link>'
          '<link name="b"/></robot>\n')
    write(out, "inertial_xml", "full.xml",
          '<mujoco><worldbody><body name="b"><inertial pos="0 0 0.1" mass="1"'
          ' fullinertia="0.4 0.5 0.6 -0.01 0 0.02"/><body name="c"><inertial pos="0 0 0" mass="1"'
          ' quat="0.7071067811865476 0 0 0.7071067811865476" diaginertia="1 2 3"/></body>'
          '</body></worldbody></mujoco>\n')
    write(out, "inertial_xml", "link.sdf",
          '<sdf version="1.7"><model name="m"><link name="c"><inertial>'
          '<pose>0 0 0 1.5707963267948966 0 0</pose><mass>1</mass><inertia><ixx>1</ixx>'
          '<iyy>2</iyy><izz>3</izz><ixy>0.1</ixy></inertia></inertial></link></model></sdf>\n')


def inertial_fixes(out):
    write(out, "inertial_fix", "robot.urdf",
          '<robot name="r">\n  <link name="a">\n    <inertial><mass value="1"/>'
          '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>\n'
          '    <collision><origin xyz="0.1 0 0" rpy="0 0.3 0"/><geometry><box size="0.1 0.2 0.3"/>'
          '</geometry></collision>\n    <collision><geometry><cylinder radius="0.1" length="0.2"/>'
          '</geometry></collision>\n  </link>\n  <link name="b"><collision><geometry>'
          '<sphere radius="0.1"/></geometry></collision></link>\n  <link name="c"/>\n</robot>\n')
    write(out, "inertial_fix", "model.xml",
          '<mujoco>\n  <compiler angle="radian" eulerseq="zyx"/>\n  <default>\n'
          '    <default class="c"><geom type="capsule" density="500"/></default>\n  </default>\n'
          '  <worldbody>\n    <body name="a" childclass="c">\n'
          '      <geom fromto="0 0 0 0.1 0.2 0.3" size="0.05"/>\n'
          '      <geom type="box" size="0.1 0.2 0.3" euler="0.1 0.2 0.3" mass="2"/>\n'
          '      <body name="b"><geom type="ellipsoid" size="0.1 0.2 0.3" xyaxes="0 1 0 -1 0 0"/>'
          '<geom type="cylinder" size="0.1 0.2" zaxis="1 1 1"/></body>\n'
          '      <body name="d"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/></body>\n'
          '    </body>\n  </worldbody>\n</mujoco>\n')
    write(out, "inertial_fix", "model.sdf",
          '<sdf version="1.9"><model name="m"><link name="l"><collision name="c">'
          '<pose degrees="true">0 0 0.1 90 0 0</pose><geometry><capsule><radius>0.05</radius>'
          '<length>0.2</length></capsule></geometry></collision><collision name="e"><geometry>'
          '<ellipsoid><radii>0.1 0.2 0.3</radii></ellipsoid></geometry></collision></link>'
          '</model></sdf>\n')


def robot_models(out):
    write(out, "robot_model", "arm.urdf",
          '<robot name="arm">\n  <link name="base"/>\n  <link name="upper">\n    <inertial>'
          '<origin xyz="0 0 0.1" rpy="0 0 0.5"/><mass value="2"/><inertia ixx="0.1" ixy="0" '
          'ixz="0" iyy="0.2" iyz="0" izz="0.3"/></inertial>\n  </link>\n  <link name="tip"/>\n'
          '  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>'
          '<origin xyz="0.1 0.2 0.3" rpy="0.3 -0.4 0.5"/><axis xyz="0 3 4"/>'
          '<dynamics damping="0.7"/></joint>\n  <joint name="rail" type="prismatic">'
          '<parent link="upper"/><child link="tip"/></joint>\n</robot>\n')
    write(out, "robot_model", "model.xml",
          '<mujoco model="m">\n  <compiler angle="degree" eulerseq="zyx"/>\n'
          '  <option gravity="0 0 -1.6"/>\n  <default>\n    <joint damping="1"/>\n'
          '    <default class="a"><joint stiffness="2" armature="0.1"/>\n'
          '      <default class="b"><joint type="slide" ref="0.2"/></default></default>\n'
          '  </default>\n  <worldbody>\n    <body name="p" pos="0 0 1" childclass="a">\n'
          '      <freejoint name="root"/>\n      <geom type="capsule" fromto="0 0 0 0 0 -0.3" '
          'size="0.05"/>\n      <body name="q" euler="10 20 30"><joint name="h" axis="1 1 0" '
          'ref="30" springref="15"/><joint name="s" class="b"/>\n'
          '        <inertial pos="0 0 0" quat="1 0 0 0" mass="1" diaginertia="1 2 2"/></body>\n'
          '      <body name="r" xyaxes="0 1 0 -1 0 0"><geom type="box" size="0.1 0.2 0.3"/></body>\n'
          '    </body>\n  </worldbody>\n</mujoco>\n')
    write(out, "robot_model", "include.xml",
          '<mujoco>\n  <worldbody>\n    <body name="a"><include file="part.xml"/></body>\n'
          '  </worldbody>\n</mujoco>\n')
    write(out, "robot_model", "model.sdf",
          '<sdf version="1.6">\n  <world name="w">\n    <gravity>0 0 -1.6</gravity>\n'
          '    <model name="m">\n      <pose>1 2 3 0 0 0.5</pose>\n'
          '      <link name="base"><pose>0 0 0.5 0 0 0</pose></link>\n'
          '      <link name="cart"><pose degrees="true">0.2 0 0.5 0 0 90</pose><inertial>'
          '<pose>0 0 0.1 0 0.3 0</pose><mass>2</mass><inertia><ixx>0.1</ixx><ixy>0.01</ixy>'
          '<iyy>0.2</iyy><izz>0.3</izz></inertia></inertial></link>\n'
          '      <link name="arm"><pose rotation_format="quat_xyzw">0.2 0 0.8 0 0.7 0 0.7</pose>'
          '</link>\n      <link name="tool"><pose>0.2 0.3 0.8 0 0 0</pose></link>\n'
          '      <joint name="weld" type="fixed"><parent>world</parent><child>base</child></joint>\n'
          '      <joint name="rail" type="prismatic"><parent>base</parent><child>cart</child>'
          '<axis><xyz>1 0 0</xyz><dynamics><damping>2</damping><spring_stiffness>30'
          '</spring_stiffness><spring_reference>0.1</spring_reference></dynamics></axis></joint>\n'
          '      <joint name="spin" type="continuous"><parent>cart</parent><child>arm</child>'
          '<pose relative_to="__model__">0 0.05 0.8 0 0 0</pose><axis><xyz>0 0 1</xyz>'
          '<use_parent_model_frame>true</use_parent_model_frame></axis></joint>\n'
          '      <joint name="hand" type="revolute"><parent>arm</parent><child>tool</child>'
          '<axis><xyz expressed_in="__model__">0 1 0</xyz></axis></joint>\n'
          '    </model>\n  </world>\n</sdf>\n')


def expressions(out):
    seeds = {
        "const": "0a*b + sin(pi/3)^2 - sqrt(abs(b)) / exp(1e-3)",
        "power": "0(a + 2)**3 - 2^-1 * log(a) + atan(b) + tanh(1.5e2)",
        "potential": "1a*9.81*(1 - cos(q)) + b*q^2/2 + 0.1*sin(t)",
        "lagrangian": "2a*q_dot^2/2 + a*(q_dot*cos(q))^2 - b*q^4 + q*q_dot*t",
        "functions": "2(1 + sinh(q)^2)*q_dot^2 - acos(q/10) + asin(q/10) + cosh(q) - tan(q)",
    }
    for name, text in seeds.items():
        write(out, "expression", name + ".txt", text)


def run_schemas(out):
    column = '{{"name": "{0}", "quantity": "{1}", "owner": "{2}", "component": "{3}", "unit": "{4}"}}'
    racket = ('{"kind": "free_bodies", "columns": [' + column.format("t", "time", "", "", "s") + ", " +
              column.format("racket.qw", "orientation", "racket", "w", "") + ", " +
              column.format("racket.wy", "angular_velocity", "racket", "y", "rad/s") + "], " +
              '"parameters": {}, "diagnostics": {"energy_initial": "J", "racket.orthonormality_max": ""}, '
              '"metrics": {"first_flip": "s"}}')
    pendulum = ('{"kind": "coordinates", "columns": [' + column.format("t", "time", "", "", "s") + ", " +
                column.format("theta", "coordinate", "theta", "", "") + ", " +
                column.format("lambda_rope", "multiplier", "rope", "", "") + "], " +
                '"parameters": {"m": "", "bob_mass": "kg", "bob_ixx": "kg·m²"}, '
                '"diagnostics": {"jacobi_max_change": "J"}, "metrics": {}}')
    seeds = {"racket": racket, "pendulum": pendulum,
             "unknown_quantity": pendulum.replace('"multiplier"', '"force"'),
             "missing_field": '{"kind": "coordinates", "columns": []}'}
    for name, text in seeds.items():
        write(out, "run_schema", name + ".json", text)


# the small sweep of fuzz/sweep_journal_fuzz.cpp: its scene file's bytes (kScene there) and grid
SWEEP_SCENE = b"# the scene of the sweep_journal fuzz target\n"


def fnv1a64(data):
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def journal_line(obj):
    return json.dumps(obj, separators=(",", ":"), ensure_ascii=False) + "\n"


def sweep_journals(out):
    """Journals as `rigid sweep` writes them (sweep.hpp: a header line, then one row per run,
    nlohmann's compact JSON) for the target's small sweep (a=0:1:3), whole and damaged."""
    desc = f"scene sweep.toml (fnv1a64 {fnv1a64(SWEEP_SCENE)}); grid a=0:1:3"

    def header(**changes):
        h = {"names": ["a"], "rigid_sweep": 1, "runs": 3, "shard": "0/1", "sweep": desc}
        h.update(changes)
        return journal_line(h)

    def row(run, a, results=(("energy", 0.5), ("period", 2.0)), error=""):
        return journal_line({"error": error, "results": [list(r) for r in results], "run": run,
                             "values": [a]})

    rows = [row(0, 0), row(1, 0.5, (("energy", 0.25), ("period", "nan"))),
            row(2, 1, (), "run 2: the step size fell below 1e-14 at t = 0.3, \"stiff\"\nsee docs")]
    seeds = {
        "complete": header() + "".join(rows),
        "out_of_order": header() + rows[2] + rows[0] + rows[1],
        "cut_short": header() + rows[0] + rows[1][:-9],
        "header_only": header(),
        "header_cut": header()[:-20],
        "shard": header(shard="1/2") + row(1, 0.5),
        "another_sweep": header(sweep=desc.replace("a=0:1:3", "a=0:2:3")) + rows[0],
        "wrong_index": header() + rows[0] + row(7, 3.5),
        "negative_index": header() + row(-1, 0),
        "twice_differently": header() + "".join(rows) + row(0, 0, (("energy", 0.75),)),
        "twice_alike": header() + "".join(rows) + rows[1],
        "non_finite": header() + row(0, "nan", (("energy", "inf"), ("period", "-inf"))) + rows[1] + rows[2],
        "missing_values": header() + journal_line({"error": "", "results": [], "run": 0}),
        "value_as_text": header() + row(0, "zero"),
        "crlf": (header() + "".join(rows)).replace("\n", "\r\n"),
        "huge_runs": header(runs=4294967296) + rows[0],
        "version_2": header(rigid_sweep=2) + rows[0],
        "units": header(units={"a": "m", "energy": "J", "period": "s", "result.a": ""}) + "".join(rows),
        "units_not_text": header(units={"a": 1}) + rows[0],
        "units_not_a_table": header(units=["m"]) + rows[0],
        "not_json": "rigid sweep journal\n",
        "extra_values_partial": header() + row(0, 0)[:-len('0]}\n')] + "0,1,2,3]}\n",
    }
    for name, text in seeds.items():
        write(out, "sweep_journal", name + ".jsonl", text)


def csv_tables(out):
    """A run's trajectory.csv (io::to_csv: a header, shortest round-trip doubles) and a sweep's
    runs.csv (numbers, then the error text quoted as RFC 4180 says), whole and damaged."""
    trajectory = "t,theta,theta_dot,energy\n0,0.5,0,1.2\n0.01,0.49975,-0.049,1.2\n0.02,0.499,-0.098,1.2000000000000002\n"
    runs = ('run,a,energy,period,error\n0,0,0.5,2,\n1,0.5,0.25,,"run 1: ""stiff"", step size\nbelow 1e-14"\n'
            '2,1,nan,inf,\n')
    seeds = {
        "trajectory.csv": trajectory,
        "trajectory_crlf.csv": trajectory.replace("\n", "\r\n"),
        "trajectory_non_finite.csv": "t,x\n0,nan\n1,inf\n2,-inf\n3,-0\n4,1e308\n5,4.9e-324\n",
        "trajectory_ragged.csv": "t,x\n0,1\n1\n",
        "trajectory_not_a_number.csv": "t,x\n0,one\n",
        "trajectory_repeated_name.csv": "t,x,x\n0,1,2\n",
        "trajectory_empty_name.csv": "t,,x\n0,1,2\n",
        "header_only.csv": "t,x\n",
        "runs.csv": runs,
        "runs_crlf.csv": runs.replace("\n", "\r\n"),
        "runs_unterminated_quote.csv": 'run,a,energy,error\n0,0,1,"cut\n',
        "runs_ragged.csv": "run,a,energy,error\n0,0,1\n",
        "runs_no_error_column.csv": "run,a,energy\n0,0,1\n",
        "runs_all_failed.csv": 'run,a,energy,error\n0,0,,failed\n1,1,,"failed, too"\n',
    }
    for name, text in seeds.items():
        write(out, "csv_table", name, text)


def command_lines(out):
    """Command lines (arguments joined by NUL bytes) of every subcommand, well formed; the
    target parses them only, so the files they name need not exist."""
    seeds = {
        "help": ["--help"],
        "version": ["--version"],
        "none": [],
        "run": ["run", "pendulum.toml", "-o", "out", "--set", "m=2", "--integrator", "dopri5",
                "--format", "csv", "--format", "npy", "--max-memory", "512MiB", "-q", "--report"],
        "check": ["check", "pendulum.toml", "--set", "simulation.t_end=20"],
        "eom": ["eom", "pendulum.toml", "--format", "latex"],
        "eom_emit": ["eom", "pendulum.toml", "--emit", "c++", "--flat", "-o", "eom.hpp"],
        "report": ["report", "out", "--report-frames", "100"],
        "modes": ["modes", "pendulum.toml", "--at", "theta=0"],
        "sweep": ["sweep", "pendulum.toml", "--grid", "m=1:2:3", "--threads", "2", "-o", "dir",
                  "--shard", "0/2"],
        "sweep_sample": ["sweep", "pendulum.toml", "--sample", "m=uniform(1,2)", "-n", "10",
                         "--seed", "18446744073709551615"],
        "sweep_merge": ["sweep", "merge", "a", "b", "-o", "c"],
        "plot": ["plot", "out", "--column", "theta", "--x", "t", "-o", "p.svg"],
        "inertia_box": ["inertia", "box", "--lx", "1", "--ly", "2", "--lz", "3", "--mass", "2",
                        "--about", "origin", "--format", "json", "--tolerance", "dims=±0.1mm"],
        "inertia_cylinder": ["inertia", "cylinder", "--radius", "0.1", "--height", "0.2",
                             "--density", "7800", "--axis", "x", "--rpy", "0,0.5,0"],
        "inertia_mesh": ["inertia", "part.stl", "--density", "2700", "--units", "mm", "--shell",
                         "--thickness", "0.001"],
        "inertia_check": ["inertia", "check", "robot.urdf"],
        "inertia_fix": ["inertia", "fix", "robot.urdf", "-o", "fixed.urdf", "--only", "a", "b"],
        "mesh_check": ["mesh", "check", "part.stl", "--units", "mm", "--fill-holes"],
        "rotation": ["rotation", "--euler", "10,20,30", "--unit", "deg", "--convention", "ZYX"],
        "rotation_quaternion": ["rotation", "--quaternion=0.5,0.5,0.5,0.5", "--order", "xyzw"],
        "demo": ["demo", "--no-report"],
    }
    for name, args in seeds.items():
        write(out, "cli_args", name, "\0".join(args))


def scenes(out):
    ex = os.path.join(ROOT, "examples")
    for name in sorted(os.listdir(ex)):
        if name.endswith(".toml"):
            os.makedirs(os.path.join(out, "scene"), exist_ok=True)
            shutil.copy(os.path.join(ex, name), os.path.join(out, "scene", name))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    meshes(out)
    inertials(out)
    inertial_fixes(out)
    robot_models(out)
    expressions(out)
    run_schemas(out)
    sweep_journals(out)
    csv_tables(out)
    command_lines(out)
    scenes(out)
    for target in sorted(os.listdir(out)):
        print(f"seeds: {target}: {len(os.listdir(os.path.join(out, target)))} files")


if __name__ == "__main__":
    main()
