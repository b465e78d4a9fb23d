// Tennis racket I = diag(1, 2, 3), ω0 = (0.01, 1, 0.01), t = 0 … 100 s: ns per step and,
// as counters, the max body-ω error against the exact elliptic solution (sampled every
// 0.1 s), the relative energy drift and the |L| drift; ODE (gyroscopic on/off) as peer.
// ns per step = 1e9 / items_per_second.
#include <algorithm>
#include <cmath>

#include <benchmark/benchmark.h>
#include <ode/ode.h>

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

}  // namespace

BENCHMARK_CAPTURE(BM_LongRun, splitting2, FreeBodyMethod::kSplitting2)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_LongRun, midpoint, FreeBodyMethod::kLiePoissonMidpoint)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_ExactOmega);
BENCHMARK_CAPTURE(BM_Rigid, rk4, FreeBodyMethod::kRk4)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rigid, splitting2, FreeBodyMethod::kSplitting2)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rigid, splitting4, FreeBodyMethod::kSplitting4)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rigid, splitting6, FreeBodyMethod::kSplitting6)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rigid, midpoint, FreeBodyMethod::kLiePoissonMidpoint)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Ode, gyro_on, true)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Ode, gyro_off, false)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
