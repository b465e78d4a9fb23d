#include "scene_output.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/io/atomic_file.hpp"
#include "rigid/io/table.hpp"

namespace rigid::cli {

std::string summary_json(const std::string& scene_file, const scene::RunResult& result) {
  const scene::RunSummary& s = result.summary;
  nlohmann::ordered_json j;
  j["scene"] = scene_file;
  j["kind"] = s.kind;
  j["integrator"] = s.integrator;
  j["t_end"] = s.t_end;
  j["dt"] = s.dt;
  if (s.tolerance > 0) j["tolerance"] = s.tolerance;
  j["steps"] = s.steps;
  if (s.rhs_evaluations > 0) j["rhs_evaluations"] = s.rhs_evaluations;
  j["samples"] = s.samples;
  j["wall_time_s"] = s.wall_seconds;
  j["parameters"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : s.parameters) j["parameters"][name] = value;
  j["diagnostics"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : s.diagnostics) j["diagnostics"][name] = value;
  const io::Table& t = result.trajectory;
  j["columns"] = t.columns();
  j["final"] = nlohmann::ordered_json::object();
  if (t.rows() > 0) {
    for (std::size_t c = 0; c < t.columns().size(); ++c) j["final"][t.columns()[c]] = t(t.rows() - 1, c);
  }
  j["warnings"] = s.warnings;
  // nlohmann prints doubles in their shortest round-trip form
  return j.dump(2) + "\n";
}

std::vector<std::string> write_scene_outputs(const std::filesystem::path& dir, const std::string& scene_file,
                                             const scene::RunResult& result,
                                             const std::vector<std::string>& formats) {
  std::vector<std::string> written;
  auto wants = [&](const char* f) { return std::find(formats.begin(), formats.end(), f) != formats.end(); };
  if (wants("csv")) {
    io::write_csv(dir / "trajectory.csv", result.trajectory);
    written.push_back((dir / "trajectory.csv").string());
  }
  if (wants("npy")) {
    io::write_npy(dir / "trajectory.npy", result.trajectory);
    written.push_back((dir / "trajectory.npy").string());
  }
  if (wants("json")) {
    io::write_file_atomically(dir / "summary.json", summary_json(scene_file, result));
    written.push_back((dir / "summary.json").string());
  }
  return written;
}

namespace {

std::string diagnostics_lines(const scene::RunSummary& s) {
  std::string out;
  for (const auto& [name, value] : s.diagnostics) out += fmt::format("  {:<36} {:.6g}\n", name, value);
  return out;
}

std::string bodies_lines(const scene::Model& model) {
  std::string out;
  for (const auto& b : model.bodies()) {
    const Eigen::Vector3d& c = b.mass.com();
    const Eigen::Matrix3d& I = b.mass.inertia_com();
    out += fmt::format("  {:<12} mass {:.6g} kg, COM ({:.6g}, {:.6g}, {:.6g}) m, I_C diag ({:.6g}, "
                       "{:.6g}, {:.6g}) kg·m²{}\n",
                       b.name, b.mass.mass(), c.x(), c.y(), c.z(), I(0, 0), I(1, 1), I(2, 2),
                       b.free ? ", free" : "");
  }
  return out;
}

}  // namespace

std::string describe_run(const std::string& scene_file, const scene::Model& model,
                         const scene::RunResult& result) {
  const scene::RunSummary& s = result.summary;
  std::string out = fmt::format("{}: {} scene, {} bodies\n", scene_file,
                                s.kind == "coordinates" ? "generalized-coordinate" : "free-body",
                                model.bodies().size());
  out += fmt::format("{} to t = {:.6g} s: {} steps", s.integrator, s.t_end, s.steps);
  if (s.rhs_evaluations > 0) out += fmt::format(", {} right-hand sides", s.rhs_evaluations);
  out += fmt::format(", {} samples, {:.3g} s wall time\n", s.samples, s.wall_seconds);
  out += diagnostics_lines(s);
  return out;
}

std::string describe_model(const std::string& scene_file, const scene::Model& model,
                           const std::string& integrator) {
  std::string out = fmt::format("{}: {} scene\n", scene_file,
                                model.kind() == scene::SceneKind::kCoordinates ? "generalized-coordinate"
                                                                               : "free-body");
  if (!model.parameters().empty()) {
    out += "parameters:";
    for (const auto& p : model.parameters()) out += fmt::format(" {} = {:.10g}", p.name, p.value);
    out += "\n";
  }
  if (model.kind() == scene::SceneKind::kCoordinates) {
    const auto& sys = model.system();
    out += fmt::format("coordinates: {}\n", fmt::join(sys.coordinate_names(), ", "));
    if (sys.num_constraints() > 0) out += fmt::format("constraints: {}\n", fmt::join(sys.constraint_names(), ", "));
  }
  out += "bodies:\n" + bodies_lines(model);
  out += fmt::format("integrator: {}, t_end = {:.6g} s\n", model.integrator(integrator), model.t_end());
  return out;
}

}  // namespace rigid::cli
