#include "rigid/body/free_body_integrators.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "rigid/body/free_body_exact.hpp"
#include "support/expect_error.hpp"
#include "support/rotation.hpp"
#include "support/tolerance.hpp"

namespace rigid::body {
namespace {

using test::angle_between;
using test::from_eigen;
using test::to_eigen;
using test::ulps;

const Eigen::Vector3d kI(1, 2, 3);
const Eigen::Vector3d kW0(0.01, 1, 0.01);  // tennis racket

double omega_error(FreeBodyMethod m, double h, double t_end) {
  FreeBodyState s;
  s.w_B = kW0;
  const int n = static_cast<int>(std::lround(t_end / h));
  for (int i = 0; i < n; ++i) s = step_free_body(m, kI, s, h);
  return (s.w_B - FreeBodyExact(kI, kW0).omega_body(t_end)).lpNorm<Eigen::Infinity>();
}

TEST(FreeBodyIntegrators, ConvergeAtTheirOrderAgainstTheExactFlow) {
  // t_end = 10 s covers the first flip. Observed order log2(e(h)/e(h/2)) must be
  // within 0.3 of the classical order (asymptotic regime chosen per method so the
  // error is far above round-off and below O(1)).
  struct Row {
    FreeBodyMethod m;
    double h;
  };
  for (const Row& r : {Row{FreeBodyMethod::kRk4, 0.02}, Row{FreeBodyMethod::kSplitting2, 0.005},
                       Row{FreeBodyMethod::kSplitting4, 0.02}, Row{FreeBodyMethod::kSplitting6, 0.05},
                       Row{FreeBodyMethod::kLiePoissonMidpoint, 0.005},
                       Row{FreeBodyMethod::kRkmk4, 0.02}, Row{FreeBodyMethod::kMoserVeselov, 0.005}}) {
    const double e1 = omega_error(r.m, r.h, 10.0);
    const double e2 = omega_error(r.m, r.h / 2, 10.0);
    const double p = std::log2(e1 / e2);
    EXPECT_NEAR(p, order_of(r.m), 0.3) << name_of(r.m) << " e(h) = " << e1 << " e(h/2) = " << e2;
  }
}

TEST(FreeBodyIntegrators, SplittingKeepsWorldMomentumAndOrthonormalityToRoundOff) {
  FreeBodyState s;
  s.w_B = kW0;
  const FreeBodyDiagnostics d0 = diagnose(kI, s);
  double max_energy_err = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    s = step_free_body(FreeBodyMethod::kSplitting4, kI, s, 0.01);
    if (i % 1000 == 0)
      max_energy_err = std::max(max_energy_err, std::abs(diagnose(kI, s).energy - d0.energy));
  }
  const FreeBodyDiagnostics d = diagnose(kI, s);
  const double L = d0.L_W.norm();
  // Each sub-flow is an exact rotation: only round-off accumulates, as a random
  // walk ≈ √(15 n) ε per component; 1e-12 allows ~ 4500 ulps.
  EXPECT_LT((d.L_W - d0.L_W).norm(), 1e-12 * L);
  EXPECT_LT(d.orthonormality_error, 1e-13);
  // Symplectic: energy error bounded by C h⁴ (no drift); C ≈ 1 for this motion.
  EXPECT_LT(max_energy_err, 1e-7);
}

// Reference splitting written the textbook way, independent of the library's kernel: every
// sub-flow of the unmerged composition (Strang = 5, Yoshida-4 = 15, Yoshida-6 = 45) turns L_B
// by the matrix exp(−θ ê_i) and the body by Eigen's AngleAxis(θ, e_i), std::sin/std::cos of
// the full and the half angle, then q is normalised [McLachlan1993; Yoshida1990].
void reference_strang(const Eigen::Vector3d& I, Eigen::Quaterniond& q, Eigen::Vector3d& L, double h) {
  const auto flow = [&](int i, double tau) {
    const double theta = tau * L(i) / I(i);
    L = Eigen::AngleAxisd(-theta, Eigen::Vector3d::Unit(i)).toRotationMatrix() * L;
    q = q * Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::Unit(i)));
  };
  flow(0, h / 2), flow(1, h / 2), flow(2, h), flow(1, h / 2), flow(0, h / 2);
}
void reference_composition(int order, const Eigen::Vector3d& I, Eigen::Quaterniond& q,
                           Eigen::Vector3d& L, double h) {
  if (order == 2) return reference_strang(I, q, L, h);
  const double g1 = 1.0 / (2.0 - std::pow(2.0, 1.0 / (order - 1)));
  for (const double g : {g1, 1.0 - 2.0 * g1, g1}) reference_composition(order - 2, I, q, L, g * h);
}

