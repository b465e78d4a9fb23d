# Type stubs of rigid, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray

from . import body as body
from . import integrate as integrate
from . import lagrange as lagrange
from . import mass as mass
from . import mesh as mesh
from . import robot as robot
from . import so3 as so3
from . import spring as spring


class _Pybind11Type(type):
    """The metaclass of the classes (pybind11_builtins.pybind11_type)."""


__version__: str


class Error(ValueError):
    """Bad input or a refused computation: the message says what, where, the value, what was expected and the remedy (the text the command line prints). A ValueError."""


class SO2(metaclass=_Pybind11Type):
    """Rotation in 2-D, stored as a unit complex number c + i s; tangent: the angle (float, rad)"""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @staticmethod
    def identity() -> SO2:
        """The identity element of SO(2)."""
    @staticmethod
    def exp(theta: float) -> SO2:
        """angle (rad, counter-clockwise) -> rotation; refuses a non-finite angle"""
    @staticmethod
    def from_angle(theta: float) -> SO2:
        """The rotation by theta (rad, counter-clockwise)."""
    @staticmethod
    def from_complex(c: float, s: float) -> SO2:
        """The rotation of the complex number c + i s (normalised)."""
    @staticmethod
    def from_matrix(R: object, tol: float = ...) -> SO2:
        """The element of SO(2) whose matrix is the 2×2 rotation matrix R (checked within tol: RᵀR = I, det R = +1); raises rigid.Error giving the defect otherwise."""
    @staticmethod
    def hat(theta: float) -> NDArray[numpy.float64]:
        """hat(xi): the Lie-algebra matrix of the tangent coordinates theta (rad, counter-clockwise)."""
    @staticmethod
    def vee(matrix: object) -> float:
        """vee(M): the tangent coordinates theta (rad, counter-clockwise) of a Lie-algebra matrix (inverse of hat)."""
    @staticmethod
    def sample(seed: int, n: int) -> list[SO2]:
        """n Haar-uniform rotations from a seeded std::mt19937_64"""
    dimension: ClassVar[int]
    def log(self) -> float:
        """angle in (-pi, pi]"""
    def angle(self) -> float:
        """The rotation angle (rad): in (-π, π] for SO(2), in [0, π] for SO(3)."""
    def homogeneous(self) -> NDArray[numpy.float64]:
        """The homogeneous matrix [[R, t], [0, 1]] (t = 0 for a rotation): acts on (p, 1)."""
    def complex(self) -> NDArray[numpy.float64]:
        """(c, s)"""
    def is_approx(self, other: SO2, tol: float = ...) -> bool:
        """True if self and other are the same element within tol (the angle of self⁻¹ · other, rad)."""
    def matrix(self) -> NDArray[numpy.float64]:
        """The 2×2 rotation matrix R."""
    def adjoint(self) -> NDArray[numpy.float64]:
        """The adjoint matrix Ad(X) on tangent coordinates: X exp(xi) X⁻¹ = exp(Ad(X) xi)."""
    def inverse(self) -> SO2:
        """The inverse rotation (Rᵀ)."""
    def interpolate(self, other: SO2, s: object) -> SO2:
        """Geodesic interpolation self · exp(s · log(self⁻¹ · other)): self at s = 0, other at s = 1."""
    def __mul__(self, other: object) -> Any:
        """Composition self * other (other: an SO2), or the rotated vector R v (other: shape (2,))."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __repr__(self) -> str: ...


class SE2(metaclass=_Pybind11Type):
    """Rigid motion of the plane (R, t): p -> R p + t; tangent (rho_x, rho_y, theta)"""
    def __init__(self, R: SO2, t: object) -> None:
        """The rigid motion p -> R p + t from its rotation R and translation t (m)."""
    @staticmethod
    def identity() -> SE2:
        """The identity element of SE(2)."""
    @staticmethod
    def exp(xi: object) -> SE2:
        """Exponential map: tangent coordinates (rho_x, rho_y, theta) (m, m, rad) -> element of SE(2)."""
    @staticmethod
    def hat(xi: object) -> NDArray[numpy.float64]:
        """hat(xi): the Lie-algebra matrix of the tangent coordinates (rho_x, rho_y, theta) (m, m, rad)."""
    @staticmethod
    def vee(matrix: object) -> NDArray[numpy.float64]:
        """vee(M): the tangent coordinates (rho_x, rho_y, theta) (m, m, rad) of a Lie-algebra matrix (inverse of hat)."""
    @staticmethod
    def right_jacobian(xi: object) -> NDArray[numpy.float64]:
        """Right Jacobian Jr(xi) of exp: exp(xi + d) ≈ exp(xi) exp(Jr(xi) d) [Sola2018]."""
    @staticmethod
    def left_jacobian(xi: object) -> NDArray[numpy.float64]:
        """Left Jacobian Jl(xi) of exp: exp(xi + d) ≈ exp(Jl(xi) d) exp(xi); Jl(xi) = Jr(-xi) [Sola2018]."""
    @staticmethod
    def right_jacobian_inverse(xi: object) -> NDArray[numpy.float64]:
        """The inverse Jr(xi)⁻¹ of the right Jacobian, in closed form."""
    @staticmethod
    def left_jacobian_inverse(xi: object) -> NDArray[numpy.float64]:
        """The inverse Jl(xi)⁻¹ of the left Jacobian, in closed form."""
    @staticmethod
    def from_matrix(T: object, tol: float = ...) -> SE2:
        """The element of SE(2) whose matrix is the 3×3 homogeneous matrix [[R, t], [0, 1]] (checked within tol: RᵀR = I, det R = +1, last row (0, ..., 0, 1)); raises rigid.Error giving the defect otherwise."""
    @staticmethod
    def sample(seed: int, n: int, half_extent: float = ...) -> list[SE2]:
        """Random elements of SE(2) from a seeded std::mt19937_64: Haar-uniform rotation, translation uniform in [-half_extent, half_extent] (m) on each axis."""
    dimension: ClassVar[int]
    def log(self) -> NDArray[numpy.float64]:
        """Logarithm: the tangent coordinates (rho_x, rho_y, theta) (m, m, rad) with exp(log(X)) = X (rotation angle in [0, π])."""
    def homogeneous(self) -> NDArray[numpy.float64]:
        """The homogeneous matrix [[R, t], [0, 1]] (t = 0 for a rotation): acts on (p, 1)."""
    def act_vector(self, v: object) -> NDArray[numpy.float64]:
        """Acts on a free vector (no translation): R v."""
    def rotation(self) -> SO2:
        """The rotation part R."""
    def translation(self) -> NDArray[numpy.float64]:
        """The translation part t (m): p -> R p + t."""
    def matrix(self) -> NDArray[numpy.float64]:
        """The 3×3 homogeneous matrix [[R, t], [0, 1]]."""
    def adjoint(self) -> NDArray[numpy.float64]:
        """The adjoint matrix Ad(X) on tangent coordinates: X exp(xi) X⁻¹ = exp(Ad(X) xi)."""
    def inverse(self) -> SE2:
        """The inverse motion (Rᵀ, -Rᵀ t): p -> Rᵀ (p - t)."""
    def interpolate(self, other: SE2, s: object) -> SE2:
        """Geodesic interpolation self · exp(s · log(self⁻¹ · other)): self at s = 0, other at s = 1."""
    def __mul__(self, other: object) -> Any:
        """Composition self * other (other: an SE2), or the moved point R p + t (other: shape (2,))."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __repr__(self) -> str: ...


