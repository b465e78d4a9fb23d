// Robot model files read by io::read_robot_model_file and moved by robot::TreeDynamics, against
// MuJoCo (libmujoco 2.2.2) loading the same files: M(q) = mj_fullM (armature included) and
// f = −qfrc_bias + qfrc_passive at 20 random states each, relative 1e-9 (the acceptance
// bound: the two implementations round differently, and MuJoCo stores each body's inertia as
// principal moments and a quaternion it computed).
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include "rigid/common/error.hpp"
#include "rigid/io/robot_model.hpp"
#include "rigid/robot/tree_dynamics.hpp"
#include "support/mujoco_model.hpp"

namespace rigid::robot {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/mujoco/model";  // Debian's libmujoco-samples
const fs::path kExamples = fs::path(RIGID_TEST_DATA_DIR).parent_path().parent_path() / "examples";

using test::load_mujoco;
using test::without_free_joints;
using MjModel = test::MjModelPtr;
using MjData = test::MjDataPtr;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A copy of MuJoCo's model directory `dir` in which every free joint is removed: MuJoCo's own
// model of the robot pinned at its root (what RobotReadOptions::pin_free_root reads).
fs::path pinned_copy(const fs::path& dir) {
  const fs::path out = fs::temp_directory_path() /
                       fmt::format("rigid_pinned_{}_{}", dir.filename().string(), ::getpid());
  fs::create_directories(out);
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".xml") {
      std::ofstream(out / e.path().filename()) << without_free_joints(read(e.path()));
    } else {
      fs::copy(e.path(), out / e.path().filename(),
               fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    }
  }
  return out;
}

// M and f of MuJoCo and of TreeDynamics at 20 random states around the reference pose.
void expect_same_dynamics(const mjModel* m, const TreeDynamics& tree, unsigned seed) {
  ASSERT_EQ(static_cast<int>(tree.dof()), m->nv);
  ASSERT_EQ(m->nq, m->nv);  // hinge and slide joints only
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  MjData d(mj_makeData(m));
  std::vector<mjtNum> dense(static_cast<std::size_t>(m->nv * m->nv));
  const Eigen::VectorXd q0 = tree.reference_configuration();
  for (int state = 0; state < 20; ++state) {
    Eigen::VectorXd q(m->nv), v(m->nv);
    for (int i = 0; i < m->nv; ++i) {
      q(i) = q0(i) + u(rng);
      v(i) = 2 * u(rng);
      d->qpos[i] = q(i);
      d->qvel[i] = v(i);
    }
    mj_forward(m, d.get());
    mj_fullM(m, dense.data(), d->qM);
    const Eigen::MatrixXd M = tree.mass_matrix(q);
    const Eigen::VectorXd f = -tree.bias_forces(q, v) + tree.passive_forces(q, v);
    const double m_scale = M.cwiseAbs().maxCoeff(),
                 f_scale = std::max(1.0, f.cwiseAbs().maxCoeff());
    for (int i = 0; i < m->nv; ++i) {
      EXPECT_NEAR(f(i), -d->qfrc_bias[i] + d->qfrc_passive[i], 1e-9 * f_scale)
          << "f row " << i << ", state " << state;
      for (int j = 0; j < m->nv; ++j) {
        EXPECT_NEAR(M(i, j), dense[static_cast<std::size_t>(i * m->nv + j)], 1e-9 * m_scale)
            << "M(" << i << ", " << j << "), state " << state;
      }
    }
  }
}

// The coordinates in MuJoCo's order: the joints' names, as MuJoCo numbers them.
void expect_same_coordinates(const mjModel* m, const io::RobotModel& model) {
  const std::vector<std::string> names = model.coordinate_names();
  ASSERT_EQ(static_cast<int>(names.size()), m->njnt);
  for (int j = 0; j < m->njnt; ++j) {
    const char* name = mj_id2name(m, mjOBJ_JOINT, j);
    if (name != nullptr) {
      EXPECT_EQ(names[static_cast<std::size_t>(j)], name);
    }
    EXPECT_EQ(m->jnt_qposadr[j], j);
  }
}

