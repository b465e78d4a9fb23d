# Type stubs of rigid.body, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray

import rigid


class _Pybind11Type(type):
    """The metaclass of the classes (pybind11_builtins.pybind11_type)."""


class FreeBodyExact(metaclass=_Pybind11Type):
    """Exact torque-free body angular velocity (Jacobi elliptic functions)."""
    def __init__(self, principal_moments: object, omega_body: object) -> None:
        """The motion of ω_B (rad/s, principal body frame) for principal moments I_B (kg·m²) from ω_B(0) = omega_body."""
    def omega_body(self, t: object) -> NDArray[numpy.float64]:
        """Body angular velocity at t (s); raises rigid.Error if t is not finite or beyond max_time."""
    @property
    def max_time(self) -> float:
        """The largest |t| (s) omega_body accepts: 1e15 rad over the rate of the phase of ω (beyond, rounding has lost the fraction of a period); inf when ω is constant."""
    @property
    def period(self) -> float:
        """Period of ω_B(t) (s; inf on a separatrix)."""
    @property
    def modulus(self) -> float:
        """Elliptic modulus k."""
    @property
    def energy(self) -> float:
        """Kinetic energy ½ ωᵀ I ω (J)."""
    @property
    def angular_momentum_norm(self) -> float:
        """|L| (kg·m²/s), constant."""
    def __repr__(self) -> str: ...


class FreeBodyMotion(metaclass=_Pybind11Type):
    """Exact torque-free motion: orientation R_WB(t) and body angular velocity in closed form."""
    def __init__(*args: Any, **kwargs: Any) -> None:
        """Overloaded function.

        1. __init__(self: rigid.body.FreeBodyMotion, principal_moments: object, q_wxyz: object, omega_body: object) -> None

        The motion from R_WB(0) (q_wxyz, principal body frame B) and ω_B(0) (rad/s) for principal moments (kg·m²).

        2. __init__(self: rigid.body.FreeBodyMotion, mass_properties: rigid.MassProperties, q_wxyz: object, omega_body: object) -> None

        The motion of a body with these mass properties in any body frame.
        """
    def orientation(self, t: object) -> NDArray[numpy.float64]:
        """Orientation R_WB(t) as a quaternion (w, x, y, z); raises rigid.Error if t is not finite or so far that an angle of the motion exceeds 1e15 rad."""
    def omega_body(self, t: object) -> NDArray[numpy.float64]:
        """Body angular velocity at t (s); raises rigid.Error as orientation."""
    @property
    def angular_momentum_world(self) -> NDArray[numpy.float64]:
        """L_W (kg·m²/s), constant."""
    @property
    def period(self) -> float:
        """Period of ω_B(t) (s)."""
    @property
    def modulus(self) -> float:
        """Elliptic modulus k of the body angular velocity's solution."""
    def __repr__(self) -> str: ...


def simulate_free_body(method: str, principal_moments: object, q_wxyz: object, omega_body: object, h_max: float, times: object) -> dict[str, Any]:
    """Integrate a free body in its principal frame (method: rk4, splitting2, splitting4, splitting6, midpoint, rkmk4, moser_veselov); returns a dict of arrays sampled at `times` (s): t, q_wxyz (R_WB), omega_body (rad/s), L_world (kg·m²/s), energy (J), orthonormality_error."""


def step_free_body(method: str, principal_moments: object, q_wxyz: object, omega_body: object, h: float) -> tuple[Any, ...]:
    """One step of size h (s) of a free-body method (as simulate_free_body) with principal moments (kg·m²), from R_WB (q_wxyz, principal body frame) and ω_B (rad/s): (q_wxyz, omega_body) after it."""


def step_free_bodies(method: str, principal_moments: object, q_wxyz: object, omega_body: object, h: float, *, steps: int = ...) -> tuple[Any, ...]:
    """`steps` steps (default 1) of size h (s) for N free bodies at once: principal_moments (N, 3) kg·m², q_wxyz (N, 4), omega_body (N, 3) rad/s; returns (q_wxyz, omega_body) after them, each row bitwise equal to `steps` calls of step_free_body on that body. The splittings run four bodies at a time in vector registers (AVX2 where the CPU has it)."""


