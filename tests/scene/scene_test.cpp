#include "rigid/scene/scene.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::scene {
namespace {

// A cylinder rolling down an incline, the smallest complete Lagrangian scene.
constexpr std::string_view kRolling = R"toml(
gravity = [0, 0, -9.81]

[parameters]
m = 2.0
r = 0.1
alpha = 0.5

[[coordinates]]
name = "s"
initial = 0
velocity = 0

[[bodies]]
name = "wheel"
primitive = "solid_cylinder"
radius = "r"
height = 0.05
mass = "m"
position = ["s*cos(alpha)", 0, "-s*sin(alpha)"]
rotation = [{axis = [0, 2, 0], angle = "s/r"}]

[simulation]
t_end = 1.5
integrator = "rk4"
dt = 1e-3
)toml";

TEST(Scene, ParsesACompleteScene) {
  const Scene s = parse_scene(kRolling, "roll.toml");
  ASSERT_EQ(s.parameters.size(), 3u);
  EXPECT_EQ(s.parameters[1].name, "r");
  EXPECT_EQ(s.parameters[1].value.number, 0.1);
  ASSERT_EQ(s.coordinates.size(), 1u);
  EXPECT_EQ(s.coordinates[0].name, "s");
  ASSERT_EQ(s.bodies.size(), 1u);
  const Body& b = s.bodies[0];
  EXPECT_FALSE(b.free);
  EXPECT_EQ(b.mass.primitive, "solid_cylinder");
  EXPECT_EQ(b.mass.mass->text, "m");
  EXPECT_EQ(b.position[0].text, "s*cos(alpha)");
  EXPECT_EQ(b.position[1].number, 0.0);
  ASSERT_EQ(b.rotations.size(), 1u);
  // The axis is normalised when read: [0, 2, 0] -> [0, 1, 0].
  EXPECT_EQ(b.rotations[0].axis[1], 1.0);
  EXPECT_EQ(s.gravity[2].number, -9.81);
  EXPECT_EQ(s.simulation.integrator, "rk4");
  EXPECT_FALSE(s.is_free_body_scene());
  // The value "s/r" starts at line 21, column 40 (the opening quote), so its character
  // 1 ('/') is at column 42.
  EXPECT_EQ(to_string(b.rotations[0].angle.at(1)), "roll.toml:21:42");
}

TEST(Scene, FreeBodyScene) {
  const Scene s = parse_scene(R"toml(
[[bodies]]
name = "racket"
free = true
inertia = {mass = 1, ixx = 1, iyy = 2, izz = 3}
initial_rotation = {axis = [0, 0, 1], angle = 3.141592653589793}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 10
)toml",
                              "racket.toml");
  ASSERT_TRUE(s.is_free_body_scene());
  const Body& b = s.bodies[0];
  EXPECT_EQ(b.mass.kind, MassSpec::Kind::kExplicit);
  EXPECT_EQ(b.mass.inertia[1].number, 2.0);
  EXPECT_EQ(b.mass.inertia[4].number, 0.0);  // ixz defaults to 0
  // Half-angle π/2 about z: w = cos(π/2) ≈ 6e-17, z = sin(π/2) = 1.
  EXPECT_NEAR(b.initial_orientation[0], 0.0, 1e-16);
  EXPECT_EQ(b.initial_orientation[3], 1.0);
  EXPECT_EQ(b.angular_velocity[1], 1.0);
}

TEST(Scene, SyntaxErrorsPointIntoTheFile) {
  EXPECT_RIGID_ERROR((void)parse_scene("[simulation]\nt_end = = 3\n", "bad.toml"),
                     "bad.toml:2:9: TOML syntax error");
}

TEST(Scene, UnknownKeysSuggestTheClosest) {
  std::string text(kRolling);
  text.replace(text.find("mass = \"m\""), 4, "mas");
  EXPECT_RIGID_ERROR((void)parse_scene(text, "s.toml"),
                     "s.toml:19:1: unknown key 'mas' in body 'wheel'; did you mean 'mass'?");
  EXPECT_RIGID_ERROR((void)parse_scene("[simulaton]\nt_end = 1\n", "s.toml"),
                     "s.toml:1:2: unknown key 'simulaton' in the scene; did you mean 'simulation'?");
}

TEST(Scene, TopLevelKeyAfterATableHeaderIsExplained) {
  EXPECT_RIGID_ERROR((void)parse_scene(R"toml([[coordinates]]
name = "x"
gravity = [0, 0, -9.81]
[simulation]
t_end = 1
)toml",
                                       "s.toml"),
                     "s.toml:3:1: unknown key 'gravity' in [[coordinates]] entry 1; 'gravity' is a "
                     "top-level key: move it above the first [table] header");
}