TEST(RobotFiles, SevenJointArmUrdfMatchesMuJoCo) {
  const fs::path file = kExamples / "arm7.urdf";
  const io::RobotModel model = io::read_robot_model_file(file.string());
  const MjModel m = load_mujoco(file);
  ASSERT_NE(m, nullptr);
  expect_same_coordinates(m.get(), model);
  expect_same_dynamics(m.get(), TreeDynamics(model), 7);
}

TEST(RobotFiles, PrismaticContinuousAndFixedUrdfMatchesMuJoCo) {
  const fs::path file = kExamples / "cart_arm.urdf";
  const io::RobotModel model = io::read_robot_model_file(file.string());
  const MjModel m = load_mujoco(file);
  ASSERT_NE(m, nullptr);
  expect_same_coordinates(m.get(), model);
  expect_same_dynamics(m.get(), TreeDynamics(model), 8);
}

TEST(RobotFiles, MuJoCoHumanoidPinnedAtTheTorso) {
  io::RobotReadOptions pin;
  pin.pin_free_root = true;
  const io::RobotModel model =
      io::read_robot_model_file((kModels / "humanoid" / "humanoid.xml").string(), pin);
  EXPECT_EQ(model.dof(), 21U);
  const fs::path dir = pinned_copy(kModels / "humanoid");
  const MjModel m = load_mujoco(dir / "humanoid.xml");
  ASSERT_NE(m, nullptr);
  expect_same_coordinates(m.get(), model);
  expect_same_dynamics(m.get(), TreeDynamics(model), 9);
  fs::remove_all(dir);
}

TEST(RobotFiles, MuJoCoHumanoid100ThroughItsInclude) {
  io::RobotReadOptions pin;
  pin.pin_free_root = true;
  const io::RobotModel model =
      io::read_robot_model_file((kModels / "humanoid100" / "humanoid100.xml").string(), pin);
  const fs::path dir = pinned_copy(kModels / "humanoid100");
  const MjModel m = load_mujoco(dir / "humanoid100.xml");
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(static_cast<int>(model.links.size()), m->nbody - 1);
  expect_same_coordinates(m.get(), model);
  expect_same_dynamics(m.get(), TreeDynamics(model), 10);
  fs::remove_all(dir);
}

TEST(RobotFiles, MuJoCoTendonArmHingeTree) {
  const fs::path file = kModels / "tendon_arm" / "arm26.xml";
  const io::RobotModel model = io::read_robot_model_file(file.string());
  const MjModel m = load_mujoco(file);
  ASSERT_NE(m, nullptr);
  expect_same_coordinates(m.get(), model);
  expect_same_dynamics(m.get(), TreeDynamics(model), 11);
}

// Every model Debian's libmujoco-samples ships, read as written and pinned: a tree whose
// dynamics build, or a rigid::Error naming the file (composites, flexible bodies, ball joints
// are refused); never another exception. The ones that read have MuJoCo's coordinate count.
TEST(RobotFiles, EveryMuJoCoSampleReadsOrIsRefusedByName) {
  int read = 0, refused = 0;
  for (const auto& e : fs::recursive_directory_iterator(kModels)) {
    if (e.path().extension() != ".xml") continue;
    SCOPED_TRACE(e.path().string());
    io::RobotReadOptions pin;
    pin.pin_free_root = true;
    try {
      const TreeDynamics tree(io::read_robot_model_file(e.path().string(), pin));
      ++read;
      EXPECT_GT(tree.dof(), 0U);
    } catch (const Error& err) {
      ++refused;
      EXPECT_NE(std::string(err.what()).find(e.path().filename().string()), std::string::npos)
          << err.what();
    }
  }
  EXPECT_GE(read, 4);  // humanoid, humanoid100, arm26, 22_humanoids at least
  EXPECT_GE(read + refused, 15);
}

}  // namespace
}  // namespace rigid::robot
