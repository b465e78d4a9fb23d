#pragma once

#include <random>
#include <utility>

#include <Eigen/Core>

#include "rigid/lie/angle_limit.hpp"

namespace rigid {

/// Rotation group SO(n) for any n ≥ 2 chosen at run time, stored as an n×n rotation matrix
/// (double precision only).
///
/// Class invariant: RᵀR = I and det R = +1 within rounding. Tangent vectors ω ∈ R^m,
/// m = n(n−1)/2, are coordinates in the basis of so(n) (skew n×n matrices) described at
/// hat(): for n = 3 it is SO3's hat (hat(ω) v = ω × v), for n = 2 SO2's hat(θ).
class SOn {
 public:
  using Tangent = Eigen::VectorXd;

  /// The identity of SO(n). @throws rigid::Error if n < 2.
  [[nodiscard]] static SOn identity(int n);
  /// Rotation matrix R_AB. @throws rigid::Error if R is empty, not square, smaller than 2×2,
  /// not finite, max|RᵀR − I| > tol or det R < 0 (the message gives the defect and the
  /// determinant). Use nearest_rotation first for a matrix that is only roughly orthonormal.
  [[nodiscard]] static SOn from_matrix(const Eigen::MatrixXd& R, double tol = 1e-9);

  /// Dimension n(n−1)/2 of SO(n).
  [[nodiscard]] static int dimension_of(int n) { return n * (n - 1) / 2; }
  /// The n with n(n−1)/2 = m. @throws rigid::Error if m is not such a number with n ≥ 2.
  [[nodiscard]] static int n_from_dimension(Eigen::Index m);

  /// Exponential map so(n) → SO(n); n is deduced from ω's size (m = n(n−1)/2).
  /// Scaling and squaring with the degree-13 Padé approximant [Higham2005] (Eigen's
  /// MatrixFunctions): for skew W the diagonal Padé approximant q(W)⁻¹ q(−W) = q(W)⁻¹ q(W)ᵀ
  /// is itself orthogonal, and squaring keeps it so, so the result is a rotation to rounding.
  /// @throws rigid::Error if ω's size is not n(n−1)/2 for some n ≥ 2 or ω is not finite.
  [[nodiscard]] static SOn exp(const Tangent& omega);
  /// Skew matrix of ω. Basis: the pairs (i, j), i < j, taken in reverse lexicographic order
  /// ((n−2, n−1), (n−3, n−1), (n−3, n−2), …, (0, 1)); component k sets
  /// W(j, i) = σ ω_k and W(i, j) = −σ ω_k with σ = (−1)^{i+j+1}. For n = 3 this is
  /// ω = (W₂₁, W₀₂, W₁₀), SO3's hat; for n = 2 it is W₁₀ = θ, SO2's hat. The basis is
  /// orthonormal for ⟨A, B⟩ = ½ tr(AᵀB).
  /// @throws rigid::Error if ω's size is not n(n−1)/2 for some n ≥ 2.
  [[nodiscard]] static Eigen::MatrixXd hat(const Tangent& omega);
  /// Inverse of hat. @throws rigid::Error if W is not square with n ≥ 2 or
  /// max|W + Wᵀ| > tol (not skew).
  [[nodiscard]] static Tangent vee(const Eigen::MatrixXd& W, double tol = 1e-9);
  /// Right and left Jacobians of exp, Jr(ω) = Σₖ (−ad_ω)ᵏ/(k+1)!, Jl(ω) = Jr(−ω)
  /// ([Sola2018] for the series; ad_ω is the m×m matrix of [hat(ω), ·]). Evaluated as the
  /// top-right block of exp([[A, I], [0, 0]]) = [[e^A, φ(A)], [0, I]] [Higham2008, §10.7],
  /// so no series is truncated. Inverses are numerical (LU), defined while the largest
  /// rotation angle is below π.
  [[nodiscard]] static Eigen::MatrixXd right_jacobian(const Tangent& omega);
  [[nodiscard]] static Eigen::MatrixXd left_jacobian(const Tangent& omega);
  [[nodiscard]] static Eigen::MatrixXd right_jacobian_inverse(const Tangent& omega);
  [[nodiscard]] static Eigen::MatrixXd left_jacobian_inverse(const Tangent& omega);
  /// The m×m matrix ad_ω of ξ ↦ vee([hat(ω), hat(ξ)]).
  [[nodiscard]] static Eigen::MatrixXd ad(const Tangent& omega);
  /// Haar-uniform random rotation: QR of an n×n standard Gaussian matrix with the signs of
  /// R's diagonal moved into Q (Haar on O(n)) [Mezzadri2007], then the first column negated
  /// when det Q = −1 (a fixed right translation, so the law on SO(n) is Haar).
  /// @throws rigid::Error if n < 2.
  [[nodiscard]] static SOn sample(int n, std::mt19937_64& rng);

  /// Principal logarithm: the ω with all rotation angles in [0, π] and exp(ω) = R, from the
  /// real Schur form R = Q T Qᵀ (T block diagonal for an orthogonal matrix): each 2×2 block
  /// gives its angle by atan2, which stays accurate near 0 and π. Where angles equal π
  /// (eigenvalue −1, paired 1×1 blocks) the logarithm is not unique and one of the valid
  /// ones is returned; near π it is ill-conditioned (a perturbation δ of R moves ω by up to
  /// ~δ/(π − θ) in the plane of that angle).
  [[nodiscard]] Tangent log() const;
  /// The rotation angles θ₁ ≥ θ₂ ≥ … ≥ 0 (⌊n/2⌋ of them) of the planes of R, in [0, π].
  [[nodiscard]] Eigen::VectorXd angles() const;
  [[nodiscard]] const Eigen::MatrixXd& matrix() const { return R_; }
  /// Homogeneous (n+1)×(n+1) form [[R, 0], [0, 1]].
  [[nodiscard]] Eigen::MatrixXd homogeneous() const;
  /// Adjoint: the m×m matrix of ω ↦ vee(R hat(ω) Rᵀ), entries the signed 2×2 minors of R
  /// (R acting on Λ²Rⁿ); g exp(ω) g⁻¹ = exp(Ad ω).
  [[nodiscard]] Eigen::MatrixXd adjoint() const;
  [[nodiscard]] int n() const { return static_cast<int>(R_.rows()); }
  [[nodiscard]] int dimension() const { return dimension_of(n()); }

  [[nodiscard]] SOn inverse() const { return SOn(R_.transpose()); }
  /// Composition. @throws rigid::Error if the two n differ.
  [[nodiscard]] SOn operator*(const SOn& b) const;
  /// Rotates a point or vector of Rⁿ. @throws rigid::Error on a size mismatch.
  [[nodiscard]] Eigen::VectorXd operator*(const Eigen::VectorXd& v) const;
  /// Geodesic interpolation a · exp(s · log(a⁻¹ b)).
  /// @throws rigid::Error if s is not finite, or s · log(a⁻¹ b) is not finite or turns by
  /// more than kMaxAngle.
  [[nodiscard]] SOn interpolate(const SOn& b, double s) const;
  /// True if max|Ra − Rb| ≤ tol. @throws rigid::Error if the two n differ.
  [[nodiscard]] bool is_approx(const SOn& b, double tol = 1e-12) const;

 private:
  explicit SOn(Eigen::MatrixXd R) : R_(std::move(R)) {}
  Eigen::MatrixXd R_;
  friend class SEn;
};

}  // namespace rigid
