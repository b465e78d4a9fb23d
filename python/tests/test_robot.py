"""rigid.robot.Robot: a URDF/MJCF tree's dynamics, against SymPy deriving the Lagrangian of the
same file independently, closed forms and its own identities; the refusals; threads.

The SymPy model reads the URDF with xml.etree (not rigid's reader), composes each link's pose
from the joints' origins (URDF's fixed-axis rpy) and axes, keeps a fixed joint's child as its
own body, and forms T = ½ q̇ᵀ M q̇ with M = Σ m J_vᵀ J_v + J_ωᵀ I_W J_ω (J_v = ∂c/∂q of each
COM, J_ω from ω̂ = Σ ∂R/∂q_k Rᵀ q̇_k), V = −Σ m g·c; then Lagrange's equation gives
f = ∂T/∂q − (∂(M q̇)/∂q) q̇ − ∂V/∂q − D q̇ (no explicit time). Tolerance 1e-11 relative to the largest
entry: both sides round once per operation on quantities of order 1 (≈ 50 operations deep);
a wrong sign, axis or inertia changes entries by ≥ 1e-3.
"""
import pathlib
import re
import threading
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import sympy as sp  # python3-sympy: missing fails, never skips

import rigid

ROOT = pathlib.Path(__file__).resolve().parents[2]
CART_ARM = ROOT / "examples" / "cart_arm.urdf"
ARM7 = ROOT / "examples" / "arm7.urdf"
REL = 1e-11


def _numbers(text, default="0 0 0"):
    return [sp.Float(v, 30) for v in (text or default).split()]


