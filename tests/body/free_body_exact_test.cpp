#include "rigid/body/free_body_exact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string_view>
#include <vector>

#include <boost/math/special_functions/ellint_1.hpp>
#include <gtest/gtest.h>

#include "rigid/body/euler.hpp"
#include "rigid/body/free_body_integrators.hpp"
#include "support/expect_error.hpp"
#include "support/rotation.hpp"
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
  // Evaluated in long double: in double, 2E·I3 − L² and L² − 2E·I1 lose ≈ 1e-12 of k'²
  // (= 2e-4 here) to cancellation, which would dominate the comparison.
  const Eigen::Vector3d I(1, 2, 3), w0(0.01, 1, 0.01);
  const long double Il[3] = {1, 2, 3}, wl[3] = {0.01L, 1, 0.01L};
  long double E2 = 0, L2 = 0;
  for (int i = 0; i < 3; ++i) {
    E2 += Il[i] * wl[i] * wl[i];
    L2 += Il[i] * Il[i] * wl[i] * wl[i];
  }
  ASSERT_GT(L2, E2 * Il[1]);
  const long double lambda = std::sqrt((Il[2] - Il[1]) * (L2 - E2 * Il[0]) / (Il[0] * Il[1] * Il[2]));
  const long double k =
      std::sqrt((Il[1] - Il[0]) * (E2 * Il[2] - L2) / ((Il[2] - Il[1]) * (L2 - E2 * Il[0])));
  const double T = static_cast<double>(4.0L * boost::math::ellint_1(k) / lambda);
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
  // the one validity check of rigid::MassProperties (check_rotational_moments)
  EXPECT_RIGID_ERROR(FreeBodyExact(Eigen::Vector3d(1, -2, 3), Eigen::Vector3d::Ones()),
                     "not positive semidefinite");
  EXPECT_RIGID_ERROR(FreeBodyExact(Eigen::Vector3d(1, 1, 3), Eigen::Vector3d::Ones()),
                     "violate I₁ + I₂ ≥ I₃ by 1 kg·m²");
  EXPECT_RIGID_ERROR(FreeBodyExact(Eigen::Vector3d(0, 1, 1), Eigen::Vector3d::Ones()),
                     "include a zero moment");
  EXPECT_RIGID_ERROR(FreeBodyExact(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(NAN, 0, 0)),
                     "initial body angular velocity must be finite");
}

// ---------------------------------------------------------------------------
// FreeBodyMotion: closed-form orientation.

// Rotation angle (rad) between two rotations (the expected ones are built on Eigen's
// quaternion and AngleAxis, independently of rigid::SO3).
double angle_between(const SO3d& a, const SO3d& b) { return test::angle_between(a, b); }
double angle_between(const SO3d& a, const Eigen::Quaterniond& b) {
  return test::angle_between(a, test::from_eigen(b));
}

struct MotionCase {
  const char* name;
  Eigen::Vector3d I, w0;
};

std::vector<MotionCase> motion_cases() {
  const double r3 = std::sqrt(3.0);
  return {
      {"racket L2>2EI2", {1, 2, 3}, {0.01, 1, 0.01}},
      {"racket L2<2EI2", {1, 2, 3}, {0.01, 1, 0.001}},
      {"generic dn axis 3", {1, 2, 3}, {0.3, 0.2, 0.9}},
      {"generic dn axis 1, negative", {1, 2, 3}, {-0.7, 0.4, -0.2}},
      {"unsorted even", {3, 1, 2}, {0.2, 0.01, 1.0}},
      {"unsorted odd", {2, 1, 3}, {0.5, 0.3, -0.4}},
      {"near separatrix +", {1, 2, 3}, {r3 * 0.1 * (1 + 1e-9), 0.5, 0.1}},
      {"near separatrix -", {1, 2, 3}, {r3 * 0.1 * (1 - 1e-9), 0.5, 0.1}},
      {"separatrix", {1, 2, 3}, {r3 * 0.1, 0.0, 0.1}},
      {"symmetric oblate", {2, 2, 3}, {0.5, 0.3, 0.4}},
      {"symmetric prolate", {1, 2, 2}, {0.5, 0.3, 0.4}},
      {"symmetric, spin on axis", {2, 2, 3}, {0, 0, 0.7}},
      {"sphere", {2, 2, 2}, {0.5, 0.3, 0.4}},
      {"steady middle axis", {1, 2, 3}, {0, 1, 0}},
      {"steady axis 1", {1, 2, 3}, {0.8, 0, 0}},
  };
}

