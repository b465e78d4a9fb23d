#pragma once

#include <random>

#include <Eigen/Core>

#include "rigid/common/scalars.hpp"
#include "rigid/lie/so3.hpp"

namespace rigid {

/// Rigid motion group SE(3): X_AB = (R_AB, p_AB) maps a point expressed in B to A,
/// p_A = R_AB p_B + p_AB.
///
/// Tangent vectors are ξ = (ρ, ω) ∈ R⁶, translation part first [Sola2018]; hat(ξ) is the 4×4
/// matrix [[hat(ω), ρ], [0, 0]]. Class invariant: the rotation is a valid SO3.
template <typename Scalar>
class SE3 {
 public:
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Vector6 = Eigen::Matrix<Scalar, 6, 1>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
  using Matrix4 = Eigen::Matrix<Scalar, 4, 4>;
  using Matrix6 = Eigen::Matrix<Scalar, 6, 6>;
  static constexpr int kDim = 6;  ///< n(n+1)/2 with n = 3
  static constexpr int kDof = 6;
  using Tangent = Vector6;
  using Point = Vector3;

  SE3(const SO3<Scalar>& R, const Vector3& t) : R_(R), t_(t) {}
  [[nodiscard]] static SE3 identity() { return SE3(SO3<Scalar>::identity(), Vector3::Zero()); }
  /// From a homogeneous 4×4 matrix. @throws rigid::Error if the last row is not (0, 0, 0, 1)
  /// or the rotation block is not a rotation (see SO3::from_matrix).
  [[nodiscard]] static SE3 from_matrix(const Matrix4& T, double tol = 1e-9);

  /// exp(ρ, ω) = (exp(ω), Jl(ω) ρ). @throws rigid::Error if ξ is not finite or |ω| > kMaxAngle.
  [[nodiscard]] static SE3 exp(const Vector6& xi);
  [[nodiscard]] static Matrix4 hat(const Vector6& xi);
  [[nodiscard]] static Vector6 vee(const Matrix4& m);
  /// Right and left Jacobians of exp (6×6, [Sola2018], [Barfoot2017]).
  [[nodiscard]] static Matrix6 right_jacobian(const Vector6& xi);
  [[nodiscard]] static Matrix6 left_jacobian(const Vector6& xi);
  /// Closed-form inverses: Jl(ξ)⁻¹ = [[Jl⁻¹, −Jl⁻¹ Q Jl⁻¹], [0, Jl⁻¹]] (block inverse of
  /// Jl(ξ), Jl⁻¹ = Jl(ω)⁻¹ in closed form) [Barfoot2017, §7.1.5], Jr(ξ)⁻¹ = Jl(−ξ)⁻¹.
  [[nodiscard]] static Matrix6 right_jacobian_inverse(const Vector6& xi) {
    return left_jacobian_inverse(-xi);
  }
  [[nodiscard]] static Matrix6 left_jacobian_inverse(const Vector6& xi);
  /// Haar-uniform rotation; translation uniform in the cube [−half_extent, half_extent]³
  /// (SE(3) is not compact, so a bounded translation law must be chosen).
  [[nodiscard]] static SE3 sample(std::mt19937_64& rng, double half_extent = 1.0);

  /// Logarithm (ρ, ω) with |ω| ≤ π.
  [[nodiscard]] Vector6 log() const;
  [[nodiscard]] const SO3<Scalar>& rotation() const { return R_; }
  [[nodiscard]] const Vector3& translation() const { return t_; }
  [[nodiscard]] Matrix4 matrix() const;
  [[nodiscard]] Matrix4 homogeneous() const { return matrix(); }
  /// Adjoint Ad = [[R, hat(t) R], [0, R]] for ξ = (ρ, ω): X exp(ξ) X⁻¹ = exp(Ad ξ).
  [[nodiscard]] Matrix6 adjoint() const;

  [[nodiscard]] SE3 inverse() const {
    const SO3<Scalar> Ri = R_.inverse();
    return SE3(Ri, -(Ri * t_));
  }
  [[nodiscard]] SE3 operator*(const SE3& b) const { return SE3(R_ * b.R_, t_ + R_ * b.t_); }
  SE3& operator*=(const SE3& b) { return *this = *this * b; }
  /// Acts on a point: R p + t.
  [[nodiscard]] Vector3 operator*(const Vector3& p) const { return R_ * p + t_; }
  /// Acts on a free vector (no translation): R v.
  [[nodiscard]] Vector3 act_vector(const Vector3& v) const { return R_ * v; }
  /// Geodesic interpolation a · exp(s · log(a⁻¹ b)).
  /// @throws rigid::Error if s is not finite, or s · log(a⁻¹ b) is not finite or turns by
  /// more than kMaxAngle.
  [[nodiscard]] SE3 interpolate(const SE3& b, const Scalar& s) const;

 private:
  SO3<Scalar> R_;
  Vector3 t_;
};

using SE3d = SE3<double>;

extern template class SE3<double>;
extern template class SE3<AutoDiffXd>;

}  // namespace rigid
