// The step limit of a run is stated as the run's: a refusal after earlier intervals counts the
// whole run and names the limit itself (it said "more than the 0 allowed" once the intervals
// before had used the budget).
#include "rigid/integrate/march.hpp"

#include <cstddef>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::integrate {
namespace {

TEST(TimeGrid, StepLimitIsTheRunsAcrossIntervals) {
  // outputs every 0.25 s to 1 s, steps of at most 2^-10 s (both exact in binary): 256 steps per
  // interval, 1024 for the run
  const double h = 1.0 / 1024;
  const TimeGrid g = TimeGrid::uniform(0.0, 1.0, 0.25);
  ASSERT_EQ(g.size(), 5u);  // the start 0 is the first output (an empty interval)
  std::size_t taken = 0;
  for (std::size_t k = 0; k < 3; ++k) taken += g.steps_in(k, h, 600, taken);
  EXPECT_EQ(taken, 512u);
  // the third interval would pass 600: the message has the run's count and the limit
  EXPECT_RIGID_ERROR((void)g.steps_in(3, h, 600, taken),
                     "1 s in steps of at most 0.0009765625 s is about 1024 steps, more than the 600 "
                     "a run may take (512 steps reach t = 0.5 s, and the next output at 0.75 s needs "
                     "256 more)");
  // the budget used up exactly: still the limit, never "0 allowed"
  EXPECT_RIGID_ERROR((void)g.steps_in(3, h, 512, taken), "more than the 512 a run may take");
}

TEST(TimeGrid, StepLimitWithNothingBeforeIsTheIntervalsCount) {
  const TimeGrid g = TimeGrid::uniform(0.0, 1.0, 0.5);
  EXPECT_EQ(g.steps_in(1, 0.1, 5), 5u);  // 0.5 / 0.1 = 5 steps: at the limit, allowed
  EXPECT_RIGID_ERROR((void)g.steps_in(1, 0.01, 5),
                     "0.5 s in steps of at most 0.01 s is 50 steps, more than the 5 allowed");
}

}  // namespace
}  // namespace rigid::integrate
