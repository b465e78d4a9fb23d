# Type stubs of rigid.lagrange, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray


class _Pybind11Type(type):
    """The metaclass of the classes (pybind11_builtins.pybind11_type)."""


class Printed(metaclass=_Pybind11Type):
    """One quantity as text (SymPy-parsable) and LaTeX."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def text(self) -> str:
        """Plain text that SymPy parses."""
    @property
    def latex(self) -> str:
        """LaTeX."""
    def __str__(self) -> str: ...
    def __repr__(self) -> str: ...


class Equations(metaclass=_Pybind11Type):
    """The derived equations: L, T, V, the mass matrix M(q), the forcing f(q, q_dot) (inertial + potential + generalized), the constraints and their Jacobian, the conserved quantities and the symbols, each quantity a Printed (text, latex)."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def coordinates(self) -> list[str]:
        """The generalized coordinates' names, in order."""
    @property
    def parameters(self) -> dict[str, Any]:
        """{name: value} in declaration order"""
    @property
    def constraint_names(self) -> list[str]:
        """The holonomic constraints' names, in order."""
    @property
    def lagrangian(self) -> Printed:
        """L = T − V (J)."""
    @property
    def kinetic_energy(self) -> Printed:
        """T (J)."""
    @property
    def potential_energy(self) -> Printed:
        """V (J)."""
    @property
    def mass_matrix(self) -> list[list[Printed]]:
        """n lists of n Printed"""
    @property
    def forcing(self) -> list[Printed]:
        """Forcing f(q, q̇) with M(q) q̈ = f: forcing_inertial + forcing_potential + forcing_generalized, one Printed per coordinate."""
    @property
    def forcing_inertial(self) -> list[Printed]:
        """∂T/∂q − (∂²T/∂q̇∂q) q̇ − ∂²T/∂q̇∂t (Coriolis, centrifugal, driven), one Printed per coordinate."""
    @property
    def forcing_potential(self) -> list[Printed]:
        """−∂V/∂q, one Printed per coordinate."""
    @property
    def forcing_generalized(self) -> list[Printed]:
        """The generalized forces Q (the `forces` given), one Printed per coordinate."""
    @property
    def equations(self) -> list[Printed]:
        """one Printed 'lhs = rhs' per coordinate"""
    @property
    def constraints(self) -> list[Printed]:
        """The holonomic constraints g(q, t) = 0, one Printed each."""
    @property
    def constraint_jacobian(self) -> list[list[Printed]]:
        """∂g/∂q: one list of n Printed per constraint."""
    @property
    def jacobi_integral(self) -> Printed:
        """The Jacobi integral h = Σ q̇ ∂L/∂q̇ − L (J; the energy when T is quadratic in q̇)."""
    @property
    def jacobi_conserved(self) -> bool:
        """True when h is conserved: L and the constraints do not depend on t, there are no forces, and the velocity constraints have no term a."""
    @property
    def cyclic(self) -> list[str]:
        """The cyclic coordinates (L independent of them)."""
    @property
    def cyclic_momenta(self) -> list[Printed]:
        """∂L/∂q̇ of each cyclic coordinate (conserved), one Printed each."""
    @property
    def intermediates(self) -> list[Any]:
        """The named intermediates of a tree derived by its recursions, in the order they are defined, each from those before it: [(name, definition)], both Printed. Empty for an expanded derivation."""
    @property
    def symbols(self) -> list[Any]:
        """Every symbol of the equations: [{'name', 'latex', 'role', 'unit'}] (role: coordinate, velocity, parameter, ...; SI unit when known)."""
    @property
    def text(self) -> list[str]:
        """the equations, one text line per coordinate"""
    @property
    def latex(self) -> list[str]:
        """the equations, one LaTeX line per coordinate"""
    def format(self, format: str = ...) -> str:
        """The document `rigid eom --format` prints: 'text', 'latex' or 'json'."""
    def __getitem__(self, arg0: str) -> Any: ...
    def __repr__(self) -> str: ...


