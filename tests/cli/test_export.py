"""Code export: `rigid eom SCENE --emit c++|python`, rigid.Scene.emit and
rigid.lagrange.System.emit. The exported Python module is imported and compared with the
engine (M, f, G, γ); the command line and Python give the same bytes and the same refusals."""
import importlib.util
import keyword
import math
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
WITH_COORDINATES = ["atwood", "cone_pendulum", "double_pendulum", "physical_pendulum",
                    "rolling_cylinder", "rolling_sphere", "rolling_tube", "sleeping_top",
                    "stiff_dumbbell"]
# examples with velocity constraints: refused (the export holds the holonomic rows only)
WITH_VELOCITY_CONSTRAINTS = ["chaplygin_sleigh", "rolling_disk"]


def import_file(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def samples(system):
    """States around the initial one, as the C++ test takes them."""
    n = len(system.coordinate_names)
    for k in range(5):
        q = np.array([0.4 * math.sin(1.3 * i + 0.9 * k + 0.2) for i in range(n)])
        qd = np.array([0.7 * math.cos(2.1 * i - 0.5 * k) for i in range(n)])
        yield q, qd, 0.37 * k


def close(a, b):
    """The same operations in the same order as the engine: equal to the last bit on one
    platform; 16 ulps of the largest entry (at least 1) allow another libm's last bit."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape
    scale = max(1.0, float(np.max(np.abs(b)))) if b.size else 1.0
    np.testing.assert_allclose(a, b, rtol=0, atol=16 * np.finfo(float).eps * scale)


@pytest.mark.parametrize("example", WITH_COORDINATES)
def test_exported_python_computes_the_engines_numbers(example, run, tmp_path):
    scene = EXAMPLES / f"{example}.toml"
    out = tmp_path / f"{example}_eom.py"
    run("eom", scene, "--emit", "python", "-o", out, check=True)
    eom = import_file(out, f"{example}_eom")
    system = rigid.Scene(scene).system
    assert list(eom.COORDINATES) == system.coordinate_names
    assert list(eom.CONSTRAINTS) == system.constraint_names
    for q, qd, t in samples(system):
        M, f = system.mass_matrix_and_forces(t, q, qd)
        G, gamma = system.constraint_terms(t, q, qd)
        close(eom.mass_matrix(q, t), M)
        close(eom.forces(q, qd, t), f)
        Me, fe = eom.mass_matrix_and_forces(q, qd, t)
        close(Me, M)
        close(fe, f)
        m = len(system.constraint_names)
        close(np.reshape(eom.constraint_jacobian(q, t), (m, len(q))), G)
        close(eom.constraint_gamma(q, qd, t), gamma)


def test_parameters_are_keyword_arguments_with_the_scenes_defaults(run, tmp_path):
    scene = EXAMPLES / "double_pendulum.toml"
    out = tmp_path / "dp.py"
    run("eom", scene, "--emit", "python", "-o", out, check=True)
    eom = import_file(out, "dp")
    assert eom.PARAMETERS == rigid.Scene(scene).parameters
    q, qd = [0.3, -0.2], [0.0, 0.0]
    # with q̇ = 0, f = −∂V/∂q and V ∝ g: doubling g doubles f exactly (binary scaling)
    assert eom.forces(q, qd, g=2 * 9.81) == [2 * v for v in eom.forces(q, qd)]
    # the engine with the same override (--set on the command line, set= in Python)
    system = rigid.Scene(scene, set=["g=19.62"]).system
    _, f = system.mass_matrix_and_forces(0.0, np.array(q), np.array(qd))
    close(eom.forces(q, qd, g=19.62), f)
    with pytest.raises(ValueError, match="q needs 2 values"):
        eom.mass_matrix([0.1])


def test_command_line_and_python_give_the_same_bytes(run):
    for example in ["atwood", "double_pendulum"]:
        scene = EXAMPLES / f"{example}.toml"
        model = rigid.Scene(scene)
        for language in ["c++", "python"]:
            first = run("eom", scene, "--emit", language, check=True).stdout
            second = run("eom", scene, "--emit", language, check=True).stdout
            assert first == second  # deterministic
            assert first == model.emit(language)
    # System.emit: the same code for the same model (the namespace named as asked)
    system = rigid.Scene(EXAMPLES / "atwood.toml").system
    # (the scene's file is named in the first line)
    by_scene = rigid.Scene(EXAMPLES / "atwood.toml").emit("python")
    assert by_scene.startswith(f"# Equations of motion of {EXAMPLES / 'atwood.toml'},")
    assert system.emit("python").split("\n", 1)[1] == by_scene.split("\n", 1)[1]
    assert "namespace atwood {" in system.emit("c++", name="atwood")


def test_written_file_and_namespace_from_its_name(run, tmp_path):
    out = tmp_path / "pendulum_eom.hpp"
    proc = run("eom", EXAMPLES / "physical_pendulum.toml", "--emit", "c++", "-o", out, check=True)
    assert proc.stdout == ""
    text = out.read_text()
    assert "namespace pendulum_eom {" in text
    assert text.count("#include") == 1 and "#include <cmath>" in text


def test_unknown_language_is_refused_with_a_close_match(run):
    proc = run("eom", EXAMPLES / "double_pendulum.toml", "--emit", "pyhton", check=False)
    assert proc.returncode == 2
    assert "--emit: unknown export language 'pyhton'; expected c++ or python; did you mean 'python'?" in proc.stderr
    with pytest.raises(rigid.Error, match="unknown export language 'pyhton'; expected c\\+\\+ or python; did you mean 'python'"):
        rigid.Scene(EXAMPLES / "double_pendulum.toml").emit("pyhton")
    with pytest.raises(rigid.Error, match="did you mean 'c\\+\\+'"):
        rigid.Scene(EXAMPLES / "double_pendulum.toml").system.emit("c+")


def test_free_bodies_are_refused_with_a_reason(run, tmp_path):
    out = tmp_path / "racket.py"
    proc = run("eom", EXAMPLES / "tennis_racket.toml", "--emit", "python", "-o", out, check=False)
    assert proc.returncode == 1
    assert "code export needs generalized coordinates" in proc.stderr
    assert "tennis_racket.toml" in proc.stderr
    assert not out.exists()
    with pytest.raises(rigid.Error, match="code export needs generalized coordinates"):
        rigid.Scene(EXAMPLES / "tennis_racket.toml").emit("python")


def test_output_needs_emit_and_latex_excludes_it(run, tmp_path):
    scene = EXAMPLES / "double_pendulum.toml"
    proc = run("eom", scene, "-o", tmp_path / "x.py", check=False)
    assert proc.returncode == 2 and "--emit" in proc.stderr
    proc = run("eom", scene, "--emit", "python", "--latex", check=False)
    assert proc.returncode == 1 and "use one" in proc.stderr


@pytest.mark.parametrize("example", WITH_VELOCITY_CONSTRAINTS)
def test_velocity_constraints_are_refused_not_left_out(run, tmp_path, example):
    out = tmp_path / "eom.hpp"
    proc = run("eom", EXAMPLES / f"{example}.toml", "--emit", "c++", "-o", out, check=False)
    assert proc.returncode == 1
    assert "the system has velocity constraints" in proc.stderr
    assert not out.exists()
    with pytest.raises(rigid.Error, match="the system has velocity constraints"):
        rigid.Scene(EXAMPLES / f"{example}.toml").emit("python")


# the 3-joint robot (a prismatic and two hinges) and the examples without constraints: their
# export holds inverse_dynamics and forward_dynamics
WITH_DYNAMICS = ["cart_arm.urdf", "double_pendulum.toml", "cone_pendulum.toml",
                 "physical_pendulum.toml", "stiff_dumbbell.toml"]


def random_states(system, seed, count=8):
    """Random (q, q̇, q̈, t) about the initial q: |Δq| ≤ 1, |q̇| ≤ 2, |q̈| ≤ 3, t in [0, 2]."""
    rng = np.random.default_rng(seed)
    n = len(system.coordinate_names)
    for _ in range(count):
        yield (np.asarray(system.initial_q) + rng.uniform(-1, 1, n), rng.uniform(-2, 2, n),
               rng.uniform(-3, 3, n), rng.uniform(0, 2))


@pytest.mark.parametrize("scene", WITH_DYNAMICS)
def test_exported_python_inverse_and_forward_dynamics(scene, run, tmp_path):
    out = tmp_path / "dyn_eom.py"
    run("eom", EXAMPLES / scene, "--emit", "python", "-o", out, check=True)
    eom = import_file(out, "dyn_eom")
    system = rigid.Scene(EXAMPLES / scene).system
    assert not system.constraint_names
    for q, qd, qdd, t in random_states(system, seed=len(scene)):
        M, f = (np.asarray(a) for a in eom.mass_matrix_and_forces(q, qd, t))
        tau = np.asarray(eom.inverse_dynamics(q, qd, qdd, t))
        # τ = M q̈ − f from the exported M and f: sums in another order, a few ulps of the scale
        scale = np.linalg.norm(M) * np.linalg.norm(qdd) + np.linalg.norm(f)
        assert np.linalg.norm(tau - (M @ qdd - f)) < 1e-12 * scale
        # q̈ back from τ (a Cholesky solve after τ + f: round-off of ε cond(M) (1 + |f|/|M q̈|),
        # cond(M) < 300 here, the largest seen 5e-13 with stiff_dumbbell's spring force)
        back = np.asarray(eom.forward_dynamics(q, qd, tau, t))
        assert np.linalg.norm(back - qdd) < 1e-10 * np.linalg.norm(qdd)
        # at τ = 0, the engine's q̈ (its own solve of M q̈ = f)
        engine, _ = system.accelerations(t, q, qd)
        forward = np.asarray(eom.forward_dynamics(q, qd, np.zeros(len(q)), t))
        assert np.linalg.norm(forward - engine) < 1e-10 * max(1.0, np.linalg.norm(engine))


def test_exported_dynamics_run_without_numpy_and_match_the_cpp_arithmetic(run, tmp_path):
    # the module on its own: an isolated interpreter without site-packages (no numpy) runs the
    # round trip; the same operations in the same order as the C++ export give these numbers
    out = tmp_path / "cart_arm_eom.py"
    run("eom", EXAMPLES / "cart_arm.urdf", "--emit", "python", "-o", out, check=True)
    script = (f"import sys; sys.path.insert(0, {str(tmp_path)!r}); import cart_arm_eom as e\n"
              "q, qd, qdd = [0.2, 0.5, -0.7], [0.3, -1.0, 2.0], [1.0, -2.0, 0.5]\n"
              "tau = e.inverse_dynamics(q, qd, qdd)\n"
              "print(repr(tau)); print(repr(e.forward_dynamics(q, qd, tau)))\n"
              "print('numpy' in sys.modules)\n")
    proc = subprocess.run([sys.executable, "-I", "-S", "-c", script], capture_output=True,
                          text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    tau_line, back_line, numpy_loaded = proc.stdout.splitlines()
    assert numpy_loaded == "False"
    back = [float(v) for v in back_line.strip("[]").split(",")]
    # cart_arm's M is well conditioned at this q: the round trip to 1e-12 of |q̈| ≈ 2.3
    np.testing.assert_allclose(back, [1.0, -2.0, 0.5], rtol=0, atol=1e-12)
    assert len(tau_line.strip("[]").split(",")) == 3


def test_forward_dynamics_raises_where_the_mass_matrix_is_not_positive_definite(run, tmp_path):
    out = tmp_path / "dp_dyn.py"
    run("eom", EXAMPLES / "double_pendulum.toml", "--emit", "python", "-o", out, check=True)
    eom = import_file(out, "dp_dyn")
    q, qd, tau = [0.3, -0.2], [0.1, 0.4], [1.0, -1.0]
    # massless bobs: M = 0, the first pivot is 0; m1 = −3: M[0][0] = (m1 + m2) l1² = −2
    with pytest.raises(ValueError, match=r"pivot 0 \(theta1\) of its Cholesky factorization is 0.0, expected > 0"):
        eom.forward_dynamics(q, qd, tau, m1=0.0, m2=0.0)
    with pytest.raises(ValueError, match="not positive definite"):
        eom.forward_dynamics(q, qd, tau, m1=-3.0)
    with pytest.raises(ValueError, match="tau needs 2 values"):
        eom.forward_dynamics(q, qd, [1.0])
    with pytest.raises(ValueError, match="q_ddot needs 2 values"):
        eom.inverse_dynamics(q, qd, [1.0, 2.0, 3.0])


@pytest.mark.parametrize("language", ["c++", "python"])
def test_a_system_with_constraints_exports_no_dynamics_and_says_why(run, language):
    # atwood.toml: two holonomic constraints (the ropes), whose multipliers enter M q̈ = f + τ + Gᵀλ
    code = run("eom", EXAMPLES / "atwood.toml", "--emit", language, check=True).stdout
    assert "inverse_dynamics(" not in code and "forward_dynamics(" not in code
    assert "inverse_dynamics and forward_dynamics are not exported: the system has constraints (m = 2)" in code


# ------------------------------------------------------------------------------------------
# names: the exported code builds and runs whatever the scene's names (docs/lagrange.md,
# "Names"). Every C++20 keyword and alternative token, C's keywords, the compiler's
# predefined and <cmath>'s object-like macros (read from the compiler), Python's keywords,
# soft keywords and the builtins the module calls, and the names the files use themselves.
CPP_KEYWORDS = """alignas alignof and and_eq asm auto bitand bitor bool break case catch char
    char8_t char16_t char32_t class compl concept const consteval constexpr constinit const_cast
    continue co_await co_return co_yield decltype default delete do double dynamic_cast else enum
    explicit export extern false float for friend goto if inline int long mutable namespace new
    noexcept not not_eq nullptr operator or or_eq private protected public register
    reinterpret_cast requires return short signed sizeof static static_assert static_cast struct
    switch template this thread_local throw true try typedef typeid typename union unsigned using
    virtual void volatile wchar_t while xor xor_eq final override import module atomic_cancel
    atomic_commit atomic_noexcept synchronized reflexpr transaction_safe typeof""".split()
C_KEYWORDS = """restrict typeof_unqual _Alignas _Alignof _Atomic _Bool _Complex _Generic _Imaginary
    _Noreturn _Static_assert _Thread_local _BitInt _Decimal32 _Pragma""".split()
# system macros of GCC and Clang on Linux targets (x86-32, MIPS, SPARC, ...; gnu modes)
SYSTEM_MACROS = ["linux", "i386", "mips", "sparc", "sun", "vax", "m68k", "hppa"]
PYTHON_WORDS = sorted(set(keyword.kwlist + keyword.softkwlist) - {"_"}) + [
    "_", "type", "float", "range", "len", "math", "ValueError", "print", "list"]
# the exported files' own names: arguments, locals, helpers, functions, types
FILE_NAMES = """q q_dot q_ddot tau M f G gamma p n L b s d l i j k v x std detail pow_int
    Parameters kNumCoordinates kNumConstraints kCoordinateNames mass_matrix forces
    mass_matrix_and_forces constraint_jacobian constraint_gamma inverse_dynamics forward_dynamics
    main COORDINATES CONSTRAINTS PARAMETERS PARAMETER_NAMES _vector _pow_int _q _qd _qdd _tau _M
    _f _v0 _v1 _mass_matrix_and_forces _inverse_dynamics _forward_dynamics p_v0 float_ sin_
    model_""".split()
# the coordinates' names: written as strings only, so kept
COORDINATES = ["lambda", "unix"]


def object_like_macros(std):
    """The object-like macros of the compiler and <cmath> in `std` (g++ -dM)."""
    out = subprocess.run(["g++", f"-std={std}", "-dM", "-E", "-x", "c++", "-"],
                         input="#include <cmath>\n", capture_output=True, text=True, check=True)
    names = set()
    for line in out.stdout.splitlines():
        name = line.split()[1]
        if "(" not in name:
            names.add(name)
    return names


def keyword_scene(tmp_path, names):
    """A ball at (x, y, 0) = (lambda, unix + 0.1 sin(lambda)) under gravity −g ŷ, pushed along
    unix by Q = Σ cₖ nameₖ with weights cₖ: every parameter enters f, each once (a product
    of their sum with the coordinates' terms would multiply the exported code's size)."""
    lines = ["gravity = [0, \"-g\", 0]", "[parameters]", "g = 9.81"]
    push = []
    for k, name in enumerate(names):
        lines.append(f"{name} = {0.5 + 0.001 * k!r}")
        push.append(f"{1 + k % 7}e-3*{name}")
    for c in COORDINATES:
        lines += ["[[coordinates]]", f"name = \"{c}\"", "initial = 0.2", "velocity = 0.1"]
    lines += ["[[bodies]]", "name = \"ball\"", "primitive = \"solid_sphere\"", "radius = 0.1",
              "mass = 1.5", "position = [\"lambda\", \"unix + 0.1*sin(lambda)\", 0]",
              "[[forces]]", "coordinate = \"unix\"", f"expression = \"{' + '.join(push)}\"",
              "[simulation]", "t_end = 1.0"]
    scene = tmp_path / "names.toml"
    scene.write_text("\n".join(lines) + "\n")
    return scene


def test_exported_code_builds_and_runs_whatever_the_names(run, tmp_path):
    macros = object_like_macros("c++20") | object_like_macros("gnu++20")
    names = sorted(set(CPP_KEYWORDS + C_KEYWORDS + SYSTEM_MACROS + PYTHON_WORDS + FILE_NAMES) | macros)
    # g is the scene's gravity, t is time, the coordinates are named below
    names = [n for n in names if n not in ["g", "t"] + COORDINATES]
    scene = keyword_scene(tmp_path, names)
    # the scene takes every name as a parameter (the export's input): all of them, by name
    model = rigid.Scene(scene)
    assert sorted(model.parameters) == sorted(names + ["g"])
    system = model.system
    assert system.coordinate_names == COORDINATES

    # C++: written as main.hpp (its namespace is then not `main`), built with int main() in
    # both dialects (gnu++20 predefines linux and unix), M and f at two states printed
    hpp = tmp_path / "main.hpp"
    run("eom", scene, "--emit", "c++", "-o", hpp, check=True)
    text = hpp.read_text()
    assert "namespace main_ {" in text
    # renamed: keywords and macros take '_', names starting with '_' a 'p'; listed up top
    # (float_ is a parameter of its own: float takes two)
    for old, new in [("float", "float__"), ("linux", "linux_"), ("i386", "i386_"), ("M_PI", "M_PI_"), ("_Complex", "p_Complex"),
                     ("__linux__", "p__linux__"), ("Parameters", "Parameters_"),
                     ("typeof", "typeof_")]:
        assert f"  double {new} = " in text, (old, new)
        assert f" {old} → {new}" in text
    assert " main → main_." in text.split("#pragma once")[0]
    # kept: names that C++ reads as p.name (no macro or keyword there)
    for kept in ["float_", "q", "tau", "M", "std", "mass_matrix", "math", "range", "None"]:
        assert f"  double {kept} = " in text, kept
    source = tmp_path / "use.cpp"
    source.write_text(
        "#include <cstdio>\n#include \"main.hpp\"\n"
        "int main() {\n"
        "  const double q[2] = {0.3, -0.4}, qd[2] = {0.7, 1.1};\n"
        "  double M[4], f[2];\n"
        "  main_::mass_matrix_and_forces(q, qd, 0.0, M, f);\n"
        "  for (double v : M) std::printf(\"%.17g\\n\", v);\n"
        "  for (double v : f) std::printf(\"%.17g\\n\", v);\n"
        "  main_::mass_matrix_and_forces(q, qd, 0.0, M, f, {.linux_ = 2.5});\n"
        "  for (double v : M) std::printf(\"%.17g\\n\", v);\n"
        "  for (double v : f) std::printf(\"%.17g\\n\", v);\n"
        "}\n")
    q, qd = np.array([0.3, -0.4]), np.array([0.7, 1.1])
    M0, f0 = system.mass_matrix_and_forces(0.0, q, qd)
    M1, f1 = rigid.Scene(scene, set=["linux=2.5"]).system.mass_matrix_and_forces(0.0, q, qd)
    # the override moves Q by its weight times the change (round-off of the sum, ~1e-15 of
    # |Q| ≈ 3, against a change of ~1e-3: rel 1e-9 is ample)
    k = names.index("linux")
    assert f1[1] - f0[1] == pytest.approx((1 + k % 7) * 1e-3 * (2.5 - (0.5 + 0.001 * k)), rel=1e-9)
    for std in ["c++20", "gnu++20"]:
        exe = tmp_path / f"use_{std}"
        build = subprocess.run(["g++", f"-std={std}", "-Wall", "-Wextra", "-Werror", "-O1",
                                "-o", exe, source], capture_output=True, text=True, timeout=120)
        assert build.returncode == 0, build.stderr[:4000]
        values = [float(v) for v in subprocess.run([exe], capture_output=True, text=True,
                                                    check=True).stdout.split()]
        close(np.reshape(values[0:4], (2, 2)), M0)
        close(values[4:6], f0)
        close(np.reshape(values[6:10], (2, 2)), M1)
        close(values[10:12], f1)

    # Python: keyword arguments under the module's names, run and compared with the engine
    py = tmp_path / "names_eom.py"
    run("eom", scene, "--emit", "python", "-o", py, check=True)
    eom = import_file(py, "names_eom")
    renames = eom.PARAMETER_NAMES
    assert list(eom.COORDINATES) == COORDINATES
    for old, new in [("float", "float__"), ("float_", "float_"), ("None", "None_"),
                     ("range", "range_"), ("match", "match_"), ("q_ddot", "q_ddot_"), ("_", "p_"),
                     ("_vector", "p_vector"), ("_Complex", "p_Complex"), ("_v0", "p_v0_")]:
        assert renames[old] == new
    assert renames["linux"] == "linux" and renames["M"] == "M"  # not reserved in Python
    assert len(set(renames.values())) == len(renames)  # distinct
    for new in renames.values():
        assert new.isidentifier() and not keyword.iskeyword(new) and not new.startswith("_")
    close(eom.mass_matrix(q), M0)
    M, f = eom.mass_matrix_and_forces(q, qd)
    close(M, M0)
    close(f, f0)
    M, f = eom.mass_matrix_and_forces(q, qd, **{renames["linux"]: 2.5})
    close(M, M1)
    close(f, f1)
    # the dynamics functions call the module's helpers past every keyword argument
    tau = eom.inverse_dynamics(q, qd, [0.5, -1.0])
    close(eom.forward_dynamics(q, qd, tau), [0.5, -1.0])


def test_the_namespace_is_never_a_name_beside_it(tmp_path):
    # the namespace sits at global scope beside <cmath>'s declarations, its macros and main():
    # every identifier of the preprocessed <cmath> and every object-like macro, tried as a
    # namespace there, gives the names the compiler refuses (the export must rename them)
    pre = subprocess.run(["g++", "-std=gnu++20", "-E", "-x", "c++", "-"], input="#include <cmath>\n",
                         capture_output=True, text=True, check=True).stdout
    ids = set()
    for line in pre.splitlines():
        if not line.startswith("#"):
            ids.update(re.findall(r"\b[A-Za-z][A-Za-z0-9_]*\b", line))
    ids |= {m for m in object_like_macros("gnu++20") if not m.startswith("_")}
    ids = sorted(ids - set(CPP_KEYWORDS + C_KEYWORDS))  # keywords: refused by the parser alone
    probe = tmp_path / "probe.cpp"
    probe.write_text("#include <cmath>\n" + "".join(f"namespace {w} {{}}\n" for w in ids))
    errors = subprocess.run(["g++", "-std=gnu++20", "-fsyntax-only", "-fmax-errors=0", probe],
                            capture_output=True, text=True).stderr
    lines = {int(m) for m in re.findall(rf"^{re.escape(str(probe))}:(\d+):\d+: error", errors, re.M)}
    clashes = sorted({ids[line - 2] for line in lines if 2 <= line < len(ids) + 2})
    assert {"sin", "expf", "div", "random", "size_t", "M_PI", "linux", "NULL"} <= set(clashes)

    system = rigid.Scene(EXAMPLES / "physical_pendulum.toml").system
    names = clashes + ["main", "std", "float", "_Foo", "__x", "2d", "my-model", ""]
    spaces = {}
    for name in names:
        ns = re.search(r"^namespace (\w+) \{$", system.emit("c++", name=name), re.M).group(1)
        assert ns != name
        spaces[name] = ns
    assert spaces["sin"] == "sin_" and spaces["main"] == "main_" and spaces["_Foo"] == "p_Foo"
    assert spaces["my-model"] == "my_model" and spaces["2d"] == "model_2d"
    # the new names build beside <cmath> and main(), in both dialects
    probe.write_text("#include <cmath>\n" +
                     "".join(f"namespace {ns} {{ inline int k = 1; }}\n" for ns in set(spaces.values())) +
                     "int main() { return sin_::k - 1; }\n")
    for std in ["c++20", "gnu++20"]:
        build = subprocess.run(["g++", f"-std={std}", "-Wall", "-Werror", "-fsyntax-only", probe],
                               capture_output=True, text=True)
        assert build.returncode == 0, build.stderr[:4000]