class SOn(metaclass=_Pybind11Type):
    """Rotation of R^n for any n >= 2 (n x n matrix); tangent in R^(n(n-1)/2), basis as in SOn::hat"""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @staticmethod
    def identity(n: int) -> SOn:
        """The identity element of SO(n)."""
    @staticmethod
    def ad(omega: object) -> NDArray[numpy.float64]:
        """The small adjoint ad(xi): the matrix of the Lie bracket [xi, ·] on tangent coordinates."""
    @staticmethod
    def dimension_of(n: int) -> int:
        """The tangent dimension of SO(n) for a given n."""
    @property
    def n(self) -> int:
        """n, the dimension of the space acted on."""
    @property
    def dimension(self) -> int:
        """Dimension of the tangent space, n(n-1)/2."""
    @staticmethod
    def exp(omega: object) -> SOn:
        """so(n) coordinates -> rotation (n from the size)"""
    @staticmethod
    def hat(omega: object) -> NDArray[numpy.float64]:
        """hat(xi): the Lie-algebra matrix of the tangent coordinates omega in R^(n(n-1)/2) (rad; basis as in hat)."""
    @staticmethod
    def vee(matrix: object, tol: float = ...) -> NDArray[numpy.float64]:
        """vee(M): the tangent coordinates omega in R^(n(n-1)/2) (rad; basis as in hat) of a Lie-algebra matrix (inverse of hat)."""
    @staticmethod
    def right_jacobian(omega: object) -> NDArray[numpy.float64]:
        """Right Jacobian Jr(xi) of exp: exp(xi + d) ≈ exp(xi) exp(Jr(xi) d) [Sola2018]."""
    @staticmethod
    def left_jacobian(omega: object) -> NDArray[numpy.float64]:
        """Left Jacobian Jl(xi) of exp: exp(xi + d) ≈ exp(Jl(xi) d) exp(xi); Jl(xi) = Jr(-xi) [Sola2018]."""
    @staticmethod
    def right_jacobian_inverse(omega: object) -> NDArray[numpy.float64]:
        """The inverse Jr(xi)⁻¹ of the right Jacobian, in closed form."""
    @staticmethod
    def left_jacobian_inverse(omega: object) -> NDArray[numpy.float64]:
        """The inverse Jl(xi)⁻¹ of the left Jacobian, in closed form."""
    @staticmethod
    def from_matrix(R: object, tol: float = ...) -> SOn:
        """The element of SO(n) whose matrix is the n×n rotation matrix R (checked within tol: RᵀR = I, det R = +1); raises rigid.Error giving the defect otherwise."""
    @staticmethod
    def sample(n: int, seed: int, count: int) -> list[SOn]:
        """count Haar-uniform rotations of R^n (seeded)"""
    def log(self) -> NDArray[numpy.float64]:
        """Logarithm: the tangent coordinates omega in R^(n(n-1)/2) (rad; basis as in hat) with exp(log(X)) = X (rotation angle in [0, π])."""
    def angles(self) -> NDArray[numpy.float64]:
        """rotation angles of the planes, descending, in [0, pi]"""
    def homogeneous(self) -> NDArray[numpy.float64]:
        """The homogeneous matrix [[R, t], [0, 1]] (t = 0 for a rotation): acts on (p, 1)."""
    def is_approx(self, other: SOn, tol: float = ...) -> bool:
        """True if self and other are the same element within tol (the angle of self⁻¹ · other, rad)."""
    def matrix(self) -> NDArray[numpy.float64]:
        """The n×n rotation matrix R."""
    def adjoint(self) -> NDArray[numpy.float64]:
        """The adjoint matrix Ad(X) on tangent coordinates: X exp(xi) X⁻¹ = exp(Ad(X) xi)."""
    def inverse(self) -> SOn:
        """The inverse rotation (Rᵀ)."""
    def interpolate(self, other: SOn, s: object) -> SOn:
        """Geodesic interpolation self · exp(s · log(self⁻¹ · other)): self at s = 0, other at s = 1."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __mul__(self, other: object) -> Any:
        """Composition self * other (other: an SOn of the same n), or the rotated vector R v (other: shape (n,))."""
    def __repr__(self) -> str: ...


class SEn(metaclass=_Pybind11Type):
    """Rigid motion of R^n (R, t) for any n >= 2; tangent (rho, omega) in R^(n(n+1)/2)"""
    def __init__(self, R: SOn, t: object) -> None:
        """The rigid motion p -> R p + t from its rotation R and translation t (m)."""
    @staticmethod
    def identity(n: int) -> SEn:
        """The identity element of SE(n)."""
    @staticmethod
    def ad(xi: object) -> NDArray[numpy.float64]:
        """The small adjoint ad(xi): the matrix of the Lie bracket [xi, ·] on tangent coordinates."""
    @staticmethod
    def dimension_of(n: int) -> int:
        """The tangent dimension of SE(n) for a given n."""
    @property
    def n(self) -> int:
        """n, the dimension of the space acted on."""
    @property
    def dimension(self) -> int:
        """Dimension of the tangent space, n(n+1)/2."""
    @staticmethod
    def exp(xi: object) -> SEn:
        """Exponential map: tangent coordinates (rho, omega) in R^(n(n+1)/2) (m, rad) -> element of SE(n)."""
    @staticmethod
    def hat(xi: object) -> NDArray[numpy.float64]:
        """hat(xi): the Lie-algebra matrix of the tangent coordinates (rho, omega) in R^(n(n+1)/2) (m, rad)."""
    @staticmethod
    def vee(matrix: object, tol: float = ...) -> NDArray[numpy.float64]:
        """vee(M): the tangent coordinates (rho, omega) in R^(n(n+1)/2) (m, rad) of a Lie-algebra matrix (inverse of hat)."""
    @staticmethod
    def right_jacobian(xi: object) -> NDArray[numpy.float64]:
        """Right Jacobian Jr(xi) of exp: exp(xi + d) ≈ exp(xi) exp(Jr(xi) d) [Sola2018]."""
    @staticmethod
    def left_jacobian(xi: object) -> NDArray[numpy.float64]:
        """Left Jacobian Jl(xi) of exp: exp(xi + d) ≈ exp(Jl(xi) d) exp(xi); Jl(xi) = Jr(-xi) [Sola2018]."""
    @staticmethod
    def right_jacobian_inverse(xi: object) -> NDArray[numpy.float64]:
        """The inverse Jr(xi)⁻¹ of the right Jacobian, in closed form."""
    @staticmethod
    def left_jacobian_inverse(xi: object) -> NDArray[numpy.float64]:
        """The inverse Jl(xi)⁻¹ of the left Jacobian, in closed form."""
    @staticmethod
    def from_matrix(T: object, tol: float = ...) -> SEn:
        """The element of SE(n) whose matrix is the (n+1)×(n+1) homogeneous matrix [[R, t], [0, 1]] (checked within tol: RᵀR = I, det R = +1, last row (0, ..., 0, 1)); raises rigid.Error giving the defect otherwise."""
    @staticmethod
    def sample(n: int, seed: int, count: int, half_extent: float = ...) -> list[SEn]:
        """Random elements of SE(n) from a seeded std::mt19937_64: Haar-uniform rotation, translation uniform in [-half_extent, half_extent] (m) on each axis."""
    def log(self) -> NDArray[numpy.float64]:
        """Logarithm: the tangent coordinates (rho, omega) in R^(n(n+1)/2) (m, rad) with exp(log(X)) = X (rotation angle in [0, π])."""
    def homogeneous(self) -> NDArray[numpy.float64]:
        """The homogeneous matrix [[R, t], [0, 1]] (t = 0 for a rotation): acts on (p, 1)."""
    def act_vector(self, v: object) -> NDArray[numpy.float64]:
        """Acts on a free vector (no translation): R v."""
    def rotation(self) -> SOn:
        """The rotation part R."""
    def translation(self) -> NDArray[numpy.float64]:
        """The translation part t (m): p -> R p + t."""
    def matrix(self) -> NDArray[numpy.float64]:
        """The (n+1)×(n+1) homogeneous matrix [[R, t], [0, 1]]."""
    def adjoint(self) -> NDArray[numpy.float64]:
        """The adjoint matrix Ad(X) on tangent coordinates: X exp(xi) X⁻¹ = exp(Ad(X) xi)."""
    def inverse(self) -> SEn:
        """The inverse motion (Rᵀ, -Rᵀ t): p -> Rᵀ (p - t)."""
    def interpolate(self, other: SEn, s: object) -> SEn:
        """Geodesic interpolation self · exp(s · log(self⁻¹ · other)): self at s = 0, other at s = 1."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __mul__(self, other: object) -> Any:
        """Composition self * other (other: an SEn of the same n), or the moved point R p + t (other: shape (n,))."""
    def __repr__(self) -> str: ...


