"""The same input through every surface gives the same answer or the same refusal: the
primitive catalogue through Python, the command line and a scene file; a run through
`rigid run` and rigid.Scene.run; a diverging scene; and the remedies each surface words in
its own terms."""
import json
import pathlib
import re
import tomllib

import numpy as np
import pytest
import sympy

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def sample_sizes(entry):
    """Sizes 0.1, 0.2, 0.3 m in the entry's order (inner < outer), the torus with minor < major,
    and a tetrahedron that is not degenerate."""
    values = [0.1 * (i + 1) for i in range(len(entry["sizes"]))]
    if entry["name"] == "solid_torus":
        values = values[::-1]
    sizes = {s["name"]: v for s, v in zip(entry["sizes"], values)}
    vertices = [(0, 0, 0), (0.1, 0, 0), (0, 0.2, 0), (0, 0, 0.3)]
    points = {p: v for p, v in zip(entry["points"], vertices)}
    return sizes, points


def cli_flag(name):
    return "--" + name.replace("_", "-")


@pytest.mark.parametrize("entry", rigid.mass.primitives(), ids=lambda e: e["name"])
def test_catalogue_through_every_surface(entry, run, tmp_path):
    sizes, points = sample_sizes(entry)
    reference = rigid.mass.primitive(entry["name"], mass=2.0, **sizes, **points)
    names = [entry["name"], *entry["aliases"]]
    for name in names + [n.replace("_", "-") for n in names if "_" in n]:
        # Python: the generic factory and the named one (underscores only)
        by_python = rigid.mass.primitive(name, mass=2.0, **sizes, **points)
        np.testing.assert_array_equal(by_python.inertia_com, reference.inertia_com)
        if "-" not in name:
            by_name = getattr(rigid.mass, name)(mass=2.0, **sizes, **points)
            np.testing.assert_array_equal(by_name.inertia_com, reference.inertia_com)
        # the command line: same numbers in its JSON (shortest round-trip doubles)
        args = []
        for k, v in sizes.items():
            args += [cli_flag(k), v]
        for k, v in points.items():
            args += ["--" + k, ",".join(map(str, v))]
        out = json.loads(run("inertia", name.replace("_", "-"), *args, "--mass", 2, "--format", "json",
                             check=True).stdout)
        np.testing.assert_array_equal(np.array(out["inertia"]), reference.inertia_com)
        np.testing.assert_array_equal(np.array(out["com"]), reference.com)
    # a scene: the body posed by a coordinate, its sizes as keys (points as arrays)
    lines = ['[[coordinates]]', 'name = "x"', '[[bodies]]', 'name = "b"', f'primitive = "{names[-1]}"',
             "mass = 2.0"]
    lines += [f"{k} = {v!r}" for k, v in sizes.items()]
    lines += [f"{k} = [{', '.join(map(str, v))}]" for k, v in points.items()]
    lines += ['position = ["x", 0, 0]', "[simulation]", "t_end = 1"]
    scene = tmp_path / "s.toml"
    scene.write_text("\n".join(lines) + "\n")
    body = rigid.Scene(scene).bodies["b"]
    np.testing.assert_array_equal(body.inertia_com, reference.inertia_com)
    run("check", scene, check=True)


def test_a_typo_gets_the_same_suggestion_everywhere(run, tmp_path):
    with pytest.raises(rigid.Error, match="did you mean 'cylinder'"):
        rigid.mass.primitive("cylindr", mass=1, radius=1, height=1)
    assert "did you mean 'cylinder'" in run("inertia", "cylindr", "--radius", 1, check=False).stderr
    scene = tmp_path / "s.toml"
    scene.write_text('[[coordinates]]\nname = "x"\n[[bodies]]\nprimitive = "cylindr"\nradius = 1\n'
                     'height = 1\nmass = 1\nposition = ["x", 0, 0]\n[simulation]\nt_end = 1\n')
    with pytest.raises(rigid.Error, match=r"s.toml:4:13: .*did you mean 'cylinder'"):
        rigid.Scene(scene)
    # a size that the shape does not take
    with pytest.raises(rigid.Error, match="did you mean 'height'"):
        rigid.mass.primitive("cylinder", mass=1, radius=1, heigth=1)


