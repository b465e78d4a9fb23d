#include "rigid/lagrange/linearize.hpp"

#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::lagrange {
namespace {

constexpr double kPi = std::numbers::pi;

// Two point masses m on massless rods of length l, angles from the downward vertical:
// L = m l² θ̇1² + ½ m l² θ̇2² + m l² θ̇1 θ̇2 cos(θ1 − θ2) + 2 m g l cos θ1 + m g l cos θ2.
SystemSpec double_pendulum(double theta1, double theta2) {
  SystemSpec spec;
  spec.parameters = {{"m", 0.7}, {"l", 1.3}, {"g", 9.81}};
  spec.coordinates = {{"theta1", theta1, 0.0}, {"theta2", theta2, 0.0}};
  spec.lagrangian =
      "m*l^2*theta1_dot^2 + m*l^2/2*theta2_dot^2 + m*l^2*theta1_dot*theta2_dot*cos(theta1 - theta2)"
      " + 2*m*g*l*cos(theta1) + m*g*l*cos(theta2)";
  return spec;
}

// Relative accuracy of the frequencies: the symmetric eigenproblem of a 2 × 2 pencil with
// condition (2 + √2)/(2 − √2) ≈ 5.8 loses a few ulps; 1e-10 is the acceptance bound.
constexpr double kRel = 1e-10;

TEST(NormalModes, DoublePendulumFromHorizontalFindsTheDownwardEquilibrium) {
  // started with both rods horizontal, where K = 0 and Newton stalls: the search follows the
  // damped motion down to θ = 0
  const System sys(double_pendulum(kPi / 2, kPi / 2));
  const NormalModes r = normal_modes(sys);
  ASSERT_EQ(r.modes.size(), 2u);
  EXPECT_TRUE(r.searched);
  EXPECT_NEAR(r.q[0], 0.0, 1e-12);  // Newton's last step: round-off of f ≈ 1e-16·m g l
  EXPECT_NEAR(r.q[1], 0.0, 1e-12);
  EXPECT_FALSE(r.gyroscopic);
  EXPECT_EQ(r.stability, Stability::kStable);
  // ω² = g (2 ∓ √2) / l for equal masses and lengths
  const double g = 9.81, l = 1.3;
  const double w2[2] = {g * (2 - std::sqrt(2.0)) / l, g * (2 + std::sqrt(2.0)) / l};
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(r.modes[k].omega_squared, w2[k], kRel * w2[k]);
    EXPECT_NEAR(r.modes[k].omega, std::sqrt(w2[k]), kRel * std::sqrt(w2[k]));
    EXPECT_NEAR(r.modes[k].hz, std::sqrt(w2[k]) / (2 * kPi), kRel * std::sqrt(w2[k]));
    EXPECT_EQ(r.modes[k].stability, Stability::kStable);
  }
  // shapes: θ2/θ1 = +√2 (slow, in phase) and −√2 (fast), M-normalised φᵀ M φ = 1
  const Eigen::VectorXd s0 = r.modes[0].shape.real(), s1 = r.modes[1].shape.real();
  EXPECT_NEAR(s0[1] / s0[0], std::sqrt(2.0), 1e-12);  // eigenvector error ~ ε κ
  EXPECT_NEAR(s1[1] / s1[0], -std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s0.dot(r.M * s0), 1.0, 1e-13);
  EXPECT_NEAR(s1.dot(r.M * s1), 1.0, 1e-13);
  EXPECT_NEAR(s0.dot(r.M * s1), 0.0, 1e-13);  // M-orthogonal
  EXPECT_DOUBLE_EQ(r.modes[0].shape.imag().cwiseAbs().maxCoeff(), 0.0);
}

TEST(NormalModes, InvertedDoublePendulumIsUnstable) {
  // both rods up, given: ω² = −g (2 ± √2)/l, two growing modes
  const System sys(double_pendulum(0.0, 0.0));
  const NormalModes r = normal_modes(sys, {.at = {{"theta1", kPi}, {"theta2", kPi}}});
  EXPECT_FALSE(r.searched);
  EXPECT_EQ(r.stability, Stability::kUnstable);
  const double g = 9.81, l = 1.3;
  ASSERT_EQ(r.modes.size(), 2u);
  EXPECT_NEAR(r.modes[0].omega_squared, -g * (2 + std::sqrt(2.0)) / l, kRel * 30);
  EXPECT_NEAR(r.modes[1].omega_squared, -g * (2 - std::sqrt(2.0)) / l, kRel * 30);
  EXPECT_NEAR(r.modes[0].growth_rate, std::sqrt(g * (2 + std::sqrt(2.0)) / l), kRel * 6);
  EXPECT_EQ(r.modes[0].stability, Stability::kUnstable);
}

