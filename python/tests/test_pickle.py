"""Pickling of the value types: pickle and multiprocessing ship them bit for bit."""
import copy
import multiprocessing
import pickle
import re

import numpy as np
import pytest

import rigid


def state_bits(x):
    # every number a value holds, as bytes: two values are equal bit for bit when these are
    # (NaN-safe and -0.0-aware, unlike ==)
    return [np.ascontiguousarray(np.asarray(v, dtype=float)).tobytes() for v in x.__getstate__()]


def values():
    so3 = rigid.SO3.exp([0.3, -1.2, 2.9])
    son = rigid.SOn.exp(np.linspace(-1.0, 1.3, 6))  # n = 4
    return [
        rigid.SO2.exp(2.0) * rigid.SO2.exp(1.1),  # a composition: (c, s) need not have norm 1 exactly
        rigid.SE2.exp([0.1, -2.0, 0.7]),
        so3,
        rigid.SE3(so3, [1e-300, -0.0, 3.5]),
        son,
        rigid.SEn(son, [0.5, -1.0, 2.0, 1.0 / 3.0]),
        rigid.mass.solid_box_with_mass(2.5, 0.1, 0.2, 0.3).rotated(so3.matrix()).shifted([0.1, 0, -0.2]),
        rigid.MassProperties2(1.5, [0.25, -1.0 / 3.0], 0.125),
        rigid.SecondMoments.from_mass_properties(rigid.mass.cylinder(mass=2.0, radius=0.1, height=0.5)),
        rigid.mesh.TriangleMesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0 / 3.0]],
                                [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]),
    ]


def echo(x):
    # run in a worker process: the value came pickled and goes back pickled
    return x, state_bits(x)


@pytest.mark.parametrize("value", values(), ids=lambda v: type(v).__name__)
def test_pickle_round_trip_is_bit_for_bit(value):
    for protocol in (2, pickle.HIGHEST_PROTOCOL):
        back = pickle.loads(pickle.dumps(value, protocol))
        assert type(back) is type(value)
        assert state_bits(back) == state_bits(value)
        assert repr(back) == repr(value)
    assert state_bits(copy.deepcopy(value)) == state_bits(value)


def test_multiprocessing_ships_every_value_type():
    sent = values()
    with multiprocessing.get_context("fork").Pool(2) as pool:
        received = pool.map(echo, sent)
    for x, (back, bits_there) in zip(sent, received):
        assert type(back) is type(x)
        assert bits_there == state_bits(x)  # what the worker got
        assert state_bits(back) == state_bits(x)  # and what came back


def test_groups_act_alike_after_the_trip():
    # the restored element is the same element, not only the same numbers: compose and act
    v = np.array([0.3, -0.4, 1.2])
    for X in (rigid.SO3.exp([0.3, -1.2, 2.9]), rigid.SE3.exp([1, 2, 3, 0.1, 0.2, 0.3])):
        Y = pickle.loads(pickle.dumps(X))
        assert np.array_equal(Y * v, X * v)
        assert np.array_equal((Y * X).matrix(), (X * X).matrix())


@pytest.mark.parametrize("cls, state, words", [
    (rigid.SO3, (np.array([2.0, 0, 0, 0]),), "not a unit quaternion"),
    (rigid.SO3, (np.array([1.0, 0, 0]),),
     "rigid.SO3.__setstate__(): argument 'state[0] (quaternion wxyz)' must have shape (4,)"),
    (rigid.SO2, (0.6, 0.6), "not a unit complex number"),
    (rigid.SO2, (1.0,), "tuple of 2 values"),
    (rigid.SOn, (np.array([[1.0, 0.1], [0.0, 1.0]]),), "not a rotation"),
    (rigid.MassProperties, (-1.0, np.zeros(3), np.eye(3)), "mass must be positive"),
])
def test_damaged_state_is_refused(cls, state, words):
    obj = cls.__new__(cls)
    with pytest.raises(rigid.Error, match=re.escape(words)):
        obj.__setstate__(state)
