"""The regressor as code (`rigid eom MODEL --regressor --emit c++|python`): the exported C++
is compiled with g++ and clang++ (-O2 -Wall -Wextra -Werror) and the Python module imported;
both are compared with rigid.robot.Robot.regressor (the library's numeric recursion) and with
the inverse dynamics itself (τ = Y π = Y_b β, Robot.inverse_dynamics: composite rigid bodies
and Newton–Euler, a separate computation), and their base parameters with the CLI's JSON."""
import importlib.util
import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"

# per line of stdin "q q_dot q_ddot" (nq + 2 nv numbers): Y, Y_b, then beta of the model's pi
DRIVER = r"""
#include <cstdio>
#include <initializer_list>
#include "exported.hpp"
using namespace exported;
int main() {
  double q[nq], v[nv], a[nv], Y[nv * np], Yb[nv * nb], beta[nb];
  base_parameters(standard_parameters, beta);
  for (;;) {
    for (double* x : {q, v, a}) {
      for (int i = 0; i < (x == q ? nq : nv); ++i) {
        if (std::scanf("%lf", &x[i]) != 1) return 0;
      }
    }
    regressor(q, v, a, Y);
    base_regressor(q, v, a, Yb);
    for (int i = 0; i < nv * np; ++i) std::printf("%.17g ", Y[i]);
    for (int i = 0; i < nv * nb; ++i) std::printf("%.17g ", Yb[i]);
    for (int i = 0; i < nb; ++i) std::printf("%.17g ", beta[i]);
    std::printf("\n");
  }
}
"""


def rigid_exe():
    return os.environ.get("RIGID_EXE", "rigid")


def export(model, language, path):
    subprocess.run([rigid_exe(), "eom", str(model), "--regressor", "--emit", language, "-o",
                    str(path)], check=True, capture_output=True, text=True)
    return path


def base_json(model):
    out = subprocess.run([rigid_exe(), "eom", str(model), "--regressor", "--json"], check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout)


def random_states(robot, count, seed):
    """q about the reference (± π per hinge, ± π m per slide or free joint's position), each
    quaternion (its w named *_qw) uniform over the rotations; velocities in ± 2."""
    rng = np.random.default_rng(seed)
    q0 = np.asarray(robot.reference_configuration)
    turns = [i for i, name in enumerate(robot.coordinates) if name.endswith("_qw")]
    states = []
    for _ in range(count):
        q = q0 + rng.uniform(-np.pi, np.pi, robot.nq)
        for i in turns:
            r = rng.normal(size=4)
            q[i:i + 4] = r / np.linalg.norm(r)
        states.append((q, rng.uniform(-2, 2, robot.nv), rng.uniform(-2, 2, robot.nv)))
    return states


def rel(a, b):
    return np.max(np.abs(np.asarray(a) - np.asarray(b))) / max(np.max(np.abs(b)), 1e-300)


# the floating base (a free joint and ball joints, every passive term) is tests/robot/data's
FLOATING = pathlib.Path(__file__).resolve().parents[1] / "robot" / "data" / "floating.xml"
MODELS = [EXAMPLES / "arm7.urdf", EXAMPLES / "cart_arm.urdf", FLOATING]