def test_remedies_are_worded_per_surface(run, tmp_path):
    # an open mesh (a box without its last triangle) as a solid: the library names its
    # settings; the command line says --shell, Python shell=True, a scene file shell = true
    v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5),
         (2, 3, 7), (2, 7, 6), (3, 0, 4)]
    off = tmp_path / "open.off"
    off.write_text("OFF\n8 11 0\n" + "".join(f"{a} {b} {c}\n" for a, b, c in v)
                   + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    err = run("inertia", off, "--density", 1000, check=False).stderr
    assert "--shell" in err and "--fill-holes" in err and "`" not in err
    with pytest.raises(rigid.Error, match=r"shell=True.*fill_holes=True"):
        rigid.mesh.mass_from_file(off, density=1000)
    scene = tmp_path / "s.toml"
    scene.write_text(f'[[coordinates]]\nname = "x"\n[[bodies]]\nmesh = "{off.name}"\ndensity = 1000\n'
                     'position = ["x", 0, 0]\n[simulation]\nt_end = 1\n')
    with pytest.raises(rigid.Error, match=r"'shell = true'.*'fill_holes = true'"):
        rigid.Scene(scene)
    # and each surface's remedy works: the same shell through all three
    shell_cli = json.loads(run("inertia", off, "--areal-density", 1000, "--format", "json",
                               check=True).stdout)
    shell_py, _ = rigid.mesh.mass_from_file(off, density=1000, shell=True)
    scene.write_text(scene.read_text().replace("density = 1000", "density = 1000\nshell = true"))
    shell_scene = rigid.Scene(scene).bodies["body1"]
    np.testing.assert_array_equal(np.array(shell_cli["inertia"]), shell_py.inertia_com)
    np.testing.assert_array_equal(shell_scene.inertia_com, shell_py.inertia_com)


def two_free_bodies(tmp_path, spinning_first):
    rest = '[[bodies]]\nname = "still"\nfree = true\ninertia = {mass = 1, ixx = 1, iyy = 2, izz = 3}\n'
    spin = ('[[bodies]]\nname = "spin"\nfree = true\ninertia = {mass = 1, ixx = 1, iyy = 2, izz = 3}\n'
            'angular_velocity = [1e3, 1e3, 1e3]\n')
    p = tmp_path / ("first.toml" if spinning_first else "second.toml")
    p.write_text((spin + rest if spinning_first else rest + spin)
                 + '[simulation]\nt_end = 10\nintegrator = "rk4"\ndt = 0.1\n')
    return p


@pytest.mark.parametrize("spinning_first", [True, False])
def test_a_diverging_body_is_refused_whichever_its_place(run, tmp_path, spinning_first):
    scene = two_free_bodies(tmp_path, spinning_first)
    out = tmp_path / "out"
    p = run("run", scene, "-o", out, check=False)
    assert p.returncode == 1
    assert "non-finite state at step 2, t = 0.2 s: body 'spin'" in p.stderr
    assert not out.exists()  # nothing half-written
    with pytest.raises(rigid.Error, match="body 'spin'"):
        rigid.Scene(scene).run(output=out)
    assert not out.exists()


def test_python_writes_the_files_rigid_run_writes(run, tmp_path):
    scene = EXAMPLES / "atwood.toml"
    run("run", scene, "-o", tmp_path / "cli", "--format", "csv", "--format", "npy", "--format", "json",
        check=True)
    out = rigid.Scene(scene).run(output=tmp_path / "py", formats=["csv", "npy", "json"])
    assert [pathlib.Path(p).name for p in out["written"]] == ["trajectory.csv", "trajectory.npy", "summary.json"]
    for name in ("trajectory.csv", "trajectory.npy"):
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "py" / name).read_bytes(), name
    a = json.loads((tmp_path / "cli" / "summary.json").read_text())
    b = json.loads((tmp_path / "py" / "summary.json").read_text())
    a.pop("wall_time_s"), b.pop("wall_time_s")
    assert a == b


# numbers in a printout that are not part of a name (theta1, m2): integers, decimals,
# exponents; a fraction is two integers
NUMBER = re.compile(r"(?<![A-Za-z_\d.])\d+(?:\.\d+)?(?:[eE][+-]?\d+)?")


def significant_digits(token):
    mantissa = re.split("[eE]", token)[0]
    digits = mantissa.replace(".", "").lstrip("0")
    if "." not in mantissa:
        digits = digits.rstrip("0")  # 1000 is one significant digit
    return len(digits)


def expressions_of(node):
    """Every string in a TOML subtree (the expressions a scene writes)."""
    if isinstance(node, str):
        yield node
    elif isinstance(node, dict):
        for v in node.values():
            yield from expressions_of(v)
    elif isinstance(node, list):
        for v in node:
            yield from expressions_of(v)


