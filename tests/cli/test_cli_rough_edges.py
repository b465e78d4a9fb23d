"""Rough edges a new user hits, each with the command as typed.

- Number literals that no double holds (underflow to 0 or a subnormal, overflow) are refused at
  file:line:col, or naming the --set argument; an expression whose value underflows likewise.
- Too small a dt states the run's step count and the real limit.
- Misspelt subcommands, options and enumerated values get "did you mean"; a bad option value
  exits 2 (usage) in every command, a refused input 1.
- Messages count in the singular and the plural, list what they say is listed, name no C++
  function, and the help of --tolerance says that primitives take it.
- A shell's --density is the material's (kg/m³) and needs --thickness; --areal-density gives
  kg/m²; an implausible areal density is warned about; no option that was given is suggested.
"""
import json
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PENDULUM = ROOT / "examples" / "physical_pendulum.toml"
RACKET = ROOT / "examples" / "tennis_racket.toml"
RANGE = "expected 0 or a magnitude from 2.2250738585072014e-308 to 1.7976931348623157e+308"


def pendulum(tmp_path, old, new):
    text = PENDULUM.read_text()
    assert old in text
    path = tmp_path / "p.toml"
    path.write_text(text.replace(old, new, 1))
    return path


# --- 1. literals out of the range of a double -------------------------------------------------

def test_subnormal_parameter_is_refused_at_its_literal(run, tmp_path):
    # was "rigid: error: floating point underflow." with no place
    p = pendulum(tmp_path, "g = 9.81", "g = 2.2250738585072014e-309")
    proc = run("check", p, check=False)
    assert proc.returncode == 1
    assert f"{p}:12:5: parameter g: '2.2250738585072014e-309' underflows: a double would hold the subnormal" \
        in proc.stderr
    assert RANGE in proc.stderr


def test_literal_in_an_expression_that_rounds_to_zero_is_refused(run, tmp_path):
    # was silently L = 0, reported later as a singular mass matrix
    p = pendulum(tmp_path, "L = 1.0", 'L = "1e-400"')
    proc = run("check", p, check=False)
    assert proc.returncode == 1
    assert f"{p}:14:" in proc.stderr and "'1e-400' underflows: a double would hold 0" in proc.stderr
    p = pendulum(tmp_path, "L = 1.0", 'L = "1e-300/1e10"')
    proc = run("check", p, check=False)
    assert proc.returncode == 1 and f"{p}:14:" in proc.stderr and "which underflows" in proc.stderr


def test_set_literal_is_refused_naming_the_argument(run, tmp_path):
    # was silently dt = 0
    proc = run("run", PENDULUM, "--set", "simulation.dt=1e-400", "--integrator", "rk4", check=False)
    assert proc.returncode == 1
    assert ("--set: override 'simulation.dt=1e-400': '1e-400' underflows: a double would hold 0; "
            + RANGE) in proc.stderr
    proc = run("check", RACKET, "--set", "racket.omega=[1e400, 1, 0]", check=False)
    assert proc.returncode == 1 and "racket.angular_velocity '1e400' overflows" in proc.stderr
    # in a file, toml++ refuses it itself ("could not be interpreted"): said as the range, at its start
    p = pendulum(tmp_path, "g = 9.81", "g = -1.8e308")
    proc = run("check", p, check=False)
    assert proc.returncode == 1 and f"{p}:12:6: '1.8e308' overflows: a double would hold infinity" in proc.stderr


def test_option_number_out_of_range_is_a_usage_error(run):
    # CLI11 read --mass 1e-400 as 0 and 2e-310 as a subnormal
    proc = run("inertia", "sphere", "--radius", 1, "--mass", "1e-400", check=False)
    assert proc.returncode == 2
    assert "--mass 1e-400: '1e-400' underflows: a double would hold 0; " + RANGE in proc.stderr
    proc = run("inertia", "sphere", "--radius=2e-310", "--mass", "1", check=False)
    assert proc.returncode == 2 and "--radius 2e-310: '2e-310' underflows" in proc.stderr


# --- 2. the step limit ------------------------------------------------------------------------

def test_too_small_a_step_states_the_real_limit(run):
    proc = run("check", PENDULUM, "--integrator", "rk4", "--set", "simulation.dt=1e-9", check=False)
    assert proc.returncode == 1
    # 6 s / 1e-9 s = 6e9 steps; the limit of a run of coordinates is 5e8
    assert "6 s in steps of at most 1e-09 s is about 6e+09 steps, more than the 500000000 a run may take" \
        in proc.stderr
    assert "more than the 0 allowed" not in proc.stderr


# --- 3. did you mean, and the exit status of a bad option value ------------------------------

