// Number literals that no double holds at their value (they underflow to 0 or to a subnormal,
// or overflow to infinity) are refused where they are written: at file:line:col in a scene (a
// TOML number or a number inside an expression string), naming the --set argument for an
// override, with what was written and the normal range of a double. An expression whose exact
// value underflows is refused the same way, at the expression.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"

namespace rigid::scene {
namespace {

// A physical pendulum whose line 3 holds g, line 5 L and line 8 theta's initial value.
std::string pendulum(const std::string& g, const std::string& L,
                     const std::string& initial = "1.0") {
  return "gravity = [0, 0, \"-g\"]\n"
         "[parameters]\n"
         "g = " +
         g +
         "\n"
         "m = 0.5\n"
         "L = " +
         L +
         "\n"
         "[[coordinates]]\n"
         "name = \"theta\"\n"
         "initial = " +
         initial +
         "\n"
         "velocity = 0\n"
         "[[bodies]]\n"
         "name = \"rod\"\n"
         "primitive = \"thin_rod\"\n"
         "length = \"L\"\n"
         "mass = \"m\"\n"
         "position = [\"-(L/2)*sin(theta)\", 0, \"-(L/2)*cos(theta)\"]\n"
         "rotation = [{axis = [0, 1, 0], angle = \"-theta\"}]\n"
         "[simulation]\n"
         "t_end = 1.0\n"
         "integrator = \"rk4\"\n"
         "dt = 1e-3\n"
         "output_dt = 0.1\n";
}

void check(const std::string& text, const std::vector<std::string>& overrides = {}) {
  Scene s = parse_scene(text, "p.toml");
  apply_overrides(s, overrides);
  Model(std::move(s)).check();
}

constexpr const char* kRange =
    "expected 0 or a magnitude from 2.2250738585072014e-308 to 1.7976931348623157e+308";

TEST(SceneLiterals, TheExampleIsValid) { EXPECT_NO_THROW(check(pendulum("9.81", "1.0"))); }

TEST(SceneLiterals, SubnormalTomlNumberIsRefusedAtItsLiteral) {
  // was "floating point underflow." from CLN, with no place
  EXPECT_RIGID_ERROR(
      check(pendulum("2.2250738585072014e-309", "1.0")),
      "p.toml:3:5: parameter g: '2.2250738585072014e-309' underflows: a double would "
      "hold the subnormal");
  EXPECT_RIGID_ERROR(check(pendulum("2.2250738585072014e-309", "1.0")), kRange);
}

TEST(SceneLiterals, TomlNumberThatRoundsToZeroIsRefused) {
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "1.0", "1e-400")), "p.toml:8:11:");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "1.0", "1e-400")),
                     "'1e-400' underflows: a double would hold 0");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "1.0", "-1_0e-4_00")), "underflows");
}

TEST(SceneLiterals, TomlNumberThatOverflowsIsRefusedAtItsStart) {
  // toml++ refuses it as "could not be interpreted as a value", at its end
  EXPECT_RIGID_ERROR(check(pendulum("1e400", "1.0")),
                     "p.toml:3:5: '1e400' overflows: a double would hold infinity");
}

TEST(SceneLiterals, LiteralInsideAnExpressionIsRefusedAtItsColumn) {
  // was silently 0, then "length must be positive" at the body
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "\"1e-400\"")), "p.toml:5:");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "\"1e-400\"")),
                     "'1e-400' underflows: a double would hold 0");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "\"2 * 1e400\"")), "'1e400' overflows");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "\"1 + 4.9e-324\"")), "'4.9e-324' underflows");
}

TEST(SceneLiterals, ExpressionWhoseValueUnderflowsIsRefused) {
  // 1e-300/1e10 = 1e-310 exactly: each literal is a normal double, the value is not
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "\"1e-300/1e10\"")), "p.toml:5:");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "\"1e-300/1e10\"")), "'1e-300/1e10' evaluates to");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "\"exp(-1000)\"")), "which underflows");
  // the smallest normal double itself is a valid value
  EXPECT_NO_THROW((void)parse_scene(pendulum("9.81", "2.2250738585072014e-308"), "p.toml"));
}

TEST(SceneLiterals, OverrideLiteralIsRefusedNamingTheSetArgument) {
  // was silently dt = 0, then "dt must be positive, got 0 s"
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "1.0"), {"simulation.dt=1e-400"}),
                     "override 'simulation.dt=1e-400': '1e-400' underflows: a double would hold 0");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "1.0"), {"g=2.2250738585072014e-309"}),
                     "override 'g=2.2250738585072014e-309': '2.2250738585072014e-309' underflows");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "1.0"), {"theta.initial=-1e999"}), "overflows");
  EXPECT_RIGID_ERROR(check(pendulum("9.81", "1.0"), {"L=2*1e-400"}), "'1e-400' underflows");
}

TEST(SceneLiterals, FreeBodyVectorOverrideElementIsRefused) {
  Scene s = load_scene(std::filesystem::path(RIGID_EXAMPLES_DIR) / "tennis_racket.toml");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"racket.omega=[0.01, 1e-400, 0]"}),
                     "element 2 '1e-400' underflows");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"racket.omega=[1e400, 1, 0]"}),
                     "racket.angular_velocity '1e400' overflows");
}

}  // namespace
}  // namespace rigid::scene