def euler_rhs(principal_moments: object, omega_body: object, torque_body: object = ...) -> NDArray[numpy.float64]:
    """ω̇_B (rad/s²) from Euler's equations I ω̇ + ω × (I ω) = τ in the principal body frame: principal moments (kg·m²), ω_B (rad/s), τ_B (N·m)."""


def rotational_energy(principal_moments: object, omega_body: object) -> float:
    """Kinetic energy of the rotation ½ ωᵀ I ω (J): principal moments (kg·m²), ω_B (rad/s)."""


def method_order(method: str) -> int:
    """Classical order of accuracy of a free-body method (rk4 4, splitting2 2, ...)."""


class RigidBody(metaclass=_Pybind11Type):
    """A rigid body: mass properties (a rigid.MassProperties in the body frame B, or mass in kg and the inertia about the COM in kg·m², any symmetric tensor), uniform gravity (m/s²) and applied loads. The state follows the COM."""
    def __init__(*args: Any, **kwargs: Any) -> None:
        """Overloaded function.

        1. __init__(self: rigid.body.RigidBody, mass_properties: rigid.MassProperties, gravity: object = (0.0, 0.0, 0.0)) -> None

        A body with these mass properties (frame B, any origin) in uniform gravity g_W (m/s², world frame). Raises rigid.Error for a principal moment 0 (a point mass, a thin rod).

        2. __init__(self: rigid.body.RigidBody, mass: float, inertia: object, gravity: object = (0.0, 0.0, 0.0)) -> None

        A body of mass (kg) with inertia I_C_B about its COM (shape (3, 3), kg·m², body frame with origin at the COM) in uniform gravity (m/s², world frame).
        """
    def add_load(self, wrench: Callable[..., Any], frame: str = ..., point: object = ...) -> None:
        """Adds a load: wrench(t, state) -> (force N, torque N·m) in `frame` ('world' or 'body'); the force acts at the body point `point` (from the COM, body frame, m). `state` is a dict with q_wxyz, omega_body, p_world, v_world."""
    @property
    def mass(self) -> float:
        """Mass (kg)."""
    @property
    def com(self) -> NDArray[numpy.float64]:
        """COM in the body frame (m)."""
    @property
    def inertia(self) -> NDArray[numpy.float64]:
        """Inertia about the COM in the body frame (kg·m²)."""
    @property
    def gravity(self) -> NDArray[numpy.float64]:
        """Uniform gravity g_W (m/s², world frame)."""
    @property
    def principal_moments(self) -> NDArray[numpy.float64]:
        """Principal moments about the COM (kg·m²), ascending (or B's own diagonal when the inertia is diagonal in B)."""
    @property
    def principal_axes(self) -> NDArray[numpy.float64]:
        """R_BP (3, 3): the principal axes as columns, in B (det +1)."""
    def acceleration(self, t: float, q_wxyz: object, omega_body: object, p_world: object, v_world: object) -> tuple[Any, ...]:
        """(a_world, alpha_body) at time t (s): the COM's acceleration in the world (m/s²) and the body angular acceleration (rad/s², body frame), from Newton's and Euler's equations."""
    def diagnose(self, q_wxyz: object, omega_body: object, p_world: object, v_world: object) -> dict[str, Any]:
        """Energy (J, gravity included), linear momentum (kg·m/s, world), angular momentum about the world origin (kg·m²/s, world) and ‖RᵀR − 1‖ of a state."""
    def step(self, method: str, t: float, q_wxyz: object, omega_body: object, p_world: object, v_world: object, h: float, free_method: str = ...) -> dict[str, Any]:
        """One step of size h (s) from time t (s) (method splitting2 or rk4; free_method is the free rotation of splitting2's drift): the next state as a dict q_wxyz (R_WB), omega_body (rad/s, body), p_world (COM, m), v_world (COM velocity, m/s). The step a scene of free bodies takes (`rigid run`), so repeated calls reproduce its trajectory."""
    def simulate(self, method: str, q_wxyz: object, omega_body: object, p_world: object, v_world: object, h_max: float, times: object, free_method: str = ...) -> dict[str, Any]:
        """Integrates from t = 0 (method: splitting2 or rk4) and samples at `times` (s, ascending); returns a dict of arrays, one row per time: q_wxyz (R_WB), omega_body (rad/s, body), p_world, v_world (COM, m and m/s), momentum_world, angular_momentum_world (about the world origin), energy (J)."""
    def __repr__(self) -> str: ...


