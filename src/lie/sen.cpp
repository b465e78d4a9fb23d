#include "rigid/lie/sen.hpp"

#include <cmath>

#include <Eigen/LU>
#include <unsupported/Eigen/MatrixFunctions>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "lie/detail/interpolation.hpp"
#include "lie/detail/phi.hpp"

namespace rigid {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

SEn::SEn(const SOn& R, const VectorXd& t) : R_(R), t_(t) {
  RIGID_REQUIRE(t.size() == R.n(), "translation has {} components, expected {} for SE({})", t.size(),
                R.n(), R.n());
  RIGID_REQUIRE(t.allFinite(), "translation {} has a non-finite component", to_string(t.transpose()));
}

int SEn::n_from_dimension(Index m) {
  // n(n+1)/2 = m ⇔ n = (√(1 + 8m) − 1)/2; round, then check exactly in integers.
  const int n = static_cast<int>(std::lround(0.5 * (std::sqrt(1.0 + 8.0 * static_cast<double>(m)) - 1.0)));
  RIGID_REQUIRE(n >= 2 && n * (n + 1) / 2 == m,
                "tangent vector has {} components, expected n(n+1)/2 for some n ≥ 2 (3, 6, 10, …)", m);
  return n;
}

SEn SEn::identity(int n) { return SEn(SOn::identity(n), VectorXd::Zero(n), true); }

SEn SEn::from_matrix(const MatrixXd& T, double tol) {
  RIGID_REQUIRE(T.rows() == T.cols() && T.rows() >= 3,
                "matrix is {}x{}, expected a square homogeneous matrix of size n + 1 ≥ 3", T.rows(),
                T.cols());
  const Index n = T.rows() - 1;
  VectorXd expected = VectorXd::Zero(n + 1);
  expected(n) = 1.0;
  const VectorXd last = T.row(n).transpose();
  RIGID_REQUIRE(last == expected, "last row of the homogeneous matrix is {}, expected {}",
                to_string(last.transpose()), to_string(expected.transpose()));
  return SEn(SOn::from_matrix(T.topLeftCorner(n, n), tol), T.topRightCorner(n, 1));
}

MatrixXd SEn::hat(const Tangent& xi) {
  const int n = n_from_dimension(xi.size());
  MatrixXd m = MatrixXd::Zero(n + 1, n + 1);
  m.topLeftCorner(n, n) = SOn::hat(xi.tail(xi.size() - n));
  m.topRightCorner(n, 1) = xi.head(n);
  return m;
}

SEn::Tangent SEn::vee(const MatrixXd& m, double tol) {
  RIGID_REQUIRE(m.rows() == m.cols() && m.rows() >= 3,
                "matrix is {}x{}, expected a square matrix of size n + 1 ≥ 3", m.rows(), m.cols());
  const Index n = m.rows() - 1;
  RIGID_REQUIRE(m.row(n).cwiseAbs().maxCoeff() <= tol,
                "last row {} of the se(n) matrix is not zero (tolerance {:.3g})", to_string(m.row(n)), tol);
  Tangent xi(n * (n + 1) / 2);
  xi.head(n) = m.topRightCorner(n, 1);
  xi.tail(n * (n - 1) / 2) = SOn::vee(m.topLeftCorner(n, n), tol);
  return xi;
}

SEn SEn::exp(const Tangent& xi) {
  RIGID_REQUIRE(xi.allFinite(), "tangent vector {} has a non-finite component", to_string(xi.transpose()));
  const int n = n_from_dimension(xi.size());
  // exp([[W, ρ], [0, 0]]) = [[e^W, φ(W) ρ], [0, 1]]; the rotation is taken from SOn::exp so
  // that SEn and SOn agree exactly on pure rotations.
  const MatrixXd E = hat(xi).exp();
  return SEn(SOn::exp(xi.tail(xi.size() - n)), E.topRightCorner(n, 1), true);
}

SEn::Tangent SEn::log() const {
  const int n = R_.n();
  const VectorXd omega = R_.log();
  // t = φ(W) ρ; φ(W) is invertible while every angle is below 2π (its eigenvalues are
  // (e^{iθ} − 1)/(iθ) and 1).
  const MatrixXd V = detail::phi(SOn::hat(omega));
  Tangent xi(dimension_of(n));
  xi.head(n) = V.partialPivLu().solve(t_);
  xi.tail(omega.size()) = omega;
  return xi;
}

MatrixXd SEn::matrix() const {
  const int n = R_.n();
  MatrixXd T = MatrixXd::Identity(n + 1, n + 1);
  T.topLeftCorner(n, n) = R_.matrix();
  T.topRightCorner(n, 1) = t_;
  return T;
}

// X hat(ξ) X⁻¹ = [[R W Rᵀ, R ρ − R W Rᵀ t], [0, 0]]: ω' = Ad_R ω, ρ' = R ρ − hat(ω') t.
MatrixXd SEn::adjoint() const {
  const int n = R_.n();
  const int m = SOn::dimension_of(n);
  const MatrixXd AdR = R_.adjoint();
  MatrixXd Mt(n, m);  // Mt ω = hat(ω) t
  for (Index k = 0; k < m; ++k) Mt.col(k) = SOn::hat(VectorXd::Unit(m, k)) * t_;
  MatrixXd A = MatrixXd::Zero(n + m, n + m);
  A.topLeftCorner(n, n) = R_.matrix();
  A.topRightCorner(n, m) = -Mt * AdR;
  A.bottomRightCorner(m, m) = AdR;
  return A;
}

MatrixXd SEn::ad(const Tangent& xi) {
  const MatrixXd X = hat(xi);
  const Index d = xi.size();
  MatrixXd A(d, d);
  for (Index l = 0; l < d; ++l) {
    const MatrixXd E = hat(Tangent::Unit(d, l));
    A.col(l) = vee(X * E - E * X);
  }
  return A;
}

MatrixXd SEn::right_jacobian(const Tangent& xi) { return detail::phi(-ad(xi)); }
MatrixXd SEn::left_jacobian(const Tangent& xi) { return detail::phi(ad(xi)); }
MatrixXd SEn::right_jacobian_inverse(const Tangent& xi) {
  return right_jacobian(xi).partialPivLu().inverse();
}
MatrixXd SEn::left_jacobian_inverse(const Tangent& xi) {
  return left_jacobian(xi).partialPivLu().inverse();
}

SEn SEn::sample(int n, std::mt19937_64& rng, double half_extent) {
  SOn R = SOn::sample(n, rng);
  std::uniform_real_distribution<double> u(-half_extent, half_extent);
  VectorXd t(n);
  for (Index k = 0; k < n; ++k) t(k) = u(rng);
  return SEn(std::move(R), std::move(t), true);
}

SEn SEn::inverse() const {
  SOn Ri = R_.inverse();
  VectorXd t = -(Ri.matrix() * t_);
  return SEn(std::move(Ri), std::move(t), true);
}

SEn SEn::interpolate(const SEn& b, double s) const {
  detail::require_finite_fraction("SEn::interpolate", s);
  const Tangent xi = s * (inverse() * b).log();
  const Eigen::Index n = t_.size();
  const double largest_rotation = xi.tail(xi.size() - n).cwiseAbs().maxCoeff();
  detail::require_interpolated_turn("SEn::interpolate", s, xi.cwiseAbs().maxCoeff(), largest_rotation);
  return *this * exp(xi);
}

SEn SEn::operator*(const SEn& b) const {
  SOn R = R_ * b.R_;  // checks that the two n agree
  VectorXd t = t_ + R_.matrix() * b.t_;
  return SEn(std::move(R), std::move(t), true);
}

VectorXd SEn::operator*(const VectorXd& p) const { return R_ * p + t_; }

}  // namespace rigid
