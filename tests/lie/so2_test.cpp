// SO2 and SE2 against closed forms, the hard angles (1e-12, π − 1e-9, π) and bad input.

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "rigid/lie.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using std::numbers::pi;
using test::ulps;
using V1 = Eigen::Matrix<double, 1, 1>;

Eigen::Matrix2d rot(double t) {
  Eigen::Matrix2d R;
  R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  return R;
}

TEST(SO2, ExpMatchesRotationMatrixAndActs) {
  for (double t : {0.0, 0.3, -1.0, 2.5, pi, -pi + 1e-3}) {
    const SO2d R = SO2d::exp(V1(t));
    EXPECT_LE((R.matrix() - rot(t)).cwiseAbs().maxCoeff(), ulps(2)) << t;
    EXPECT_EQ(R.real(), std::cos(t));
    EXPECT_EQ(R.imag(), std::sin(t));
  }
  const SO2d Q = SO2d::from_angle(pi / 2);
  EXPECT_LE((Q * Eigen::Vector2d(1, 0) - Eigen::Vector2d(0, 1)).cwiseAbs().maxCoeff(), ulps(2));
  // Angles add: exp(a) exp(b) = exp(a + b) (abelian group).
  const Eigen::Matrix2d AB = (SO2d::from_angle(0.7) * SO2d::from_angle(-2.1)).matrix();
  EXPECT_LE((AB - rot(-1.4)).cwiseAbs().maxCoeff(), ulps(4));
}

TEST(SO2, TinyAngleIsRelativelyAccurate) {
  const SO2d R = SO2d::exp(V1(1e-12));
  // sin(1e-12) = 1e-12 to ~1e-36 and atan2(s, 1) = s to the same order: exact in double.
  EXPECT_EQ(R.log()(0), 1e-12);
  EXPECT_EQ(SO2d::exp(V1(-1e-12)).log()(0), -1e-12);
}

TEST(SO2, NearAndAtPi) {
  const double t = pi - 1e-9;
  // atan2 keeps the angle to an ulp of π near the cut.
  EXPECT_NEAR(SO2d::exp(V1(t)).log()(0), t, ulps(2, pi));
  EXPECT_NEAR(SO2d::exp(V1(-t)).log()(0), -t, ulps(2, pi));
  // Exactly π (stored as c = −1, s = 0): the log is +π, the documented end of (−π, π].
  const SO2d P = SO2d::from_complex(-1.0, 0.0);
  EXPECT_EQ(P.log()(0), pi);
  EXPECT_EQ(SO2d::from_matrix(-Eigen::Matrix2d::Identity()).log()(0), pi);
}

TEST(SO2, FromMatrixAndComplexRoundTrip) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const SO2d R = SO2d::sample(rng);
    EXPECT_TRUE(SO2d::from_matrix(R.matrix()).is_approx(R, ulps(4)));
    EXPECT_TRUE(SO2d::from_complex(3 * R.real(), 3 * R.imag()).is_approx(R, ulps(4)));
  }
}

TEST(SO2, SampleIsUniformInAngle) {
  // Haar on SO(2): θ uniform on (−π, π], so E[cos θ] = E[sin θ] = 0 and E[θ²] = π²/3.
  std::mt19937_64 rng(5);
  const int n = 20000;
  double c = 0, s = 0, t2 = 0;
  for (int i = 0; i < n; ++i) {
    const SO2d R = SO2d::sample(rng);
    c += R.real();
    s += R.imag();
    t2 += R.angle() * R.angle();
  }
  // σ(cos) = σ(sin) = 1/√2, σ(θ²) = 4π²/(3√5) ≈ 5.9: 5σ/√n gives 0.025 and 0.21.
  EXPECT_NEAR(c / n, 0.0, 0.025);
  EXPECT_NEAR(s / n, 0.0, 0.025);
  EXPECT_NEAR(t2 / n, pi * pi / 3, 0.21);
}

TEST(SO2, BadInput) {
  Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
  M(0, 1) = 1e-3;
  EXPECT_RIGID_ERROR((void)SO2d::from_matrix(M), "is not a rotation: orthonormality defect max|RᵀR − I| = 0.001");
  EXPECT_RIGID_ERROR((void)SO2d::from_matrix(Eigen::Vector2d(1, -1).asDiagonal().toDenseMatrix()),
                     "determinant -1 (expected +1)");
  M(1, 1) = std::nan("");
  EXPECT_RIGID_ERROR((void)SO2d::from_matrix(M), "has a non-finite entry");
  EXPECT_RIGID_ERROR((void)SO2d::from_complex(0, 0), "(c, s) = (0, 0) has norm 0, expected a nonzero number");
  EXPECT_RIGID_ERROR((void)SO2d::from_complex(std::nan(""), 1), "has a non-finite component");
  EXPECT_RIGID_ERROR((void)SO2d::from_angle(INFINITY), "angle inf is not finite");
}

