"""A robot model file (URDF, MJCF, SDF) as a scene on the command line and in Python: the
modes of a pinned pendulum against its closed form (stiffness and armature included), `rigid
run` against rigid.Scene.run and the printed equations against rigid.robot.Robot (the same tree
in numbers), the energy of a damped and an undamped arm, a sweep, `rigid check`, the
refusals, which every surface words alike and locates by file:line, and arm7 read from URDF
and from SDF."""
import csv
import json
import math
import pathlib

import numpy as np
import pytest

import rigid

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
CART_ARM = EXAMPLES / "cart_arm.urdf"
HUMANOID = pathlib.Path("/usr/share/mujoco/model/humanoid/humanoid.xml")
G = 9.81  # URDF has no gravity element: MuJoCo's default, (0, 0, -9.81) m/s²
PREFIX = "rigid: error: "


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array(rows[1:], dtype=float)


# --- 1. the modes of a pinned pendulum --------------------------------------------------------

M_BOB, L_COM, I_YY = 2.5, 0.7, 0.13  # kg, m below the hinge, kg·m² about the COM (axis y)


def pendulum_urdf(path, yaw=0.0, damping=None):
    """A hinge at the world origin about the world y axis carrying one link whose COM hangs
    L_COM below it. With yaw ≠ 0 the link frame is turned by yaw about z, so the axis and the
    inertia are written in that frame: the same physical pendulum in other numbers."""
    c, s = math.cos(yaw), math.sin(yaw)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])  # world ← link
    I_link = R.T @ np.diag([0.1, I_YY, 0.05]) @ R
    axis = R.T @ np.array([0, 1, 0])
    dyn = f'\n    <dynamics damping="{damping!r}"/>' if damping is not None else ""
    path.write_text(f"""<?xml version="1.0"?>
<robot name="pendulum">
  <link name="base"/>
  <link name="bob">
    <inertial>
      <origin xyz="0 0 {-L_COM!r}" rpy="0 0 0"/>
      <mass value="{M_BOB!r}"/>
      <inertia ixx="{I_link[0, 0]!r}" ixy="{I_link[0, 1]!r}" ixz="0" iyy="{I_link[1, 1]!r}" iyz="0" izz="{I_link[2, 2]!r}"/>
    </inertial>
  </link>
  <joint name="theta" type="continuous">
    <parent link="base"/>
    <child link="bob"/>
    <origin xyz="0 0 0" rpy="0 0 {yaw!r}"/>
    <axis xyz="{axis[0]!r} {axis[1]!r} {axis[2]!r}"/>{dyn}
  </joint>
</robot>
""")
    return path


def pendulum_mjcf(path, stiffness, armature):
    # URDF has no joint stiffness or armature: MJCF states them (N·m/rad, kg·m²)
    path.write_text(f"""<mujoco model="pendulum">
  <worldbody>
    <body name="bob">
      <joint name="theta" type="hinge" axis="0 1 0" stiffness="{stiffness!r}" armature="{armature!r}"/>
      <inertial pos="0 0 {-L_COM!r}" mass="{M_BOB!r}" diaginertia="0.1 {I_YY!r} 0.05"/>
    </body>
  </worldbody>
</mujoco>
""")
    return path


def modes_json(run, path):
    return json.loads(run("modes", path, "--json", check=True).stdout)


# The linearisation of a one-coordinate scene is M, K of 1×1 and ω = sqrt(K/M): a few ε of
# round-off in M = I + m l², K = m g l and the square root; 1e-9 leaves six orders of margin
# and still catches any wrong term (a missing m l² is a 90 % error, a missing armature 20 %).
OMEGA_RTOL = 1e-9


@pytest.mark.parametrize("yaw", [0.0, 0.7])
def test_pendulum_urdf_modes_are_the_closed_form(run, tmp_path, yaw):
    d = modes_json(run, pendulum_urdf(tmp_path / "pendulum.urdf", yaw=yaw))
    assert d["coordinates"] == ["theta"] and d["stability"] == "stable"
    assert len(d["modes"]) == 1
    omega = math.sqrt(M_BOB * G * L_COM / (I_YY + M_BOB * L_COM**2))
    assert d["modes"][0]["omega"] == pytest.approx(omega, rel=OMEGA_RTOL)


