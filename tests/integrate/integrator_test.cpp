#include "rigid/integrate/integrator.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::integrate {
namespace {

using test::ulps;

// harmonic oscillator q'' = -q, q(0) = 1, v(0) = 0: q = cos t, v = -sin t
Problem oscillator(double t_end) {
  Problem p;
  p.rhs = [](double, const Eigen::VectorXd& y, Eigen::VectorXd& d) {
    d[0] = y[1];
    d[1] = -y[0];
  };
  p.y0 = Eigen::Vector2d(1.0, 0.0);
  p.t_end = t_end;
  return p;
}

double final_error(Method m, double dt) {
  const Solution s = integrate(oscillator(2.0), Options{.method = m, .dt = dt});
  const double t = s.t.back();
  return std::hypot(s.y.back()[0] - std::cos(t), s.y.back()[1] + std::sin(t));
}

// measured order: err(dt)/err(dt/2) = 2^p within ±10% (the leading error term dominates at
// these step sizes; the errors stay far above round-off, ≥ 1e-10)
void expect_order(Method m, double dt, double p) {
  const double ratio = final_error(m, dt) / final_error(m, dt / 2);
  EXPECT_NEAR(ratio, std::pow(2.0, p), 0.1 * std::pow(2.0, p)) << to_string(m);
}

TEST(Integrator, Rk4IsFourthOrder) { expect_order(Method::kRk4, 0.05, 4); }
TEST(Integrator, ImplicitMidpointIsSecondOrder) {
  expect_order(Method::kImplicitMidpoint, 0.02, 2);
}
TEST(Integrator, StormerVerletIsSecondOrder) { expect_order(Method::kStormerVerlet, 0.02, 2); }

TEST(Integrator, Dopri5MeetsItsToleranceWithDenseOutput) {
  const Solution s = integrate(oscillator(10.0), Options{.method = Method::kDopri5,
                                                         .rtol = 1e-12, .atol = 1e-12,
                                                         .output_dt = 0.1});
  ASSERT_EQ(s.t.size(), 101u);
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    EXPECT_NEAR(s.t[k], 0.1 * static_cast<double>(k), ulps(64, 10.0));
    // global error of a 1e-12 local tolerance over ~10 s of a stable oscillator: < 1e-10
    EXPECT_NEAR(s.y[k][0], std::cos(s.t[k]), 1e-10);
    EXPECT_NEAR(s.y[k][1], -std::sin(s.t[k]), 1e-10);
  }
  EXPECT_EQ(s.t.back(), 10.0);
}

TEST(Integrator, Dopri5ErrorShrinksWithTolerance) {
  auto err = [](double tol) {
    const Solution s = integrate(oscillator(5.0), Options{.method = Method::kDopri5,
                                                          .rtol = tol, .atol = tol});
    return std::abs(s.y.back()[0] - std::cos(5.0));
  };
  // a 5th-order method: 1e4 smaller tolerance gives ≥ 100× smaller error
  EXPECT_LT(err(1e-10), err(1e-6) / 100);
}

TEST(Integrator, SymplecticMethodsBoundTheEnergyError) {
  // 1000 periods with 63 steps per period: the energy ½(q² + v²) oscillates but does not drift
  for (Method m : {Method::kImplicitMidpoint, Method::kStormerVerlet}) {
    const Solution s = integrate(oscillator(2000 * M_PI), Options{.method = m, .dt = 0.1,
                                                                  .output_dt = 1.0});
    double worst = 0;
    for (const auto& y : s.y) worst = std::max(worst, std::abs(0.5 * y.squaredNorm() - 0.5));
    // implicit midpoint conserves quadratic invariants exactly (up to the Newton tolerance);
    // Verlet's modified energy differs from H by O(h²) = h²/8 ≈ 1.3e-3
    EXPECT_LT(worst, m == Method::kImplicitMidpoint ? 1e-10 : 2e-3) << to_string(m);
  }
}

