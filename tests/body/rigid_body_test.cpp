#include "rigid/body/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "rigid/body/free_body_exact.hpp"
#include "rigid/common/format.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::body {
namespace {

using rigid::test::ulps;

// A body frame that is not principal: I_C_B = Q diag(I_P) Qᵀ with the columns of Q the
// principal axes, so the full-tensor path is exercised and the principal frame is known
// independently of the eigen-solver inside RigidBody.
const Eigen::Vector3d kIP(1.0, 2.0, 3.0);
const Eigen::Matrix3d kQ = SO3d::from_axis_angle(Eigen::Vector3d(1, 2, 3), 0.7).matrix();
const Eigen::Matrix3d kIfull = kQ * kIP.asDiagonal() * kQ.transpose();

double rotation_distance(const SO3d& a, const SO3d& b) { return (a.inverse() * b).log().norm(); }

const std::vector<RigidBodyMethod> kMethods{RigidBodyMethod::kSplitting2, RigidBodyMethod::kRk4};

TEST(RigidBody, ProjectileWithSpinFollowsParabolaAndFreeBodyRotation) {
  const double m = 2.0;
  const Eigen::Vector3d g(0, 0, -9.81);
  const RigidBody body(m, kIfull, g);
  RigidBodyState s0;
  s0.p_WC = Eigen::Vector3d(1, 2, 3);
  s0.v_WC = Eigen::Vector3d(4, -1, 10);
  // tennis-racket spin about the intermediate principal axis Q e2
  const Eigen::Vector3d w0_P(0.01, 1.0, 0.01);
  s0.w_B = kQ * w0_P;
  const FreeBodyExact exact(kIP, w0_P);
  const double h = 1e-3;
  const int n = 2000;
  for (const RigidBodyMethod method : kMethods) {
    SCOPED_TRACE(method == RigidBodyMethod::kRk4 ? "rk4" : "splitting2");
    RigidBodyState s = s0;
    // the same rotation by the free-body stepper in the principal frame Q
    FreeBodyState fs{SO3d::from_matrix(kQ), w0_P};
    const double E0 = body.diagnose(s0).energy;
    for (int i = 0; i < n; ++i) {
      s = step_rigid_body(body, method, i * h, s, h);
      if (method == RigidBodyMethod::kSplitting2) fs = step_free_body(FreeBodyMethod::kSplitting2, kIP, fs, h);
    }
    const double t = n * h;
    // COM: p = p0 + v0 t + ½ g t², v = v0 + g t. Both methods are exact for a quadratic
    // in t (kick-drift-kick; RK4 integrates polynomials of degree ≤ 4 exactly), so only
    // round-off remains: a few ulps of |p| ≈ 25 m per step, summed over n steps.
    const Eigen::Vector3d p_exact = s0.p_WC + s0.v_WC * t + 0.5 * g * t * t;
    const Eigen::Vector3d v_exact = s0.v_WC + g * t;
    EXPECT_LT((s.p_WC - p_exact).norm(), ulps(4.0 * n, p_exact.norm()));
    EXPECT_LT((s.v_WC - v_exact).norm(), ulps(4.0 * n, v_exact.norm()));
    // rotation = the free body: ω_B in the principal frame vs the elliptic solution.
    // splitting2 (order 2) at h = 1e-3 over 2 s before the first flip: error ~ h² ω³ t ≈ 1e-6
    // bounds it; RK4 (order 4) is ~h⁴ smaller, so round-off (≈ n ε) dominates.
    const Eigen::Vector3d w_P = kQ.transpose() * s.w_B;
    const double w_tol = method == RigidBodyMethod::kRk4 ? 1e-11 : 1e-6;
    EXPECT_LT((w_P - exact.omega_body(t)).lpNorm<Eigen::Infinity>(), w_tol);
    if (method == RigidBodyMethod::kSplitting2) {
      // same sub-flows in exact arithmetic (the principal frame differs from Q only by a
      // proper axis relabelling that leaves each sub-flow unchanged): round-off only,
      // ~10 ulps per step over n steps.
      EXPECT_LT(rotation_distance(s.R_WB, fs.R_WB * SO3d::from_matrix(kQ.transpose())), ulps(10.0 * n));
      EXPECT_LT((w_P - fs.w_B).norm(), ulps(10.0 * n));
    }
    // energy: translation exact, rotation's energy error O(h²) ≈ 1e-6 relative (splitting),
    // round-off for RK4 at this step
    const auto d = body.diagnose(s);
    EXPECT_LT(std::abs(d.energy - E0) / std::abs(E0), 1e-6);
    EXPECT_LT(d.orthonormality_error, ulps(8));
  }
}

TEST(RigidBody, ConstantTorqueAboutPrincipalAxisSpinsUpLinearly) {
  // ω ∥ a (a principal axis): ω × Iω = 0, so I_a ω̇ = τ: ω(t) = (w0 + τ t / I_a) a, and the
  // body turns about the fixed axis a by θ(t) = w0 t + τ t² / (2 I_a)  [Landau1976, §36].
  const Eigen::Vector3d a = kQ.col(2);
  const double Ia = kIP(2), w0 = 0.5, tau = 0.3;
  const double h = 1e-2;
  const int n = 300;
  const double t = n * h;
  const double w_exact = w0 + tau * t / Ia;
  const SO3d R_exact = SO3d::from_axis_angle(a, w0 * t + 0.5 * tau * t * t / Ia);
  for (const LoadFrame frame : {LoadFrame::kBody, LoadFrame::kWorld}) {
    // R a = a at all times, so the same torque vector is τ a in both frames
    RigidBody body(1.0, kIfull);
    body.add_load({[&](double, const RigidBodyState&) { return Wrench{Eigen::Vector3d::Zero(), tau * a}; },
                   frame});
    for (const RigidBodyMethod method : kMethods) {
      SCOPED_TRACE(::testing::Message() << "frame " << static_cast<int>(frame) << " method "
                                        << static_cast<int>(method));
      RigidBodyState s;
      s.w_B = w0 * a;
      for (int i = 0; i < n; ++i) s = step_rigid_body(body, method, i * h, s, h);
      // ω is linear in t: both methods exact up to round-off (~ulps per step, n steps)
      EXPECT_LT((s.w_B - w_exact * a).norm(), ulps(10.0 * n, w_exact));
      // splitting: exact kick and exact rotation about a principal axis → round-off;
      // RK4 on the quaternion: O(h⁴) error, h⁴ θ⁽⁵⁾ t ≈ 1e-8·(w/2)⁵·3 ≪ 1e-9
      const double R_tol = method == RigidBodyMethod::kRk4 ? 1e-9 : ulps(20.0 * n);
      EXPECT_LT(rotation_distance(s.R_WB, R_exact), R_tol);
      EXPECT_EQ(s.p_WC, Eigen::Vector3d::Zero());
    }
  }
}

TEST(RigidBody, ForceAtBodyPointIsForceAtComPlusMomentArm) {
  // a spring from the body point Q to a world anchor: F_W = −k (p_WQ − anchor)
  const Eigen::Vector3d r_B(0.3, -0.2, 0.5), anchor(1, 0, 2);
  const double k = 4.0;
  auto spring = [&](const RigidBodyState& s) -> Eigen::Vector3d {
    return -k * (s.p_WC + s.R_WB * r_B - anchor);
  };
  RigidBody at_point_world(1.5, kIfull), at_point_body(1.5, kIfull), at_com(1.5, kIfull);
  at_point_world.add_load({[&](double, const RigidBodyState& s) { return Wrench{spring(s), Eigen::Vector3d::Zero()}; },
                           LoadFrame::kWorld, r_B});
  at_point_body.add_load({[&](double, const RigidBodyState& s) {
                            return Wrench{s.R_WB.inverse() * spring(s), Eigen::Vector3d::Zero()};
                          },
                          LoadFrame::kBody, r_B});
  at_com.add_load({[&](double, const RigidBodyState& s) {
                     const Eigen::Vector3d F = spring(s);
                     return Wrench{F, (s.R_WB * r_B).cross(F)};  // τ_W = p_CQ_W × F_W
                   },
                   LoadFrame::kWorld});
  RigidBodyState s0;
  s0.R_WB = SO3d::from_axis_angle(Eigen::Vector3d(0, 1, 1), 0.4);
  s0.w_B = Eigen::Vector3d(0.2, 1.0, -0.5);
  s0.v_WC = Eigen::Vector3d(0.1, 0.0, -0.3);
  // the wrench itself, against the torque computed here with matrices: τ_B = r_B × (Rᵀ F_W)
  const Eigen::Vector3d F = spring(s0);
  const Eigen::Vector3d tau_B = r_B.cross(s0.R_WB.matrix().transpose() * F);
  for (const RigidBody* b : {&at_point_world, &at_point_body, &at_com}) {
    const Wrench w = b->total_wrench(0.0, s0);
    EXPECT_LT((w.force - F).norm(), ulps(8, F.norm()));
    EXPECT_LT((w.torque - tau_B).norm(), ulps(16, F.norm()));
  }
  // and the trajectories agree to round-off (same rates up to ulps at every stage)
  for (const RigidBodyMethod method : kMethods) {
    RigidBodyState a = s0, b = s0, c = s0;
    const double h = 1e-2;
    for (int i = 0; i < 200; ++i) {
      a = step_rigid_body(at_point_world, method, i * h, a, h);
      b = step_rigid_body(at_point_body, method, i * h, b, h);
      c = step_rigid_body(at_com, method, i * h, c, h);
    }
    // 200 steps of a bounded oscillation: differences grow at most like n ulps × O(1) rates
    for (const RigidBodyState* o : {&b, &c}) {
      EXPECT_LT((a.p_WC - o->p_WC).norm(), 1e-12);
      EXPECT_LT((a.v_WC - o->v_WC).norm(), 1e-12);
      EXPECT_LT((a.w_B - o->w_B).norm(), 1e-12);
      EXPECT_LT(rotation_distance(a.R_WB, o->R_WB), 1e-12);
    }
    // with the forces on, momentum is not conserved: the comparison is not trivial
    EXPECT_GT((a.v_WC - s0.v_WC).norm(), 0.1);
  }
}

TEST(RigidBody, MomentaConservedWithoutLoads) {
  // a body that is not principal, off the origin, tumbling: P_W = m v and the angular
  // momentum about the world origin L_W = R I ω + m p × v are constants of the motion.
  const double m = 3.0;
  const RigidBody body(m, kIfull);
  RigidBodyState s;
  s.R_WB = SO3d::from_axis_angle(Eigen::Vector3d(1, -1, 2), 1.1);
  s.w_B = Eigen::Vector3d(0.7, -1.3, 0.4);
  s.p_WC = Eigen::Vector3d(5, -3, 2);
  s.v_WC = Eigen::Vector3d(0.5, 0.25, -1);
  const auto d0 = body.diagnose(s);
  const int n = 5000;
  const double h = 1e-2;
  for (int i = 0; i < n; ++i) s = step_rigid_body(body, RigidBodyMethod::kSplitting2, i * h, s, h);
  const auto d = body.diagnose(s);
  // v never changes (no kick adds anything): P_W bitwise
  EXPECT_EQ(d.P_W, d0.P_W);
  // every sub-flow of the splitting keeps L_W exactly (rotations of L_B that the body's
  // rotation undoes; p × v with p += h v): a round-off walk of a few ulps per step
  EXPECT_LT((d.L_W - d0.L_W).norm() / d0.L_W.norm(), ulps(n));
  // symplectic, order 2: the energy error is bounded by O(h²) (no drift), ≈ 1e-4 here
  EXPECT_LT(std::abs(d.energy - d0.energy) / d0.energy, 1e-3);
  EXPECT_LT(d.orthonormality_error, ulps(8));
}

TEST(RigidBody, ConvergesAtItsOrderAgainstDragClosedForm) {
  // linear drag F_W = −c v and spin damping τ_B = −c_r ω about a principal axis a:
  // v(t) = v0 e^{−c t/m}, p(t) = p0 + v0 (m/c)(1 − e^{−c t/m}),
  // ω(t) = w0 e^{−c_r t/I_a} a, θ(t) = w0 (I_a/c_r)(1 − e^{−c_r t/I_a}).
  // Velocity-dependent loads: the splitting's kick is the midpoint rule, so order 2.
  const double m = 2.0, c = 1.5, cr = 2.0, Ia = kIP(2), w0 = 3.0;
  const Eigen::Vector3d a = kQ.col(2), v0(1.0, -2.0, 0.5);
  RigidBody body(m, kIfull);
  body.add_load({[&](double, const RigidBodyState& s) { return Wrench{-c * s.v_WC, Eigen::Vector3d::Zero()}; },
                 LoadFrame::kWorld});
  body.add_load({[&](double, const RigidBodyState& s) { return Wrench{Eigen::Vector3d::Zero(), -cr * s.w_B}; },
                 LoadFrame::kBody});
  const double T = 1.0;
  const Eigen::Vector3d p_exact = v0 * (m / c) * (1 - std::exp(-c * T / m));
  const Eigen::Vector3d w_exact = w0 * std::exp(-cr * T / Ia) * a;
  const SO3d R_exact = SO3d::from_axis_angle(a, w0 * (Ia / cr) * (1 - std::exp(-cr * T / Ia)));
  auto error = [&](RigidBodyMethod method, int n) {
    RigidBodyState s;
    s.v_WC = v0;
    s.w_B = w0 * a;
    const double h = T / n;
    for (int i = 0; i < n; ++i) s = step_rigid_body(body, method, i * h, s, h);
    return std::max({(s.p_WC - p_exact).norm(), (s.w_B - w_exact).norm(), rotation_distance(s.R_WB, R_exact)});
  };
  for (const auto& [method, order] : {std::pair{RigidBodyMethod::kSplitting2, 2}, std::pair{RigidBodyMethod::kRk4, 4}}) {
    const double e1 = error(method, 20), e2 = error(method, 40);
    // errors stay far above round-off here (≥ 1e-8); ratio 2^p within ±10% (STYLE.md §7)
    EXPECT_GT(e2, 1e-10);
    EXPECT_NEAR(std::log2(e1 / e2), order, 0.1 * order) << "e(h) = " << e1 << ", e(h/2) = " << e2;
  }
}

TEST(RigidBody, ConvergesAtItsOrderOnCoupledMotion) {
  // tumbling racket in gravity, held by a spring at an off-COM body point with drag there:
  // no closed form, so the order is measured on successive differences
  // d(h) = ‖x_h − x_{h/2}‖ ∝ h^p (Richardson: x_h − x = C h^p + O(h^{p+1})).
  const Eigen::Vector3d r_B(0.2, 0.1, -0.3), anchor(0, 0, 1);
  RigidBody body(1.0, kIfull, Eigen::Vector3d(0, 0, -9.81));
  body.add_load({[&](double, const RigidBodyState& s) {
                   // world velocity of Q: v_C + R (ω_B × r_B)
                   const Eigen::Vector3d v_Q = s.v_WC + s.R_WB * s.w_B.cross(r_B);
                   return Wrench{-20.0 * (s.p_WC + s.R_WB * r_B - anchor) - 0.5 * v_Q, Eigen::Vector3d::Zero()};
                 },
                 LoadFrame::kWorld, r_B});
  auto run = [&](RigidBodyMethod method, int n) {
    RigidBodyState s;
    s.w_B = kQ * Eigen::Vector3d(0.1, 2.0, 0.1);
    const double h = 1.0 / n;
    for (int i = 0; i < n; ++i) s = step_rigid_body(body, method, i * h, s, h);
    return s;
  };
  auto diff = [](const RigidBodyState& x, const RigidBodyState& y) {
    return std::max({(x.p_WC - y.p_WC).norm(), (x.v_WC - y.v_WC).norm(), (x.w_B - y.w_B).norm(),
                     rotation_distance(x.R_WB, y.R_WB)});
  };
  for (const auto& [method, order] : {std::pair{RigidBodyMethod::kSplitting2, 2}, std::pair{RigidBodyMethod::kRk4, 4}}) {
    const RigidBodyState s1 = run(method, 50), s2 = run(method, 100), s3 = run(method, 200);
    const double d1 = diff(s1, s2), d2 = diff(s2, s3);
    EXPECT_GT(d2, 1e-11);  // far above round-off, so the ratio measures truncation error
    EXPECT_NEAR(std::log2(d1 / d2), order, 0.1 * order) << "d1 = " << d1 << ", d2 = " << d2;
  }
}

TEST(RigidBody, SimulateSamplesTheSteppedTrajectory) {
  // free fall with spin: the samples are the parabola at the requested times (to round-off,
  // as in the projectile test), the diagnostics are those of the sampled states, and P_W
  // grows by m g t exactly as a kick-drift-kick of constant force does
  const double m = 2.0;
  const Eigen::Vector3d g(0, 0, -9.81), v0(1, 0, 3);
  const RigidBody body(m, kIfull, g);
  RigidBodyState s0;
  s0.v_WC = v0;
  s0.w_B = Eigen::Vector3d(0.3, 1.0, -0.2);
  const std::vector<double> times{0.0, 0.25, 1.0, 1.0, 2.5};
  const auto traj = simulate_rigid_body(body, RigidBodyMethod::kSplitting2, s0, 0.01, times);
  ASSERT_EQ(traj.t, times);
  ASSERT_EQ(traj.states.size(), times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    const Eigen::Vector3d p = v0 * t + 0.5 * g * t * t;
    EXPECT_LT((traj.states[i].p_WC - p).norm(), ulps(1000, 30.0)) << "t = " << t;
    EXPECT_LT((traj.diagnostics[i].P_W - m * (v0 + g * t)).norm(), ulps(1000, 50.0)) << "t = " << t;
    EXPECT_EQ(traj.diagnostics[i].energy, body.diagnose(traj.states[i]).energy);
  }
  EXPECT_EQ(traj.states[2].p_WC, traj.states[3].p_WC);  // a repeated time takes no step
  EXPECT_RIGID_ERROR((void)simulate_rigid_body(body, RigidBodyMethod::kRk4, s0, 0.01, {1.0, 0.5}),
                     "output times must be finite, ≥ the start t0 = 0 s and ascending; entry 1 is 0.5 s after 1 s");
  EXPECT_RIGID_ERROR((void)simulate_rigid_body(body, RigidBodyMethod::kRk4, s0, -1.0, {1.0}),
                     "step h_max must be positive and finite, got -1 s");
}

TEST(RigidBody, TakesMassPropertiesWithTheComAwayFromTheOrigin) {
  // B's origin is not at the COM: the state follows the COM, origin_position() gives B's
  // origin, and the motion is that of the same body with its frame at the COM.
  const Eigen::Vector3d c(0.1, -0.2, 0.3);
  const RigidBody at_com(2.0, kIfull), offset(MassProperties(2.0, c, kIfull));
  EXPECT_EQ(offset.com(), c);
  RigidBodyState s;
  s.w_B = Eigen::Vector3d(0.3, 1.0, -0.2);
  s.p_WC = Eigen::Vector3d(1, 2, 3);
  RigidBodyState a = s, b = s;
  for (int i = 0; i < 100; ++i) {
    a = step_rigid_body(at_com, RigidBodyMethod::kSplitting2, 0.01 * i, a, 0.01);
    b = step_rigid_body(offset, RigidBodyMethod::kSplitting2, 0.01 * i, b, 0.01);
  }
  EXPECT_EQ(a.w_B, b.w_B);  // the same computation: the COM offset enters only the output pose
  EXPECT_LT((offset.origin_position(b) - (b.p_WC - b.R_WB * c)).norm(), ulps(4, 4.0));
}

TEST(RigidBody, DivergenceIsRefusedNamingTheComponent) {
  // RK4 with h|ω| ≈ 170 (spin 1e3 rad/s about every axis, h = 0.1 s): far outside its
  // stability region, the state overflows
  const RigidBody body(1.0, Eigen::Vector3d(1, 2, 3).asDiagonal().toDenseMatrix());
  RigidBodyState s;
  s.w_B = Eigen::Vector3d(1e3, 1e3, 1e3);
  EXPECT_RIGID_ERROR((void)simulate_rigid_body(body, RigidBodyMethod::kRk4, s, 0.1, {10.0}),
                     "non-finite state at step");
}

TEST(RigidBody, ImplicitFreeFlowThatDoesNotConvergeIsRefusedNamingTheStep) {
  // the drift's free rotation by the Lie–Poisson midpoint, racket spun at 3 rad/s about its
  // middle principal axis: the first step, of 0.5 s, converges (38 iterations, measured), the
  // second, of 1 s (h |ω| max(I)/min(I) = 9), does not
  const RigidBody body(1.0, kIfull, Eigen::Vector3d(0, 0, -9.81));
  RigidBodyState s;
  s.w_B = kQ * Eigen::Vector3d(0.01, 3, 0.01);
  EXPECT_RIGID_ERROR((void)simulate_rigid_body(body, RigidBodyMethod::kSplitting2, s, 1.0,
                                               {0.5, 1.5}, FreeBodyMethod::kLiePoissonMidpoint),
                     "at step 2 from t = 0.5 s: step_free_body(): the Lie–Poisson midpoint step "
                     "(midpoint) did not converge: h = 1 s");
}

TEST(RigidBody, FormatsStateAndWrench) {
  RigidBodyState s;
  s.p_WC = Eigen::Vector3d(1, 2.5, -3);
  s.v_WC = Eigen::Vector3d(0, 0, 0.25);
  const std::string text = fmt::format("{}", s);
  EXPECT_NE(text.find("RigidBodyState{R_WB: "), std::string::npos) << text;
  EXPECT_NE(text.find(fmt::format("p_WC: {} m", rigid::to_string(s.p_WC.transpose()))), std::string::npos) << text;
  EXPECT_NE(text.find(fmt::format("v_WC: {} m/s", rigid::to_string(s.v_WC.transpose()))), std::string::npos) << text;
  const std::string w = fmt::format("{}", Wrench{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 2)});
  EXPECT_NE(w.find("N·m}"), std::string::npos) << w;
  EXPECT_EQ(w.rfind("Wrench{force: ", 0), 0u) << w;
}