@pytest.mark.parametrize("stiffness, armature", [(0.0, 0.0), (3.2, 0.0), (0.0, 0.4), (3.2, 0.4)])
def test_stiffness_and_armature_enter_the_pendulums_frequency(run, tmp_path, stiffness, armature):
    d = modes_json(run, pendulum_mjcf(tmp_path / "pendulum.xml", stiffness, armature))
    # spring: V gains ½ k θ², so K = m g l + k; armature: T gains ½ a θ̇², so M = I + m l² + a
    omega = math.sqrt((M_BOB * G * L_COM + stiffness) / (I_YY + M_BOB * L_COM**2 + armature))
    assert d["modes"][0]["omega"] == pytest.approx(omega, rel=OMEGA_RTOL)
    assert d["M"][0][0] == pytest.approx(I_YY + M_BOB * L_COM**2 + armature, rel=1e-14)
    assert d["K"][0][0] == pytest.approx(M_BOB * G * L_COM + stiffness, rel=1e-14)


def test_damping_makes_the_pendulums_mode_decay(run, tmp_path):
    c = 0.3  # N·m·s/rad
    d = modes_json(run, pendulum_urdf(tmp_path / "damped.urdf", damping=c))
    J, K = I_YY + M_BOB * L_COM**2, M_BOB * G * L_COM
    assert d["C"] == [[pytest.approx(c, rel=1e-15)]]
    # J λ² + c λ + K = 0: λ = −c/(2J) ± i sqrt(K/J − (c/2J)²); round-off only, as above
    eig = d["modes"][0]["eigenvalue"]
    assert eig["re"] == pytest.approx(-c / (2 * J), rel=OMEGA_RTOL)
    assert abs(eig["im"]) == pytest.approx(math.sqrt(K / J - (c / (2 * J))**2), rel=OMEGA_RTOL)


# --- 2. the seams: rigid run = rigid.Scene.run; rigid eom = rigid.robot.Robot -------------------

OVERRIDES = ["shoulder.initial=0.8", "simulation.t_end=0.5"]


def cli_run(run, model, out, *overrides):
    sets = [a for o in overrides for a in ("--set", o)]
    run("run", model, *sets, "-o", out, "-q", check=True)
    return read_csv(out / "trajectory.csv"), json.loads((out / "summary.json").read_text())


def test_rigid_run_and_python_give_the_same_trajectory(run, tmp_path):
    (names, rows), summary = cli_run(run, CART_ARM, tmp_path / "cli", *OVERRIDES)
    py = rigid.Scene(str(CART_ARM), set=OVERRIDES).run()
    assert list(py["columns"]) == names
    assert rows[-1, 0] == 0.5 and summary["t_end"] == 0.5
    assert py["summary"]["steps"] == summary["steps"]
    # the same engine on the same input; the CSV holds shortest round-trip decimals, so the
    # last row agrees to the bit — 1e-12 only allows for a last-digit difference in printing
    for j, name in enumerate(names):
        np.testing.assert_allclose(py["columns"][name][-1], rows[-1, j], rtol=1e-12, atol=1e-15,
                                   err_msg=name)


def evaluate(text, values):
    """A printed expression (sin, cos, sqrt, ^, rationals) at the given symbol values."""
    return eval(text.replace("^", "**"), {"__builtins__": {}},
                {"sin": math.sin, "cos": math.cos, "sqrt": math.sqrt, **values})


def test_printed_equations_are_the_trees_dynamics(run):
    d = json.loads(run("eom", CART_ARM, "--format", "json", check=True).stdout)
    robot = rigid.robot.Robot(str(CART_ARM))
    assert d["coordinates"] == robot.coordinates == ["x", "shoulder", "elbow"]
    assert len(d["equations"]["text"]) == robot.dof == 3
    q, q_dot = np.array([0.3, -0.7, 1.1]), np.array([0.4, -1.3, 2.2])  # a generic state
    values = {**dict(zip(d["coordinates"], q)), **{f"{n}_dot": v for n, v in zip(d["coordinates"], q_dot)}}
    M = np.array([[evaluate(e, values) for e in row] for row in d["mass_matrix"]["text"]])
    f = np.array([evaluate(e, values) for e in d["forcing"]["text"]])
    # M q̈ = f with f = −b(q, q̇) + p(q, q̇); the printed coefficients carry ≥ 17 digits, so
    # the two differ by the round-off of summing ~10 terms of size ≤ 10: 1e-12 absolute
    np.testing.assert_allclose(M, robot.mass_matrix(q), rtol=0, atol=1e-12)
    np.testing.assert_allclose(f, robot.passive_forces(q, q_dot) - robot.bias_forces(q, q_dot),
                               rtol=0, atol=1e-12)
    # the damping of the file (x: 2 N·s/m, shoulder: 0.05 N·m·s/rad) as generalized forces
    expected = -np.array([2.0, 0.05, 0.0]) * q_dot
    np.testing.assert_allclose([evaluate(e, values) for e in d["forcing_generalized"]["text"]],
                               expected, rtol=0, atol=1e-15)


