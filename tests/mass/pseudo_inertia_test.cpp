#include "rigid/mass/pseudo_inertia.hpp"

#include <cmath>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using test::ulps;

// A random physical body: mass in [0.1, 10] kg, second moments about the COM in
// [0.01, 1]·m kg·m² along random principal axes (any positive ones give a valid body), COM
// in [−1, 1]³ m. The bodies are at most ~10³ from a degenerate one, so round trips lose at
// most a few hundred ε of the scale m(|c|² + tr Σ_C).
MassProperties random_body(std::mt19937& gen) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double m = 0.1 + 9.9 * u(gen);
  const Eigen::Vector3d sigma = m * (0.01 + 0.99 * Eigen::Array3d(u(gen), u(gen), u(gen))).matrix();
  const Eigen::Matrix3d R =
      Eigen::Quaterniond(u(gen) - 0.5, u(gen) - 0.5, u(gen) - 0.5, u(gen) - 0.5).normalized().toRotationMatrix();
  const Eigen::Matrix3d Sigma_C = R * sigma.asDiagonal() * R.transpose();
  const Eigen::Vector3d c(2 * u(gen) - 1, 2 * u(gen) - 1, 2 * u(gen) - 1);
  return MassProperties(m, c, Sigma_C.trace() * Eigen::Matrix3d::Identity() - Sigma_C);
}

double scale_of(const MassProperties& mp) { return mp.mass() * mp.com().squaredNorm() + mp.inertia_com().trace(); }

void expect_same_body(const MassProperties& a, const MassProperties& b, double tol) {
  EXPECT_NEAR(a.mass(), b.mass(), tol * a.mass());
  EXPECT_LE((a.com() - b.com()).norm(), tol * (1.0 + a.com().norm()));
  EXPECT_LE((a.inertia_com() - b.inertia_com()).cwiseAbs().maxCoeff(), tol * scale_of(a))
      << a.inertia_com() << "\nvs\n" << b.inertia_com();
}

TEST(PseudoInertia, IsTheSecondMomentMatrixOfTheBody) {
  // box lx, ly, lz with its centre at c: Σ_O = ∫ r rᵀ dm = m diag(l²)/12 + m c cᵀ, h = m c
  const double m = 3.0;
  const Eigen::Vector3d l(0.2, 0.4, 0.6), c(0.1, -0.2, 0.3);
  const Eigen::Matrix4d J = mass::pseudo_inertia(mass::solid_box_with_mass(m, l.x(), l.y(), l.z()).shifted(c));
  Eigen::Matrix4d expected = Eigen::Matrix4d::Zero();
  expected.topLeftCorner<3, 3>() = m * Eigen::Matrix3d(l.cwiseAbs2().asDiagonal()) / 12 + m * c * c.transpose();
  expected.topRightCorner<3, 1>() = m * c;
  expected.bottomLeftCorner<1, 3>() = m * c.transpose();
  expected(3, 3) = m;
  // a few flops per element: a few ε of the largest
  EXPECT_LE((J - expected).cwiseAbs().maxCoeff(), ulps(8, expected.cwiseAbs().maxCoeff())) << J;
}

TEST(PseudoInertia, RoundTripsExactlyToRoundOffOnRandomBodies) {
  std::mt19937 gen(2017);
  for (int k = 0; k < 200; ++k) {
    const MassProperties mp = random_body(gen);
    // body → J → body: 256 ε of the scale (see random_body)
    expect_same_body(mp, mass::from_pseudo_inertia(mass::pseudo_inertia(mp)), ulps(256));
    // body → θ → body
    const mass::LogCholesky theta = mass::log_cholesky(mp);
    expect_same_body(mp, mass::from_log_cholesky(theta), ulps(256));
    // θ → J → θ: the Cholesky factor is unique (positive diagonal), so θ comes back
    EXPECT_LE((mass::log_cholesky(mass::from_log_cholesky(theta)) - theta).cwiseAbs().maxCoeff(),
              ulps(1024, 1.0 + theta.cwiseAbs().maxCoeff()))
        << theta.transpose();
    // m = e^{2α} [Rucker2022]
    EXPECT_NEAR(std::exp(2 * theta(0)), mp.mass(), ulps(16, mp.mass()));
  }
}

