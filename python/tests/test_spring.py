"""rigid.spring: the network has the body's mass properties, is at rest in equilibrium, and the
implicit midpoint keeps momentum and angular momentum (linear and quadratic invariants)."""
import numpy as np
import pytest

import rigid

EPS = np.finfo(float).eps


def box_network(k=1e4):
    box = rigid.mass.solid_box_with_mass(2.0, 0.3, 0.5, 0.7).shifted([0.1, -0.2, 0.3])
    return box, rigid.spring.network_with_inertia(box, k)


def test_network_has_the_mass_properties_of_the_body():
    box, net = box_network()
    m, p = net.mass, net.position
    assert p.shape == (6, 3) and len(net.springs) == 15
    assert m.sum() == pytest.approx(box.mass, rel=8 * EPS)
    com = (m[:, None] * p).sum(axis=0) / m.sum()
    np.testing.assert_allclose(com, box.com, rtol=0, atol=16 * EPS)
    # inertia of the particles about their COM, from the definition Σ m (|r|² 1 − r rᵀ)
    r = p - com
    I_C = sum(mi * (ri @ ri * np.eye(3) - np.outer(ri, ri)) for mi, ri in zip(m, r))
    np.testing.assert_allclose(I_C, box.inertia_com, rtol=0, atol=64 * EPS * np.trace(box.inertia_com))
    # at rest lengths: no force, no energy
    assert np.abs(net.forces()).max() < 64 * EPS * 1e4
    assert net.energy() == 0.0


def test_implicit_midpoint_keeps_momentum_and_angular_momentum():
    _, rest = box_network()
    w = np.array([0.3, 1.0, -0.2])
    v = np.cross(w, rest.position) + np.array([0.5, 0, 0])  # a rigid motion: spin plus drift
    net = rigid.spring.Network(rest.mass, rest.position, v, rest.springs)
    m = net.mass[:, None]
    P0 = (m * net.velocity).sum(axis=0)
    L0 = np.cross(net.position, m * net.velocity).sum(axis=0)
    E0 = net.energy()
    for _ in range(200):
        net.step(1e-3)
    P = (m * net.velocity).sum(axis=0)
    L = np.cross(net.position, m * net.velocity).sum(axis=0)
    # linear and quadratic invariants of the implicit midpoint rule, up to the Newton tolerance
    # (1e-15 relative per step) and round-off of 200 steps
    np.testing.assert_allclose(P, P0, rtol=0, atol=200 * 64 * EPS * np.linalg.norm(P0))
    np.testing.assert_allclose(L, L0, rtol=0, atol=200 * 64 * EPS * np.linalg.norm(L0))
    # energy: the midpoint rule keeps quadratic invariants; the springs are not quadratic, so
    # only an O(h²) error bounded over time (k = 1e4 N/m, h = 1 ms: under 1e-3 of E)
    assert abs(net.energy() - E0) < 1e-3 * E0
    out = rigid.spring.Network(rest.mass, rest.position, v, rest.springs).simulate(1e-3, [0.1, 0.2])
    assert out["position"].shape == (2, 6, 3)
    np.testing.assert_array_equal(out["position"][1], net.position)  # the same 200 steps


def test_network_input_is_checked():
    with pytest.raises(rigid.Error, match=r"rigid\.spring\.Network\(\): spring 0 joins particles 0 and 2; "
                                          r"expected two different particles from 0 to 1"):
        rigid.spring.Network([1.0, 1.0], np.zeros((2, 3)), np.zeros((2, 3)), [(0, 2, 1.0, 1.0)])
    with pytest.raises(rigid.Error, match=r"mass\[1\] = -1 kg; expected a positive mass"):
        rigid.spring.Network([1.0, -1.0], np.zeros((2, 3)), np.zeros((2, 3)), [])
    with pytest.raises(rigid.Error, match=r"2 masses, 3 positions and 2 velocities"):
        rigid.spring.Network([1.0, 1.0], np.zeros((3, 3)), np.zeros((2, 3)), [])
    with pytest.raises(rigid.Error, match=r"Network\.step\(\): step h must be positive and finite, got 0 s"):
        box_network()[1].step(0.0)
    with pytest.raises(rigid.Error, match="stiffness"):
        rigid.spring.network_with_inertia(rigid.mass.solid_sphere_with_mass(1.0, 1.0), -1.0)
