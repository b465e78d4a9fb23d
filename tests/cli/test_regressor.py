"""`rigid eom MODEL --regressor [--json]`: the base parameters of a robot model file's inverse
dynamics. The text and the JSON say the same; each base parameter's value is its combination
evaluated on the standard parameters' values; a planar two-link arm groups as Khalil's closed
form says; anything but a robot model file is refused."""
import json
import pathlib
import re

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"

# A planar 2R arm (hinges about parallel z axes, link 2's joint at l1 = 0.7 m along link 1's x,
# gravity in the plane): Izz_1 + Ia_1 + m_2 l1² is one base parameter (Khalil & Dombre 2002,
# ch. 9); l1² = 0.49.
PLANAR_2R = """<mujoco model="planar2r">
  <option gravity="0 -9.81 0"/>
  <worldbody>
    <body name="link1">
      <joint name="j1" type="hinge" axis="0 0 1" armature="0.03" damping="0.2"/>
      <inertial pos="0.3 0.02 0" mass="2" diaginertia="0.01 0.05 0.055"/>
      <body name="link2" pos="0.7 0 0">
        <joint name="j2" type="hinge" axis="0 0 1" armature="0.03"/>
        <inertial pos="0.25 -0.01 0" mass="1.3" diaginertia="0.01 0.05 0.055"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def regressor_json(run, model, *flags):
    proc = run("eom", model, "--regressor", "--json", *flags, check=True)
    return json.loads(proc.stdout)


def text_lines(run, model, *flags):
    """The base parameters of the text output: {name: (expression, value)}, and the rest."""
    out = run("eom", model, "--regressor", *flags, check=True).stdout
    base = {}
    for m in re.finditer(r"^  (beta_\d+) = (.+) = (\S+) \S+$", out, re.M):
        base[m[1]] = (m[2], float(m[3]))
    rank = int(re.search(r"^rank: (\d+) ", out, re.M)[1])
    unidentifiable = re.search(r"^unidentifiable \(\d+, no effect on tau\):(.*)$", out, re.M)[1].split()
    return base, rank, unidentifiable


def evaluate(expression, values):
    """A text combination `a + 0.49*b - c` on the standard values."""
    total = 0.0
    for sign, coefficient, name in re.findall(r"(^|[+-]) ?(?:([0-9.e+-]+)\*)?(\w+)", expression):
        c = float(coefficient) if coefficient else 1.0
        total += -c * values[name] if sign == "-" else c * values[name]
    return total


@pytest.mark.parametrize("model", ["arm7.urdf", "cart_arm.urdf", "arm7.sdf"])
def test_json_values_are_the_combinations_on_the_standard_values(run, model):
    doc = regressor_json(run, EXAMPLES / model)
    values = {p["name"]: p["value"] for p in doc["standard_parameters"]}
    assert len(doc["base_parameters"]) == doc["rank"] > 0
    for beta in doc["base_parameters"]:
        terms = [t["coefficient"] * values[t["parameter"]] for t in beta["terms"]]
        # the same products summed in another order: round-off of the largest term
        scale = max([abs(t) for t in terms] + [1e-300])
        assert abs(sum(terms) - beta["value"]) <= 1e-14 * scale, beta
        assert beta["terms"][0]["coefficient"] == 1.0
        assert beta["unit"] == next(p["unit"] for p in doc["standard_parameters"]
                                    if p["name"] == beta["terms"][0]["parameter"])
    # every standard parameter is independent, dependent or unidentifiable, once
    independent = [b["terms"][0]["parameter"] for b in doc["base_parameters"]]
    assert sorted(independent + doc["dependent"] + doc["unidentifiable"]) == sorted(values)


def test_text_says_what_the_json_says(run):
    model = EXAMPLES / "cart_arm.urdf"
    doc = regressor_json(run, model)
    base, rank, unidentifiable = text_lines(run, model)
    values = {p["name"]: p["value"] for p in doc["standard_parameters"]}
    assert rank == doc["rank"] == len(base)
    assert unidentifiable == doc["unidentifiable"]
    for beta in doc["base_parameters"]:
        expression, value = base[beta["name"]]
        assert expression == beta["expression"]
        # the text prints 10 significant digits, its coefficients 12
        assert value == pytest.approx(beta["value"], rel=1e-9, abs=1e-12)
        assert evaluate(expression, values) == pytest.approx(beta["value"], rel=1e-9, abs=1e-12)


def test_format_json_is_json(run):
    a = run("eom", EXAMPLES / "arm7.urdf", "--regressor", "--format", "json", check=True).stdout
    assert json.loads(a) == regressor_json(run, EXAMPLES / "arm7.urdf")


def test_planar_two_link_arm_groups_as_the_closed_form(run, tmp_path):
    model = tmp_path / "planar2r.xml"
    model.write_text(PLANAR_2R)
    base, rank, unidentifiable = text_lines(run, model)
    # 7 inertial and armature base parameters (ZZR1, MXR1, MY1, ZZ2, MX2, MY2, Ia2) and each
    # joint's damping and stiffness
    assert rank == 11
    expressions = {e for e, _ in base.values()}
    assert "Izz_link1 + Ia_j1 + 0.49*m_link2" in expressions
    assert "mx_link1 + 0.7*m_link2" in expressions
    assert "m_link1" in unidentifiable and "Ixx_link2" in unidentifiable
    # Izz_link1 about the link origin: 0.055 + 2 (0.3² + 0.02²)
    value = dict(base.values())["Izz_link1 + Ia_j1 + 0.49*m_link2"]
    assert value == pytest.approx(0.055 + 2 * (0.09 + 0.0004) + 0.03 + 1.3 * 0.49, rel=1e-9)


def test_pinned_humanoid(run):
    doc = regressor_json(run, "/usr/share/mujoco/model/humanoid/humanoid.xml", "--pin-free-root")
    assert doc["rank"] == len(doc["base_parameters"]) > 100
    # the rank decision's margin: dependent columns at round-off, chosen ones far above
    assert doc["largest_dependent"] < 1e-12 < 1e-9 < doc["smallest_independent"]


def test_a_scene_file_is_refused(run):
    proc = run("eom", EXAMPLES / "double_pendulum.toml", "--regressor", check=False)
    assert proc.returncode == 1
    assert "double_pendulum.toml is not a robot model file" in proc.stderr
    assert "takes a URDF, MJCF or SDF file" in proc.stderr
    assert "Traceback" not in proc.stderr and "terminate" not in proc.stderr


@pytest.mark.parametrize("flags, message", [
    (["--emit", "c++", "--json"], "--regressor: --json prints the base parameters; --emit writes"),
    (["--latex"], "--regressor: --latex prints the equations"),
    (["--format", "latex"], "--regressor: --format latex is not a format of the base parameters"),
    (["--set", "m_link1=2"], "--regressor: --set changes a scene's values"),
    (["--symbolic-inertia"], "--regressor: --symbolic-inertia is implied"),
])
def test_flags_that_do_not_apply_are_refused(run, flags, message):
    proc = run("eom", EXAMPLES / "arm7.urdf", "--regressor", *flags, check=False)
    assert proc.returncode == 1 and message in proc.stderr, proc.stderr


def test_json_needs_regressor(run):
    proc = run("eom", EXAMPLES / "arm7.urdf", "--json", check=False)
    assert proc.returncode != 0 and "--json requires --regressor" in proc.stderr


def test_missing_file(run, tmp_path):
    proc = run("eom", tmp_path / "none.urdf", "--regressor", check=False)
    assert proc.returncode == 1 and "none.urdf" in proc.stderr


FLOATING = pathlib.Path(__file__).resolve().parents[1] / "robot" / "data" / "floating.xml"
HUMANOID = pathlib.Path("/usr/share/mujoco/model/humanoid/humanoid.xml")


def random_state(robot, rng):
    """q about the reference, each quaternion (its w named *_qw) uniform over the rotations;
    velocities and accelerations in ± 2 (nv each)."""
    import numpy as np

    q = np.asarray(robot.reference_configuration) + rng.uniform(-2, 2, robot.nq)
    for i, name in enumerate(robot.coordinates):
        if name.endswith("_qw"):
            r = rng.normal(size=4)
            q[i:i + 4] = r / np.linalg.norm(r)
    return q, rng.uniform(-2, 2, robot.nv), rng.uniform(-2, 2, robot.nv)


@pytest.mark.parametrize("model", [EXAMPLES / "cart_arm.urdf", FLOATING, HUMANOID],
                         ids=lambda path: path.name)
def test_python_regressor_and_base_parameters_agree_with_the_dynamics_and_the_cli(run, model):
    """Robot.regressor times π is Robot.inverse_dynamics, and Y_b β too, at 5 random states;
    a free joint's and a ball joint's quaternions in q (nq), their velocities in q̇ (nv); the base
    parameters are the CLI's."""
    import numpy as np
    import rigid

    robot = rigid.robot.Robot(str(model))
    names, pi = robot.standard_parameters()
    base = robot.base_parameters()
    rng = np.random.default_rng(5)
    for _ in range(5):
        q, q_dot, q_ddot = random_state(robot, rng)
        Y = robot.regressor(q, q_dot, q_ddot)
        assert Y.shape == (robot.nv, len(names))
        tau = robot.inverse_dynamics(q, q_dot, q_ddot)
        # round-off of the largest term, as in tests/robot/regressor_test.cpp
        scale = max(np.abs(tau).max(), (np.abs(Y) @ np.abs(pi)).max())
        assert np.abs(Y @ pi - tau).max() <= 1e-12 * scale
        Yb = Y[:, base.independent_columns]
        assert np.abs(Yb @ base.values - tau).max() <= 1e-12 * scale
    assert np.allclose(base.combination @ base.standard_values, base.values, rtol=1e-14, atol=0)
    doc = regressor_json(run, model)
    assert base.rank == doc["rank"]
    assert base.expressions == [b["expression"] for b in doc["base_parameters"]]
    assert list(base.values) == [b["value"] for b in doc["base_parameters"]]
    assert base.unidentifiable == doc["unidentifiable"]


def test_floating_base_text_and_refusals(run):
    """The floating base's free joint's units name both its translations and rotations, in the
    text as in the JSON; a quaternion off the unit sphere and a q of nv entries are refused,
    naming what."""
    import numpy as np
    import rigid

    doc = regressor_json(run, FLOATING)
    units = {p["name"]: p["unit"] for p in doc["standard_parameters"]}
    assert units["Ia_root"] == "kg|kg·m²" and units["k_shoulder"] == "N·m/rad"
    base, rank, _ = text_lines(run, FLOATING)
    assert rank == doc["rank"] and len(base) == rank
    robot = rigid.robot.Robot(str(FLOATING))
    q, v, a = random_state(robot, np.random.default_rng(1))
    with pytest.raises(rigid.Error, match=r"argument 'q' must have shape \(16,\); got \(13,\)"):
        robot.regressor(q[:13], v, a)
    q[3:7] = [1.01, 0, 0, 0]
    with pytest.raises(rigid.Error, match=r"joint 'root' \(type free\): its quaternion q\[3..6\]"):
        robot.regressor(q, v, a)
