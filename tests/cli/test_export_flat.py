"""The flat C++ layout of the code export (`rigid eom MODEL --emit c++ --flat`): the dynamics
as robot code calls them. The exported file is compiled with g++ and clang++ (-O2 -Wall
-Wextra -Werror) and its numbers are compared with rigid.robot.Robot, an independent numeric
implementation (recursive Newton–Euler and composite rigid bodies in numbers, not symbols),
and with central differences of the exported functions themselves."""
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"

# A driver: per line of stdin "q q_dot q_ddot tau" (nq + 3 nv numbers), one line of every output.
DRIVER = r"""
#include <cstdio>
#include <initializer_list>
#include "model.hpp"
int main() {
  double q[nq], v[nv], a[nv], tau[nv];
  for (;;) {
    for (double* x : {q, v, a, tau}) {
      for (int i = 0; i < (x == q ? nq : nv); ++i) {
        if (std::scanf("%lf", &x[i]) != 1) return 0;
      }
    }
    double M[nv * nv], t[nv], b[nv], A[nv * nv], B[nv * nv], C[nv * nv], D[nv * nv],
        E[nv * nv], F[nv * nv], b2[nv];
    mass_matrix(q, M);
    inverse_dynamics(q, v, a, t);
    forward_dynamics(q, v, tau, b);
    inverse_dynamics_derivatives(q, v, a, A, B, C);
    forward_dynamics_derivatives(q, v, tau, b2, D, E, F);
    for (const double* x : {M, A, B, C, D, E, F}) {
      for (int i = 0; i < nv * nv; ++i) std::printf("%.17g ", x[i]);
    }
    for (const double* x : {t, b, b2}) {
      for (int i = 0; i < nv; ++i) std::printf("%.17g ", x[i]);
    }
    std::printf("\n");
  }
}
"""


def build(tmp_path, model, compiler, *options):
    """Exports `model` flat (with the CLI's `options`), compiles the driver with `compiler`;
    returns the program."""
    header = tmp_path / "model.hpp"
    subprocess.run([rigid_exe(), "eom", str(model), "--emit", "c++", "--flat", *options, "-o", str(header)],
                   check=True)
    source = tmp_path / "driver.cpp"
    source.write_text(DRIVER)
    program = tmp_path / f"driver_{compiler.replace('+', 'p')}"
    out = subprocess.run([compiler, "-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror",
                          str(source), "-o", str(program)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-3000:]
    return program


def rigid_exe():
    import os
    return os.environ.get("RIGID_EXE", "rigid")


class Flat:
    """The exported functions of one compiled model, called through the driver."""

    def __init__(self, program, nv):
        self.program, self.nv = program, nv

    def __call__(self, states):
        text = "\n".join(" ".join(f"{x:.17g}" for x in np.concatenate(s)) for s in states)
        out = subprocess.run([str(self.program)], input=text + "\n", capture_output=True,
                             text=True, check=True)
        n = self.nv
        results = []
        for line in out.stdout.splitlines():
            x = np.array([float(v) for v in line.split()])
            mats = [x[k * n * n:(k + 1) * n * n].reshape(n, n) for k in range(7)]
            vecs = [x[7 * n * n + k * n:7 * n * n + (k + 1) * n] for k in range(3)]
            names = ["M", "dtau_dq", "dtau_dqd", "dtau_dqdd", "dqdd_dq", "dqdd_dqd", "dqdd_dtau"]
            r = dict(zip(names, mats))
            r.update(tau=vecs[0], qdd=vecs[1], qdd2=vecs[2])
            results.append(r)
        return results


def random_states(robot, count, seed):
    rng = np.random.default_rng(seed)
    q0 = robot.reference_configuration
    n = robot.dof
    return [(q0 + rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(-1, 1, n),
             rng.uniform(-1, 1, n)) for _ in range(count)]


def rel(a, b):
    return np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300)


@pytest.fixture(scope="module")
def arm7(tmp_path_factory):
    if shutil.which("clang++") is None:
        pytest.fail("clang++ is not installed (scripts/install-deps.sh installs clang)")
    tmp = tmp_path_factory.mktemp("arm7_flat")
    model = EXAMPLES / "arm7.urdf"
    programs = {c: build(tmp, model, c) for c in ("g++", "clang++")}
    robot = rigid.robot.Robot(str(model))
    return robot, {c: Flat(p, robot.dof) for c, p in programs.items()}, tmp