const SO3d kQ0 = SO3d::from_quaternion(0.3, -0.5, 0.7, 0.4);

TEST(FreeBodyMotion, OrientationSatisfiesTheKinematicEquation) {
  // Ṙ = R ω̂ checked by a central difference of the orientation itself:
  // 2 vec(q(t−h)⁻¹ q(t+h)) / (2h) = ω_B(t) + O(h² (|ω̈| + |ω|³)); with h = 1e-4 and
  // |ω|, |ω̈| ≲ 1.2 the truncation is ≲ 1e-8 and the round-off ≈ 10 ε / h ≈ 2e-11.
  const double h = 1e-4;
  for (const MotionCase& c : motion_cases()) {
    const FreeBodyMotion motion(c.I, kQ0, c.w0);
    for (double t : {0.0, 0.9, -3.7, 14.2, 61.0, -250.5}) {
      const SO3d dq = motion.orientation(t - h).inverse() * motion.orientation(t + h);
      const Eigen::Vector3d w_fd = (dq.w() >= 0 ? 1.0 : -1.0) * Eigen::Vector3d(dq.x(), dq.y(), dq.z()) / h;
      EXPECT_LT((w_fd - motion.omega_body(t)).lpNorm<Eigen::Infinity>(), 1e-8)
          << c.name << " t = " << t << " fd " << w_fd.transpose() << " exact "
          << motion.omega_body(t).transpose();
    }
  }
}

TEST(FreeBodyMotion, WorldAngularMomentumIsConstant) {
  for (const MotionCase& c : motion_cases()) {
    const FreeBodyMotion motion(c.I, kQ0, c.w0);
    const Eigen::Vector3d L0 = kQ0 * c.I.cwiseProduct(c.w0);
    for (double t : {0.0, 0.37, 5.0, -11.0, 99.0, 1000.0, -3000.0}) {
      const FreeBodyState s = motion.state(t);
      const Eigen::Vector3d L = s.R_WB * c.I.cwiseProduct(s.w_B);
      // A handful of rounded products (quaternion composition, Q from l): ≲ 50 ε.
      EXPECT_LT((L - L0).norm(), 1e-12 * L0.norm() + 1e-300) << c.name << " t = " << t;
    }
  }
}

TEST(FreeBodyMotion, IsAFlow) {
  // φ_{t1+t2} = φ_{t2} ∘ φ_{t1}: a motion restarted from the state at t1 reaches the
  // state at t1 + t2 (the restart has a new phase u0, a new M and new reductions).
  for (const MotionCase& c : motion_cases()) {
    const FreeBodyMotion motion(c.I, kQ0, c.w0);
    for (const auto& [t1, t2] : {std::pair{700.0, -650.3}, std::pair{-12.5, 31.0}}) {
      // On the separatrix the state at t1 = 700 is the unstable equilibrium to within
      // sech(70) ≈ 1e-30: restarting from it and running back cannot recover the orbit.
      if (std::string_view(c.name) == "separatrix" && t1 > 100) continue;
      const FreeBodyState s1 = motion.state(t1);
      const FreeBodyMotion restarted(c.I, s1.R_WB, s1.w_B);
      // The motion near the separatrix amplifies the restart's rounding of ω(t1)
      // (≈ 1e-15) by up to e^{λ|t|}-like factors over a flip; 1e-9 rad bounds it here.
      EXPECT_LT(angle_between(restarted.orientation(t2), motion.orientation(t1 + t2)), 1e-9)
          << c.name << " t1 = " << t1 << " t2 = " << t2;
      EXPECT_LT((restarted.omega_body(t2) - motion.omega_body(t1 + t2)).lpNorm<Eigen::Infinity>(), 1e-9)
          << c.name;
    }
  }
}

