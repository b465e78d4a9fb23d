// SOn and SEn for n = 2..8: group identities on random elements, agreement with SO2/SO3/SE2/SE3
// at n = 2, 3 (independent fixed-size code), angles 1e-12, π − 1e-9 and π, Haar moments and
// bad input.

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/SVD>
#include <gtest/gtest.h>

#include "rigid/lie.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using std::numbers::pi;
using test::ulps;

double max_abs(const MatrixXd& A) { return A.cwiseAbs().maxCoeff(); }

// Random ω ∈ so(n) whose largest rotation angle (the largest singular value of hat(ω), which
// the angle pairs ±iθ of a normal matrix make equal to max θ) is uniform in [0, max_angle).
VectorXd random_omega(int n, std::mt19937_64& rng, double max_angle) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  VectorXd w(SOn::dimension_of(n));
  for (Eigen::Index k = 0; k < w.size(); ++k) w(k) = g(rng);
  const double top = Eigen::JacobiSVD<MatrixXd>(SOn::hat(w)).singularValues()(0);
  return w * (max_angle * u(rng) / top);
}

VectorXd random_xi(int n, std::mt19937_64& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VectorXd xi(SEn::dimension_of(n));
  for (int k = 0; k < n; ++k) xi(k) = u(rng);
  xi.tail(SOn::dimension_of(n)) = random_omega(n, rng, max_angle);
  return xi;
}

// Per n: 2000 random elements (n = 2..8, 14,000 in all): the O(n³) Schur and Padé steps make
// 10,000 per n too slow for the unit-test budget at n = 8.
constexpr int kSamples = 2000;
// Entries of R are O(1); Padé exp and the Schur log each carry O(n ε) backward error, so 1e-12
// (≈ 4500 ulps) bounds them at n = 8 with margin while catching any wrong term.
constexpr double kTol = 1e-12;

TEST(SOn, ExpLogRoundTripsForNFrom2To8) {
  for (int n = 2; n <= 8; ++n) {
    std::mt19937_64 rng(100 + n);
    for (int i = 0; i < kSamples; ++i) {
      const SOn g = SOn::sample(n, rng);
      ASSERT_LE(max_abs(SOn::exp(g.log()).matrix() - g.matrix()), kTol) << "n " << n << " sample " << i;
      const VectorXd w = random_omega(n, rng, 3.1);
      const SOn R = SOn::exp(w);
      ASSERT_LE(max_abs(R.matrix().transpose() * R.matrix() - MatrixXd::Identity(n, n)), ulps(8 * n));
      ASSERT_LE(max_abs(R.log() - w), kTol) << "n " << n << " omega " << w.transpose();
    }
  }
}

TEST(SOn, GroupAxiomsAdjointAndAction) {
  for (int n = 2; n <= 8; ++n) {
    std::mt19937_64 rng(200 + n);
    for (int i = 0; i < kSamples / 4; ++i) {
      const SOn a = SOn::sample(n, rng), b = SOn::sample(n, rng), c = SOn::sample(n, rng);
      ASSERT_LE(max_abs((a * a.inverse()).matrix() - MatrixXd::Identity(n, n)), kTol);
      ASSERT_LE(max_abs(((a * b) * c).matrix() - (a * (b * c)).matrix()), kTol);
      ASSERT_LE(max_abs(a.matrix().transpose() * a.matrix() - MatrixXd::Identity(n, n)), ulps(8 * n));
      ASSERT_GT(a.matrix().determinant(), 0.0);
      const VectorXd v = VectorXd::Random(n);
      ASSERT_LE(max_abs(a * v - a.homogeneous().topLeftCorner(n, n) * v), ulps(4 * n));
      // g exp(ω) g⁻¹ = exp(Ad ω) and, at the algebra level, g hat(ω) gᵀ = hat(Ad ω).
      const VectorXd w = random_omega(n, rng, 3.0);
      const VectorXd aw = a.adjoint() * w;
      ASSERT_LE(max_abs((a * SOn::exp(w) * a.inverse()).matrix() - SOn::exp(aw).matrix()), kTol);
      ASSERT_LE(max_abs(a.matrix() * SOn::hat(w) * a.matrix().transpose() - SOn::hat(aw)), kTol);
      ASSERT_EQ(SOn::vee(SOn::hat(w)), w);  // exact: vee reads back the stored entries
    }
  }
}