def test_arm7_matches_the_numeric_tree(arm7):
    """M, τ and q̈ equal rigid.robot.Robot's (an independent implementation in numbers) to
    1e-12 relative: both are exact, so only rounding separates them (~1e-15 per operation over a
    few hundred operations)."""
    robot, flat, _ = arm7
    states = random_states(robot, 20, 1)
    for compiler, run in flat.items():
        for (q, v, a, tau), r in zip(states, run(states)):
            assert rel(r["M"], robot.mass_matrix(q)) < 1e-12, compiler
            assert rel(r["tau"], robot.inverse_dynamics(q, v, a)) < 1e-12, compiler
            assert rel(r["qdd"], robot.forward_dynamics(q, v, tau)) < 1e-10, compiler
            # the derivatives' q̈ is forward_dynamics', and ∂τ/∂q̈ is M: the same outputs
            assert np.array_equal(r["qdd2"], r["qdd"])
            assert np.array_equal(r["dtau_dqdd"], r["M"])
            # ∂q̈/∂τ = M⁻¹
            assert np.max(np.abs(r["dqdd_dtau"] @ r["M"] - np.eye(robot.dof))) < 1e-10


def central_differences(robot, f, x, h):
    """∂f/∂x by central differences with step h (columns)."""
    cols = []
    for j in range(len(x)):
        e = np.zeros(len(x))
        e[j] = h
        cols.append((f(x + e) - f(x - e)) / (2 * h))
    return np.array(cols).T


def test_arm7_derivatives_match_central_differences(arm7):
    """∂τ/∂(q, q̇) and ∂q̈/∂(q, q̇, τ) against central differences of the numeric tree with a
    step-size study: the error of a central difference is ~h² f''' + ε/h, smallest near
    h ~ 1e-5 (~1e-10 relative); it must reach 1e-6 relative there and shrink as h² from 1e-2 to
    1e-3 (a wrong derivative stays at its error whatever h)."""
    robot, flat, _ = arm7
    check_derivatives(robot, flat["g++"], random_states(robot, 3, 2))


def check_derivatives(robot, run, states):
    """The exported derivatives at `states` against central differences of `robot`, with the
    step-size study of test_arm7_derivatives_match_central_differences."""
    for (q, v, a, tau), r in zip(states, run(states)):
        checks = [
            (r["dtau_dq"], lambda x: robot.inverse_dynamics(x, v, a), q),
            (r["dtau_dqd"], lambda x: robot.inverse_dynamics(q, x, a), v),
            (r["dqdd_dq"], lambda x: robot.forward_dynamics(x, v, tau), q),
            (r["dqdd_dqd"], lambda x: robot.forward_dynamics(q, x, tau), v),
            (r["dqdd_dtau"], lambda x: robot.forward_dynamics(q, v, x), tau),
        ]
        for exact, f, x in checks:
            errors = {h: rel(central_differences(robot, f, x, h), exact)
                      for h in (1e-2, 1e-3, 1e-5)}
            assert errors[1e-5] < 1e-6, errors
            if errors[1e-2] > 1e-9:  # not linear in x (τ is linear in τ: no truncation error)
                assert errors[1e-3] < errors[1e-2] / 30, errors