TEST(FreeBodyIntegrators, SplittingKernelEqualsTheUnmergedCompositionUpToRoundOff) {
  // The library merges same-axis neighbours and takes one half-angle polynomial sin/cos per
  // sub-flow: an exact rewriting, so only round-off may differ. 20 steps of h = 0.02 s for
  // random bodies (all half angles inside the polynomial's range |θ/2| ≤ 0.5), and one step
  // of h = 0.6 s for I = (1, 2, 3) kg·m², |ω| up to 3√3 rad/s (half angles up to ≈ 2.5, so
  // the std::sin/std::cos fallback runs too; a moderate inertia ratio and a single step keep
  // the amplification of round-off by these large turns small).
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> side(0.1, 1.0), omega(-3.0, 3.0);
  for (const FreeBodyMethod m : {FreeBodyMethod::kSplitting2, FreeBodyMethod::kSplitting4,
                                 FreeBodyMethod::kSplitting6}) {
    for (const double h : {0.02, 0.6}) {
      double max_w = 0, max_q = 0;
      for (int b = 0; b < 20; ++b) {
        const double x = side(rng), y = side(rng), z = side(rng);
        const Eigen::Vector3d I = h < 0.1 ? Eigen::Vector3d((y * y + z * z) / 12, (x * x + z * z) / 12,
                                                            (x * x + y * y) / 12)
                                          : kI;
        FreeBodyState s{from_eigen(Eigen::Quaterniond::UnitRandom()),
                        Eigen::Vector3d(omega(rng), omega(rng), omega(rng))};
        Eigen::Quaterniond q = to_eigen(s.R_WB);
        Eigen::Vector3d L = I.cwiseProduct(s.w_B);
        for (int k = 0; k < (h < 0.1 ? 20 : 1); ++k) {
          s = step_free_body(m, I, s, h);
          reference_composition(order_of(m), I, q, L, h);
          q.normalize();
        }
        max_w = std::max(max_w, (s.w_B - L.cwiseQuotient(I)).lpNorm<Eigen::Infinity>() /
                                    L.cwiseQuotient(I).lpNorm<Eigen::Infinity>());
        max_q = std::max(max_q, to_eigen(s.R_WB).angularDistance(q));
      }
      // h = 0.02: ≤ 45 sub-flows × 20 steps of ~1e-16 each sum to < 1e-13 even without
      // cancellation (observed 6e-15). h = 0.6: Yoshida-6's sub-flows turn by up to ~5 rad and
      // each multiplies earlier round-off by up to ~|θ|, so 1e-10 (observed 5e-12). A wrong
      // coefficient, axis order or sin/cos term gives differences of order h² ≥ 4e-4 instead.
      const double tol = h < 0.1 ? 1e-13 : 1e-10;
      EXPECT_LT(max_w, tol) << name_of(m) << " h = " << h;
      EXPECT_LT(max_q, tol) << name_of(m) << " h = " << h;
    }
  }
}