# --- 3. the energy -----------------------------------------------------------------------------

def test_the_damped_arm_loses_the_energy_its_dampers_dissipate(run, tmp_path):
    (names, rows), summary = cli_run(run, CART_ARM, tmp_path / "run", *OVERRIDES)
    col = {n: rows[:, j] for j, n in enumerate(names)}
    E, t = col["energy"], col["t"]
    # dE/dt = −2 ẋ² − 0.05 θ̇_shoulder² ≤ 0. Between steps E falls by ≥ 7.8e-9 J here (the first
    # step, from rest, falls least), while the undamped copy below drifts by ≤ 1.5e-9 J over the
    # whole run: any rise above 1e-9 · |E(0)| ≈ 3.6e-9 J is not integration error.
    assert np.all(np.diff(E) <= 1e-9 * abs(E[0])), np.diff(E).max()
    # and the loss is the dampers' work: E(0) − E(T) = ∫ (2 ẋ² + 0.05 θ̇²) dt, by the trapezoid
    # rule on dopri5's ~80 steps of h ≈ 7 ms: its error ≈ h²/12 · ∫|P''| ≈ (7e-3 · 10 s⁻¹)²/12
    # ≈ 4e-4 of the integral (measured 4e-5); 2e-3 catches a wrong coefficient
    power = 2 * col["x_dot"]**2 + 0.05 * col["shoulder_dot"]**2
    dissipated = np.sum(np.diff(t) * (power[1:] + power[:-1]) / 2)
    assert E[0] - E[-1] == pytest.approx(dissipated, rel=2e-3)
    assert summary["diagnostics"]["energy_final"] == E[-1]
    # the energy column is the tree's T + V (rigid.robot.Robot, independent numbers): the same
    # up to the round-off of a few J
    robot = rigid.robot.Robot(str(CART_ARM))
    q = np.stack([col[n] for n in robot.coordinates], axis=1)
    q_dot = np.stack([col[f"{n}_dot"] for n in robot.coordinates], axis=1)
    TV = np.array([sum(robot.energy(q[k], q_dot[k])) for k in range(len(t))])
    np.testing.assert_allclose(TV - TV[0], E - E[0], rtol=0, atol=1e-12)


def test_without_damping_the_energy_is_conserved_to_the_integrators_tolerance(run, tmp_path):
    text = CART_ARM.read_text()
    undamped = "\n".join(line for line in text.splitlines() if "<dynamics" not in line)
    assert undamped.count("<dynamics") == 0 and text.count("<dynamics") == 2
    model = tmp_path / "undamped.urdf"
    model.write_text(undamped)
    _, summary = cli_run(run, model, tmp_path / "run", *OVERRIDES)
    _, damped = cli_run(run, CART_ARM, tmp_path / "damped", *OVERRIDES)
    # a robot scene takes the coordinates' default integrator, dopri5 at a tolerance of 1e-9
    # per step: over 79 steps the energy can drift by at most ~79 · 1e-9 · |E| ≈ 1e-7 |E|
    # (measured 1.4e-9 J, 4e-10 |E|); 1e-6 |E| is the bound, and the damped run's change,
    # 0.27 J = 7 % of E, is five orders above it
    assert summary["integrator"] == "dopri5" and summary["tolerance"] == 1e-9
    d = summary["diagnostics"]
    assert d["energy_max_change"] < 1e-6 * abs(d["energy_initial"])
    assert damped["diagnostics"]["energy_max_change"] > 1e-2 * abs(d["energy_initial"])
    assert damped["diagnostics"]["energy_initial"] == d["energy_initial"]


# --- 4. a sweep; 6. rigid check ----------------------------------------------------------------

def test_a_sweep_over_the_shoulders_start(run, tmp_path):
    out = tmp_path / "sweep"
    run("sweep", CART_ARM, "--grid", "shoulder.initial=0.1:1.0:4", "--set", "simulation.t_end=0.5",
        "-o", out, "-q", check=True)
    with open(out / "runs.csv", newline="") as f:
        runs = list(csv.DictReader(f))
    assert len(runs) == 4
    assert [float(r["shoulder.initial"]) for r in runs] == pytest.approx([0.1, 0.4, 0.7, 1.0], abs=1e-15)
    assert all(r["error"] == "" for r in runs)
    assert json.loads((out / "summary.json").read_text())["failures"] == 0
    # a run of the sweep is `rigid run` with the same overrides: the same numbers, bit for bit
    # but for printing (1e-12)
    _, single = cli_run(run, CART_ARM, tmp_path / "single", "shoulder.initial=1.0", "simulation.t_end=0.5")
    for key in ("energy_initial", "energy_final", "energy_max_change"):
        assert float(runs[-1][key]) == pytest.approx(single["diagnostics"][key], rel=1e-12), key


