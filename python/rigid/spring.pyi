# Type stubs of rigid.spring, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray

import rigid


class _Pybind11Type(type):
    """The metaclass of the classes (pybind11_builtins.pybind11_type)."""


class Network(metaclass=_Pybind11Type):
    """Particles (mass kg, position m and velocity m/s in the world frame, one per row) joined by springs (i, j, stiffness N/m, rest length m)."""
    def __init__(self, mass: object, position: object, velocity: object, springs: list[tuple[int, int, float, float]]) -> None:
        """mass (n,) kg; position, velocity (n, 3) in m and m/s, one particle per row, world frame; springs: [(i, j, stiffness N/m, rest_length m)]."""
    @property
    def mass(self) -> NDArray[numpy.float64]:
        """Masses (kg), shape (n,)."""
    @property
    def position(self) -> NDArray[numpy.float64]:
        """Positions (m, world), shape (n, 3)."""
    @property
    def velocity(self) -> NDArray[numpy.float64]:
        """Velocities (m/s, world), shape (n, 3)."""
    @property
    def springs(self) -> list[tuple[int, int, float, float]]:
        """[(i, j, stiffness N/m, rest_length m)]."""
    def forces(self) -> NDArray[numpy.float64]:
        """Spring forces on every particle (N, world), shape (n, 3)."""
    def energy(self) -> float:
        """Total energy (J): kinetic + spring potential."""
    def step(self, h: float, max_iterations: int = ..., tolerance: float = ...) -> None:
        """Advances the network in place by one implicit-midpoint step of size h (s): Newton on the stage positions with the exact stiffness matrix, A-stable (h is not limited by √(m/k)); keeps linear and angular momentum up to the Newton tolerance (a correction at most tolerance·(1 + max|p|), m). Raises rigid.Error, leaving the network unchanged, if Newton does not converge."""
    def simulate(self, h_max: float, times: object, max_iterations: int = ..., tolerance: float = ...) -> dict[str, Any]:
        """Integrates from t = 0 by implicit-midpoint steps (the fewest equal steps ≤ h_max, s, between output times) and samples at `times` (s, ascending): a dict with t, position and velocity (shape (len(times), n, 3), m and m/s, world) and energy (J). Releases the GIL; Ctrl-C raises KeyboardInterrupt."""
    def __repr__(self) -> str: ...


def network_with_inertia(mass_properties: rigid.MassProperties, stiffness: float) -> Network:
    """Six particles of mass m/6 at C ± a_i e_i along the principal axes of the body (its frame B taken as the world at t = 0), at rest, with the body's mass, COM and inertia about the COM, joined by all 15 springs of stiffness (N/m) at their rest lengths. Needs I_i < I_j + I_k strictly (a flat body cannot be spanned by six particles)."""