class SO3(metaclass=_Pybind11Type):
    """Rotation in 3-D, stored as a unit quaternion (w, x, y, z)"""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @staticmethod
    def identity() -> SO3:
        """The identity element of SO(3)."""
    @staticmethod
    def exp(omega: object) -> SO3:
        """rotation vector (rad) -> rotation; refuses a non-finite omega"""
    @staticmethod
    def hat(omega: object) -> NDArray[numpy.float64]:
        """hat(xi): the Lie-algebra matrix of the tangent coordinates omega (rotation vector: axis · angle, rad)."""
    @staticmethod
    def vee(matrix: object) -> NDArray[numpy.float64]:
        """vee(M): the tangent coordinates omega (rotation vector: axis · angle, rad) of a Lie-algebra matrix (inverse of hat)."""
    @staticmethod
    def right_jacobian(omega: object) -> NDArray[numpy.float64]:
        """Right Jacobian Jr(xi) of exp: exp(xi + d) ≈ exp(xi) exp(Jr(xi) d) [Sola2018]."""
    @staticmethod
    def left_jacobian(omega: object) -> NDArray[numpy.float64]:
        """Left Jacobian Jl(xi) of exp: exp(xi + d) ≈ exp(Jl(xi) d) exp(xi); Jl(xi) = Jr(-xi) [Sola2018]."""
    @staticmethod
    def right_jacobian_inverse(omega: object) -> NDArray[numpy.float64]:
        """The inverse Jr(xi)⁻¹ of the right Jacobian, in closed form."""
    @staticmethod
    def left_jacobian_inverse(omega: object) -> NDArray[numpy.float64]:
        """The inverse Jl(xi)⁻¹ of the left Jacobian, in closed form."""
    @staticmethod
    def from_matrix(R: object, tol: float = ...) -> SO3:
        """The element of SO(3) whose matrix is the 3×3 rotation matrix R_AB (v_A = R_AB v_B) (checked within tol: RᵀR = I, det R = +1); raises rigid.Error giving the defect otherwise."""
    @staticmethod
    def from_quaternion(w: object, x: object, y: object, z: object) -> SO3:
        """The rotation of the quaternion (w, x, y, z), normalised; raises rigid.Error if it is not finite or its norm is below 1e-12."""
    @staticmethod
    def from_axis_angle(axis: object, angle: object) -> SO3:
        """The rotation by `angle` (rad) about `axis` (normalised); raises rigid.Error on a zero axis."""
    @staticmethod
    def sample(seed: int, n: int) -> list[SO3]:
        """n Haar-uniform rotations from a seeded std::mt19937_64"""
    @staticmethod
    def from_euler(angles: object, sequence: str = ..., intrinsic: bool = ...) -> SO3:
        """The rotation of Euler angles (rad) about the axes of `sequence` (any of the 12, e.g. 'ZYX', 'ZXZ'; intrinsic: about the moving axes, else about the fixed axes)."""
    def to_euler(self, sequence: str = ..., intrinsic: bool = ...) -> NDArray[numpy.float64]:
        """The Euler angles (rad) of this rotation for `sequence` and intrinsic/extrinsic, as from_euler takes them."""
    def log(self) -> NDArray[numpy.float64]:
        """Logarithm: the tangent coordinates omega (rotation vector: axis · angle, rad) with exp(log(X)) = X (rotation angle in [0, π])."""
    def angle(self) -> float:
        """The rotation angle (rad): in (-π, π] for SO(2), in [0, π] for SO(3)."""
    def homogeneous(self) -> NDArray[numpy.float64]:
        """The homogeneous matrix [[R, t], [0, 1]] (t = 0 for a rotation): acts on (p, 1)."""
    def quaternion(self) -> NDArray[numpy.float64]:
        """(w, x, y, z)"""
    def is_approx(self, other: SO3, tol: float = ...) -> bool:
        """True if self and other are the same element within tol (the angle of self⁻¹ · other, rad)."""
    def matrix(self) -> NDArray[numpy.float64]:
        """The 3×3 rotation matrix R_AB (v_A = R_AB v_B)."""
    def adjoint(self) -> NDArray[numpy.float64]:
        """The adjoint matrix Ad(X) on tangent coordinates: X exp(xi) X⁻¹ = exp(Ad(X) xi)."""
    def inverse(self) -> SO3:
        """The inverse rotation (Rᵀ)."""
    def interpolate(self, other: SO3, s: object) -> SO3:
        """Geodesic interpolation self · exp(s · log(self⁻¹ · other)): self at s = 0, other at s = 1."""
    def __mul__(self, other: object) -> Any:
        """Composition self * other (R_AC = R_AB * R_BC; other: an SO3), or the rotated vector R v (v_A = R_AB v_B; other: shape (3,))."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __repr__(self) -> str: ...


class SE3(metaclass=_Pybind11Type):
    """Rigid motion (R, t): p -> R p + t; tangent (rho, omega)"""
    def __init__(self, R: SO3, t: object) -> None:
        """The rigid motion p -> R p + t from its rotation R and translation t (m)."""
    @staticmethod
    def identity() -> SE3:
        """The identity element of SE(3)."""
    @staticmethod
    def exp(xi: object) -> SE3:
        """Exponential map: tangent coordinates (rho, omega) (m, rad; translation part first) -> element of SE(3)."""
    @staticmethod
    def hat(xi: object) -> NDArray[numpy.float64]:
        """hat(xi): the Lie-algebra matrix of the tangent coordinates (rho, omega) (m, rad; translation part first)."""
    @staticmethod
    def vee(matrix: object) -> NDArray[numpy.float64]:
        """vee(M): the tangent coordinates (rho, omega) (m, rad; translation part first) of a Lie-algebra matrix (inverse of hat)."""
    @staticmethod
    def right_jacobian(xi: object) -> NDArray[numpy.float64]:
        """Right Jacobian Jr(xi) of exp: exp(xi + d) ≈ exp(xi) exp(Jr(xi) d) [Sola2018]."""
    @staticmethod
    def left_jacobian(xi: object) -> NDArray[numpy.float64]:
        """Left Jacobian Jl(xi) of exp: exp(xi + d) ≈ exp(Jl(xi) d) exp(xi); Jl(xi) = Jr(-xi) [Sola2018]."""
    @staticmethod
    def right_jacobian_inverse(xi: object) -> NDArray[numpy.float64]:
        """The inverse Jr(xi)⁻¹ of the right Jacobian, in closed form."""
    @staticmethod
    def left_jacobian_inverse(xi: object) -> NDArray[numpy.float64]:
        """The inverse Jl(xi)⁻¹ of the left Jacobian, in closed form."""
    @staticmethod
    def from_matrix(T: object, tol: float = ...) -> SE3:
        """The element of SE(3) whose matrix is the 4×4 homogeneous matrix [[R, t], [0, 1]] (checked within tol: RᵀR = I, det R = +1, last row (0, ..., 0, 1)); raises rigid.Error giving the defect otherwise."""
    def log(self) -> NDArray[numpy.float64]:
        """Logarithm: the tangent coordinates (rho, omega) (m, rad; translation part first) with exp(log(X)) = X (rotation angle in [0, π])."""
    def rotation(self) -> SO3:
        """The rotation part R."""
    def translation(self) -> NDArray[numpy.float64]:
        """The translation part t (m): p -> R p + t."""
    def matrix(self) -> NDArray[numpy.float64]:
        """The 4×4 homogeneous matrix [[R, t], [0, 1]]."""
    def adjoint(self) -> NDArray[numpy.float64]:
        """The adjoint matrix Ad(X) on tangent coordinates: X exp(xi) X⁻¹ = exp(Ad(X) xi)."""
    def inverse(self) -> SE3:
        """The inverse motion (Rᵀ, -Rᵀ t): p -> Rᵀ (p - t)."""
    def interpolate(self, other: SE3, s: object) -> SE3:
        """Geodesic interpolation self · exp(s · log(self⁻¹ · other)): self at s = 0, other at s = 1."""
    def __mul__(self, other: object) -> Any:
        """Composition self * other (X_AC = X_AB * X_BC; other: an SE3), or the moved point R p + t (other: shape (3,))."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __repr__(self) -> str: ...


