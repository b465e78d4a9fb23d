// The `lagrangian` key of a scene: the same system as rigid::lagrange::SystemSpec::lagrangian
// with the same text, and errors inside it at file:line:col (also in multi-line strings).
#include <cmath>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rigid/lagrange/linearize.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/modes.hpp"
#include "rigid/scene/scene.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::scene {
namespace {

constexpr const char* kLagrangian =
    "m*l^2*theta1_dot^2 + m*l^2/2*theta2_dot^2 + m*l^2*theta1_dot*theta2_dot*cos(theta1 - theta2) "
    "+ 2*m*g*l*cos(theta1) + m*g*l*cos(theta2)";

std::string scene_text(const std::string& lagrangian_line) {
  // the lagrangian comes first: after a [table] header a key would belong to that table
  return lagrangian_line + R"toml(
[parameters]
m = 0.7
l = 1.3
g = 9.81

[[coordinates]]
name = "theta1"
initial = 0.4
velocity = 0.3
[[coordinates]]
name = "theta2"
initial = -0.2
velocity = 1.1

[simulation]
t_end = 1.0
)toml";
}

TEST(SceneLagrangian, GivesTheAccelerationsOfTheStringApi) {
  const Model model(parse_scene(scene_text(fmt::format("lagrangian = \"{}\"", kLagrangian)), "dp.toml"));
  lagrange::SystemSpec spec;
  spec.parameters = {{"m", 0.7}, {"l", 1.3}, {"g", 9.81}};
  spec.coordinates = {{"theta1", 0.4, 0.3}, {"theta2", -0.2, 1.1}};
  spec.lagrangian = kLagrangian;
  const lagrange::System direct(spec);
  Eigen::VectorXd a_scene, a_direct, lambda;
  model.system().accelerations(0.0, model.system().initial_q(), model.system().initial_q_dot(), a_scene, lambda);
  direct.accelerations(0.0, direct.initial_q(), direct.initial_q_dot(), a_direct, lambda);
  // the same text derives the same expressions; GiNaC may order a sum's terms differently
  // in two derivations (its order follows its symbols' serial numbers), so the tapes agree to
  // the rounding of a few additions of terms of size |a|
  ASSERT_EQ(a_scene.size(), 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(a_scene[i], a_direct[i], test::ulps(64, a_direct.cwiseAbs().maxCoeff()));
}

TEST(SceneLagrangian, MultiLineStringsGiveTheSameSystem) {
  const Model one(parse_scene(scene_text(fmt::format("lagrangian = \"{}\"", kLagrangian)), "a.toml"));
  const Model many(parse_scene(scene_text(R"x(lagrangian = """
m*l^2*theta1_dot^2 + m*l^2/2*theta2_dot^2
  + m*l^2*theta1_dot*theta2_dot*cos(theta1 - theta2)
  + 2*m*g*l*cos(theta1) + m*g*l*cos(theta2)""")x"), "b.toml"));
  Eigen::VectorXd a1, a2, lambda;
  const Eigen::VectorXd q = one.system().initial_q(), qd = one.system().initial_q_dot();
  one.system().accelerations(0.0, q, qd, a1, lambda);
  many.system().accelerations(0.0, q, qd, a2, lambda);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(a1[i], a2[i], test::ulps(64, a1.cwiseAbs().maxCoeff()));  // as above
}

TEST(SceneLagrangian, ErrorsPointIntoTheFile) {
  // line 1 of the scene is the lagrangian; col 17 is the 'x' of "m*x" in lagrangian = "m*x"
  EXPECT_RIGID_ERROR(Model(parse_scene(scene_text("lagrangian = \"m*x\""), "e.toml")),
                     "e.toml:1:17: Lagrangian: ");
  // a multi-line basic string: the unknown name on its second line, column 5
  EXPECT_RIGID_ERROR(Model(parse_scene(scene_text("lagrangian = \"\"\"\nm*l^2*theta1_dot^2/2\n  + zz*theta2_dot^2\"\"\""), "f.toml")),
                     "f.toml:3:5: Lagrangian: ");
  // a literal multi-line string on one line: three columns for its delimiter
  EXPECT_RIGID_ERROR(Model(parse_scene(scene_text("lagrangian = '''theta1_dot^2 + qq'''"), "g.toml")),
                     "g.toml:1:32: Lagrangian: ");
  EXPECT_RIGID_ERROR((void)parse_scene(scene_text("lagrangian = 3"), "h.toml"),
                     "h.toml:1:14: lagrangian must be an expression string");
}

TEST(SceneLagrangian, ModesOfTheSceneMatchTheDoublePendulum) {
  const Model model(parse_scene(scene_text(fmt::format("lagrangian = \"{}\"", kLagrangian)), "dp.toml"));
  const lagrange::NormalModes r = normal_modes(model, {"theta1=0", "theta2=0*pi"});
  ASSERT_EQ(r.modes.size(), 2u);
  // ω² = g (2 ∓ √2) / l; 1e-10 relative: the acceptance bound (a few ulps expected)
  const double w2 = 9.81 * (2 - std::sqrt(2.0)) / 1.3;
  EXPECT_NEAR(r.modes[0].omega_squared, w2, 1e-10 * w2);
  EXPECT_RIGID_ERROR((void)normal_modes(model, {"theta1"}), "point 'theta1' is not of the form name=value");
  EXPECT_RIGID_ERROR((void)normal_modes(model, {"theta1=pj"}), "point 'theta1=pj'");
}

}  // namespace
}  // namespace rigid::scene