# A branched tree whose bodies carry several joints (a slide and a hinge on one body, two
# hinges on another, axes not along a frame axis, anchors off the origin), with damping and a
# spring: the closed-form derivatives of the tree (recursive.cpp) meet every case of their
# pairs (a joint above, below, on the same body, on another branch) and the forward-mode
# derivatives of what the joints add.
BRANCHED = """<mujoco model="branched">
  <option gravity="0.3 -0.2 -9.81"/>
  <worldbody>
    <body name="torso" pos="0.1 0 1" quat="0.9 0.1 0.3 0.2">
      <joint name="slide" type="slide" axis="1 0.2 0" damping="0.3"/>
      <joint name="yaw" type="hinge" axis="0 0.1 1" pos="0.05 0 0"/>
      <inertial pos="0.02 0.01 -0.03" mass="3" fullinertia="0.09 0.07 0.05 0.004 -0.003 0.002"/>
      <body name="left" pos="0 0.2 -0.1" quat="0.8 0.2 -0.1 0.3">
        <joint name="lx" type="hinge" axis="1 0 0" pos="0 0 0.02" stiffness="4" springref="0.2"/>
        <joint name="ly" type="hinge" axis="0.3 1 0.1"/>
        <inertial pos="0 0.01 -0.15" mass="1.2" fullinertia="0.02 0.021 0.004 0.001 0.0005 -0.002"/>
        <body name="foot" pos="0.01 0 -0.3">
          <joint name="ankle" type="hinge" axis="0 1 1" pos="0 0.03 0" damping="0.05"/>
          <inertial pos="0.05 0 -0.02" mass="0.4" diaginertia="0.001 0.002 0.0025"/>
        </body>
      </body>
      <body name="right" pos="0 -0.2 -0.1">
        <joint name="rx" type="hinge" axis="0.2 0.1 1" pos="0 -0.01 0.02"/>
        <inertial pos="0.01 -0.02 -0.12" mass="0.9" diaginertia="0.012 0.011 0.003"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_branched_tree_derivatives_match_central_differences(tmp_path):
    model = tmp_path / "branched.xml"
    model.write_text(BRANCHED)
    robot = rigid.robot.Robot(str(model))
    assert robot.dof == 6
    run = Flat(build(tmp_path, model, "g++"), robot.dof)
    states = random_states(robot, 3, 4)
    for (q, v, a, tau), r in zip(states, run(states)):
        assert rel(r["tau"], robot.inverse_dynamics(q, v, a)) < 1e-12
        assert rel(r["qdd"], robot.forward_dynamics(q, v, tau)) < 1e-10
    check_derivatives(robot, run, states)


def test_derivatives_by_column_solves_within_a_stack_bound(arm7, tmp_path):
    """Below 16 n² + 8 n bytes of --max-stack-bytes, forward_dynamics_derivatives solves column by
    column with O(n) stack (the path of a tree of more than 64 degrees of freedom): its numbers
    are the products' to round-off, and everything else is the same code."""
    robot, programs, _ = arm7
    n = robot.dof
    need = 16 * n * n + 8 * n  # M⁻¹ and the product as n × n doubles, and one column
    scene = rigid.Scene(str(EXAMPLES / "arm7.urdf"))
    products = scene.emit("c++", "model", flat=True, max_stack_bytes=need)
    solves = scene.emit("c++", "model", flat=True, max_stack_bytes=need - 1)
    assert "double Mi[" in products and "double Mi[" not in solves
    # 2n columns of −∂τ/∂x and the loop over the n columns of M⁻¹, each a solve along the tree
    assert solves.count("::solve(H, c);") == 2 * n + 1
    assert products == scene.emit("c++", "model", flat=True)  # the default holds n = 7
    run = Flat(build(tmp_path, EXAMPLES / "arm7.urdf", "g++", "--max-stack-bytes", str(need - 1)), n)
    assert (tmp_path / "model.hpp").read_text() == solves  # the CLI and Python agree
    states = random_states(robot, 8, 11)
    for a, b in zip(run(states), programs["g++"](states)):
        for key in ("M", "tau", "qdd", "qdd2", "dtau_dq", "dtau_dqd", "dtau_dqdd"):
            np.testing.assert_array_equal(a[key], b[key], err_msg=key)
        # the same quantities by other sums: a few ulps of the largest entry
        for key in ("dqdd_dq", "dqdd_dqd", "dqdd_dtau"):
            assert rel(a[key], b[key]) < 1e-13, key
    check_derivatives(robot, run, states[:3])
    # the bound is for the flat layout, and a whole number
    with pytest.raises(rigid.Error, match="give flat=True with it"):
        scene.emit("c++", "model", max_stack_bytes=0)
    p = subprocess.run([rigid_exe(), "eom", str(EXAMPLES / "arm7.urdf"), "--emit", "c++", "--max-stack-bytes", "0"],
                       capture_output=True, text=True)
    assert p.returncode == 2 and "--max-stack-bytes requires --flat" in p.stderr
    p = subprocess.run([rigid_exe(), "eom", str(EXAMPLES / "arm7.urdf"), "--emit", "c++", "--flat",
                        "--max-stack-bytes", "-1"], capture_output=True, text=True)
    assert p.returncode == 2 and "--max-stack-bytes -1: the stack bound (bytes) must be a whole number" in p.stderr


