// Sweeps: scene::run_sweep, the path of `rigid sweep` without the files (a separate binary from
// run_bench, which must keep building against older commits).
//  - runs per second on 1 and 2 threads for a grid of 32 runs of a small scene: the racket for
//    10 s (splitting4, 10³ steps), and the physical pendulum for 2 s by dopri5 (tolerance 1e-10),
//    whose equations are derived once per sweep and shared by its runs;
//  - the CPU time per run of a 32-run sweep on one thread (apply the override, build the model
//    from the scene read once, run, make the row; the derivation amortised over 32 runs) against
//    Model::run of a model built once: the difference is a sweep's overhead per run beyond the
//    integration;
//  - one run through run_sweep (the file read, and a coordinate scene's derivation, included);
//  - the serial work per run (the symbolic core's lock held) of a grid of the pendulum, the
//    racket and a mesh body, and of a Monte Carlo sample of the pendulum;
//  - a free-body sweep (the racket example) with its runs marched four at a time through the
//    four-body kernel against one by one.
// MPI ranks are measured from the command line (docs/performance.md gives the commands).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "mesh/mesh_builders.hpp"
#include "rigid/io/table.hpp"
#include "rigid/lagrange/symbolic_core.hpp"
#include "rigid/mesh/read_mesh.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "rigid/scene/sweep.hpp"

namespace {

constexpr const char* kSmallRacket = R"toml(
[parameters]
I2 = 2
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = "I2", izz = 2.9}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 10.0
integrator = "splitting4"
dt = 0.01
output_dt = 0.05
)toml";

// examples/tennis_racket.toml (100 s at the default 1 ms, its flip and energy metrics), its
// middle moment swept: the free-body sweep whose runs march four at a time.
constexpr const char* kRacket100 = R"toml(
[parameters]
I2 = 2
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = "I2", izz = 3}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 100.0
output_dt = 0.05
[[output.metrics]]
name = "first_flip"
kind = "crossing"
column = "racket.wy"
k = 1
[[output.metrics]]
name = "energy_drift"
kind = "drift"
column = "energy"
)toml";

constexpr const char* kSmallPendulum = R"toml(
gravity = [0, 0, "-g"]
[parameters]
g = 9.81
m = 0.5
L = 1.0
[[coordinates]]
name = "theta"
initial = 1.0
[[bodies]]
name = "rod"
primitive = "thin_rod"
length = "L"
mass = "m"
position = ["-(L/2)*sin(theta)", 0, "-(L/2)*cos(theta)"]
rotation = [{axis = [0, 1, 0], angle = "-theta"}]
[simulation]
t_end = 2.0
integrator = "dopri5"
tolerance = 1e-10
output_dt = 0.005
)toml";

// A free body whose shape is a 199,808-triangle UV sphere of radius 0.1 m in a binary STL
// (written once), its density swept: each run measures the mesh for its density.
constexpr const char* kMeshBody = R"toml(
[parameters]
rho = 1000
[[bodies]]
name = "ball"
free = true
mesh = "rigid_sweep_bench_sphere.stl"
density = "rho"
angular_velocity = [0.1, 2, 0.1]
[simulation]
t_end = 0.1
dt = 0.01
output_dt = 0.05
)toml";

void write_sphere_once() {
  const auto file = std::filesystem::temp_directory_path() / "rigid_sweep_bench_sphere.stl";
  if (!std::filesystem::exists(file)) rigid::mesh::write_stl_binary(rigid::test::uv_sphere(0.1, 224), file.string());
}

// The sweep of the scene `text` (written to a temporary file named after `name`) over `axis`,
// with the overrides `set` for every run.
std::filesystem::path scene_file(const std::string& name, const char* text) {
  const auto file = std::filesystem::temp_directory_path() / ("rigid_sweep_bench_" + name + ".toml");
  std::ofstream(file) << text;
  return file;
}