TEST(SOn, AgreesWithSO2AtN2) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3.1, 3.1);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Matrix<double, 1, 1> t(u(rng)), s(u(rng));
    const VectorXd tv = t, sv = s;
    EXPECT_EQ(SOn::hat(tv), MatrixXd(SO2d::hat(t)));
    EXPECT_LE(max_abs(SOn::exp(tv).matrix() - SO2d::exp(t).matrix()), ulps(4));
    EXPECT_NEAR(SOn::exp(tv).log()(0), SO2d::exp(t).log()(0), ulps(8, pi));
    EXPECT_LE(max_abs((SOn::exp(tv) * SOn::exp(sv)).matrix() - (SO2d::exp(t) * SO2d::exp(s)).matrix()),
              ulps(8));
    EXPECT_LE(max_abs(SOn::exp(tv).adjoint() - MatrixXd::Identity(1, 1)), ulps(2));
  }
}

TEST(SOn, AgreesWithSO3AtN3) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 1000; ++i) {
    const SO3d a = SO3d::sample(rng), b = SO3d::sample(rng);
    const Eigen::Vector3d w = a.log();
    const VectorXd wv = w;
    EXPECT_EQ(SOn::hat(wv), MatrixXd(SO3d::hat(w)));
    EXPECT_LE(max_abs(SOn::exp(wv).matrix() - a.matrix()), kTol);
    const SOn an = SOn::from_matrix(a.matrix()), bn = SOn::from_matrix(b.matrix());
    EXPECT_LE(max_abs(an.log() - w), kTol) << w.transpose();
    EXPECT_LE(max_abs((an * bn).matrix() - (a * b).matrix()), ulps(16));
    EXPECT_LE(max_abs(an.adjoint() - a.adjoint()), ulps(16));
    EXPECT_LE(max_abs(SOn::right_jacobian(wv) - SO3d::right_jacobian(w)), kTol);
    EXPECT_LE(max_abs(SOn::left_jacobian_inverse(wv) - SO3d::left_jacobian_inverse(w)), 1e-10);
  }
}

TEST(SOn, JacobiansMatchCentralDifferences) {
  for (int n : {2, 4, 5}) {
    std::mt19937_64 rng(300 + n);
    for (int i = 0; i < 20; ++i) {
      const VectorXd w = random_omega(n, rng, 3.0);
      const Eigen::Index m = w.size();
      const SOn X = SOn::exp(w);
      const MatrixXd Jr = SOn::right_jacobian(w), Jl = SOn::left_jacobian(w);
      // Central difference, h = 1e-5: truncation ~1e-10, rounding ~1e-11 (see the typed suite).
      const double h = 1e-5;
      for (Eigen::Index j = 0; j < m; ++j) {
        const VectorXd e = VectorXd::Unit(m, j) * h;
        const VectorXd right = ((X.inverse() * SOn::exp(w + e)).log() - (X.inverse() * SOn::exp(w - e)).log()) / (2 * h);
        const VectorXd left = ((SOn::exp(w + e) * X.inverse()).log() - (SOn::exp(w - e) * X.inverse()).log()) / (2 * h);
        ASSERT_LE(max_abs(right - Jr.col(j)), 1e-8) << "n " << n;
        ASSERT_LE(max_abs(left - Jl.col(j)), 1e-8) << "n " << n;
      }
      ASSERT_LE(max_abs(Jl - X.adjoint() * Jr), 1e-12);
      ASSERT_LE(max_abs(SOn::right_jacobian_inverse(w) * Jr - MatrixXd::Identity(m, m)), 1e-11);
    }
  }
}

TEST(SOn, TinyNearPiAndPiAngles) {
  // Planes (0,1) and (2,3) of R⁴, conjugated by a fixed random rotation Q.
  std::mt19937_64 rng(13);
  const SOn Q = SOn::sample(4, rng);
  auto make = [&](double a, double b) {
    MatrixXd W = MatrixXd::Zero(4, 4);
    W(1, 0) = a;
    W(0, 1) = -a;
    W(3, 2) = b;
    W(2, 3) = -b;
    return VectorXd(SOn::vee(Q.matrix() * W * Q.matrix().transpose(), 1e-15));
  };
  // Tiny: absolute accuracy of a few ulps (the Schur route is backward stable, not relatively
  // accurate at 1e-12; SO2 and SO3 are).
  const VectorXd tiny = make(1e-12, -3e-12);
  EXPECT_LE(max_abs(SOn::exp(tiny).log() - tiny), ulps(8));
  // π − 1e-9: atan2 on the 2×2 Schur block keeps the angle to rounding.
  const VectorXd near = make(pi - 1e-9, 0.5);
  const SOn Rn = SOn::exp(near);
  EXPECT_LE(max_abs(Rn.log() - near), 1e-13);
  EXPECT_NEAR(Rn.angles()(0), pi - 1e-9, ulps(16, pi));
  EXPECT_NEAR(Rn.angles()(1), 0.5, ulps(16));
  // Exactly π in two planes (R = −I in R⁴): log is not unique; the one returned must have both
  // angles π and exponentiate back to R.
  const SOn minus = SOn::from_matrix(-MatrixXd::Identity(4, 4));
  const VectorXd lw = minus.log();
  EXPECT_LE(max_abs(SOn::exp(lw).matrix() + MatrixXd::Identity(4, 4)), ulps(32));
  EXPECT_NEAR(minus.angles()(0), pi, ulps(4, pi));
  EXPECT_NEAR(minus.angles()(1), pi, ulps(4, pi));
  // π in one plane of R³ agrees with SO3 up to the sign of the axis.
  const SOn half = SOn::from_matrix(Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix());
  const VectorXd hw = half.log();
  EXPECT_NEAR(hw.norm(), pi, ulps(4, pi));
  EXPECT_NEAR(std::abs(hw(0)), pi, ulps(4, pi));
}

