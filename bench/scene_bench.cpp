// Whole scene runs, the path of `rigid run` without the files: the tennis racket (a free
// body: 10⁴ steps of splitting4 and 2001 output rows) and the double pendulum (coordinates:
// implicit midpoint, 2·10⁴ steps and 2001 rows with the bodies' poses). The model is built
// once; a run is what is timed.
#include <benchmark/benchmark.h>

#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"

namespace {

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

BENCHMARK_CAPTURE(BM_SceneRun, tennis_racket, kRacket)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SceneRun, double_pendulum, kDoublePendulum)->Unit(benchmark::kMillisecond);

}  // namespace