TEST(Scene, WrongTypesAndMissingFields) {
  std::string text(kRolling);
  text.replace(text.find("t_end = 1.5"), 11, "t_end = true");
  EXPECT_RIGID_ERROR((void)parse_scene(text, "s.toml"),
                     "s.toml:24:9: t_end must be a number or an expression string, got a boolean");
  text = std::string(kRolling);
  text.replace(text.find("mass = \"m\""), 10, "");
  EXPECT_RIGID_ERROR((void)parse_scene(text, "s.toml"),
                     "body 'wheel' needs exactly one of 'mass' (kg) and 'density' (kg/m³)");
  EXPECT_RIGID_ERROR((void)parse_scene("[[coordinates]]\nname = \"x\"\n", "s.toml"),
                     "the scene has no [simulation] table; expected at least t_end (s)");
  EXPECT_RIGID_ERROR(
      (void)parse_scene("[[coordinates]]\nname = \"2x\"\n[simulation]\nt_end=1\n", "s.toml"),
      "s.toml:2:8: coordinate name '2x' is not a valid name");
}

TEST(Scene, NamesMustBeDistinctAndReferencesKnown) {
  EXPECT_RIGID_ERROR((void)parse_scene(R"toml([parameters]
x = 1
[[coordinates]]
name = "x"
[simulation]
t_end = 1
)toml",
                                       "s.toml"),
                     "s.toml:4:8: coordinate 'x' is already defined");
  EXPECT_RIGID_ERROR((void)parse_scene(R"toml([[coordinates]]
name = "theta"
[[forces]]
coordinate = "thete"
expression = "-0.1*theta_dot"
[simulation]
t_end = 1
)toml",
                                       "s.toml"),
                     "force on unknown coordinate 'thete'; did you mean 'theta'?");
}

TEST(Scene, FreeAndPosedBodiesDoNotMix) {
  EXPECT_RIGID_ERROR((void)parse_scene(R"toml([[bodies]]
name = "a"
free = true
inertia = {mass = 1, ixx = 1, iyy = 1, izz = 1}
[[bodies]]
name = "b"
inertia = {mass = 1, ixx = 1, iyy = 1, izz = 1}
[simulation]
t_end = 1
)toml",
                                       "s.toml"),
                     "s.toml:5:1: body 'b' has no 'free = true' but other bodies do");
  EXPECT_RIGID_ERROR((void)parse_scene(R"toml([[bodies]]
free = true
inertia = {mass = 1, ixx = 1, iyy = 1, izz = 1}
initial_quaternion = [1, 0, 0, 0.1]
[simulation]
t_end = 1
)toml",
                                       "s.toml"),
                     "initial_quaternion (w, x, y, z) has norm 1.004987");
}

TEST(Scene, OverridesReplaceParameters) {
  Scene s = parse_scene(kRolling, "roll.toml");
  apply_overrides(s, {"r=0.25", "alpha=pi/6"});
  EXPECT_EQ(s.parameters[1].value.number, 0.25);
  EXPECT_EQ(s.parameters[2].value.text, "pi/6");
  EXPECT_FALSE(s.parameters[2].value.number.has_value());
  EXPECT_RIGID_ERROR(apply_overrides(s, {"rr=1"}),
                     "override 'rr=1': the scene has no parameter, setting or initial condition 'rr'; did "
                     "you mean 'r'?");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"r"}), "override 'r' is not of the form name=value");
}

// Settings and initial conditions are named as the file nests them.
TEST(Scene, OverridesSetSimulationSettingsAndInitialConditions) {
  Scene s = parse_scene(kRolling, "roll.toml");
  apply_overrides(s, {"simulation.t_end=20", "simulation.tolerance = 1e-12", "simulation.integrator=dopri5",
                      "simulation.output_dt=0.1", "simulation.dt=2*r", "s.initial=0.2", "s.velocity=-1"});
  EXPECT_EQ(s.simulation.t_end.number, 20.0);
  ASSERT_TRUE(s.simulation.tolerance.has_value());
  EXPECT_EQ(s.simulation.tolerance->number, 1e-12);
  EXPECT_EQ(s.simulation.integrator, "dopri5");
  EXPECT_EQ(s.simulation.output_dt->number, 0.1);
  EXPECT_EQ(s.simulation.dt->text, "2*r");
  EXPECT_EQ(s.coordinates[0].initial.number, 0.2);
  EXPECT_EQ(s.coordinates[0].velocity.number, -1.0);
}

