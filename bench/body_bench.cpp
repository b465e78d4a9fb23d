// Tennis racket I = diag(1, 2, 3), ω0 = (0.01, 1, 0.01), t = 0 … 100 s: ns per step and,
// as counters, the max body-ω error against the exact elliptic solution (sampled every
// 0.1 s), the relative energy drift and the |L| drift; peers in the same binary: ODE
// (gyroscopic on/off), MuJoCo (Euler, RK4), Bullet (implicit gyroscopic term on/off).
// ns per step = 1e9 / items_per_second. BM_Batch*: ns per body-step for many bodies.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <BulletCollision/CollisionShapes/btEmptyShape.h>
#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>
#include <mujoco/mujoco.h>
#include <ode/ode.h>

#include "body/detail/free_body_batch_paths.hpp"
#include "rigid/body.hpp"

namespace {

using rigid::body::FreeBodyExact;
using rigid::body::FreeBodyMethod;
using rigid::body::FreeBodyState;

const Eigen::Vector3d kI(1, 2, 3);
const Eigen::Vector3d kW0(0.01, 1, 0.01);
constexpr double kTEnd = 100.0;

struct Errors {
  double omega = 0, energy = 0, L = 0;
};

template <typename Stepper>
Errors measure(double dt, Stepper&& step_and_get) {
  const FreeBodyExact exact(kI, kW0);
  const double E0 = 0.5 * (kI.array() * kW0.array().square()).sum();
  const double L0 = kI.cwiseProduct(kW0).norm();
  const auto n = static_cast<long>(std::lround(kTEnd / dt));
  const long every = std::max(1L, static_cast<long>(std::lround(0.1 / dt)));
  Errors e;
  for (long i = 1; i <= n; ++i) {
    const Eigen::Vector3d w = step_and_get();
    if (i % every == 0 || i == n) {
      e.omega = std::max(e.omega, (w - exact.omega_body(dt * static_cast<double>(i))).lpNorm<Eigen::Infinity>());
      e.energy = std::max(e.energy, std::abs(0.5 * (kI.array() * w.array().square()).sum() - E0) / E0);
      e.L = std::max(e.L, std::abs(kI.cwiseProduct(w).norm() - L0) / L0);
    }
  }
  return e;
}

void report(benchmark::State& st, const Errors& e, long steps_per_iter) {
  st.counters["w_err"] = e.omega;
  st.counters["E_drift"] = e.energy;
  st.counters["L_drift"] = e.L;
  st.SetItemsProcessed(st.iterations() * steps_per_iter);
}

void BM_Rigid(benchmark::State& st, FreeBodyMethod m) {
  const double dt = 1.0 / static_cast<double>(st.range(0));
  const long n = std::lround(kTEnd / dt);
  for (auto _ : st) {
    FreeBodyState s;
    s.w_B = kW0;
    for (long i = 0; i < n; ++i) s = rigid::body::step_free_body(m, kI, s, dt);
    benchmark::DoNotOptimize(s);
  }
  FreeBodyState s;
  s.w_B = kW0;
  report(st, measure(dt, [&] {
           s = rigid::body::step_free_body(m, kI, s, dt);
           return s.w_B;
         }),
         n);
}

// The single-body splitting stepper as it was before the shared kernel (for before/after in
// one binary): unmerged sub-flows, std::cos/std::sin of the full and of the half angle in each,
// q normalised by a square root at the end of the step.
namespace previous {
void axis_flow(int i, Eigen::Quaterniond& q, Eigen::Vector3d& L, double h) {
  const double theta = h * L(i) / kI(i);
  const double c = std::cos(theta), s = std::sin(theta);
  const int j = (i + 1) % 3, k = (i + 2) % 3;
  const double Lj = L(j), Lk = L(k);
  L(j) = c * Lj + s * Lk;
  L(k) = -s * Lj + c * Lk;
  Eigen::Quaterniond r(std::cos(0.5 * theta), 0, 0, 0);
  r.vec()(i) = std::sin(0.5 * theta);
  q = q * r;
}
void composition(int order, Eigen::Quaterniond& q, Eigen::Vector3d& L, double h) {
  if (order == 2) {
    for (const auto& [i, c] : {std::pair{0, 0.5}, {1, 0.5}, {2, 1.0}, {1, 0.5}, {0, 0.5}}) axis_flow(i, q, L, c * h);
    return;
  }
  const double g1 = 1.0 / (2.0 - std::pow(2.0, 1.0 / (order - 1)));
  for (const double g : {g1, 1.0 - 2.0 * g1, g1}) composition(order - 2, q, L, g * h);
}
FreeBodyState step(int order, const FreeBodyState& st, double h) {
  Eigen::Quaterniond q(st.R_WB.w(), st.R_WB.x(), st.R_WB.y(), st.R_WB.z());
  Eigen::Vector3d L = kI.cwiseProduct(st.w_B);
  composition(order, q, L, h);
  q.normalize();
  return {rigid::SO3d::from_unit_quaternion(q.w(), q.x(), q.y(), q.z()), L.cwiseQuotient(kI)};
}
}  // namespace previous

void BM_RigidPrevious(benchmark::State& st, int order) {
  const double dt = 1.0 / static_cast<double>(st.range(0));
  const long n = std::lround(kTEnd / dt);
  for (auto _ : st) {
    FreeBodyState s;
    s.w_B = kW0;
    for (long i = 0; i < n; ++i) s = previous::step(order, s, dt);
    benchmark::DoNotOptimize(s);
  }
  FreeBodyState s;
  s.w_B = kW0;
  report(st, measure(dt, [&] {
           s = previous::step(order, s, dt);
           return s.w_B;
         }),
         n);
}

struct OdeBody {
  dWorldID world;
  dBodyID body;
  OdeBody(bool gyro) {
    world = dWorldCreate();
    dWorldSetGravity(world, 0, 0, 0);
    body = dBodyCreate(world);
    dMass m;
    dMassSetParameters(&m, 1.0, 0, 0, 0, kI(0), kI(1), kI(2), 0, 0, 0);
    dBodySetMass(body, &m);
    dBodySetAngularVel(body, kW0(0), kW0(1), kW0(2));  // R = 1: world = body
    dBodySetGyroscopicMode(body, gyro ? 1 : 0);
  }
  ~OdeBody() { dWorldDestroy(world); }
  Eigen::Vector3d omega_body() const {
    const dReal* w = dBodyGetAngularVel(body);
    const dReal* R = dBodyGetRotation(body);  // row-major 3×4
    Eigen::Vector3d wb;
    for (int c = 0; c < 3; ++c) wb(c) = R[0 * 4 + c] * w[0] + R[1 * 4 + c] * w[1] + R[2 * 4 + c] * w[2];
    return wb;
  }
};

void BM_Ode(benchmark::State& st, bool gyro) {
  dInitODE2(0);
  const double dt = 1.0 / static_cast<double>(st.range(0));
  const long n = std::lround(kTEnd / dt);
  for (auto _ : st) {
    OdeBody b(gyro);
    for (long i = 0; i < n; ++i) dWorldStep(b.world, dt);
    benchmark::DoNotOptimize(dBodyGetAngularVel(b.body));
  }
  OdeBody b(gyro);
  report(st, measure(dt, [&] {
           dWorldStep(b.world, dt);
           return b.omega_body();
         }),
         n);
}

void BM_ExactOmega(benchmark::State& st) {
  const FreeBodyExact exact(kI, kW0);
  double t = 0;
  for (auto _ : st) {
    t += 0.0137;
    if (t > kTEnd) t -= kTEnd;
    benchmark::DoNotOptimize(exact.omega_body(t));
  }
}

// Closed-form orientation R_WB(t) of the same motion (one evaluation).
void BM_ExactOrientation(benchmark::State& st) {
  const rigid::body::FreeBodyMotion motion(kI, rigid::SO3d::identity(), kW0);
  double t = 0;
  for (auto _ : st) {
    t += 0.0137;
    if (t > kTEnd) t -= kTEnd;
    benchmark::DoNotOptimize(motion.orientation(t));
  }
}

}  // namespace

