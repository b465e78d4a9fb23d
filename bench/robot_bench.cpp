// Robot trees: rigid::robot::TreeDynamics per call (M(q), the bias forces, forward dynamics)
// against MuJoCo in the same run on the same file: mj_forward (all MuJoCo computes before a
// step: kinematics, M and its factorisation, bias and passive forces, collisions and
// constraints where the model has them) and the parts that are the same work as ours
// (mj_kinematics + mj_comPos + mj_crb for M; + mj_comVel + mj_rne for the bias). Models: the
// seven-joint arm of examples/arm7.urdf and MuJoCo's humanoid pinned at the torso (21 hinges).
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include "rigid/io/robot_model.hpp"
#include "rigid/robot/tree_dynamics.hpp"
#include "support/mjcf_text.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kSource = fs::path(__FILE__).parent_path().parent_path();
const fs::path kHumanoid = "/usr/share/mujoco/model/humanoid/humanoid.xml";

// the humanoid without its free joint, for MuJoCo (rigid reads it with pin_free_root)
std::string pinned_humanoid() {
  static const std::string path = [] {
    std::ifstream in(kHumanoid);
    std::stringstream s;
    s << in.rdbuf();
    const fs::path out =
        fs::temp_directory_path() / ("rigid_bench_humanoid_" + std::to_string(::getpid()) + ".xml");
    std::ofstream(out) << rigid::test::without_free_joints(s.str());
    return out.string();
  }();
  return path;
}

// both engines on one model, at one random state
struct Pair {
  rigid::robot::TreeDynamics tree;
  mjModel* m = nullptr;
  mjData* d = nullptr;
  Eigen::VectorXd q, v, tau;

  Pair(const std::string& rigid_file, const std::string& mujoco_file, bool pin)
      : tree(rigid::io::read_robot_model_file(rigid_file, options(pin))) {
    char error[1000] = "";
    m = mj_loadXML(mujoco_file.c_str(), nullptr, error, sizeof error);
    if (m == nullptr) throw std::runtime_error(std::string("mj_loadXML: ") + error);
    d = mj_makeData(m);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto n = static_cast<Eigen::Index>(tree.dof());
    q = tree.reference_configuration();
    v.resize(n);
    tau.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      q(i) += u(rng);
      v(i) = u(rng);
      tau(i) = u(rng);
      d->qpos[i] = q(i);
      d->qvel[i] = v(i);
      d->qfrc_applied[i] = tau(i);
    }
  }
  Pair(const Pair&) = delete;
  Pair& operator=(const Pair&) = delete;
  ~Pair() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  static rigid::io::RobotReadOptions options(bool pin) {
    rigid::io::RobotReadOptions o;
    o.pin_free_root = pin;
    return o;
  }
};

Pair& model(int which) {
  static Pair arm((kSource / "examples" / "arm7.urdf").string(),
                  (kSource / "examples" / "arm7.urdf").string(), false);
  static Pair humanoid(kHumanoid.string(), pinned_humanoid(), true);
  return which == 0 ? arm : humanoid;
}

const char* name_of(int which) { return which == 0 ? "arm7" : "humanoid_pinned"; }

void BM_Robot_massMatrix(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  for (auto _ : state) benchmark::DoNotOptimize(p.tree.mass_matrix(p.q));
}

void BM_Robot_biasForces(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  for (auto _ : state) benchmark::DoNotOptimize(p.tree.bias_forces(p.q, p.v));
}

void BM_Robot_forwardDynamics(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  for (auto _ : state) benchmark::DoNotOptimize(p.tree.forward_dynamics(p.q, p.v, p.tau));
}

// MuJoCo's M: positions, COM frames, composite inertias (qM, its sparse form)
void BM_MuJoCo_massMatrix(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    mj_kinematics(p.m, p.d);
    mj_comPos(p.m, p.d);
    mj_crb(p.m, p.d);
    benchmark::DoNotOptimize(p.d->qM);
  }
}

// MuJoCo's bias: positions, COM frames, velocities, recursive Newton–Euler
void BM_MuJoCo_biasForces(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    mj_kinematics(p.m, p.d);
    mj_comPos(p.m, p.d);
    mj_comVel(p.m, p.d);
    mj_rne(p.m, p.d, 0, p.d->qfrc_bias);
    benchmark::DoNotOptimize(p.d->qfrc_bias);
  }
}

void BM_MuJoCo_forward(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    mj_forward(p.m, p.d);
    benchmark::DoNotOptimize(p.d->qacc);
  }
}

BENCHMARK(BM_Robot_massMatrix)->Arg(0)->Arg(1);
BENCHMARK(BM_MuJoCo_massMatrix)->Arg(0)->Arg(1);
BENCHMARK(BM_Robot_biasForces)->Arg(0)->Arg(1);
BENCHMARK(BM_MuJoCo_biasForces)->Arg(0)->Arg(1);
BENCHMARK(BM_Robot_forwardDynamics)->Arg(0)->Arg(1);
BENCHMARK(BM_MuJoCo_forward)->Arg(0)->Arg(1);

}  // namespace