rigid::scene::SweepIdentity sweep_of(const std::string& name, const char* text, const char* axis,
                                     std::vector<std::string> set = {}) {
  return {.scene = scene_file(name, text), .set = std::move(set), .integrator = "",
          .spec = {.grid = {rigid::scene::parse_grid_axis(axis)}}};
}

// A Monte Carlo sweep of the scene `text` (as sweep_of): `count` runs drawn from `axis`
// (NAME=DIST(A,B)), seed 1.
rigid::scene::SweepIdentity sample_of(const std::string& name, const char* text, const char* axis,
                                      std::size_t count) {
  return {.scene = scene_file(name, text), .set = {}, .integrator = "",
          .spec = {.sample = {rigid::scene::parse_sample_axis(axis)}, .samples = count, .seed = 1}};
}

void BM_Sweep_runs(benchmark::State& st, const char* name, const char* text, const char* axis,
                   std::vector<std::string> set = {}) {
  write_sphere_once();  // the mesh scenes' file
  const auto id = sweep_of(name, text, axis, std::move(set));
  std::vector<std::size_t> all(rigid::scene::run_count(id.spec));
  std::iota(all.begin(), all.end(), 0);
  for (auto _ : st) {
    const auto rows = rigid::scene::run_sweep(id, all, {.threads = static_cast<std::size_t>(st.range(0))});
    benchmark::DoNotOptimize(rows.data());
  }
  st.counters["runs/s"] =
      benchmark::Counter(static_cast<double>(st.iterations() * all.size()), benchmark::Counter::kIsRate);
}

// A free-body sweep with its runs marched together (range(0) = 1: Model::run_batch, the
// rotations of four runs in one call of the four-body kernel) or one by one (0), on range(1)
// threads, with `integrator`; counter "runs/s".
void BM_Sweep_freeBatch(benchmark::State& st, const char* name, const char* text, const char* axis,
                        const char* integrator) {
  auto id = sweep_of(name, text, axis);
  id.integrator = integrator;
  std::vector<std::size_t> all(rigid::scene::run_count(id.spec));
  std::iota(all.begin(), all.end(), 0);
  const rigid::scene::SweepRunOptions options{.threads = static_cast<std::size_t>(st.range(1)),
                                              .batch = st.range(0) != 0};
  for (auto _ : st) {
    const auto rows = rigid::scene::run_sweep(id, all, options);
    benchmark::DoNotOptimize(rows.data());
  }
  st.counters["runs/s"] =
      benchmark::Counter(static_cast<double>(st.iterations() * all.size()), benchmark::Counter::kIsRate);
}

