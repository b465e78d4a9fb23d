// The [model] section of a scene (docs/scene-format.md): a robot model file as the scene's bodies,
// coordinates and passive terms, with the scene's forces, initial values and settings added; its
// path relative to the scene file; the read options of the section and of load_scene's
// ModelOptions over them; the refusals, located in the scene file or in the model file.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "rigid/common/error.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "support/expect_error.hpp"

namespace rigid::scene {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(RIGID_EXAMPLES_DIR);

// A fresh directory of this test: robots/ holds the model files, scenes/ the scenes, so that
// "../robots/…" in a scene is resolved against the scene's directory, not the working one.
class ModelSection : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("rigid_model_section_{}_{}", ::getpid(),
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "robots");
    fs::create_directories(dir_ / "scenes");
    fs::copy_file(kExamples / "cart_arm.urdf", dir_ / "robots" / "cart_arm.urdf");
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& relative, const std::string& text) const {
    const fs::path p = dir_ / relative;
    std::ofstream(p) << text;
    return p;
  }

  fs::path dir_;
};

// cart_arm.urdf's coordinates, in the model's order: x (prismatic, damping 2), shoulder, elbow.
constexpr double kKp = 40, kKd = 3, kTarget = 0.5;  // N·m/rad, N·m·s/rad, rad

TEST_F(ModelSection, PdTorqueAddsExactlyItsForceToTheModelsEquations) {
  const fs::path scene = write("scenes/pd.toml", R"x(# a PD controller on the shoulder
[model]
file = "../robots/cart_arm.urdf"

[parameters]
kp = 40
kd = 3
target = 0.5
w0 = 0.25

[[coordinates]]
name = "shoulder"
initial = 0.3
velocity = "w0"

[[forces]]
coordinate = "shoulder"
expression = "-kp*(shoulder - target) - kd*shoulder_dot"

[[forces]]
coordinate = "x"
expression = "0.5*sin(t)"
)x");
  const Model with(load_scene(scene));
  const Model bare(load_scene(dir_ / "robots" / "cart_arm.urdf"));
  const lagrange::System& s = with.system();
  const lagrange::System& b = bare.system();
  ASSERT_EQ(s.coordinate_names(), (std::vector<std::string>{"x", "shoulder", "elbow"}));
  ASSERT_EQ(b.coordinate_names(), s.coordinate_names());
  // the entry set the shoulder's initial state; the others keep the model's (ref 0, at rest)
  EXPECT_EQ(s.initial_q(), Eigen::Vector3d(0, 0.3, 0));
  EXPECT_EQ(s.initial_q_dot(), Eigen::Vector3d(0, 0.25, 0));

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int state = 0; state < 10; ++state) {
    const double t = 2 * std::abs(u(rng));
    const Eigen::Vector3d q(u(rng), u(rng), u(rng));
    const Eigen::Vector3d v(2 * u(rng), 2 * u(rng), 2 * u(rng));
    Eigen::MatrixXd M, M_bare;
    Eigen::VectorXd f, f_bare;
    s.mass_matrix_and_forces(t, q, v, M, f);
    b.mass_matrix_and_forces(t, q, v, M_bare, f_bare);
    // the same expressions derived twice: only the order of the sums may differ (GiNaC orders
    // terms by hashes of its symbols), so they agree to rounding, 1e-12 of the largest entry
    EXPECT_LT((M - M_bare).cwiseAbs().maxCoeff(), 1e-12 * M_bare.cwiseAbs().maxCoeff()) << state;
    const Eigen::Vector3d Q(0.5 * std::sin(t), -kKp * (q(1) - kTarget) - kKd * v(1), 0.0);
    EXPECT_LT((f - f_bare - Q).cwiseAbs().maxCoeff(),
              1e-12 * std::max(1.0, f_bare.cwiseAbs().maxCoeff()))
        << state << ": " << (f - f_bare).transpose() << " against " << Q.transpose();
  }
  // the model's gravity, its default run and the scene's file for the outputs
  EXPECT_EQ(with.scene().gravity[2].number, -9.81);
  EXPECT_EQ(with.t_end(), 5.0);
  EXPECT_EQ(with.output_directory(), fs::path("out") / "pd");
}

TEST_F(ModelSection, PathIsRelativeToTheSceneFilesDirectory) {
  const fs::path scene = write("scenes/arm.toml", R"x([model]
file = "../robots/cart_arm.urdf"
)x");
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_ / "robots");  // a working directory where "../robots/…" does not lead
  const Scene s = load_scene(scene);
  fs::current_path(cwd);
  ASSERT_TRUE(s.model.has_value());
  EXPECT_EQ(fs::weakly_canonical(s.model->file),
            fs::weakly_canonical(dir_ / "robots" / "cart_arm.urdf"));
  EXPECT_EQ(s.file, scene);
  EXPECT_EQ(s.coordinates.size(), 3u);
  EXPECT_FALSE(s.model->pin_free_root);
  EXPECT_FALSE(s.model->inertia_from_geometry);

  // a file that is not there is refused at the `file` value, naming the path it was resolved to
  const fs::path missing = write("scenes/missing.toml", "[model]\nfile = \"arm.urdf\"\n");
  EXPECT_RIGID_ERROR((void)load_scene(missing),
                     fmt::format("{}:2:8: [model] file: cannot open model file '{}'",
                                 missing.string(), (dir_ / "scenes" / "arm.urdf").string()));
  const fs::path toml = write("scenes/toml.toml", "[model]\nfile = \"missing.toml\"\n");
  EXPECT_RIGID_ERROR((void)load_scene(toml), "is not XML");
}