// The previous evaluation (Π by Carlson's R_F/R_J duplication loop), kept in
// FreeBodyMotion as the tests' reference: the before/after pair in one run.
namespace rigid::body {
struct FreeBodyMotionPeer {
  static rigid::SO3d orientation_carlson(const FreeBodyMotion& m, double t) {
    return m.orientation_impl(t, true);
  }
};
}  // namespace rigid::body

namespace {

void BM_ExactOrientationCarlson(benchmark::State& st) {
  const rigid::body::FreeBodyMotion motion(kI, rigid::SO3d::identity(), kW0);
  double t = 0;
  for (auto _ : st) {
    t += 0.0137;
    if (t > kTEnd) t -= kTEnd;
    benchmark::DoNotOptimize(rigid::body::FreeBodyMotionPeer::orientation_carlson(motion, t));
  }
}

// 10⁷ steps (t = 1e5 s at dt = 0.01): drift of L_W, |L|, energy and ‖RᵀR − 1‖ of the
// Lie–Poisson methods (one iteration; the counters are the point, not the time).
void BM_LongRun(benchmark::State& st, FreeBodyMethod m) {
  FreeBodyState s;
  s.w_B = kW0;
  const auto d0 = rigid::body::diagnose(kI, s);
  for (auto _ : st) {
    for (long i = 0; i < 10'000'000; ++i) s = rigid::body::step_free_body(m, kI, s, 0.01);
  }
  const auto d = rigid::body::diagnose(kI, s);
  st.counters["LW_drift"] = (d.L_W - d0.L_W).norm() / d0.L_W.norm();
  st.counters["absL_drift"] = std::abs(kI.cwiseProduct(s.w_B).norm() - d0.L_W.norm()) / d0.L_W.norm();
  st.counters["E_drift"] = std::abs(d.energy - d0.energy) / d0.energy;
  st.counters["orthonormality"] = d.orthonormality_error;
}

// MuJoCo 2.2: the racket as a model with one free-joint body (diaginertia = I, no geoms,
// gravity 0). The free joint's qvel is (v_W, ω_B): linear velocity in the world frame,
// angular velocity in the body's local frame, so qvel[3..5] is ω_B directly.
mjModel* load_mujoco(const std::string& xml) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("rigid_body_bench_" + std::to_string(std::hash<std::string>{}(xml)) + ".xml");
  std::ofstream(file) << xml;
  char error[1000] = "";
  mjModel* model = mj_loadXML(file.string().c_str(), nullptr, error, sizeof(error));
  std::filesystem::remove(file);
  if (model == nullptr) throw std::runtime_error(std::string("mj_loadXML: ") + error);
  return model;
}

