#include "rigid/body/free_body_exact.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <boost/math/special_functions/ellint_1.hpp>
#include <gtest/gtest.h>

#include "rigid/body/euler.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::body {
namespace {

using test::ulps;

// Independent reference: classical RK4 on Euler's equations with a small step.
Eigen::Vector3d rk4_omega(const Eigen::Vector3d& I, Eigen::Vector3d w, double t, int n) {
  const double h = t / n;
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d k1 = euler_rhs<double>(I, w, z);
    const Eigen::Vector3d k2 = euler_rhs<double>(I, Eigen::Vector3d(w + 0.5 * h * k1), z);
    const Eigen::Vector3d k3 = euler_rhs<double>(I, Eigen::Vector3d(w + 0.5 * h * k2), z);
    const Eigen::Vector3d k4 = euler_rhs<double>(I, Eigen::Vector3d(w + h * k3), z);
    w += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return w;
}

struct Case {
  Eigen::Vector3d I, w0;
};

TEST(FreeBodyExact, MatchesRk4ForEveryCaseAndOrdering) {
  const std::vector<Case> cases = {
      {{1, 2, 3}, {0.01, 1, 0.01}},     // tennis racket, L² > 2E I2 by 2e-4 (dn on axis 3)
      {{1, 2, 3}, {0.01, 1, 0.001}},    // L² < 2E I2 near the separatrix (dn on axis 1)
      {{1, 2, 3}, {0.3, 0.2, 0.9}},     // L² > 2E I2 (dn on axis 3)
      {{1, 2, 3}, {-0.7, 0.4, -0.2}},   // negative dn sign, axis 1
      {{1, 2, 3}, {0.2, -0.5, -0.9}},   // negative dn sign, axis 3
      {{3, 1, 2}, {0.2, 0.01, 1.0}},    // unsorted moments (even relabelling)
      {{2, 1, 3}, {0.5, 0.3, -0.4}},    // unsorted moments (odd relabelling)
      {{2, 2, 3}, {0.5, 0.3, 0.4}},     // symmetric about axis 3, oblate
      {{1, 2, 2}, {0.5, 0.3, 0.4}},     // symmetric about axis 1, prolate
      {{2, 2, 2}, {0.5, 0.3, 0.4}},     // sphere
  };
  for (const Case& c : cases) {
    const FreeBodyExact exact(c.I, c.w0);
    for (double t : {0.0, 0.7, 3.1, 12.0}) {
      const Eigen::Vector3d ref = t == 0 ? c.w0 : rk4_omega(c.I, c.w0, t, 20000);
      const Eigen::Vector3d got = exact.omega_body(t);
      // RK4 with h ≤ 6e-4 and |ω| ≤ 1.1: global error ≈ C h⁴ t ≲ 1e-11.
      EXPECT_LT((got - ref).lpNorm<Eigen::Infinity>(), 1e-10)
          << "I = " << c.I.transpose() << " w0 = " << c.w0.transpose() << " t = " << t
          << " got " << got.transpose() << " ref " << ref.transpose();
    }
  }
}

TEST(FreeBodyExact, ConservesEnergyAndMomentumNormToRoundOff) {
  const Eigen::Vector3d I(1, 2, 3), w0(0.01, 1, 0.01);
  const FreeBodyExact exact(I, w0);
  const double E0 = rotational_energy<double>(I, w0);
  const double L0 = I.cwiseProduct(w0).norm();
  for (double t = 0; t < 100; t += 1.37) {
    const Eigen::Vector3d w = exact.omega_body(t);
    EXPECT_NEAR(rotational_energy<double>(I, w), E0, ulps(64, E0));
    EXPECT_NEAR(I.cwiseProduct(w).norm(), L0, ulps(64, L0));
  }
}

TEST(FreeBodyExact, TennisRacketFlipsWithTheEllipticPeriod) {
  // Independent closed form [Landau1976, §37, eq. 37.10]: here L² > 2E I2
  // (4.001 > 4.0008), so ω3 ∝ dn and the period of ω is T = 4K(k)/λ with
  // λ² = (I3−I2)(L² − 2E I1)/(I1 I2 I3), k² = (I2−I1)(2E I3 − L²)/((I3−I2)(L² − 2E I1)).
  // ω2 changes sign twice per T.
  const Eigen::Vector3d I(1, 2, 3), w0(0.01, 1, 0.01);
  const double E2 = (I.array() * w0.array().square()).sum();
  const double L2 = (I.array().square() * w0.array().square()).sum();
  ASSERT_GT(L2, E2 * I(1));
  const double lambda = std::sqrt((I(2) - I(1)) * (L2 - E2 * I(0)) / (I(0) * I(1) * I(2)));
  const double k = std::sqrt((I(1) - I(0)) * (E2 * I(2) - L2) / ((I(2) - I(1)) * (L2 - E2 * I(0))));
  const double T = 4.0 * boost::math::ellint_1(k) / lambda;
  const FreeBodyExact exact(I, w0);
  EXPECT_EQ(exact.solution_case(), FreeBodyCase::kAsymmetric);
  EXPECT_NEAR(exact.period(), T, ulps(64, T));
  // Sign changes of ω2 in an RK4 trajectory (independent of the closed form).
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  const double h = 1e-3;
  Eigen::Vector3d w = w0;
  std::vector<double> crossings;
  for (int i = 0; i < 100000; ++i) {  // 100 s
    const Eigen::Vector3d k1 = euler_rhs<double>(I, w, z);
    const Eigen::Vector3d k2 = euler_rhs<double>(I, Eigen::Vector3d(w + 0.5 * h * k1), z);
    const Eigen::Vector3d k3 = euler_rhs<double>(I, Eigen::Vector3d(w + 0.5 * h * k2), z);
    const Eigen::Vector3d k4 = euler_rhs<double>(I, Eigen::Vector3d(w + h * k3), z);
    const Eigen::Vector3d wn = w + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    if (w(1) * wn(1) < 0) crossings.push_back(h * (i + w(1) / (w(1) - wn(1))));
    w = wn;
  }
  ASSERT_GE(crossings.size(), 3u) << "the racket must flip (ω2 changes sign)";
  for (std::size_t i = 2; i < crossings.size(); ++i) {
    // Linear interpolation of the crossing: error ≲ h²·|ω̈2|/|ω̇2| ≈ 1e-6 s.
    EXPECT_NEAR(crossings[i] - crossings[i - 2], T, 1e-5);
  }
}

TEST(FreeBodyExact, SymmetricTopPrecessesAtTheBodyRate) {
  // Transverse ω turns at Ω = (I3 − I1) ω3 / I1 about the symmetry axis.
  const Eigen::Vector3d I(2, 2, 3), w0(0.5, 0.0, 0.4);
  const FreeBodyExact exact(I, w0);
  const double Omega = (3.0 - 2.0) * 0.4 / 2.0;
  EXPECT_EQ(exact.solution_case(), FreeBodyCase::kSymmetric);
  EXPECT_NEAR(exact.period(), 2 * std::numbers::pi / Omega, ulps(16, 40));
  const double t = 2.3;
  const Eigen::Vector3d w = exact.omega_body(t);
  EXPECT_NEAR(w(0), 0.5 * std::cos(Omega * t), ulps(8));
  EXPECT_NEAR(w(1), 0.5 * std::sin(Omega * t), ulps(8));
  EXPECT_EQ(w(2), 0.4);
}

TEST(FreeBodyExact, GracefulAtAndNearTheSeparatrix) {
  // On the separatrix (L² = 2E I2, ω1 = ω3 / √... chosen so) the motion tends to
  // rotation about the middle axis: ω2 → ±√(2E/I2)·… and ω1, ω3 → 0 as t → ∞.
  // I = (1,2,3): L² − 2E I2 = I1(I1−I2)ω1² + I3(I3−I2)ω3² = −ω1² + 3ω3² = 0.
  const Eigen::Vector3d I(1, 2, 3);
  const Eigen::Vector3d w0(std::sqrt(3.0) * 0.1, 0.0, 0.1);
  const FreeBodyExact exact(I, w0);
  EXPECT_GT(exact.modulus(), 1.0 - 1e-12);
  const Eigen::Vector3d ref = rk4_omega(I, w0, 5.0, 20000);
  EXPECT_LT((exact.omega_body(5.0) - ref).lpNorm<Eigen::Infinity>(), 1e-10);
  const Eigen::Vector3d far = exact.omega_body(500.0);
  EXPECT_TRUE(far.allFinite());
  const double L0 = I.cwiseProduct(w0).norm();
  EXPECT_NEAR(I.cwiseProduct(far).norm(), L0, ulps(64, L0));
  // Just off the separatrix on each side: finite, period grows like log(1/|k'|).
  for (double eps : {1e-9, -1e-9}) {
    const FreeBodyExact near(I, Eigen::Vector3d(std::sqrt(3.0) * 0.1 * (1 + eps), 0.0, 0.1));
    EXPECT_TRUE(near.omega_body(37.0).allFinite());
    EXPECT_TRUE(std::isfinite(near.period()));
    EXPECT_GT(near.period(), 50.0);
  }
}

TEST(FreeBodyExact, RejectsBadInput) {
  EXPECT_RIGID_ERROR(FreeBodyExact(Eigen::Vector3d(1, -2, 3), Eigen::Vector3d::Ones()),
                     "principal moments must be finite and > 0");
  EXPECT_RIGID_ERROR(FreeBodyExact(Eigen::Vector3d(1, 1, 3), Eigen::Vector3d::Ones()),
                     "violate the triangle inequality at axis 3");
  EXPECT_RIGID_ERROR(FreeBodyExact(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(NAN, 0, 0)),
                     "initial body angular velocity must be finite");
}

}  // namespace
}  // namespace rigid::body