def test_rigid_check_accepts_the_cart_arm(run):
    proc = run("check", CART_ARM, check=True)
    assert "coordinates: x, shoulder, elbow" in proc.stdout
    # the tool (0.3 kg) welded to the lower link joins it: 1 + 0.3 kg
    assert "lower        mass 1.3 kg" in proc.stdout


# --- 5. refusals ---------------------------------------------------------------------------------

LINK = ('<link name="{name}"><inertial><origin xyz="0 0 -0.1"/><mass value="1"/>'
        '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>')


def chain(n):
    """n links hanging in a chain by continuous joints: line 3 is the base, link i on line 4 + i."""
    links = ['<link name="base"/>'] + [LINK.format(name=f"l{i}") for i in range(n)]
    joints = [f'<joint name="j{i}" type="continuous"><parent link="{"base" if i == 0 else f"l{i - 1}"}"/>'
              f'<child link="l{i}"/><origin xyz="0 0 {-0.2 if i else 0}"/><axis xyz="0 1 0"/></joint>'
              for i in range(n)]
    return '<?xml version="1.0"?>\n<robot name="chain">\n' + "\n".join(links + joints) + "\n</robot>\n"


def two_links(joint2_extra="", joint2_type="continuous"):
    return ('<?xml version="1.0"?>\n<robot name="r">\n<link name="base"/>\n'   # lines 1-3
            + LINK.format(name="a") + "\n" + LINK.format(name="b") + "\n"      # lines 4-5
            + '<joint name="j1" type="continuous"><parent link="base"/><child link="a"/>'
              '<axis xyz="0 1 0"/></joint>\n'                                   # line 6
            + f'<joint name="j2" type="{joint2_type}"><parent link="a"/><child link="b"/>'
              f'<origin xyz="0 0 -0.2"/><axis xyz="0 1 0"/>{joint2_extra}</joint>\n'  # line 7
            + "</robot>\n")


# (file name, its text (None: the file as it is), the line the message starts with,
#  the words it must name)
REFUSALS = {
    "truncated": ("trunc.urdf", '<robot name="x"><link name="a">', 1, ["malformed XML"]),
    "floating": ("floating.urdf", two_links(joint2_type="floating"), 7,
                 ["'j2'", "floating"]),
    "mimic": ("mimic.urdf", two_links('<mimic joint="j1" multiplier="2"/>'), 7,
              ["'j2'", "mimic"]),
    "ball_spring": ("ball_spring.xml", '<mujoco>\n<worldbody>\n<body name="a" pos="0 0 1">\n'
                    '<joint name="j2" type="ball" stiffness="2"/>\n<geom type="sphere" size="0.1" mass="1"/>\n'
                    '</body>\n</worldbody>\n</mujoco>\n', 4, ["'j2' (ball) has stiffness 2", "rotation vector"]),
    "missing": ("missing.urdf", None, None, ["missing.urdf", "No such file"]),
    "sdf_ball": ("ball.sdf", '<sdf version="1.7">\n<model name="r">\n<link name="a"/>\n'
                 '<link name="b"/>\n<joint name="j2" type="ball"><parent>a</parent>'
                 '<child>b</child></joint>\n</model>\n</sdf>\n', 5, ["'j2'", "ball"]),
}


@pytest.mark.parametrize("case", list(REFUSALS))
def test_refusals_are_located_and_the_same_in_python(run, tmp_path, case):
    name, text, where, words = REFUSALS[case]
    path = tmp_path / name
    if text is not None:
        path.write_text(text)
    messages = set()
    for verb in (["check"], ["eom"], ["modes"], ["run", "-o", tmp_path / "out"],
                 ["sweep", "--grid", "j1.initial=0:1:2", "-o", tmp_path / "sweep"]):
        proc = run(verb[0], path, *verb[1:], check=False)
        assert proc.returncode == 1, (verb, proc.stdout, proc.stderr)
        assert "Traceback" not in proc.stderr and proc.stderr.count("\n") == 1, proc.stderr
        assert proc.stderr.startswith(PREFIX), proc.stderr
        messages.add(proc.stderr.strip().removeprefix(PREFIX))
    assert len(messages) == 1, messages  # every verb says the same
    assert not (tmp_path / "out").exists() and not (tmp_path / "sweep").exists()  # nothing written
    message = messages.pop()
    if where is not None:
        assert message.startswith(f"{path}:{where}: "), message
    for word in words:
        assert word in message, (word, message)
    with pytest.raises(rigid.Error) as refused:
        rigid.Scene(str(path))
    assert str(refused.value) == message