class OrthogonalityReport(metaclass=_Pybind11Type):
    """How far a matrix M is from O(n) and SO(n): check_orthogonal(M, tol)."""
    def __init__(self, *args: Any, **kwargs: Any) -> None: ...
    @property
    def defect(self) -> float:
        """max |MᵀM − I| (entrywise)."""
    @property
    def determinant(self) -> float:
        """det M."""
    @property
    def orthogonal(self) -> bool:
        """True if the defect is within tol (M in O(n))."""
    @property
    def rotation(self) -> bool:
        """True if also det M > 0 (M in SO(n))."""
    def __repr__(self) -> str: ...


def check_orthogonal(M: object, tol: float = ...) -> OrthogonalityReport:
    """O(n) membership: max|MᵀM − I| and det M"""


def nearest_rotation(M: object) -> NDArray[numpy.float64]:
    """closest SO(n) matrix (SVD)"""


class MassProperties(metaclass=_Pybind11Type):
    """Mass (kg), center of mass p_OC_B (m) and inertia about the COM I_C_B (kg·m²) of a 3D body, validated when built."""
    def __init__(self, mass: float, p_OC_B: object, I_C_B: object) -> None:
        """Validated mass properties: mass (kg), COM p_OC_B from the frame origin O in B (shape (3,), m), inertia about the COM I_C_B in B (shape (3, 3), kg·m², the physical tensor: off-diagonal −∫ρxy dV). Raises rigid.Error naming the failed condition and its margin."""
    @property
    def mass(self) -> float:
        """Mass (kg)."""
    @property
    def com(self) -> NDArray[numpy.float64]:
        """Centre of mass p_OC_B (m), shape (3,)."""
    @property
    def inertia_com(self) -> NDArray[numpy.float64]:
        """Inertia about the COM expressed in B (kg·m²), shape (3, 3)."""
    def inertia_about(self, p_OQ_B: object) -> NDArray[numpy.float64]:
        """Inertia (kg·m²) about the point Q at p_OQ_B (m, in B), expressed in B: the parallel-axis theorem I_Q = I_C + m (|d|² 1 − d dᵀ), d = p_OC − p_OQ."""
    def inertia_about_axis(self, p_OQ_B: object, unit_B: object) -> float:
        """Moment of inertia uᵀ I_Q u (kg·m²) about the line through Q (p_OQ_B, m, in B) along the unit vector unit_B (in B; |u| within 1e-12 of 1)."""
    def shifted(self, d_B: object) -> MassProperties:
        """The same body moved by d_B (m, in B): COM + d_B, inertia unchanged."""
    def rotated(self, R_AB: object) -> MassProperties:
        """The same body re-expressed in frame A (common origin): p_OC_A = R_AB p_OC_B, I_C_A = R_AB I_C_B R_ABᵀ; R_AB (3, 3) must be a rotation within 1e-9."""
    def transformed(self, R_AB: object, p_AB_A: object) -> MassProperties:
        """The same body expressed in frame A, given the pose of B in A: rotation R_AB (3, 3) and position p_AB_A (m) of B's origin in A."""
    def principal_axes(self) -> tuple[Any, ...]:
        """(ascending principal moments, R_BP with the principal axes as columns, det +1)."""
    def invalidity_report(self) -> str | None:
        """Why these mass properties are not physical, or None (always None once built; see check)."""
    @staticmethod
    def check(mass: float, p_OC_B: object, I_C_B: object) -> str | None:
        """Why (mass kg, COM p_OC_B m, inertia about the COM I_C_B kg·m²) is not a physical body, or None when it is."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __repr__(self) -> str: ...


def combine(parts: list[MassProperties]) -> MassProperties:
    """Mass properties of the union of bodies in one frame."""


def subtract(whole: MassProperties, hole: MassProperties) -> MassProperties:
    """The body with a hole removed; refuses non-physical results."""


class MassProperties2(metaclass=_Pybind11Type):
    """Planar mass, COM and moment about the COM."""
    def __init__(self, mass: float, p_OC_B: object, moment_com: float) -> None:
        """Mass (kg), COM p_OC_B (shape (2,), m) and moment about the COM (kg·m²) of a lamina."""
    @property
    def mass(self) -> float:
        """Mass (kg)."""
    @property
    def com(self) -> NDArray[numpy.float64]:
        """Center of mass p_OC_B in the plane frame B (m)."""
    @property
    def moment_com(self) -> float:
        """Polar moment of inertia about the normal through the COM (kg·m²)."""
    def moment_about(self, p_OQ_B: object) -> float:
        """Polar moment (kg·m²) about the point Q at p_OQ_B (shape (2,), m)."""
    def shifted(self, d_B: object) -> MassProperties2:
        """The same lamina moved by d_B (shape (2,), m): COM + d_B, moment unchanged."""
    def rotated(self, angle: float) -> MassProperties2:
        """The same lamina with its coordinates rotated by angle (rad, counter-clockwise); the moment about the COM is unchanged."""
    @staticmethod
    def combine(a: MassProperties2, b: MassProperties2) -> MassProperties2:
        """The union of two laminae in one frame: masses add, moments are shifted to the common COM and added."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __repr__(self) -> str: ...