TEST(SE2, ExpIsARotationAboutACentre) {
  // A rotation by θ about the point c is p ↦ R (p − c) + c; its generator is
  // hat(ξ) = [[θJ, −θ J c], [0, 0]], i.e. ρ = −θ J c = θ (c_y, −c_x).
  const Eigen::Vector2d c(0.4, -1.3);
  for (double t : {0.5, -2.0, 3.0}) {
    const SE2d X = SE2d::exp(Eigen::Vector3d(t * c(1), -t * c(0), t));
    EXPECT_LE((X.translation() - (c - rot(t) * c)).cwiseAbs().maxCoeff(), ulps(16)) << t;
    EXPECT_LE((X.rotation().matrix() - rot(t)).cwiseAbs().maxCoeff(), ulps(2));
    // The centre is fixed.
    EXPECT_LE((X * c - c).cwiseAbs().maxCoeff(), ulps(16));
  }
  // Pure translation.
  const SE2d T = SE2d::exp(Eigen::Vector3d(1.5, -2, 0));
  EXPECT_EQ(T.translation(), Eigen::Vector2d(1.5, -2));
}

TEST(SE2, TinyAndPiAngles) {
  const Eigen::Vector3d tiny(0.3, -0.7, 1e-12);
  const Eigen::Vector3d back = SE2d::exp(tiny).log();
  // Series branch: the angle is exact (see SO2) and ρ within a few ulps.
  EXPECT_EQ(back(2), 1e-12);
  EXPECT_LE((back - tiny).cwiseAbs().maxCoeff(), ulps(4));
  const Eigen::Vector3d near_pi(1.0, 2.0, pi - 1e-9);
  EXPECT_LE((SE2d::exp(near_pi).log() - near_pi).cwiseAbs().maxCoeff(), 1e-14);
  // At exactly π: V⁻¹ = [[0, π/2], [−π/2, 0]] and exp(log X) = X.
  const SE2d X(SO2d::from_complex(-1, 0), Eigen::Vector2d(1, 2));
  const Eigen::Vector3d xi = X.log();
  EXPECT_LE((xi - Eigen::Vector3d(pi, -pi / 2, pi)).cwiseAbs().maxCoeff(), ulps(8, pi));
  EXPECT_LE((SE2d::exp(xi).matrix() - X.matrix()).cwiseAbs().maxCoeff(), ulps(16));
}

TEST(SE2, BadInput) {
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  T(2, 0) = 1;
  EXPECT_RIGID_ERROR((void)SE2d::from_matrix(T), "last row of the homogeneous matrix is [1, 0, 1], expected [0, 0, 1]");
  T = Eigen::Matrix3d::Identity();
  T(1, 2) = std::nan("");
  EXPECT_RIGID_ERROR((void)SE2d::from_matrix(T), "translation [0, nan] has a non-finite component");
  T = Eigen::Matrix3d::Identity();
  T(0, 0) = 1.1;
  EXPECT_RIGID_ERROR((void)SE2d::from_matrix(T), "is not a rotation");
}

TEST(SO2, ExpAndInterpolateRefuseNonFiniteAndHugeAngles) {
  EXPECT_RIGID_ERROR((void)SO2d::exp(SO2d::Tangent(std::nan(""))), "angle nan is not finite");
  EXPECT_RIGID_ERROR((void)SO2d::from_angle(1e300), "angle 1e+300 rad is too large");
  const SO2d a = SO2d::identity(), b = SO2d::from_angle(0.5);
  EXPECT_RIGID_ERROR((void)a.interpolate(b, std::nan("")),
                     "SO2::interpolate(): fraction s = nan is not finite");
  EXPECT_RIGID_ERROR((void)a.interpolate(b, 1e300), "turning by at most kMaxAngle");
}

TEST(SE2, ExpAndInterpolateRefuseNonFiniteInput) {
  EXPECT_RIGID_ERROR((void)SE2d::exp(SE2d::Tangent(1, std::nan(""), 0)),
                     "SE2::exp(): tangent vector [1, nan, 0] has a non-finite component");
  const SE2d a = SE2d::identity(), b = SE2d::exp(SE2d::Tangent(1, 2, 0.5));
  EXPECT_RIGID_ERROR((void)a.interpolate(b, INFINITY),
                     "SE2::interpolate(): fraction s = inf is not finite");
}

}  // namespace
}  // namespace rigid