TEST(FreeBodyMotion, AgreesWithSixthOrderSplittingOver100s) {
  // Independent reference: Yoshida-6 splitting (each sub-flow an exact rotation about a
  // body axis) at h = 1e-2: truncation ≈ 1e-12; the splitting's own round-off, amplified
  // by the flips, is what limits the agreement: over h = 1e-2 … 1e-3 its deviation from
  // the exact solution wanders between 1e-10 and 3e-9 (measured), 1e-9 at h = 1e-2.
  const double h = 1e-2;
  for (const MotionCase& c : {MotionCase{"racket L2>2EI2", {1, 2, 3}, {0.01, 1, 0.01}},
                              MotionCase{"racket L2<2EI2", {1, 2, 3}, {0.01, 1, 0.001}},
                              MotionCase{"unsorted odd", {2, 1, 3}, {0.5, 0.3, -0.4}}}) {
    const FreeBodyMotion motion(c.I, kQ0, c.w0);
    FreeBodyState s{kQ0, c.w0};
    double max_angle = 0, max_w = 0;
    for (int i = 1; i <= 10000; ++i) {
      s = step_free_body(FreeBodyMethod::kSplitting6, c.I, s, h);
      if (i % 50 == 0) {
        const FreeBodyState e = motion.state(h * i);
        max_angle = std::max(max_angle, angle_between(e.R_WB, s.R_WB));
        max_w = std::max(max_w, (e.w_B - s.w_B).lpNorm<Eigen::Infinity>());
      }
    }
    EXPECT_LT(max_angle, 1e-9) << c.name;
    EXPECT_LT(max_w, 1e-9) << c.name;
  }
}

TEST(FreeBodyMotion, SymmetricTopMatchesTheAnalyticPrecession) {
  // [Landau1976, §33]: R(t) = exp(t L_W/I1 ^) R0 exp(t ν ê3), ν = (1/I3 − 1/I1) L3:
  // the symmetry axis precesses about L_W at |L|/I1 while the body spins at ν about it.
  // Differentiating: R⁻¹Ṙ = (Rᵀ L_W/I1 + ν e3)^ = (L_B/I1 + ν e3)^ = ω_B^.
  const Eigen::Vector3d I(2, 2, 3), w0(0.5, -0.2, 0.4);
  const FreeBodyMotion motion(I, kQ0, w0);
  const Eigen::Vector3d L_W = kQ0 * I.cwiseProduct(w0);
  const double nu = (1.0 / I(2) - 1.0 / I(0)) * I(2) * w0(2);
  for (double t : {0.5, 7.0, -40.0, 300.0}) {
    const Eigen::Quaterniond expected =
        Eigen::Quaterniond(Eigen::AngleAxisd(t * L_W.norm() / I(0), L_W.normalized())) * test::to_eigen(kQ0) *
        Eigen::Quaterniond(Eigen::AngleAxisd(t * nu, Eigen::Vector3d::UnitZ()));
    // Angles up to ~130 rad are rounded to ≈ 130 ε each.
    EXPECT_LT(angle_between(motion.orientation(t), expected), 1e-12) << "t = " << t;
  }
}

