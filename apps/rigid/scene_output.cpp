#include "scene_output.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "cli_error.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/table.hpp"
#include "rigid/scene/density_field.hpp"

namespace rigid::cli {

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
    // a density field's numbers are a cubature's: its estimated errors, as `rigid inertia
    // --density-field` prints them
    if (b.density_field) out += fmt::format("    density field: {}\n", scene::describe(*b.density_field));
  }
  return out;
}

}  // namespace

std::string describe_run(const std::string& scene_file, const scene::Model& model,
                         const scene::RunResult& result) {
  const scene::RunSummary& s = result.summary;
  std::string out = fmt::format("{}: {} scene, {}\n", scene_file,
                                s.kind == rigid::io::RunKind::kCoordinates ? "generalized-coordinate" : "free-body",
                                counted(model.bodies().size(), "body", "bodies"));
  out += fmt::format("{} to t = {:.6g} s: {}", s.integrator, s.t_end, counted(s.steps, "step"));
  if (s.rhs_evaluations > 0) out += fmt::format(", {}", counted(s.rhs_evaluations, "right-hand side"));
  out += fmt::format(", {}, {:.3g} s wall time\n", counted(s.samples, "sample"), s.wall_seconds);
  out += diagnostics_lines(s);
  if (!s.metrics.empty()) out += "metrics:\n";
  for (const io::Metric& m : s.metrics) {
    const std::string unit = m.unit.empty() ? "" : " " + m.unit;
    // 10 significant digits: what a period or a crossing time is located to at tight tolerances
    out += std::isfinite(m.value) ? fmt::format("  {:<36} {:.10g}{}\n", m.name, m.value, unit)
                                  : fmt::format("  {:<36} nan ({})\n", m.name, m.note);
  }
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

scene::ModelOptions model_options(const ModelFlags& flags) {
  scene::ModelOptions o;
  if (flags.pin_free_root) o.pin_free_root = true;
  if (flags.inertia_from_geometry) o.inertia_from_geometry = true;
  if (flags.symbolic_inertia) o.symbolic_inertia = true;
  if (!flags.density.empty()) {
    const std::string& text = flags.density;
    double rho = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), rho);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(rho) || !(rho > 0)) {
      throw Error(fmt::format("--density {}: expected a finite number > 0 (kg/m³)", text));
    }
    o.density = rho;
  }
  return o;
}

scene::Model load_scene(const std::string& file, const std::vector<std::string>& set,
                        const ModelFlags& flags) {
  const scene::ModelOptions options = model_options(flags);
  scene::Model model = [&] {
    try {
      return scene::load_model(file, set, options);
    } catch (const Error& e) {
      // an override comes from --set: say so
      const std::string what = e.what();
      if (what.starts_with("override '")) throw Error("--set: " + what);
      throw;
    }
  }();
  for (const auto& w : model.warnings()) {
    std::fprintf(stderr, "rigid: warning: %s\n", word_for(Surface::kCli, w).c_str());
  }
  return model;
}

std::uint64_t unsigned_option(const std::string& text, const char* option, const char* what) {
  if (text.empty()) return 0;
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.find_first_not_of("0123456789") != std::string::npos || ec != std::errc() ||
      end != text.data() + text.size()) {
    throw UsageError(fmt::format("{} {}: {} must be a whole number from 0 to 18446744073709551615 "
                                 "(2^64 - 1){}",
                            option, text, what,
                            ec == std::errc::result_out_of_range ? ", and this is larger" : ""));
  }
  return value;
}

}  // namespace rigid::cli