TEST(NormalModes, PhysicalPendulum) {
  // a body with its COM at d below the pivot, turning about y: ω0² = m g d / I_p,
  // I_p = I_c + m d² (parallel axes)
  SystemSpec spec;
  spec.parameters = {{"m", 0.5}, {"d", 0.4}, {"Ic", 0.03}, {"g", 9.81}};
  spec.coordinates = {{"theta", 1.0, 0.0}};
  Body rod;
  rod.name = "rod";
  rod.mass.mass = "m";
  rod.mass.inertia = {Expression("Ic"), Expression("Ic"), Expression("0.001"), Expression("0"),
                      Expression("0"), Expression("0")};
  rod.position = {Expression("-d*sin(theta)"), Expression("0"), Expression("-d*cos(theta)")};
  rod.rotations = {{Eigen::Vector3d::UnitY(), Expression("theta")}};  // body z to the pivot
  spec.bodies = {rod};
  spec.gravity_W = Eigen::Vector3d(0, 0, -9.81);
  const NormalModes r = normal_modes(System(spec));
  ASSERT_EQ(r.modes.size(), 1u);
  const double w2 = 0.5 * 9.81 * 0.4 / (0.03 + 0.5 * 0.16);
  EXPECT_NEAR(r.q[0], 0.0, 1e-12);
  EXPECT_NEAR(r.modes[0].omega_squared, w2, kRel * w2);
  EXPECT_EQ(r.stability, Stability::kStable);
  // M-normalised: φ = 1/√I_p
  EXPECT_NEAR(r.modes[0].shape[0].real(), 1 / std::sqrt(0.03 + 0.08), 1e-13);
}

// A symmetric top on a pivot, tilted by a (about x) then b (about y), spinning by psi about its
// axis; COM at d on the axis above the pivot; I1 about the COM (transverse), I3 (axial).
SystemSpec sleeping_top(double spin) {
  SystemSpec spec;
  spec.parameters = {{"m", 1.0}, {"d", 0.03}, {"I1c", 4.0833e-4}, {"I3", 8e-4}, {"g", 9.81}};
  spec.coordinates = {{"a", 0.0, 0.0}, {"b", 0.0, 0.0}, {"psi", 0.0, spin}};
  Body top;
  top.name = "top";
  top.mass.mass = "m";
  top.mass.inertia = {Expression("I1c"), Expression("I1c"), Expression("I3"), Expression("0"),
                      Expression("0"), Expression("0")};
  top.position = {Expression("d*sin(b)"), Expression("-d*sin(a)*cos(b)"),
                  Expression("d*cos(a)*cos(b)")};
  top.rotations = {{Eigen::Vector3d::UnitX(), Expression("a")},
                   {Eigen::Vector3d::UnitY(), Expression("b")},
                   {Eigen::Vector3d::UnitZ(), Expression("psi")}};
  spec.bodies = {top};
  spec.gravity_W = Eigen::Vector3d(0, 0, -9.81);
  return spec;
}

TEST(NormalModes, SleepingTopIsStableAboveTheThresholdAndUnstableBelow) {
  // ω3² > 4 m g d I1 / I3² with I1 = I1c + m d² about the pivot [Goldstein2002, §5.7]
  const double m = 1.0, d = 0.03, g = 9.81, I1 = 4.0833e-4 + m * d * d, I3 = 8e-4;
  const double critical = 2 * std::sqrt(m * g * d * I1) / I3;
  for (const double factor : {1.01, 0.99}) {
    const double spin = factor * critical;
    const NormalModes r = normal_modes(System(sleeping_top(spin)));
    ASSERT_EQ(r.ignorable_names, std::vector<std::string>{"psi"});
    EXPECT_TRUE(r.gyroscopic);
    EXPECT_EQ(r.q_dot[2], spin);
    // a + i b ∝ e^{iωt}: I1 ω² − I3 Ω ω + m g d = 0
    const double disc = I3 * I3 * spin * spin - 4 * I1 * m * g * d;
    const double scale = I3 * spin / (2 * I1);
    // the eigenvalues of the 4 × 4 state matrix, separated by √|disc|/(2 I1) ≈ 0.14 scale:
    // a few hundred ulps of the largest
    const double tol = 1e-12 * scale;
    if (factor > 1) {
      EXPECT_EQ(r.stability, Stability::kStable) << to_text(r);
      ASSERT_EQ(r.modes.size(), 2u);
      EXPECT_NEAR(r.modes[0].omega, scale - std::sqrt(disc) / (2 * I1), tol);
      EXPECT_NEAR(r.modes[1].omega, scale + std::sqrt(disc) / (2 * I1), tol);
      EXPECT_NEAR(r.modes[0].growth_rate, 0.0, tol);
    } else {
      EXPECT_EQ(r.stability, Stability::kUnstable) << to_text(r);
      const double growth = std::sqrt(-disc) / (2 * I1);
      double largest = 0;
      for (const Mode& md : r.modes) {
        largest = std::max(largest, md.growth_rate);
        EXPECT_NEAR(md.omega, scale, tol);
      }
      EXPECT_NEAR(largest, growth, tol);
    }
  }
}

