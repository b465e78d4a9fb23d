"""Bad array input from Python, for every function that takes an array: a wrong shape, a dtype
that is not real numbers (complex, strings), NaN, a ragged list and an object that is no array
each get a clear error naming the function, the argument and the expected shape, never a crash
and never pybind11's "incompatible function arguments"; non-contiguous, read-only and integer
arrays are accepted and give the same numbers as a plain float64 array."""
import re

import numpy as np
import pytest

import rigid

BOX = rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7)
BALL = rigid.mass.n_ball_with_mass(1.0, 1.0, 3)
LAMINA = rigid.mass.disk_lamina_with_mass(1.0, 0.5)
TOP = rigid.body.HeavyTop(rigid.mass.solid_cone_with_mass(1.0, 0.05, 0.2), [0, 0, 0.2])
BODY = rigid.body.RigidBody(BOX)
NET = rigid.spring.network_with_inertia(BOX, 1e3)
SYSTEM = rigid.lagrange.System([("x", 0.1, 0.0)], lagrangian="x_dot^2/2 - x^2/2")
CUBE_V = np.array([[(i & 1), (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], float)
CUBE_F = np.array([(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3),
                   (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)])
CUBE = rigid.mesh.TriangleMesh(CUBE_V, CUBE_F)
Q1 = np.array([1.0, 0, 0, 0])
W = np.array([0.1, 1.0, 0.2])
I3 = np.array([1.0, 2.0, 2.5])
# Lie-group samples: a rotation of the plane, of space (a rotation by 0.7 rad about (0, 0.6, 0.8)),
# of R^4, motions, and Lie-algebra matrices (hat of a tangent vector, built by hand)
ROT2 = np.array([[np.cos(0.4), -np.sin(0.4)], [np.sin(0.4), np.cos(0.4)]])
SO2_R = rigid.SO2.from_angle(0.4)
SE2_X = rigid.SE2(SO2_R, [0.5, -1.0])
SE2_HAT = np.array([[0, -0.3, 0.1], [0.3, 0, 0.2], [0, 0, 0.0]])
SO3_HAT = np.array([[0, -0.2, 1.0], [0.2, 0, -0.1], [-1.0, 0.1, 0]])
SO3_R = rigid.SO3.from_axis_angle([0.0, 0.6, 0.8], 0.7)
ROT3 = SO3_R.matrix()
SE3_X = rigid.SE3(SO3_R, [0.5, -1.0, 2.0])
SE3_HAT = np.vstack([np.hstack([SO3_HAT, [[1.0], [2.0], [3.0]]]), np.zeros((1, 4))])
XI6 = np.array([0.1, -0.2, 0.3, 0.4, -0.5, 0.6])
SOn_R = rigid.SOn.exp(XI6)  # n = 4: 6 = 4·3/2 coordinates
SOn_HAT = np.triu(np.arange(1.0, 17.0).reshape(4, 4), 1)
SOn_HAT = SOn_HAT - SOn_HAT.T
SEn_X = rigid.SEn(rigid.SOn.exp([0.1, 0.2, 0.3]), [1.0, 2.0, 3.0])  # n = 3
SEn_HAT = np.vstack([np.hstack([SO3_HAT, [[1.0], [2.0], [3.0]]]), np.zeros((1, 4))])

# (function as named in messages, argument, expected shape, call with the argument x, a good x,
#  whether NaN is refused)
CASES = [
    ("rigid.MassProperties", "p_OC_B", "(3,)", lambda x: rigid.MassProperties(1.0, x, np.eye(3)), [0.1, 0, 0], True),
    ("rigid.MassProperties", "I_C_B", "(3, 3)", lambda x: rigid.MassProperties(1.0, [0, 0, 0], x), np.eye(3), True),
    ("rigid.MassProperties.check", "p_OC_B", "(3,)", lambda x: rigid.MassProperties.check(1.0, x, np.eye(3)), [0, 0, 0.0], False),
    ("MassProperties.inertia_about", "p_OQ_B", "(3,)", BOX.inertia_about, [0.1, 0.2, 0.3], True),
    ("MassProperties.inertia_about_axis", "unit_B", "(3,)", lambda x: BOX.inertia_about_axis([0, 0, 0], x), [0, 0, 1.0], True),
    ("MassProperties.shifted", "d_B", "(3,)", BOX.shifted, [0.1, 0.2, 0.3], True),
    ("MassProperties.rotated", "R_AB", "(3, 3)", BOX.rotated, np.eye(3), True),
    ("MassProperties.transformed", "p_AB_A", "(3,)", lambda x: BOX.transformed(np.eye(3), x), [1.0, 2, 3], True),
    ("rigid.MassProperties2", "p_OC_B", "(2,)", lambda x: rigid.MassProperties2(1.0, x, 0.5), [0.1, 0.2], True),
    ("MassProperties2.moment_about", "p_OQ_B", "(2,)", LAMINA.moment_about, [0.1, 0.2], True),
    ("rigid.SecondMoments", "com", "(n,)", lambda x: rigid.SecondMoments(1.0, x, np.eye(2)), [0.1, 0.2], True),
    ("SecondMoments.J_about", "q", "(3,)", BALL.J_about, [0.1, 0.2, 0.3], True),
    ("SecondMoments.apply", "Omega", "(3, 3)", BALL.apply, [[0, 1, 0], [-1, 0, 0], [0, 0, 0.0]], True),
    ("rigid.mass.point_mass", "p", "(3,)", lambda x: rigid.mass.point_mass(1.0, x), [0.1, 0.2, 0.3], True),
    ("rigid.mass.point_masses", "masses", "(n,)", lambda x: rigid.mass.point_masses(x, [[0, 0, 0], [1, 0, 0]]), [1.0, 2.0], True),
    ("rigid.mass.point_masses", "points", "(n, 3)", lambda x: rigid.mass.point_masses([1.0, 2.0], x), [[0, 0, 0], [1.0, 0, 0]], True),
    ("rigid.mass.n_box_with_mass", "sizes", "(n,)", lambda x: rigid.mass.n_box_with_mass(1.0, x), [0.1, 0.2, 0.3, 0.4], True),
    ("rigid.mass.solid_tetrahedron_with_mass", "v1", "(3,)",
     lambda x: rigid.mass.solid_tetrahedron_with_mass(1.0, [0, 0, 0], x, [0, 1, 0], [0, 0, 1]), [1.0, 0, 0], True),
    ("rigid.mass.solid_tetrahedron", "v2", "(3,)",
     lambda x: rigid.mass.solid_tetrahedron(mass=1.0, v0=[0, 0, 0], v1=[1, 0, 0], v2=x, v3=[0, 0, 1]), [0, 1.0, 0], True),
    ("rigid.mass.polygon_lamina_with_mass", "vertices", "(n, 2)",
     lambda x: rigid.mass.polygon_lamina_with_mass(1.0, x), [[0, 0], [1, 0], [1, 1], [0, 1.0]], True),
    ("rigid.mass.place", "origin", "(3,)", lambda x: rigid.mass.place(BOX, origin=x), [0.1, 0, 0], True),
    ("rigid.mass.place", "rpy", "(3,)", lambda x: rigid.mass.place(BOX, rpy=x), [0.1, 0, 0], True),
    ("rigid.mass.placement_rotation", "rpy", "(3,)", lambda x: rigid.mass.placement_rotation("x", x), [0.1, 0, 0], True),
    ("rigid.mass.write_inertial_document", "inertial_frame", "(3, 3)",
     lambda x: rigid.mass.write_inertial_document(BOX, "urdf", principal=True, inertial_frame=x), np.eye(3), True),
    ("rigid.mass.from_pseudo_inertia", "J", "(4, 4)", rigid.mass.from_pseudo_inertia,
     rigid.mass.pseudo_inertia(BOX), True),
    ("rigid.mass.from_log_cholesky", "theta", "(10,)", rigid.mass.from_log_cholesky, np.linspace(0, 0.9, 10), True),
    ("rigid.mass.pseudo_inertia_from_log_cholesky", "theta", "(10,)", rigid.mass.pseudo_inertia_from_log_cholesky,
     np.linspace(0, 0.9, 10), True),
    ("rigid.mesh.TriangleMesh", "vertices", "(n, 3)", lambda x: rigid.mesh.TriangleMesh(x, CUBE_F), CUBE_V, True),
    ("rigid.mesh.vertex_noise_uncertainty", "about", "(3,)",
     lambda x: rigid.mesh.vertex_noise_uncertainty(CUBE, 1e-4, density=1.0, about=x), [0.5, 0.5, 0.5], True),
    ("rigid.body.FreeBodyExact", "principal_moments", "(3,)", lambda x: rigid.body.FreeBodyExact(x, W).omega_body(1.0), I3, True),
    ("rigid.body.FreeBodyExact", "omega_body", "(3,)", lambda x: rigid.body.FreeBodyExact(I3, x).omega_body(1.0), W, True),
    ("rigid.body.FreeBodyMotion", "q_wxyz", "(4,)", lambda x: rigid.body.FreeBodyMotion(I3, x, W).orientation(1.0), Q1, True),
    ("rigid.body.simulate_free_body", "times", "(n,)",
     lambda x: rigid.body.simulate_free_body("rk4", I3, Q1, W, 0.1, x), [0.5, 1.0], True),
    ("rigid.body.simulate_free_body", "principal_moments", "(3,)",
     lambda x: rigid.body.simulate_free_body("rk4", x, Q1, W, 0.1, [0.5]), I3, True),
    ("rigid.body.step_free_body", "q_wxyz", "(4,)", lambda x: rigid.body.step_free_body("splitting2", I3, x, W, 0.01), Q1, True),
    ("rigid.body.step_free_body", "omega_body", "(3,)", lambda x: rigid.body.step_free_body("splitting2", I3, Q1, x, 0.01), W, True),
    ("rigid.body.step_free_bodies", "omega_body", "(2, 3)",
     lambda x: rigid.body.step_free_bodies("splitting4", [I3, I3], [Q1, Q1], x, 0.01), [W, 2 * W], True),
    ("rigid.body.euler_rhs", "torque_body", "(3,)", lambda x: rigid.body.euler_rhs(I3, W, x), [0.1, 0, 0], True),
    ("rigid.body.rotational_energy", "omega_body", "(3,)", lambda x: rigid.body.rotational_energy(I3, x), W, True),
    ("rigid.body.euler_arnold_rhs", "J", "(n,)", lambda x: rigid.body.euler_arnold_rhs(x, np.zeros((3, 3))), [1.0, 2, 3], True),
    ("rigid.body.euler_arnold_rk4_step", "M", "(4, 4)",
     lambda x: rigid.body.euler_arnold_rk4_step([1.0, 2, 3, 4], x, 0.01), np.triu(np.ones((4, 4)), 1) - np.tril(np.ones((4, 4)), -1), True),
    ("rigid.body.RigidBody", "inertia", "(3, 3)", lambda x: rigid.body.RigidBody(1.0, x).principal_moments, np.eye(3), True),
    ("rigid.body.RigidBody", "gravity", "(3,)", lambda x: rigid.body.RigidBody(BOX, x).gravity, [0, 0, -9.81], True),
    ("RigidBody.step", "p_world", "(3,)",
     lambda x: BODY.step("splitting2", 0.0, Q1, W, x, [0, 0, 0], 0.01), [1.0, 2, 3], True),
    ("RigidBody.simulate", "times", "(n,)",
     lambda x: BODY.simulate("splitting2", Q1, W, [0, 0, 0], [0, 0, 0], 0.1, x), [0.5, 1.0], True),
    ("rigid.body.HeavyTop", "pivot", "(3,)", lambda x: rigid.body.HeavyTop(BOX, x).com_from_pivot, [0, 0, 0.5], True),
    ("HeavyTop.energy", "q_wxyz", "(4,)", lambda x: TOP.energy(x, W), Q1, True),
    ("HeavyTop.torque", "q_wxyz", "(4,)", TOP.torque, Q1, True),
    ("HeavyTop.step", "omega_body", "(3,)", lambda x: TOP.step(Q1, x, 1e-3), W, True),
    ("HeavyTop.simulate", "times", "(n,)", lambda x: TOP.simulate(Q1, W, 1e-3, x), [0.01, 0.02], True),
    ("rigid.spring.Network", "position", "(n, 3)",
     lambda x: rigid.spring.Network([1.0, 1.0], x, np.zeros((2, 3)), [(0, 1, 10.0, 1.0)]).energy(), [[0, 0, 0], [1.0, 0, 0]], True),
    ("Network.simulate", "times", "(n,)", lambda x: NET.simulate(1e-3, x)["energy"], [0.001, 0.002], True),
    ("rigid.lagrange.System", "gravity", "(3,)",
     lambda x: rigid.lagrange.System([("x", 0.0, 0.0)], lagrangian="x_dot^2/2", gravity=x).coordinate_names, [0, 0, -9.81], True),
    ("System.accelerations", "q", "(1,)", lambda x: SYSTEM.accelerations(0.0, x, [0.0]), [0.1], True),
    ("System.mass_matrix_and_forces", "q_dot", "(1,)", lambda x: SYSTEM.mass_matrix_and_forces(0.0, [0.1], x), [0.2], True),
    ("System.energy", "q", "(1,)", lambda x: SYSTEM.energy(0.0, x, [0.0]), [0.1], True),
    ("System.simulate", "q0", "(1,)", lambda x: SYSTEM.simulate(0.01, q0=x)["q"], [0.1], True),
    # the Lie groups (python/lie_py.cpp)
    ("rigid.SO2.from_matrix", "R", "(2, 2)", lambda x: rigid.SO2.from_matrix(x).angle(), ROT2, True),
    ("rigid.SO2.vee", "matrix", "(2, 2)", rigid.SO2.vee, [[0, -0.3], [0.3, 0.0]], True),
    ("SO2.__mul__", "other", "(2,)", lambda x: SO2_R * x, [1.0, 2.0], True),
    ("rigid.SE2", "t", "(2,)", lambda x: rigid.SE2(SO2_R, x).matrix(), [1.0, 2.0], True),
    ("rigid.SE2.exp", "xi", "(3,)", lambda x: rigid.SE2.exp(x).matrix(), [0.1, 0.2, 0.3], True),
    ("rigid.SE2.hat", "xi", "(3,)", rigid.SE2.hat, [0.1, 0.2, 0.3], True),
    ("rigid.SE2.vee", "matrix", "(3, 3)", rigid.SE2.vee, SE2_HAT, True),
    ("rigid.SE2.from_matrix", "T", "(3, 3)", lambda x: rigid.SE2.from_matrix(x).matrix(), SE2_X.matrix(), True),
    ("rigid.SE2.right_jacobian", "xi", "(3,)", rigid.SE2.right_jacobian, [0.1, 0.2, 0.3], True),
    ("rigid.SE2.left_jacobian_inverse", "xi", "(3,)", rigid.SE2.left_jacobian_inverse, [0.1, 0.2, 0.3], True),
    ("SE2.act_vector", "v", "(2,)", SE2_X.act_vector, [1.0, 2.0], True),
    ("SE2.__mul__", "other", "(2,)", lambda x: SE2_X * x, [1.0, 2.0], True),
    ("rigid.SO3.exp", "omega", "(3,)", lambda x: rigid.SO3.exp(x).quaternion(), W, False),  # NaN: below
    ("rigid.SO3.hat", "omega", "(3,)", rigid.SO3.hat, W, True),
    ("rigid.SO3.vee", "matrix", "(3, 3)", rigid.SO3.vee, SO3_HAT, True),
    ("rigid.SO3.from_matrix", "R", "(3, 3)", lambda x: rigid.SO3.from_matrix(x).quaternion(), ROT3, True),
    ("rigid.SO3.from_axis_angle", "axis", "(3,)", lambda x: rigid.SO3.from_axis_angle(x, 0.5).quaternion(),
     [0.0, 0.6, 0.8], True),
    ("rigid.SO3.from_euler", "angles", "(3,)", lambda x: rigid.SO3.from_euler(x).quaternion(), [0.1, 0.2, 0.3], False),
    ("rigid.SO3.right_jacobian", "omega", "(3,)", rigid.SO3.right_jacobian, W, True),
    ("rigid.SO3.left_jacobian", "omega", "(3,)", rigid.SO3.left_jacobian, W, True),
    ("rigid.SO3.right_jacobian_inverse", "omega", "(3,)", rigid.SO3.right_jacobian_inverse, W, True),
    ("rigid.SO3.left_jacobian_inverse", "omega", "(3,)", rigid.SO3.left_jacobian_inverse, W, True),
    ("SO3.__mul__", "other", "(3,)", lambda x: SO3_R * x, [1.0, 2.0, 3.0], True),
    ("rigid.SE3", "t", "(3,)", lambda x: rigid.SE3(SO3_R, x).matrix(), [1.0, 2.0, 3.0], True),
    ("rigid.SE3.exp", "xi", "(6,)", lambda x: rigid.SE3.exp(x).matrix(), XI6, True),
    ("rigid.SE3.hat", "xi", "(6,)", rigid.SE3.hat, XI6, True),
    ("rigid.SE3.vee", "matrix", "(4, 4)", rigid.SE3.vee, SE3_HAT, True),
    ("rigid.SE3.from_matrix", "T", "(4, 4)", lambda x: rigid.SE3.from_matrix(x).matrix(), SE3_X.matrix(), True),
    ("rigid.SE3.right_jacobian", "xi", "(6,)", rigid.SE3.right_jacobian, XI6, True),
    ("rigid.SE3.left_jacobian", "xi", "(6,)", rigid.SE3.left_jacobian, XI6, True),
    ("rigid.SE3.right_jacobian_inverse", "xi", "(6,)", rigid.SE3.right_jacobian_inverse, XI6, True),
    ("rigid.SE3.left_jacobian_inverse", "xi", "(6,)", rigid.SE3.left_jacobian_inverse, XI6, True),
    ("SE3.__mul__", "other", "(3,)", lambda x: SE3_X * x, [1.0, 2.0, 3.0], True),
    ("rigid.SOn.exp", "omega", "(n(n-1)/2,)", lambda x: rigid.SOn.exp(x).matrix(), XI6, True),
    ("rigid.SOn.hat", "omega", "(n(n-1)/2,)", rigid.SOn.hat, XI6, True),
    ("rigid.SOn.ad", "omega", "(n(n-1)/2,)", rigid.SOn.ad, XI6, True),
    ("rigid.SOn.vee", "matrix", "(n, n)", rigid.SOn.vee, SOn_HAT, True),
    ("rigid.SOn.from_matrix", "R", "(n, n)", lambda x: rigid.SOn.from_matrix(x).matrix(), SOn_R.matrix(), True),
    ("rigid.SOn.right_jacobian", "omega", "(n(n-1)/2,)", rigid.SOn.right_jacobian, XI6, True),
    ("rigid.SOn.left_jacobian_inverse", "omega", "(n(n-1)/2,)", rigid.SOn.left_jacobian_inverse, XI6, True),
    ("SOn.__mul__", "other", "(4,)", lambda x: SOn_R * x, [1.0, 2.0, 3.0, 4.0], True),
    ("rigid.SEn", "t", "(4,)", lambda x: rigid.SEn(SOn_R, x).matrix(), [1.0, 2.0, 3.0, 4.0], True),
    ("rigid.SEn.exp", "xi", "(n(n+1)/2,)", lambda x: rigid.SEn.exp(x).matrix(), XI6, True),
    ("rigid.SEn.hat", "xi", "(n(n+1)/2,)", rigid.SEn.hat, XI6, True),
    ("rigid.SEn.ad", "xi", "(n(n+1)/2,)", rigid.SEn.ad, XI6, True),
    ("rigid.SEn.vee", "matrix", "(n+1, n+1)", rigid.SEn.vee, SEn_HAT, True),
    ("rigid.SEn.from_matrix", "T", "(n+1, n+1)", lambda x: rigid.SEn.from_matrix(x).matrix(), SEn_X.matrix(), True),
    ("rigid.SEn.left_jacobian", "xi", "(n(n+1)/2,)", rigid.SEn.left_jacobian, XI6, True),
    ("rigid.SEn.right_jacobian_inverse", "xi", "(n(n+1)/2,)", rigid.SEn.right_jacobian_inverse, XI6, True),
    ("SEn.act_vector", "v", "(3,)", SEn_X.act_vector, [1.0, 2.0, 3.0], True),
    ("SEn.__mul__", "other", "(3,)", lambda x: SEn_X * x, [1.0, 2.0, 3.0], True),
    ("rigid.check_orthogonal", "M", "(n, n)", lambda x: rigid.check_orthogonal(x).defect, ROT3, True),
    ("rigid.nearest_rotation", "M", "(n, n)", rigid.nearest_rotation, ROT3 + 1e-3, True),
]
IDS = [f"{c[0]}-{c[1]}" for c in CASES]
# arguments whose None is the default (no frame, the COM, the system's initial state)
OPTIONAL = {("rigid.mass.write_inertial_document", "inertial_frame"), ("rigid.mesh.vertex_noise_uncertainty", "about"),
            ("System.simulate", "q0")}


def canon(x):
    """Results as nested lists and floats, so two calls compare exactly."""
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, (list, tuple)):
        return [canon(e) for e in x]
    if isinstance(x, dict):
        return {k: canon(v) for k, v in x.items()}
    if isinstance(x, (float, int, str, type(None))):
        return x
    fields = [f for f in ("mass", "com", "inertia_com", "moment_com", "J_com", "vertices", "triangles")
              if hasattr(x, f)]
    assert fields, f"no way to compare {type(x).__name__}"
    return {f: canon(getattr(x, f)) for f in fields}


def prefix(function, argument):
    return re.escape(f"{function}(): argument '{argument}'")


@pytest.mark.parametrize("function, argument, shape, call, good, finite", CASES, ids=IDS)
def test_wrong_shape_names_function_argument_and_shape(function, argument, shape, call, good, finite):
    bad = np.zeros(np.shape(good) + (2,))  # one dimension too many: wrong for every argument
    got = "(" + ", ".join(map(str, bad.shape)) + ")"
    with pytest.raises(rigid.Error, match=prefix(function, argument)
                       + re.escape(f" must have shape {shape}; got {got}")):
        call(bad)


@pytest.mark.parametrize("function, argument, shape, call, good, finite", CASES, ids=IDS)
@pytest.mark.parametrize("dtype", [complex, str])
def test_complex_and_string_dtypes_are_refused(function, argument, shape, call, good, finite, dtype):
    bad = np.asarray(good).astype(dtype)
    with pytest.raises(rigid.Error, match=prefix(function, argument) + r" must hold real numbers .*"
                       + re.escape(f"of shape {shape}; got dtype {bad.dtype}")):
        call(bad)


@pytest.mark.parametrize("function, argument, shape, call, good, finite", CASES, ids=IDS)
def test_nan_and_inf_are_refused_where_a_number_is_needed(function, argument, shape, call, good, finite):
    for value in (np.nan, np.inf):
        bad = np.array(good, dtype=float)
        bad.flat[bad.size - 1] = value
        index = ", ".join(str(i) for i in np.unravel_index(bad.size - 1, bad.shape))
        if finite:
            with pytest.raises(rigid.Error, match=prefix(function, argument)
                               + re.escape(f" must be finite; got {value} at [{index}]")):
                call(bad)


@pytest.mark.parametrize("function, argument, shape, call, good, finite", CASES, ids=IDS)
def test_an_object_that_is_no_array_is_a_type_error(function, argument, shape, call, good, finite):
    for bad in ({"a": 1}, "abc") if (function, argument) in OPTIONAL else (None, {"a": 1}, "abc"):
        with pytest.raises(TypeError, match=prefix(function, argument)
                           + re.escape(f" must be an array of numbers of shape {shape}; got {type(bad).__name__}")):
            call(bad)


@pytest.mark.parametrize("function, argument, shape, call, good, finite", CASES, ids=IDS)
def test_non_contiguous_read_only_and_list_input_give_the_same_numbers(function, argument, shape, call, good, finite):
    reference = canon(call(np.array(good, dtype=float)))
    # every other element of a twice-as-wide array: a strided, read-only view
    wide = np.repeat(np.array(good, dtype=float), 2, axis=-1)
    view = wide[..., ::2]
    view.flags.writeable = False
    assert not view.flags.c_contiguous or view.ndim == 0 or view.size <= 1
    assert canon(call(view)) == reference
    # the transpose of a transposed copy: Fortran order
    fortran = np.asfortranarray(np.array(good, dtype=float))
    assert canon(call(fortran)) == reference
    assert canon(call(np.array(good, dtype=float).tolist())) == reference


def test_ragged_lists_are_refused_as_not_rectangular():
    with pytest.raises(rigid.Error, match=re.escape("rigid.mass.point_masses(): argument 'points' must be an "
                                                    "array of numbers of shape (n, 3); got a list that is not rectangular")):
        rigid.mass.point_masses([1.0, 1.0], [[0, 0, 0], [1, 0]])


def test_integer_arrays_are_numbers():
    ints = rigid.mass.point_masses(np.array([1, 2], np.int32), np.array([[0, 0, 0], [3, 0, 0]], np.int64))
    floats = rigid.mass.point_masses([1.0, 2.0], [[0.0, 0, 0], [3.0, 0, 0]])
    assert canon(ints) == canon(floats)
    # unsigned and small integer dtypes too
    assert canon(rigid.mass.point_mass(1.0, np.array([1, 2, 3], np.uint8))) == canon(rigid.mass.point_mass(1.0, [1.0, 2, 3]))


def test_booleans_are_not_numbers():
    with pytest.raises(rigid.Error, match=r"argument 'p' must hold real numbers .* got dtype bool"):
        rigid.mass.point_mass(1.0, np.array([True, False, True]))


def test_points_as_columns_are_refused_with_the_transpose_named():
    # (3, n) for n ≠ 3 is the transpose of the convention: refused, naming .T; (3, 3) is read as rows
    cols = np.array([[0.0, 1.0], [0.0, 0.0], [0.0, 0.0]])
    with pytest.raises(rigid.Error, match=re.escape("rigid.mass.point_masses(): argument 'points' must have shape "
                                                    "(n, 3); got (3, 2) (one point per row: pass points.T")):
        rigid.mass.point_masses([1.0, 1.0], cols)
    mp = rigid.mass.point_masses([1.0, 1.0], cols.T)
    np.testing.assert_array_equal(mp.com, [0.5, 0, 0])
    rows = np.array([[1.0, 0, 0], [0, 2.0, 0], [0, 0, 3.0]])
    np.testing.assert_array_equal(rigid.mass.point_masses([1.0, 1.0, 1.0], rows).com, [1 / 3, 2 / 3, 1.0])


def test_triangle_indices_must_be_integers():
    with pytest.raises(rigid.Error, match=re.escape("rigid.mesh.TriangleMesh(): argument 'triangles' must hold "
                                                    "integer vertex indices; got dtype float64")):
        rigid.mesh.TriangleMesh(CUBE_V, CUBE_F.astype(float))
    with pytest.raises(rigid.Error, match=re.escape("argument 'triangles' must have shape (m, 3); got (12, 2)")):
        rigid.mesh.TriangleMesh(CUBE_V, CUBE_F[:, :2])
    with pytest.raises(TypeError, match="argument 'triangles' must be an integer array"):
        rigid.mesh.TriangleMesh(CUBE_V, None)
    # a strided, read-only index array of another integer type
    wide = np.repeat(CUBE_F.astype(np.int16), 2, axis=1)[:, ::2]
    wide.flags.writeable = False
    assert len(rigid.mesh.TriangleMesh(CUBE_V, wide)) == 12


def test_counts_that_disagree_are_named():
    with pytest.raises(rigid.Error, match=re.escape("rigid.mass.point_masses(): 3 masses and 2 points; expected "
                                                    "one mass per point (row)")):
        rigid.mass.point_masses([1.0, 1.0, 1.0], [[0, 0, 0], [1, 0, 0]])
    with pytest.raises(rigid.Error, match=re.escape("rigid.body.step_free_bodies(): argument 'q_wxyz' must have "
                                                    "shape (2, 4); got (1, 4)")):
        rigid.body.step_free_bodies("splitting2", [I3, I3], [Q1], [W, W], 0.01)


def test_a_quaternion_that_is_not_unit_is_named():
    with pytest.raises(rigid.Error, match=r"rigid\.body\.step_free_body\(\): argument 'q_wxyz': quaternion "
                                          r"\(w, x, y, z\) = \(2, 0, 0, 0\) has norm 2; expected a unit quaternion"):
        rigid.body.step_free_body("splitting2", I3, [2.0, 0, 0, 0], W, 0.01)


@pytest.mark.parametrize("bad", ["a", True, [1.0, 2.0], None, 1j])
def test_catalogue_keywords_must_be_numbers(bad):
    with pytest.raises(TypeError, match=re.escape("rigid.mass.cylinder(): argument 'mass' must be a number; got ")):
        rigid.mass.cylinder(mass=bad, radius=0.1, height=0.5)
    with pytest.raises(TypeError, match=re.escape("rigid.mass.solid_box(): argument 'lx' must be a number")):
        rigid.mass.solid_box(density=1.0, lx=bad, ly=1.0, lz=1.0)
    # numpy scalars are numbers
    assert rigid.mass.cylinder(mass=np.float32(2.0), radius=np.int64(1), height=0.5).mass == 2.0


@pytest.mark.parametrize("omega, tail", [
    ([0.0, np.nan, 0.0], "rotation vector [0, nan, 0] has a non-finite component"),
    ([0.0, 0.0, -np.inf], "rotation vector [0, 0, -inf] has a non-finite component"),
    ([1e200, 0.0, 0.0], "rotation vector [1e+200, 0, 0] is too long: |ω|² overflows"),
])
def test_scalar_so3_exp_refuses_what_the_batch_refuses_in_its_words(omega, tail):
    # SO3.exp of such a vector would be NaN: refused, as rigid.so3.exp refuses a single element
    with pytest.raises(rigid.Error) as scalar:
        rigid.SO3.exp(np.array(omega))
    with pytest.raises(rigid.Error) as batch:
        rigid.so3.exp(np.array(omega))
    assert str(scalar.value) == "rigid.SO3.exp(): argument 'omega': " + tail
    assert str(batch.value) == "so3.exp(): argument 'omega': " + tail


def test_mul_of_a_lie_group_refuses_another_group_as_a_type_error():
    # `*` takes an element of the same group or an array; anything else is no array of numbers
    with pytest.raises(TypeError, match=prefix("SO3.__mul__", "other")
                       + re.escape(" must be an array of numbers of shape (3,); got SE3")):
        SO3_R * SE3_X
    with pytest.raises(TypeError, match=prefix("SE2.__mul__", "other") + r" .* got SO2"):
        SE2_X * SO2_R
    # SOn acts on vectors of its own n
    with pytest.raises(rigid.Error, match=prefix("SOn.__mul__", "other") + re.escape(" must have shape (4,); got (3,)")):
        SOn_R * np.ones(3)
    with pytest.raises(rigid.Error, match=prefix("rigid.SEn", "t") + re.escape(" must have shape (4,); got (3,)")):
        rigid.SEn(SOn_R, np.ones(3))


def test_square_matrices_are_required_where_n_is_free():
    with pytest.raises(rigid.Error, match=prefix("rigid.SOn.from_matrix", "R") + re.escape(" must have shape (n, n); got (3, 4)")):
        rigid.SOn.from_matrix(np.zeros((3, 4)))
    with pytest.raises(rigid.Error, match=prefix("rigid.SEn.vee", "matrix") + re.escape(" must have shape (n+1, n+1); got (4, 3)")):
        rigid.SEn.vee(np.zeros((4, 3)))
    with pytest.raises(rigid.Error, match=prefix("rigid.check_orthogonal", "M") + re.escape(" must have shape (n, n); got (2, 3)")):
        rigid.check_orthogonal(np.zeros((2, 3)))
    # a tangent vector whose length is no n(n-1)/2 is the library's to refuse, as before
    with pytest.raises(rigid.Error, match="tangent vector has 4 components"):
        rigid.SOn.exp(np.zeros(4))


def test_batch_arguments_are_read_by_the_same_converter():
    # rigid.so3 takes (N, k) or (k,) through convert.hpp: the same refusals, in the same words,
    # as the scalar functions (with the batch's expected shape)
    with pytest.raises(TypeError, match=re.escape("so3.exp(): argument 'omega' must be an array of numbers of shape "
                                                  "(N, 3) or (3,); got NoneType")):
        rigid.so3.exp(None)
    with pytest.raises(rigid.Error, match=re.escape("so3.act(): argument 'v' must hold real numbers (a float or integer "
                                                    "dtype) of shape (N, 3) or (3,); got dtype complex128")):
        rigid.so3.act(Q1, np.ones(3, complex))
    with pytest.raises(rigid.Error, match=re.escape("so3.compose(): argument 'b' must be an array of numbers of shape "
                                                    "(N, 4) or (4,); got a list that is not rectangular")):
        rigid.so3.compose(Q1, [[1, 0, 0, 0], [1, 0, 0]])
    # and the same conversions: a strided, read-only int8 array gives the numbers of its float64 copy
    v = np.repeat(np.array([[1, 2, 3]], np.int8), 2, axis=1)[:, ::2]
    v.flags.writeable = False
    assert np.array_equal(rigid.so3.act(Q1, v), rigid.so3.act(Q1, np.array([[1.0, 2.0, 3.0]])))


# An angle is a float, not an array: NaN and infinity are refused by name, as array arguments are
# (the rotation of a NaN angle would be NaN in every entry).
@pytest.mark.parametrize("function", ["exp", "from_angle", "hat"])
@pytest.mark.parametrize("theta", [float("nan"), float("inf"), -float("inf")])
def test_so2_angles_must_be_finite(function, theta):
    with pytest.raises(rigid.Error, match=rf"rigid\.SO2\.{function}\(\): argument 'theta' must be finite"):
        getattr(rigid.SO2, function)(theta)
    # a finite angle still works: exp(π/2) rotates x onto y
    assert np.allclose(rigid.SO2.exp(np.pi / 2).matrix(), [[0, -1], [1, 0]], atol=1e-15)
