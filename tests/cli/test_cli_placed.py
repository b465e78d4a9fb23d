"""`rigid inertia PRIMITIVE`: the hoop, placed primitives (--axis/--origin/--rpy, --about with
every format), pseudo-inertia and log-Cholesky output, and --tolerance; each compared with a
closed form and with the Python module (the same input gives the same numbers)."""
import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

rigid = pytest.importorskip("rigid")

# closed forms are a few flops: 1e-12 relative is the project's bar for them
REL = 1e-12


def test_hoop_acceptance_numbers(run):
    j = json.loads(run("inertia", "hoop", "--radius", 0.5, "--mass", 2, "--format", "json",
                       check=True).stdout)
    # I = (m r²/2, m r²/2, m r²) with m = 2, r = 0.5
    assert np.diag(j["inertia"]) == pytest.approx([0.25, 0.25, 0.5], rel=REL)
    # independent: the line integral over the circle by an N-point rule, exact for the
    # trigonometric polynomials of degree 2 here (N > 2), so equal to round-off
    n = 64
    th = 2 * np.pi * np.arange(n) / n
    p = np.stack([0.5 * np.cos(th), 0.5 * np.sin(th), 0 * th], axis=1)
    dm = 2.0 / n
    I = dm * sum(p_i @ p_i * np.eye(3) - np.outer(p_i, p_i) for p_i in p)
    assert np.array(j["inertia"]) == pytest.approx(I, rel=1e-14, abs=1e-15)
    # every alias and the Python factory say the same
    for name in ("ring", "thin-ring", "thin_hoop"):
        k = json.loads(run("inertia", name, "--radius", 0.5, "--mass", 2, "--format", "json",
                           check=True).stdout)
        assert k["inertia"] == j["inertia"]
    py = rigid.mass.hoop(mass=2.0, radius=0.5)
    assert py.inertia_com.tolist() == j["inertia"]
    assert rigid.mass.thin_ring_with_density(1.0, 0.5).mass == pytest.approx(math.pi, rel=REL)