TEST(Integrator, OutputSpacingOfFixedSteps) {
  const Solution s = integrate(oscillator(1.05), Options{.method = Method::kRk4, .dt = 0.01,
                                                         .output_dt = 0.1});
  ASSERT_EQ(s.t.size(), 12u);  // 0, 0.1, ..., 1.0 and the final t_end
  EXPECT_EQ(s.t.back(), 1.05);
  EXPECT_EQ(s.steps, 105u);
}

TEST(Integrator, ParsesMethodNames) {
  EXPECT_EQ(parse_method("implicit_midpoint"), Method::kImplicitMidpoint);
  EXPECT_RIGID_ERROR((void)parse_method("euler"), "unknown integrator 'euler'");
}

TEST(Integrator, RejectsBadOptions) {
  EXPECT_RIGID_ERROR((void)integrate(oscillator(1.0), Options{.dt = -1}),
                     "dt must be positive and finite, got -1 s");
  EXPECT_RIGID_ERROR((void)integrate(oscillator(-1.0), Options{}),
                     "t_end = -1 s must be finite and greater than t0 = 0 s");
}

TEST(Integrator, FixedStepsFollowTheOneStepRule) {
  // output_dt = 0.1 with dt = 0.03: each interval takes ⌈0.1/0.03⌉ = 4 equal steps of 0.025 s
  const Solution s = integrate(oscillator(1.0), Options{.method = Method::kRk4, .dt = 0.03,
                                                        .output_dt = 0.1});
  ASSERT_EQ(s.t.size(), 11u);
  EXPECT_EQ(s.steps, 40u);
  // RK4's error at h = 0.025 over 1 s is ~h⁴/120·t ≈ 3e-9, well inside 1e-8
  EXPECT_NEAR(s.y.back()[0], std::cos(1.0), 1e-8);
}

TEST(Integrator, StopsOnNonFiniteStateNamingTheComponent) {
  // y' = y², y(0) = 1 blows up at t = 1
  Problem p;
  p.rhs = [](double, const Eigen::VectorXd& y, Eigen::VectorXd& d) { d[0] = y[0] * y[0]; };
  p.y0 = Eigen::VectorXd::Constant(1, 1.0);
  p.t_end = 2.0;
  p.names = {"x"};
  EXPECT_RIGID_ERROR((void)integrate(p, Options{.method = Method::kRk4, .dt = 0.1}),
                     "non-finite state at step");
  EXPECT_RIGID_ERROR((void)integrate(p, Options{.method = Method::kRk4, .dt = 0.1}), "x = ");
}

// y' = y², y(0) = 1 by the implicit midpoint: y1 = y0 + h m², m = (y0 + y1)/2, so
// m = y0 + (h/2) m², a quadratic with the root m = (1 − √(1 − 2 h y0))/h (the one that tends
// to y0 as h → 0) when 2 h y0 ≤ 1 and no real root otherwise.
Problem blow_up(double t_end) {
  Problem p;
  p.rhs = [](double, const Eigen::VectorXd& y, Eigen::VectorXd& d) { d[0] = y[0] * y[0]; };
  p.y0 = Eigen::VectorXd::Constant(1, 1.0);
  p.t_end = t_end;
  return p;
}

double midpoint_step_of_blow_up(double y0, double h) {
  const double m = (1.0 - std::sqrt(1.0 - 2.0 * h * y0)) / h;
  return 2.0 * m - y0;
}