// The CPU time per run of a sweep of `axis` on one thread (counter "per_run"), to compare with
// BM_Sweep_modelRun of the same scene.
void BM_Sweep_perRun(benchmark::State& st, const char* name, const char* text, const char* axis) {
  const auto id = sweep_of(name, text, axis);
  std::vector<std::size_t> all(rigid::scene::run_count(id.spec));
  std::iota(all.begin(), all.end(), 0);
  for (auto _ : st) {
    const auto rows = rigid::scene::run_sweep(id, all, {.threads = 1});
    benchmark::DoNotOptimize(rows.data());
  }
  st.counters["per_run"] = benchmark::Counter(static_cast<double>(st.iterations() * all.size()),
                                              benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// One run through the sweep's path, to compare with BM_Sweep_modelRun of the same scene.
void BM_Sweep_oneRun(benchmark::State& st, const char* name, const char* text, const char* axis) {
  const auto id = sweep_of(name, text, axis);
  const std::vector<std::size_t> one{0};
  for (auto _ : st) {
    const auto rows = rigid::scene::run_sweep(id, one, {.threads = 1});
    benchmark::DoNotOptimize(rows.data());
  }
}

// The integration alone: Model::run of a model built once.
void BM_Sweep_modelRun(benchmark::State& st, const char* text) {
  const rigid::scene::Model model(rigid::scene::parse_scene(text, "bench.toml"));
  for (auto _ : st) {
    const auto result = model.run();
    benchmark::DoNotOptimize(result.trajectory.data().data());
  }
}

// The measurement of BM_Sweep_serialPerRun: a sweep `large` of 16 runs more than `small`.
void serial_per_run(benchmark::State& st, const rigid::scene::SweepIdentity& small,
                    const rigid::scene::SweepIdentity& large) {
  double serial = 0.0, entries = 0.0, runs = 0.0;
  for (auto _ : st) {
    for (const auto* id : {&small, &large}) {
      std::vector<std::size_t> all(rigid::scene::run_count(id->spec));
      std::iota(all.begin(), all.end(), 0);
      const auto before = rigid::lagrange::symbolic_core_usage();
      const auto rows = rigid::scene::run_sweep(*id, all, {.threads = 2});
      benchmark::DoNotOptimize(rows.data());
      const auto after = rigid::lagrange::symbolic_core_usage();
      const double sign = id == &small ? -1.0 : 1.0;
      serial += sign * (after.seconds_held - before.seconds_held);
      entries += sign * static_cast<double>(after.entries - before.entries);
    }
    runs += 16.0;
  }
  st.counters["serial_us"] = 1e6 * serial / runs;
  st.counters["entries"] = entries / runs;
}

// The serial work per run of a sweep: the time the symbolic core's lock (the one lock a run could
// wait for) was held, per run, beyond what the prototype (derivation, mesh read) took: a sweep of
// `2·count` runs against one of `count`, on 2 threads. Counter "serial_us" (µs per run) and
// "entries" (symbolic-core entries per run); the Amdahl bound at P cores is
// 1 / (s + (1 − s)/P) with s = serial / (serial + parallel per run).
// `axis` is a grid axis without its count ("L=0.5:2:"), or with `sample` a distribution
// ("L=uniform(0.5,2)": a Monte Carlo sweep of 16 and 32 draws).
void BM_Sweep_serialPerRun(benchmark::State& st, const char* name, const char* text, const char* axis,
                           bool sample = false) {
  write_sphere_once();
  const auto small = sample ? sample_of(name, text, axis, 16) : sweep_of(name, text, (std::string(axis) + "16").c_str());
  const auto large = sample ? sample_of(name, text, axis, 32) : sweep_of(name, text, (std::string(axis) + "32").c_str());
  serial_per_run(st, small, large);
}

// The same for a robot model file of examples/ (its joints' initial angles swept), 0.2 s a run.
void BM_Sweep_serialPerRunFile(benchmark::State& st, const char* file, const char* axis) {
  auto of = [&](int count) {
    return rigid::scene::SweepIdentity{.scene = std::filesystem::path(RIGID_EXAMPLES_DIR) / file,
                                       .set = {"simulation.t_end=0.2"}, .integrator = "",
                                       .spec = {.grid = {rigid::scene::parse_grid_axis(fmt::format("{}{}", axis, count))}}};
  };
  serial_per_run(st, of(16), of(32));
}

BENCHMARK_CAPTURE(BM_Sweep_serialPerRun, pendulum, "pendulums", kSmallPendulum, "L=0.5:2:")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_serialPerRun, racket, "rackets", kSmallRacket, "I2=1.95:2.05:")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_serialPerRun, mesh, "meshs", kMeshBody, "rho=900:1100:")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_serialPerRunFile, cart_arm_urdf, "cart_arm.urdf", "shoulder.initial=0.2:1.0:")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_serialPerRun, pendulum_sample, "pendulumm", kSmallPendulum, "L=uniform(0.5,2)", true)
    ->Unit(benchmark::kMillisecond);
// A sweep of the mesh body: 8 runs on 1 and 2 threads (the file read once, by the prototype).
BENCHMARK_CAPTURE(BM_Sweep_runs, mesh_x8, "mesh", kMeshBody, "rho=900:1100:8")
    ->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
