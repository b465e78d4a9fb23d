// [[velocity_constraints]] in scenes: parsed with their places, turned into the System's rows,
// run with their multipliers and residual in the trajectory and the summary, refused at
// file:line:col.
#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "support/expect_error.hpp"

namespace rigid::scene {
namespace {

// The Chaplygin sleigh (examples/chaplygin_sleigh.toml, smaller): m = 1, I = 0.1, a = 0.3.
constexpr std::string_view kSleigh = R"toml([parameters]
m = 1.0
I = 0.1
a = 0.3
[[coordinates]]
name = "x"
velocity = 0.5
[[coordinates]]
name = "y"
[[coordinates]]
name = "theta"
velocity = 2.0
[[bodies]]
name = "sleigh"
inertia = { mass = "m", com = ["a", 0, 0], ixx = 0.05, iyy = 0.07, izz = "I" }
position = ["x", "y", 0]
rotation = [{axis = [0, 0, 1], angle = "theta"}]
[[velocity_constraints]]
name = "blade"
coefficients = { x = "-sin(theta)", y = "cos(theta)" }
[simulation]
t_end = 1.0
integrator = "dopri5"
tolerance = 1e-11
output_dt = 0.1
)toml";

std::string replaced(std::string_view base, const std::string& from, const std::string& to) {
  std::string s(base);
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(SceneVelocityConstraints, ParsesNameCoefficientsTermAndPlace) {
  const Scene s = parse_scene(replaced(kSleigh, "y = \"cos(theta)\" }", "y = \"cos(theta)\" }\nterm = 0"),
                              "s.toml");
  ASSERT_EQ(s.velocity_constraints.size(), 1u);
  const VelocityConstraint& vc = s.velocity_constraints[0];
  EXPECT_EQ(vc.name, "blade");
  ASSERT_EQ(vc.coefficients.size(), 2u);
  EXPECT_EQ(vc.coefficients[0].name, "x");
  EXPECT_EQ(vc.coefficients[0].expression.text, "-sin(theta)");
  EXPECT_EQ(vc.coefficients[0].expression.where.line, 20);
  ASSERT_TRUE(vc.term.has_value());
  EXPECT_EQ(vc.term->text, "0");
  EXPECT_EQ(vc.where.file, "s.toml");
}

TEST(SceneVelocityConstraints, RunReportsMultipliersAndResidual) {
  const Model model(parse_scene(kSleigh, "s.toml"));
  EXPECT_EQ(model.system().velocity_constraint_names(), std::vector<std::string>{"blade"});
  const RunResult r = model.run();
  const io::Table& tr = r.trajectory;
  const std::size_t mu = tr.column("mu_blade"), res = tr.column("velocity_constraint_residual");
  const std::size_t th = tr.column("theta"), xd = tr.column("x_dot"), yd = tr.column("y_dot"),
                    wd = tr.column("theta_dot");
  // closed form [Bloch2015, ch. 1]: v = V tanh s, ω = ω0 cosh s0 / cosh s, s = (a m V/J) t + s0
  const double m = 1.0, I = 0.1, a = 0.3, v0 = 0.5, w0 = 2.0, J = I + m * a * a;
  const double V = std::sqrt(v0 * v0 + J * w0 * w0 / m), s0 = std::atanh(v0 / V);
  for (std::size_t k = 0; k < tr.rows(); ++k) {
    const double t = tr(k, 0), s = a * m * V / J * t + s0;
    const double v = tr(k, xd) * std::cos(tr(k, th)) + tr(k, yd) * std::sin(tr(k, th));
    // dopri5 at 1e-11 over 1 s on O(1) values: errors ≲ 1e-10
    EXPECT_NEAR(v, V * std::tanh(s), 1e-8) << "t = " << t;
    EXPECT_NEAR(tr(k, wd), w0 * std::cosh(s0) / std::cosh(s), 1e-8) << "t = " << t;
    // the blade's sideways force m I v ω / J (the same tolerance)
    EXPECT_NEAR(tr(k, mu), m * I * v * tr(k, wd) / J, 1e-8) << "t = " << t;
    EXPECT_LE(tr(k, res), 1e-9);
  }
  bool reported = false;
  for (const auto& [name, value] : r.summary.diagnostics) {
    if (name == "velocity_constraint_residual_max") reported = value <= 1e-9;
  }
  EXPECT_TRUE(reported);
}

TEST(SceneVelocityConstraints, RefusalsAreLocated) {
  // an unknown coordinate, at its key
  EXPECT_RIGID_ERROR((void)parse_scene(replaced(kSleigh, "{ x = \"-sin", "{ xx = \"-sin"), "s.toml"),
                     "s.toml:20:18: [[velocity_constraints]] entry 1 coefficients: 'xx' is not a "
                     "coordinate; did you mean 'x'?");
  // a velocity in a coefficient, at the velocity inside the string
  EXPECT_RIGID_ERROR((void)Model(parse_scene(replaced(kSleigh, "\"-sin(theta)\"", "\"-theta_dot\""), "s.toml")),
                     "s.toml:20:24: velocity constraint 'blade' coefficient of 'x': depends on the "
                     "velocity 'theta_dot'");
  // a term not linear in the velocities, at the term
  EXPECT_RIGID_ERROR((void)Model(parse_scene(replaced(kSleigh, "y = \"cos(theta)\" }", "y = \"cos(theta)\" }\nterm = \"x_dot*theta_dot\""),
                                             "s.toml")),
                     "s.toml:21:9: velocity constraint 'blade' term: is not linear in the velocities");
  // no velocity at all, and two dependent rows, at the entry
  EXPECT_RIGID_ERROR((void)parse_scene(replaced(kSleigh, "coefficients = { x = \"-sin(theta)\", y = \"cos(theta)\" }", ""),
                                       "s.toml"),
                     "s.toml:18:1: [[velocity_constraints]] entry 1 has no velocity in it");
  EXPECT_RIGID_ERROR((void)Model(parse_scene(replaced(kSleigh, "[simulation]",
                                                      "[[velocity_constraints]]\nname = \"twice\"\n"
                                                      "coefficients = { x = \"-2*sin(theta)\", y = \"2*cos(theta)\" }\n"
                                                      "[simulation]"),
                                             "s.toml")),
                     "s.toml:21:1: velocity constraints 'blade', 'twice' are dependent for every q");
  // free bodies have no coordinates to constrain
  EXPECT_RIGID_ERROR((void)Model(parse_scene(R"toml([[bodies]]
name = "b"
free = true
primitive = "box"
size = [0.1, 0.2, 0.3]
mass = 1
[[velocity_constraints]]
term = "1"
[simulation]
t_end = 1
)toml", "f.toml")),
                     "f.toml:7:1: [[velocity_constraints]] act on coordinates");
}

}  // namespace
}  // namespace rigid::scene