TEST(FreeBodyIntegrators, MidpointKeepsQuadraticInvariants) {
  FreeBodyState s;
  s.w_B = kW0;
  const FreeBodyDiagnostics d0 = diagnose(kI, s);
  const double L0 = kI.cwiseProduct(kW0).norm();
  for (int i = 0; i < 20000; ++i) s = step_free_body(FreeBodyMethod::kLiePoissonMidpoint, kI, s, 0.01);
  // Fixed point solved to 1e-16 relative per step; round-off random walk over 2e4 steps.
  EXPECT_NEAR(kI.cwiseProduct(s.w_B).norm(), L0, 1e-12 * L0);
  EXPECT_NEAR(diagnose(kI, s).energy, d0.energy, 1e-12 * d0.energy);
  EXPECT_LT(diagnose(kI, s).orthonormality_error, 1e-13);
}

TEST(FreeBodyIntegrators, OrientationConvergesAtTheOrderAgainstTheClosedForm) {
  // The closed-form orientation (FreeBodyMotion) as reference for the Lie-group
  // methods; same ±0.3 criterion as for ω.
  const SO3d q0 = SO3d::from_quaternion(0.9, 0.1, -0.3, 0.2);
  const FreeBodyMotion exact(kI, q0, kW0);
  for (const auto& [m, h] : {std::pair{FreeBodyMethod::kRkmk4, 0.02}, std::pair{FreeBodyMethod::kMoserVeselov, 0.005}}) {
    double e[2];
    for (int j = 0; j < 2; ++j) {
      const double hj = h / (1 << j);
      FreeBodyState s{q0, kW0};
      const int n = static_cast<int>(std::lround(10.0 / hj));
      for (int i = 0; i < n; ++i) s = step_free_body(m, kI, s, hj);
      e[j] = angle_between(s.R_WB, exact.orientation(10.0));
    }
    EXPECT_NEAR(std::log2(e[0] / e[1]), order_of(m), 0.3) << name_of(m) << " " << e[0] << " " << e[1];
  }
}

TEST(FreeBodyIntegrators, MoserVeselovKeepsMomentumAndEnergyToRoundOff) {
  FreeBodyState s;
  s.w_B = kW0;
  const FreeBodyDiagnostics d0 = diagnose(kI, s);
  const double L0 = d0.L_W.norm();
  double max_energy_err = 0;
  const int n = 100000;  // 1000 s, ~25 flips
  for (int i = 0; i < n; ++i) {
    s = step_free_body(FreeBodyMethod::kMoserVeselov, kI, s, 0.01);
    if (i % 100 == 0) max_energy_err = std::max(max_energy_err, std::abs(diagnose(kI, s).energy - d0.energy));
  }
  const FreeBodyDiagnostics d = diagnose(kI, s);
  // Each step is an exact rotation of L_B and of the body: round-off only, a random
  // walk ≈ √n · few ε ≈ 1e-13 relative after 1e5 steps.
  EXPECT_LT((d.L_W - d0.L_W).norm(), 1e-12 * L0);
  EXPECT_NEAR(kI.cwiseProduct(s.w_B).norm(), L0, 1e-12 * L0);
  EXPECT_LT(d.orthonormality_error, 1e-13);
  // Energy too: with h L_k = 2(q0 Iq + q × Iq) and h L_{k+1} = 2(q0 Iq − q × Iq) the
  // cross term of L·I⁻¹L is ±4 q0 (q × Iq)·q = 0, so ½ L·I⁻¹L is the same at both
  // ends of a step [McLachlan2005, §2]; only round-off remains.
  EXPECT_LT(max_energy_err, 1e-12 * d0.energy);
}

TEST(FreeBodyIntegrators, Rkmk4KeepsOrthonormalityToRoundOff) {
  FreeBodyState s;
  s.w_B = kW0;
  for (int i = 0; i < 100000; ++i) s = step_free_body(FreeBodyMethod::kRkmk4, kI, s, 0.01);
  // Updated by q ← q exp(Θ) and renormalised: the defect stays at a few ε.
  EXPECT_LT(diagnose(kI, s).orthonormality_error, ulps(16));
}

