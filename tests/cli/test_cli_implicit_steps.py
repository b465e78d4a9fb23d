"""`rigid run` with an implicit free-body method at a step too large for its solve to converge:
the run is refused (exit 1) naming the step, the method and the remedy, and writes nothing.
Before, the Lie-Poisson midpoint accepted its unconverged iterate and this run exited 0 having
lost 22 % of the energy."""
import json
import pathlib

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"

# the racket spun at 3 rad/s about its middle axis, one step per second: h |w| max(I)/min(I) = 9,
# far outside the contraction of the fixed-point iterations (< 1)
def overrides(dt):
    return ["--set", "racket.omega=[0.01,3,0.01]", "--set", f"simulation.dt={dt}",
            "--set", "simulation.output_dt=1"]


@pytest.mark.parametrize("method, name", [("midpoint", "Lie–Poisson midpoint"),
                                          ("moser_veselov", "Moser–Veselov")])
def test_step_too_large_to_converge_is_refused_and_nothing_is_written(run, tmp_path, method, name):
    out = tmp_path / "o"
    p = run("run", EXAMPLES / "tennis_racket.toml", "--integrator", method, *overrides(1), "-o", out,
            check=False)
    assert p.returncode == 1, p.stderr
    assert p.stderr.startswith("rigid: error: at step 1 from t = 0 s: "), p.stderr
    assert f"the {name} step ({method}) did not converge: h = 1 s" in p.stderr
    assert "residual of its implicit equation" in p.stderr and "above the tolerance" in p.stderr
    assert "smaller step" in p.stderr
    assert "Traceback" not in p.stderr and "terminate" not in p.stderr
    # no output directory, and no temporary one beside it
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []


def test_the_remedy_works(run, tmp_path):
    # a quarter of the step converges at every step; the midpoint then keeps the quadratic
    # invariants to round-off (E ≈ 9 J: 1e-12 J is thousands of ulps of margin over 400 steps)
    out = tmp_path / "o"
    run("run", EXAMPLES / "tennis_racket.toml", "--integrator", "midpoint", *overrides(0.25), "-o", out,
        "--quiet", check=True)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["diagnostics"]["energy_max_change"] < 1e-12
