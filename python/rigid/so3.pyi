# Type stubs of rigid.so3, generated from the built module's signatures by scripts/make_stubs.py:
# do not edit; rerun the script after changing a binding.
import os
from typing import Any, Callable, ClassVar, Iterable, Iterator, Sequence

import numpy
from numpy.typing import NDArray


def exp(omega: object, *, output: str = ..., order: str = ..., fast: bool = ...) -> NDArray[numpy.float64]:
    """Exponential map: rotation vectors omega (N, 3), axis times angle in rad (right hand), to rotations: quaternions (N, 4) (output='quaternion') or matrices (N, 3, 3) (output='matrix'). As SO3.exp(omega[i]), bit for bit. Refuses a non-finite omega. fast=True: a vectorised loop (polynomial sin and cos), each quaternion component within 4 ε (ε = 2⁻⁵²) of the default's (so3_kernels::kFastExpUlps), matrix entries within 24 ε; the same refusals."""


def log(q: object, *, order: str = ..., fast: bool = ...) -> NDArray[numpy.float64]:
    """Logarithm: quaternions (N, 4) to rotation vectors (N, 3) in rad with angle in [0, π] (accurate near 0 and π). As SO3.from_quaternion(*q[i]).log() (to an ulp: the quaternion is normalised by a Newton step). fast=True: a vectorised loop (polynomial atan), each component within 4 ε |ω| (ε = 2⁻⁵², |ω| the angle) of the default's (so3_kernels::kFastLogUlps); the same refusals."""


def compose(a: object, b: object, *, order: str = ...) -> NDArray[numpy.float64]:
    """Composition a[i] * b[i] (apply b first, then a: R_AC = R_AB * R_BC) of quaternions (N, 4); either may be a single (4,) quaternion. As SO3 * SO3."""


def act(q: object, v: object, *, order: str = ...) -> NDArray[numpy.float64]:
    """Rotated vectors q[i] * v[i] (N, 3) (active rotation: v_A = R_AB v_B); either argument may be a single element. As SO3 * vector."""


def inverse(q: object, *, order: str = ...) -> NDArray[numpy.float64]:
    """Inverse rotations (conjugate quaternions, normalised) (N, 4). As SO3.inverse()."""


def to_matrix(q: object, *, order: str = ...) -> NDArray[numpy.float64]:
    """Rotation matrices (N, 3, 3) of quaternions (N, 4). As SO3.matrix()."""


def from_matrix(R: object, *, tol: float = ..., order: str = ...) -> NDArray[numpy.float64]:
    """Quaternions (N, 4) of rotation matrices (N, 3, 3). As SO3.from_matrix(R[i], tol): refuses a matrix with max|RᵀR − I| > tol or det R < 0 (use rigid.nearest_rotation first for a matrix that is only roughly orthonormal)."""


def from_euler(angles: object, sequence: str = ..., *, intrinsic: bool = ..., order: str = ...) -> NDArray[numpy.float64]:
    """Quaternions (N, 4) of Euler angles (N, 3) in rad. sequence: one of XYZ XZY YXZ YZX ZXY ZYX XYX XZX YXY YZY ZXZ ZYZ (either case); intrinsic=True: axes moving with the body, R = R_1(a) R_2(b) R_3(c); intrinsic=False: fixed axes, R = R_3(c) R_2(b) R_1(a). SciPy spells intrinsic with upper case ('ZYX') and extrinsic with lower case ('zyx'). As SO3.from_euler(angles[i], sequence, intrinsic)."""


def to_euler(q: object, sequence: str = ..., *, intrinsic: bool = ..., order: str = ...) -> NDArray[numpy.float64]:
    """Euler angles (N, 3) in rad of quaternions (N, 4), for the sequence and intrinsic/extrinsic as in from_euler. Middle angle in [−π/2, π/2] (Tait–Bryan) or [0, π] (proper Euler), the others in (−π, π]. At gimbal lock the third intrinsic angle (the first extrinsic one) is 0. As SO3.to_euler(sequence, intrinsic)."""


sequences: tuple[str, ...]