class HeavyTop(metaclass=_Pybind11Type):
    """A rigid body on a fixed frictionless pivot in uniform gravity: its mass properties in the body frame B, the pivot in B (m), gravity (m/s²). State: R_WB as q_wxyz and the body angular velocity omega_body (rad/s)."""
    def __init__(self, mass_properties: rigid.MassProperties, pivot: object, gravity: object = ...) -> None:
        """A top with these mass properties (frame B) turning about the pivot p_OP_B (m, in B) in uniform gravity g_W (m/s², world). Raises rigid.Error if the moments about the pivot leave a rotation undefined (a thin rod pivoted on its own axis)."""
    @property
    def mass(self) -> float:
        """Mass (kg)."""
    @property
    def gravity(self) -> NDArray[numpy.float64]:
        """g_W (m/s², world)."""
    @property
    def pivot(self) -> NDArray[numpy.float64]:
        """p_OP_B: the pivot in B (m)."""
    @property
    def inertia_about_pivot(self) -> NDArray[numpy.float64]:
        """I_P_B: the inertia about the pivot in B (kg·m²)."""
    @property
    def com_from_pivot(self) -> NDArray[numpy.float64]:
        """p_PC_B: the COM from the pivot, in B (m)."""
    @property
    def principal_moments(self) -> NDArray[numpy.float64]:
        """Principal moments about the pivot (kg·m²)."""
    @property
    def principal_axes(self) -> NDArray[numpy.float64]:
        """R_BP (3, 3): the principal axes about the pivot as columns, in B."""
    def energy(self, q_wxyz: object, omega_body: object) -> float:
        """Total energy (J): ½ ω_Bᵀ I_P_B ω_B − m g_W · (R_WB p_PC_B), zero potential at the pivot's height."""
    def torque(self, q_wxyz: object) -> NDArray[numpy.float64]:
        """Gravity torque about the pivot in B (N·m): p_PC_B × (m R_WBᵀ g_W)."""
    def angular_momentum_world(self, q_wxyz: object, omega_body: object) -> NDArray[numpy.float64]:
        """Angular momentum about the pivot in the world (kg·m²/s): R_WB I_P_B ω_B."""
    def step(self, q_wxyz: object, omega_body: object, h: float, free_method: str = ...) -> tuple[Any, ...]:
        """One step of size h (s) of the symmetric splitting V(h/2) T(h) V(h/2) (gravity kick around the free flow by splitting2/4/6): (q_wxyz, omega_body) after it. Symplectic; keeps the vertical angular momentum g_W · L_W to round-off. The step a scene's top takes."""
    def simulate(self, q_wxyz: object, omega_body: object, h_max: float, times: object, free_method: str = ...) -> dict[str, Any]:
        """Integrates by the gravity-kick splitting around the free flow (splitting2/4/6); returns a dict of arrays sampled at `times` (s): t, q_wxyz, omega_body, L_world (about the pivot, kg·m²/s), energy (J, total), orthonormality_error."""
    def __repr__(self) -> str: ...


def euler_arnold_velocity(J: object, M: object) -> NDArray[numpy.float64]:
    """Body angular velocity Ω ∈ so(n) (rad/s) of the body angular momentum M ∈ so(n) (n × n skew, kg·m²/s) of the generalised rigid body with mass matrix J = diag(J_1 … J_n) (shape (n,), kg·m², J = Σ m x xᵀ in principal axes): Ω_ij = M_ij / (J_i + J_j)."""


def euler_arnold_rhs(J: object, M: object) -> NDArray[numpy.float64]:
    """Ṁ = [M, Ω] = MΩ − ΩM (kg·m²/s²), the Euler–Arnold equations on SO(n) [Ratiu1980] in the body frame. For n = 3, M = hat(L) and I_1 = J_2 + J_3 (cyclic): Euler's equations."""


def euler_arnold_rk4_step(J: object, M: object, h: float) -> NDArray[numpy.float64]:
    """M after one classical RK4 step of size h (s) of the Euler–Arnold equations; the Casimirs tr(M^2k) are kept to the method's O(h⁴) error."""