TEST(SOn, SampleHasHaarTraceMoments) {
  // Haar on SO(n), n ≥ 3: E[tr R] = 0 and E[(tr R)²] = 1 (the trivial representation occurs
  // once in R ⊗ R); E[R₀₀²] = 1/n (the first column is uniform on the sphere). Without the sign
  // fix of [Mezzadri2007] the diagonal of Householder QR biases all three.
  for (int n = 3; n <= 6; ++n) {
    std::mt19937_64 rng(400 + n);
    const int N = 4000;
    double t1 = 0, t2 = 0, r00 = 0;
    for (int i = 0; i < N; ++i) {
      const MatrixXd R = SOn::sample(n, rng).matrix();
      const double t = R.trace();
      t1 += t;
      t2 += t * t;
      r00 += R(0, 0) * R(0, 0);
    }
    // σ(tr) = 1, σ(tr²) ≤ √(E tr⁴) ≤ 2 (E tr⁴ ≤ 3 for n ≥ 3), σ(R₀₀²) < 1/2: 5σ/√N is 0.08,
    // 0.16 and 0.04.
    EXPECT_NEAR(t1 / N, 0.0, 0.08) << n;
    EXPECT_NEAR(t2 / N, 1.0, 0.16) << n;
    EXPECT_NEAR(r00 / N, 1.0 / n, 0.04) << n;
  }
}

TEST(SOn, BadInput) {
  MatrixXd M = MatrixXd::Identity(4, 4);
  M(0, 1) = 1e-3;
  EXPECT_RIGID_ERROR((void)SOn::from_matrix(M), "is not a rotation: orthonormality defect max|RᵀR − I| = 0.001");
  M = MatrixXd::Identity(5, 5);
  M(4, 4) = -1;
  EXPECT_RIGID_ERROR((void)SOn::from_matrix(M), "determinant -1 (expected +1)");
  M(2, 2) = std::nan("");
  EXPECT_RIGID_ERROR((void)SOn::from_matrix(M), "has a non-finite entry");
  EXPECT_RIGID_ERROR((void)SOn::from_matrix(M), "from_matrix(): matrix [1, 0, 0, 0, 0; ");
  EXPECT_RIGID_ERROR((void)SOn::from_matrix(MatrixXd::Identity(1, 1)),
                     "matrix is 1x1, expected a square matrix of size n ≥ 2");
  EXPECT_RIGID_ERROR((void)SOn::exp(VectorXd::Zero(4)),
                     "tangent vector has 4 components, expected n(n−1)/2 for some n ≥ 2");
  EXPECT_RIGID_ERROR((void)SOn::exp(VectorXd::Constant(3, NAN)), "has a non-finite component");
  EXPECT_RIGID_ERROR((void)SOn::identity(1), "n = 1, expected n ≥ 2");
  EXPECT_RIGID_ERROR((void)(SOn::identity(3) * SOn::identity(4)), "SO(3) and SO(4) differ");
  EXPECT_RIGID_ERROR((void)(SOn::identity(3) * VectorXd::Zero(2)), "vector has 2 components, expected 3");
  EXPECT_RIGID_ERROR((void)SOn::vee(MatrixXd::Identity(3, 3)), "is not skew-symmetric: max|W + Wᵀ| = 2");
}