# --- 6. SDF ----------------------------------------------------------------------------------

def test_arm7_sdf_prints_the_urdfs_equations(run):
    """examples/arm7.sdf is arm7.urdf in SDFormat's frames (link poses in the model frame, joint
    poses in the child link): `rigid eom` of each, evaluated at one generic state (the printed
    intermediates first, in order), gives the same M and f. The two trees differ by the rounding
    of their placements and the printed coefficients carry 17 digits: 3e-16 of the largest entry
    measured; 1e-12 leaves a wide margin, while a wrong axis, anchor or inertial frame changes
    entries by O(1)."""
    eoms = [json.loads(run("eom", EXAMPLES / name, "--format", "json", check=True).stdout)
            for name in ("arm7.urdf", "arm7.sdf")]
    assert eoms[0]["coordinates"] == eoms[1]["coordinates"] == [f"joint{i}" for i in range(1, 8)]
    q = [0.3, -0.7, 1.1, 0.4, -1.3, 0.9, 2.2]
    q_dot = [0.5, -0.2, 0.8, -1.1, 0.6, 1.4, -0.9]
    names = eoms[0]["coordinates"]
    M, f = [], []
    for d in eoms:
        values = {**dict(zip(names, q)), **{f"{n}_dot": v for n, v in zip(names, q_dot)}}
        for intermediate in d["intermediates"]:
            values[intermediate["name"]] = evaluate(intermediate["text"], values)
        M.append(np.array([[evaluate(e, values) for e in row] for row in d["mass_matrix"]["text"]]))
        f.append(np.array([evaluate(e, values) for e in d["forcing"]["text"]]))
    np.testing.assert_allclose(M[1], M[0], rtol=0, atol=1e-12 * np.abs(M[0]).max())
    np.testing.assert_allclose(f[1], f[0], rtol=0, atol=1e-12 * np.abs(f[0]).max())


# --- 7. how a model file is read: --pin-free-root, --inertia-from-geometry, --density, [model] --

ARM7 = EXAMPLES / "arm7.urdf"
ARM7_PD = EXAMPLES / "robots" / "arm7_pd.toml"
SCENE_VERBS = (["check"], ["eom"], ["modes"], ["run", "-q", "-o"], ["sweep", "--grid", "m1=1:2:2", "-q", "-o"])

BOX_URDF = """<?xml version="1.0"?>
<robot name="box">
  <link name="base"/>
  <link name="box">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
    <collision>
      <origin xyz="0 0 -0.5"/>
      <geometry><box size="0.1 0.2 0.3"/></geometry>
    </collision>
  </link>
  <joint name="hinge" type="continuous">
    <parent link="base"/>
    <child link="box"/>
    <axis xyz="0 1 0"/>
  </joint>
</robot>
"""


def test_arm7_from_geometry_keeps_its_inertials(run):
    """arm7.urdf has no collision geometry, so with --inertia-from-geometry every link keeps its
    stated inertial (the rule of `rigid inertia fix`): the option is accepted and the equations
    are the same bytes (they print alike from separate processes, tests/cli/test_eom.py)."""
    assert "<collision" not in ARM7.read_text()
    plain = json.loads(run("eom", ARM7, "--format", "json", check=True).stdout)
    from_geometry = json.loads(run("eom", ARM7, "--format", "json", "--inertia-from-geometry",
                                   check=True).stdout)
    assert from_geometry["mass_matrix"] == plain["mass_matrix"]
    assert from_geometry["forcing"] == plain["forcing"]


def test_inertia_from_geometry_and_density_reach_the_links(run, tmp_path):
    # the box's mass at density ρ: ρ · 0.1 · 0.2 · 0.3 m³ (its stated inertial says 1 kg)
    box = tmp_path / "box.urdf"
    box.write_text(BOX_URDF)
    for flags, mass in (([], "1"), (["--inertia-from-geometry"], "6"),
                        (["--inertia-from-geometry", "--density", "500"], "3")):
        out = run("check", box, *flags, check=True).stdout
        assert f"box          mass {mass} kg," in out, (flags, out)
    # a density alone would change nothing: refused, naming the flag it goes with
    proc = run("check", box, "--density", "500", check=False)
    assert proc.returncode == 1 and "--inertia-from-geometry" in proc.stderr, proc.stderr
    for bad in ("0", "-2", "nan", "x"):
        proc = run("check", box, "--inertia-from-geometry", f"--density={bad}", check=False)
        assert proc.returncode == 1, proc.stderr
        assert proc.stderr == f"{PREFIX}--density {bad}: expected a finite number > 0 (kg/m³)\n"
    # Python: the same keywords
    body = rigid.Scene(str(box), inertia_from_geometry=True, density=500).bodies["box"]
    assert body.mass == pytest.approx(500 * 0.1 * 0.2 * 0.3, rel=1e-15)


