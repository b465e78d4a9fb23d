#include "rigid/integrate/march.hpp"

#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::integrate {
namespace {

const auto kNoNonFinite = [] { return std::optional<NonFinite>{}; };

TEST(TimeGrid, UniformSamplesAreWholeMultiplesAndCloseOnTheEnd) {
  const TimeGrid g = TimeGrid::uniform(0.0, 1.05, 0.1);
  ASSERT_EQ(g.size(), 12u);  // 0, 0.1, …, 1.0 and 1.05
  for (std::size_t k = 0; k <= 10; ++k) EXPECT_EQ(g[k], 0.1 * static_cast<double>(k));
  EXPECT_EQ(g[11], 1.05);
  EXPECT_EQ(g.start(), 0.0);
  // a span that is a whole multiple up to round-off (0.3/0.1 = 2.9999999999999996) gets no
  // sliver of an interval at the end
  const TimeGrid h = TimeGrid::uniform(0.0, 0.3, 0.1);
  ASSERT_EQ(h.size(), 4u);
  EXPECT_EQ(h[3], 0.3);
}

TEST(TimeGrid, StepRuleIsTheFewestEqualStepsNoLongerThanHmax) {
  const TimeGrid g = TimeGrid::from_times(0.0, {1.0, 1.0, 1.35});
  EXPECT_EQ(g.steps_in(0, 0.1, 1000), 10u);   // exact multiple: 1/0.1 = 10 up to round-off
  EXPECT_EQ(g.steps_in(1, 0.1, 1000), 0u);    // an empty interval takes no step
  EXPECT_EQ(g.steps_in(2, 0.1, 1000), 4u);    // 0.35/0.1 = 3.5 → 4 steps of 0.0875
  EXPECT_EQ(g.steps_in(2, 10.0, 1000), 1u);   // a step longer than the interval: one step
}

TEST(TimeGrid, RefusesCountsThatDoNotFitInsteadOfCasting) {
  const TimeGrid g = TimeGrid::from_times(0.0, {1.0});
  // 1/1e-300 = 1e300 steps: refused with the count, never converted to an integer
  EXPECT_RIGID_ERROR((void)g.steps_in(0, 1e-300, 1'000'000), "1e+300 steps, more than the 1000000 allowed");
  EXPECT_RIGID_ERROR((void)TimeGrid::uniform(0.0, 1.0, 1e-12), "more than the 50000000 a run may write");
  EXPECT_RIGID_ERROR((void)TimeGrid::uniform(0.0, 1.0, 0.0), "output spacing must be positive");
  EXPECT_RIGID_ERROR((void)TimeGrid::uniform(0.0, std::nan(""), 0.1), "must be finite");
  EXPECT_RIGID_ERROR((void)TimeGrid::from_times(0.0, {1.0, 0.5}), "entry 1 is 0.5 s after 1 s");
}

TEST(March, StepsEquallyBetweenOutputsAndLandsOnThem) {
  const TimeGrid g = TimeGrid::uniform(0.0, 1.0, 0.25);
  std::vector<double> step_times, output_times;
  double x = 0;  // integrates dx/dt = 1 exactly: x(t) = t up to the rounding of the sum
  const MarchStats stats = march(
      g, 0.1, [&](double t, double h) { step_times.push_back(t); x += h; }, kNoNonFinite,
      [&](std::size_t, double t) {
        output_times.push_back(t);
        EXPECT_NEAR(x, t, 1e-15);  // a dozen additions of h ≤ 0.1: a few ulps
      });
  EXPECT_EQ(stats.steps, 12u);  // 4 intervals of 0.25 s, 3 steps of 1/12 s each
  ASSERT_EQ(output_times.size(), 5u);
  EXPECT_EQ(output_times.back(), 1.0);
  EXPECT_EQ(step_times[3], 0.25);  // an interval starts at its output time exactly
}

TEST(March, NamesTheNonFiniteComponentTheStepAndTheTime) {
  const TimeGrid g = TimeGrid::uniform(0.0, 1.0, 0.5);
  double w = 1.0;
  int steps = 0;
  auto step = [&](double, double) {
    if (++steps == 3) w = std::numeric_limits<double>::quiet_NaN();
  };
  auto find = [&]() -> std::optional<NonFinite> {
    if (!std::isfinite(w)) return NonFinite{"body 'b2'", "w_B.y", w};
    return std::nullopt;
  };
  EXPECT_RIGID_ERROR((void)march(g, 0.1, step, find, [](std::size_t, double) {}),
                     "non-finite state at step 3, t = 0.30000000000000004 s: body 'b2' w_B.y = nan");
}

TEST(March, ProgressAndCancellation) {
  const TimeGrid g = TimeGrid::uniform(0.0, 10.0, 1.0);
  std::vector<double> reported;
  MarchControl control;
  control.progress = [&](double t) { reported.push_back(t); };
  (void)march(g, 0.5, [](double, double) {}, kNoNonFinite, [](std::size_t, double) {}, control);
  ASSERT_EQ(reported.size(), 11u);  // after every output (and every kPollSteps steps)
  EXPECT_EQ(reported.back(), 10.0);

  std::atomic<bool> cancel{false};
  MarchControl stop;
  stop.cancel = &cancel;
  int steps = 0;
  auto step = [&](double, double) {
    if (++steps == 5) cancel = true;
  };
  EXPECT_THAT([&] { (void)march(g, 0.5, step, kNoNonFinite, [](std::size_t, double) {}, stop); },
              ::testing::ThrowsMessage<Cancelled>(::testing::HasSubstr("cancelled at t = 2.5 s")));  // the step that saw it
}

TEST(March, RefusesABadStep) {
  const TimeGrid g = TimeGrid::uniform(0.0, 1.0, 0.5);
  EXPECT_RIGID_ERROR(
      (void)march(g, -1.0, [](double, double) {}, kNoNonFinite, [](std::size_t, double) {}),
      "the step h_max must be positive and finite, got -1 s");
  MarchControl few;
  few.max_steps = 10;
  EXPECT_RIGID_ERROR(
      (void)march(g, 0.01, [](double, double) {}, kNoNonFinite, [](std::size_t, double) {}, few),
      "50 steps, more than the 10 allowed");
}

// Ctrl-C inside one long output interval: the flag is read after every step, not only at the
// progress polls (every kPollSteps steps), so the run stops at the step that saw it.
TEST(March, CancelFlagIsReadEveryStep) {
  const TimeGrid g = TimeGrid::uniform(0.0, 1.0, 1.0);  // one interval of 1000 steps
  std::atomic<bool> cancel{false};
  MarchControl stop;
  stop.cancel = &cancel;
  int steps = 0;
  auto step = [&](double, double) {
    if (++steps == 7) cancel = true;
  };
  EXPECT_THAT([&] { (void)march(g, 1e-3, step, kNoNonFinite, [](std::size_t, double) {}, stop); },
              ::testing::ThrowsMessage<Cancelled>(::testing::HasSubstr("cancelled at t = 0.007")));
  EXPECT_EQ(steps, 7);
}

}  // namespace
}  // namespace rigid::integrate