TEST(PseudoInertia, EveryLogCholeskyVectorIsAPhysicalBody) {
  std::mt19937 gen(2022);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    mass::LogCholesky theta;
    for (int i = 0; i < 10; ++i) theta(i) = n(gen);
    const Eigen::Matrix4d J = mass::pseudo_inertia_from_log_cholesky(theta);
    EXPECT_EQ(Eigen::LLT<Eigen::Matrix4d>(J).info(), Eigen::Success);
    const MassProperties mp = mass::from_log_cholesky(theta);  // validated by its constructor
    EXPECT_LE((mass::pseudo_inertia(mp) - J).cwiseAbs().maxCoeff(), ulps(256, J.cwiseAbs().maxCoeff()));
  }
}

TEST(PseudoInertia, InvalidParametersAreRefusedWithTheReason) {
  Eigen::Matrix4d J = mass::pseudo_inertia(mass::solid_box_with_mass(1.0, 1.0, 1.0, 1.0));
  Eigen::Matrix4d bad = J;
  bad(3, 3) = -1.0;
  EXPECT_RIGID_ERROR((void)mass::from_pseudo_inertia(bad), "its mass J(3,3) must be positive, got -1 kg");
  // Σ = diag(1/12, 1/12, −0.1): a negative second moment, i.e. I_zz > I_xx + I_yy
  bad = J;
  bad(2, 2) = -0.1;
  EXPECT_RIGID_ERROR((void)mass::from_pseudo_inertia(bad), "violate the triangle inequality I₁ + I₂ ≥ I₃ by 0.2 kg·m²");
  EXPECT_RIGID_ERROR((void)mass::from_pseudo_inertia(bad), "eigenvalues of Σ − h hᵀ/m, are (-0.1,");
  bad = J;
  bad(0, 3) = 0.5;
  EXPECT_RIGID_ERROR((void)mass::from_pseudo_inertia(bad), "pseudo-inertia J must be symmetric");
  bad = J;
  bad(1, 1) = NAN;
  EXPECT_RIGID_ERROR((void)mass::from_pseudo_inertia(bad), "pseudo-inertia J must be finite");
  // a thin rod's J is singular: no logarithm
  EXPECT_RIGID_ERROR((void)mass::log_cholesky(mass::thin_rod_with_mass(1.0, 1.0)),
                     "log-Cholesky parameters need a positive definite pseudo-inertia");
  mass::LogCholesky huge = mass::LogCholesky::Zero();
  huge(0) = 400.0;
  EXPECT_RIGID_ERROR((void)mass::from_log_cholesky(huge), "overflows a double");
  huge(0) = NAN;
  EXPECT_RIGID_ERROR((void)mass::from_log_cholesky(huge), "log-Cholesky parameters must be finite");
}

TEST(PseudoInertia, RefusesABodyWhosePseudoInertiaOverflows) {
  // a unit cube of 1e308 kg with its COM 10 m from O: m |c|² = 1e310 overflows (printed as inf
  // and nan before)
  const MassProperties heavy(1e308, Eigen::Vector3d(10, 0, 0),
                             Eigen::Vector3d::Constant(1e308 / 6.0).asDiagonal().toDenseMatrix());
  EXPECT_RIGID_ERROR((void)mass::pseudo_inertia(heavy),
                     "pseudo_inertia(): the pseudo-inertia of the body (mass 1e+308 kg, center of "
                     "mass [10, 0, 0] m from the origin) overflows a double");
  EXPECT_RIGID_ERROR((void)mass::log_cholesky(heavy), "overflows a double");
  // about its own COM the same body has a finite pseudo-inertia; its log-Cholesky parameters
  // are finite (α = ½ ln m)
  const MassProperties at_com(1e308, Eigen::Vector3d::Zero(),
                              Eigen::Vector3d::Constant(1e308 / 6.0).asDiagonal().toDenseMatrix());
  EXPECT_TRUE(mass::pseudo_inertia(at_com).allFinite());
  const mass::LogCholesky th = mass::log_cholesky(at_com);
  EXPECT_TRUE(th.allFinite());
  EXPECT_NEAR(th(0), 0.5 * std::log(1e308), ulps(8) * 355.0);  // α = ½ ln m to 8 ulps of 355
}

}  // namespace
}  // namespace rigid