@pytest.fixture(scope="module", params=MODELS, ids=lambda path: path.name)
def exported(request, tmp_path_factory):
    """(robot, the JSON document, {compiler: run(states)}, the Python module) for one model."""
    if shutil.which("clang++") is None:
        pytest.fail("clang++ is not installed (scripts/install-deps.sh installs clang)")
    model = request.param
    tmp = tmp_path_factory.mktemp("regressor_" + model.stem)
    export(model, "c++", tmp / "exported.hpp")
    (tmp / "driver.cpp").write_text(DRIVER)
    robot = rigid.robot.Robot(str(model))
    doc = base_json(model)
    n, p, r = robot.nv, len(doc["standard_parameters"]), doc["rank"]
    runs = {}
    for compiler in ("g++", "clang++"):
        program = tmp / f"driver_{compiler.replace('+', 'p')}"
        out = subprocess.run([compiler, "-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror",
                              str(tmp / "driver.cpp"), "-o", str(program)],
                             capture_output=True, text=True)
        assert out.returncode == 0, out.stderr[-3000:]

        def run(states, program=program):
            text = "\n".join(" ".join(f"{x:.17g}" for x in np.concatenate(s)) for s in states)
            res = subprocess.run([str(program)], input=text + "\n", capture_output=True,
                                 text=True, check=True)
            rows = []
            for line in res.stdout.splitlines():
                x = np.array([float(v) for v in line.split()])
                rows.append((x[:n * p].reshape(n, p), x[n * p:n * p + n * r].reshape(n, r),
                             x[n * p + n * r:]))
            return rows
        runs[compiler] = run
    spec = importlib.util.spec_from_file_location(
        "exported_" + model.stem, export(model, "python", tmp / f"exported_{model.stem}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return robot, doc, runs, module


def test_exported_regressor_is_the_librarys(exported):
    """Y of the compiled C++ and of the Python module equals Robot.regressor to 1e-12 relative
    at 12 random states: the same recursion with the model's constants written as shortest
    round-trip decimals (exact), so only the order of a few hundred roundings differs
    (~1e-15 each); Y_b is the base columns of Y, and Y π and Y_b β are the inverse dynamics."""
    robot, doc, runs, module = exported
    _, pi = robot.standard_parameters()
    beta = np.array([b["value"] for b in doc["base_parameters"]])
    columns = list(module.BASE_COLUMNS)
    states = random_states(robot, 12, 5)
    for compiler, run in runs.items():
        for (q, v, a), (Y, Yb, _) in zip(states, run(states)):
            Y_ref = robot.regressor(q, v, a)
            assert rel(Y, Y_ref) < 1e-12, compiler
            assert np.array_equal(Yb, Y[:, columns]), compiler
            tau = robot.inverse_dynamics(q, v, a)
            assert rel(Y @ pi, tau) < 1e-11, compiler
            assert rel(Yb @ beta, tau) < 1e-9, compiler
    for q, v, a in states[:4]:
        Y = np.array(module.regressor(q, v, a))
        assert rel(Y, robot.regressor(q, v, a)) < 1e-12
        assert np.array_equal(np.array(module.base_regressor(q, v, a)), Y[:, columns])


def test_exported_base_parameters_are_the_clis(exported):
    """The exported names, π, base columns and β (from base_parameters(standard_parameters),
    the file's C = [1 K] applied in code) equal the CLI's JSON: same parameters, same choice of
    columns, β to 1e-12 relative (the JSON's β is C π in Eigen; the file's sums the same terms
    with coefficients printed exactly)."""
    robot, doc, runs, module = exported
    names = [s["name"] for s in doc["standard_parameters"]]
    assert list(module.PARAMETERS) == names
    assert list(module.PARAMETERS.values()) == [s["value"] for s in doc["standard_parameters"]]
    assert list(module.PARAMETER_UNITS.values()) == [s["unit"] for s in doc["standard_parameters"]]
    beta = np.array([b["value"] for b in doc["base_parameters"]])
    assert list(module.BASE_PARAMETERS) == [b["name"] for b in doc["base_parameters"]]
    assert [names[c] for c in module.BASE_COLUMNS] == [b["terms"][0]["parameter"]
                                                       for b in doc["base_parameters"]]
    assert rel(module.base_parameters(), beta) < 1e-12
    assert rel(list(module.BASE_PARAMETERS.values()), beta) == 0
    state = random_states(robot, 1, 9)
    for run in runs.values():
        _, _, beta_cpp = run(state)[0]
        assert rel(beta_cpp, beta) < 1e-12


def test_base_parameters_of_other_values(exported):
    """base_parameters(pi) is linear: β of 2π is 2β, and of a π that changes one dependent
    parameter, the change of its coefficient (β = π_I + K π_D)."""
    _, doc, _, module = exported
    pi = np.array(list(module.PARAMETERS.values()))
    beta = np.array(module.base_parameters())
    assert rel(module.base_parameters(2 * pi), 2 * beta) < 1e-15
    with pytest.raises(ValueError, match="pi needs"):
        module.base_parameters(pi[:-1])
    with pytest.raises(ValueError, match="q needs"):
        module.regressor([0.0], [0.0], [0.0])


def test_namespace_follows_the_output_file(tmp_path):
    """The C++ namespace is the output file's stem made an identifier (main → main_, so that
    it cannot clash with int main()); standard output uses the model file's stem."""
    model = EXAMPLES / "cart_arm.urdf"
    text = export(model, "c++", tmp_path / "main.hpp").read_text()
    assert "namespace main_ {" in text
    out = subprocess.run([rigid_exe(), "eom", str(model), "--regressor", "--emit", "c++"],
                         check=True, capture_output=True, text=True).stdout
    assert "namespace cart_arm {" in out


@pytest.mark.parametrize("extra, expected", [
    (["--json"], "--json prints the base parameters; --emit writes them as code"),
    (["--format", "json"], "--format json prints the base parameters"),
    (["--flat"], "--flat is the layout of the exported dynamics"),
])
def test_refusals(extra, expected, tmp_path):
    out = subprocess.run([rigid_exe(), "eom", str(EXAMPLES / "arm7.urdf"), "--regressor",
                          "--emit", "c++", *extra], capture_output=True, text=True)
    assert out.returncode == 1, out.stderr
    assert expected in out.stderr
    assert "Traceback" not in out.stderr and "terminate" not in out.stderr
