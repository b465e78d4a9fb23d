"""Inertials at the top of the double range are refused the same way by the CLI (`rigid inertia
check`) and Python (`rigid.mass.read_inertials`): a tensor whose trace overflows, and products of
inertia whose sum I + Iᵀ overflowed, used to be accepted (the tolerance 1e-10·tr I became inf,
or the eigenvalues NaN) and came back out with ixx = inf. The same files are replayed by ctest
through the C++ reader (fuzz/regressions/inertial_xml/)."""
import pathlib

import pytest

rigid = pytest.importorskip("rigid")

REGRESSIONS = pathlib.Path(__file__).resolve().parents[2] / "fuzz" / "regressions" / "inertial_xml"
CASES = {
    "inertia_trace_overflows.urdf": "inertia tensor is too large: the sum of its diagonal elements overflows",
    "huge_product_of_inertia.xml": "inertia tensor is not positive semidefinite: principal moments (-1e+308",
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_overflowing_inertial_is_refused_on_every_surface(run, name):
    path = REGRESSIONS / name
    proc = run("inertia", "check", path, check=False)
    assert proc.returncode == 1
    assert CASES[name] in proc.stdout + proc.stderr
    entries = rigid.mass.read_inertials(path)
    assert len(entries) == 1 and entries[0]["problem"] is not None
    assert CASES[name] in entries[0]["problem"]
