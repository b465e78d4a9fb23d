#include "rigid/lie/so2.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/LU>  // determinant

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "lie/detail/interpolation.hpp"
#include "lie/detail/value_of.hpp"

namespace rigid {

using detail::value_of;

template <typename Scalar>
SO2<Scalar> SO2<Scalar>::from_angle_unchecked(const Scalar& theta) {
  using std::cos;
  using std::sin;
  // cos and sin are correctly rounded to within an ulp, so c² + s² = 1 to a few ulps.
  return SO2(cos(theta), sin(theta));
}

template <typename Scalar>
SO2<Scalar> SO2<Scalar>::from_angle(const Scalar& theta) {
  RIGID_REQUIRE(std::isfinite(value_of(theta)), "angle {} is not finite", value_of(theta));
  RIGID_REQUIRE(std::abs(value_of(theta)) <= kMaxAngle,
                "angle {} rad is too large: expected |angle| <= kMaxAngle = {:.0e} rad (beyond, "
                "rounding has lost the fraction of a turn)",
                value_of(theta), kMaxAngle);
  return from_angle_unchecked(theta);
}

template <typename Scalar>
SO2<Scalar> SO2<Scalar>::interpolate(const SO2& b, const Scalar& s) const {
  detail::require_finite_fraction("SO2::interpolate", value_of(s));
  const Scalar theta = s * (inverse() * b).angle();
  detail::require_interpolated_turn("SO2::interpolate", value_of(s), std::abs(value_of(theta)),
                                    std::abs(value_of(theta)));
  return *this * from_angle_unchecked(theta);
}

template <typename Scalar>
SO2<Scalar> SO2<Scalar>::from_complex(const Scalar& c, const Scalar& s) {
  using std::sqrt;
  RIGID_REQUIRE(std::isfinite(value_of(c)) && std::isfinite(value_of(s)),
                "complex number (c, s) = ({}, {}) has a non-finite component", value_of(c),
                value_of(s));
  const Scalar n = sqrt(c * c + s * s);
  RIGID_REQUIRE(value_of(n) >= 1e-12,
                "complex number (c, s) = ({}, {}) has norm {}, expected a nonzero number "
                "(norm >= 1e-12)",
                value_of(c), value_of(s), value_of(n));
  return SO2(c / n, s / n);
}

template <typename Scalar>
SO2<Scalar> SO2<Scalar>::from_matrix(const Matrix2& R, double tol) {
  Eigen::Matrix2d Rd;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) Rd(i, j) = value_of(R(i, j));
  RIGID_REQUIRE(Rd.allFinite(), "matrix {} has a non-finite entry", to_string(Rd));
  const double defect = (Rd.transpose() * Rd - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff();
  const double det = Rd.determinant();
  RIGID_REQUIRE(defect <= tol && det > 0.0,
                "matrix {} is not a rotation: orthonormality defect max|RᵀR − I| = {:.3g} "
                "(tolerance {:.3g}), determinant {:.17g} (expected +1)",
                to_string(Rd), defect, tol, det);
  // Average the two copies of (c, s) in [[c, −s], [s, c]], then normalise: the closest
  // unit complex number to the matrix in the Frobenius norm.
  return from_complex(0.5 * (R(0, 0) + R(1, 1)), 0.5 * (R(1, 0) - R(0, 1)));
}

template <typename Scalar>
SO2<Scalar> SO2<Scalar>::sample(std::mt19937_64& rng) {
  // The Haar measure of SO(2) is dθ / 2π.
  std::uniform_real_distribution<double> u(-std::numbers::pi, std::numbers::pi);
  return from_angle_unchecked(Scalar(u(rng)));
}

template <typename Scalar>
Scalar SO2<Scalar>::angle() const {
  using std::atan2;
  // atan2 is accurate over the whole circle, including θ → 0 (relative) and θ → ±π.
  return atan2(s_, c_);
}

template <typename Scalar>
bool SO2<Scalar>::is_approx(const SO2& b, double tol) const {
  using std::abs;
  return abs(value_of((inverse() * b).angle())) <= tol;
}

template class SO2<double>;
template class SO2<AutoDiffXd>;

}  // namespace rigid
