#pragma once

/// Euler–Arnold equations of the generalised rigid body on SO(n) [Ratiu1980]:
///   Ṁ = [M, Ω],  M = JΩ + ΩJ,
/// with J = diag(J_1 … J_n) > 0 the mass matrix (Σ m x xᵀ for a body of particles),
/// Ω ∈ so(n) the body angular velocity and M ∈ so(n) the body angular momentum.
/// For n = 3, M = hat(L) with L = Iω and I_1 = J_2 + J_3 (cyclic): Euler's equations.
/// The Casimirs tr(M^{2k}) are constants of the motion (M evolves isospectrally).

#include <Eigen/Core>

namespace rigid::body {

/// Ω from M: Ω_ij = M_ij / (J_i + J_j). `J` has n > 0 entries; `M` is n×n skew.
[[nodiscard]] Eigen::MatrixXd euler_arnold_velocity(const Eigen::VectorXd& J, const Eigen::MatrixXd& M);

/// Ṁ = MΩ − ΩM.
[[nodiscard]] Eigen::MatrixXd euler_arnold_rhs(const Eigen::VectorXd& J, const Eigen::MatrixXd& M);

/// One classical RK4 step of size h (s). Casimirs are kept to the method's O(h⁴) error.
[[nodiscard]] Eigen::MatrixXd euler_arnold_rk4_step(const Eigen::VectorXd& J, const Eigen::MatrixXd& M,
                                                    double h);

}  // namespace rigid::body
