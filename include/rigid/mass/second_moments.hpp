#pragma once

#include <span>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"

namespace rigid {

/// Second moments of a body in n dimensions: mass m (kg), center of mass c (m) and the
/// second-moment matrix about the COM, J_C = ∫ρ (x − c)(x − c)ᵀ dV (kg·m²).
///
/// J is what generalises the inertia tensor: the body's kinetic energy of rotation with
/// body angular velocity Ω ∈ so(n) (skew n × n) is T = ½ tr(Ω J Ωᵀ) and its angular momentum is
/// M = J Ω + Ω J. In 3D, I = tr(J) 1 − J and J = ½ tr(I) 1 − I.
///
/// Class invariant: m > 0, finite, J_C symmetric positive semidefinite (within 1e-10·tr J).
class SecondMoments {
 public:
  /// @throws rigid::Error if the dimensions disagree or the invariant fails.
  SecondMoments(double mass, const Eigen::VectorXd& com, const Eigen::MatrixXd& J_com);

  [[nodiscard]] Eigen::Index dimension() const { return com_.size(); }
  [[nodiscard]] double mass() const { return mass_; }
  [[nodiscard]] const Eigen::VectorXd& com() const { return com_; }
  [[nodiscard]] const Eigen::MatrixXd& J_com() const { return J_com_; }

  /// J about the point q: J_q = J_C + m (c − q)(c − q)ᵀ.
  [[nodiscard]] Eigen::MatrixXd J_about(const Eigen::VectorXd& q) const;

  /// Angular momentum of the body-frame angular velocity Ω (n × n skew): M = J_C Ω + Ω J_C.
  /// @throws rigid::Error if Ω is not n × n or not skew-symmetric within 1e-12·max|Ω|.
  [[nodiscard]] Eigen::MatrixXd apply(const Eigen::MatrixXd& Omega) const;

  /// The 3D inertia tensor about the COM, I = tr(J) 1 − J. @throws unless dimension() == 3.
  [[nodiscard]] MassProperties to_mass_properties() const;

  /// J of 3D mass properties: J = ½ tr(I) 1 − I.
  [[nodiscard]] static SecondMoments from_mass_properties(const MassProperties& mp);

 private:
  double mass_;
  Eigen::VectorXd com_;
  Eigen::MatrixXd J_com_;
};

}  // namespace rigid

namespace rigid::mass {

/// Uniform n-ball of radius r in n ≥ 1 dimensions: J = m r²/(n + 2) · 1;
/// volume π^{n/2} rⁿ / Γ(n/2 + 1). Mass (or density, kg/mⁿ) first, as every factory.
/// @param m mass (kg); r radius (m); n dimension.
/// @throws rigid::Error if m (rho) or r is not positive and finite, or n < 1.
[[nodiscard]] SecondMoments n_ball_with_mass(double m, double r, int n);
[[nodiscard]] SecondMoments n_ball_with_density(double rho, double r, int n);

/// Uniform n-box with edge lengths `sizes` (n = sizes.size() ≥ 1), centred:
/// J = m diag(l_i²/12); volume Π l_i.
[[nodiscard]] SecondMoments n_box_with_mass(double m, const Eigen::VectorXd& sizes);
[[nodiscard]] SecondMoments n_box_with_density(double rho, const Eigen::VectorXd& sizes);

/// Point masses masses[i] at points.col(i) (n × k).
[[nodiscard]] SecondMoments point_set_second_moments(std::span<const double> masses,
                                                     const Eigen::MatrixXd& points);

}  // namespace rigid::mass