class System(metaclass=_Pybind11Type):
    """A Lagrangian system: L = lagrangian + Σ bodies (T − V_gravity) − Σ potentials, with generalized forces and holonomic constraints."""
    def __init__(self, coordinates: list[tuple[str, float, float]], parameters: dict[str, Any] = ..., lagrangian: str = ..., bodies: list[dict[str, Any]] = ..., gravity: object = ..., potentials: list[tuple[str, str]] = ..., forces: list[tuple[str, str]] = ..., constraints: list[tuple[str, str]] = ..., springs: list[dict[str, Any]] = ..., velocity_constraints: list[dict[str, Any]] = ...) -> None:
        """coordinates: [(name, q0, q_dot0)]; parameters: {name: value}; bodies: [{'name', 'mass': rigid.MassProperties, 'position': [3 expressions], 'rotations': [(axis, angle expression)]}]; potentials/forces/constraints: [(name, expression)] (a force's name is its coordinate); springs: [{'body_a', 'point_a', 'body_b' (omit: world), 'point_b', 'stiffness', 'rest_length'}]; velocity_constraints: [{'name', 'coefficients': {coordinate: A_i(q, t)}, 'term': a(q, t)}] for Σ A_i q̇_i + a = 0."""
    @property
    def coordinate_names(self) -> list[str]:
        """The entries of q, in order (a ball coordinate b: b_qw b_qx b_qy b_qz)."""
    @property
    def velocity_names(self) -> list[str]:
        """The entries of q_dot, M's rows and f: c_dot per coordinate c, a ball's body-frame angular velocity b_wx b_wy b_wz."""
    def coordinate_rates(self, q: object, q_dot: object) -> NDArray[numpy.float64]:
        """dq/dt at (q, q_dot): q_dot's entries, and 1/2 q * (0, w) for a ball's quaternion."""
    @property
    def constraint_names(self) -> list[str]:
        """The holonomic constraints, in order."""
    @property
    def cyclic_coordinates(self) -> list[str]:
        """Coordinates L does not depend on (their momenta are conserved)."""
    @property
    def velocity_constraint_names(self) -> list[str]:
        """The velocity (non-holonomic) constraints, in order."""
    @property
    def body_names(self) -> list[str]:
        """Names of the bodies, in order."""
    @property
    def initial_q(self) -> NDArray[numpy.float64]:
        """q(0) from the coordinates' declarations, shape (n,)."""
    @property
    def initial_q_dot(self) -> NDArray[numpy.float64]:
        """q̇(0), shape (nv,) (the velocities: a ball's ω in its body's frame)."""
    @property
    def parameters(self) -> dict[str, Any]:
        """{name: value} of the parameters, in declaration order."""
    @property
    def tape_size(self) -> int:
        """Instructions in the compiled tape that evaluates M, f and the constraints."""
    def set_parameter(self, name: str, value: float) -> None:
        """Sets a parameter's value (SI units) for later evaluations and runs; the equations keep its name."""
    def equations(self) -> Equations:
        """The equations, printed canonically (the same on every run) and simplified: a rigid.lagrange.Equations with each quantity as text and LaTeX."""
    def emit(self, language: str, name: str = ..., flat: bool = ..., *, max_stack_bytes: int | None = ..., namespace: str = ...) -> str:
        """The equations of motion (M, f, G, γ) as one dependency-free source file: language 'c++' (a header, <cmath> only, namespace `name`) or 'python' (a module, math only); parameters are named arguments with the current values as defaults. flat=True (C++): the dynamics at global scope without t (mass_matrix, inverse_dynamics, forward_dynamics and their derivatives), as `rigid eom --emit c++ --flat`; max_stack_bytes (with flat=True): the stack bound of the derivatives (16 n² + 8 n bytes for the products; default 66048), as Scene.emit; namespace (with flat=True): the C++ namespace of its declarations, as Scene.emit."""
    def velocity_constraint_residual(self, t: float, q: object, q_dot: object) -> NDArray[numpy.float64]:
        """A(q, t) q̇ + a(q, t) at time t (s), q and q̇ of shape (n,): one entry per velocity constraint."""
    def energy(self, t: float, q: object, q_dot: object) -> float:
        """T + V (J) at time t (s) and (q, q̇), each shape (n,)."""
    def jacobi_integral(self, t: float, q: object, q_dot: object) -> float:
        """The Jacobi integral h = Σ q̇ ∂L/∂q̇ − L (J) at (t, q, q̇); conserved when L does not depend on t."""
    def constraint_residual(self, t: float, q: object) -> NDArray[numpy.float64]:
        """g(q, t) of the holonomic constraints (one entry each)."""
    def body_poses(self, t: float, q: object) -> dict[str, Any]:
        """{body: {'p_world': origin of B in W (m), 'q_wxyz': R_WB, 'R_WB': (3, 3)}} at (t, q)."""
    def mass_matrix_and_forces(self, t: float, q: object, q_dot: object) -> tuple[Any, ...]:
        """(M, f) at (t, q, q̇)."""
    def constraint_terms(self, t: float, q: object, q_dot: object) -> tuple[Any, ...]:
        """(G, γ) at (t, q, q̇): the constraint Jacobian ∂g/∂q (m × n) and γ with G q̈ = γ."""
    def accelerations(self, t: float, q: object, q_dot: object) -> tuple[Any, ...]:
        """(q̈, λ) at (t, q, q̇); λ holds the holonomic multipliers, then the velocity constraints' μ."""
    def simulate(self, t_end: float, method: str = ..., dt: float = ..., tolerance: float = ..., output_dt: float = ..., stabilization: float = ..., project_initial: bool = ..., q0: object = ..., q_dot0: object = ...) -> dict[str, Any]:
        """Integrates; returns a dict of numpy arrays (rows are samples): t, q, q_dot, lambda, energy, jacobi, cyclic_momenta, residual, velocity_residual, mu, velocity_constraint_residual, and the name lists (coordinate_names for q's columns, velocity_names for q_dot's: a ball coordinate has four of the first, three of the second, its quaternion written normalised)."""
    def __repr__(self) -> str: ...
    def modes(self, at: object = ..., parameters: dict[str, float] = ...) -> NormalModes:
        """Linearises about an equilibrium or steady motion: `at` holds coordinates at values and gives cyclic rates ({'theta1': 0.0, 'psi_dot': 60.0} or ['theta1=0']); the other coordinates are found from the initial values. Returns rigid.lagrange.NormalModes."""


