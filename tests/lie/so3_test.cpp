// SO3 and SE3 against closed forms, the hard angles (1e-12, π − 1e-9, π) and bad input.

#include <cmath>
#include <limits>
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

Eigen::Matrix3d rot_z(double t) {
  Eigen::Matrix3d R;
  R << std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t), 0, 0, 0, 1;
  return R;
}

TEST(SO3, ExpAboutZMatchesClosedForm) {
  for (double t : {0.0, 0.3, 1.0, 2.5, pi}) {
    const SO3d R = SO3d::exp(Eigen::Vector3d(0, 0, t));
    EXPECT_LE((R.matrix() - rot_z(t)).cwiseAbs().maxCoeff(), ulps(8)) << t;
    // q = (cos t/2, 0, 0, sin t/2).
    EXPECT_LE((R.quaternion() - Eigen::Vector4d(std::cos(t / 2), 0, 0, std::sin(t / 2))).cwiseAbs().maxCoeff(),
              ulps(4));
  }
}

TEST(SO3, ActRotatesXIntoYAboutZ) {
  const SO3d R = SO3d::from_axis_angle(Eigen::Vector3d(0, 0, 2), pi / 2);
  EXPECT_LE((R * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(0, 1, 0)).cwiseAbs().maxCoeff(), ulps(4));
}

TEST(SO3, TinyAngleRoundTripIsRelativelyAccurate) {
  const Eigen::Vector3d w = Eigen::Vector3d(1, -2, 0.5).normalized() * 1e-12;
  const Eigen::Vector3d back = SO3d::exp(w).log();
  // Relative error a few ulps: the series branch is exact to O(θ²) ≈ 1e-24.
  EXPECT_LE((back - w).norm(), ulps(8, 1e-12));
  EXPECT_LE(std::abs(SO3d::exp(w).angle() - 1e-12), ulps(8, 1e-12));
}

TEST(SO3, NearPiRoundTrip) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.4, 0.866).normalized();
  const double t = pi - 1e-9;
  const Eigen::Vector3d back = SO3d::exp(axis * t).log();
  // Through the quaternion, w = cos(t/2) ≈ 5e-10 is held to 1 ulp of 1, so the angle is
  // good to ~2 ulps of π; an acos-of-trace log would lose ~8 digits here.
  EXPECT_LE((back - axis * t).norm(), 1e-14);
  // Through the matrix (Shepperd), the same accuracy.
  const Eigen::Vector3d via_matrix = SO3d::from_matrix(SO3d::exp(axis * t).matrix()).log();
  EXPECT_LE((via_matrix - axis * t).norm(), 1e-14);
}

TEST(SO3, ExactlyPi) {
  Eigen::Matrix3d R = Eigen::Vector3d(1, -1, -1).asDiagonal();  // rotation by π about x
  const Eigen::Vector3d w = SO3d::from_matrix(R).log();
  EXPECT_NEAR(w.norm(), pi, ulps(4, pi));
  EXPECT_NEAR(std::abs(w(0)), pi, ulps(4, pi));
  EXPECT_EQ(w(1), 0.0);
  EXPECT_EQ(w(2), 0.0);
  // exp of a π rotation vector and back gives ±the same vector (both represent it).
  const Eigen::Vector3d a = Eigen::Vector3d(1, 2, 2) / 3.0 * pi;
  const Eigen::Vector3d b = SO3d::exp(a).log();
  EXPECT_LE(std::min((b - a).norm(), (b + a).norm()), 1e-15 * 8);
  EXPECT_LE((SO3d::exp(b).matrix() - SO3d::exp(a).matrix()).cwiseAbs().maxCoeff(), ulps(16));
}

TEST(SO3, QuaternionAndMatrixRoundTrip) {
  std::mt19937_64 rng(31);
  for (int i = 0; i < 1000; ++i) {
    const SO3d R = SO3d::sample(rng);
    const SO3d back = SO3d::from_matrix(R.matrix());
    EXPECT_TRUE(back.is_approx(R, 1e-14));
    const Eigen::Vector4d q = R.quaternion();
    EXPECT_TRUE(SO3d::from_quaternion(q(0), q(1), q(2), q(3)).is_approx(R, 1e-15));
    // −q is the same rotation.
    EXPECT_TRUE(SO3d::from_quaternion(-q(0), -q(1), -q(2), -q(3)).is_approx(R, 1e-15));
  }
}

TEST(SO3, FromQuaternionNormalises) {
  const SO3d R = SO3d::from_quaternion(2, 0, 0, 0);
  EXPECT_EQ(R.quaternion(), Eigen::Vector4d(1, 0, 0, 0));
}