TEST_F(ModelSection, SettingsAndOverridesAreRefusedByNameAndLine) {
  // an unknown key, with the close one
  const fs::path typo = write("scenes/typo.toml", R"x([model]
file = "../robots/cart_arm.urdf"
inertia_from_geometry = true
densty = 500
)x");
  EXPECT_RIGID_ERROR((void)load_scene(typo),
                     fmt::format("{}:4:1: unknown key 'densty' in [model]; did you mean 'density'?",
                                 typo.string()));
  // a density that is none
  for (const char* rho : {"0", "-5", "0.0"}) {
    const fs::path bad =
        write("scenes/bad.toml", fmt::format("[model]\nfile = \"../robots/cart_arm.urdf\"\n"
                                             "inertia_from_geometry = true\ndensity = {}\n",
                                             rho));
    EXPECT_RIGID_ERROR((void)load_scene(bad),
                       fmt::format("{}:4:11: [model] density is", bad.string()));
  }
  const fs::path nan = write("scenes/nan.toml", R"x([model]
file = "../robots/cart_arm.urdf"
inertia_from_geometry = true
density = nan
)x");
  EXPECT_RIGID_ERROR((void)load_scene(nan), "expected a finite number");
  // a density without inertia_from_geometry would change nothing
  const fs::path unused = write("scenes/unused.toml", R"x([model]
file = "../robots/cart_arm.urdf"
density = 500
)x");
  EXPECT_RIGID_ERROR((void)load_scene(unused),
                     fmt::format("{}:3:11: [model] density", unused.string()));
  // and by load_scene's options (the command line's, Python's)
  const fs::path arm = write("scenes/arm.toml", "[model]\nfile = \"../robots/cart_arm.urdf\"\n");
  EXPECT_RIGID_ERROR((void)load_scene(arm, {.density = 500.0}), "`inertia_from_geometry = true`");
  EXPECT_RIGID_ERROR((void)load_scene(arm, {.inertia_from_geometry = true, .density = -1.0}),
                     "density -1 kg/m³ is not a density");
  EXPECT_RIGID_ERROR((void)load_scene(dir_ / "robots" / "cart_arm.urdf", {.density = 0.0}),
                     "density 0 kg/m³ is not a density");
  // a TOML scene without [model] reads no model file: the options are refused, naming the file
  EXPECT_RIGID_ERROR((void)load_scene(kExamples / "atwood.toml", {.pin_free_root = true}),
                     "atwood.toml: `pin_free_root = true` applies to a robot model file");
  EXPECT_RIGID_ERROR((void)parse_scene("", "x.toml", {.density = 2.0}), "density 2 kg/m³ applies");
}

TEST_F(ModelSection, EntriesThatDoNotFitTheModelAreRefused) {
  const std::string head = "[model]\nfile = \"../robots/cart_arm.urdf\"\n";
  const fs::path unknown = write("scenes/u.toml", head + "[[coordinates]]\nname = \"sholder\"\n");
  EXPECT_RIGID_ERROR((void)load_scene(unknown),
                     fmt::format("{}:4:8: [[coordinates]] entry 1: 'sholder' is "
                                 "not a joint of the model",
                                 unknown.string()));
  EXPECT_RIGID_ERROR((void)load_scene(unknown), "did you mean 'shoulder'?");
  const fs::path twice = write("scenes/t.toml", head +
                                                    "[[coordinates]]\nname = \"x\"\n"
                                                    "[[coordinates]]\nname = \"x\"\n");
  EXPECT_RIGID_ERROR((void)load_scene(twice), "coordinate 'x' is already set at line 4");
  const fs::path bodies = write("scenes/b.toml", head + R"x([[bodies]]
name = "ball"
primitive = "sphere"
radius = 0.1
mass = 1
)x");
  EXPECT_RIGID_ERROR((void)load_scene(bodies),
                     "adding [[bodies]] to a model's tree is not supported");
  // a parameter may not take a joint's name
  const fs::path clash = write("scenes/c.toml", "[parameters]\nelbow = 1\n" + head);
  EXPECT_RIGID_ERROR((void)load_scene(clash),
                     "parameter 'elbow' is already defined (a joint coordinate "
                     "of the model");
  // without [simulation] the model's 5 s; with one, the scene's; gravity replaced by the scene's
  const fs::path moon =
      write("scenes/moon.toml", "gravity = [0, 0, -1.62]\n" + head + "[simulation]\nt_end = 2\n");
  const Scene s = load_scene(moon);
  EXPECT_EQ(s.gravity[2].number, -1.62);
  EXPECT_EQ(s.simulation.t_end.number, 2.0);
}

