#include "rigid/io/run_output.hpp"

#include <array>
#include <system_error>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/io/atomic_file.hpp"

namespace rigid::io {
namespace {

constexpr std::array<std::pair<OutputFormat, std::string_view>, 3> kFormats{{
    {OutputFormat::kCsv, "csv"}, {OutputFormat::kNpy, "npy"}, {OutputFormat::kJson, "json"}}};

}  // namespace

std::string_view to_string(OutputFormat format) {
  for (const auto& [f, name] : kFormats) {
    if (f == format) return name;
  }
  return "?";
}

OutputFormat parse_output_format(std::string_view name) {
  for (const auto& [f, n] : kFormats) {
    if (n == name) return f;
  }
  const std::vector<std::string> names = {"csv", "npy", "json"};
  throw Error(fmt::format("unknown output format '{}'{}; expected csv, npy or json", name,
                          did_you_mean_hint(name, names)));
}

std::string_view file_name(OutputFormat format) {
  switch (format) {
    case OutputFormat::kCsv: return "trajectory.csv";
    case OutputFormat::kNpy: return "trajectory.npy";
    case OutputFormat::kJson: return "summary.json";
  }
  return "?";
}

std::string summary_json(const RunResult& result) {
  const RunSummary& s = result.summary;
  nlohmann::ordered_json j;
  j["scene"] = s.scene;
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
  const Table& t = result.trajectory;
  j["columns"] = t.columns();
  j["final"] = nlohmann::ordered_json::object();
  if (t.rows() > 0) {
    for (std::size_t c = 0; c < t.columns().size(); ++c) j["final"][t.columns()[c]] = t(t.rows() - 1, c);
  }
  j["warnings"] = s.warnings;
  // nlohmann prints doubles in their shortest round-trip form
  return j.dump(2) + "\n";
}

std::vector<std::filesystem::path> write_run(const std::filesystem::path& directory,
                                             const RunResult& result,
                                             std::span<const OutputFormat> formats) {
  RIGID_REQUIRE(!formats.empty(), "no output format selected; expected csv, npy or json");
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  RIGID_REQUIRE(!ec && std::filesystem::is_directory(directory),
                "cannot create the output directory '{}': {}", directory.string(),
                ec ? ec.message() : "a file of that name exists");
  std::vector<std::filesystem::path> written;
  for (const OutputFormat f : formats) {
    const std::filesystem::path path = directory / file_name(f);
    switch (f) {
      case OutputFormat::kCsv: write_csv(path, result.trajectory); break;
      case OutputFormat::kNpy: write_npy(path, result.trajectory); break;
      case OutputFormat::kJson: write_file_atomically(path, summary_json(result)); break;
    }
    written.push_back(path);
  }
  return written;
}

}  // namespace rigid::io