TEST(SO3, SampleIsHaarUniformInAngleDistribution) {
  // Under the Haar measure the angle θ has density (1 − cos θ)/π on [0, π], so
  // E[θ] = π/2 + 2/π and E[cos θ] = −1/2.
  std::mt19937_64 rng(37);
  const int n = 20000;
  double sum_t = 0, sum_c = 0;
  for (int i = 0; i < n; ++i) {
    const double t = SO3d::sample(rng).angle();
    sum_t += t;
    sum_c += std::cos(t);
  }
  // Standard deviations of θ and cos θ are below 0.7, so 5σ/√n < 0.025.
  EXPECT_NEAR(sum_t / n, pi / 2 + 2 / pi, 0.025);
  EXPECT_NEAR(sum_c / n, -0.5, 0.025);
}

TEST(SO3, BadInput) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  M(0, 1) = 1e-3;
  EXPECT_RIGID_ERROR((void)SO3d::from_matrix(M), "is not a rotation: orthonormality defect max|RᵀR − I| = 0.001");
  EXPECT_RIGID_ERROR((void)SO3d::from_matrix(Eigen::Vector3d(1, 1, -1).asDiagonal().toDenseMatrix()),
                     "determinant -1 (expected +1)");
  M = Eigen::Matrix3d::Identity();
  M(2, 2) = std::nan("");
  EXPECT_RIGID_ERROR((void)SO3d::from_matrix(M), "has a non-finite entry");
  EXPECT_RIGID_ERROR((void)SO3d::from_axis_angle(Eigen::Vector3d::Zero(), 1.0),
                     "axis [0, 0, 0] has norm 0, expected a nonzero axis");
  EXPECT_RIGID_ERROR((void)SO3d::from_axis_angle(Eigen::Vector3d(1, 0, 0), std::nan("")), "angle nan is not finite");
  EXPECT_RIGID_ERROR((void)SO3d::from_quaternion(0, 0, 0, 0), "has norm 0, expected a nonzero quaternion");
  EXPECT_RIGID_ERROR((void)SO3d::from_quaternion(1, std::nan(""), 0, 0), "has a non-finite component");
}

TEST(Orthogonal, ReportsDefectAndDeterminant) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(5, 5);
  M(4, 4) = -1;
  OrthogonalityReport r = check_orthogonal(M);
  EXPECT_TRUE(r.orthogonal);
  EXPECT_FALSE(r.rotation);
  EXPECT_EQ(r.determinant, -1.0);
  EXPECT_EQ(r.defect, 0.0);
  M(0, 0) = 2;  // MᵀM has entry 4 at (0, 0): defect 3
  r = check_orthogonal(M);
  EXPECT_FALSE(r.orthogonal);
  EXPECT_EQ(r.defect, 3.0);
  EXPECT_RIGID_ERROR((void)check_orthogonal(Eigen::MatrixXd::Zero(2, 3)), "matrix is 2x3, expected a non-empty square");
}

TEST(Orthogonal, NearestRotationProjects) {
  std::mt19937_64 rng(41);
  std::normal_distribution<double> g(0.0, 1e-3);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Matrix3d R = SO3d::sample(rng).matrix();
    Eigen::Matrix3d noisy = R;
    for (int k = 0; k < 9; ++k) noisy(k) += g(rng);
    const Eigen::MatrixXd P = nearest_rotation(noisy);
    const OrthogonalityReport r = check_orthogonal(P, 1e-14);
    EXPECT_TRUE(r.rotation) << r.defect << " " << r.determinant;
    // Exact projection of an exact rotation is itself.
    EXPECT_LE((nearest_rotation(R) - R).cwiseAbs().maxCoeff(), 1e-14);
    // The projection is at least as close to the noisy matrix as R is (it is the minimiser).
    EXPECT_LE((P - noisy).norm(), (R - noisy).norm() + 1e-15);
  }
  // A reflection is projected to a proper rotation.
  const Eigen::MatrixXd F = Eigen::Vector3d(1, 1, -1).asDiagonal();
  EXPECT_GT(nearest_rotation(F).determinant(), 0.0);
}

TEST(SE3, ExpOfPureTranslationAndScrew) {
  Eigen::Matrix<double, 6, 1> xi;
  xi << 1, 2, 3, 0, 0, 0;
  const SE3d X = SE3d::exp(xi);
  EXPECT_EQ(X.translation(), Eigen::Vector3d(1, 2, 3));
  // Screw about z through the origin: rotation t, advance v along z: exp((0,0,v,0,0,t)).
  xi << 0, 0, 0.7, 0, 0, 1.3;
  const SE3d S = SE3d::exp(xi);
  EXPECT_LE((S.rotation().matrix() - rot_z(1.3)).cwiseAbs().maxCoeff(), ulps(8));
  EXPECT_LE((S.translation() - Eigen::Vector3d(0, 0, 0.7)).cwiseAbs().maxCoeff(), ulps(8));
}

