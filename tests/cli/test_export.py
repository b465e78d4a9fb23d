"""Code export: `rigid eom SCENE --emit c++|python`, rigid.Scene.emit and
rigid.lagrange.System.emit. The exported Python module is imported and compared with the
engine (M, f, G, γ); the command line and Python give the same bytes and the same refusals."""
import importlib.util
import math
import pathlib
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