TEST(FreeBodyMotion, SphereAndPermanentRotationsTurnUniformly) {
  for (const auto& [I, w0] : {std::pair{Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(0.5, 0.3, 0.4)},
                              std::pair{Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0, 1, 0)},
                              std::pair{Eigen::Vector3d(3, 1, 2), Eigen::Vector3d(0, 0, -2)}}) {
    const FreeBodyMotion motion(I, kQ0, w0);
    for (double t : {1.0, -20.0, 100.0}) {
      const Eigen::Quaterniond expected =
          test::to_eigen(kQ0) * Eigen::Quaterniond(Eigen::AngleAxisd(t * w0.norm(), w0.normalized()));
      EXPECT_LT(angle_between(motion.orientation(t), expected), 1e-12) << "t = " << t;
      EXPECT_EQ(motion.omega_body(t), w0);
    }
  }
  // At rest the orientation stays put.
  const FreeBodyMotion rest(Eigen::Vector3d(1, 2, 3), kQ0, Eigen::Vector3d::Zero());
  EXPECT_LT(angle_between(rest.orientation(50.0), kQ0), ulps(4));
}

}  // namespace

// Reaches FreeBodyMotion's reference path: Π(n; am u, k) by Carlson's R_F and R_J (the
// implementation before the theta form), everything else shared.
struct FreeBodyMotionPeer {
  static SO3d orientation_carlson(const FreeBodyMotion& m, double t) {
    return m.orientation_impl(t, true);
  }
};