TEST(SE3, ClosedFormJacobianInversesMatchNumericInverse) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    Eigen::Matrix<double, 6, 1> xi;
    for (int k = 0; k < 6; ++k) xi(k) = u(rng);
    // Angles from 1e-6 (series branch of Q) to 3 (closed form).
    xi.tail<3>() *= std::pow(10.0, -6.0 + 6.5 * 0.5 * (u(rng) + 1.0)) / xi.tail<3>().norm();
    const Eigen::Matrix<double, 6, 6> Jl = SE3d::left_jacobian(xi), Jr = SE3d::right_jacobian(xi);
    // LU of a 6×6 with condition number ≲ 1e2 (|θ| ≤ 3.2): ~1e-14; 1e-12 is the margin.
    EXPECT_LE((SE3d::left_jacobian_inverse(xi) - Jl.inverse()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE((SE3d::right_jacobian_inverse(xi) - Jr.inverse()).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(SO3, TurnAboutABodyAxisIsTheProductWithItsExp) {
  // R.turned_about_axis<i>(sin θ/2, cos θ/2 − 1) = R · exp(θ e_i); both sides from independent
  // code (the increment form vs exp and the Hamilton product). A few ulps.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int k = 0; k < 1000; ++k) {
    const SO3d R = SO3d::sample(rng);
    const double theta = u(rng);
    const double s = std::sin(0.5 * theta), c1 = std::cos(0.5 * theta) - 1.0;
    const SO3d turned[3] = {R.turned_about_axis<0>(s, c1), R.turned_about_axis<1>(s, c1),
                            R.turned_about_axis<2>(s, c1)};
    for (int i = 0; i < 3; ++i) {
      const SO3d expected = R * SO3d::exp(theta * Eigen::Vector3d::Unit(i));
      EXPECT_LT((turned[i].quaternion() - expected.quaternion()).cwiseAbs().maxCoeff(), ulps(8));
    }
  }
}

TEST(SO3, RenormalizedRestoresTheUnitNormQuadratically) {
  // a product of many turns drifts from |q| = 1 by round-off; one Newton step takes a drift δ
  // to O(δ²): after 10⁶ turns (|δ| ~ 1e-13 at most) |q| is 1 to an ulp or two.
  SO3d R = SO3d::identity();
  const double s = std::sin(0.05), c1 = std::cos(0.05) - 1.0;
  for (int k = 0; k < 1'000'000; ++k) R = R.turned_about_axis<1>(s, c1).turned_about_axis<2>(s, c1);
  const double drift = std::abs(R.quaternion().norm() - 1.0);
  const double after = std::abs(R.renormalized().quaternion().norm() - 1.0);
  EXPECT_LE(after, ulps(2));
  EXPECT_LT(after, std::max(drift, ulps(2)));
}

TEST(SO3, QuaternionRateIsTheDerivativeOfRExpTw) {
  // d/dt [R0 exp(t ω)] at t = 0 as a central difference of the quaternion coefficients
  // (h = 1e-5: truncation h²|ω|³/6 ≈ 1e-10, round-off ε/h ≈ 2e-11)
  std::mt19937_64 rng(8);
  for (int k = 0; k < 100; ++k) {
    const SO3d R0 = SO3d::sample(rng);
    const Eigen::Vector3d w(0.7, -1.3, 0.4);
    const double h = 1e-5;
    const Eigen::Vector4d fd =
        ((R0 * SO3d::exp(h * w)).quaternion() - (R0 * SO3d::exp(-h * w)).quaternion()) / (2 * h);
    EXPECT_LT((SO3d::quaternion_rate(R0.quaternion(), w) - fd).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(SO3, InvalidMarksADivergedComputation) {
  const SO3d bad = SO3d::invalid();
  EXPECT_TRUE(std::isnan(bad.w()) && std::isnan(bad.x()) && std::isnan(bad.y()) && std::isnan(bad.z()));
  const SO3d q = SO3d::from_unit_quaternion(0.6, 0.0, 0.8, 0.0);
  EXPECT_EQ(q.y(), 0.8);  // kept as given, not normalised again
}

TEST(SE3, BadInput) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T(3, 0) = 1;
  EXPECT_RIGID_ERROR((void)SE3d::from_matrix(T), "last row of the homogeneous matrix is [1, 0, 0, 1]");
  T = Eigen::Matrix4d::Identity();
  T(0, 3) = std::nan("");
  EXPECT_RIGID_ERROR((void)SE3d::from_matrix(T), "translation [nan, 0, 0] has a non-finite component");
  T = Eigen::Matrix4d::Identity();
  T(0, 0) = 1.1;
  EXPECT_RIGID_ERROR((void)SE3d::from_matrix(T), "is not a rotation");
}

TEST(SO3, ExpRefusesNonFiniteAndMeaninglessRotationVectors) {
  const double nan = std::nan("");
  EXPECT_RIGID_ERROR((void)SO3d::exp(Eigen::Vector3d(0, nan, 0)),
                     "SO3::exp(): rotation vector [0, nan, 0] has a non-finite component");
  EXPECT_RIGID_ERROR((void)SO3d::exp(Eigen::Vector3d(INFINITY, 0, 0)), "non-finite component");
  // |ω|² overflows at 1e200: refused as too long, not returned as NaN
  EXPECT_RIGID_ERROR((void)SO3d::exp(Eigen::Vector3d(1e200, 0, 0)),
                     "rotation vector [1e+200, 0, 0] is too long: angle |ω| = 1e+200 rad, expected "
                     "at most kMaxAngle = 1e+15 rad");
  EXPECT_RIGID_ERROR((void)SO3d::exp(Eigen::Vector3d(0, 0, 1.01e15)), "is too long");
  // the limit itself is accepted, and gives a unit quaternion (|q| = 1 to rounding: 4 ulps)
  const SO3d R = SO3d::exp(Eigen::Vector3d(0, 0, kMaxAngle));
  EXPECT_NEAR(R.quaternion().norm(), 1.0, 4 * std::numeric_limits<double>::epsilon());
}

TEST(SO3, FromAxisAngleRefusesAnAngleBeyondTheLimit) {
  EXPECT_RIGID_ERROR((void)SO3d::from_axis_angle(Eigen::Vector3d::UnitX(), 1e300),
                     "from_axis_angle(): angle 1e+300 rad is too large: expected |angle| <= "
                     "kMaxAngle = 1e+15 rad");
  EXPECT_RIGID_ERROR((void)SO3d::from_axis_angle(Eigen::Vector3d::UnitX(), std::nan("")),
                     "angle nan is not finite");
}

TEST(SO3, InterpolateRefusesANonFiniteOrHugeFraction) {
  const SO3d a = SO3d::identity();
  const SO3d b = SO3d::exp(Eigen::Vector3d(0, 0, 1.0));
  EXPECT_RIGID_ERROR((void)a.interpolate(b, std::nan("")),
                     "SO3::interpolate(): fraction s = nan is not finite, expected a finite s");
  EXPECT_RIGID_ERROR((void)a.interpolate(b, INFINITY), "fraction s = inf is not finite");
  // s · angle = 1e300 rad: beyond kMaxAngle
  EXPECT_RIGID_ERROR((void)a.interpolate(b, 1e300),
                     "SO3::interpolate(): fraction s = 1e+300 gives the tangent s · log(a⁻¹ b) with "
                     "largest entry 1e+300");
  // a finite s far outside [0, 1] stays allowed: the rotation by s rad about z (4 ulps)
  const SO3d far = a.interpolate(b, 7.0);
  EXPECT_NEAR((far.log() - Eigen::Vector3d(0, 0, 7.0 - 2.0 * pi)).norm(), 0.0, 1e-14);
}

TEST(SO3, LogAndAngleRefuseTheInvalidMarker) {
  EXPECT_RIGID_ERROR((void)SO3d::invalid().log(), "SO3::log(): the rotation is SO3::invalid()");
  EXPECT_RIGID_ERROR((void)SO3d::invalid().angle(), "SO3::angle(): the rotation is SO3::invalid()");
}

TEST(SE3, ExpAndInterpolateRefuseNonFiniteInput) {
  Eigen::Matrix<double, 6, 1> xi = Eigen::Matrix<double, 6, 1>::Zero();
  xi(1) = std::nan("");
  EXPECT_RIGID_ERROR((void)SE3d::exp(xi), "SE3::exp(): tangent vector [0, nan, 0, 0, 0, 0] has a "
                                          "non-finite component");
  xi(1) = 0.0;
  xi(4) = 1e200;
  EXPECT_RIGID_ERROR((void)SE3d::exp(xi), "SO3::exp(): rotation vector [0, 1e+200, 0] is too long");
  const SE3d a = SE3d::identity();
  const SE3d b(SO3d::exp(Eigen::Vector3d(0.1, 0, 0)), Eigen::Vector3d(1, 2, 3));
  EXPECT_RIGID_ERROR((void)a.interpolate(b, std::nan("")),
                     "SE3::interpolate(): fraction s = nan is not finite");
  // a translation of 1e308 · 3 overflows: refused, not returned as inf
  EXPECT_RIGID_ERROR((void)a.interpolate(b, 1e308), "expected a finite tangent");
}

}  // namespace
}  // namespace rigid
