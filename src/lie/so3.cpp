#include "rigid/lie/so3.hpp"

#include <cmath>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "lie/detail/interpolation.hpp"
#include "lie/detail/value_of.hpp"

namespace rigid {

namespace {

using detail::value_of;

// Below this angle the closed forms lose digits; the Taylor series used instead have a
// truncation error O(θ⁶) < 1e-30 relative.
constexpr double kSmallAngle = 1e-5;

// Coefficients of hat(ω) and hat(ω)² in the SO3 Jacobians, as functions of θ² = |ω|².
// a = (1 − cos θ)/θ², b = (θ − sin θ)/θ³, c = 1/θ² − (1 + cos θ)/(2 θ sin θ).
template <typename Scalar>
void jacobian_coefficients(const Scalar& theta2, Scalar& a, Scalar& b, Scalar& c) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  // The closed forms cancel for small θ (c loses ~log10(1/θ²) digits), so below θ = 1e-2 use
  // series whose first omitted term is O(θ⁸) < 1e-22.
  if (value_of(theta2) < 1e-4) {
    const Scalar t4 = theta2 * theta2;
    const Scalar t6 = t4 * theta2;
    a = 0.5 - theta2 / 24.0 + t4 / 720.0 - t6 / 40320.0;
    b = 1.0 / 6.0 - theta2 / 120.0 + t4 / 5040.0 - t6 / 362880.0;
    c = 1.0 / 12.0 + theta2 / 720.0 + t4 / 30240.0 + t6 / 1209600.0;
    return;
  }
  const Scalar theta = sqrt(theta2);
  const Scalar s = sin(theta);
  const Scalar co = cos(theta);
  a = (1.0 - co) / theta2;
  b = (theta - s) / (theta2 * theta);
  c = 1.0 / theta2 - (1.0 + co) / (2.0 * theta * s);
}

// rigid::Error "<function>(): rotation vector [..] has a non-finite component" or "... is too
// long: ..." for a rotation vector refused by exp (out of line: the exp path stays small).
[[noreturn, gnu::cold, gnu::noinline]] void refuse_rotation_vector(const char* function,
                                                                  const Eigen::Vector3d& w) {
  if (!w.allFinite()) {
    detail::throw_error(function, fmt::format("rotation vector {} has a non-finite component",
                                              to_string(w.transpose())));
  }
  detail::throw_error(
      function,
      fmt::format("rotation vector {} is too long: angle |ω| = {:.6g} rad, expected at most "
                  "kMaxAngle = {:.0e} rad (beyond, rounding has lost the fraction of a turn)",
                  to_string(w.transpose()), w.stableNorm(), kMaxAngle));
}

template <typename Vector3>
Eigen::Vector3d values_of(const Vector3& v) {
  return {value_of(v(0)), value_of(v(1)), value_of(v(2))};
}

}  // namespace

template <typename Scalar>
SO3<Scalar> SO3<Scalar>::from_quaternion(const Scalar& w, const Scalar& x, const Scalar& y,
                                         const Scalar& z) {
  using std::sqrt;
  RIGID_REQUIRE(std::isfinite(value_of(w)) && std::isfinite(value_of(x)) &&
                    std::isfinite(value_of(y)) && std::isfinite(value_of(z)),
                "quaternion (w, x, y, z) = ({}, {}, {}, {}) has a non-finite component",
                value_of(w), value_of(x), value_of(y), value_of(z));
  const Scalar n = sqrt(w * w + x * x + y * y + z * z);
  RIGID_REQUIRE(value_of(n) >= 1e-12,
                "quaternion (w, x, y, z) = ({}, {}, {}, {}) has norm {}, expected a nonzero "
                "quaternion (norm >= 1e-12)",
                value_of(w), value_of(x), value_of(y), value_of(z), value_of(n));
  return SO3(w / n, x / n, y / n, z / n);
}