TEST(Integrator, ImplicitMidpointThatDoesNotConvergeIsRefused) {
  // steps of 1/8 s (exact binary times): 2 h y0 = 0.25, 0.29, …, 0.68 at the first six steps
  // (a solution exists), 1.055 at the seventh (y0 = 4.22, from t = 0.75 s): no solution, so no
  // Newton iteration converges and the step is refused
  const Problem p = blow_up(1.0);
  const Options o{.method = Method::kImplicitMidpoint, .dt = 0.125};
  EXPECT_RIGID_ERROR(
      (void)integrate(p, o),
      "at step 7 from t = 0.75 s: integrate(): implicit midpoint: the Newton iteration "
      "did not converge in 30 iterations (with the kept Jacobian, then with a fresh "
      "one): h = 0.125 s; the residual of the implicit equation, |y1 − y0 − h f(t + h/2, "
      "(y0 + y1)/2)|∞ = ");
  EXPECT_RIGID_ERROR((void)integrate(p, o), "above the tolerance");
  EXPECT_RIGID_ERROR((void)integrate(p, o), "use a smaller step dt");
  EXPECT_RIGID_ERROR(
      (void)integrate(p, Options{.method = Method::kImplicitMidpoint, .max_newton = 0}),
      "the implicit midpoint needs max_newton ≥ 1 and a positive, finite newton_tol, "
      "got 0 and 1e-14");
}

TEST(Integrator, ImplicitMidpointStepsThatConvergeSolveTheirEquation) {
  // the first three steps of the run above, each against the root of its quadratic: Newton
  // stops when its correction is ≤ newton_tol · max(1, |y0|) ≤ 1.4e-14, and the simplified
  // iteration contracts by ≈ 0.01 here (J at y0 against J at the midpoint), so the error left
  // is far below that; the closed form rounds to a few ulps of y ≈ 1.4 (its 1 − √(1 − 2 h y0)
  // cancels to 0.13 of 1, ≈ 8 ulps): 2e-14
  const Solution s =
      integrate(blow_up(0.375), Options{.method = Method::kImplicitMidpoint, .dt = 0.125});
  ASSERT_EQ(s.y.size(), 4u);
  for (std::size_t k = 1; k < 4; ++k) {
    EXPECT_NEAR(s.y[k][0], midpoint_step_of_blow_up(s.y[k - 1][0], 0.125), 2e-14) << "step " << k;
  }
}

// rtol = 1e-300 never advanced (dopri5's error estimate is round-off, the step shrank to
// nothing) and, sampling every step, grew by 65 MB/s: tolerances below 10 ε are refused.
TEST(Integrator, Dopri5RefusesToleranceBelowDoublePrecision) {
  EXPECT_RIGID_ERROR((void)integrate(oscillator(1.0), Options{.rtol = 1e-300}),
                     "dopri5 relative tolerance rtol = 1e-300 is below what double precision can deliver; "
                     "expected rtol ≥ 2.22e-15 (10 ε)");
  EXPECT_RIGID_ERROR((void)integrate(oscillator(1.0), Options{.rtol = 1e-16}), "below what double precision");
  // the floor itself is accepted and meets the cosine to 1e-12 (the tolerance of a 1 s run)
  const Solution s = integrate(oscillator(1.0), Options{.rtol = kMinRelativeTolerance, .atol = 1e-14});
  EXPECT_NEAR(s.y.back()[0], std::cos(1.0), 1e-12);
  // fixed-step methods do not use it
  EXPECT_NO_THROW((void)integrate(oscillator(1.0), Options{.method = Method::kRk4, .rtol = 1e-300}));
}

// rtol = 1e300 returned 5.8e20 for a unit oscillator (every step the stability allows was
// accepted): tolerances above kMaxTolerance = 0.1 are refused, rtol and atol each by name.
TEST(Integrator, Dopri5RefusesToleranceAboveTheBound) {
  EXPECT_RIGID_ERROR((void)integrate(oscillator(1.0), Options{.rtol = 1e300}),
                     "rtol = 1e+300 is above 0.1, the loosest tolerance an error control honours");
  EXPECT_RIGID_ERROR((void)integrate(oscillator(1.0), Options{.atol = 0.2}), "expected atol ≤ 0.1");
  // the bound itself is accepted; at 0.1 per step the 1 s run is still within 0.1 of the cosine
  // (10% of the unit amplitude per step, over the few steps of a 1 s run)
  const Solution s = integrate(oscillator(1.0), Options{.rtol = kMaxTolerance, .atol = kMaxTolerance});
  EXPECT_NEAR(s.y.back()[0], std::cos(1.0), 0.1);
  // fixed-step methods do not use them
  EXPECT_NO_THROW((void)integrate(oscillator(1.0), Options{.method = Method::kRk4, .rtol = 1e300}));
}