def test_flat_export_is_the_same_through_python(arm7):
    """The CLI and rigid.Scene.emit(flat=True) write the same bytes."""
    _, _, tmp = arm7
    scene = rigid.Scene(str(EXAMPLES / "arm7.urdf"))
    assert scene.emit("c++", "model", flat=True) == (tmp / "model.hpp").read_text()


def test_a_scene_with_damping_and_springs(tmp_path):
    """A coordinate scene (its expanded derivation, a dense M, a given damping force): the flat
    τ, q̈ equal the engine's M q̈ − f to 1e-12 (rigid.lagrange.System, the same equations
    evaluated by its tape)."""
    scene_file = EXAMPLES / "double_pendulum.toml"
    header = tmp_path / "model.hpp"
    subprocess.run([rigid_exe(), "eom", str(scene_file), "--emit", "c++", "--flat", "-o",
                    str(header)], check=True)
    source = tmp_path / "driver.cpp"
    source.write_text(DRIVER)
    program = tmp_path / "driver"
    subprocess.run(["g++", "-std=c++17", "-O1", "-Wall", "-Wextra", "-Werror", str(source), "-o",
                    str(program)], check=True)
    system = rigid.Scene(str(scene_file)).system
    n = len(system.coordinate_names)
    rng = np.random.default_rng(3)
    states = [tuple(rng.uniform(-1, 1, n) for _ in range(4)) for _ in range(10)]
    for (q, v, a, tau), r in zip(states, Flat(program, n)(states)):
        M, f = system.mass_matrix_and_forces(0.0, q, v)
        assert rel(r["M"], M) < 1e-12
        assert rel(r["tau"], M @ a - f) < 1e-12
        assert rel(r["qdd"], np.linalg.solve(M, f + tau)) < 1e-10


def test_refusals(tmp_path):
    """--flat needs --emit c++; a system with constraints or explicit time is refused, saying
    why; the same through Python."""
    def eom(*args):
        return subprocess.run([rigid_exe(), "eom", *args], capture_output=True, text=True)

    out = eom(str(EXAMPLES / "arm7.urdf"), "--flat")
    assert out.returncode != 0 and "--emit" in out.stderr
    out = eom(str(EXAMPLES / "arm7.urdf"), "--emit", "python", "--flat")
    assert out.returncode != 0 and "--flat is a layout of the C++ export" in out.stderr
    out = eom(str(EXAMPLES / "atwood.toml"), "--emit", "c++", "--flat")
    assert out.returncode != 0 and "without constraints" in out.stderr, out.stderr
    assert "Traceback" not in out.stderr and "terminate" not in out.stderr
    with pytest.raises(rigid.Error, match="without constraints"):
        rigid.Scene(str(EXAMPLES / "atwood.toml")).emit("c++", flat=True)
    timed = tmp_path / "driven.toml"
    pendulum = (EXAMPLES / "physical_pendulum.toml").read_text()
    timed.write_text(pendulum.replace(
        "[simulation]", '[[forces]]\ncoordinate = "theta"\nexpression = "0.1*sin(t)"\n\n[simulation]'))
    out = eom(str(timed), "--emit", "c++", "--flat")
    assert out.returncode != 0 and "depend on t" in out.stderr, out.stderr


def test_the_same_bytes_on_every_run():
    """The flat export is the same file on every run and through Python (GiNaC orders terms by
    hashes that move with the address space; a system without a tree once came out differently
    on 5 of 6 runs)."""
    for model in ("cart_arm.urdf", "double_pendulum.toml", "arm7.urdf"):
        texts = {subprocess.run([rigid_exe(), "eom", str(EXAMPLES / model), "--emit", "c++",
                                 "--flat"], capture_output=True, check=True).stdout
                 for _ in range(3)}
        assert len(texts) == 1, model
        assert rigid.Scene(str(EXAMPLES / model)).emit("c++", pathlib.Path(model).stem,
                                                       flat=True).encode() == texts.pop(), model