// A URDF link with a collision box and a stated inertial: inertia_from_geometry replaces the
// latter by the box at the density (m = ρ · 0.1 · 0.2 · 0.3 m³ = ρ · 0.006 m³).
constexpr const char* kBoxUrdf = R"x(<?xml version="1.0"?>
<robot name="box">
  <link name="base"/>
  <link name="box">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
    <collision>
      <origin xyz="0 0 -0.5"/>
      <geometry><box size="0.1 0.2 0.3"/></geometry>
    </collision>
  </link>
  <joint name="hinge" type="continuous">
    <parent link="base"/>
    <child link="box"/>
    <axis xyz="0 1 0"/>
  </joint>
</robot>
)x";

TEST_F(ModelSection, ReadOptionsOfTheSectionAndOverTheSection) {
  write("robots/box.urdf", kBoxUrdf);
  const fs::path scene = write("scenes/box.toml", R"x([model]
file = "../robots/box.urdf"
inertia_from_geometry = true
density = 500
)x");
  const double volume = 0.1 * 0.2 * 0.3;  // m³
  // masses: ρ V, up to the rounding of the volume's product (a few ulps)
  EXPECT_NEAR(Model(load_scene(scene)).bodies().at(0).mass.mass(), 500 * volume, 1e-14);
  EXPECT_NEAR(Model(load_scene(scene, {.density = 2000.0})).bodies().at(0).mass.mass(),
              2000 * volume, 1e-13);
  EXPECT_EQ(Model(load_scene(dir_ / "robots" / "box.urdf")).bodies().at(0).mass.mass(), 1.0);
  EXPECT_NEAR(Model(load_scene(dir_ / "robots" / "box.urdf", {.inertia_from_geometry = true}))
                  .bodies()
                  .at(0)
                  .mass.mass(),
              1000 * volume, 1e-13);
  const Scene s = load_scene(scene, {.density = 2000.0});
  EXPECT_TRUE(s.model->inertia_from_geometry);
  EXPECT_EQ(s.model->density, 2000.0);
}

// An MJCF whose root body is free: its free joint's coordinates (three slides and a ball), or
// the hinge alone when pinned by the section or by the options.
constexpr const char* kFreeRootMjcf = R"x(<mujoco model="floating">
  <worldbody>
    <body name="torso" pos="0 0 1">
      <freejoint name="root"/>
      <geom type="sphere" size="0.1" mass="2"/>
      <body name="arm" pos="0 0 -0.1">
        <joint name="swing" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.03" mass="1"/>
      </body>
    </body>
  </worldbody>
</mujoco>
)x";

TEST_F(ModelSection, ModelFileErrorsNameTheModelFileAndPinningReachesTheReader) {
  const fs::path robot = write("robots/floating.xml", kFreeRootMjcf);
  const fs::path scene =
      write("scenes/floating.toml", "[model]\nfile = \"../robots/floating.xml\"\n");
  // free: root_x, root_y, root_z and the ball 'root' (at the free joint's line), then the hinge
  const Scene free = load_scene(scene);
  ASSERT_EQ(free.coordinates.size(), 5u);
  EXPECT_EQ(free.coordinates[3].name, "root");
  EXPECT_EQ(free.coordinates[3].kind, Coordinate::Kind::kBall);
  EXPECT_EQ(free.coordinates[3].where.file, robot.string());
  EXPECT_EQ(free.coordinates[3].where.line, 4);
  // a wrong setting in the model file is named there: a free joint on a child body
  std::string nested = kFreeRootMjcf;
  nested.replace(nested.find(R"(<joint name="swing" type="hinge" axis="0 1 0"/>)"),
                 std::string(R"(<joint name="swing" type="hinge" axis="0 1 0"/>)").size(), "<freejoint/>");
  write("robots/floating.xml", nested);
  EXPECT_RIGID_ERROR((void)load_scene(scene), fmt::format("{}:7:", robot.string()));
  EXPECT_RIGID_ERROR((void)load_scene(scene), "free");
  write("robots/floating.xml", kFreeRootMjcf);
  const Scene pinned = load_scene(scene, {.pin_free_root = true});
  EXPECT_EQ(pinned.coordinates.size(), 1u);
  EXPECT_EQ(pinned.coordinates[0].name, "swing");
  EXPECT_TRUE(pinned.model->pin_free_root);
  const fs::path section = write("scenes/pinned.toml",
                                 "[model]\nfile = \"../robots/floating.xml\"\n"
                                 "pin_free_root = true\n");
  EXPECT_EQ(load_scene(section).coordinates.size(), 1u);
  EXPECT_EQ(load_scene(robot, {.pin_free_root = true}).coordinates.size(), 1u);
  // a density is a URDF's: an MJCF geom carries its own
  EXPECT_RIGID_ERROR(
      (void)load_scene(robot,
                       {.pin_free_root = true, .inertia_from_geometry = true, .density = 500.0}),
      "applies to a URDF's collision geometry");
}

}  // namespace
}  // namespace rigid::scene