def _rpy(r, p, y):
    cx, sx, cy, sy, cz, sz = sp.cos(r), sp.sin(r), sp.cos(p), sp.sin(p), sp.cos(y), sp.sin(y)
    Rx = sp.Matrix([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    Ry = sp.Matrix([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    Rz = sp.Matrix([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return Rz * Ry * Rx


def _axis_rotation(u, th):
    ux = sp.Matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return sp.eye(3) + sp.sin(th) * ux + (1 - sp.cos(th)) * ux * ux


def sympy_model(path):
    """(q symbols, q̇ symbols, M, f) of a URDF with revolute/continuous/prismatic/fixed joints."""
    root = ET.parse(path).getroot()
    links = {l.get("name"): l for l in root.findall("link")}
    joints = root.findall("joint")
    child_of = {j.find("child").get("link"): j for j in joints}
    base = next(n for n in links if n not in child_of)
    q, damping = [], []
    pose = {base: (sp.zeros(3, 1), sp.eye(3))}
    order = [base]
    # depth first, children in the joints' file order
    def visit(parent):
        for j in joints:
            if j.find("parent").get("link") != parent:
                continue
            child = j.find("child").get("link")
            o = j.find("origin")
            xyz = sp.Matrix(_numbers(o.get("xyz") if o is not None else None))
            R_o = _rpy(*_numbers(o.get("rpy") if o is not None else None))
            p_P, R_P = pose[parent]
            p, R = p_P + R_P * xyz, R_P * R_o
            kind = j.get("type")
            if kind != "fixed":
                u = sp.Matrix(_numbers(j.find("axis").get("xyz")))
                u = u / sp.sqrt((u.T * u)[0])
                qi = sp.Symbol(j.get("name"))
                q.append(qi)
                dyn = j.find("dynamics")
                damping.append(sp.Float(dyn.get("damping"), 30) if dyn is not None else 0)
                if kind == "prismatic":
                    p = p + R * u * qi
                else:
                    R = R * _axis_rotation(u, qi)
            pose[child] = (p, R)
            order.append(child)
            visit(child)
    visit(base)
    g = sp.Matrix([0, 0, -sp.Float("9.81", 30)])
    n = len(q)
    vs = sp.Matrix(sp.symbols(f"v0:{n}"))
    M, V = sp.zeros(n, n), 0
    for name in order:
        inertial = links[name].find("inertial")
        if inertial is None:
            continue
        p, R = pose[name]
        o = inertial.find("origin")
        c_L = sp.Matrix(_numbers(o.get("xyz")))
        R_I = _rpy(*_numbers(o.get("rpy")))
        m = sp.Float(inertial.find("mass").get("value"), 30)
        a = {k: sp.Float(v, 30) for k, v in inertial.find("inertia").attrib.items()}
        I_I = sp.Matrix([[a["ixx"], a["ixy"], a["ixz"]], [a["ixy"], a["iyy"], a["iyz"]], [a["ixz"], a["iyz"], a["izz"]]])
        c = p + R * c_L
        I_W = (R * R_I) * I_I * (R * R_I).T
        J_v = c.jacobian(q)
        J_w = sp.zeros(3, n)
        for k in range(n):
            W = R.diff(q[k]) * R.T  # ω̂ per unit q̇_k, world frame
            J_w[:, k] = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
        M += m * J_v.T * J_v + J_w.T * I_W * J_w
        V -= m * (g.T * c)[0]
    # Lagrange's equation with T = ½ q̇ᵀ M(q) q̇: ∂T/∂q_i − d/dt ∂T/∂q̇_i − ∂V/∂q_i − d_i q̇_i,
    # the acceleration terms M q̈ on the left
    Mv = M * vs
    f = sp.Matrix([(vs.T * M.diff(q[i]) * vs)[0] / 2 - sum(Mv[i].diff(q[k]) * vs[k] for k in range(n))
                   - V.diff(q[i]) - damping[i] * vs[i] for i in range(n)])
    qs = q
    return sp.lambdify([qs, list(vs)], M, "numpy", cse=True), sp.lambdify([qs, list(vs)], f, "numpy", cse=True), n


@pytest.fixture(scope="module")
def cart_arm_sympy():
    return sympy_model(CART_ARM)


def test_cart_arm_against_sympy(cart_arm_sympy):
    M_of, f_of, n = cart_arm_sympy
    robot = rigid.robot.Robot(CART_ARM)
    assert robot.dof == n == 3
    assert robot.coordinates == ["x", "shoulder", "elbow"]
    rng = np.random.default_rng(4)
    for _ in range(10):
        q, v = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
        M_ref = np.array(M_of(q, v), dtype=float)
        f_ref = np.array(f_of(q, v), dtype=float).reshape(n)
        M = robot.mass_matrix(q)
        f = -robot.bias_forces(q, v) + robot.passive_forces(q, v)
        assert np.max(np.abs(M - M_ref)) <= REL * np.max(np.abs(M_ref))
        assert np.max(np.abs(f - f_ref)) <= REL * max(1.0, np.max(np.abs(f_ref)))


def test_inverse_and_forward_dynamics_agree():
    robot = rigid.robot.Robot(ARM7)
    rng = np.random.default_rng(5)
    q, v, a = (rng.uniform(-1, 1, robot.dof) for _ in range(3))
    tau = robot.inverse_dynamics(q, v, a)
    np.testing.assert_allclose(tau, robot.mass_matrix(q) @ a + robot.bias_forces(q, v) - robot.passive_forces(q, v),
                               rtol=0, atol=1e-12 * max(1.0, np.max(np.abs(tau))))
    np.testing.assert_allclose(robot.forward_dynamics(q, v, tau), a, rtol=0, atol=1e-10)
    T, V = robot.energy(q, v)
    assert T == pytest.approx(0.5 * v @ robot.mass_matrix(q) @ v, rel=1e-14)


def test_pendulum_closed_form(tmp_path):
    # a bob of 2 kg at 0.5 m below a y hinge, inertia 0.02 about y: M = 0.02 + 2·0.25,
    # b = m g l sin θ
    f = tmp_path / "pendulum.urdf"
    f.write_text("""<robot name="p"><link name="base"/>
<link name="bob"><inertial><origin xyz="0 0 -0.5"/><mass value="2"/>
<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.015"/></inertial></link>
<joint name="theta" type="continuous"><parent link="base"/><child link="bob"/><axis xyz="0 1 0"/></joint>
</robot>""")
    robot = rigid.robot.Robot(f)
    for th in (-1.0, 0.0, 0.4):
        assert robot.mass_matrix([th])[0, 0] == pytest.approx(0.52, rel=1e-15)
        assert robot.bias_forces([th], [0.3])[0] == pytest.approx(2 * 9.81 * 0.5 * np.sin(th), rel=1e-14, abs=1e-15)


def test_refusals(tmp_path):
    robot = rigid.robot.Robot(ARM7)
    with pytest.raises(rigid.Error, match=r"q.*\(7,\)"):
        robot.mass_matrix([0.0, 1.0])
    with pytest.raises(rigid.Error, match="q_dot"):
        robot.bias_forces(np.zeros(7), [np.nan] * 7)
    bad = tmp_path / "floating.urdf"
    bad.write_text("""<robot name="f"><link name="a"/><link name="b"/><link name="c"/>
<joint name="hinge" type="continuous"><parent link="a"/><child link="b"/></joint>
<joint name="free" type="floating"><parent link="b"/><child link="c"/></joint></robot>""")
    with pytest.raises(rigid.Error, match=r"floating\.urdf:3.*'free'.*only from the root link 'a'"):
        rigid.robot.Robot(bad)
    assert rigid.robot.Robot("/usr/share/mujoco/model/humanoid/humanoid.xml", pin_free_root=True).dof == 21


def test_free_root_uses_mujocos_qpos_and_qvel():
    robot = rigid.robot.Robot("/usr/share/mujoco/model/humanoid/humanoid.xml")
    assert (robot.nq, robot.nv, robot.dof) == (28, 27, 27)
    assert robot.coordinates[:8] == ["root_x", "root_y", "root_z", "root_qw", "root_qx", "root_qy",
                                     "root_qz", "abdomen_z"]
    assert robot.velocities[:7] == ["root_vx", "root_vy", "root_vz", "root_wx", "root_wy", "root_wz",
                                    "abdomen_z"]
    q = robot.reference_configuration
    np.testing.assert_array_equal(q[:7], [0, 0, 1.5, 1, 0, 0, 0])  # the torso's placement
    assert robot.mass_matrix(q).shape == (27, 27)
    # at rest with no force the whole body falls: the root's vertical acceleration is g
    v_dot = robot.forward_dynamics(q, np.zeros(27), np.zeros(27))
    assert v_dot[2] == pytest.approx(-9.81, rel=1e-9)  # M is solved: cond(M) ~ 1e4
    with pytest.raises(rigid.Error, match=r"q_dot.*\(27,\)"):
        robot.bias_forces(q, np.zeros(28))
    q[3] = 2.0
    with pytest.raises(rigid.Error, match="joint 'root' .*unit quaternion"):
        robot.mass_matrix(q)


def test_threads_share_one_robot():
    # an immutable model: four threads calling it at once give the serial answers bit for bit
    robot = rigid.robot.Robot(ARM7)
    rng = np.random.default_rng(6)
    states = [(rng.uniform(-1, 1, 7), rng.uniform(-1, 1, 7)) for _ in range(50)]
    expected = [(robot.mass_matrix(q), robot.bias_forces(q, v)) for q, v in states]
    failures = []

    def work():
        for _ in range(20):
            for (q, v), (M, b) in zip(states, expected):
                if not (np.array_equal(robot.mass_matrix(q), M) and np.array_equal(robot.bias_forces(q, v), b)):
                    failures.append((q, v))

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not failures


def test_a_deep_trees_equations_carry_their_intermediates():
    # arm7 (7 joints on one chain) is derived by the tree's recursions: M and f name the
    # intermediates, each defined before use; cart_arm (3 joints) keeps the expanded form
    eq = rigid.Scene(str(ROOT / "examples" / "arm7.urdf")).system.equations()
    names = [name.text for name, _ in eq.intermediates]
    assert len(names) == len(set(names)) > 50
    defined = set()
    for name, value in eq.intermediates:
        used = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", value.text)) & set(names)
        assert used <= defined, (name.text, used - defined)
        defined.add(name.text)
    assert any(n in eq.mass_matrix[1][1].text for n in names)
    assert rigid.Scene(str(ROOT / "examples" / "cart_arm.urdf")).system.equations().intermediates == []
