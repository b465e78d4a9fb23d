# Type stubs of rigid.integrate, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray


def solve(rhs: Callable[..., Any], y0: object, t_end: float, *, t0: float = ..., method: str = ..., dt: float = ..., rtol: float = ..., atol: float = ..., output_dt: float = ..., n_position: int = ..., names: list[str] = ...) -> dict[str, Any]:
    """Integrates dy/dt = rhs(t, y) from y(t0) = y0 (shape (n,)) to t_end (s) with the library's method: 'rk4' or 'implicit_midpoint' (fixed steps, the fewest equal steps ≤ dt between outputs), 'dopri5' (adaptive: 2.2e-15 ≤ rtol ≤ 0.1, 0 < atol ≤ 0.1; dt the first step), 'stormer_verlet' (y = (q, v) with the first n_position components q, default half; rhs's v̇ must not depend on v). Outputs at t0 + k·output_dt and t_end (output_dt = 0: every step). Returns {'t': (m,), 'y': (m, n), 'steps', 'rhs_evaluations'}. Every step is checked for a non-finite state (the error names the step, t and the component, by `names` when given). The GIL is held (rhs is Python); Ctrl-C raises KeyboardInterrupt."""


def methods() -> list[str]:
    """The method names solve() accepts."""