@pytest.mark.parametrize("args, message", [
    (["rnu", str(PENDULUM)], "unknown subcommand 'rnu' of `rigid`; did you mean 'run'?"),
    (["mesh", "chek", "x.stl"], "unknown subcommand 'chek' of `rigid mesh`; did you mean 'check'?"),
    (["run", str(PENDULUM), "--integrater", "rk4"],
     "unknown option '--integrater' for `rigid run`; did you mean '--integrator'?"),
    (["rotation", "--euler", "1,2,3", "--convnetion", "ZYX"],
     "unknown option '--convnetion' for `rigid rotation`; did you mean '--convention'?"),
    (["run", str(PENDULUM), "--integrator", "rk5"],
     "--integrator: unknown integrator 'rk5'; did you mean 'rk4'?"),
    (["check", str(RACKET), "--integrator", "spliting4"], "did you mean 'splitting4'?"),
    (["run", str(PENDULUM), "--format", "cvs"], "did you mean 'csv'?"),
    (["eom", str(PENDULUM), "--format", "latx"], "did you mean 'latex'?"),
    (["inertia", "sphere", "--radius", "1", "--mass", "1", "--format", "jsn"], "did you mean 'json'?"),
    (["inertia", "sphere", "--radius", "1", "--mass", "1", "--frame", "principle"],
     "did you mean 'principal'?"),
    (["inertia", "sphere", "--radius", "1", "--mass", "1", "--about", "comm"], "did you mean 'com'?"),
    (["inertia", "x.stl", "--units", "mmm", "--mass", "1"], "--units: unknown unit 'mmm'"),
    (["mesh", "check", "x.stl", "--units", "cn"], "did you mean 'cm'?"),
    (["inertia", "fix", "m.urdf", "--from", "colision"], "did you mean 'collision'?"),
    (["rotation", "--euler", "1,2,3", "--unit", "degs"], "did you mean 'deg'?"),
    (["rotation", "--euler", "1,2,3", "--convention", "ZYXX"], "did you mean 'ZYX'?"),
    (["run", str(PENDULUM), "--max-memory", "12XB"], "--max-memory: memory size '12XB' is not a size"),
    (["run", str(PENDULUM), "--report-frames", "10"], "give --report with it"),
])
def test_bad_option_values_are_usage_errors_with_a_guess(run, args, message):
    proc = run(*args, check=False)
    assert proc.returncode == 2, proc.stderr
    assert message in proc.stderr
    assert proc.stdout == ""


def test_help_states_the_usage_status_of_a_bad_option_value(run):
    out = run("--help", check=True).stdout
    assert "2 usage (an unknown subcommand or option, a missing or conflicting option, an option value" in out


def test_a_refused_input_is_status_1_and_names_exact_for_free_bodies(run):
    # a name of the other scene kind is a value the scene refuses (1), with its kind's list
    proc = run("check", RACKET, "--set", "simulation.integrator=dopri5", check=False)
    assert proc.returncode == 1
    assert "expected one of exact (closed form, no pivot), rk4, splitting2" in proc.stderr
    proc = run("check", RACKET, "--set", "simulation.integrator=exat", check=False)
    assert proc.returncode == 1 and "did you mean 'exact'?" in proc.stderr
    proc = run("check", PENDULUM, "--set", "simulation.integrator=dopri", check=False)
    assert proc.returncode == 1 and "did you mean 'dopri5'?" in proc.stderr


# --- 4. messages ----------------------------------------------------------------------------

BOX_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
BOX_F = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5),
         (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def write_off(path, vertices, faces):
    path.write_text(f"OFF\n{len(vertices)} {len(faces)} 0\n"
                    + "".join(f"{x} {y} {z}\n" for x, y, z in vertices)
                    + "".join(f"3 {a} {b} {c}\n" for a, b, c in faces))
    return path


def test_components_are_listed_where_they_are_mentioned(run, tmp_path):
    # two unit cubes 2 m apart: `rigid inertia` lists no components of its own
    v = BOX_V + [(x + 2, y, z) for x, y, z in BOX_V]
    f = BOX_F + [(a + 8, b + 8, c + 8) for a, b, c in BOX_F]
    proc = run("inertia", write_off(tmp_path / "two.off", v, f), "--density", 1000, check=True)
    assert ("2 separate components (1: 12 triangles, volume 1 m³; 2: 12 triangles, volume 1 m³); "
            "their volumes add") in proc.stderr
    assert "listed above" not in proc.stderr


def test_counts_are_singular_for_one(run, tmp_path):
    proc = run("run", PENDULUM, "--set", "simulation.t_end=0.01", "-o", tmp_path / "o", check=True)
    assert "generalized-coordinate scene, 1 body\n" in proc.stdout
    urdf = tmp_path / "one.urdf"
    urdf.write_text('<robot name="r"><link name="flat"><inertial><mass value="1"/>'
                    '<inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="4"/></inertial></link></robot>\n')
    proc = run("inertia", "check", urdf, check=False)
    assert proc.returncode == 1
    assert f"1 of 1 inertial in {urdf} is invalid" in proc.stderr


def test_no_cpp_function_name_reaches_the_command_line(run, tmp_path):
    # a closed but inside-out cube: flipped by repair; a flat closed "pillow" has no volume
    flat = write_off(tmp_path / "flat.off", [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2), (0, 2, 1)])
    proc = run("inertia", flat, "--density", 1000, check=False)
    assert proc.returncode == 1 and "volume" in proc.stderr
    assert "repair_mesh" not in proc.stderr


