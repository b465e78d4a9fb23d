#include "rigid/mass/second_moments.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using test::ulps;

TEST(SecondMoments, ThreeDRelationToInertia) {
  // n-ball in 3D: J = m r²/5 · 1, so I = tr(J) − J = 2/5 m r² (the solid sphere)
  const auto ball = mass::n_ball_with_mass(2.0, 0.5, 3);
  const auto mp = ball.to_mass_properties();
  EXPECT_NEAR(mp.inertia_com()(0, 0), 0.4 * 2.0 * 0.25, ulps(4));
  // n-box in 3D equals the solid box; J ↔ I round trip
  Eigen::VectorXd sizes(3);
  sizes << 0.3, 0.5, 0.7;
  const auto box = mass::n_box_with_density(10.0, sizes).to_mass_properties();
  const auto expected = mass::solid_box_with_density(10.0, 0.3, 0.5, 0.7);
  EXPECT_NEAR(box.mass(), expected.mass(), ulps(4, box.mass()));
  EXPECT_TRUE(box.inertia_com().isApprox(expected.inertia_com(), ulps(16)));
  const auto back = SecondMoments::from_mass_properties(expected);
  EXPECT_TRUE(back.J_com().isApprox(
      Eigen::MatrixXd((expected.mass() / 12.0 * sizes.cwiseProduct(sizes)).asDiagonal()), ulps(16)));
}

TEST(SecondMoments, NBallVolumes) {
  // unit-density unit balls: V₁ = 2, V₂ = π, V₄ = π²/2, V₅ = 8π²/15
  const double kPi = std::numbers::pi;
  EXPECT_NEAR(mass::n_ball_with_density(1.0, 1.0, 1).mass(), 2.0, ulps(8));
  EXPECT_NEAR(mass::n_ball_with_density(1.0, 1.0, 2).mass(), kPi, ulps(8, kPi));
  EXPECT_NEAR(mass::n_ball_with_density(1.0, 1.0, 4).mass(), kPi * kPi / 2, ulps(16, 5));
  EXPECT_NEAR(mass::n_ball_with_density(1.0, 1.0, 5).mass(), 8 * kPi * kPi / 15, ulps(16, 5));
  // 1D ball = rod of length 2r: J = m r²/3 = m (2r)²/12
  EXPECT_NEAR(mass::n_ball_with_mass(3.0, 0.5, 1).J_com()(0, 0), 3.0 * 1.0 / 12, ulps(4));
}

TEST(SecondMoments, NBallMonteCarloIn4D) {
  // independent check of J = m r²/(n+2) in 4D: uniform samples in the ball by rejection,
  // 2·10⁵ accepted samples; the statistical error of E[x²] ≈ r²/6 is about
  // sqrt(Var(x²)/N) ≈ 0.19/sqrt(2e5)·r² ≈ 4e-4 r², so 5σ ≈ 2e-3 r².
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double sum = 0.0;
  int n = 0;
  while (n < 200000) {
    Eigen::Vector4d x(u(rng), u(rng), u(rng), u(rng));
    if (x.squaredNorm() <= 1.0) {
      sum += x(0) * x(0);
      ++n;
    }
  }
  const double expected = mass::n_ball_with_mass(1.0, 1.0, 4).J_com()(0, 0);
  EXPECT_NEAR(sum / n, expected, 2e-3);
  EXPECT_NEAR(expected, 1.0 / 6.0, ulps(4));
}

TEST(SecondMoments, ActionOnSoN) {
  // 4D box: J = diag(j); (JΩ + ΩJ)_ab = (j_a + j_b) Ω_ab
  Eigen::VectorXd sizes(4);
  sizes << 1, 2, 3, 4;
  const auto box = mass::n_box_with_mass(12.0, sizes);  // J = diag(1, 4, 9, 16)
  Eigen::MatrixXd Omega = Eigen::MatrixXd::Zero(4, 4);
  Omega(0, 3) = 0.5;
  Omega(3, 0) = -0.5;
  Omega(1, 2) = -2.0;
  Omega(2, 1) = 2.0;
  const Eigen::MatrixXd M = box.apply(Omega);
  EXPECT_NEAR(M(0, 3), (1 + 16) * 0.5, ulps(8, 10));
  EXPECT_NEAR(M(1, 2), (4 + 9) * -2.0, ulps(8, 30));
  EXPECT_NEAR((M + M.transpose()).cwiseAbs().maxCoeff(), 0.0, ulps(8, 30));
  EXPECT_RIGID_ERROR((void)box.apply(Eigen::MatrixXd::Identity(4, 4)), "must be skew-symmetric");
  EXPECT_RIGID_ERROR((void)box.apply(Eigen::MatrixXd::Zero(3, 3)), "Ω must be 4 × 4, got 3 × 3");
}

TEST(SecondMoments, In3DActionMatchesInertiaTimesOmega) {
  // with Ω = hat(ω): JΩ + ΩJ = hat(I ω) where I = tr(J) 1 − J
  const auto box = mass::solid_box_with_mass(2.0, 0.3, 0.5, 0.7);
  const auto sm = SecondMoments::from_mass_properties(box);
  const Eigen::Vector3d w(0.3, -1.2, 2.0);
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  const Eigen::Matrix3d M = sm.apply(W);
  const Eigen::Vector3d L = box.inertia_com() * w;
  EXPECT_TRUE(Eigen::Vector3d(M(2, 1), M(0, 2), M(1, 0)).isApprox(L, ulps(16)));
}

TEST(SecondMoments, PointSet) {
  Eigen::MatrixXd pts(2, 2);
  pts << 1, -1, 0, 0;
  const double masses[] = {1.0, 1.0};
  const auto sm = mass::point_set_second_moments(masses, pts);
  EXPECT_NEAR(sm.J_com()(0, 0), 2.0, ulps(4));
  EXPECT_NEAR(sm.J_com()(1, 1), 0.0, ulps(4));
  EXPECT_NEAR(sm.J_about(Eigen::Vector2d(0, 1))(1, 1), 2.0, ulps(4));
}

TEST(SecondMoments, BadInput) {
  EXPECT_RIGID_ERROR((void)mass::n_ball_with_mass(1.0, 1.0, 0), "dimension must be at least 1, got 0");
  EXPECT_RIGID_ERROR((void)mass::n_ball_with_mass(1.0, -1.0, 3), "radius must be positive and finite, got -1 m");
  Eigen::VectorXd sizes(2);
  sizes << 1.0, 0.0;
  EXPECT_RIGID_ERROR((void)mass::n_box_with_mass(1.0, sizes), "edge length 1 must be positive and finite, got 0 m");
  EXPECT_RIGID_ERROR(SecondMoments(1.0, Eigen::VectorXd::Zero(2), -Eigen::MatrixXd::Identity(2, 2)),
                     "J must be positive semidefinite");
}

}  // namespace
}  // namespace rigid
