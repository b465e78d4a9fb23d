#pragma once

#include <random>

#include <Eigen/Core>

#include "rigid/lie/angle_limit.hpp"

#include "rigid/lie/son.hpp"

namespace rigid {

/// Rigid motion group SE(n) for any n ≥ 2 chosen at run time: X_AB = (R_AB, p_AB) maps a
/// point expressed in B to A, p_A = R_AB p_B + p_AB (double precision only).
///
/// Tangent vectors ξ = (ρ, ω) ∈ R^{n + n(n−1)/2} = R^{n(n+1)/2}, translation part first as in
/// SE3, ω in SOn's basis; hat(ξ) = [[hat(ω), ρ], [0, 0]] ((n+1)×(n+1)). For n = 3 this is
/// SE3's convention. Class invariant: the rotation is a valid SOn, t has n finite entries.
class SEn {
 public:
  using Tangent = Eigen::VectorXd;

  /// @throws rigid::Error if t does not have R.n() entries or is not finite.
  SEn(const SOn& R, const Eigen::VectorXd& t);
  /// The identity of SE(n). @throws rigid::Error if n < 2.
  [[nodiscard]] static SEn identity(int n);
  /// From a homogeneous (n+1)×(n+1) matrix. @throws rigid::Error if it is not square of size
  /// ≥ 3, its last row is not (0, …, 0, 1), the translation is not finite or the rotation
  /// block is not a rotation (see SOn::from_matrix).
  [[nodiscard]] static SEn from_matrix(const Eigen::MatrixXd& T, double tol = 1e-9);

  /// Dimension n(n+1)/2 of SE(n).
  [[nodiscard]] static int dimension_of(int n) { return n * (n + 1) / 2; }
  /// The n with n(n+1)/2 = m. @throws rigid::Error if m is not such a number with n ≥ 2.
  [[nodiscard]] static int n_from_dimension(Eigen::Index m);

  /// exp(ρ, ω) = (exp(ω), φ(hat ω) ρ), φ(W) = Σₖ Wᵏ/(k+1)! (the top-right column of the
  /// matrix exponential of hat(ξ)). @throws rigid::Error if ξ's size is not n(n+1)/2, n ≥ 2.
  [[nodiscard]] static SEn exp(const Tangent& xi);
  [[nodiscard]] static Eigen::MatrixXd hat(const Tangent& xi);
  /// @throws rigid::Error if m is not (n+1)×(n+1), n ≥ 2, with a zero last row and a skew
  /// top-left block (within tol).
  [[nodiscard]] static Tangent vee(const Eigen::MatrixXd& m, double tol = 1e-9);
  /// The matrix ad_ξ of ζ ↦ vee([hat(ξ), hat(ζ)]).
  [[nodiscard]] static Eigen::MatrixXd ad(const Tangent& xi);
  /// Jacobians of exp, Jr(ξ) = φ(−ad_ξ), Jl(ξ) = φ(ad_ξ) [Sola2018] (evaluated as in SOn);
  /// inverses numerical (LU).
  [[nodiscard]] static Eigen::MatrixXd right_jacobian(const Tangent& xi);
  [[nodiscard]] static Eigen::MatrixXd left_jacobian(const Tangent& xi);
  [[nodiscard]] static Eigen::MatrixXd right_jacobian_inverse(const Tangent& xi);
  [[nodiscard]] static Eigen::MatrixXd left_jacobian_inverse(const Tangent& xi);
  /// Haar-uniform rotation (SOn::sample); translation uniform in [−half_extent, half_extent]ⁿ.
  [[nodiscard]] static SEn sample(int n, std::mt19937_64& rng, double half_extent = 1.0);

  /// Logarithm (ρ, ω) with ω = R.log(), ρ = φ(hat ω)⁻¹ t.
  [[nodiscard]] Tangent log() const;
  [[nodiscard]] const SOn& rotation() const { return R_; }
  [[nodiscard]] const Eigen::VectorXd& translation() const { return t_; }
  [[nodiscard]] Eigen::MatrixXd matrix() const;
  [[nodiscard]] Eigen::MatrixXd homogeneous() const { return matrix(); }
  /// Adjoint [[R, −M_t Ad_R], [0, Ad_R]], M_t ω = hat(ω) t: X exp(ξ) X⁻¹ = exp(Ad ξ).
  [[nodiscard]] Eigen::MatrixXd adjoint() const;
  [[nodiscard]] int n() const { return R_.n(); }
  [[nodiscard]] int dimension() const { return dimension_of(n()); }

  [[nodiscard]] SEn inverse() const;
  /// Composition. @throws rigid::Error if the two n differ.
  [[nodiscard]] SEn operator*(const SEn& b) const;
  /// Acts on a point: R p + t. @throws rigid::Error on a size mismatch.
  [[nodiscard]] Eigen::VectorXd operator*(const Eigen::VectorXd& p) const;
  /// Acts on a free vector (no translation): R v.
  [[nodiscard]] Eigen::VectorXd act_vector(const Eigen::VectorXd& v) const { return R_ * v; }
  /// Geodesic interpolation a · exp(s · log(a⁻¹ b)).
  /// @throws rigid::Error if s is not finite, or s · log(a⁻¹ b) is not finite or turns by
  /// more than kMaxAngle.
  [[nodiscard]] SEn interpolate(const SEn& b, double s) const;

 private:
  SEn(SOn R, Eigen::VectorXd t, bool /*unchecked*/) : R_(std::move(R)), t_(std::move(t)) {}
  SOn R_;
  Eigen::VectorXd t_;
};

}  // namespace rigid