class SecondMoments(metaclass=_Pybind11Type):
    """n-D mass, COM and second-moment matrix J about the COM."""
    def __init__(self, mass: float, com: object, J_com: object) -> None:
        """Mass (kg), COM (shape (n,), m) and second-moment matrix J = ∫ρ r rᵀ about the COM (shape (n, n), kg·m²) of an n-dimensional body."""
    @property
    def mass(self) -> float:
        """Mass (kg)."""
    @property
    def com(self) -> NDArray[numpy.float64]:
        """Center of mass in the body frame (m)."""
    @property
    def J_com(self) -> NDArray[numpy.float64]:
        """Second-moment matrix ∫ρ r rᵀ dV about the COM (kg·m²)."""
    @property
    def dimension(self) -> int:
        """n, the dimension of the space."""
    def J_about(self, q: object) -> NDArray[numpy.float64]:
        """Second moments about the point q (shape (n,), m): J_C + m d dᵀ, d = c − q."""
    def apply(self, Omega: object) -> NDArray[numpy.float64]:
        """Body angular momentum M = J Ω + Ω J (kg·m²/s) of the angular velocity Ω ∈ so(n) (n × n skew, rad/s)."""
    def to_mass_properties(self) -> MassProperties:
        """The 3D MassProperties (I = tr(J) 1 − J); raises rigid.Error unless n = 3."""
    @staticmethod
    def from_mass_properties(mp: MassProperties) -> SecondMoments:
        """The second moments of 3D mass properties: J = ½ tr(I) 1 − I."""
    def __getstate__(self) -> tuple[Any, ...]: ...
    def __setstate__(self, arg0: tuple[Any, ...]) -> None: ...
    def __repr__(self) -> str: ...