def test_pinned_humanoid_gets_past_the_free_joint(run):
    assert HUMANOID.exists(), "libmujoco-samples is missing: scripts/install-deps.sh installs it"
    pinned = run("check", HUMANOID, "--pin-free-root")
    assert pinned.returncode == 0, pinned.stderr
    assert "coordinates: abdomen_z" in pinned.stdout


HUMANOID_SPIN = ["simulation.t_end=0.3", "root.angular_velocity=[0.5, -1, 2]", "root_x.velocity=0.4",
                 "right_knee.velocity=-1.5"]


def test_free_root_humanoid_through_every_front_end(run, tmp_path):
    # MuJoCo's humanoid with its free root: q is qpos (28), the velocities qvel (27); check, eom,
    # run, a two-thread sweep and Python take it with the same names and numbers, and what does
    # not take a ball coordinate yet refuses by name, without a trace and without output
    assert HUMANOID.exists(), "libmujoco-samples is missing: scripts/install-deps.sh installs it"
    check = run("check", HUMANOID, check=True).stdout
    assert "coordinates: root_x, root_y, root_z, root_qw, root_qx, root_qy, root_qz, abdomen_z" in check
    doc = json.loads(run("eom", HUMANOID, "--format", "json", check=True).stdout)
    assert len(doc["coordinates"]) == 28 and len(doc["velocities"]) == 27
    assert doc["velocities"][3:6] == ["root_wx", "root_wy", "root_wz"]
    assert len(doc["equations"]["text"]) == 27 and len(doc["mass_matrix"]["text"]) == 27
    # the quaternion's rate, ½ q ⊗ (0, ω), as printed
    assert doc["coordinate_rates"]["text"][3] == "-1/2*root_qx*root_wx - 1/2*root_qy*root_wy - 1/2*root_qz*root_wz"
    scene = rigid.Scene(str(HUMANOID))
    assert list(scene.system.coordinate_names) == doc["coordinates"]
    assert list(scene.system.velocity_names) == doc["velocities"]
    # q̇ = ½ q ⊗ (0, ω): turning about the torso's z at the identity moves q_z at ω/2
    v = np.zeros(27)
    v[5] = 2.0
    rates = scene.system.coordinate_rates(scene.system.initial_q, v)
    assert list(rates[3:7]) == [0.0, 0.0, 0.0, 1.0] and len(rates) == 28
    with pytest.raises(rigid.Error, match="q_dot"):
        scene.system.coordinate_rates(scene.system.initial_q, np.zeros(28))
    # a run: the CLI's CSV and Python's columns agree to the printing (as for the cart arm)
    (names, rows), summary = cli_run(run, HUMANOID, tmp_path / "cli", *HUMANOID_SPIN)
    assert names[1:8] == ["root_x", "root_y", "root_z", "root_qw", "root_qx", "root_qy", "root_qz"]
    assert names[29:35] == ["root_x_dot", "root_y_dot", "root_z_dot", "root_wx", "root_wy", "root_wz"]
    py = rigid.Scene(str(HUMANOID), set=HUMANOID_SPIN).run()
    assert list(py["columns"]) == names
    assert py["summary"]["steps"] == summary["steps"]
    for j, name in enumerate(names):
        np.testing.assert_allclose(py["columns"][name][-1], rows[-1, j], rtol=1e-12, atol=1e-15, err_msg=name)
    # the quaternion is written normalised, and it turned: w left 1
    quat = rows[:, 4:8]
    np.testing.assert_allclose(np.linalg.norm(quat, axis=1), 1.0, rtol=0, atol=1e-15)
    assert quat[-1, 0] < 0.99
    # a sweep on two threads over the root's start: each run is `rigid run` with that value
    out = tmp_path / "sweep"
    run("sweep", HUMANOID, "--grid", "root_x.velocity=0:0.4:3", *[a for o in HUMANOID_SPIN[:3] for a in ("--set", o)],
        "--threads", "2", "-o", out, "-q", check=True)
    with open(out / "runs.csv", newline="") as f:
        runs = list(csv.DictReader(f))
    assert [r["error"] for r in runs] == ["", "", ""]
    _, last = cli_run(run, HUMANOID, tmp_path / "last", *HUMANOID_SPIN[:3], "root_x.velocity=0.4")
    assert float(runs[-1]["energy_final"]) == pytest.approx(last["diagnostics"]["energy_final"], rel=1e-12)
    # refused by name, exit 1, nothing on stdout
    for args, words in ((["modes", HUMANOID], "normal modes of a system with ball coordinates (here 'root'"),
                        (["eom", HUMANOID, "--emit", "c++"], "the code export of a system with ball coordinates")):
        proc = run(*args, check=False)
        assert proc.returncode == 1 and words in proc.stderr and proc.stdout == "", proc.stderr
        assert "Traceback" not in proc.stderr and "terminate" not in proc.stderr
    with pytest.raises(rigid.Error, match="normal modes of a system with ball coordinates"):
        scene.modes()
    # a ball's state is set by its own keys
    proc = run("run", HUMANOID, "--set", "root.initial=1", "-o", tmp_path / "bad", check=False)
    assert proc.returncode == 1 and "'root' is a ball coordinate: set 'root.orientation'" in proc.stderr
    assert not (tmp_path / "bad").exists()


