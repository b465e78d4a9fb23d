#pragma once

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"

/// Parameterisations of the ten inertial parameters for identification: the pseudo-inertia
/// matrix, whose positive definiteness is physical consistency [Wensing2017], and the
/// log-Cholesky parameters, a smooth unconstrained map onto the positive definite ones
/// [Rucker2022]. Both describe the body about the frame origin O, expressed in B.
namespace rigid::mass {

/// The ten log-Cholesky parameters θ = (α, d₁, d₂, d₃, s₁₂, s₂₃, s₁₃, t₁, t₂, t₃) [Rucker2022,
/// eq. 8 ordering]; J = U Uᵀ with U = e^α [[e^d₁, s₁₂, s₁₃, t₁], [0, e^d₂, s₂₃, t₂],
/// [0, 0, e^d₃, t₃], [0, 0, 0, 1]], so m = e^{2α}.
using LogCholesky = Eigen::Matrix<double, 10, 1>;

/// The pseudo-inertia J = [[Σ, h], [hᵀ, m]] (4×4) of the body about the frame origin O, in B:
/// Σ = ∫ρ r rᵀ dV = ½ tr(I_O) 1 − I_O (kg·m²), h = m p_OC_B (kg·m), m (kg) [Wensing2017, eq. 9].
/// @throws rigid::Error if an entry of J overflows a double (m |p_OC|² for a heavy body far
///   from O, a mass near the largest double), naming the mass and the COM.
[[nodiscard]] Eigen::Matrix4d pseudo_inertia(const MassProperties& mp);

/// The body of a pseudo-inertia J (about O, in B): m = J₃₃, p_OC = h/m,
/// Σ_C = Σ − m p pᵀ, I_C = tr(Σ_C) 1 − Σ_C.
/// @throws rigid::Error if J is not finite or not symmetric (within 1e-12 of its largest
///   element), or not positive semidefinite, naming the condition that fails: the mass
///   J₃₃ > 0, or the second moment about the COM Σ_C ⪰ 0, which is the triangle inequality of
///   the principal moments (with its margin, from MassProperties::check).
[[nodiscard]] MassProperties from_pseudo_inertia(const Eigen::Matrix4d& J);

/// The log-Cholesky parameters of the body about O in B [Rucker2022, eq. 8]: U from the
/// Cholesky factor of the reversed J (J = U Uᵀ, U upper triangular with a positive diagonal).
/// @throws rigid::Error if J is only semidefinite (a rod, a plate, a point mass: Σ_C has a zero
///   eigenvalue, below 1e-12 of tr Σ_C), which has no logarithm.
///   Also if J overflows (as pseudo_inertia) or its factorisation or a parameter is not finite.
[[nodiscard]] LogCholesky log_cholesky(const MassProperties& mp);

/// J = U Uᵀ of log-Cholesky parameters θ: positive definite for every finite θ.
/// @throws rigid::Error if θ is not finite or J overflows.
[[nodiscard]] Eigen::Matrix4d pseudo_inertia_from_log_cholesky(const LogCholesky& theta);

/// from_pseudo_inertia(pseudo_inertia_from_log_cholesky(θ)).
[[nodiscard]] MassProperties from_log_cholesky(const LogCholesky& theta);

}  // namespace rigid::mass
