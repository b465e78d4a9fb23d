#include "rigid/body/heavy_top.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "support/expect_error.hpp"
#include "support/rotation.hpp"

namespace rigid::body {
namespace {

using test::from_eigen;

// A top with mass m whose inertia about the pivot (at B's origin) is diag(I_pivot) and whose
// COM is at p_PC from it: the inertia about the COM follows from the parallel-axis theorem,
// I_C = I_P − m (|d|² 1 − d dᵀ).
HeavyTop make_top(double m, const Eigen::Vector3d& I_pivot, const Eigen::Vector3d& p_PC,
                  const Eigen::Vector3d& g = Eigen::Vector3d(0, 0, -9.81)) {
  const Eigen::Matrix3d I_C = Eigen::Matrix3d(I_pivot.asDiagonal()) -
                              m * (p_PC.squaredNorm() * Eigen::Matrix3d::Identity() - p_PC * p_PC.transpose());
  return HeavyTop(MassProperties(m, p_PC, I_C), Eigen::Vector3d::Zero(), g);
}

TEST(HeavyTop, EnergyBoundedAndVerticalMomentumExact) {
  const Eigen::Vector3d I(1.0, 1.0, 0.5);
  const HeavyTop top = make_top(1.0, I, Eigen::Vector3d(0, 0, 0.1));
  FreeBodyState s;
  s.R_WB = SO3d::exp(Eigen::Vector3d(0.5, 0, 0));
  s.w_B = Eigen::Vector3d(0.3, -0.2, 20.0);
  const double E0 = top.energy(s);
  const double Lz0 = (s.R_WB * I.cwiseProduct(s.w_B)).z();
  const double L30 = I(2) * s.w_B(2);
  double max_dE = 0;
  for (int i = 0; i < 20000; ++i) {
    s = top.step(s, 1e-3);
    max_dE = std::max(max_dE, std::abs(top.energy(s) - E0));
  }
  const double Lz = (s.R_WB * I.cwiseProduct(s.w_B)).z();
  // L_z: each sub-flow keeps it exactly; round-off over 2e4 steps × 7 sub-flows.
  EXPECT_NEAR(Lz, Lz0, 1e-11 * std::abs(L30));
  // Second-order symplectic splitting: energy error O(h² |ω|² ...) bounded, no drift.
  EXPECT_LT(max_dE / E0, 1e-4);
  // Symmetric top: L_3 is a constant of the motion; the axis-wise splitting keeps it
  // to O(h²) (the 1- and 2-axis sub-flows exchange L_3 with L_1, L_2).
  EXPECT_NEAR(I(2) * s.w_B(2), L30, 1e-4 * std::abs(L30));
}

TEST(HeavyTop, FastTopPrecessesAtMgdOverI3Omega3) {
  // Fast-top approximation [Goldstein2002, §5.7]: Ω_p ≈ m g d / (I3 ω3), relative error
  // O(m g d I_t / (I3 ω3)²) = 9.81·0.1·1/(0.5·200)² ≈ 1e-4, plus nutation wobble of the
  // azimuth of amplitude ~ Ω_p/ω_nut ≈ 1e-4 rad over a 1-rad sweep.
  const HeavyTop top = make_top(1.0, Eigen::Vector3d(1.0, 1.0, 0.5), Eigen::Vector3d(0, 0, 0.1));
  const double w3 = 200.0;
  FreeBodyState s;
  s.R_WB = SO3d::exp(Eigen::Vector3d(0.4, 0, 0));
  s.w_B = Eigen::Vector3d(0, 0, w3);
  const double Omega_p = top.mass() * 9.81 * 0.1 / (0.5 * w3);
  const double T = 1.0 / Omega_p;  // sweeps 1 rad
  const int n = 20000;
  double phi = 0, prev = std::atan2((s.R_WB * Eigen::Vector3d::UnitZ()).y(), (s.R_WB * Eigen::Vector3d::UnitZ()).x());
  for (int i = 0; i < n; ++i) {
    s = top.step(s, T / n, FreeBodyMethod::kSplitting4);
    const Eigen::Vector3d axis = s.R_WB * Eigen::Vector3d::UnitZ();
    const double a = std::atan2(axis.y(), axis.x());
    double d = a - prev;
    if (d > M_PI) d -= 2 * M_PI;
    if (d < -M_PI) d += 2 * M_PI;
    phi += d;
    prev = a;
  }
  EXPECT_NEAR(phi / T, Omega_p, 2e-3 * Omega_p);
}

TEST(HeavyTop, KovalevskayaCaseConservesItsIntegral) {
  // I = (2, 2, 1), COM on body axis 1 at distance d, μ = m g d. With γ = R_WBᵀ e_z and
  // Euler's equations 2ω̇1 = ω2ω3, 2ω̇2 = −ω1ω3 + μγ3, ω̇3 = −μγ2, γ̇ = γ × ω, the
  // Kovalevskaya integral K = (ω1² − ω2² − μγ1)² + (2ω1ω2 − μγ2)² has dK/dt = 0
  // (checked symbolically by hand/CAS, independent of this code).
  const HeavyTop top = make_top(1.0, Eigen::Vector3d(2.0, 2.0, 1.0), Eigen::Vector3d(0.5, 0, 0),
                                Eigen::Vector3d(0, 0, -2.0));
  const double mu = 1.0 * 2.0 * 0.5;
  auto K = [&](const FreeBodyState& s) {
    const Eigen::Vector3d g = s.R_WB.inverse() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d& w = s.w_B;
    const double a = w(0) * w(0) - w(1) * w(1) - mu * g(0), b = 2 * w(0) * w(1) - mu * g(1);
    return a * a + b * b;
  };
  auto max_dK = [&](double h) {
    FreeBodyState s;
    s.R_WB = SO3d::from_axis_angle(Eigen::Vector3d(1, 2, 0.5), 1.0);
    s.w_B = Eigen::Vector3d(0.7, -0.4, 1.3);
    const double K0 = K(s);
    double m = 0;
    const int n = static_cast<int>(std::lround(10.0 / h));  // 10 s, several tumbles
    for (int i = 0; i < n; ++i) {
      s = top.step(s, h, FreeBodyMethod::kSplitting4);
      m = std::max(m, std::abs(K(s) - K0) / K0);
    }
    return m;
  };
  // The kick–drift–kick splitting is 2nd order overall, so K is kept to O(h²): the
  // deviation must fall by 4 when h halves (a wrong integral would not converge to 0).
  const double e1 = max_dK(2e-3), e2 = max_dK(1e-3);
  EXPECT_LT(e1, 1e-5);
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.3) << "e(h) = " << e1 << ", e(h/2) = " << e2;
}

TEST(HeavyTop, RejectsNonSplittingFreeFlow) {
  const HeavyTop top = make_top(1.0, Eigen::Vector3d(1, 1, 0.5), Eigen::Vector3d(0, 0, 0.1));
  EXPECT_RIGID_ERROR((void)top.step(FreeBodyState{}, 0.1, FreeBodyMethod::kRk4),
                     "heavy top: the free flow around a torque kick must be a splitting method "
                     "(splitting2, splitting4 or splitting6), got 'rk4'");
}

TEST(HeavyTop, TakesMassPropertiesInAnyFrame) {
  // The same top described in a frame B turned by R from the frame A of make_top: I_C and the
  // COM rotate with it, the pivot stays at the origin. Stepping in B (whose inertia about the
  // pivot is full, so the free flow runs in its principal frame) must reproduce the motion in
  // A: R_WB = R_WA R, ω_B = Rᵀ ω_A.
  // moments ascending, so that A's own axes and B's principal axes order them alike (the
  // splitting then turns about the same physical axes in the same order, up to signs)
  const Eigen::Vector3d I(0.5, 1.0, 1.3), p(0.02, -0.01, 0.1);
  const HeavyTop top_A = make_top(1.0, I, p);
  const SO3d R = SO3d::exp(Eigen::Vector3d(0.4, -0.9, 0.3));
  const Eigen::Matrix3d I_C_A = top_A.inertia_about_pivot() -
                                (p.squaredNorm() * Eigen::Matrix3d::Identity() - p * p.transpose());
  const MassProperties mass_B(1.0, R.inverse() * p, R.matrix().transpose() * I_C_A * R.matrix());
  const HeavyTop top_B(mass_B, Eigen::Vector3d::Zero());
  FreeBodyState a{SO3d::exp(Eigen::Vector3d(0.3, 0.1, 0)), Eigen::Vector3d(0.5, -0.4, 12.0)};
  FreeBodyState b{a.R_WB * R, R.inverse() * a.w_B};
  for (int i = 0; i < 2000; ++i) {
    a = top_A.step(a, 1e-3, FreeBodyMethod::kSplitting4);
    b = top_B.step(b, 1e-3, FreeBodyMethod::kSplitting4);
  }
  // the principal axes of A and B are the same physical axes up to sign and the round-off of the
  // eigenvectors (~1e-15): the runs differ by round-off amplified over 2 s of a fast top, far
  // below the O(h²) = 1e-6 of a wrong change of frame
  EXPECT_LT(test::angle_between(b.R_WB, a.R_WB * R), 1e-9);
  EXPECT_LT((b.w_B - R.inverse() * a.w_B).norm(), 1e-8);
  EXPECT_NEAR(top_B.energy(b), top_A.energy(a), 1e-10 * std::abs(top_A.energy(a)));
}

TEST(HeavyTop, RefusesAMomentlessAxisAndDivergence) {
  // a thin rod pivoted at its end, along z: no moment about z
  EXPECT_RIGID_ERROR(HeavyTop(MassProperties(1.0, Eigen::Vector3d(0, 0, 0.5),
                                             Eigen::Vector3d(1.0 / 12, 1.0 / 12, 0).asDiagonal().toDenseMatrix()),
                              Eigen::Vector3d::Zero()),
                     "HeavyTop: inertia about the pivot: principal moments");
  const HeavyTop top = make_top(1.0, Eigen::Vector3d(1, 1, 0.5), Eigen::Vector3d(0, 0, 0.1));
  FreeBodyState s{SO3d::identity(), Eigen::Vector3d(0, 0, std::nan(""))};
  EXPECT_RIGID_ERROR((void)top.simulate(s, 0.01, {1.0}), "the initial state is not finite: w_B.z = nan");
}

}  // namespace
}  // namespace rigid::body

namespace rigid::body {
namespace {

TEST(HeavyTop, OverflowingStateIsRefusedDuringTheRun) {
  // ω ≈ 1e308 rad/s about every axis: finite, but the sub-flows' angles and L = I ω overflow in
  // the first step; the march names the component and t
  const HeavyTop top = make_top(1.0, Eigen::Vector3d(1, 1, 0.5), Eigen::Vector3d(0, 0, 0.1));
  const FreeBodyState s{SO3d::identity(), Eigen::Vector3d::Constant(1e308)};
  EXPECT_RIGID_ERROR((void)top.simulate(s, 0.01, {1.0}, FreeBodyMethod::kSplitting2),
                     "non-finite state at step 1, t = 0.01 s");
}

}  // namespace
}  // namespace rigid::body
