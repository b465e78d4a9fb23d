#include "rigid/lie/se3.hpp"

#include <cmath>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "lie/detail/interpolation.hpp"
#include "lie/detail/value_of.hpp"

namespace rigid {

namespace {

using detail::value_of;

}  // namespace

template <typename Scalar>
SE3<Scalar> SE3<Scalar>::from_matrix(const Matrix4& T, double tol) {
  Eigen::Vector4d last;
  for (int j = 0; j < 4; ++j) last(j) = value_of(T(3, j));
  RIGID_REQUIRE(last == Eigen::Vector4d(0, 0, 0, 1),
                "last row of the homogeneous matrix is {}, expected [0, 0, 0, 1]", to_string(last.transpose()));
  const Vector3 t = T.template topRightCorner<3, 1>();
  const Eigen::Vector3d td(value_of(t(0)), value_of(t(1)), value_of(t(2)));
  RIGID_REQUIRE(td.allFinite(), "translation {} has a non-finite component", to_string(td.transpose()));
  return SE3(SO3<Scalar>::from_matrix(T.template topLeftCorner<3, 3>(), tol), t);
}

template <typename Scalar>
SE3<Scalar> SE3<Scalar>::exp(const Vector6& xi) {
  Eigen::Matrix<double, 6, 1> xd;
  for (int i = 0; i < 6; ++i) xd(i) = value_of(xi(i));
  RIGID_REQUIRE_AS("SE3::exp", xd.allFinite(), "tangent vector {} has a non-finite component",
                   to_string(xd.transpose()));
  const Vector3 rho = xi.template head<3>();
  const Vector3 omega = xi.template tail<3>();
  return SE3(SO3<Scalar>::exp(omega), SO3<Scalar>::left_jacobian(omega) * rho);
}

template <typename Scalar>
SE3<Scalar> SE3<Scalar>::interpolate(const SE3& b, const Scalar& s) const {
  detail::require_finite_fraction("SE3::interpolate", value_of(s));
  const Vector6 xi = s * (inverse() * b).log();
  Eigen::Matrix<double, 6, 1> xd;
  for (int i = 0; i < 6; ++i) xd(i) = value_of(xi(i));
  detail::require_interpolated_turn("SE3::interpolate", value_of(s), xd.cwiseAbs().maxCoeff(),
                                    xd.tail<3>().stableNorm());
  return *this * exp(xi);
}

template <typename Scalar>
typename SE3<Scalar>::Vector6 SE3<Scalar>::log() const {
  const Vector3 omega = R_.log();
  Vector6 xi;
  xi.template head<3>() = SO3<Scalar>::left_jacobian_inverse(omega) * t_;
  xi.template tail<3>() = omega;
  return xi;
}

template <typename Scalar>
typename SE3<Scalar>::Matrix4 SE3<Scalar>::hat(const Vector6& xi) {
  Matrix4 m = Matrix4::Zero();
  m.template topLeftCorner<3, 3>() = SO3<Scalar>::hat(xi.template tail<3>());
  m.template topRightCorner<3, 1>() = xi.template head<3>();
  return m;
}

template <typename Scalar>
typename SE3<Scalar>::Vector6 SE3<Scalar>::vee(const Matrix4& m) {
  Vector6 xi;
  xi.template head<3>() = m.template topRightCorner<3, 1>();
  xi.template tail<3>() = SO3<Scalar>::vee(m.template topLeftCorner<3, 3>());
  return xi;
}

template <typename Scalar>
typename SE3<Scalar>::Matrix4 SE3<Scalar>::matrix() const {
  Matrix4 T = Matrix4::Identity();
  T.template topLeftCorner<3, 3>() = R_.matrix();
  T.template topRightCorner<3, 1>() = t_;
  return T;
}

template <typename Scalar>
typename SE3<Scalar>::Matrix6 SE3<Scalar>::adjoint() const {
  const Matrix3 R = R_.matrix();
  Matrix6 A = Matrix6::Zero();
  A.template topLeftCorner<3, 3>() = R;
  A.template topRightCorner<3, 3>() = SO3<Scalar>::hat(t_) * R;
  A.template bottomRightCorner<3, 3>() = R;
  return A;
}

namespace {

// Barfoot's Q(ρ, ω), the top-right block of Jl(ξ).
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 3> barfoot_q(const Eigen::Matrix<Scalar, 6, 1>& xi) {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Vector3 rho = xi.template head<3>();
  const Vector3 omega = xi.template tail<3>();
  const Matrix3 P = SO3<Scalar>::hat(rho);
  const Matrix3 W = SO3<Scalar>::hat(omega);
  const Scalar t2 = omega.squaredNorm();
  Scalar c1, c2, c3;
  if (value_of(t2) < 1e-2) {
    // Below θ = 0.1 the closed forms cancel badly (c3 loses ~9 digits at θ = 0.01); the
    // series below omit terms O(θ⁸) < 1e-16 relative.
    // c1 = (θ − sin θ)/θ³ = 1/6 − θ²/120 + θ⁴/5040 − θ⁶/362880 …
    // c2 = (θ² + 2 cos θ − 2)/(2 θ⁴) = 1/24 − θ²/720 + θ⁴/40320 − θ⁶/3628800 …
    // c3 = (2θ − 3 sin θ + θ cos θ)/(2 θ⁵) = 1/120 − θ²/2520 + θ⁴/120960 − θ⁶/9979200 …
    const Scalar t4 = t2 * t2;
    const Scalar t6 = t4 * t2;
    c1 = 1.0 / 6.0 - t2 / 120.0 + t4 / 5040.0 - t6 / 362880.0;
    c2 = 1.0 / 24.0 - t2 / 720.0 + t4 / 40320.0 - t6 / 3628800.0;
    c3 = 1.0 / 120.0 - t2 / 2520.0 + t4 / 120960.0 - t6 / 9979200.0;
  } else {
    const Scalar t = sqrt(t2);
    const Scalar s = sin(t), c = cos(t);
    c1 = (t - s) / (t2 * t);
    c2 = (t2 + 2.0 * c - 2.0) / (2.0 * t2 * t2);
    c3 = (2.0 * t - 3.0 * s + t * c) / (2.0 * t2 * t2 * t);
  }
  // Q = ½P + c1 (WP + PW + WPW) + c2 (W²P + PW² − 3WPW) + c3 (WPW² + W²PW)
  const Matrix3 WP = W * P, PW = P * W, WPW = W * P * W;
  return 0.5 * P + c1 * (WP + PW + WPW) + c2 * (W * WP + PW * W - 3.0 * WPW) +
         c3 * (WPW * W + W * WPW);
}

}  // namespace

// Jl(ξ) = [[Jl(ω), Q(ρ, ω)], [0, Jl(ω)]] with Q the closed form of [Barfoot2017] (the matrix
// Q), written as a function of θ = |ω|.
template <typename Scalar>
typename SE3<Scalar>::Matrix6 SE3<Scalar>::left_jacobian(const Vector6& xi) {
  const Matrix3 Q = barfoot_q<Scalar>(xi);
  const Matrix3 Jl = SO3<Scalar>::left_jacobian(xi.template tail<3>());
  Matrix6 J = Matrix6::Zero();
  J.template topLeftCorner<3, 3>() = Jl;
  J.template topRightCorner<3, 3>() = Q;
  J.template bottomRightCorner<3, 3>() = Jl;
  return J;
}

// Block inverse of [[A, Q], [0, A]]: [[A⁻¹, −A⁻¹ Q A⁻¹], [0, A⁻¹]], with A⁻¹ = Jl(ω)⁻¹ in
// closed form [Barfoot2017, §7.1.5], [Sola2018, App. D]: no 6×6 factorisation.
template <typename Scalar>
typename SE3<Scalar>::Matrix6 SE3<Scalar>::left_jacobian_inverse(const Vector6& xi) {
  const Matrix3 Q = barfoot_q<Scalar>(xi);
  const Matrix3 Ai = SO3<Scalar>::left_jacobian_inverse(xi.template tail<3>());
  Matrix6 J = Matrix6::Zero();
  J.template topLeftCorner<3, 3>() = Ai;
  J.template topRightCorner<3, 3>() = -(Ai * Q * Ai);
  J.template bottomRightCorner<3, 3>() = Ai;
  return J;
}

template <typename Scalar>
typename SE3<Scalar>::Matrix6 SE3<Scalar>::right_jacobian(const Vector6& xi) {
  return left_jacobian(-xi);
}

template <typename Scalar>
SE3<Scalar> SE3<Scalar>::sample(std::mt19937_64& rng, double half_extent) {
  std::uniform_real_distribution<double> u(-half_extent, half_extent);
  const SO3<Scalar> R = SO3<Scalar>::sample(rng);
  const double x = u(rng), y = u(rng), z = u(rng);
  return SE3(R, Vector3(Scalar(x), Scalar(y), Scalar(z)));
}

template class SE3<double>;
template class SE3<AutoDiffXd>;

}  // namespace rigid