std::string mujoco_bodies_xml(const std::vector<Eigen::Vector3d>& inertias) {
  std::ostringstream xml;
  xml.precision(17);
  xml << "<mujoco><option gravity=\"0 0 0\"/><worldbody>";
  for (const auto& I : inertias)
    xml << "<body><freejoint/><inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"" << I(0) << ' '
        << I(1) << ' ' << I(2) << "\"/></body>";
  xml << "</worldbody></mujoco>";
  return xml.str();
}

struct MuJoCoRun {
  mjModel* m;
  mjData* d;
  MuJoCoRun(const std::vector<Eigen::Vector3d>& inertias, const std::vector<Eigen::Vector3d>& w0,
            int integrator, double dt)
      : m(load_mujoco(mujoco_bodies_xml(inertias))), d(mj_makeData(m)) {
    m->opt.integrator = integrator;
    m->opt.timestep = dt;
    for (std::size_t b = 0; b < w0.size(); ++b)
      for (int c = 0; c < 3; ++c) d->qvel[6 * b + 3 + static_cast<std::size_t>(c)] = w0[b](c);
  }
  MuJoCoRun(const MuJoCoRun&) = delete;
  MuJoCoRun& operator=(const MuJoCoRun&) = delete;
  ~MuJoCoRun() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  [[nodiscard]] Eigen::Vector3d omega_body(int b = 0) const {
    return {d->qvel[6 * b + 3], d->qvel[6 * b + 4], d->qvel[6 * b + 5]};
  }
};

void BM_MuJoCo(benchmark::State& st, int integrator) {
  const double dt = 1.0 / static_cast<double>(st.range(0));
  const long n = std::lround(kTEnd / dt);
  try {
    for (auto _ : st) {
      st.PauseTiming();
      MuJoCoRun r({kI}, {kW0}, integrator, dt);
      st.ResumeTiming();
      for (long i = 0; i < n; ++i) mj_step(r.m, r.d);
      benchmark::DoNotOptimize(r.d->qvel[3]);
    }
    MuJoCoRun r({kI}, {kW0}, integrator, dt);
    report(st, measure(dt, [&] {
             mj_step(r.m, r.d);
             return r.omega_body();
           }),
           n);
  } catch (const std::exception& e) {
    st.SkipWithError(e.what());
  }
}

