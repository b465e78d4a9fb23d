#include "rigid/lie/se2.hpp"

#include <cmath>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "lie/detail/interpolation.hpp"
#include "lie/detail/value_of.hpp"

namespace rigid {

namespace {

using detail::value_of;

// Coefficients of SE(2)'s exp and Jacobians as functions of θ:
//   a  = sin θ / θ,          b  = (1 − cos θ)/θ        (V = a I + b J)
//   c1 = (θ − sin θ)/θ²,     c2 = (1 − cos θ)/θ²       (Jacobian column)
//   A  = (θ/2) cot(θ/2) = θ sin θ / (2 (1 − cos θ))    (V⁻¹ = [[A, θ/2], [−θ/2, A]])
// Below |θ| = 1e-2 the quotients cancel, so Taylor series are used whose first omitted term
// is O(θ⁸) < 1e-16 relative.
template <typename Scalar>
struct Coefficients {
  Scalar a, b, c1, c2, A;
};

template <typename Scalar>
Coefficients<Scalar> coefficients(const Scalar& theta) {
  using std::cos;
  using std::sin;
  Coefficients<Scalar> k;
  const Scalar t2 = theta * theta;
  if (value_of(t2) < 1e-4) {
    const Scalar t4 = t2 * t2;
    const Scalar t6 = t4 * t2;
    k.a = 1.0 - t2 / 6.0 + t4 / 120.0 - t6 / 5040.0;
    k.c2 = 0.5 - t2 / 24.0 + t4 / 720.0 - t6 / 40320.0;
    k.b = theta * k.c2;
    k.c1 = theta * (1.0 / 6.0 - t2 / 120.0 + t4 / 5040.0 - t6 / 362880.0);
    k.A = 1.0 - t2 / 12.0 - t4 / 720.0 - t6 / 30240.0;
    return k;
  }
  const Scalar s = sin(theta), c = cos(theta);
  k.a = s / theta;
  k.b = (1.0 - c) / theta;
  k.c1 = (theta - s) / t2;
  k.c2 = (1.0 - c) / t2;
  // 1 − cos θ > 0 here (|θ| ≤ π after log, and θ ≠ 0 on this branch); at θ = ±π, A = 0.
  k.A = theta * s / (2.0 * (1.0 - c));
  return k;
}

}  // namespace

template <typename Scalar>
SE2<Scalar> SE2<Scalar>::from_matrix(const Matrix3& T, double tol) {
  Eigen::Vector3d last(value_of(T(2, 0)), value_of(T(2, 1)), value_of(T(2, 2)));
  RIGID_REQUIRE(last == Eigen::Vector3d(0, 0, 1),
                "last row of the homogeneous matrix is {}, expected [0, 0, 1]",
                to_string(last.transpose()));
  const Vector2 t = T.template topRightCorner<2, 1>();
  const Eigen::Vector2d td(value_of(t(0)), value_of(t(1)));
  RIGID_REQUIRE(td.allFinite(), "translation {} has a non-finite component",
                to_string(td.transpose()));
  return SE2(SO2<Scalar>::from_matrix(T.template topLeftCorner<2, 2>(), tol), t);
}

template <typename Scalar>
SE2<Scalar> SE2<Scalar>::exp(const Tangent& xi) {
  const Eigen::Vector3d xd(value_of(xi(0)), value_of(xi(1)), value_of(xi(2)));
  RIGID_REQUIRE_AS("SE2::exp", xd.allFinite(), "tangent vector {} has a non-finite component",
                   to_string(xd.transpose()));
  const Coefficients<Scalar> k = coefficients(xi(2));
  // V ρ with V = [[a, −b], [b, a]].
  const Vector2 t(k.a * xi(0) - k.b * xi(1), k.b * xi(0) + k.a * xi(1));
  return SE2(SO2<Scalar>::exp(typename SO2<Scalar>::Tangent(xi(2))), t);
}

template <typename Scalar>
SE2<Scalar> SE2<Scalar>::interpolate(const SE2& b, const Scalar& s) const {
  detail::require_finite_fraction("SE2::interpolate", value_of(s));
  const Tangent xi = s * (inverse() * b).log();
  const Eigen::Vector3d xd(value_of(xi(0)), value_of(xi(1)), value_of(xi(2)));
  detail::require_interpolated_turn("SE2::interpolate", value_of(s), xd.cwiseAbs().maxCoeff(),
                                    std::abs(xd(2)));
  return *this * exp(xi);
}

template <typename Scalar>
typename SE2<Scalar>::Tangent SE2<Scalar>::log() const {
  const Scalar theta = R_.angle();
  const Coefficients<Scalar> k = coefficients(theta);
  const Scalar h = 0.5 * theta;
  // ρ = V⁻¹ t with V⁻¹ = [[A, θ/2], [−θ/2, A]] (V = a I + b J, a² + b² = 4 sin²(θ/2)/θ²).
  return Tangent(k.A * t_(0) + h * t_(1), -h * t_(0) + k.A * t_(1), theta);
}

// Left Jacobian: a left perturbation exp(ε) X = (e^{iε_θ} R, p + ε_ρ + ε_θ J p) to first
// order, with p = V(θ) ρ. Differentiating exp(ξ + δ) = (R(θ + δθ), V ρ + V δρ + V'(θ) ρ δθ)
// and matching gives ε_θ = δθ and ε_ρ = V δρ + (V' − J V) ρ δθ, and
// V' − J V = (a' + b) I + (b' − a) J = c1 I − c2 J.
template <typename Scalar>
typename SE2<Scalar>::Matrix3 SE2<Scalar>::left_jacobian(const Tangent& xi) {
  const Coefficients<Scalar> k = coefficients(xi(2));
  Matrix3 J = Matrix3::Identity();
  J(0, 0) = k.a;
  J(0, 1) = -k.b;
  J(1, 0) = k.b;
  J(1, 1) = k.a;
  // c1 ρ − c2 J ρ with J ρ = (−ρy, ρx).
  J(0, 2) = k.c1 * xi(0) + k.c2 * xi(1);
  J(1, 2) = k.c1 * xi(1) - k.c2 * xi(0);
  return J;
}

template <typename Scalar>
typename SE2<Scalar>::Matrix3 SE2<Scalar>::left_jacobian_inverse(const Tangent& xi) {
  const Coefficients<Scalar> k = coefficients(xi(2));
  const Scalar h = 0.5 * xi(2);
  // Block inverse of [[V, w], [0, 1]]: [[V⁻¹, −V⁻¹ w], [0, 1]].
  Matrix2 Vi;
  Vi << k.A, h, -h, k.A;
  const Vector2 w(k.c1 * xi(0) + k.c2 * xi(1), k.c1 * xi(1) - k.c2 * xi(0));
  Matrix3 J = Matrix3::Identity();
  J.template topLeftCorner<2, 2>() = Vi;
  J.template topRightCorner<2, 1>() = -(Vi * w);
  return J;
}

template <typename Scalar>
SE2<Scalar> SE2<Scalar>::sample(std::mt19937_64& rng, double half_extent) {
  std::uniform_real_distribution<double> u(-half_extent, half_extent);
  const SO2<Scalar> R = SO2<Scalar>::sample(rng);
  const double x = u(rng), y = u(rng);
  return SE2(R, Vector2(Scalar(x), Scalar(y)));
}

template class SE2<double>;
template class SE2<AutoDiffXd>;

}  // namespace rigid
