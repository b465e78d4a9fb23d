#include "rigid/mass/second_moments.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid {

SecondMoments::SecondMoments(double mass, const Eigen::VectorXd& com, const Eigen::MatrixXd& J_com)
    : mass_(mass), com_(com), J_com_(0.5 * (J_com + J_com.transpose())) {
  RIGID_REQUIRE(std::isfinite(mass) && mass > 0.0, "mass must be positive and finite, got {} kg",
                mass);
  RIGID_REQUIRE(com.size() >= 1 && J_com.rows() == com.size() && J_com.cols() == com.size(),
                "J must be n × n for an n-vector COM, got a {}-vector and a {} × {} matrix",
                com.size(), J_com.rows(), J_com.cols());
  RIGID_REQUIRE(com.allFinite() && J_com.allFinite(), "COM and J must be finite, got {} and {}",
                to_string(com.transpose()), to_string(J_com));
  const double tol = 1e-10 * std::abs(J_com.trace());
  const double asym = (J_com - J_com.transpose()).cwiseAbs().maxCoeff();
  RIGID_REQUIRE(asym <= tol, "J must be symmetric, got max |J_ij − J_ji| = {} kg·m²", asym);
  const double smallest =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(J_com_, Eigen::EigenvaluesOnly)
          .eigenvalues()(0);
  RIGID_REQUIRE(smallest >= -tol,
                "J must be positive semidefinite, got smallest eigenvalue {} kg·m² (tolerance {})",
                smallest, tol);
}

Eigen::MatrixXd SecondMoments::J_about(const Eigen::VectorXd& q) const {
  RIGID_REQUIRE(q.size() == dimension(), "point has {} coordinates, expected {}", q.size(),
                dimension());
  const Eigen::VectorXd d = com_ - q;
  return J_com_ + mass_ * d * d.transpose();
}

Eigen::MatrixXd SecondMoments::apply(const Eigen::MatrixXd& Omega) const {
  const Eigen::Index n = dimension();
  RIGID_REQUIRE(Omega.rows() == n && Omega.cols() == n, "Ω must be {} × {}, got {} × {}", n, n,
                Omega.rows(), Omega.cols());
  const double skew_error = (Omega + Omega.transpose()).cwiseAbs().maxCoeff();
  RIGID_REQUIRE(skew_error <= 1e-12 * Omega.cwiseAbs().maxCoeff(),
                "Ω must be skew-symmetric (an element of so({})), got max |Ω + Ωᵀ| = {}", n,
                skew_error);
  return J_com_ * Omega + Omega * J_com_;
}

MassProperties SecondMoments::to_mass_properties() const {
  RIGID_REQUIRE(dimension() == 3, "needs a 3D body, got dimension {}", dimension());
  const Eigen::Matrix3d J = J_com_;
  return MassProperties(mass_, Eigen::Vector3d(com_),
                        J.trace() * Eigen::Matrix3d::Identity() - J);
}

SecondMoments SecondMoments::from_mass_properties(const MassProperties& mp) {
  const Eigen::Matrix3d& I = mp.inertia_com();
  const Eigen::Matrix3d J = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
  return SecondMoments(mp.mass(), Eigen::VectorXd(mp.com()), Eigen::MatrixXd(J));
}

}  // namespace rigid

namespace rigid::mass {
namespace {

double n_ball_volume(int n, double r) {
  // π^{n/2} rⁿ / Γ(n/2 + 1)
  return std::pow(std::numbers::pi, 0.5 * n) * std::pow(r, n) / std::tgamma(0.5 * n + 1.0);
}

void check_ball(const char* fn, int n, double r) {
  if (n < 1) detail::throw_error(fn, fmt::format("dimension must be at least 1, got {}", n));
  if (!std::isfinite(r) || !(r > 0.0)) {
    detail::throw_error(fn, fmt::format("radius must be positive and finite, got {} m", r));
  }
}

void check_sizes(const char* fn, const Eigen::VectorXd& sizes) {
  if (sizes.size() < 1) detail::throw_error(fn, "needs at least one edge length, got none");
  for (Eigen::Index i = 0; i < sizes.size(); ++i) {
    if (!std::isfinite(sizes(i)) || !(sizes(i) > 0.0)) {
      detail::throw_error(fn, fmt::format("edge length {} must be positive and finite, got {} m", i,
                                          sizes(i)));
    }
  }
}

void check_positive(const char* fn, const char* what, const char* unit, double v) {
  if (!std::isfinite(v) || !(v > 0.0)) {
    detail::throw_error(fn, fmt::format("{} must be positive and finite, got {} {}", what, v, unit));
  }
}

}  // namespace

SecondMoments n_ball_with_mass(double m, double r, int n) {
  check_ball(__func__, n, r);
  check_positive(__func__, "mass", "kg", m);
  return SecondMoments(m, Eigen::VectorXd::Zero(n),
                       m * r * r / (n + 2.0) * Eigen::MatrixXd::Identity(n, n));
}

SecondMoments n_ball_with_density(double rho, double r, int n) {
  check_ball(__func__, n, r);
  check_positive(__func__, "density", "kg/mⁿ", rho);
  return n_ball_with_mass(rho * n_ball_volume(n, r), r, n);
}

SecondMoments n_box_with_mass(double m, const Eigen::VectorXd& sizes) {
  check_sizes(__func__, sizes);
  check_positive(__func__, "mass", "kg", m);
  const Eigen::VectorXd d = m / 12.0 * sizes.cwiseProduct(sizes);
  return SecondMoments(m, Eigen::VectorXd::Zero(sizes.size()), Eigen::MatrixXd(d.asDiagonal()));
}

SecondMoments n_box_with_density(double rho, const Eigen::VectorXd& sizes) {
  check_sizes(__func__, sizes);
  check_positive(__func__, "density", "kg/mⁿ", rho);
  return n_box_with_mass(rho * sizes.prod(), sizes);
}

SecondMoments point_set_second_moments(std::span<const double> masses,
                                       const Eigen::MatrixXd& points) {
  RIGID_REQUIRE(!masses.empty() && static_cast<Eigen::Index>(masses.size()) == points.cols(),
                "needs one mass per point and at least one point, got {} masses and {} points",
                masses.size(), points.cols());
  double m = 0.0;
  Eigen::VectorXd F = Eigen::VectorXd::Zero(points.rows());
  for (std::size_t i = 0; i < masses.size(); ++i) {
    RIGID_REQUIRE(std::isfinite(masses[i]) && masses[i] > 0.0,
                  "mass {} must be positive and finite, got {} kg", i, masses[i]);
    m += masses[i];
    F += masses[i] * points.col(static_cast<Eigen::Index>(i));
  }
  const Eigen::VectorXd c = F / m;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(points.rows(), points.rows());
  for (std::size_t i = 0; i < masses.size(); ++i) {
    const Eigen::VectorXd d = points.col(static_cast<Eigen::Index>(i)) - c;
    J += masses[i] * d * d.transpose();
  }
  return SecondMoments(m, c, J);
}

}  // namespace rigid::mass