// y' = −sign(y) chatters about y = 0 after t = 1; with a vanishing absolute tolerance no step
// meets the error test there, and the accepted step falls to the round-off of t. That is an
// error naming t, not a run that stands still (it used to sample the same t forever).
TEST(Integrator, Dopri5StepUnderflowIsAnError) {
  Problem p;
  p.rhs = [](double, const Eigen::VectorXd& y, Eigen::VectorXd& d) { d[0] = y[0] > 0 ? -1.0 : y[0] < 0 ? 1.0 : 0.0; };
  p.y0 = Eigen::VectorXd::Constant(1, 1.0);
  p.t_end = 2.0;
  const auto run = [&] { (void)integrate(p, Options{.rtol = 1e-10, .atol = 1e-300}); };
  EXPECT_THAT(run, ::testing::ThrowsMessage<Error>(::testing::AnyOf(
                       ::testing::HasSubstr("dopri5 step size underflow at t = "),
                       ::testing::HasSubstr("dopri5 found no step size that meets the tolerance"))));
}

// dopri5 without an output spacing records every step; their number is known only while it
// runs, so the cap (set by a front end from its memory limit) is applied as they come.
TEST(Integrator, Dopri5EveryStepRowsAreCapped) {
  Options o{.rtol = 1e-12, .atol = 1e-12};
  o.control.max_outputs = 10;
  EXPECT_RIGID_ERROR((void)integrate(oscillator(10.0), o),
                     "dopri5 without an output spacing records every step: more than 10 rows");
  o.output_dt = 1.0;  // 11 rows on a grid: the cap is the front end's to check before the run
  EXPECT_EQ(integrate(oscillator(10.0), o).t.size(), 11u);
}

}  // namespace
}  // namespace rigid::integrate

namespace rigid::integrate {
namespace {

// Every accepted step reaches control.on_step: the spans tile [t0, t_end] in order, the state
// is the step's end, and dopri5's dense output inside a step is the solution to its tolerance
// (cos t at the step's midpoint within 1e-8 at rtol = atol = 1e-10: the continuous extension
// is one order below the step, and a step at this tolerance is ~0.05 s).
TEST(Integrator, OnStepSeesEveryStepWithItsStateAndDenseOutput) {
  for (Method m : {Method::kRk4, Method::kDopri5, Method::kImplicitMidpoint, Method::kStormerVerlet}) {
    SCOPED_TRACE(to_string(m));
    Options o{.method = m, .dt = 1e-2, .output_dt = 0.25};
    std::size_t seen = 0;
    double reached = 0.0, worst = 0.0;
    o.control.on_step = [&](const StepView& v) {
      ++seen;
      EXPECT_NEAR(v.t0, reached, 1e-15);  // t0 + j·h against the last step's t + h: round-off
      EXPECT_GT(v.t1, v.t0);
      reached = v.t1;
      ASSERT_EQ(v.y.size(), 2u);
      if (v.dense) {
        std::array<double, 2> mid{};
        const double tm = 0.5 * (v.t0 + v.t1);
        v.dense(tm, mid);
        worst = std::max(worst, std::abs(mid[0] - std::cos(tm)));
      }
    };
    const Solution s = integrate(oscillator(2.0), o);
    EXPECT_EQ(seen, s.steps);
    // the last fixed step ends on t_end; dopri5's may pass it (its dense output closes the run)
    if (m == Method::kDopri5) {
      EXPECT_GE(reached, 2.0);
    } else {
      EXPECT_EQ(reached, 2.0);
    }
    if (m == Method::kDopri5) {
      EXPECT_LT(worst, 1e-8);
    }
  }
}

}  // namespace
}  // namespace rigid::integrate