TEST(FreeBodyIntegrators, Rk4DriftsWhichTheDiagnosticsShow) {
  // Baseline without structure: RK4's energy drifts (it is a check that the diagnostics can
  // fail), while its rotation is projected onto |q| = 1 every step (SO3's invariant).
  FreeBodyState s;
  s.w_B = kW0;
  const double E0 = diagnose(kI, s).energy;
  for (int i = 0; i < 1000; ++i) s = step_free_body(FreeBodyMethod::kRk4, kI, s, 0.1);
  // h = 0.1 over 100 s through five flips: RK4's O(h⁴) energy error accumulates to ~1e-6
  // relative (measured 2.6e-6); a symplectic method keeps it bounded near 1e-9 here.
  EXPECT_GT(std::abs(diagnose(kI, s).energy - E0), 1e-7 * E0);
  EXPECT_LT(diagnose(kI, s).orthonormality_error, ulps(16));
}

TEST(FreeBodyIntegrators, SimulateReturnsRequestedTimes) {
  FreeBodyState s;
  s.w_B = kW0;
  const auto traj = simulate_free_body(FreeBodyMethod::kSplitting6, kI, s, 0.05, {0.0, 1.0, 2.5});
  ASSERT_EQ(traj.t.size(), 3u);
  EXPECT_EQ(traj.t[2], 2.5);
  const Eigen::Vector3d exact = FreeBodyExact(kI, kW0).omega_body(2.5);
  // 6th order at h = 0.05 over 2.5 s: error ≈ 1e-9 (from the convergence test scale).
  EXPECT_LT((traj.states[2].w_B - exact).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(FreeBodyIntegrators, NamesAndBadInput) {
  EXPECT_EQ(free_body_method_from_name("splitting4"), FreeBodyMethod::kSplitting4);
  EXPECT_EQ(name_of(FreeBodyMethod::kLiePoissonMidpoint), "midpoint");
  EXPECT_EQ(free_body_method_from_name("rkmk4"), FreeBodyMethod::kRkmk4);
  EXPECT_EQ(name_of(FreeBodyMethod::kMoserVeselov), "moser_veselov");
  EXPECT_RIGID_ERROR((void)free_body_method_from_name("euler"), "unknown free-body method 'euler'");
  FreeBodyState s;
  EXPECT_RIGID_ERROR((void)simulate_free_body(FreeBodyMethod::kRk4, kI, s, 0.0, {1.0}),
                     "the step h_max must be positive and finite, got 0 s");
  EXPECT_RIGID_ERROR((void)simulate_free_body(FreeBodyMethod::kRk4, kI, s, 0.1, {1.0, 0.5}),
                     "entry 1 is 0.5 s after 1 s");
  EXPECT_RIGID_ERROR((void)simulate_free_body(FreeBodyMethod::kRk4, Eigen::Vector3d(1, 1, 3), s, 0.1, {1.0}),
                     "violate I₁ + I₂ ≥ I₃");
  s.w_B(1) = std::nan("");
  EXPECT_RIGID_ERROR((void)simulate_free_body(FreeBodyMethod::kRk4, kI, s, 0.1, {1.0}),
                     "the initial state is not finite: w_B.y = nan");
}

TEST(FreeBodyIntegrators, DivergenceIsRefusedNamingTheComponentAndTime) {
  // RK4 on the racket spun at 1e3 rad/s about every axis with h = 0.1 s: h|ω| ≈ 170, far
  // outside RK4's stability region: the stage quaternions overflow at the second step.
  FreeBodyState s;
  s.w_B = Eigen::Vector3d(1e3, 1e3, 1e3);
  EXPECT_RIGID_ERROR((void)simulate_free_body(FreeBodyMethod::kRk4, kI, s, 0.1, {10.0}),
                     "non-finite state at step 2, t = 0.2 s: R_WB.w = nan; the motion diverged");
}

// The implicit methods converge or throw. The racket of the CLI's known defect, spun at 3 rad/s
// about its middle axis with h = 1 s: h |ω| max(I)/min(I) = 9, far outside the contraction of
// the fixed-point iterations. The midpoint's iteration ran its 100 iterations and returned the
// unconverged iterate (22 % of the energy lost over 100 s); it is now refused.
TEST(FreeBodyIntegrators, MidpointThatDoesNotConvergeIsRefused) {
  const FreeBodyState s{SO3d::identity(), Eigen::Vector3d(0.01, 3, 0.01)};
  EXPECT_RIGID_ERROR((void)step_free_body(FreeBodyMethod::kLiePoissonMidpoint, kI, s, 1.0),
                     "step_free_body(): the Lie–Poisson midpoint step (midpoint) did not converge: "
                     "h = 1 s, |ω| = 3.00003");
  EXPECT_RIGID_ERROR(
      (void)step_free_body(FreeBodyMethod::kLiePoissonMidpoint, kI, s, 1.0),
      "rad/s; after 100 fixed-point iterations the residual of its implicit equation, "
      "|L1 − L0 − h L̄ × ω̄|/|L0| = ");
  EXPECT_RIGID_ERROR((void)step_free_body(FreeBodyMethod::kLiePoissonMidpoint, kI, s, 1.0),
                     "is above the tolerance");
  EXPECT_RIGID_ERROR(
      (void)step_free_body(FreeBodyMethod::kLiePoissonMidpoint, kI, s, 1.0),
      "use a smaller step (the iteration contracts for h |ω| max(I)/min(I) < 1, here 9)");
  // through the march: the step number and its start time in front
  EXPECT_RIGID_ERROR(
      (void)simulate_free_body(FreeBodyMethod::kLiePoissonMidpoint, kI, s, 1.0, {0.0, 1.0, 2.0}),
      "at step 1 from t = 0 s: step_free_body(): the Lie–Poisson midpoint step (midpoint) did not "
      "converge: h = 1 s");
  // the same spin at h = 0.25 s converges (20 iterations, measured): the remedy works
  EXPECT_NO_THROW(
      (void)simulate_free_body(FreeBodyMethod::kLiePoissonMidpoint, kI, s, 0.25, {1.0}));
}

TEST(FreeBodyIntegrators, MoserVeselovThatDoesNotConvergeIsRefused) {
  // ω = (0.01, 1, 0.01), h = 1 s: |q| ≈ h|ω|/2 = 0.5 stays below 1, so the old check (|q| < 1
  // after the iteration) passed, but the iteration had not converged: the residual after 100
  // iterations is 7e-5 of h|L| (measured), and the step returned a wrong rotation.
  const FreeBodyState s{SO3d::identity(), kW0};
  EXPECT_RIGID_ERROR(
      (void)step_free_body(FreeBodyMethod::kMoserVeselov, kI, s, 1.0),
      "step_free_body(): the Moser–Veselov step (moser_veselov) did not converge: h = "
      "1 s, |ω| = 1.0000999");
  EXPECT_RIGID_ERROR((void)step_free_body(FreeBodyMethod::kMoserVeselov, kI, s, 1.0),
                     "after 100 fixed-point iterations the residual of its implicit equation, "
                     "|h L − 2 q0 I q − 2 q × I q|/(h |L|) = ");
  EXPECT_RIGID_ERROR(
      (void)step_free_body(FreeBodyMethod::kMoserVeselov, kI, s, 1.0),
      "use a smaller step (the iteration contracts for h |ω| max(I)/min(I) < 1, here 3)");
  // h = 1.25 s: no rotation solves it (|q| leaves the unit ball); refused the same way
  EXPECT_RIGID_ERROR((void)step_free_body(FreeBodyMethod::kMoserVeselov, kI, s, 1.25),
                     "the Moser–Veselov step (moser_veselov) did not converge: h = 1.25 s");
  // through the march: one step of 0.5 s converges, the next of 1.5 s does not
  EXPECT_RIGID_ERROR(
      (void)simulate_free_body(FreeBodyMethod::kMoserVeselov, kI, s, 1.5, {0.5, 2.0}),
      "at step 2 from t = 0.5 s: step_free_body(): the Moser–Veselov step "
      "(moser_veselov) did not converge: h = 1.5 s");
}

// The fixed-point iterations exactly as the steps always ran them (the reference for the
// bitwise comparison below: the convergence check must not change a step that converges).
Eigen::Vector3d midpoint_L1(const Eigen::Vector3d& I, const Eigen::Vector3d& w, double h) {
  const Eigen::Vector3d L0 = I.cwiseProduct(w);
  Eigen::Vector3d L1 = L0;
  for (int it = 0; it < 100; ++it) {
    const Eigen::Vector3d Lm = 0.5 * (L0 + L1);
    const Eigen::Vector3d next = L0 + h * Lm.cross(Lm.cwiseQuotient(I));
    const double change = (next - L1).lpNorm<Eigen::Infinity>();
    L1 = next;
    if (change <= 1e-16 * L0.lpNorm<Eigen::Infinity>()) break;
  }
  return L1;
}

TEST(FreeBodyIntegrators, MidpointStepsThatConvergeAreUnchanged) {
  // (a) ω = (1, 0.5, 0.2), h = 1 s: the iteration stalls at round-off (its update never falls
  // below 1e-16 |L0|, so it runs all 100 iterations; measured residual 1.1e-16 |L0|) and is
  // accepted; (b) the racket at h = 0.01 s stops by the rule after a few iterations.
  for (const auto& [w, h] : {std::pair{Eigen::Vector3d(1, 0.5, 0.2), 1.0}, std::pair{kW0, 0.01}}) {
    const FreeBodyState s0{SO3d::identity(), w};
    const FreeBodyState s1 = step_free_body(FreeBodyMethod::kLiePoissonMidpoint, kI, s0, h);
    // bitwise: the same iteration and the same stopping rule as before the check was added
    EXPECT_EQ(s1.w_B, midpoint_L1(kI, w, h).cwiseQuotient(kI)) << "h = " << h;
    // the quadratic invariants to round-off: for L1 = L0 + h L̄ × ω̄ + r (residual r),
    // |L1|² − |L0|² = 2 r·L̄ and 2E1 − 2E0 = 2 r·ω̄, with |r|∞ ≤ 16 ε (|L0|∞ + h |L̄|∞ |ω̄|∞)
    // ≤ 32 ε |L0| in both cases. So |L| changes by at most √3 · 32 ε |L0| ≈ 55 ε |L0| and E by
    // at most √3 |r|∞ |ω̄| ≈ 110 ε E0 (E = ½ L·ω); ω = L/I and back and the norms add a few
    // ulps: 64 and 128 ulps. (Measured: 0 and at most 2 ulps.)
    const double L0 = kI.cwiseProduct(w).norm(), E0 = diagnose(kI, s0).energy;
    EXPECT_NEAR(kI.cwiseProduct(s1.w_B).norm(), L0, ulps(64, L0)) << "h = " << h;
    EXPECT_NEAR(diagnose(kI, s1).energy, E0, ulps(128, E0)) << "h = " << h;
  }
}

TEST(FreeBodyIntegrators, MoserVeselovStepsThatConvergeKeepTheInvariants) {
  // h = 0.75 s (h |ω| max/min = 2.25, 25 iterations, measured): converges; one step keeps
  // L_W (an exact rotation of L_B and of the body, round-off only: a few ulps of |L|, 16 here)
  // and the energy (the cross term of L·I⁻¹L cancels [McLachlan2005, §2]; 16 ulps likewise)
  const FreeBodyState s0{SO3d::identity(), kW0};
  const FreeBodyState s1 = step_free_body(FreeBodyMethod::kMoserVeselov, kI, s0, 0.75);
  const FreeBodyDiagnostics d0 = diagnose(kI, s0), d1 = diagnose(kI, s1);
  EXPECT_LT((d1.L_W - d0.L_W).norm(), ulps(16, d0.L_W.norm()));
  EXPECT_NEAR(d1.energy, d0.energy, ulps(16, d0.energy));
}

}  // namespace
}  // namespace rigid::body
