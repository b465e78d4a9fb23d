// Robot model files as scenes (scene::load_scene on a URDF or MJCF; rigid/scene/robot_scene.hpp):
// the symbolic equations of the scene against robot::TreeDynamics (recursive Newton–Euler and
// composite inertias in numbers, itself held to MuJoCo in tests/robot) on the same file; the
// fusion of welded and massless links; the passive terms; the refusals.
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "rigid/common/error.hpp"
#include "rigid/io/robot_model.hpp"
#include "rigid/lagrange/export.hpp"
#include "rigid/lagrange/linearize.hpp"
#include "rigid/robot/tree_dynamics.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/robot_scene.hpp"
#include "rigid/scene/scene.hpp"
#include "support/expect_error.hpp"

namespace rigid::scene {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(RIGID_TEST_DATA_DIR).parent_path().parent_path() / "examples";

fs::path write(const std::string& name, const std::string& text) {
  const fs::path p =
      fs::temp_directory_path() / fmt::format("rigid_robot_scene_{}_{}", ::getpid(), name);
  std::ofstream(p) << text;
  return p;
}

// M and f = −b + p of the scene's symbolic system (evaluated through `w`) and of TreeDynamics
// at `states` random states, to 1e-10 relative to the largest entry: the tape evaluates the
// expanded expressions (a few hundred terms, each a handful of roundings) or the recursions'
// intermediates, TreeDynamics its own recursive sums in another order.
void expect_same_at_random_states(const lagrange::System& system, lagrange::Workspace& w,
                                  const robot::TreeDynamics& tree, unsigned seed, int states) {
  ASSERT_EQ(static_cast<std::size_t>(system.num_coordinates()), tree.dof());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const auto n = static_cast<Eigen::Index>(tree.dof());
  for (int state = 0; state < states; ++state) {
    Eigen::VectorXd q(n), v(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      q(i) = u(rng);
      v(i) = 2 * u(rng);
    }
    Eigen::MatrixXd M;
    Eigen::VectorXd f;
    system.mass_matrix_and_forces(w, 0.0, q, v, M, f);
    const Eigen::MatrixXd M_ref = tree.mass_matrix(q);
    const Eigen::VectorXd f_ref = -tree.bias_forces(q, v) + tree.passive_forces(q, v);
    EXPECT_LT((M - M_ref).cwiseAbs().maxCoeff(), 1e-10 * M_ref.cwiseAbs().maxCoeff())
        << "state " << state << "\n"
        << M << "\n\n"
        << M_ref;
    EXPECT_LT((f - f_ref).cwiseAbs().maxCoeff(), 1e-10 * std::max(1.0, f_ref.cwiseAbs().maxCoeff()))
        << "state " << state << "\n"
        << f.transpose() << "\n"
        << f_ref.transpose();
  }
}

// The same for a model file read both ways, with its coordinates' names and initial values.
void expect_same_equations(const fs::path& file, unsigned seed) {
  const Model model(load_scene(file));
  const robot::TreeDynamics tree(io::read_robot_model_file(file.string()));
  const lagrange::System& system = model.system();
  ASSERT_EQ(static_cast<std::size_t>(system.num_coordinates()), tree.dof());
  EXPECT_EQ(system.coordinate_names(), tree.model().coordinate_names());
  EXPECT_TRUE(system.initial_q().isApprox(tree.reference_configuration(), 0.0) ||
              system.initial_q() == tree.reference_configuration());
  lagrange::Workspace w = system.make_workspace();
  expect_same_at_random_states(system, w, tree, seed, 10);
}

TEST(RobotScene, UrdfWithPrismaticContinuousAndFixedJoints) {
  expect_same_equations(kExamples / "cart_arm.urdf", 1);
}

// MJCF: several joints on one body, hinges through anchors, a slide, ref, springs with springref,
// armature, damping, defaults, a welded body whose inertial joins its parent's, degrees.
TEST(RobotScene, MjcfWithMultiJointBodiesAnchorsSpringsAndArmature) {
  const fs::path f = write("tree.xml", R"(<mujoco model="tree">
  <option gravity="0.2 0 -9.81"/>
  <default><joint damping="0.3" armature="0.02"/></default>
  <worldbody>
    <body name="base" pos="0 0 1" euler="10 20 30">
      <joint name="yaw" type="hinge" axis="0 0 1" pos="0.05 0 0" ref="15" stiffness="2" springref="5"/>
      <joint name="lift" type="slide" axis="0 0.6 0.8"/>
      <inertial pos="0.02 0 0.1" mass="2" fullinertia="0.03 0.04 0.02 0.001 0.002 -0.001"/>
      <body name="mount" pos="0.1 0 0" quat="0.9 0.1 0.3 0">
        <inertial pos="0 0 0" mass="0.4" diaginertia="0.001 0.001 0.001"/>
      </body>
      <body name="arm" pos="0.2 0 0" axisangle="1 1 0 30">
        <joint name="a1" axis="1 0 0" pos="0 0 0.05" damping="0"/>
        <joint name="a2" axis="0 1 1" pos="0.1 0 0"/>
        <inertial pos="0.15 0 0" quat="1 0.2 0 0.1" mass="1.2" diaginertia="0.01 0.02 0.025"/>
      </body>
    </body>
  </worldbody>
</mujoco>
)");
  expect_same_equations(f, 2);
  fs::remove(f);
}

// A massless link between two joints (a URDF's way to write a two-axis joint) is merged into the
// link it carries; the equations are those of the tree as written.
TEST(RobotScene, MasslessLinkBetweenJointsIsMerged) {
  const fs::path f = write("gimbal.urdf", R"(<robot name="gimbal">
  <link name="base"/>
  <link name="yoke"/>
  <link name="bob"><inertial><origin xyz="0 0.1 -0.4" rpy="0.2 0 0"/><mass value="1.5"/>
    <inertia ixx="0.02" ixy="0.001" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial></link>
  <joint name="pan" type="continuous"><parent link="base"/><child link="yoke"/>
    <origin xyz="0 0 0.5" rpy="0 0 0.4"/><axis xyz="0 0 1"/></joint>
  <joint name="tilt" type="revolute"><parent link="yoke"/><child link="bob"/>
    <origin xyz="0.1 0 0" rpy="0.3 0 0"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
    <dynamics damping="0.1"/></joint>
</robot>
)");
  const Scene s = load_scene(f);
  ASSERT_EQ(s.bodies.size(), 1U);
  EXPECT_EQ(s.bodies[0].name, "bob");
  EXPECT_EQ(s.bodies[0].joints.size(), 2U);
  expect_same_equations(f, 3);
  fs::remove(f);
}

TEST(RobotScene, UndampedRunKeepsItsEnergy) {
  // the cart arm without damping, released from a bent pose: the default dopri5 keeps the energy
  // to its tolerance's order (1e-6 of the energy scale over 2 s)
  std::ifstream in(kExamples / "cart_arm.urdf");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  for (std::size_t at; (at = text.find("<dynamics")) != std::string::npos;)
    text.erase(at, text.find("/>", at) + 2 - at);
  const fs::path f = write("cart_arm_free.urdf", text);
  Scene s = load_scene(f);
  apply_overrides(s, {"shoulder.initial=1.2", "elbow.velocity=2", "simulation.t_end=2"});
  const RunResult r = Model(s).run();
  double change = -1, scale = 0;
  for (const auto& [name, value] : r.summary.diagnostics) {
    if (name == "energy_max_change") change = value;
    if (name == "energy_initial") scale = std::abs(value);
  }
  ASSERT_GE(change, 0);
  EXPECT_LT(change, 1e-5 * std::max(1.0, scale));
  fs::remove(f);
}

TEST(RobotScene, Refusals) {
  // a massless link with joints that carries two moving links
  const fs::path fork = write("fork.urdf", R"(<robot name="fork">
  <link name="base"/><link name="hub"/>
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j0" type="continuous"><parent link="base"/><child link="hub"/><axis xyz="0 0 1"/></joint>
  <joint name="j1" type="continuous"><parent link="hub"/><child link="a"/><axis xyz="1 0 0"/></joint>
  <joint name="j2" type="continuous"><parent link="hub"/><child link="b"/><axis xyz="0 1 0"/></joint>
</robot>
)");
  try {
    (void)load_scene(fork);
    FAIL() << "expected rigid::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("link 'hub' has joints but no mass"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(fork.string() + ":2"), std::string::npos) << e.what();
  }
  fs::remove(fork);
  // an XML file that is neither URDF nor MJCF
  const fs::path other = write("other.xml", "<svg/>\n");
  EXPECT_THROW((void)load_scene(other), Error);
  fs::remove(other);
}

// A chain deeper than three joints is derived by the tree's recursions (lagrange
// SystemSpec::Derivation): a 9-joint chain, the 7-joint arm and MuJoCo's humanoid pinned at the
// torso (21 hinges, 9 on the path to a foot) against TreeDynamics.
TEST(RobotScene, DeepChainsAreDerivedByTheTreesRecursions) {
  std::string links = R"(<robot name="chain"><link name="l0"/>)", joints;
  for (int i = 1; i <= 9; ++i) {
    links += fmt::format(
        R"(<link name="l{}"><inertial><origin xyz="0 0 -0.1"/><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>)"
        "\n",
        i);
    joints += fmt::format(
        R"(<joint name="j{}" type="continuous"><parent link="l{}"/><child link="l{}"/><origin xyz="0 0 -0.2"/><axis xyz="{}"/></joint>)",
        i, i - 1, i, i % 2 ? "0 1 0" : "1 0 0");
  }
  const fs::path f = write("chain.urdf", links + joints + "</robot>\n");
  expect_same_equations(f, 9);
  fs::remove(f);
  expect_same_equations(kExamples / "arm7.urdf", 7);
}

// MuJoCo's humanoid with its free root: q is MuJoCo's qpos (the root's position, then its
// quaternion as the ball coordinate 'root'), the velocities its qvel; what does not take ball
// coordinates yet says so by name rather than computing something else.
TEST(RobotScene, FreeRootHumanoidHasBallCoordinates) {
  const fs::path file = "/usr/share/mujoco/model/humanoid/humanoid.xml";  // libmujoco-samples
  ASSERT_TRUE(fs::exists(file)) << file << " is missing: scripts/install-deps.sh installs it";
  const Model model(load_scene(file));
  const lagrange::System& system = model.system();
  EXPECT_EQ(system.num_coordinates(), 28);
  EXPECT_EQ(system.num_velocities(), 27);
  EXPECT_TRUE(system.has_ball_coordinates());
  const std::vector<std::string> head(system.coordinate_names().begin(), system.coordinate_names().begin() + 8);
  EXPECT_EQ(head, (std::vector<std::string>{"root_x", "root_y", "root_z", "root_qw", "root_qx", "root_qy",
                                            "root_qz", "abdomen_z"}));
  // the torso's placement (pos 0 0 1.5, no rotation) is the free joint's initial value
  EXPECT_EQ(system.initial_q().head<7>(), (Eigen::Matrix<double, 7, 1>() << 0, 0, 1.5, 1, 0, 0, 0).finished());
  // q̇ = ½ q ⊗ (0, ω): about the body's z axis at the identity, q̇ = (0, 0, 0, ω/2)
  Eigen::VectorXd v = Eigen::VectorXd::Zero(27);
  v(5) = 2.0;
  const Eigen::VectorXd rate = system.coordinate_rates(system.initial_q(), v);
  EXPECT_EQ(rate.segment<4>(3), Eigen::Vector4d(0, 0, 0, 1));
  EXPECT_RIGID_ERROR((void)lagrange::normal_modes(system),
                     "normal modes of a system with ball coordinates (here 'root': a ball or free joint) are not supported yet");
  EXPECT_RIGID_ERROR((void)lagrange::emit_cpp(system), "the code export of a system with ball coordinates");
  // an initial state set on the ball by its own keys; the scalar keys are not the ball's
  Scene s = load_scene(file);
  apply_overrides(s, {"root.orientation=[0, 1, 0, 0]", "root.angular_velocity=[0, 0, 3]"});
  const Model turned(s);
  EXPECT_EQ(turned.system().initial_q().segment<4>(3), Eigen::Vector4d(0, 1, 0, 0));
  EXPECT_EQ(turned.system().initial_q_dot().segment<3>(3), Eigen::Vector3d(0, 0, 3));
  EXPECT_RIGID_ERROR(apply_overrides(s, {"root.initial=1"}),
                     "'root' is a ball coordinate: set 'root.orientation' or 'root.angular_velocity'");
  EXPECT_RIGID_ERROR(apply_overrides(s, {"root.orientation=[1, 1, 0, 0]"}),
                     "root.orientation has norm 1.4142135623730951; expected a unit quaternion");
  // the same through a scene file's [[coordinates]]
  const fs::path toml = write("humanoid_turned.toml", fmt::format(R"([model]
file = "{}"

[[coordinates]]
name = "root"
orientation = [0, 1, 0, 0]
angular_velocity = [0, 0, "3"]
)", file.string()));
  const Model from_file(load_scene(toml));
  EXPECT_EQ(from_file.system().initial_q(), turned.system().initial_q());
  EXPECT_EQ(from_file.system().initial_q_dot(), turned.system().initial_q_dot());
  const fs::path scalar = write("humanoid_scalar.toml", fmt::format(R"([model]
file = "{}"

[[coordinates]]
name = "root"
initial = 1
)", file.string()));
  EXPECT_RIGID_ERROR((void)load_scene(scalar),
                     "unknown key 'initial' in [[coordinates]] entry 1 (the ball coordinate 'root')");
  fs::remove(toml);
  fs::remove(scalar);
}

TEST(RobotScene, PinnedHumanoidEqualsTreeDynamics) {
  const fs::path file = "/usr/share/mujoco/model/humanoid/humanoid.xml";  // libmujoco-samples
  ASSERT_TRUE(fs::exists(file)) << file << " is missing: scripts/install-deps.sh installs it";
  io::RobotReadOptions pin;
  pin.pin_free_root = true;
  const io::RobotModel robot = io::read_robot_model_file(file.string(), pin);
  const Model model(scene_from_robot(robot, file));
  const robot::TreeDynamics tree(robot);
  lagrange::Workspace w = model.system().make_workspace();
  expect_same_at_random_states(model.system(), w, tree, 21, 5);
}

// With symbolic inertia the links' mass properties are parameters (m_<link>, com_<link>_x,
// I_<link>_xx …) with the file's values: the same equations at those values, and at changed
// values the equations of the file with the link's inertial changed (TreeDynamics of an edited
// RobotModel: an independent path); an impossible value is refused naming the body.
TEST(RobotScene, SymbolicInertiaParametersAreTheLinksInertials) {
  const fs::path file = kExamples / "arm7.urdf";
  ModelOptions symbolic;
  symbolic.symbolic_inertia = true;
  const Model model(load_scene(file, symbolic));
  const lagrange::System& system = model.system();
  const std::vector<lagrange::Parameter> params = system.parameters();
  ASSERT_EQ(params.size(), 7u * 10u);  // 7 links × (m, COM 3, inertia 6)
  EXPECT_EQ(params[0].name, "m_link1");
  EXPECT_EQ(params[4].name, "I_link1_xx");
  EXPECT_EQ(params[9].name, "I_link1_yz");
  io::RobotModel robot = io::read_robot_model_file(file.string());
  // link3 heavier, its COM moved and its inertia changed: in the scene by parameters, in the
  // file's model by hand
  std::size_t link3 = 0;
  while (robot.links[link3].name != "link3") ++link3;
  lagrange::Workspace w = system.make_workspace();
  Eigen::Matrix3d& I3 = robot.links[link3].inertia_com;
  w.set_parameters({{"m_link3", 2.5},
                    {"com_link3_y", 0.05},
                    {"I_link3_xx", I3(0, 0) * 1.5},
                    {"I_link3_yy", I3(1, 1) * 1.5},
                    {"I_link3_zz", I3(2, 2) * 1.5}});
  robot.links[link3].mass = 2.5;
  robot.links[link3].com.y() = 0.05;
  for (int k = 0; k < 3; ++k) I3(k, k) *= 1.5;
  const robot::TreeDynamics changed(robot);
  expect_same_at_random_states(system, w, changed, 3, 5);
  try {
    w.set_parameter("I_link3_zz", 1e3);  // breaks the triangle inequality I_xx + I_yy ≥ I_zz
    FAIL() << "expected rigid::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("link3"), std::string::npos) << e.what();
  }
}

// Coordinates are the joints' names made usable in expressions: an unnamed MJCF joint is q<i>,
// other characters become '_'; two joints that would share a name are refused, naming both.
TEST(RobotScene, CoordinateNamesFromJointNames) {
  const fs::path f = write("names.xml", R"(<mujoco><worldbody>
<body name="b" pos="0 0 1"><joint axis="0 1 0"/><geom type="sphere" size="0.1" pos="0 0 -0.5"/></body>
<body name="c"><joint name="r-hip.x" axis="1 0 0"/><geom type="sphere" size="0.1" pos="0 0 -0.5"/></body>
</worldbody></mujoco>
)");
  const Scene s = load_scene(f);
  ASSERT_EQ(s.coordinates.size(), 2U);
  EXPECT_EQ(s.coordinates[0].name, "q0");
  EXPECT_EQ(s.coordinates[1].name, "r_hip_x");
  EXPECT_NO_THROW((void)Model(s));
  const fs::path clash = write("clash.xml", R"(<mujoco><worldbody>
<body name="b" pos="0 0 1"><joint name="a-b" axis="0 1 0"/><geom type="sphere" size="0.1" pos="0 0 -0.5"/>
<body name="c"><joint name="a_b" axis="1 0 0"/><geom type="sphere" size="0.1" pos="0 0 -0.5"/></body></body>
</worldbody></mujoco>
)");
  try {
    (void)load_scene(clash);
    FAIL() << "expected rigid::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  clash.string() + ":3: joint 'a_b' would be the coordinate 'a_b', the name of "
                                   "the joint 'a-b' (line 2)"),
              std::string::npos)
        << e.what();
  }
  fs::remove(f);
  fs::remove(clash);
}

// A robot scene's model, built once, run from eight threads at once (ThreadSanitizer in make
// test): every run's trajectory equals the serial one bit for bit. cart_arm is derived expanded,
// arm7 by the tree's recursions (its tape reads the intermediates' slots), MuJoCo's humanoid on
// its free root with ball coordinates (an absolute path: kExamples / it is it).
TEST(RobotSceneThreads, OneModelRunsOnEightThreads) {
  for (const auto& [file, set] : {std::pair{"cart_arm.urdf", "shoulder.initial=0.8"},
                                  std::pair{"arm7.urdf", "joint2.initial=0.6"},
                                  std::pair{"/usr/share/mujoco/model/humanoid/humanoid.xml",
                                            "root.angular_velocity=[0, 0, 3]"}}) {
    SCOPED_TRACE(file);
    Scene s = load_scene(kExamples / file);
    apply_overrides(s, {set, "simulation.t_end=0.5"});
    const Model model(s);
    const RunResult serial = model.run();
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int th = 0; th < 8; ++th) {
      threads.emplace_back([&] {
        const RunResult r = model.run();
        if (r.trajectory.data() != serial.trajectory.data()) {
          ++mismatches;
        }
      });
    }
    for (std::thread& th : threads) th.join();
    EXPECT_EQ(mismatches.load(), 0);
  }
}

}  // namespace
}  // namespace rigid::scene