HUMANOID = pathlib.Path("/usr/share/mujoco/model/humanoid/humanoid.xml")


def test_free_root_humanoid_exports_flat_and_compiles_without_warnings(tmp_path):
    """MuJoCo's humanoid on its free root: the flat layout with nq = 28, nv = 27, its velocity
    names, coordinate_rates and the derivatives along the root's tangent, the same bytes through
    the CLI (twice) and Python; it compiles
    with g++ and clang++ under -Wall -Wextra -Werror (tests/robot/exported_floating_base_test.cpp
    compares its numbers with MuJoCo's). The namespaced C++ and the Python export refuse it."""
    assert HUMANOID.exists(), "libmujoco-samples is missing: scripts/install-deps.sh installs it"
    texts = {subprocess.run([rigid_exe(), "eom", str(HUMANOID), "--emit", "c++", "--flat"],
                            capture_output=True, check=True).stdout for _ in range(2)}
    assert len(texts) == 1
    text = texts.pop().decode()
    assert rigid.Scene(str(HUMANOID)).emit("c++", "humanoid", flat=True) == text
    assert "inline constexpr int nq = 28;" in text and "inline constexpr int nv = 27;" in text
    assert 'velocity_names[] = {"root_x_dot", "root_y_dot", "root_z_dot", "root_wx",' in text
    assert "inline void coordinate_rates(" in text
    assert "inline void forward_dynamics_derivatives(" in text and "along its tangent" in text
    header = tmp_path / "humanoid.hpp"
    header.write_text(text)
    source = tmp_path / "use.cpp"
    source.write_text('#include "humanoid.hpp"\nint main() {\n  double q[nq] = {0, 0, 1.5, 1}, v[nv] = {}, '
                      'tau[nv] = {}, a[nv], r[nq];\n  forward_dynamics(q, v, tau, a);\n'
                      '  coordinate_rates(q, v, r);\n  return a[2] < -9 ? 0 : 1;\n}\n')
    for compiler in ("g++", "clang++"):
        out = subprocess.run([compiler, "-std=c++17", "-fsyntax-only", "-Wall", "-Wextra", "-Werror",
                              str(source)], capture_output=True, text=True)
        assert out.returncode == 0, (compiler, out.stderr[-3000:])
    for args in (["--emit", "c++"], ["--emit", "python"]):
        out = subprocess.run([rigid_exe(), "eom", str(HUMANOID), *args], capture_output=True, text=True)
        assert out.returncode == 1 and out.stdout == ""
        assert "the code export of a system with ball coordinates (here 'root'" in out.stderr
        assert "writes the flat C++ layout only (--flat)" in out.stderr


BALL_TREE = pathlib.Path(__file__).resolve().parents[1] / "robot" / "data" / "ball_tree.xml"


def tangent_step(q, names, velocity, h):
    """q moved by h along one velocity: a ball's (`b_wx` …) turns its quaternion as
    q ⊗ exp(h e_k) (the body's own axis k, MuJoCo's tangent); any other (`c_dot`) moves c."""
    q = np.array(q, dtype=float)
    if velocity.endswith(("_wx", "_wy", "_wz")):
        at = names.index(velocity[:-3] + "_qw")
        k = "xyz".index(velocity[-1])
        w, x, y, z = q[at:at + 4]
        c, s = np.cos(h / 2), np.sin(h / 2)
        e = [c, 0.0, 0.0, 0.0]
        e[1 + k] = s
        ew, ex, ey, ez = e
        q[at:at + 4] = [w * ew - x * ex - y * ey - z * ez, w * ex + x * ew + y * ez - z * ey,
                        w * ey - x * ez + y * ew + z * ex, w * ez + x * ey - y * ex + z * ew]
    else:
        q[names.index(velocity[:-len("_dot")])] += h
    return q