TEST(SEn, ExpLogAdjointForNFrom2To8) {
  for (int n = 2; n <= 8; ++n) {
    std::mt19937_64 rng(500 + n);
    for (int i = 0; i < kSamples / 4; ++i) {
      const SEn g = SEn::sample(n, rng);
      ASSERT_LE(max_abs(SEn::exp(g.log()).matrix() - g.matrix()), kTol) << "n " << n;
      const VectorXd xi = random_xi(n, rng, 3.0);
      ASSERT_LE(max_abs(SEn::exp(xi).log() - xi), kTol) << "n " << n << " xi " << xi.transpose();
      const SEn a = SEn::sample(n, rng), b = SEn::sample(n, rng);
      ASSERT_LE(max_abs((a * b).matrix() - a.matrix() * b.matrix()), kTol);
      ASSERT_LE(max_abs((a * a.inverse()).matrix() - MatrixXd::Identity(n + 1, n + 1)), kTol);
      const VectorXd p = VectorXd::Random(n);
      VectorXd ph(n + 1);
      ph << p, 1.0;
      ASSERT_LE(max_abs(a * p - (a.homogeneous() * ph).head(n)), kTol);
      const VectorXd ax = a.adjoint() * xi;
      ASSERT_LE(max_abs((a * SEn::exp(xi) * a.inverse()).matrix() - SEn::exp(ax).matrix()), kTol);
      ASSERT_EQ(SEn::vee(SEn::hat(xi)), xi);
    }
  }
}

TEST(SEn, AgreesWithSE2AndSE3) {
  std::mt19937_64 rng(17);
  for (int i = 0; i < 500; ++i) {
    const SE3d X = SE3d::sample(rng);
    const Eigen::Matrix<double, 6, 1> xi = X.log();
    const VectorXd xv = xi;
    EXPECT_EQ(SEn::hat(xv), MatrixXd(SE3d::hat(xi)));
    EXPECT_LE(max_abs(SEn::exp(xv).matrix() - X.matrix()), kTol);
    EXPECT_LE(max_abs(SEn::from_matrix(X.matrix()).log() - xi), kTol);
    EXPECT_LE(max_abs(SEn::from_matrix(X.matrix()).adjoint() - X.adjoint()), ulps(32));
    EXPECT_LE(max_abs(SEn::left_jacobian(xv) - SE3d::left_jacobian(xi)), kTol);
    EXPECT_LE(max_abs(SEn::right_jacobian_inverse(xv) - SE3d::right_jacobian_inverse(xi)), 1e-10);

    const SE2d Y = SE2d::sample(rng);
    const Eigen::Vector3d eta = Y.log();
    const VectorXd ev = eta;
    EXPECT_EQ(SEn::hat(ev), MatrixXd(SE2d::hat(eta)));
    EXPECT_LE(max_abs(SEn::exp(ev).matrix() - Y.matrix()), kTol);
    EXPECT_LE(max_abs(SEn::from_matrix(Y.matrix()).log() - eta), kTol);
    EXPECT_LE(max_abs(SEn::from_matrix(Y.matrix()).adjoint() - Y.adjoint()), ulps(32));
    EXPECT_LE(max_abs(SEn::right_jacobian(ev) - SE2d::right_jacobian(eta)), kTol);
  }
}

TEST(SEn, BadInput) {
  EXPECT_RIGID_ERROR((void)SEn(SOn::identity(3), VectorXd::Zero(2)),
                     "translation has 2 components, expected 3 for SE(3)");
  EXPECT_RIGID_ERROR((void)SEn(SOn::identity(2), VectorXd::Constant(2, NAN)), "translation [nan, nan] has a non-finite");
  MatrixXd T = MatrixXd::Identity(5, 5);
  T(4, 1) = 2;
  EXPECT_RIGID_ERROR((void)SEn::from_matrix(T), "last row of the homogeneous matrix is [0, 2, 0, 0, 1], expected [0, 0, 0, 0, 1]");
  T = MatrixXd::Identity(5, 5);
  T(0, 0) = 1.5;
  EXPECT_RIGID_ERROR((void)SEn::from_matrix(T), "is not a rotation");
  EXPECT_RIGID_ERROR((void)SEn::exp(VectorXd::Zero(4)), "tangent vector has 4 components, expected n(n+1)/2");
  EXPECT_RIGID_ERROR((void)(SEn::identity(2) * SEn::identity(3)), "SO(2) and SO(3) differ");
}

TEST(SOn, InterpolateRefusesANonFiniteOrHugeFraction) {
  const SOn a = SOn::identity(4);
  const SOn b = SOn::exp(Eigen::VectorXd::Constant(6, 0.1));
  EXPECT_RIGID_ERROR((void)a.interpolate(b, std::nan("")),
                     "SOn::interpolate(): fraction s = nan is not finite");
  EXPECT_RIGID_ERROR((void)a.interpolate(b, 1e300), "turning by at most kMaxAngle");
}

TEST(SEn, InterpolateRefusesANonFiniteFraction) {
  const SEn a = SEn::identity(3);
  const SEn b = SEn::exp(Eigen::VectorXd::Constant(6, 0.1));
  EXPECT_RIGID_ERROR((void)a.interpolate(b, -INFINITY),
                     "SEn::interpolate(): fraction s = -inf is not finite");
}

}  // namespace
}  // namespace rigid