template <typename Scalar>
SO3<Scalar> SO3<Scalar>::from_unit_quaternion(const Scalar& w, const Scalar& x, const Scalar& y,
                                              const Scalar& z) {
  RIGID_ASSERT(std::abs(value_of(w * w + x * x + y * y + z * z) - 1.0) <= 1e-12);
  return SO3(w, x, y, z);
}

template <typename Scalar>
SO3<Scalar> SO3<Scalar>::from_unit_quaternion(const Scalar& w, const Scalar& x, const Scalar& y,
                                              const Scalar& z, double tolerance) {
  const double n = std::sqrt(value_of(w * w + x * x + y * y + z * z));
  RIGID_REQUIRE(std::isfinite(n) && std::abs(n - 1.0) <= tolerance,
                "quaternion (w, x, y, z) = ({}, {}, {}, {}) has norm {}; expected a unit quaternion "
                "(norm within {} of 1)",
                value_of(w), value_of(x), value_of(y), value_of(z), n, tolerance);
  return from_quaternion(w, x, y, z);
}

template <typename Scalar>
SO3<Scalar> SO3<Scalar>::from_matrix(const Matrix3& R, double tol) {
  using std::sqrt;
  Eigen::Matrix3d Rd;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Rd(i, j) = value_of(R(i, j));
  RIGID_REQUIRE(Rd.allFinite(), "matrix {} has a non-finite entry", to_string(Rd));
  const double defect = (Rd.transpose() * Rd - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = Rd.determinant();
  RIGID_REQUIRE(defect <= tol && det > 0.0,
                "matrix {} is not a rotation: orthonormality defect max|RᵀR − I| = {:.3g} "
                "(tolerance {:.3g}), determinant {:.17g} (expected +1)",
                to_string(Rd), defect, tol, det);
  // [Shepperd1978]: take the square root of the largest of 4w², 4x², 4y², 4z².
  const Scalar tr = R(0, 0) + R(1, 1) + R(2, 2);
  const double trd = value_of(tr);
  int k = -1;
  double best = trd;
  for (int i = 0; i < 3; ++i) {
    if (Rd(i, i) > best) {
      best = Rd(i, i);
      k = i;
    }
  }
  Scalar w, x, y, z;
  if (k < 0) {
    const Scalar s = 2.0 * sqrt(1.0 + tr);  // s = 4w
    w = 0.25 * s;
    x = (R(2, 1) - R(1, 2)) / s;
    y = (R(0, 2) - R(2, 0)) / s;
    z = (R(1, 0) - R(0, 1)) / s;
  } else if (k == 0) {
    const Scalar s = 2.0 * sqrt(1.0 + R(0, 0) - R(1, 1) - R(2, 2));  // s = 4x
    w = (R(2, 1) - R(1, 2)) / s;
    x = 0.25 * s;
    y = (R(0, 1) + R(1, 0)) / s;
    z = (R(0, 2) + R(2, 0)) / s;
  } else if (k == 1) {
    const Scalar s = 2.0 * sqrt(1.0 - R(0, 0) + R(1, 1) - R(2, 2));  // s = 4y
    w = (R(0, 2) - R(2, 0)) / s;
    x = (R(0, 1) + R(1, 0)) / s;
    y = 0.25 * s;
    z = (R(1, 2) + R(2, 1)) / s;
  } else {
    const Scalar s = 2.0 * sqrt(1.0 - R(0, 0) - R(1, 1) + R(2, 2));  // s = 4z
    w = (R(1, 0) - R(0, 1)) / s;
    x = (R(0, 2) + R(2, 0)) / s;
    y = (R(1, 2) + R(2, 1)) / s;
    z = 0.25 * s;
  }
  const Scalar n = sqrt(w * w + x * x + y * y + z * z);
  return SO3(w / n, x / n, y / n, z / n);
}

template <typename Scalar>
SO3<Scalar> SO3<Scalar>::from_axis_angle(const Vector3& axis, const Scalar& angle) {
  using std::sqrt;
  const Eigen::Vector3d a(value_of(axis(0)), value_of(axis(1)), value_of(axis(2)));
  RIGID_REQUIRE(a.allFinite(), "axis {} has a non-finite component", to_string(a.transpose()));
  RIGID_REQUIRE(std::isfinite(value_of(angle)), "angle {} is not finite", value_of(angle));
  RIGID_REQUIRE(std::abs(value_of(angle)) <= kMaxAngle,
                "angle {} rad is too large: expected |angle| <= kMaxAngle = {:.0e} rad (beyond, "
                "rounding has lost the fraction of a turn)",
                value_of(angle), kMaxAngle);
  RIGID_REQUIRE(a.norm() > 1e-12, "axis {} has norm {}, expected a nonzero axis (norm > 1e-12)",
                to_string(a.transpose()), a.norm());
  const Scalar n = sqrt(axis.squaredNorm());
  return exp(axis * (angle / n));
}

template <typename Scalar>
SO3<Scalar> SO3<Scalar>::exp(const Vector3& omega) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Scalar theta2 = omega.squaredNorm();
  Scalar w, k;  // q = (cos θ/2, k ω), k = sin(θ/2)/θ
  if (value_of(theta2) < kSmallAngle * kSmallAngle) {
    // cos(θ/2) = 1 − θ²/8 + θ⁴/384 …, sin(θ/2)/θ = 1/2 − θ²/48 + θ⁴/3840 …
    w = 1.0 - theta2 / 8.0;
    k = 0.5 - theta2 / 48.0;
  } else {
    // (also false for NaN: a non-finite ω, or one whose |ω|² overflows)
    if (!(value_of(theta2) <= kMaxAngle * kMaxAngle)) [[unlikely]]
      refuse_rotation_vector("SO3::exp", values_of(omega));
    const Scalar theta = sqrt(theta2);
    w = cos(0.5 * theta);
    k = sin(0.5 * theta) / theta;
  }
  SO3 r(w, k * omega(0), k * omega(1), k * omega(2));
  if (value_of(theta2) < kSmallAngle * kSmallAngle) {
    // Truncated series leaves |q| − 1 = O(θ⁶): renormalise to keep the invariant exact.
    const Scalar n = sqrt(r.q_.squaredNorm());
    r.q_ /= n;
  }
  return r;
}

