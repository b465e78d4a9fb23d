#include "cmd_regressor.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/robot_model.hpp"
#include "rigid/lagrange/export.hpp"
#include "rigid/robot/regressor.hpp"
#include "rigid/robot/regressor_export.hpp"
#include "rigid/scene/robot_scene.hpp"
#include "scene_output.hpp"

namespace rigid::cli {

namespace {

// The flags of `rigid eom` that mean nothing to the regressor: refused, naming them.
void refuse_other_flags(const SceneOptions& scene, const EomFlags& eom) {
  const auto refuse = [](const char* flag, const char* why) {
    throw Error(fmt::format("--regressor: {} {}", flag, why));
  };
  if (!eom.language.empty() && (eom.format == "json" || eom.format == "text")) {
    refuse(fmt::format("--format {}", eom.format).c_str(),
           "prints the base parameters; --emit writes them as code: give one of the two");
  }
  if (eom.flat) {
    refuse("--flat", "is the layout of the exported dynamics; the exported regressor has one layout");
  }
  if (eom.latex) refuse("--latex", "prints the equations; use --json for the regressor's document");
  if (!eom.format.empty() && eom.format != "text" && eom.format != "json") {
    refuse(fmt::format("--format {}", eom.format).c_str(),
           "is not a format of the base parameters (text or json)");
  }
  if (!scene.set.empty()) {
    refuse("--set",
           "changes a scene's values; the regressor takes the model file's (its "
           "parameters are the unknowns)");
  }
  if (!scene.integrator.empty()) refuse("--integrator", "applies to a simulation");
  if (scene.model.symbolic_inertia) {
    refuse("--symbolic-inertia",
           "is implied: the base parameters are combinations of the "
           "links' inertial parameters by name");
  }
}

// The robot model of `file`, refused when it is not one (a TOML scene).
io::RobotModel read_model(const SceneOptions& scene) {
  const std::string& file = scene.scene;
  std::ifstream in(file, std::ios::binary);
  if (in) {
    std::ostringstream text;
    text << in.rdbuf();
    if (!scene::looks_like_xml(text.str())) {
      throw Error(fmt::format(
          "--regressor: {} is not a robot model file (its first character is not '<'); the "
          "regressor takes a URDF, MJCF or SDF file (for a TOML scene with [model], give its "
          "model file)",
          file));
    }
  }
  // read_robot_model_file says why a file that did not open cannot be read
  const io::RobotReadOptions ro = scene::robot_read_options(model_options(scene.model), file);
  return io::read_robot_model_file(file, ro);
}

std::string text_document(const std::string& file, const robot::BaseParameters& b,
                          const robot::BaseParameterOptions& o) {
  const robot::StandardParameters& s = b.standard;
  std::string out = fmt::format(
      "{}: inverse dynamics tau = Y(q, q_dot, q_ddot) pi = Y_b(q, q_dot, q_ddot) beta\n"
      "standard parameters pi: {} (per link, in its frame about its origin: m, mx, my, mz, Ixx, "
      "Ixy, Ixz, Iyy, Iyz, Izz; per joint: armature Ia, damping fv, stiffness k)\n"
      "rank: {} ({} random states, seed {}; a column counts when its distance to the others "
      "is above {:g} of the largest: chosen ones are at >= {:.3g}, dependent ones at <= "
      "{:.3g})\n"
      "base parameters beta ({}):\n",
      file, s.values.size(), b.rank, b.samples, o.seed, b.rank_tolerance, b.smallest_independent,
      b.largest_dependent, b.rank);
  for (std::size_t i = 0; i < b.rank; ++i) {
    out += fmt::format("  {} = {} = {:.10g} {}\n", b.name(i), b.expression(i),
                       b.values(static_cast<Eigen::Index>(i)), s.units[b.independent[i]]);
  }
  out += fmt::format("unidentifiable ({}, no effect on tau):", b.unidentifiable.size());
  for (std::size_t u : b.unidentifiable) out += " " + s.names[u];
  out += "\n";
  return out;
}

std::string json_document(const std::string& file, const io::RobotModel& model,
                          const robot::BaseParameters& b, const robot::BaseParameterOptions& o) {
  const robot::StandardParameters& s = b.standard;
  nlohmann::ordered_json doc;
  doc["model"] = rigid::escaped(file);  // a file name of any bytes (\xff) as valid UTF-8
  doc["coordinates"] = model.coordinate_names();
  doc["standard_parameters"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < s.names.size(); ++i) {
    doc["standard_parameters"].push_back({{"name", s.names[i]},
                                          {"unit", s.units[i]},
                                          {"value", s.values(static_cast<Eigen::Index>(i))}});
  }
  doc["rank"] = b.rank;
  doc["samples"] = b.samples;
  doc["seed"] = o.seed;
  doc["rank_tolerance"] = b.rank_tolerance;
  doc["smallest_independent"] = b.smallest_independent;
  doc["largest_dependent"] = b.largest_dependent;
  doc["base_parameters"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < b.rank; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    nlohmann::ordered_json terms = nlohmann::ordered_json::array();
    // the independent parameter first, as in the expression
    terms.push_back({{"parameter", s.names[b.independent[i]]}, {"coefficient", 1.0}});
    for (Eigen::Index j = 0; j < b.combination.cols(); ++j) {
      const auto index = static_cast<std::size_t>(j);
      if (b.combination(row, j) == 0 || index == b.independent[i]) continue;
      terms.push_back({{"parameter", s.names[index]}, {"coefficient", b.combination(row, j)}});
    }
    doc["base_parameters"].push_back({{"name", b.name(i)},
                                      {"expression", b.expression(i)},
                                      {"value", b.values(row)},
                                      {"unit", s.units[b.independent[i]]},
                                      {"terms", terms}});
  }
  doc["dependent"] = nlohmann::ordered_json::array();
  for (std::size_t d : b.dependent) doc["dependent"].push_back(s.names[d]);
  doc["unidentifiable"] = nlohmann::ordered_json::array();
  for (std::size_t u : b.unidentifiable) doc["unidentifiable"].push_back(s.names[u]);
  // names read from the file are not checked for UTF-8: an invalid byte is replaced (U+FFFD)
  return doc.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

[[noreturn]] void refuse_json_with_emit() {
  throw Error("--regressor: --json prints the base parameters; --emit writes them as code: give "
              "one of the two");
}

}  // namespace

void run_regressor(const SceneOptions& scene, const RegressorOptions& opts, const EomFlags& eom) {
  refuse_other_flags(scene, eom);
  const io::RobotModel model = read_model(scene);
  const robot::BaseParameterOptions options;
  const robot::BaseParameters base = robot::base_parameters(model, options);
  if (!eom.language.empty()) {
    if (opts.json) refuse_json_with_emit();
    const std::filesystem::path out(eom.output);
    robot::RegressorExportOptions export_options;
    // the namespace: the output file's stem, else the model's, by the code export's naming rule
    std::string stem = (out.empty() ? std::filesystem::path(scene.scene) : out).stem().string();
    export_options.name = lagrange::export_namespace(stem.empty() ? "model" : stem);
    export_options.source = rigid::escaped(scene.scene);
    const std::string code = lagrange::parse_language(eom.language) == lagrange::Language::kCpp
                                 ? robot::emit_regressor_cpp(model, base, export_options)
                                 : robot::emit_regressor_python(model, base, export_options);
    if (out.empty()) {
      std::fwrite(code.data(), 1, code.size(), stdout);
    } else {
      io::write_file_atomically(out, code);
    }
    return;
  }
  const bool json = opts.json || eom.format == "json";
  fmt::print("{}", json ? json_document(scene.scene, model, base, options)
                        : text_document(scene.scene, base, options));
}

}  // namespace rigid::cli