def same_equations(a, b):
    """Two printouts of equations that say the same thing, whatever the order of their terms:
    line by line, each `left = right` read by SymPy and compared as left − right."""
    la, lb = a.splitlines(), b.splitlines()
    if len(la) != len(lb):
        return False
    for x, y in zip(la, lb):
        if " = " not in x:
            if x != y:
                return False
            continue
        diff = []
        try:
            for line in (x, y):
                left, right = line.split(" = ", 1)
                left = left.rsplit(" ", 1)[-1]  # "energy (Jacobi integral) h" -> h
                diff.append(sympy.sympify(left.replace("^", "**")) - sympy.sympify(right.replace("^", "**")))
        except (sympy.SympifyError, SyntaxError, TypeError):
            if x != y:  # prose with an '=' in it: compared as text
                return False
            continue
        if sympy.expand(diff[0] - diff[1]) != 0:
            return False
    return True


def without_measured_values(text):
    """The printout less its line of measured constants' values ("where rod_mass = …")."""
    return "\n".join(line for line in text.splitlines()
                     if not (line.startswith("where ") and "computed from the bodies'" in line))


@pytest.mark.parametrize("scene", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_eom_prints_short_numbers_and_the_scene_parameter_names(run, scene):
    text = run("eom", scene, check=True).stdout
    long_numbers = [t for t in NUMBER.findall(text) if significant_digits(t) > 8]
    assert not long_numbers, f"numbers with more than 8 significant digits: {long_numbers}\n{text}"
    # every parameter the dynamics use (bodies, gravity, springs, constraints, potentials,
    # forces; not the initial conditions) stays a name: the printout does not change when its
    # value does (one that cancels, like a rolling sphere's radius, is absent either way)
    doc = tomllib.loads(scene.read_text())
    params = doc.get("parameters", {})
    used = set()
    for key in ("bodies", "gravity", "springs", "constraints", "potentials", "forces"):
        for expression in expressions_of(doc.get(key, [])):
            used |= set(params) & set(re.findall(r"[A-Za-z_]\w*", expression))
    for p in sorted(used):
        if not isinstance(params[p], (int, float)):
            continue
        changed = run("eom", scene, "--set", f"{p}={params[p] * 1.1!r}", check=True).stdout
        # the values of the constants measured from a body (a density field's mass and inertia)
        # change with the parameters they are measured at; the equations, in their names, do not
        assert same_equations(without_measured_values(changed), without_measured_values(text)), (
            f"'{p}' entered as a number:\n{text}\nwith {p} changed:\n{changed}")
    appearing = [p for p in used if re.search(rf"(?<![A-Za-z_\d]){re.escape(p)}(?![A-Za-z_\d])", text)]
    assert len(appearing) >= len(used) - 1, (used, text)  # at most one cancels (a rolling radius)


@pytest.mark.parametrize("example", ["double_pendulum", "tennis_racket", "atwood", "heavy_top"])
def test_the_run_schema_is_one_through_every_surface(example, run, tmp_path):
    """The schema a Scene publishes before running is its run's, is the one `rigid run` writes
    into summary.json, and names the columns of trajectory.csv in order; the report page's series
    take their units from it."""
    scene = rigid.Scene(str(EXAMPLES / f"{example}.toml"))
    schema = scene.schema
    out = scene.run(output=str(tmp_path / "py"))
    assert out["schema"] == schema
    assert [c["name"] for c in schema["columns"]] == list(out["columns"])
    assert list(schema["diagnostics"]) == list(out["summary"]["diagnostics"])
    assert list(schema["metrics"]) == list(out["summary"]["metrics"])
    run("run", EXAMPLES / f"{example}.toml", "-o", tmp_path / "cli", "-q", check=True)
    summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    assert summary["schema"] == schema
    assert json.loads((tmp_path / "py" / "summary.json").read_text())["schema"] == schema
    header = (tmp_path / "cli" / "trajectory.csv").read_text().split("\n", 1)[0].split(",")
    assert header == [c["name"] for c in schema["columns"]]
    # units by quantity, as docs/scene-format.md states them
    units = {"time": "s", "position": "m", "velocity": "m/s", "angular_velocity": "rad/s",
             "angular_momentum": "kg·m²/s", "energy": "J", "jacobi": "J"}
    for c in schema["columns"]:
        assert c["unit"] == units.get(c["quantity"], ""), c