class Mode(metaclass=_Pybind11Type):
    """One normal mode: δq(t) = Re(shape · e^{λ t})."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def eigenvalue(self) -> Any:
        """λ (1/s), Im λ ≥ 0"""
    @property
    def omega(self) -> float:
        """angular frequency |Im λ| (rad/s)"""
    @property
    def hz(self) -> float:
        """frequency omega/2π (Hz)"""
    @property
    def omega_squared(self) -> float:
        """ω² of K φ = ω² M φ (1/s², negative: unstable); nan for the state-space problem"""
    @property
    def growth_rate(self) -> float:
        """Re λ (1/s)"""
    @property
    def stability(self) -> str:
        """'stable', 'unstable' or 'marginal' (this mode alone, from its eigenvalue)."""
    @property
    def shape(self) -> NDArray[Any]:
        """complex shape over all coordinates, M-normalised, largest component real > 0"""
    def __repr__(self) -> str: ...


class NormalModes(metaclass=_Pybind11Type):
    """The linearisation M δq̈ + C δq̇ + K δq = 0 about an equilibrium or steady motion, and its modes (docs/lagrange.md, Normal modes)."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def coordinates(self) -> list[str]:
        """The coordinates of the system, in order."""
    @property
    def ignorable(self) -> list[str]:
        """cyclic coordinates whose momentum is held (Routh reduction)"""
    @property
    def reduced_coordinates(self) -> list[str]:
        """The coordinates the modes are computed in (the ignorable ones removed)."""
    @property
    def q(self) -> NDArray[numpy.float64]:
        """the point"""
    @property
    def q_dot(self) -> NDArray[numpy.float64]:
        """The velocities at the point (the cyclic rates of a steady motion, else 0)."""
    @property
    def searched(self) -> bool:
        """True if the point was found by a Newton search (coordinates not given in `at`)."""
    @property
    def iterations(self) -> int:
        """Newton iterations of the search (0 when nothing was searched)."""
    @property
    def residual(self) -> float:
        """max |q̈| at the point"""
    @property
    def stability(self) -> str:
        """'stable', 'marginal' or 'unstable'"""
    @property
    def gyroscopic(self) -> bool:
        """solved as the state-space eigenproblem (C ≠ 0 or K not symmetric)"""
    @property
    def M(self) -> NDArray[numpy.float64]:
        """Mass matrix of the linearisation M δq̈ + C δq̇ + K δq = 0 (SI units of the coordinates)."""
    @property
    def C(self) -> NDArray[numpy.float64]:
        """Velocity (damping and gyroscopic) matrix C of the linearisation."""
    @property
    def K(self) -> NDArray[numpy.float64]:
        """Stiffness matrix K of the linearisation."""
    @property
    def M_reduced(self) -> NDArray[numpy.float64]:
        """M in the reduced coordinates (ignorable ones removed)."""
    @property
    def C_reduced(self) -> NDArray[numpy.float64]:
        """C in the reduced coordinates."""
    @property
    def K_reduced(self) -> NDArray[numpy.float64]:
        """K in the reduced coordinates."""
    @property
    def eigenvalues(self) -> NDArray[Any]:
        """Every eigenvalue λ (1/s) of the linearisation."""
    @property
    def modes(self) -> list[Mode]:
        """The modes (rigid.lagrange.Mode), one per eigenvalue pair."""
    @property
    def omega(self) -> NDArray[numpy.float64]:
        """the modes' angular frequencies (rad/s)"""
    def json(self) -> str:
        """The JSON document `rigid modes -o` writes."""
    def __str__(self) -> str: ...
    def __repr__(self) -> str: ...
