// Robot trees: rigid::robot::TreeDynamics per call (M(q), the bias forces, forward dynamics)
// against MuJoCo in the same run on the same file: mj_forward (all MuJoCo computes before a
// step: kinematics, M and its factorisation, bias and passive forces, collisions and
// constraints where the model has them) and the parts that are the same work as ours
// (mj_kinematics + mj_comPos + mj_crb for M; + mj_comVel + mj_rne for the bias). Models: the
// seven-joint arm of examples/arm7.urdf, MuJoCo's humanoid pinned at the torso (21 hinges) and
// (TreeDynamics only) the humanoid as shipped, on its free root (nq = 28, nv = 27).
// And the symbolic side: the file's scene derived and compiled (the tree's recursions on named
// intermediates), its printed equations, and its compiled tape's M and f per call; and its
// flat C++ export (`rigid eom MODEL --emit c++ --flat`, compiled into this binary): M, inverse
// and forward dynamics and their derivatives per call, against mj_forward with constraints and
// contacts disabled and MuJoCo's recursive Newton–Euler with accelerations (inverse dynamics).
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include "rigid/io/robot_model.hpp"
#include "rigid/lagrange/system.hpp"
#include "rigid/robot/tree_dynamics.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/robot_scene.hpp"
#include "robot_codegen.hpp"
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
    const auto nq = static_cast<Eigen::Index>(tree.nq());
    const auto n = static_cast<Eigen::Index>(tree.nv());
    q = tree.reference_configuration();
    v.resize(n);
    tau.resize(n);
    // a free root (nq = nv + 1): its position and a random unit quaternion
    const Eigen::Index first = nq > n ? 7 : 0;
    if (nq > n) {
      Eigen::Vector4d quat(u(rng), u(rng), u(rng), u(rng));
      q.segment<4>(3) = quat.normalized();
    }
    for (Eigen::Index i = first; i < nq; ++i) q(i) += u(rng);
    for (Eigen::Index i = 0; i < nq; ++i) d->qpos[i] = q(i);
    for (Eigen::Index i = 0; i < n; ++i) {
      v(i) = u(rng);
      tau(i) = u(rng);
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
  if (which == 2) {  // the humanoid as shipped: its free root, nq = 28, nv = 27
    static Pair free(kHumanoid.string(), kHumanoid.string(), false);
    return free;
  }
  return which == 0 ? arm : humanoid;
}

const char* name_of(int which) {
  return which == 0 ? "arm7" : which == 1 ? "humanoid_pinned" : "humanoid_free";
}

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

// the exported code of the model: which == 0 arm7, 1 the pinned humanoid, 2 the humanoid on its
// free root
const rigid_bench::Codegen& codegen(int which) {
  return which == 0   ? rigid_bench::codegen_arm7()
         : which == 1 ? rigid_bench::codegen_humanoid_pinned()
                      : rigid_bench::codegen_humanoid_free();
}

void BM_Exported_massMatrix(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  Pair& p = model(which);
  state.SetLabel(name_of(which));
  const rigid_bench::Codegen& c = codegen(which);
  std::vector<double> M(static_cast<std::size_t>(c.nv * c.nv));
  for (auto _ : state) {
    c.mass_matrix(p.q.data(), M.data());
    benchmark::DoNotOptimize(M.data());
  }
}

// τ at the state's q, q̇ with q̈ = the state's τ values (any accelerations do)
void BM_Exported_inverseDynamics(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  Pair& p = model(which);
  state.SetLabel(name_of(which));
  const rigid_bench::Codegen& c = codegen(which);
  std::vector<double> tau(static_cast<std::size_t>(c.nv));
  for (auto _ : state) {
    c.inverse_dynamics(p.q.data(), p.v.data(), p.tau.data(), tau.data());
    benchmark::DoNotOptimize(tau.data());
  }
}

void BM_Exported_forwardDynamics(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  Pair& p = model(which);
  state.SetLabel(name_of(which));
  const rigid_bench::Codegen& c = codegen(which);
  std::vector<double> a(static_cast<std::size_t>(c.nv));
  for (auto _ : state) {
    c.forward_dynamics(p.q.data(), p.v.data(), p.tau.data(), a.data());
    benchmark::DoNotOptimize(a.data());
  }
}

void BM_Exported_inverseDynamicsDerivatives(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  Pair& p = model(which);
  state.SetLabel(name_of(which));
  const rigid_bench::Codegen& c = codegen(which);
  const auto nn = static_cast<std::size_t>(c.nv * c.nv);
  std::vector<double> dq(nn), dv(nn), da(nn);
  for (auto _ : state) {
    c.inverse_dynamics_derivatives(p.q.data(), p.v.data(), p.tau.data(), dq.data(), dv.data(),
                                   da.data());
    benchmark::DoNotOptimize(dq.data());
  }
}

