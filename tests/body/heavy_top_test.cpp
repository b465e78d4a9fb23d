#include "rigid/body/heavy_top.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::body {
namespace {

TEST(HeavyTop, EnergyBoundedAndVerticalMomentumExact) {
  HeavyTop top;
  top.mass = 1.0;
  top.I_B = Eigen::Vector3d(1.0, 1.0, 0.5);
  top.p_PC_B = Eigen::Vector3d(0, 0, 0.1);
  FreeBodyState s;
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()));
  s.w_B = Eigen::Vector3d(0.3, -0.2, 20.0);
  const double E0 = heavy_top_energy(top, s);
  const double Lz0 = (s.q_WB * top.I_B.cwiseProduct(s.w_B)).z();
  const double L30 = top.I_B(2) * s.w_B(2);
  double max_dE = 0;
  for (int i = 0; i < 20000; ++i) {
    s = step_heavy_top(top, s, 1e-3);
    max_dE = std::max(max_dE, std::abs(heavy_top_energy(top, s) - E0));
  }
  const double Lz = (s.q_WB * top.I_B.cwiseProduct(s.w_B)).z();
  // L_z: each sub-flow keeps it exactly; round-off over 2e4 steps × 7 sub-flows.
  EXPECT_NEAR(Lz, Lz0, 1e-11 * std::abs(L30));
  // Second-order symplectic splitting: energy error O(h² |ω|² ...) bounded, no drift.
  EXPECT_LT(max_dE / E0, 1e-4);
  // Symmetric top: L_3 is a constant of the motion; the axis-wise splitting keeps it
  // to O(h²) (the 1- and 2-axis sub-flows exchange L_3 with L_1, L_2).
  EXPECT_NEAR(top.I_B(2) * s.w_B(2), L30, 1e-4 * std::abs(L30));
}

TEST(HeavyTop, FastTopPrecessesAtMgdOverI3Omega3) {
  // Fast-top approximation [Goldstein2002, §5.7]: Ω_p ≈ m g d / (I3 ω3), relative error
  // O(m g d I_t / (I3 ω3)²) = 9.81·0.1·1/(0.5·200)² ≈ 1e-4, plus nutation wobble of the
  // azimuth of amplitude ~ Ω_p/ω_nut ≈ 1e-4 rad over a 1-rad sweep.
  HeavyTop top;
  top.mass = 1.0;
  top.I_B = Eigen::Vector3d(1.0, 1.0, 0.5);
  top.p_PC_B = Eigen::Vector3d(0, 0, 0.1);
  const double w3 = 200.0;
  FreeBodyState s;
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()));
  s.w_B = Eigen::Vector3d(0, 0, w3);
  const double Omega_p = top.mass * 9.81 * 0.1 / (top.I_B(2) * w3);
  const double T = 1.0 / Omega_p;  // sweeps 1 rad
  const int n = 20000;
  double phi = 0, prev = std::atan2((s.q_WB * Eigen::Vector3d::UnitZ()).y(), (s.q_WB * Eigen::Vector3d::UnitZ()).x());
  for (int i = 0; i < n; ++i) {
    s = step_heavy_top(top, s, T / n, FreeBodyMethod::kSplitting4);
    const Eigen::Vector3d axis = s.q_WB * Eigen::Vector3d::UnitZ();
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
  HeavyTop top;
  top.mass = 1.0;
  top.I_B = Eigen::Vector3d(2.0, 2.0, 1.0);
  top.p_PC_B = Eigen::Vector3d(0.5, 0, 0);
  top.g_W = Eigen::Vector3d(0, 0, -2.0);
  const double mu = 1.0 * 2.0 * 0.5;
  auto K = [&](const FreeBodyState& s) {
    const Eigen::Vector3d g = s.q_WB.conjugate() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d& w = s.w_B;
    const double a = w(0) * w(0) - w(1) * w(1) - mu * g(0), b = 2 * w(0) * w(1) - mu * g(1);
    return a * a + b * b;
  };
  auto max_dK = [&](double h) {
    FreeBodyState s;
    s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 0.5).normalized()));
    s.w_B = Eigen::Vector3d(0.7, -0.4, 1.3);
    const double K0 = K(s);
    double m = 0;
    const int n = static_cast<int>(std::lround(10.0 / h));  // 10 s, several tumbles
    for (int i = 0; i < n; ++i) {
      s = step_heavy_top(top, s, h, FreeBodyMethod::kSplitting4);
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
  EXPECT_RIGID_ERROR((void)step_heavy_top(HeavyTop{}, FreeBodyState{}, 0.1, FreeBodyMethod::kRk4),
                     "heavy-top free flow must be a splitting method (splitting2/4/6), got 'rk4'");
}

}  // namespace
}  // namespace rigid::body