// Bullet 3.24, the double-precision build Debian ships as bullet-float64 (BT_USE_DOUBLE_PRECISION):
// one btRigidBody (mass 1, local inertia I, empty shape) in a btDiscreteDynamicsWorld with zero
// gravity, stepped by stepSimulation(dt, 0) (one step of exactly dt); sleeping disabled, since
// |ω| ≈ 1 rad/s is at Bullet's default angular sleeping threshold. Bullet's angular velocity is
// in the world frame: ω_B = Rᵀ ω_W.
struct BulletBody {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  btEmptyShape shape;
  btDefaultMotionState motion;
  btRigidBody body{btRigidBody::btRigidBodyConstructionInfo(1.0, &motion, &shape,
                                                            btVector3(kI(0), kI(1), kI(2)))};
  explicit BulletBody(int gyro_flags) {
    world.setGravity(btVector3(0, 0, 0));
    body.setFlags(gyro_flags);
    body.setActivationState(DISABLE_DEACTIVATION);
    body.setAngularVelocity(btVector3(kW0(0), kW0(1), kW0(2)));  // R = 1: world = body
    world.addRigidBody(&body);
  }
  BulletBody(const BulletBody&) = delete;
  BulletBody& operator=(const BulletBody&) = delete;
  ~BulletBody() { world.removeRigidBody(&body); }
  [[nodiscard]] Eigen::Vector3d omega_body() const {
    const btVector3 wb = body.getWorldTransform().getBasis().transpose() * body.getAngularVelocity();
    return {wb.x(), wb.y(), wb.z()};
  }
};

void BM_Bullet(benchmark::State& st, int gyro_flags) {
  const double dt = 1.0 / static_cast<double>(st.range(0));
  const long n = std::lround(kTEnd / dt);
  for (auto _ : st) {
    st.PauseTiming();
    auto b = std::make_unique<BulletBody>(gyro_flags);
    st.ResumeTiming();
    for (long i = 0; i < n; ++i) b->world.stepSimulation(dt, 0, dt);
    benchmark::DoNotOptimize(b->body.getAngularVelocity());
  }
  const auto b = std::make_unique<BulletBody>(gyro_flags);
  report(st, measure(dt, [&] {
           b->world.stepSimulation(dt, 0, dt);
           return b->omega_body();
         }),
         n);
}

// The general rigid body (RigidBody, full state with position) on the same racket thrown in
// uniform gravity: uniform gravity exerts no torque about the COM, so ω_B is still the free
// body's and is scored against the exact solution; counter p_err is the COM's distance from
// the parabola at t = 100 s. Shows the cost of the general path over the free-body stepper.
void BM_RigidBody(benchmark::State& st, rigid::body::RigidBodyMethod m) {
  using rigid::body::RigidBodyState;
  const double dt = 1.0 / static_cast<double>(st.range(0));
  const long n = std::lround(kTEnd / dt);
  const Eigen::Vector3d g(0, 0, -9.81), v0(1, 2, 500);
  const rigid::body::RigidBody body(1.0, kI.asDiagonal().toDenseMatrix(), g);
  RigidBodyState s0;
  s0.w_B = kW0;
  s0.v_WC = v0;
  for (auto _ : st) {
    RigidBodyState s = s0;
    for (long i = 0; i < n; ++i) s = rigid::body::step_rigid_body(body, m, dt * static_cast<double>(i), s, dt);
    benchmark::DoNotOptimize(s);
  }
  RigidBodyState s = s0;
  long i = 0;
  report(st, measure(dt, [&] {
           s = rigid::body::step_rigid_body(body, m, dt * static_cast<double>(i++), s, dt);
           return s.w_B;
         }),
         n);
  st.counters["p_err"] = (s.p_WC - (v0 * kTEnd + 0.5 * g * kTEnd * kTEnd)).norm();
}

// Batch: kBatch free bodies with random principal moments (those of random boxes with sides
// in [0.1, 1] m and unit mass, so the triangle inequality holds) and random ω ∈ [−1, 1]³ rad/s;
// one iteration steps every body once at dt = 0.01 s. ns per body-step = 1e9 / items_per_second.
struct Batch {
  std::vector<Eigen::Vector3d> I, w0;
  explicit Batch(long n) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> side(0.1, 1.0), omega(-1.0, 1.0);
    for (long i = 0; i < n; ++i) {
      const double a = side(rng), b = side(rng), c = side(rng);
      I.emplace_back((b * b + c * c) / 12, (a * a + c * c) / 12, (a * a + b * b) / 12);
      w0.emplace_back(omega(rng), omega(rng), omega(rng));
    }
  }
};

void BM_BatchRigid(benchmark::State& st, FreeBodyMethod m) {
  const Batch batch(st.range(0));
  std::vector<FreeBodyState> s(batch.I.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i].w_B = batch.w0[i];
  for (auto _ : st) {
    for (std::size_t i = 0; i < s.size(); ++i) s[i] = rigid::body::step_free_body(m, batch.I[i], s[i], 0.01);
    benchmark::ClobberMemory();
  }
  st.SetItemsProcessed(st.iterations() * st.range(0));
}

