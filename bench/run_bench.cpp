// Whole runs: the loops around the kernels (output times, step counts, per-step checks,
// samples and their diagnostics), through the library's entry points
//  - simulate_free_body: the tennis racket for 100 s, splitting4 at h ≤ 0.01 s, a sample every
//    0.05 s (10⁴ steps, 2001 samples with diagnostics);
//  - lagrange::System::simulate: the N-link chain of lagrange_bench for 10 s by RK4 at
//    dt = 1e-3 s, sampled every 0.01 s (10⁴ steps, 4·10⁴ right-hand sides, 1001 rows);
//  - scene::Model::run, the path of `rigid run` without the files: the tennis racket (free
//    bodies) and the double pendulum (coordinates, implicit midpoint: 2·10⁴ steps, 2001 rows
//    with the bodies' poses); the model is built once, a run is what is timed.
// These calls have the same signature before and after the one-loop redesign, so this file
// builds against either (scripts/compare-benchmarks.sh runs both in one session).
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "lagrange_chain.hpp"
#include "rigid/body/free_body_integrators.hpp"
#include "rigid/lagrange/system.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"

namespace {

void BM_SimulateFreeBody(benchmark::State& st) {
  rigid::body::FreeBodyState s;
  s.w_B = Eigen::Vector3d(0.01, 1, 0.01);
  const Eigen::Vector3d I(1, 2, 3);
  std::vector<double> times;
  for (int k = 0; k <= 2000; ++k) times.push_back(0.05 * k);
  for (auto _ : st) {
    const auto traj =
        rigid::body::simulate_free_body(rigid::body::FreeBodyMethod::kSplitting4, I, s, 0.01, times);
    benchmark::DoNotOptimize(traj.states.back());
  }
  st.SetItemsProcessed(st.iterations() * 10'000);
}

void BM_LagrangeSimulate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const rigid::lagrange::System sys(rigid::bench::chain_spec(n));
  rigid::lagrange::SimulationOptions o;
  o.t_end = 10.0;
  o.method = rigid::integrate::Method::kRk4;
  o.dt = 1e-3;
  o.output_dt = 0.01;
  for (auto _ : state) {
    const rigid::lagrange::Trajectory tr = sys.simulate(o);
    benchmark::DoNotOptimize(tr.q.data());
  }
}

constexpr const char* kRacket = R"toml(
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = 2, izz = 3}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 100.0
integrator = "splitting4"
dt = 0.01
output_dt = 0.05
)toml";

constexpr const char* kDoublePendulum = R"toml(
gravity = [0, 0, "-g"]
[parameters]
g = 9.81
m1 = 1.0
m2 = 1.0
l1 = 1.0
l2 = 1.0
[[coordinates]]
name = "theta1"
initial = 1.5707963267948966
[[coordinates]]
name = "theta2"
initial = 1.5707963267948966
[[bodies]]
name = "bob1"
point_masses = [{mass = "m1", position = [0, 0, 0]}]
position = ["l1*sin(theta1)", 0, "-l1*cos(theta1)"]
[[bodies]]
name = "bob2"
point_masses = [{mass = "m2", position = [0, 0, 0]}]
position = ["l1*sin(theta1) + l2*sin(theta2)", 0, "-l1*cos(theta1) - l2*cos(theta2)"]
[simulation]
t_end = 20.0
integrator = "implicit_midpoint"
dt = 1e-3
output_dt = 0.01
)toml";

void BM_SceneRun(benchmark::State& st, const char* text) {
  const rigid::scene::Model model(rigid::scene::parse_scene(text, "bench.toml"));
  for (auto _ : st) {
    const auto result = model.run();
    benchmark::DoNotOptimize(result.trajectory.data().data());
  }
}

BENCHMARK(BM_SimulateFreeBody)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LagrangeSimulate)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SceneRun, tennis_racket, kRacket)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SceneRun, double_pendulum, kDoublePendulum)->Unit(benchmark::kMillisecond);

}  // namespace
