#pragma once

/// Euler's equations of a rigid body in its principal body frame B:
///   I ω̇_B + ω_B × (I ω_B) = τ_B,
/// with I = diag(I1, I2, I3) the principal moments about the centre of mass (kg·m²),
/// ω_B the body-frame angular velocity (rad/s) and τ_B the body-frame torque (N·m).
/// Templated on the scalar so derivatives can pass through (double and AutoDiffXd
/// are compiled once in src/body/euler.cpp).

#include <Eigen/Core>

#include "rigid/common/scalars.hpp"

namespace rigid::body {

/// ω̇_B from Euler's equations, principal moments `I_B` (all > 0), body angular
/// velocity `w_B` and body torque `tau_B`.
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> euler_rhs(const Eigen::Vector3d& I_B,
                                      const Eigen::Matrix<Scalar, 3, 1>& w_B,
                                      const Eigen::Matrix<Scalar, 3, 1>& tau_B);

/// Kinetic energy ½ ωᵀ I ω (J) of the rotation.
template <typename Scalar>
Scalar rotational_energy(const Eigen::Vector3d& I_B, const Eigen::Matrix<Scalar, 3, 1>& w_B);

extern template Eigen::Vector3d euler_rhs<double>(const Eigen::Vector3d&, const Eigen::Vector3d&,
                                                  const Eigen::Vector3d&);
extern template Eigen::Matrix<AutoDiffXd, 3, 1> euler_rhs<AutoDiffXd>(
    const Eigen::Vector3d&, const Eigen::Matrix<AutoDiffXd, 3, 1>&,
    const Eigen::Matrix<AutoDiffXd, 3, 1>&);
extern template double rotational_energy<double>(const Eigen::Vector3d&, const Eigen::Vector3d&);
extern template AutoDiffXd rotational_energy<AutoDiffXd>(const Eigen::Vector3d&,
                                                         const Eigen::Matrix<AutoDiffXd, 3, 1>&);

}  // namespace rigid::body
