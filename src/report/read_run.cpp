// The outputs of an earlier run read back, for `rigid report DIR`.
#include <cmath>
#include <fstream>
#include <sstream>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "rigid/common/error.hpp"
#include "rigid/io/run_schema.hpp"
#include "rigid/io/table.hpp"
#include "rigid/report/report.hpp"

namespace rigid::report {
namespace {

namespace fs = std::filesystem;

nlohmann::ordered_json read_summary(const fs::path& directory) {
  const fs::path file = directory / io::file_name(io::OutputFormat::kJson);
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    throw Error(fmt::format("'{}' is not a directory; expected the output directory of a run (with "
                            "trajectory.csv and summary.json)",
                            directory.string()));
  }
  if (!fs::is_regular_file(file, ec)) {
    throw Error(fmt::format("'{}' is missing; a report needs the summary.json of the run (run with the "
                            "json format, the default)",
                            file.string()));
  }
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    throw Error(fmt::format("'{}' is not a run summary: it is not a JSON object", file.string()));
  }
  return j;
}

// summary[key] as T, or a refusal naming the key.
template <class T>
T field(const nlohmann::ordered_json& j, const char* key, const fs::path& file, T fallback,
        bool required) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) {
    if (!required) return fallback;
    throw Error(fmt::format("'{}' has no \"{}\"; expected the summary.json a run writes", file.string(), key));
  }
  const auto wrong_type = [&] {
    return Error(fmt::format("'{}': \"{}\" has the wrong type; expected the summary.json a run writes",
                             file.string(), key));
  };
  // a count is a whole number ≥ 0: get<std::size_t>() turns −1 into 2⁶⁴ − 1, and of 5e66 (a
  // float to nlohmann) it is undefined behaviour
  if constexpr (std::is_integral_v<T>) {
    if (!it->is_number_unsigned()) throw wrong_type();
  }
  try {
    return it->get<T>();
  } catch (const nlohmann::json::exception&) {
    throw wrong_type();
  }
}

}  // namespace

io::RunResult read_run(const fs::path& directory) {
  const nlohmann::ordered_json j = read_summary(directory);
  const fs::path summary = directory / io::file_name(io::OutputFormat::kJson);
  const fs::path csv = directory / io::file_name(io::OutputFormat::kCsv);
  std::error_code ec;
  if (!fs::is_regular_file(csv, ec)) {
    throw Error(fmt::format("'{}' is missing; a report needs the trajectory of the run as CSV (run with "
                            "the csv format, the default)",
                            csv.string()));
  }
  io::RunResult r;
  r.trajectory = io::read_csv(csv);
  io::RunSummary& s = r.summary;
  s.scene = field<std::string>(j, "scene", summary, "", true);
  const std::string kind = field<std::string>(j, "kind", summary, "", true);
  try {
    s.kind = io::parse_run_kind(kind);
  } catch (const Error& e) {
    throw Error(fmt::format("'{}': \"kind\": {}", summary.string(), e.what()));
  }
  s.integrator = field<std::string>(j, "integrator", summary, "", true);
  s.t_end = field<double>(j, "t_end", summary, 0.0, false);
  s.dt = field<double>(j, "dt", summary, 0.0, false);
  s.tolerance = field<double>(j, "tolerance", summary, 0.0, false);
  s.steps = field<std::size_t>(j, "steps", summary, 0, false);
  s.rhs_evaluations = field<std::size_t>(j, "rhs_evaluations", summary, 0, false);
  s.samples = field<std::size_t>(j, "samples", summary, r.trajectory.rows(), false);
  s.wall_seconds = field<double>(j, "wall_time_s", summary, 0.0, false);
  for (const char* group : {"parameters", "diagnostics"}) {
    const auto it = j.find(group);
    if (it == j.end() || !it->is_object()) continue;
    auto& out = std::string_view(group) == "parameters" ? s.parameters : s.diagnostics;
    for (const auto& [k, v] : it->items()) {
      if (v.is_number()) out.emplace_back(k, v.get<double>());
    }
  }
  s.warnings = field<std::vector<std::string>>(j, "warnings", summary, {}, false);
  // metrics: {name: {value (null: the event did not happen), unit, note}}
  if (const auto it = j.find("metrics"); it != j.end() && it->is_object()) {
    for (const auto& [k, v] : it->items()) {
      if (!v.is_object()) continue;
      io::Metric m;
      m.name = k;
      const auto value = v.find("value");
      m.value = value != v.end() && value->is_number() ? value->get<double>() : std::nan("");
      if (const auto u = v.find("unit"); u != v.end() && u->is_string()) m.unit = u->get<std::string>();
      if (const auto note = v.find("note"); note != v.end() && note->is_string()) m.note = note->get<std::string>();
      s.metrics.push_back(std::move(m));
    }
  }
  // a run written before runs carried their schema has none: the report takes the model's
  if (const auto it = j.find("schema"); it != j.end()) {
    r.schema = io::parse_schema_json(it->dump(), summary.string());
    if (r.schema.column_names() != r.trajectory.columns()) {
      throw Error(fmt::format(
          "'{}' and '{}' disagree: the schema names the columns {}, the trajectory has {}; "
          "expected the files of one run",
          summary.string(), csv.string(), fmt::join(r.schema.column_names(), ", "),
          fmt::join(r.trajectory.columns(), ", ")));
    }
  }
  return r;
}

fs::path scene_of_run(const fs::path& directory) {
  const nlohmann::ordered_json j = read_summary(directory);
  const fs::path summary = directory / io::file_name(io::OutputFormat::kJson);
  const std::string scene = field<std::string>(j, "scene", summary, "", false);
  if (scene.empty()) {
    throw Error(fmt::format("'{}' names no scene file; a report needs the scene (a run of a scene file "
                            "records it)",
                            summary.string()));
  }
  std::error_code ec;
  const fs::path given(scene);
  if (fs::is_regular_file(given, ec)) return given;
  const fs::path beside = directory.parent_path() / given;
  if (given.is_relative() && fs::is_regular_file(beside, ec)) return beside;
  throw Error(fmt::format("the scene '{}' that '{}' names is not found (from the working directory or "
                          "beside '{}'); read the run from the directory it was made in",
                          scene, summary.string(), directory.string()));
}

}  // namespace rigid::report
