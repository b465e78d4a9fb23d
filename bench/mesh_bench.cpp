// Mesh mass properties: accumulation throughput on a generated closed mesh of 1M+ triangles,
// and file-to-result time for a binary STL, next to MuJoCo's mesh inertia (a model whose body
// inertia comes from the mesh geom) on the same file. Counters report each result's relative
// deviation from the analytic sphere (the tessellation itself is ~1e-3 below it at 80k
// triangles; the exact polyhedron's own values are what rigid computes).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include "mesh/mesh_builders.hpp"
#include "rigid/mesh.hpp"

namespace {

using rigid::mesh::TriangleMesh;

// The test suite's UV sphere (tests/mesh/mesh_builders.hpp): 4n(n−1) triangles.
using rigid::test::uv_sphere;

constexpr double kRadius = 0.1;     // m
constexpr double kDensity = 1000;   // kg/m³
const double kMassExact = kDensity * 4.0 / 3 * std::numbers::pi * std::pow(kRadius, 3);
const double kInertiaExact = 0.4 * kMassExact * kRadius * kRadius;

std::string stl_file(int n) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("rigid_mesh_bench_sphere_" + std::to_string(n) + ".stl");
  if (!std::filesystem::exists(path)) rigid::mesh::write_stl_binary(uv_sphere(kRadius, n), path);
  return path.string();
}

void BM_RigidAccumulate(benchmark::State& state) {
  const TriangleMesh m = uv_sphere(kRadius, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto mom = rigid::mesh::volume_moments(m);
    benchmark::DoNotOptimize(mom);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(m.size()));
  state.counters["triangles"] = static_cast<double>(m.size());
}
BENCHMARK(BM_RigidAccumulate)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond);

void BM_RigidReadStl(benchmark::State& state) {
  const std::string file = stl_file(static_cast<int>(state.range(0)));
  std::size_t n = 0;
  for (auto _ : state) {
    auto m = rigid::mesh::read_mesh(file);
    n = m.size();
    benchmark::DoNotOptimize(m);
  }
  state.counters["triangles"] = static_cast<double>(n);
}
BENCHMARK(BM_RigidReadStl)->Arg(144)->Arg(512)->Unit(benchmark::kMillisecond);

// repair_mesh alone on the mesh read from the file (a fresh copy per iteration, untimed).
void BM_RigidRepair(benchmark::State& state) {
  const TriangleMesh soup = rigid::mesh::read_mesh(stl_file(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    state.PauseTiming();
    TriangleMesh m = soup;
    state.ResumeTiming();
    auto report = rigid::mesh::repair_mesh(m);
    benchmark::DoNotOptimize(report);
  }
  state.counters["triangles"] = static_cast<double>(soup.size());
}
BENCHMARK(BM_RigidRepair)->Arg(144)->Unit(benchmark::kMillisecond);

// read + weld/orient/inspect + mass properties, step by step (read_mesh, repair_mesh,
// mesh_mass_properties: an exact weld that finds nothing after the welding reader, and a second
// edge matching for closedness); with exact_weld_first = false the tolerance weld runs on every
// vertex read.
void file_to_result_steps(benchmark::State& state, bool exact_weld_first) {
  const std::string file = stl_file(static_cast<int>(state.range(0)));
  double mass = 0, ixx = 0;
  std::size_t n = 0;
  for (auto _ : state) {
    auto m = rigid::mesh::read_mesh(file);
    rigid::mesh::repair_mesh(m, {.exact_weld_first = exact_weld_first});
    const auto r = rigid::mesh::mesh_mass_properties(m, {std::nullopt, kDensity, false, {}});
    mass = r.properties.mass();
    ixx = r.properties.inertia_com()(0, 0);
    n = m.size();
  }
  state.counters["triangles"] = static_cast<double>(n);
  state.counters["mass_rel_err"] = mass / kMassExact - 1;
  state.counters["Ixx_rel_err"] = ixx / kInertiaExact - 1;
}

// The same in one call (mesh_mass_from_file: no redundant exact weld, one edge matching), as
// `rigid inertia FILE` runs it; bitwise the same result (tests/mesh).
void BM_RigidFileToResult(benchmark::State& state) {
  const std::string file = stl_file(static_cast<int>(state.range(0)));
  double mass = 0, ixx = 0;
  std::size_t n = 0;
  for (auto _ : state) {
    const auto r = rigid::mesh::mesh_mass_from_file(file, 1.0, {std::nullopt, kDensity, false, {}});
    mass = r.mass.properties.mass();
    ixx = r.mass.properties.inertia_com()(0, 0);
    n = r.repair.input_triangles;
  }
  state.counters["triangles"] = static_cast<double>(n);
  state.counters["mass_rel_err"] = mass / kMassExact - 1;
  state.counters["Ixx_rel_err"] = ixx / kInertiaExact - 1;
}
BENCHMARK(BM_RigidFileToResult)->Arg(144)->Arg(512)->Unit(benchmark::kMillisecond);

void BM_RigidFileToResultSteps(benchmark::State& state) { file_to_result_steps(state, true); }
BENCHMARK(BM_RigidFileToResultSteps)->Arg(144)->Arg(512)->Unit(benchmark::kMillisecond);

void BM_RigidFileToResultToleranceWeld(benchmark::State& state) {
  file_to_result_steps(state, false);
}
BENCHMARK(BM_RigidFileToResultToleranceWeld)->Arg(144)->Arg(512)->Unit(benchmark::kMillisecond);

// MuJoCo: compile a model whose only body's inertia comes from the mesh geom.
void BM_MuJoCoFileToResult(benchmark::State& state) {
  const std::string file = stl_file(static_cast<int>(state.range(0)));
  const auto xml = std::filesystem::temp_directory_path() / "rigid_mesh_bench_model.xml";
  std::ofstream(xml) << "<mujoco><compiler inertiafromgeom=\"true\"/><asset><mesh name=\"m\" file=\""
                     << file << "\"/></asset><worldbody><body><freejoint/><geom type=\"mesh\" "
                     << "mesh=\"m\" density=\"" << kDensity << "\"/></body></worldbody></mujoco>";
  double mass = 0, ixx = 0;
  char error[1000] = "";
  for (auto _ : state) {
    mjModel* model = mj_loadXML(xml.string().c_str(), nullptr, error, sizeof(error));
    if (model == nullptr) {
      state.SkipWithError(error);
      return;
    }
    mass = model->body_mass[1];
    ixx = model->body_inertia[3];
    mj_deleteModel(model);
  }
  state.counters["mass_rel_err"] = mass / kMassExact - 1;
  state.counters["Ixx_rel_err"] = ixx / kInertiaExact - 1;
}
BENCHMARK(BM_MuJoCoFileToResult)->Arg(144)->Unit(benchmark::kMillisecond);

}  // namespace