def test_pinned_humanoids_modes_against_the_tree_dynamics(run):
    # 21 hinges, 9 on the path to a foot: derived by the tree's recursions. The equilibrium the
    # search finds is one for rigid.robot.Robot's own Newton–Euler (b − p = 0 at q̇ = 0), M there
    # is Robot's, and K = −∂f/∂q (the tape's forward-mode derivative) is Robot's by central
    # differences: h = 1e-6 rad gives h²|f‴| + ε|f|/h ≲ 1e-8 of |K| ~ 10² N·m/rad
    proc = run("modes", HUMANOID, "--pin-free-root", "--json", check=True)
    d = json.loads(proc.stdout)
    robot = rigid.robot.Robot(str(HUMANOID), pin_free_root=True)
    names = list(robot.coordinates)
    assert d["coordinates"] == names and len(names) == 21
    assert d["stability"] in ("stable", "marginal", "unstable")
    q = np.array([d["point"]["q"][c] for c in names])
    zero = np.zeros(len(q))

    def f(x):
        return -robot.bias_forces(x, zero) + robot.passive_forces(x, zero)

    assert np.abs(f(q)).max() < 1e-10 * np.abs(robot.bias_forces(zero, zero)).max()
    M = robot.mass_matrix(q)
    assert np.abs(np.array(d["M"]) - M).max() < 1e-10 * np.abs(M).max()
    K = np.column_stack([-(f(q + 1e-6 * e) - f(q - 1e-6 * e)) / 2e-6 for e in np.eye(len(q))])
    assert np.abs(np.array(d["K"]) - K).max() < 1e-6 * np.abs(K).max()


def test_a_deep_chains_equations_name_the_recursions_intermediates(run, tmp_path):
    # 9 links: derived by the tree's recursions, printed with their intermediates ("where")
    path = tmp_path / "chain9.urdf"
    path.write_text(chain(9))
    text = run("eom", path, check=True).stdout
    assert "where (the tree's recursions" in text and "R_l8_xx = " in text
    doc = json.loads(run("eom", path, "--format", "json", check=True).stdout)
    names = [i["name"] for i in doc["intermediates"]]
    assert len(names) == len(set(names)) and "Fn_j8_y" in names


@pytest.mark.parametrize("flags", [["--pin-free-root"], ["--inertia-from-geometry"],
                                   ["--inertia-from-geometry", "--density", "500"]])
def test_model_flags_are_refused_for_a_toml_scene_without_model(run, tmp_path, flags):
    atwood = EXAMPLES / "atwood.toml"
    for verb in SCENE_VERBS:
        out = [tmp_path / "out"] if verb[-1] == "-o" else []
        proc = run(verb[0], atwood, *verb[1:], *out, *flags, check=False)
        assert proc.returncode == 1, (verb, proc.stderr)
        said = "--pin-free-root applies" if len(flags) == 1 and flags[0] == "--pin-free-root" else \
            "--inertia-from-geometry applies" if len(flags) == 1 else \
            "--inertia-from-geometry, density 500 kg/m³ apply"
        assert proc.stderr.startswith(f"{PREFIX}{atwood}: {said} to a robot model file"), proc.stderr
        assert proc.stderr.rstrip().endswith("this TOML scene has no [model]"), proc.stderr
        assert not (tmp_path / "out").exists()
    with pytest.raises(rigid.Error, match="pin_free_root=True applies to a robot model file"):
        rigid.Scene(str(atwood), pin_free_root=True)


