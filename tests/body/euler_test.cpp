#include "rigid/body/euler.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "support/tolerance.hpp"

namespace rigid::body {
namespace {

using test::ulps;

TEST(Euler, MatchesVectorForm) {
  // Independent evaluation of ω̇ = I⁻¹(τ − ω × Iω) with Eigen's cross product.
  const Eigen::Vector3d I(1.0, 2.5, 3.0), w(0.3, -1.2, 0.7), tau(0.1, 0.2, -0.4);
  const Eigen::Vector3d expected = (tau - w.cross(I.cwiseProduct(w))).cwiseQuotient(I);
  const Eigen::Vector3d got = euler_rhs<double>(I, w, tau);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got(i), expected(i), ulps(8, 3.0));
}

TEST(Euler, TorqueFreeKeepsEnergyAndMomentumNormInstantaneously) {
  // d/dt(½ωᵀIω) = ωᵀIω̇ = 0 and d/dt|Iω|² = 2(Iω)ᵀ(Iω̇) = 0 without torque.
  const Eigen::Vector3d I(1.0, 2.0, 3.0), w(0.4, -0.8, 1.1);
  const Eigen::Vector3d wd = euler_rhs<double>(I, w, Eigen::Vector3d::Zero());
  EXPECT_NEAR(w.dot(I.cwiseProduct(wd)), 0.0, ulps(16, 10.0));
  EXPECT_NEAR(I.cwiseProduct(w).dot(I.cwiseProduct(wd)), 0.0, ulps(16, 30.0));
}

TEST(Euler, AutoDiffJacobianMatchesHandDerivative) {
  const Eigen::Vector3d I(1.0, 2.0, 3.0), w(0.4, -0.8, 1.1);
  Eigen::Matrix<AutoDiffXd, 3, 1> wa;
  for (int i = 0; i < 3; ++i) wa(i) = AutoDiffXd(w(i), 3, i);
  const Eigen::Matrix<AutoDiffXd, 3, 1> tau = Eigen::Matrix<AutoDiffXd, 3, 1>::Zero();
  const auto f = euler_rhs<AutoDiffXd>(I, wa, tau);
  // ∂ω̇1/∂ω2 = (I2 − I3) ω3 / I1, ∂ω̇1/∂ω3 = (I2 − I3) ω2 / I1.
  EXPECT_NEAR(f(0).derivatives()(1), (I(1) - I(2)) * w(2) / I(0), ulps(4));
  EXPECT_NEAR(f(0).derivatives()(2), (I(1) - I(2)) * w(1) / I(0), ulps(4));
  EXPECT_EQ(f(0).derivatives()(0), 0.0);
  EXPECT_NEAR(rotational_energy<double>(I, w), 0.5 * (0.16 + 2 * 0.64 + 3 * 1.21), ulps(4, 3));
}

}  // namespace
}  // namespace rigid::body