TEST(NormalModes, CartPendulumReducesTheCyclicCart) {
  // a pendulum (m, l) hanging from a free cart (mass Mc): x is cyclic; with its momentum held,
  // ω² = g (Mc + m) / (Mc l), and the cart moves by δx = −m l / (Mc + m) δθ
  SystemSpec spec;
  spec.parameters = {{"Mc", 2.0}, {"m", 0.5}, {"l", 0.8}, {"g", 9.81}};
  spec.coordinates = {{"x", 0.3, 0.0}, {"theta", 0.2, 0.0}};
  spec.lagrangian = "(Mc + m)/2*x_dot^2 + m*l*x_dot*theta_dot*cos(theta) + m*l^2/2*theta_dot^2"
                    " + m*g*l*cos(theta)";
  const NormalModes r = normal_modes(System(spec));
  ASSERT_EQ(r.ignorable_names, std::vector<std::string>{"x"});
  ASSERT_EQ(r.modes.size(), 1u);
  const double w2 = 9.81 * 2.5 / (2.0 * 0.8);
  EXPECT_NEAR(r.modes[0].omega_squared, w2, kRel * w2);
  EXPECT_EQ(r.q[0], 0.3);  // the cart stays where it was
  const Eigen::VectorXd phi = r.modes[0].shape.real();
  EXPECT_NEAR(phi[0] / phi[1], -0.5 * 0.8 / 2.5, 1e-14);
  EXPECT_NEAR(phi.dot(r.M * phi), 1.0, 1e-13);  // the Schur complement: φᵀ M φ = φ_θ² M̃
}

TEST(NormalModes, DampedOscillatorUsesTheStateSpaceProblem) {
  // m ẍ + c ẋ + k x = 0: λ = −c/2m ± i √(k/m − c²/4m²)
  SystemSpec spec;
  spec.parameters = {{"m", 2.0}, {"k", 50.0}, {"c", 3.0}};
  spec.coordinates = {{"x", 0.1, 0.0}};
  spec.lagrangian = "m/2*x_dot^2 - k/2*x^2";
  spec.forces = {{"x", "-c*x_dot"}};
  const NormalModes r = normal_modes(System(spec));
  EXPECT_TRUE(r.gyroscopic);
  ASSERT_EQ(r.modes.size(), 1u);
  EXPECT_NEAR(r.modes[0].growth_rate, -0.75, 1e-13);
  EXPECT_NEAR(r.modes[0].omega, std::sqrt(25.0 - 0.5625), 1e-13);
  EXPECT_EQ(r.stability, Stability::kStable);
}