// The same body run 100 s at 1 ms steps (~40 ms a run here): runs long enough against the one
// read of the file for a sweep to scale with threads.
BENCHMARK_CAPTURE(BM_Sweep_runs, mesh_100s_x32, "meshl", kMeshBody, "rho=900:1100:32",
                  std::vector<std::string>{"simulation.t_end=100", "simulation.dt=0.001"})
    ->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_Sweep_runs, racket_10s_x32, "racket", kSmallRacket, "I2=1.95:2.05:32")
    ->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
// the racket example's sweep, one by one and batched, on 1 and 2 threads
BENCHMARK_CAPTURE(BM_Sweep_freeBatch, racket_100s_x32_splitting4, "racketb4", kRacket100, "I2=2:2.5:32",
                  "splitting4")
    ->ArgsProduct({{0, 1}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_freeBatch, racket_100s_x32_splitting2, "racketb2", kRacket100, "I2=2:2.5:32",
                  "splitting2")
    ->ArgsProduct({{0, 1}, {1}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_runs, pendulum_2s_x32, "pendulum", kSmallPendulum, "L=0.5:2:32")
    ->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_modelRun, racket_10s, kSmallRacket)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Sweep_perRun, racket_10s_x32, "racketp", kSmallRacket, "I2=1.95:2.05:32")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_perRun, pendulum_2s_x32, "pendulump", kSmallPendulum, "L=0.5:2:32")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep_oneRun, racket_10s, "racket1", kSmallRacket, "I2=2:2:1")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Sweep_modelRun, pendulum_2s, kSmallPendulum)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Sweep_oneRun, pendulum_2s, "pendulum1", kSmallPendulum, "L=1:1:1")->Unit(benchmark::kMicrosecond);

// The serial end of a sweep, after its runs: make_outputs (the sort by run, the table, the
// summary's statistics) and the bytes of runs.csv and runs.npy, for `range(0)` rows of one
// swept value and five results (the pendulum example's), in memory (no file is written);
// the rows in the order of a sweep's journal: nearly by run.
// Counter "rows_per_s" (its inverse is the serial cost of a row).
std::vector<rigid::scene::SweepRow> synthetic_rows(std::size_t count) {
  std::vector<rigid::scene::SweepRow> rows(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double x = 0.1 + 2.4 * static_cast<double>(i) / static_cast<double>(count);
    rows[i].index = i ^ 1U;  // neighbours swapped, as two threads finish them (count even)
    rows[i].values = {x};
    rows[i].results = {{"period", 6.28 + x * x}, {"energy_initial", -2.44 * std::cos(x)},
                       {"energy_final", -2.44 * std::cos(x) + 1e-12 * x}, {"energy_max_change", 1e-12 * x},
                       {"jacobi_max_change", 3e-13 * x}};
  }
  return rows;
}

void BM_Sweep_outputs(benchmark::State& st) {
  const auto count = static_cast<std::size_t>(st.range(0));
  const auto rows = synthetic_rows(count);
  const std::vector<std::string> names{"theta.initial"};
  std::size_t bytes = 0;
  for (auto _ : st) {
    st.PauseTiming();
    auto copy = rows;  // make_outputs takes them (the CLI moves its rows in)
    st.ResumeTiming();
    const auto out = rigid::scene::make_outputs(names, count, std::move(copy), {{"theta.initial", "rad"}});
    const std::string csv = rigid::io::to_csv(out.numbers, "error", out.errors);
    const std::string npy = rigid::io::to_npy(out.numbers);
    bytes = csv.size() + npy.size() + out.summary_json.size();
    benchmark::DoNotOptimize(bytes);
  }
  st.counters["rows_per_s"] = benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate);
  st.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_Sweep_outputs)->Arg(40000)->Unit(benchmark::kMillisecond);

}  // namespace