def sweep(scene: object, *, grid: list[str] = ..., sample: list[str] = ..., samples: int = ..., seed: int = ..., set: list[str] = ..., integrator: str = ..., threads: int = ..., output: object = ..., report: object = ...) -> dict[str, Any]:
    """Runs one scene file many times, as `rigid sweep`: over a grid (grid=['L=0.5:2:4', ...], every combination, the first axis slowest) or a Monte Carlo sample (sample=['m=uniform(1,2)', 'k=normal(10,1)', 'c=loguniform(1e-3,1)'], samples=N, seed=S; reproducible whatever the threads). Each run gets `set` then its own values as overrides. Returns {'columns': {run, the swept names, each run's metrics and diagnostics: numpy arrays, NaN for a failed run}, 'errors': [text per run, '' when it succeeded], 'summary': statistics per column as summary.json}; with `output` (a directory) also writes runs.csv, runs.npy and summary.json, byte for byte what `rigid sweep` writes; with `report` (a file name) also writes the sweep's page there, as `rigid sweep --report` (returned as 'report'). Runs on `threads` threads with the GIL released; Ctrl-C raises KeyboardInterrupt."""


class Scene(metaclass=_Pybind11Type):
    """A scene file turned into a model (parameters evaluated, mass properties and equations built). Errors are rigid.Error with file:line:col."""
    def __init__(self, path: object, set: list[str] = ..., *, pin_free_root: bool | None = ..., inertia_from_geometry: bool | None = ..., density: float | None = ..., symbolic_inertia: bool | None = ...) -> None:
        """Loads a TOML scene file or a robot model file (URDF, MJCF; a str or pathlib.Path; mesh and [model] paths are relative to its directory; errors start with file:line:col); `set` holds 'name=value' overrides: parameters, simulation.<key>, <coordinate>.initial/.velocity, <body>.omega (docs/scene-format.md). pin_free_root, inertia_from_geometry and density (kg/m³, a URDF's collision geometry with inertia_from_geometry) say how the robot model file is read, the one given or the one [model] names (over the section's settings; None: the section's, else False, False, 1000); symbolic_inertia keeps each link's mass, COM and inertia as the parameters m_<link>, com_<link>_x.., I_<link>_xx..; a TOML scene without [model] refuses them. Text is loaded by Scene.from_string."""
    @staticmethod
    def from_string(text: str, set: list[str] = ..., name: object = ...) -> Scene:
        """A scene from TOML text (what a scene file holds): errors start with name:line:col (name default '<string>'), and mesh paths are relative to name's directory (the current directory by default); `set` as in rigid.Scene(path, set)."""
    @property
    def kind(self) -> str:
        """'coordinates' (a Lagrangian system of generalized coordinates) or 'free_bodies'."""
    @property
    def schema(self) -> Any:
        """What a run returns, known before it runs: {'kind', 'columns': [{'name', 'quantity', 'owner', 'component', 'unit'}, ...] in the order of run()'s columns, 'parameters' / 'diagnostics' / 'metrics': {name: SI unit}} ('' when dimensionless or not stated; docs/scene-format.md)."""
    @property
    def parameters(self) -> dict[str, Any]:
        """The scene's parameters after `set` overrides, {name: value} in file order (SI units)."""
    @property
    def bodies(self) -> dict[str, Any]:
        """The bodies' mass properties (rigid.MassProperties in each body's frame), by name."""
    @property
    def warnings(self) -> list[str]:
        """What the scene's checks found suspicious but not wrong (the CLI prints them too)."""
    @property
    def t_end(self) -> float:
        """End time of a run (s)."""
    def integrator(self, requested: str = ...) -> str:
        """The method a run uses (the requested one, the scene's, or the kind's default)."""
    def equations(self, latex: bool = ..., format: str = ...) -> str:
        """The equations of motion as `rigid eom` prints them: format 'text' (default), 'latex' or 'json' (latex=True is format='latex')."""
    def emit(self, language: str, name: str = ..., flat: bool = ..., *, max_stack_bytes: int | None = ..., namespace: str = ...) -> str:
        """The equations of motion (M, f, G, γ) as one dependency-free source file: 'c++' (a header, <cmath> only; namespace `name`, default the file's stem) or 'python' (a module, math only), with the scene's parameters as defaults. flat=True (C++): the dynamics at global scope without t, as `rigid eom --emit c++ --flat`; max_stack_bytes (with flat=True): the most stack forward_dynamics_derivatives may take for M⁻¹ and its products, 16 n² + 8 n bytes (default 66048: n ≤ 64), above which it solves column by column, as --max-stack-bytes; namespace (with flat=True): the C++ namespace of its declarations instead of global scope, as --namespace."""
    @property
    def system(self) -> lagrange.System: ...
    def check(self, integrator: str = ..., max_memory: object = ...) -> None:
        """Runs the checks of a run (initial conditions, mass matrix, steps, the trajectory's memory against max_memory) without integrating."""
    def run(self, integrator: str = ..., output: os.PathLike[str] | None = ..., formats: list[str] = ..., max_memory: object = ..., report: object = ..., report_frames: object = ...) -> dict[str, Any]:
        """Simulates to t_end: {'columns': {name: numpy array}, 'summary': {...}, 'schema': Scene.schema} with the columns of docs/scene-format.md; summary['metrics'] holds the scene's [[output.metrics]] as {name: {'value', 'unit', 'note'}} (value NaN, with a note, when the event did not happen). With `output` (a directory), also writes the files `rigid run` writes (trajectory.csv, trajectory.npy, summary.json; `formats` as in the scene's [output] by default; summary.json always comes with trajectory.npy) as one set that replaces the directory, only after the run succeeded; the paths are under 'written'. `max_memory` (bytes or a size such as "512MiB"; default: the scene's [output] max_memory, else 2 GiB) caps the trajectory, checked before the run. Ctrl-C raises KeyboardInterrupt and writes nothing. `report=True` adds report.html to the files in `output` (one self-contained page: 3D motion, plots, equations; docs/report.md), `report=PATH` writes the page alone; its path is under 'report'. `report_frames` (default 2000) caps the frames the page keeps."""
    def __repr__(self) -> str: ...
    def modes(self, at: object = ...) -> lagrange.NormalModes:
        """The normal modes of a scene of coordinates, as `rigid modes SCENE --at ...`: `at` as in System.modes (values may be expressions of the scene's parameters). Returns rigid.lagrange.NormalModes."""
