#pragma once

#include <random>

#include <Eigen/Core>

#include "rigid/lie/angle_limit.hpp"

#include "rigid/common/scalars.hpp"

namespace rigid {

/// Rotation group SO(2), stored as a unit complex number z = c + i s = e^{iθ}.
///
/// Class invariant: c² + s² = 1 within a few ulps. The tangent is the angle θ (radians,
/// counter-clockwise), held in a 1-vector so that SO2 has the same API shape as SO3;
/// hat(θ) = [[0, −θ], [θ, 0]]. SO(2) is abelian: Ad = 1 and both Jacobians are 1.
template <typename Scalar>
class SO2 {
 public:
  using Vector1 = Eigen::Matrix<Scalar, 1, 1>;
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;
  using Matrix1 = Eigen::Matrix<Scalar, 1, 1>;
  using Matrix2 = Eigen::Matrix<Scalar, 2, 2>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
  static constexpr int kDim = 1;  ///< n(n−1)/2 with n = 2
  static constexpr int kDof = 1;
  using Tangent = Vector1;
  using Point = Vector2;

  /// The identity rotation.
  [[nodiscard]] static SO2 identity() { return SO2(Scalar(1), Scalar(0)); }
  /// Rotation by `theta` radians, counter-clockwise. @throws rigid::Error if theta is not finite
  /// or |theta| > kMaxAngle.
  [[nodiscard]] static SO2 from_angle(const Scalar& theta);
  /// Unit complex number c + i s; a non-unit input is normalised.
  /// @throws rigid::Error if a component is not finite or the norm is below 1e-12.
  [[nodiscard]] static SO2 from_complex(const Scalar& c, const Scalar& s);
  /// Rotation matrix R_AB. @throws rigid::Error if R is not finite, max|RᵀR − I| > tol or
  /// det R < 0 (the message gives the defect and the determinant).
  [[nodiscard]] static SO2 from_matrix(const Matrix2& R, double tol = 1e-9);

  /// Exponential map: angle θ → e^{iθ}. @throws rigid::Error as from_angle.
  [[nodiscard]] static SO2 exp(const Tangent& theta) { return from_angle(theta(0)); }
  /// hat(θ) = [[0, −θ], [θ, 0]].
  [[nodiscard]] static Matrix2 hat(const Tangent& theta) {
    Matrix2 m;
    m << Scalar(0), -theta(0), theta(0), Scalar(0);
    return m;
  }
  /// Inverse of hat (reads the lower-left entry).
  [[nodiscard]] static Tangent vee(const Matrix2& m) { return Tangent(m(1, 0)); }
  /// Jacobians of exp: all equal to 1 (the group is abelian).
  [[nodiscard]] static Matrix1 right_jacobian(const Tangent&) { return Matrix1::Identity(); }
  [[nodiscard]] static Matrix1 left_jacobian(const Tangent&) { return Matrix1::Identity(); }
  [[nodiscard]] static Matrix1 right_jacobian_inverse(const Tangent&) { return Matrix1::Identity(); }
  [[nodiscard]] static Matrix1 left_jacobian_inverse(const Tangent&) { return Matrix1::Identity(); }
  /// Haar-uniform random rotation (angle uniform on [−π, π)).
  [[nodiscard]] static SO2 sample(std::mt19937_64& rng);

  /// Logarithm: the angle in (−π, π] (atan2 of the stored complex number).
  [[nodiscard]] Tangent log() const { return Tangent(angle()); }
  /// Rotation angle in (−π, π].
  [[nodiscard]] Scalar angle() const;
  /// Rotation matrix [[c, −s], [s, c]].
  [[nodiscard]] Matrix2 matrix() const {
    Matrix2 R;
    R << c_, -s_, s_, c_;
    return R;
  }
  /// Adjoint (1 × 1 identity: rotations of the plane commute).
  [[nodiscard]] Matrix1 adjoint() const { return Matrix1::Identity(); }
  /// Homogeneous 3×3 form [[R, 0], [0, 1]].
  [[nodiscard]] Matrix3 homogeneous() const {
    Matrix3 T = Matrix3::Identity();
    T.template topLeftCorner<2, 2>() = matrix();
    return T;
  }
  [[nodiscard]] const Scalar& real() const { return c_; }
  [[nodiscard]] const Scalar& imag() const { return s_; }

  [[nodiscard]] SO2 inverse() const { return SO2(c_, -s_); }
  /// Composition: the complex product (6 flops).
  [[nodiscard]] SO2 operator*(const SO2& b) const {
    return SO2(c_ * b.c_ - s_ * b.s_, c_ * b.s_ + s_ * b.c_);
  }
  SO2& operator*=(const SO2& b) { return *this = *this * b; }
  /// Rotates a point or vector of the plane.
  [[nodiscard]] Vector2 operator*(const Vector2& v) const {
    return Vector2(c_ * v(0) - s_ * v(1), s_ * v(0) + c_ * v(1));
  }
  /// Geodesic interpolation a · exp(s · log(a⁻¹ b)).
  /// @throws rigid::Error if s is not finite, or s · log(a⁻¹ b) is not finite or turns by
  /// more than kMaxAngle.
  [[nodiscard]] SO2 interpolate(const SO2& b, const Scalar& s) const;
  /// True if the two represent the same rotation within `tol` (|angle of a⁻¹ b|, radians).
  [[nodiscard]] bool is_approx(const SO2& b, double tol = 1e-12) const;

 private:
  SO2(const Scalar& c, const Scalar& s) : c_(c), s_(s) {}
  static SO2 from_angle_unchecked(const Scalar& theta);
  Scalar c_;
  Scalar s_;
};

using SO2d = SO2<double>;

extern template class SO2<double>;
extern template class SO2<AutoDiffXd>;

}  // namespace rigid