template <typename Scalar>
typename SO3<Scalar>::Vector3 SO3<Scalar>::log() const {
  using std::atan2;
  using std::sqrt;
  RIGID_REQUIRE_AS("SO3::log", !std::isnan(value_of(q_(0))),
                   "the rotation is SO3::invalid() (the NaN marker of a diverged computation), "
                   "expected a valid rotation");
  // Use the representative with w ≥ 0 so that the angle lies in [0, π].
  const Scalar sign = value_of(q_(0)) < 0.0 ? Scalar(-1.0) : Scalar(1.0);
  const Scalar w = sign * q_(0);
  const Vector3 v = sign * q_.template tail<3>();
  const Scalar n2 = v.squaredNorm();
  Scalar k;  // ω = k v, k = 2 atan2(|v|, w)/|v|
  if (value_of(n2) < kSmallAngle * kSmallAngle) {
    // 2 atan(n/w)/n = 2/w (1 − n²/(3w²) + n⁴/(5w⁴) …); here w ≈ 1.
    k = 2.0 / w * (1.0 - n2 / (3.0 * w * w));
  } else {
    const Scalar n = sqrt(n2);
    // atan2 keeps full relative accuracy near θ = π, where w → 0 (acos(w) would not).
    k = 2.0 * atan2(n, w) / n;
  }
  return k * v;
}

template <typename Scalar>
Scalar SO3<Scalar>::angle() const {
  using std::abs;
  using std::atan2;
  using std::sqrt;
  RIGID_REQUIRE_AS("SO3::angle", !std::isnan(value_of(q_(0))),
                   "the rotation is SO3::invalid() (the NaN marker of a diverged computation), "
                   "expected a valid rotation");
  const Scalar n = sqrt(q_.template tail<3>().squaredNorm());
  return 2.0 * atan2(n, abs(q_(0)));
}

