#pragma once

#include <random>

#include <Eigen/Core>

#include "rigid/lie/angle_limit.hpp"

#include "rigid/common/scalars.hpp"
#include "rigid/lie/so2.hpp"

namespace rigid {

/// Rigid motion group SE(2): X_AB = (R_AB, p_AB) maps a point expressed in B to A,
/// p_A = R_AB p_B + p_AB.
///
/// Tangent vectors are ξ = (ρx, ρy, θ) ∈ R³, translation part first as in SE3 [Sola2018];
/// hat(ξ) = [[0, −θ, ρx], [θ, 0, ρy], [0, 0, 0]]. Class invariant: the rotation is a valid SO2.
template <typename Scalar>
class SE2 {
 public:
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Matrix2 = Eigen::Matrix<Scalar, 2, 2>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
  static constexpr int kDim = 3;  ///< n(n+1)/2 with n = 2
  static constexpr int kDof = 3;
  using Tangent = Vector3;
  using Point = Vector2;

  SE2(const SO2<Scalar>& R, const Vector2& t) : R_(R), t_(t) {}
  [[nodiscard]] static SE2 identity() { return SE2(SO2<Scalar>::identity(), Vector2::Zero()); }
  /// From a homogeneous 3×3 matrix. @throws rigid::Error if the last row is not (0, 0, 1),
  /// the translation is not finite or the rotation block is not a rotation.
  [[nodiscard]] static SE2 from_matrix(const Matrix3& T, double tol = 1e-9);

  /// exp(ρ, θ) = (e^{iθ}, V(θ) ρ), V(θ) = (sin θ/θ) I + ((1 − cos θ)/θ) J,
  /// J = [[0, −1], [1, 0]] [Sola2018, eq. 156].
  [[nodiscard]] static SE2 exp(const Tangent& xi);
  [[nodiscard]] static Matrix3 hat(const Tangent& xi) {
    Matrix3 m = Matrix3::Zero();
    m(0, 1) = -xi(2);
    m(1, 0) = xi(2);
    m(0, 2) = xi(0);
    m(1, 2) = xi(1);
    return m;
  }
  [[nodiscard]] static Tangent vee(const Matrix3& m) { return Tangent(m(0, 2), m(1, 2), m(1, 0)); }
  /// Left Jacobian Jl(ξ) = [[V(θ), c1 ρ − c2 J ρ], [0, 1]], c1 = (θ − sin θ)/θ²,
  /// c2 = (1 − cos θ)/θ² (derived in se2.cpp; agrees with [Sola2018, eq. 164]); Jr(ξ) = Jl(−ξ).
  [[nodiscard]] static Matrix3 left_jacobian(const Tangent& xi);
  [[nodiscard]] static Matrix3 right_jacobian(const Tangent& xi) { return left_jacobian(-xi); }
  /// Closed-form inverses [[V⁻¹, −V⁻¹ w], [0, 1]] with V⁻¹ = [[A, θ/2], [−θ/2, A]],
  /// A = (θ/2) cot(θ/2).
  [[nodiscard]] static Matrix3 left_jacobian_inverse(const Tangent& xi);
  [[nodiscard]] static Matrix3 right_jacobian_inverse(const Tangent& xi) {
    return left_jacobian_inverse(-xi);
  }
  /// Haar-uniform rotation; translation uniform in the square [−half_extent, half_extent]²
  /// (SE(2) is not compact, so a bounded translation law must be chosen).
  [[nodiscard]] static SE2 sample(std::mt19937_64& rng, double half_extent = 1.0);

  /// Logarithm (ρ, θ) with θ ∈ (−π, π].
  [[nodiscard]] Tangent log() const;
  [[nodiscard]] const SO2<Scalar>& rotation() const { return R_; }
  [[nodiscard]] const Vector2& translation() const { return t_; }
  [[nodiscard]] Matrix3 matrix() const {
    Matrix3 T = Matrix3::Identity();
    T.template topLeftCorner<2, 2>() = R_.matrix();
    T.template topRightCorner<2, 1>() = t_;
    return T;
  }
  [[nodiscard]] Matrix3 homogeneous() const { return matrix(); }
  /// Adjoint Ad = [[R, −J t], [0, 1]] for ξ = (ρ, θ): X exp(ξ) X⁻¹ = exp(Ad ξ) [Sola2018, eq. 159].
  [[nodiscard]] Matrix3 adjoint() const {
    Matrix3 A = Matrix3::Identity();
    A.template topLeftCorner<2, 2>() = R_.matrix();
    A(0, 2) = t_(1);
    A(1, 2) = -t_(0);
    return A;
  }

  [[nodiscard]] SE2 inverse() const {
    const SO2<Scalar> Ri = R_.inverse();
    return SE2(Ri, -(Ri * t_));
  }
  [[nodiscard]] SE2 operator*(const SE2& b) const { return SE2(R_ * b.R_, t_ + R_ * b.t_); }
  SE2& operator*=(const SE2& b) { return *this = *this * b; }
  /// Acts on a point: R p + t.
  [[nodiscard]] Vector2 operator*(const Vector2& p) const { return R_ * p + t_; }
  /// Acts on a free vector (no translation): R v.
  [[nodiscard]] Vector2 act_vector(const Vector2& v) const { return R_ * v; }
  /// Geodesic interpolation a · exp(s · log(a⁻¹ b)).
  /// @throws rigid::Error if s is not finite, or s · log(a⁻¹ b) is not finite or turns by
  /// more than kMaxAngle.
  [[nodiscard]] SE2 interpolate(const SE2& b, const Scalar& s) const;

 private:
  SO2<Scalar> R_;
  Vector2 t_;
};

using SE2d = SE2<double>;

extern template class SE2<double>;
extern template class SE2<AutoDiffXd>;

}  // namespace rigid