TEST(RigidBody, RejectsBadInput) {
  EXPECT_RIGID_ERROR(RigidBody(-1.0, kIfull), "mass must be positive and finite, got -1 kg");
  Eigen::Matrix3d asym = kIfull;
  asym(0, 1) += 1e-3;
  // the one validity check of rigid::MassProperties
  EXPECT_RIGID_ERROR(RigidBody(1.0, asym), "inertia tensor is not symmetric");
  EXPECT_RIGID_ERROR(RigidBody(1.0, Eigen::Vector3d(1, -2, 3).asDiagonal().toDenseMatrix()),
                     "not positive semidefinite");
  EXPECT_RIGID_ERROR(RigidBody(1.0, Eigen::Vector3d(1, 1, 3).asDiagonal().toDenseMatrix()),
                     "violate I₁ + I₂ ≥ I₃ by 1 kg·m²");
  EXPECT_RIGID_ERROR(RigidBody(1.0, Eigen::Vector3d(0, 1, 1).asDiagonal().toDenseMatrix()),
                     "RigidBody: inertia about the COM: principal moments (0, 1, 1) kg·m² include a zero moment");
  EXPECT_RIGID_ERROR(RigidBody(1.0, kIfull, Eigen::Vector3d(0, 0, NAN)), "gravity g_W must be finite");
  RigidBody body(1.0, kIfull);
  EXPECT_RIGID_ERROR(body.add_load({}), "load 0 has no wrench function");
  const RigidBodyState s;
  EXPECT_RIGID_ERROR((void)step_rigid_body(body, RigidBodyMethod::kSplitting2, 0.0, s, 0.0),
                     "step h must be positive and finite, got 0 s");
  RigidBodyState bad;
  bad.v_WC(1) = INFINITY;
  EXPECT_RIGID_ERROR((void)step_rigid_body(body, RigidBodyMethod::kRk4, 0.0, bad, 0.1),
                     "state at t = 0 s is not finite");
  body.add_load({[](double t, const RigidBodyState&) {
                   return Wrench{Eigen::Vector3d(t > 0.15 ? NAN : 0.0, 0, 0), Eigen::Vector3d::Zero()};
                 },
                 LoadFrame::kBody});
  RigidBodyState x;
  EXPECT_RIGID_ERROR(
      for (int i = 0; i < 5; ++i) x = step_rigid_body(body, RigidBodyMethod::kSplitting2, 0.1 * i, x, 0.1),
      "load 0 returned a non-finite wrench at t = 0.2 s");
  EXPECT_RIGID_ERROR((void)rigid_body_method_from_name("euler"),
                     "unknown rigid-body method 'euler'; expected one of splitting2, rk4");
  EXPECT_EQ(rigid_body_method_from_name("rk4"), RigidBodyMethod::kRk4);
}

}  // namespace
}  // namespace rigid::body