template <typename Scalar>
SO3<Scalar> SO3<Scalar>::interpolate(const SO3& b, const Scalar& s) const {
  detail::require_finite_fraction("SO3::interpolate", value_of(s));
  const Vector3 omega = s * (inverse() * b).log();
  const Eigen::Vector3d w = values_of(omega);
  detail::require_interpolated_turn("SO3::interpolate", value_of(s), w.cwiseAbs().maxCoeff(),
                                    w.stableNorm());
  return *this * exp(omega);
}

template <typename Scalar>
typename SO3<Scalar>::Matrix3 SO3<Scalar>::matrix() const {
  const Scalar &w = q_(0), &x = q_(1), &y = q_(2), &z = q_(3);
  const Scalar xx = x * x, yy = y * y, zz = z * z;
  const Scalar xy = x * y, xz = x * z, yz = y * z, wx = w * x, wy = w * y, wz = w * z;
  Matrix3 R;
  R << 1.0 - 2.0 * (yy + zz), 2.0 * (xy - wz), 2.0 * (xz + wy),  //
      2.0 * (xy + wz), 1.0 - 2.0 * (xx + zz), 2.0 * (yz - wx),   //
      2.0 * (xz - wy), 2.0 * (yz + wx), 1.0 - 2.0 * (xx + yy);
  return R;
}

template <typename Scalar>
Eigen::Matrix<Scalar, 4, 4> SO3<Scalar>::homogeneous() const {
  Eigen::Matrix<Scalar, 4, 4> T = Eigen::Matrix<Scalar, 4, 4>::Identity();
  T.template topLeftCorner<3, 3>() = matrix();
  return T;
}

template <typename Scalar>
typename SO3<Scalar>::Matrix3 SO3<Scalar>::right_jacobian(const Vector3& omega) {
  Scalar a, b, c;
  jacobian_coefficients(Scalar(omega.squaredNorm()), a, b, c);
  const Matrix3 W = hat(omega);
  return Matrix3::Identity() - a * W + b * (W * W);
}

template <typename Scalar>
typename SO3<Scalar>::Matrix3 SO3<Scalar>::right_jacobian_inverse(const Vector3& omega) {
  Scalar a, b, c;
  jacobian_coefficients(Scalar(omega.squaredNorm()), a, b, c);
  const Matrix3 W = hat(omega);
  return Matrix3::Identity() + 0.5 * W + c * (W * W);
}

template <typename Scalar>
typename SO3<Scalar>::Matrix3 SO3<Scalar>::left_jacobian(const Vector3& omega) {
  return right_jacobian(-omega);
}

template <typename Scalar>
typename SO3<Scalar>::Matrix3 SO3<Scalar>::left_jacobian_inverse(const Vector3& omega) {
  return right_jacobian_inverse(-omega);
}

template <typename Scalar>
SO3<Scalar> SO3<Scalar>::sample(std::mt19937_64& rng) {
  // A standard normal 4-vector has a rotation-invariant density, so its direction is uniform
  // on S³, whose image in SO(3) is the Haar measure.
  std::normal_distribution<double> normal(0.0, 1.0);
  for (;;) {
    const Eigen::Vector4d g(normal(rng), normal(rng), normal(rng), normal(rng));
    const double n = g.norm();
    if (n > 1e-6) return SO3(Scalar(g(0) / n), Scalar(g(1) / n), Scalar(g(2) / n), Scalar(g(3) / n));
  }
}

template <typename Scalar>
bool SO3<Scalar>::is_approx(const SO3& b, double tol) const {
  return value_of((inverse() * b).angle()) <= tol;
}

template class SO3<double>;
template class SO3<AutoDiffXd>;

}  // namespace rigid