namespace {

TEST(FreeBodyMotion, ThetaFormAgreesWithTheCarlsonReference) {
  // The two paths differ only in Π(n; am u, k): theta phase vs Carlson R_F/R_J, each
  // accurate to a few ε of Π (jacobi_elliptic_test checks the theta form against Boost).
  // ψ = |L| t/I_d + |L|(I_d − I_c)/(I_c I_d λ) (Π(u) − Π(u0)) is summed in a different
  // order, so the paths may differ by an ulp or two of ψ, |ψ| ≤ |L| |t| / I_min (the
  // precession rate lies between |L|/I_max and |L|/I_min [Landau1976, §37]):
  // tolerance 1e-13 (≈ 450 ε, the 1e-12 goal with margin) + 4 ε |L| |t| / I_min.
  std::vector<MotionCase> cases = motion_cases();
  cases.push_back({"almost symmetric, I_d → I2 (n → −∞)", {1, 2, 2 + 1e-7}, {0.3, 0.2, 0.9}});
  cases.push_back({"almost symmetric, I_c → I2 (n → 0)", {2, 2 + 2e-7, 3}, {0.3, 0.2, 0.9}});
  cases.push_back({"k² just above ½", {1, 2, 3}, {0.5, 0.6, 0.45}});
  cases.push_back({"fast, far from the separatrix", {0.2, 1.5, 1.6}, {2.0, -3.0, 7.0}});
  for (const MotionCase& c : cases) {
    const FreeBodyMotion motion(c.I, kQ0, c.w0);
    const double psi_rate_max = c.I.cwiseProduct(c.w0).norm() / c.I.minCoeff();
    std::vector<double> times;
    for (double t = 0.0; t <= 100.0; t += 0.0625) times.push_back(t);      // the goal's range
    for (double t = -3000.0; t <= 3000.0; t += 0.37 + std::abs(t) * 0.01) times.push_back(t);
    for (double t : times) {
      const double tol = 1e-13 + 4.0 * test::kEps * psi_rate_max * std::abs(t);
      EXPECT_LT(angle_between(motion.orientation(t), FreeBodyMotionPeer::orientation_carlson(motion, t)),
                tol)
          << c.name << " k = " << motion.omega_solution().modulus() << " t = " << t;
    }
  }
}

TEST(FreeBodyMotion, OrientationMatchesA40DigitReference) {
  // Expected q_WB(t) (q0 = identity) from an independent 40-digit evaluation of the same
  // closed form in mpmath (ellipk, ellipf, ellippi, ellipfun; R = M R_z(ψ) Qᵀ converted to a
  // quaternion), with the inputs taken as the exact doubles below. The only error left is
  // double rounding, dominated by that of ψ (|ψ| ≤ |L| t / I_min ≈ 200 rad here): 16 ε |ψ|max
  // ≈ 7e-13 at t = 100 s, inside the 1e-12 goal (measured worst 2e-14 … 5e-14 over
  // t ∈ [0, 100] on a 0.25 s grid for these cases).
  struct Sample {
    double t;
    std::array<double, 4> q;  // (w, x, y, z)
  };
  struct RefCase {
    const char* name;
    Eigen::Vector3d I, w0;
    std::vector<Sample> samples;
  };
  const std::vector<RefCase> cases = {
      {"racket L2>2EI2 (k² = 0.9998)", {1, 2, 3}, {0.01, 1, 0.01},
       {{7.25, {0.87975635112971120886, -0.11170362141647180627, 0.4621033318765421268, -0.0034020990550226099637}},
        {61.0, {0.015140657483268891172, -0.79111158861425858338, -0.000025558495571408451547, 0.61148443495968213139}},
        {100.0, {0.015646241514854160381, -0.96543957427426947671, 0.000079716094039754726965, 0.26015690880105512902}}}},
      {"dn axis 1 (k² = 0.43, real nome)", {1, 2, 3}, {-0.7, 0.4, -0.2},
       {{7.25, {0.58747321357392217274, -0.26316207877775510176, -0.51326481908455300718, -0.56760916933802303933}},
        {61.0, {0.97898270018869057931, 0.031073186226388735755, 0.11029159691065934332, -0.16871008707216405834}},
        {100.0, {0.44314418597147576446, 0.57655162433619450276, -0.47605881769216273976, -0.49454975180715025153}}}},
      {"k² = 0.63 (imaginary transformation)", {1, 2, 3}, {0.5, 0.6, 0.45},
       {{7.25, {0.63585759193308901648, -0.6183908819294036124, 0.24092759588411403988, -0.39399458558351875662}},
        {61.0, {0.46091900178746061473, -0.21631631139943129265, 0.50873961417199896497, 0.69422253794148802463}},
        {100.0, {0.97901312844042153508, 0.11751555813095256937, 0.071501290630387323472, -0.15036938975954607439}}}},
  };
  for (const RefCase& c : cases) {
    const FreeBodyMotion motion(c.I, SO3d::identity(), c.w0);
    const double psi_max = c.I.cwiseProduct(c.w0).norm() / c.I.minCoeff() * 100.0;
    for (const Sample& smp : c.samples) {
      const Eigen::Quaterniond expected(smp.q[0], smp.q[1], smp.q[2], smp.q[3]);
      EXPECT_LT(angle_between(motion.orientation(smp.t), expected), ulps(16, psi_max))
          << c.name << " t = " << smp.t;
    }
  }
}

TEST(FreeBodyMotion, RejectsNonPhysicalMoments) {
  EXPECT_RIGID_ERROR(FreeBodyMotion(Eigen::Vector3d(1, 2, 5), SO3d::identity(), Eigen::Vector3d(0, 1, 0)),
                     "violate I₁ + I₂ ≥ I₃ by 2 kg·m²");
}

TEST(FreeBodyMotion, AnyBodyFrameThroughMassProperties) {
  // The same body described in a frame B turned by R_BP0 from its principal frame: its inertia
  // about the COM is R I_P Rᵀ (full). The MassProperties form must give R_WB(t) = R_WP(t) R_BP0ᵀ
  // and ω_B = R_BP0 ω_P of the principal-frame motion; the principal axes that MassProperties
  // picks may differ from R_BP0 by relabelling, which the closed form absorbs.
  const Eigen::Vector3d I_P(1, 2, 3), w_P(0.4, -0.3, 0.8);
  const SO3d R_BP0 = SO3d::exp(Eigen::Vector3d(0.3, -1.1, 0.7));
  const Eigen::Matrix3d I_B = R_BP0.matrix() * I_P.asDiagonal() * R_BP0.matrix().transpose();
  const MassProperties mass_B(2.0, Eigen::Vector3d(0.1, 0.2, 0.3), I_B);
  const FreeBodyMotion principal(I_P, kQ0 * R_BP0, w_P);
  const FreeBodyMotion general(mass_B, kQ0, R_BP0 * w_P);
  for (double t : {0.0, 3.3, 47.0}) {
    // a few rounded rotations of the inputs, amplified by the motion over ~50 s: 1e-11
    EXPECT_LT(angle_between(general.orientation(t), principal.orientation(t) * R_BP0.inverse()), 1e-11)
        << "t = " << t;
    EXPECT_LT((general.omega_body(t) - R_BP0 * principal.omega_body(t)).norm(), 1e-11) << "t = " << t;
  }
}

TEST(FreeBodyExact, RefusesANonFiniteOrTooDistantTime) {
  const FreeBodyExact e(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 0.5, 0.2));
  ASSERT_EQ(e.solution_case(), FreeBodyCase::kAsymmetric);
  EXPECT_RIGID_ERROR((void)e.omega_body(std::nan("")),
                     "omega_body(): time t = nan s is not finite, expected a finite time");
  EXPECT_RIGID_ERROR((void)e.omega_body(-INFINITY), "time t = -inf s is not finite");
  EXPECT_RIGID_ERROR((void)e.omega_body(1e300),
                     "omega_body(): time t = 1e+300 s is too far: the phase of ω(t) there is");
  // below max_time the result is finite (the energy is conserved to rounding of the phase)
  ASSERT_TRUE(std::isfinite(e.max_time()));
  EXPECT_TRUE(e.omega_body(0.5 * e.max_time()).allFinite());
  EXPECT_RIGID_ERROR((void)e.omega_body(2.0 * e.max_time()), "is too far");
  // constant ω (a sphere): every finite time is accepted
  const FreeBodyExact sphere(Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(sphere.max_time(), INFINITY);
  EXPECT_EQ(sphere.omega_body(1e300), Eigen::Vector3d(0, 0, 1));
}

TEST(FreeBodyExact, RefusesAMotionWhoseEnergyOverflows) {
  EXPECT_RIGID_ERROR(FreeBodyExact(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1e200, 0, 0)),
                     "FreeBodyExact(): initial body angular velocity [1e+200, 0, 0] rad/s with "
                     "principal moments [1, 2, 3] kg·m² overflows");
}