def test_ball_coordinates_with_terms_of_the_quaternion(tmp_path):
    """A robot scene on tests/robot/data/ball_tree.xml (balls below a hinge and at the world)
    with a potential and a force that read the balls' quaternions: what the scene adds is
    differentiated in forward mode over q's four entries and taken to the ball's tangent by
    ∂q/∂δθ_k = ½ q ⊗ (0, e_k). The exported ∂τ and ∂q̈ against central differences of its own
    inverse and forward dynamics along that tangent, with check_derivatives' step-size study."""
    scene = tmp_path / "ball_terms.toml"
    scene.write_text(f"""[model]
file = "{BALL_TREE}"

[parameters]
kappa = 3.0
c = 0.4

[[potentials]]
name = "twist"
expression = "kappa*(cup_qx^2 + 2*cup_qy^2 + cup_qz^2) + 0.5*kappa*swing_qz*swing_qw*yaw"

[[forces]]
coordinate = "swing_wy"
expression = "-c*swing_qx*swing_wy + 0.1*cup_qz"
""")
    # a force on a ball names an entry of its angular velocity (the model's damping of 'swing'
    # is one, at the model file's line); another name is refused with the ones it may take
    wrong = tmp_path / "wrong.toml"
    wrong.write_text(scene.read_text().replace('coordinate = "swing_wy"', 'coordinate = "swing_y"'))
    out = subprocess.run([rigid_exe(), "check", str(wrong)], capture_output=True, text=True)
    assert out.returncode == 1 and out.stdout == ""
    words = ("force on unknown coordinate 'swing_y' (a force on a ball coordinate names an entry "
             "of its angular velocity: <ball>_wx, _wy or _wz); did you mean 'swing_wy'?")
    assert words in out.stderr
    with pytest.raises(rigid.Error) as refused:  # the same words from Python
        rigid.Scene(str(wrong))
    assert words in str(refused.value)
    system = rigid.Scene(str(scene)).system
    names, velocities = system.coordinate_names, system.velocity_names
    nq, nv = len(names), len(velocities)
    assert (nq, nv) == (11, 9)
    run = Flat(build(tmp_path, scene, "g++"), nv)
    rng = np.random.default_rng(8)
    steps = (1e-2, 1e-3, 1e-5)
    for _ in range(3):
        q = np.array(system.initial_q)
        for i, name in enumerate(names):
            if name.endswith("_qw"):
                r = rng.normal(size=4)
                q[i:i + 4] = r / np.linalg.norm(r)
            elif not name.endswith(("_qx", "_qy", "_qz")):
                q[i] = rng.uniform(-1, 1)
        v, a, tau = rng.uniform(-1, 1, (3, nv))
        # the state, then per step and velocity j: q moved ±h along j, and q̇ moved ±h along j
        states = [(q, v, a, tau)]
        for h in steps:
            for j in range(nv):
                e = np.zeros(nv)
                e[j] = h
                states += [(tangent_step(q, names, velocities[j], h), v, a, tau),
                           (tangent_step(q, names, velocities[j], -h), v, a, tau),
                           (q, v + e, a, tau), (q, v - e, a, tau)]
        results = run(states)
        exact = results[0]
        for k, h in enumerate(steps):
            block = results[1 + 4 * nv * k:1 + 4 * nv * (k + 1)]
            diff = {name: np.array([(block[4 * j + off][field] - block[4 * j + off + 1][field]) / (2 * h)
                                    for j in range(nv)]).T
                    for name, field, off in (("dtau_dq", "tau", 0), ("dtau_dqd", "tau", 2),
                                             ("dqdd_dq", "qdd", 0), ("dqdd_dqd", "qdd", 2))}
            errors = {name: rel(d, exact[name]) for name, d in diff.items()}
            if h == 1e-5:
                assert max(errors.values()) < 1e-6, errors
            if h == 1e-3:  # second order where not exact (τ and q̈ are quadratic in q̇)
                assert all(errors[name] < previous[name] / 30 for name in errors
                           if previous[name] > 1e-9), (previous, errors)
            previous = errors


# Two models' flat exports in one program, each in a namespace of its own (--namespace): the
# same numbers as each alone. At global scope the two would declare the same inline names.
TWO_MODELS = r"""
#include <cstdio>
#include "arm7_in.hpp"
#include "cart_arm_in.hpp"
int main() {
  double qa[arm7::nq], va[arm7::nv], ta[arm7::nv], aa[arm7::nv];
  double qc[cart::nq], vc[cart::nv], tc[cart::nv], ac[cart::nv];
  for (int i = 0; i < arm7::nv; ++i) qa[i] = 0.1 * i, va[i] = 0.2, ta[i] = 0.5 - 0.1 * i;
  for (int i = 0; i < cart::nv; ++i) qc[i] = 0.3 * i, vc[i] = -0.1, tc[i] = 0.2 * i;
  arm7::forward_dynamics(qa, va, ta, aa);
  cart::forward_dynamics(qc, vc, tc, ac);
  for (double x : aa) std::printf("%.17g ", x);
  for (double x : ac) std::printf("%.17g ", x);
  std::printf("\n");
}
"""