def test_a_model_scene_adds_its_forces_and_takes_the_flags(run, tmp_path):
    # the example's two PD torques are the generalized forces of joint2 and joint4, the others'
    # are the joints' damping alone
    doc = json.loads(run("eom", ARM7_PD, "--format", "json", check=True).stdout)
    assert doc["coordinates"] == [f"joint{i}" for i in range(1, 8)]
    sympy = pytest.importorskip("sympy")
    damping = ["0.5", "0.5", "0.4", "0.4", "0.2", "0.2", "0.1"]  # arm7.urdf's, N·m·s/rad
    pd = {2: "-kp*(joint2 - shoulder_target) - kd*joint2_dot",
          4: "-kp*(joint4 - elbow_target) - kd*joint4_dot"}
    for i, printed in enumerate(doc["forcing_generalized"]["text"], start=1):
        expected = f"-{damping[i - 1]}*joint{i}_dot" + (f" + ({pd[i]})" if i in pd else "")
        # as exact rationals: the printed 1/2 and the file's 0.5 are the same number
        difference = sympy.sympify(printed.replace("^", "**"), rational=True) - \
            sympy.sympify(expected, rational=True)
        assert sympy.expand(difference) == 0, (i, printed, expected)
    out = run("check", ARM7_PD, check=True).stdout
    assert "kp = 200 kd = 20" in out and "t_end = 2 s" in out
    # the flags go over the section: arm7 has no collision geometry, so its links stay as stated
    assert run("check", ARM7_PD, "--inertia-from-geometry", check=True).stdout == out
    proc = run("check", ARM7_PD, "--density", "500", check=False)
    assert proc.returncode == 1 and "--inertia-from-geometry" in proc.stderr
    # a sweep of the controller's gain: one model, two runs
    run("sweep", ARM7_PD, "--grid", "kp=100:200:2", "-o", tmp_path / "sweep", "-q", check=True)
    with open(tmp_path / "sweep" / "runs.csv", newline="") as f:
        rows = list(csv.reader(f))
    assert "shoulder_final" in rows[0] and len(rows) == 3, rows


def test_the_scene_format_pages_model_example_is_the_example_file():
    """docs/scene-format.md shows examples/robots/arm7_pd.toml as it is, which the tests above run."""
    page = (EXAMPLES.parent / "docs" / "scene-format.md").read_text()
    section = page[page.index("### `[model]`"):]
    block = section[section.index("```toml\n") + len("```toml\n"):]
    assert block[:block.index("```")] == ARM7_PD.read_text()


def test_symbolic_inertia_keeps_the_links_inertials_as_parameters(run):
    # the parameters carry the file's values: at them the equations are the numeric ones (M at
    # the reference pose, the tape of both to a few ulps); --set moves a mass; Python alike
    model = EXAMPLES / "cart_arm.urdf"
    numeric = json.loads(run("modes", model, "--json", check=True).stdout)
    symbolic = json.loads(run("modes", model, "--symbolic-inertia", "--json", check=True).stdout)
    assert np.allclose(symbolic["M"], numeric["M"], rtol=1e-13, atol=1e-15)
    doc = json.loads(run("eom", model, "--symbolic-inertia", "--format", "json", check=True).stdout)
    names = [p["name"] for p in doc["parameters"]]
    assert names[:10] == ["m_cart", "com_cart_x", "com_cart_y", "com_cart_z", "I_cart_xx",
                          "I_cart_yy", "I_cart_zz", "I_cart_xy", "I_cart_xz", "I_cart_yz"]
    assert "m_cart" in doc["mass_matrix"]["text"][0][0]
    # x is the cart's slide: M_xx is the total mass, so a heavier cart adds exactly its excess
    heavier = json.loads(run("modes", model, "--symbolic-inertia", "--set", "m_cart=12.5",
                             "--json", check=True).stdout)
    m_cart = next(p["value"] for p in doc["parameters"] if p["name"] == "m_cart")
    assert heavier["M"][0][0] == pytest.approx(numeric["M"][0][0] + 12.5 - m_cart, rel=1e-14)
    scene = rigid.Scene(str(model), symbolic_inertia=True)
    assert list(scene.system.parameters)[:2] == ["m_cart", "com_cart_x"]


def test_the_printed_units_follow_the_joints(run):
    # cart_arm: x is the cart's prismatic joint (a length), shoulder and elbow hinges (angles)
    doc = json.loads(run("eom", EXAMPLES / "cart_arm.urdf", "--format", "json", check=True).stdout)
    units = {s["name"]: s["unit"] for s in doc["symbols"]}
    assert (units["x"], units["x_dot"], units["x_ddot"]) == ("m", "m/s", "m/s^2")
    assert (units["shoulder"], units["elbow_dot"]) == ("rad", "rad/s")