def test_help_says_primitives_take_tolerance(run):
    out = run("inertia", "--help", check=True).stdout
    assert "primitives take it" in out and "mesh files" in out


# --- 5. a shell's amount ----------------------------------------------------------------------

def open_box(tmp_path):
    return write_off(tmp_path / "cover.off", BOX_V, BOX_F[:-1])  # 5.5 m² of sheet, 3 open edges


def test_shell_density_without_thickness_is_refused_with_both_remedies(run, tmp_path):
    # was 7850 taken as kg/m² (97 kg for a sheet-metal cover), then a warning "use --shell"
    proc = run("inertia", open_box(tmp_path), "--shell", "--density", 7850, check=False)
    assert proc.returncode == 2
    assert "--shell with --density 7850 needs --thickness" in proc.stderr
    assert "--areal-density 7850 (kg/m²)" in proc.stderr


def test_shell_with_thickness_and_areal_density(run, tmp_path):
    cover = open_box(tmp_path)
    proc = run("inertia", cover, "--shell", "--thickness", 0.002, "--density", 7850, "--format", "json",
               check=True)
    # m = ρ t A = 7850 × 0.002 × 5.5 (rounding of three products: 1e-12 relative)
    assert json.loads(proc.stdout)["mass"] == pytest.approx(7850 * 0.002 * 5.5, rel=1e-12)
    assert "--shell" not in proc.stderr and "warning" not in proc.stderr
    proc = run("inertia", cover, "--areal-density", 15.7, "--format", "json", check=True)
    assert json.loads(proc.stdout)["mass"] == pytest.approx(15.7 * 5.5, rel=1e-12)
    assert "warning" not in proc.stderr


def test_a_shell_whose_holes_cannot_be_filled_is_not_told_to_use_shell(run, tmp_path):
    # two triangles meeting at one vertex: the boundary through it is not a simple loop, so
    # --fill-holes refuses it; the remedy said "use --shell" to a shell (and named repair_mesh,
    # which the command had run). It now fits both: a shell without --fill-holes.
    bowtie = write_off(tmp_path / "bowtie.off",
                       [(0, 0, 0), (1, 0, 0), (0, 1, 0), (-1, 0, 0), (0, -1, 0)],
                       [(0, 1, 2), (0, 3, 4)])
    for given in (["--shell", "--thickness", 0.002, "--density", 7850], ["--areal-density", 1],
                  ["--density", 7850]):
        proc = run("inertia", bowtie, *given, "--fill-holes", check=False)
        assert proc.returncode == 1, proc.stderr
        assert ("only simple holes can be filled: measure the open mesh as a thin shell (--shell "
                "without --fill-holes)") in proc.stderr
        assert "use --shell" not in proc.stderr and "repair_mesh" not in proc.stderr
    # and the shell is measured as advised: two unit right triangles, 1 m² at 1 kg/m²
    proc = run("inertia", bowtie, "--areal-density", 1, "--format", "json", check=True)
    assert json.loads(proc.stdout)["mass"] == pytest.approx(1.0, rel=1e-15)


def test_implausible_areal_density_is_warned_without_suggesting_given_options(run, tmp_path):
    proc = run("inertia", open_box(tmp_path), "--areal-density", 7850, "--format", "json", check=True)
    assert json.loads(proc.stdout)["mass"] == pytest.approx(7850 * 5.5, rel=1e-12)
    assert "the areal density 7850 kg/m² is outside real sheets and plates (0.01 to 1000 kg/m²" in proc.stderr
    assert "give the wall thickness" in proc.stderr
    assert "--shell" not in proc.stderr and "--areal-density" not in proc.stderr


def test_areal_density_conflicts_are_usage_errors(run, tmp_path):
    cover = open_box(tmp_path)
    proc = run("inertia", cover, "--areal-density", 15.7, "--thickness", 0.002, check=False)
    assert proc.returncode == 2 and "would count the wall twice" in proc.stderr
    proc = run("inertia", cover, "--areal-density", 15.7, "--density", 7850, check=False)
    assert proc.returncode == 2 and "give exactly one of --mass" in proc.stderr