namespace rigid::integrate {
namespace {

// control.on_step sees each step after its finiteness check: the spans tile the grid.
TEST(March, OnStepSeesEveryStepInOrder) {
  const TimeGrid grid = TimeGrid::uniform(0.0, 1.0, 0.3);
  std::vector<std::pair<double, double>> spans;
  MarchControl control;
  control.on_step = [&](const StepView& v) { spans.emplace_back(v.t0, v.t1); };
  const MarchStats stats = march(grid, 0.1, [](double, double) {}, kNoNonFinite, [](std::size_t, double) {}, control);
  ASSERT_EQ(spans.size(), stats.steps);
  EXPECT_EQ(spans.front().first, 0.0);
  EXPECT_EQ(spans.back().second, 1.0);
  // t0 + j·h against the previous step's t + h: equal up to round-off
  for (std::size_t i = 1; i < spans.size(); ++i) EXPECT_NEAR(spans[i].first, spans[i - 1].second, 1e-15);
}

TEST(March, AnErrorOfAStepNamesTheStepAndItsStart) {
  // an implicit step that does not converge (or any rigid::Error of a step) gets the place in
  // front once, here, for every stepping client; other exceptions pass unchanged
  const TimeGrid g = TimeGrid::uniform(0.0, 1.0, 0.5);
  int steps = 0;
  auto failing = [&](double, double) {
    if (++steps == 4) throw Error("the step did not converge");
  };
  EXPECT_RIGID_ERROR((void)march(g, 0.25, failing, kNoNonFinite, [](std::size_t, double) {}),
                     "at step 4 from t = 0.75 s: the step did not converge");
  EXPECT_THAT(
      [&] {
        (void)march(
            g, 0.25, [](double, double) { throw Cancelled("cancelled at t = 0 s"); }, kNoNonFinite,
            [](std::size_t, double) {});
      },
      ::testing::ThrowsMessage<Cancelled>(::testing::StrEq("cancelled at t = 0 s")));
  EXPECT_THAT(
      [&] {
        (void)march(
            g, 0.25, [](double, double) { throw std::runtime_error("not ours"); }, kNoNonFinite,
            [](std::size_t, double) {});
      },
      ::testing::ThrowsMessage<std::runtime_error>(::testing::StrEq("not ours")));
}

}  // namespace
}  // namespace rigid::integrate