ALONE = r"""
#include <cstdio>
#include "alone.hpp"
int main() {
  double q[nq], v[nv], t[nv], a[nv];
  for (int i = 0; i < nv; ++i) {
    q[i] = SCALE_Q * i, v[i] = V, t[i] = T0 + T1 * i;
  }
  forward_dynamics(q, v, t, a);
  for (double x : a) std::printf("%.17g ", x);
  std::printf("\n");
}
"""


def test_two_models_in_one_program_by_namespace(tmp_path):
    """`--namespace NAME` (Python: emit(..., flat=True, namespace=NAME)) puts the flat export in a
    namespace: arm7's and cart_arm's in one program give, bit for bit, what each gives alone
    at global scope. A name the export would have to change is refused, and the option needs
    --flat."""
    for model, ns in (("arm7.urdf", "arm7"), ("cart_arm.urdf", "cart")):
        header = tmp_path / f"{model.split('.')[0]}_in.hpp"
        subprocess.run([rigid_exe(), "eom", str(EXAMPLES / model), "--emit", "c++", "--flat",
                        "--namespace", ns, "-o", str(header)], check=True)
        text = header.read_text()
        assert f"namespace {ns} {{" in text and text.endswith(f"}}  // namespace {ns}\n")
        assert f"in namespace {ns} (no t)" in text
        assert rigid.Scene(str(EXAMPLES / model)).emit("c++", header.stem, flat=True,
                                                       namespace=ns) == text
    (tmp_path / "two.cpp").write_text(TWO_MODELS)
    # -O0: the same arithmetic in both programs, compiled quickly
    out = subprocess.run(["g++", "-std=c++17", "-O0", "-Wall", "-Wextra", "-Werror",
                          str(tmp_path / "two.cpp"), "-o", str(tmp_path / "two")],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-3000:]
    together = subprocess.run([str(tmp_path / "two")], capture_output=True, text=True,
                              check=True).stdout.split()
    alone = []
    for model, scale_q, v, t0, t1 in (("arm7.urdf", "0.1", "0.2", "0.5", "-0.1"),
                                      ("cart_arm.urdf", "0.3", "-0.1", "0.0", "0.2")):
        subprocess.run([rigid_exe(), "eom", str(EXAMPLES / model), "--emit", "c++", "--flat", "-o",
                        str(tmp_path / "alone.hpp")], check=True)
        (tmp_path / "alone.cpp").write_text(ALONE)
        subprocess.run(["g++", "-std=c++17", "-O0", f"-DSCALE_Q={scale_q}", f"-DV={v}",
                        f"-DT0={t0}", f"-DT1={t1}", str(tmp_path / "alone.cpp"), "-o",
                        str(tmp_path / "alone")], check=True)
        alone += subprocess.run([str(tmp_path / "alone")], capture_output=True, text=True,
                                check=True).stdout.split()
    assert together == alone and len(alone) == 7 + 3
    for bad in ("std", "2arm", "int"):
        out = subprocess.run([rigid_exe(), "eom", str(EXAMPLES / "arm7.urdf"), "--emit", "c++",
                              "--flat", "--namespace", bad], capture_output=True, text=True)
        assert out.returncode == 1 and out.stdout == ""
        assert f"the namespace '{bad}' is not a C++ identifier the export may take" in out.stderr
    out = subprocess.run([rigid_exe(), "eom", str(EXAMPLES / "arm7.urdf"), "--emit", "c++",
                          "--namespace", "arm7"], capture_output=True, text=True)
    assert out.returncode == 2 and "--namespace requires --flat" in out.stderr
    with pytest.raises(rigid.Error, match="give flat=True with it"):
        rigid.Scene(str(EXAMPLES / "arm7.urdf")).emit("c++", namespace="arm7")