// `--set theta=0.2` said "the scene has no parameter 'theta'": a coordinate named alone says
// how to set it.
TEST(Scene, OverrideOfACoordinateNamesItsInitialConditions) {
  Scene s = parse_scene(kRolling, "roll.toml");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"s=0.2"}), "override 's=0.2': 's' is a coordinate: set 's.initial' or 's.velocity'");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"simulation.t_edn=3"}), "did you mean 'simulation.t_end'?");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"s.inital=3"}), "did you mean 's.initial'?");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"wheel.omega=[1,2,3]"}), "body 'wheel' is posed by the coordinates");
}

TEST(Scene, OverridesSetAFreeBodysInitialState) {
  Scene s = parse_scene(R"toml(
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = 2, izz = 3}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 1
)toml",
                        "racket.toml");
  apply_overrides(s, {"racket.omega=[0.02, 1, 0.01]", "racket.initial_velocity=[1,2,3]", "racket.position=[0,0,1.5]",
                      "racket.quaternion=[0, 1, 0, 0]"});
  EXPECT_EQ(s.bodies[0].angular_velocity, (std::array<double, 3>{0.02, 1, 0.01}));
  EXPECT_EQ(s.bodies[0].initial_velocity, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(s.bodies[0].initial_position, (std::array<double, 3>{0, 0, 1.5}));
  EXPECT_EQ(s.bodies[0].initial_orientation, (std::array<double, 4>{0, 1, 0, 0}));
  EXPECT_RIGID_ERROR(apply_overrides(s, {"racket.omega=[1, 2]"}),
                     "override 'racket.omega=[1, 2]': racket.angular_velocity has 2 elements; expected 3 numbers");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"racket.omega=1"}), "racket.angular_velocity '1' is not an array");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"racket.omega=[1, nan, 0]"}), "element 2 is not a finite number");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"racket.quaternion=[1, 1, 0, 0]"}), "expected a unit quaternion");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"racket=1"}), "'racket' is a free body: set 'racket.position'");
  const std::vector<std::string> names = override_names(s);
  EXPECT_NE(std::find(names.begin(), names.end(), "racket.omega"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "simulation.t_end"), names.end());
}

TEST(Scene, DidYouMeanOnlyForCloseWords) {
  EXPECT_EQ(did_you_mean("integrater", {"integrator", "t_end"}), "integrator");
  EXPECT_EQ(did_you_mean("zzz", {"integrator", "t_end"}), std::nullopt);
}

// `rigid check /dev/zero` read 4.2 GB: only regular files are read, up to kMaxSceneFileBytes.
TEST(Scene, LoadReadsOnlyRegularFilesOfBoundedSize) {
  EXPECT_RIGID_ERROR((void)load_scene("/dev/zero"), "scene file '/dev/zero' is not a regular file");
  const auto dir = std::filesystem::temp_directory_path() / "rigid_scene_load_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  EXPECT_RIGID_ERROR((void)load_scene(dir), "is a directory; expected a TOML file");
  EXPECT_RIGID_ERROR((void)load_scene(dir / "missing.toml"), "cannot open scene file");
  // a sparse file one byte over the cap (nothing is allocated on disk)
  const auto big = dir / "big.toml";
  std::ofstream(big) << "";
  std::filesystem::resize_file(big, kMaxSceneFileBytes + 1);
  EXPECT_RIGID_ERROR((void)load_scene(big), "has 16777217 bytes, more than the 16777216 (16 MiB)");
  std::filesystem::remove_all(dir);
}

// An integer above 2^53 has no exact double: toml++ gave none and std::optional threw
// "bad optional access".
TEST(Scene, IntegersBeyondDoublePrecisionAreRefused) {
  std::string text(kRolling);
  text.replace(text.find("m = 2.0"), 7, "m = 9007199254740993");
  EXPECT_RIGID_ERROR((void)parse_scene(text, "roll.toml"),
                     "roll.toml:5:5: parameter m is the integer 9007199254740993, beyond the integers a double "
                     "holds exactly");
  text.replace(text.find("m = 9007199254740993"), 20, "m = 9007199254740992");  // 2^53 is exact
  EXPECT_EQ(*parse_scene(text, "roll.toml").parameters[0].value.number, 9007199254740992.0);
}

}  // namespace
}  // namespace rigid::scene