// the same batch through the library's batch kernel (merged sub-flows, one sincos each)
void BM_BatchRigidKernel(benchmark::State& st, FreeBodyMethod m) {
  const Batch batch(st.range(0));
  std::vector<FreeBodyState> s(batch.I.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i].w_B = batch.w0[i];
  for (auto _ : st) {
    rigid::body::step_free_bodies(m, batch.I, s, 0.01);
    benchmark::ClobberMemory();
  }
  st.SetItemsProcessed(st.iterations() * st.range(0));
}

// the batch kernel on one named code path (body/detail/free_body_batch_paths.hpp): body by
// body, four bodies in SSE2 vectors, four bodies in AVX2 vectors; the same bits on each
void BM_BatchRigidPath(benchmark::State& st, FreeBodyMethod m, rigid::body::detail::BatchPath path) {
  if (!rigid::body::detail::batch_path_available(path)) {
    st.SkipWithError("this CPU lacks AVX2");
    return;
  }
  const Batch batch(st.range(0));
  std::vector<FreeBodyState> s(batch.I.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i].w_B = batch.w0[i];
  for (auto _ : st) {
    rigid::body::detail::step_free_bodies_on(path, m, batch.I, s, 0.01);
    benchmark::ClobberMemory();
  }
  st.SetItemsProcessed(st.iterations() * st.range(0));
}

void BM_BatchMuJoCo(benchmark::State& st, int integrator) {
  const Batch batch(st.range(0));
  try {
    MuJoCoRun r(batch.I, batch.w0, integrator, 0.01);
    for (auto _ : st) {
      mj_step(r.m, r.d);
      benchmark::ClobberMemory();
    }
  } catch (const std::exception& e) {
    st.SkipWithError(e.what());
  }
  st.SetItemsProcessed(st.iterations() * st.range(0));
}

}  // namespace

BENCHMARK_CAPTURE(BM_LongRun, splitting2, FreeBodyMethod::kSplitting2)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_LongRun, midpoint, FreeBodyMethod::kLiePoissonMidpoint)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_ExactOmega);
BENCHMARK(BM_ExactOrientation);
BENCHMARK(BM_ExactOrientationCarlson);
BENCHMARK_CAPTURE(BM_Rigid, rk4, FreeBodyMethod::kRk4)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rigid, splitting2, FreeBodyMethod::kSplitting2)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rigid, splitting4, FreeBodyMethod::kSplitting4)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rigid, splitting6, FreeBodyMethod::kSplitting6)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RigidPrevious, splitting2, 2)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RigidPrevious, splitting4, 4)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RigidPrevious, splitting6, 6)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rigid, midpoint, FreeBodyMethod::kLiePoissonMidpoint)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RigidBody, splitting2, rigid::body::RigidBodyMethod::kSplitting2)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RigidBody, rk4, rigid::body::RigidBodyMethod::kRk4)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Ode, gyro_on, true)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Ode, gyro_off, false)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MuJoCo, euler, static_cast<int>(mjINT_EULER))->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MuJoCo, rk4, static_cast<int>(mjINT_RK4))->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Bullet, gyro_implicit_body, static_cast<int>(BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY))->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Bullet, gyro_off, 0)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigid, rk4, FreeBodyMethod::kRk4)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigid, splitting2, FreeBodyMethod::kSplitting2)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigid, splitting4, FreeBodyMethod::kSplitting4)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigid, midpoint, FreeBodyMethod::kLiePoissonMidpoint)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigidKernel, splitting2, FreeBodyMethod::kSplitting2)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigidKernel, splitting4, FreeBodyMethod::kSplitting4)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigidKernel, splitting6, FreeBodyMethod::kSplitting6)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigidPath, splitting2_scalar, FreeBodyMethod::kSplitting2, rigid::body::detail::BatchPath::kScalar)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigidPath, splitting2_sse2, FreeBodyMethod::kSplitting2, rigid::body::detail::BatchPath::kLanes)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigidPath, splitting2_avx2, FreeBodyMethod::kSplitting2, rigid::body::detail::BatchPath::kLanesAvx2)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigidPath, splitting4_scalar, FreeBodyMethod::kSplitting4, rigid::body::detail::BatchPath::kScalar)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchRigidPath, splitting4_avx2, FreeBodyMethod::kSplitting4, rigid::body::detail::BatchPath::kLanesAvx2)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchMuJoCo, euler, static_cast<int>(mjINT_EULER))->Arg(1000)->Arg(10'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BatchMuJoCo, rk4, static_cast<int>(mjINT_RK4))->Arg(1000)->Arg(10'000)->Unit(benchmark::kMillisecond);