void BM_Exported_forwardDynamicsDerivatives(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  Pair& p = model(which);
  state.SetLabel(name_of(which));
  const rigid_bench::Codegen& c = codegen(which);
  const auto nn = static_cast<std::size_t>(c.nv * c.nv);
  std::vector<double> a(static_cast<std::size_t>(c.nv)), dq(nn), dv(nn), dtau(nn);
  for (auto _ : state) {
    c.forward_dynamics_derivatives(p.q.data(), p.v.data(), p.tau.data(), a.data(), dq.data(),
                                   dv.data(), dtau.data());
    benchmark::DoNotOptimize(dq.data());
  }
}

// What MuJoCo offers for the derivatives: mjd_transitionFD, centered finite differences of its
// Euler step (constraints and contacts off), here A = ∂(q', v')/∂(q, v) only: 4 nv + 1 steps, each
// a forward pass. Not the same quantity as ∂q̈/∂x (h ∂q̈/∂x is A's lower half), but what its
// users call for it.
void BM_MuJoCo_transitionFD(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  const int flags = p.m->opt.disableflags;
  const int integrator = p.m->opt.integrator;
  p.m->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT;
  p.m->opt.integrator = mjINT_EULER;
  const int n = 2 * p.m->nv + p.m->na;
  std::vector<mjtNum> A(static_cast<std::size_t>(n * n));
  for (auto _ : state) {
    mjd_transitionFD(p.m, p.d, 1e-6, 1, A.data(), nullptr, nullptr, nullptr);
    benchmark::DoNotOptimize(A.data());
  }
  p.m->opt.disableflags = flags;
  p.m->opt.integrator = integrator;
}

// mj_forward with constraints and contacts disabled: the same work as forward dynamics
void BM_MuJoCo_forwardNoConstraints(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  const int flags = p.m->opt.disableflags;
  p.m->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT;
  for (auto _ : state) {
    mj_forward(p.m, p.d);
    benchmark::DoNotOptimize(p.d->qacc);
  }
  p.m->opt.disableflags = flags;
}

// MuJoCo's inverse dynamics without constraints: positions, COM frames, velocities and
// recursive Newton–Euler with the accelerations (M q̈ + bias)
void BM_MuJoCo_inverseDynamics(benchmark::State& state) {
  Pair& p = model(static_cast<int>(state.range(0)));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  for (int i = 0; i < p.m->nv; ++i) p.d->qacc[i] = p.tau(i);
  std::vector<mjtNum> tau(static_cast<std::size_t>(p.m->nv));
  for (auto _ : state) {
    mj_kinematics(p.m, p.d);
    mj_comPos(p.m, p.d);
    mj_comVel(p.m, p.d);
    mj_rne(p.m, p.d, 1, tau.data());
    benchmark::DoNotOptimize(tau.data());
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

// the model file → its scene → its System: read, derive, compile the tapes
rigid::scene::Model derived_model(int which) {
  const std::string file = which == 0 ? (kSource / "examples" / "arm7.urdf").string() : kHumanoid.string();
  rigid::io::RobotReadOptions o;
  o.pin_free_root = which == 1;
  return rigid::scene::Model(
      rigid::scene::scene_from_robot(rigid::io::read_robot_model_file(file, o), file));
}

void BM_Robot_derive(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  state.SetLabel(name_of(which));
  for (auto _ : state) benchmark::DoNotOptimize(derived_model(which).system().tape_size());
}

// what `rigid eom` adds: the equations simplified and printed (text, LaTeX)
void BM_Robot_deriveAndPrint(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  state.SetLabel(name_of(which));
  for (auto _ : state) {
    const rigid::scene::Model m = derived_model(which);
    benchmark::DoNotOptimize(m.system().equations().text.size());
  }
}

// the compiled tape's M and f of M q̈ = f (passive terms included) at one state
void BM_Robot_tapeMf(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  state.SetLabel(name_of(which));
  static const rigid::scene::Model arm = derived_model(0), humanoid = derived_model(1);
  const rigid::lagrange::System& system = (which == 0 ? arm : humanoid).system();
  rigid::lagrange::Workspace w = system.make_workspace();
  Pair& p = model(which);
  Eigen::MatrixXd M;
  Eigen::VectorXd f;
  for (auto _ : state) {
    system.mass_matrix_and_forces(w, 0.0, p.q, p.v, M, f);
    benchmark::DoNotOptimize(f.data());
  }
}

BENCHMARK(BM_Robot_derive)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Robot_deriveAndPrint)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Robot_tapeMf)->Arg(0)->Arg(1);
BENCHMARK(BM_Robot_massMatrix)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_MuJoCo_massMatrix)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_Robot_biasForces)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_MuJoCo_biasForces)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_Robot_forwardDynamics)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_MuJoCo_forward)->Arg(0)->Arg(1);
BENCHMARK(BM_Exported_massMatrix)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_Exported_inverseDynamics)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_MuJoCo_inverseDynamics)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_Exported_forwardDynamics)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_MuJoCo_forwardNoConstraints)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_Exported_inverseDynamicsDerivatives)->Arg(0)->Arg(2);
BENCHMARK(BM_Exported_forwardDynamicsDerivatives)->Arg(0)->Arg(2);
BENCHMARK(BM_MuJoCo_transitionFD)->Arg(0)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
