// What normal_modes takes for an equilibrium: a point within round-off of balance, where the
// round-off of a coordinate is 1e-9 or 64 ulps of its value (not a fraction of the value
// itself), and the point the search found by its own criterion at a degenerate minimum.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "rigid/lagrange/linearize.hpp"
#include "support/expect_error.hpp"

namespace rigid::lagrange {
namespace {

constexpr double kPi = std::numbers::pi;

// A simple pendulum, m l² θ̇²/2 + m g l cos θ (m = 1 kg, l = 1 m, g = 9.81 m/s²): k = 9.81 N·m/rad.
System pendulum() {
  SystemSpec spec;
  spec.parameters = {{"g", 9.81}};
  spec.coordinates = {{"theta", 0.0, 0.0}};
  spec.lagrangian = "theta_dot^2/2 + g*cos(theta)";
  return System(spec);
}

TEST(ModesEquilibrium, AHugeAngleDoesNotWidenTheTolerance) {
  // 1e9π + 0.5 rad is half a radian from hanging: the torque is g sin(0.5) ≈ 4.7 N·m whatever
  // the number of turns before it
  const double turns = 1e9 * kPi;
  EXPECT_RIGID_ERROR((void)normal_modes(pendulum(), {.at = {{"theta", turns + 0.5}}}),
                     "is not an equilibrium");
  // 1e9π itself is an equilibrium to the resolution of the double that holds it: its rounding
  // (≤ ulp(3.1e9)/2 = 2.4e-7 rad) leaves a torque of about 2.4e-6 N·m, below k · 64 ε |θ| =
  // 4.4e-4 N·m; an even number of half turns hangs (stable), an odd one stands (unstable)
  const NormalModes down = normal_modes(pendulum(), {.at = {{"theta", turns}}});
  EXPECT_EQ(down.stability, Stability::kStable);
  EXPECT_NEAR(down.modes.at(0).omega, std::sqrt(9.81), 1e-6);
  const NormalModes up = normal_modes(pendulum(), {.at = {{"theta", turns + kPi}}});
  EXPECT_EQ(up.stability, Stability::kUnstable);
}

TEST(ModesEquilibrium, TheSearchesPointAtAQuarticMinimumIsAccepted) {
  // V = x⁴/4: the force −x³ and the stiffness 3x² both vanish at x = 0, so the search (Newton,
  // linear convergence here) stops at a small x where the force is round-off of the start's
  SystemSpec spec;
  spec.coordinates = {{"x", 1.0, 0.0}};
  spec.lagrangian = "x_dot^2/2 - x^4/4";
  const NormalModes r = normal_modes(System(spec));
  EXPECT_TRUE(r.searched);
  EXPECT_LT(std::abs(r.q[0]), 1e-3);
  // and a point given far from 0 is still refused: x = 0.1 leaves a force of 1e-3 N
  EXPECT_RIGID_ERROR((void)normal_modes(System(spec), {.at = {{"x", 0.1}}}),
                     "is not an equilibrium");
}

}  // namespace
}  // namespace rigid::lagrange
