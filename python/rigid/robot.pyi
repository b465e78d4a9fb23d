# Type stubs of rigid.robot, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray


class _Pybind11Type(type):
    """The metaclass of the classes (pybind11_builtins.pybind11_type)."""


class Robot(metaclass=_Pybind11Type):
    """A kinematic tree read from a URDF, MJCF or SDF file: links, joints (hinge, slide, ball, free; depth first from the root, MuJoCo's order), inertials and gravity. q is MuJoCo's qpos (nq entries: a ball's quaternion w x y z, a free joint's world position and quaternion), q_dot its qvel (nv entries: angular velocities in the link frame, a free joint's linear velocity in the world); forces have nv entries. Immutable; every method may be called from any thread."""
    def __init__(self, file: object, *, pin_free_root: bool = ...) -> None:
        """Reads the model. pin_free_root: weld a free-floating root (MJCF <freejoint>, URDF floating) where it is."""
    @property
    def dof(self) -> int:
        """Degrees of freedom (nv)."""
    @property
    def nq(self) -> int:
        """Entries of q (MuJoCo's qpos)."""
    @property
    def nv(self) -> int:
        """Entries of q_dot (MuJoCo's qvel)."""
    @property
    def coordinates(self) -> list[str]:
        """The names of q's entries (a hinge's or slide's: its joint's; a free joint 'j': j_x j_y j_z j_qw j_qx j_qy j_qz; a ball 'j': j_qw j_qx j_qy j_qz)."""
    @property
    def velocities(self) -> list[str]:
        """The names of q_dot's entries (a free joint 'j': j_vx j_vy j_vz j_wx j_wy j_wz; a ball 'j': j_wx j_wy j_wz)."""
    @property
    def links(self) -> list[str]:
        """The links' names, depth first from the root."""
    @property
    def gravity(self) -> NDArray[numpy.float64]:
        """m/s², world frame."""
    @property
    def reference_configuration(self) -> NDArray[numpy.float64]:
        """q at which every link sits at its placement (MuJoCo's qpos0)."""
    def mass_matrix(self, q: object) -> NDArray[numpy.float64]:
        """M(q), nv × nv, armature on the diagonal."""
    def bias_forces(self, q: object, q_dot: object) -> NDArray[numpy.float64]:
        """b(q, q̇): Coriolis, centrifugal and gravity forces (MuJoCo's qfrc_bias)."""
    def passive_forces(self, q: object, q_dot: object) -> NDArray[numpy.float64]:
        """p(q, q̇) = −damping q̇ − stiffness (q − springref) (MuJoCo's qfrc_passive)."""
    def inverse_dynamics(self, q: object, q_dot: object, q_ddot: object) -> NDArray[numpy.float64]:
        """τ = M q̈ + b − p."""
    def forward_dynamics(self, q: object, q_dot: object, tau: object) -> NDArray[numpy.float64]:
        """q̈ = M⁻¹ (τ − b + p)."""
    def energy(self, q: object, q_dot: object) -> tuple[Any, ...]:
        """(T, V) in J: T = ½ q̇ᵀ M q̇, V = gravity's and the joint springs'."""
    def link_poses(self, q: object) -> list[Any]:
        """Each link's world pose (position (3,), rotation (3, 3)), in link order."""
    def __repr__(self) -> str: ...
    def standard_parameters(self) -> tuple[Any, ...]:
        """(names, values): the standard parameters pi, per link m, mx, my, mz, Ixx, Ixy, Ixz, Iyy, Iyz, Izz in the link frame about its origin, per joint Ia, fv, k (SI units)."""
    def regressor(self, q: object, q_dot: object, q_ddot: object) -> NDArray[numpy.float64]:
        """Y (nv, p): tau = Y pi for the standard parameters pi (gravity and the joints' passive forces included). q has nq entries (a ball's or free joint's unit quaternion among them), q_dot and q_ddot nv (MuJoCo's qpos and qvel, as inverse_dynamics)."""
    def base_parameters(self, *, samples: int = ..., seed: int = ..., rank_tolerance: float = ...) -> BaseParameters:
        """The base parameters (BaseParameters) by a QR of Y stacked at `samples` random states (0: automatic) drawn from `seed`; a column is independent when its distance to the others exceeds rank_tolerance of the largest column norm."""


class BaseParameters(metaclass=_Pybind11Type):
    """The base (identifiable) parameters of a robot's inverse dynamics: beta = C pi, tau = Y_b beta with Y_b = Y[:, independent_columns] (Robot.base_parameters)."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def rank(self) -> int:
        """r: the number of base parameters."""
    @property
    def names(self) -> list[str]:
        """beta_1 … beta_r."""
    @property
    def expressions(self) -> list[str]:
        """Each base parameter as a combination of the named standard parameters."""
    @property
    def values(self) -> NDArray[numpy.float64]:
        """beta of the model (r,), SI units of each one's independent parameter."""
    @property
    def combination(self) -> NDArray[numpy.float64]:
        """C (r, p): beta = C pi, pi in standard_names' order."""
    @property
    def standard_names(self) -> list[str]:
        """The p standard parameters' names (pi's order)."""
    @property
    def standard_values(self) -> NDArray[numpy.float64]:
        """pi of the model (p,)."""
    @property
    def independent_columns(self) -> list[int]:
        """The r columns of Y that form Y_b (indices into pi)."""
    @property
    def independent(self) -> list[str]:
        """The standard parameters each base parameter is led by (coefficient 1)."""
    @property
    def dependent(self) -> list[str]:
        """The standard parameters grouped into the base parameters (their columns are combinations of the independent ones)."""
    @property
    def unidentifiable(self) -> list[str]:
        """The standard parameters that do not move tau at all."""
    def __repr__(self) -> str: ...