TEST(NormalModes, RefusesWithAReason) {
  const System dp(double_pendulum(0.1, 0.1));
  EXPECT_RIGID_ERROR((void)normal_modes(dp, {.at = {{"theta3", 0.0}}}),
                     "unknown coordinate 'theta3'; did you mean");
  EXPECT_RIGID_ERROR((void)normal_modes(dp, {.at = {{"theta1_dot", 1.0}}}),
                     "'theta1' is not one (the system has no cyclic coordinates)");
  // theta1 held at 0.5: theta2 is found (0), but theta1's equation does not balance
  EXPECT_RIGID_ERROR((void)normal_modes(dp, {.at = {{"theta1", 0.5}}}),
                     "is not an equilibrium: the generalized force on 'theta1'");
  EXPECT_RIGID_ERROR((void)normal_modes(dp, {.parameters = {{"q", 1.0}}}), "unknown parameter 'q'");

  SystemSpec falling;  // a constant force: no equilibrium anywhere
  falling.coordinates = {{"z", 0.0, 0.0}};
  falling.lagrangian = "z_dot^2/2 - 9.81*z";
  EXPECT_RIGID_ERROR((void)normal_modes(System(falling)), "no equilibrium found from (z = 0)");

  SystemSpec driven = falling;
  driven.lagrangian = "z_dot^2/2 - z^2/2 + z*sin(t)";
  EXPECT_RIGID_ERROR((void)normal_modes(System(driven)), "depends on the time t");

  // a knife edge (x_dot·sin(th) − y_dot·cos(th) = 0) in a bowl: velocity constraints are
  // refused, not linearised as if they were absent
  SystemSpec blade;
  blade.coordinates = {{"x", 0.1, 0.0}, {"y", 0.0, 0.0}, {"th", 0.0, 0.0}};
  blade.lagrangian = "(x_dot^2 + y_dot^2 + th_dot^2)/2 - (x^2 + y^2)/2";
  blade.velocity_constraints = {{"blade", {{"x", "sin(th)"}, {"y", "-cos(th)"}}, "", {}}};
  EXPECT_RIGID_ERROR((void)normal_modes(System(blade)),
                     "the system has velocity constraints (blade); normal modes are computed for "
                     "holonomic systems only");
}

// A point mass m on a rod of length l in Cartesian coordinates: g = x² + y² − l² = 0.
SystemSpec cartesian_pendulum() {
  SystemSpec spec;
  spec.parameters = {{"m", 0.3}, {"l", 0.9}, {"g", 9.81}};
  spec.coordinates = {{"x", 0.9, 0.0}, {"y", 0.0, 0.0}};  // the rod horizontal
  spec.lagrangian = "m/2*(x_dot^2 + y_dot^2) - m*g*y";
  spec.constraints = {{"rod", "x^2 + y^2 - l^2"}};
  return spec;
}

TEST(NormalModes, ConstrainedPendulumOnTheCircle) {
  // the search slides along the circle to the bottom (0, −l); there f + Gᵀλ = 0 gives
  // λ = −m g / (2 l) (the rod's tension m g, per unit of ∂g/∂y = −2 l), the constraint force's
  // change adds −λ ∂²g/∂q² = (m g / l) 1 to K, and on the tangent (x) ω² = g / l
  const NormalModes r = normal_modes(System(cartesian_pendulum()));
  const double m = 0.3, l = 0.9, g = 9.81;
  EXPECT_NEAR(r.q[0], 0.0, 1e-12);
  EXPECT_NEAR(r.q[1], -l, 1e-12);
  ASSERT_EQ(r.lambda.size(), 1);
  EXPECT_NEAR(r.lambda[0], -m * g / (2 * l), test::ulps(16, m * g / l));
  ASSERT_EQ(r.modes.size(), 1u);
  EXPECT_NEAR(r.modes[0].omega_squared, g / l, kRel * g / l);
  EXPECT_EQ(r.stability, Stability::kStable);
  // the shape is tangent to the circle: along x, M-normalised (m φ² = 1)
  EXPECT_NEAR(r.modes[0].shape[0].real(), 1 / std::sqrt(m), 1e-14);
  EXPECT_NEAR(std::abs(r.modes[0].shape[1]), 0.0, 1e-14);
  // the top of the circle, given: unstable with ω² = −g / l
  const NormalModes top = normal_modes(System(cartesian_pendulum()), {.at = {{"x", 0.0}, {"y", 0.9}}});
  EXPECT_EQ(top.stability, Stability::kUnstable);
  EXPECT_NEAR(top.modes[0].omega_squared, -g / l, kRel * g / l);
  // a point off the circle is refused, naming the constraint
  EXPECT_RIGID_ERROR((void)normal_modes(System(cartesian_pendulum()), {.at = {{"x", 0.0}, {"y", -0.5}}}),
                     "violates the constraint 'rod' by");
}

TEST(NormalModes, ToTextNamesTheModes) {
  const std::string text = to_text(normal_modes(System(double_pendulum(0.0, 0.0))));
  EXPECT_THAT(text, ::testing::HasSubstr("stability: stable"));
  EXPECT_THAT(text, ::testing::HasSubstr("mode 2: oscillating, omega = "));
}

}  // namespace
}  // namespace rigid::lagrange