TEST(FreeBodyMotion, OrientationRefusesANonFiniteOrTooDistantTime) {
  // before the check, t = 1e300 reached an internal assertion on a NaN quaternion
  const FreeBodyMotion m(Eigen::Vector3d(1, 2, 3), SO3d::identity(), Eigen::Vector3d(1, 0.5, 0.2));
  EXPECT_RIGID_ERROR((void)m.orientation(std::nan("")), "orientation(): time t = nan s is not finite");
  EXPECT_RIGID_ERROR((void)m.orientation(1e300), "orientation(): time t = 1e+300 s is too far");
  EXPECT_RIGID_ERROR((void)m.state(1e300), "time t = 1e+300 s is too far");
  EXPECT_RIGID_ERROR((void)m.omega_body(std::nan("")), "omega_body(): time t = nan s is not finite");
  // a uniform rotation (sphere) at 1 rad/s: refused once it has turned beyond kMaxAngle
  const FreeBodyMotion sphere(Eigen::Vector3d(2, 2, 2), SO3d::identity(), Eigen::Vector3d(0, 0, 1));
  EXPECT_RIGID_ERROR((void)sphere.orientation(2e15),
                     "orientation(): time t = 2000000000000000 s is too far: the body has turned by 2e+15 rad");
  // the symmetric top: its precession angle grows without bound
  const FreeBodyMotion top(Eigen::Vector3d(1, 1, 2), SO3d::identity(), Eigen::Vector3d(0.3, 0, 1));
  EXPECT_RIGID_ERROR((void)top.orientation(1e300), "is too far");
  EXPECT_NEAR(top.orientation(1e3).quaternion().norm(), 1.0, 1e-15);  // |q| = 1 to 4 ulps
}

}  // namespace
}  // namespace rigid::body
