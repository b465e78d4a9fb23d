// The page of a sweep (rigid sweep --report, rigid report SWEEP_DIR, rigid.sweep(report=)).
#include "rigid/report/sweep_page.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/report/report.hpp"
#include "detail/sweep_files.hpp"

namespace rigid::report {
namespace {
using detail::read_text;
using detail::base64;

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// Two values of a 1-D grid's axis are evenly spaced when their step is within this fraction of
// the axis' range of the first step: linspace's values are start + i (stop − start)/(n − 1),
// each rounded once (a relative error of a few 1e-16), so 1e-9 separates them from a sample's
// random gaps by many orders of magnitude.
constexpr double kEvenSpacing = 1e-9;



// "f64:BASE64": the doubles' little-endian bytes, whatever the machine's order (exact, NaN kept)
std::string f64(const std::vector<double>& values) {
  std::string bytes;
  bytes.reserve(8 * values.size());
  for (const double v : values) {
    const auto w = std::bit_cast<std::uint64_t>(v);
    for (int k = 0; k < 8; ++k) bytes.push_back(static_cast<char>((w >> (8 * k)) & 0xFF));
  }
  return "f64:" + base64(bytes);
}

std::string u32(const std::vector<std::uint32_t>& values) {
  std::string bytes;
  bytes.reserve(4 * values.size());
  for (const std::uint32_t w : values) {
    for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<char>((w >> (8 * k)) & 0xFF));
  }
  return "u32:" + base64(bytes);
}

// runs.csv (detail::read_runs_csv, the reader rigid plot uses) into the page's data
void read_runs_csv(const fs::path& file, SweepData& out) {
  detail::RunsCsv csv = detail::read_runs_csv(file);
  out.names = std::move(csv.names);
  out.columns = std::move(csv.columns);
  out.errors = std::move(csv.errors);
}

// "grid" or "sample" from the journal's description ("scene …; grid L=…; grid m=…"), or ""
std::string kind_of_description(const std::string& description) {
  if (description.find("; sample ") != std::string::npos) return "sample";
  if (description.find("; grid ") != std::string::npos) return "grid";
  return {};
}

// The grid's axes when the swept columns are one (the values of each in the order they first
// appear; every combination, the first axis varying slowest, as rigid sweep runs a grid), or
// nothing. One axis is a grid only when its values are evenly spaced (a sample's are not).
std::optional<std::vector<std::vector<double>>> grid_axes(const SweepData& s,
                                                          const std::vector<std::size_t>& cols,
                                                          std::size_t runs) {
  if (cols.empty() || runs == 0) return std::nullopt;
  std::vector<std::vector<double>> axes;
  std::size_t product = 1;
  for (const std::size_t c : cols) {
    std::vector<double> values;
    for (const double v : s.columns[c]) {
      if (!std::isfinite(v)) return std::nullopt;
      if (std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
    }
    product *= values.size();
    if (product > runs) return std::nullopt;
    axes.push_back(std::move(values));
  }
  if (product != runs) return std::nullopt;
  for (std::size_t i = 0; i < runs; ++i) {
    std::size_t rest = i;
    for (std::size_t k = axes.size(); k-- > 0;) {
      const std::size_t digit = rest % axes[k].size();
      rest /= axes[k].size();
      if (s.columns[cols[k]][i] != axes[k][digit]) return std::nullopt;
    }
  }
  if (const std::vector<double>& a = axes.front(); axes.size() == 1 && a.size() >= 3) {
    const double step = a[1] - a[0];
    const double range = std::abs(a.back() - a.front());
    for (std::size_t k = 2; k < a.size(); ++k) {
      if (std::abs(a[k] - a[k - 1] - step) > kEvenSpacing * range) return std::nullopt;
    }
  }
  return axes;
}

}  // namespace

bool is_sweep_directory(const fs::path& directory) {
  std::error_code ec;
  return fs::exists(directory / "runs.csv", ec);
}

SweepData read_sweep(const fs::path& directory) {
  const std::string dir = escaped(directory.string());
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    throw Error(fmt::format(
        "'{}' is not a directory; expected the directory of a sweep (rigid sweep -o DIR)", dir));
  }
  if (!is_sweep_directory(directory)) {
    throw Error(fmt::format(
        "'{}' holds no runs.csv; expected the directory of a sweep (rigid sweep -o DIR)", dir));
  }
  SweepData s;
  read_runs_csv(directory / "runs.csv", s);
  const fs::path summary_file = directory / "summary.json";
  s.summary_json = read_text(summary_file, "the summary.json that rigid sweep writes");
  const auto summary = json::parse(s.summary_json, nullptr, false);
  if (summary.is_discarded() || !summary.is_object() || !summary.contains("swept") ||
      !summary["swept"].is_array()) {
    throw Error(fmt::format(
        "'{}' names no swept value (\"swept\"); expected the summary.json that rigid sweep writes",
        escaped(summary_file.string())));
  }
  for (const auto& n : summary["swept"]) {
    if (n.is_string()) s.swept.push_back(n.get<std::string>());
  }
  s.units = detail::sweep_directory_units(directory);
  // the journal's first line: {"rigid_sweep":1,"sweep":"<description>",…}
  if (std::ifstream journal(directory / ".journal.jsonl"); journal) {
    std::string line;
    std::getline(journal, line);
    const auto head = json::parse(line, nullptr, false);
    if (!head.is_discarded() && head.is_object() && head.contains("sweep") &&
        head["sweep"].is_string()) {
      s.description = head["sweep"].get<std::string>();
    }
  }
  fs::path name = directory.filename();
  if (name.empty()) name = directory.parent_path().filename();
  s.title = escaped(name.string());
  return s;
}

std::string sweep_json(const SweepData& s) {
  RIGID_REQUIRE(s.names.size() == s.columns.size(), "a sweep's data have {} names and {} columns",
                s.names.size(), s.columns.size());
  const std::size_t runs = s.errors.size();
  for (std::size_t k = 0; k < s.columns.size(); ++k) {
    RIGID_REQUIRE(s.columns[k].size() == runs, "the sweep's column '{}' has {} values for {} runs",
                  s.names[k], s.columns[k].size(), runs);
  }
  json j;
  j["rigid_sweep_page"] = 1;
  j["title"] = s.title;
  j["description"] = escaped(s.description);
  j["runs"] = runs;
  j["swept"] = s.swept;

  // the swept columns, and whether they are a grid's
  std::vector<std::size_t> swept_cols;
  for (const std::string& n : s.swept) {
    const auto it = std::find(s.names.begin(), s.names.end(), n);
    if (it == s.names.end()) {
      throw Error(
          fmt::format("the sweep's swept name '{}' is not a column of its runs.csv", escaped(n)));
    }
    swept_cols.push_back(static_cast<std::size_t>(it - s.names.begin()));
  }
  const std::string stated = kind_of_description(s.description);
  const auto axes = stated == "sample" ? std::nullopt : grid_axes(s, swept_cols, runs);
  json layout;
  layout["kind"] = axes ? "grid" : "sample";
  if (axes) {
    json a = json::array();
    for (std::size_t k = 0; k < axes->size(); ++k)
      a.push_back({{"name", s.swept[k]}, {"values", (*axes)[k]}});
    layout["axes"] = a;
  }
  j["layout"] = layout;

  json columns = json::array();
  for (std::size_t k = 0; k < s.names.size(); ++k) {
    const auto u = s.units.find(s.names[k]);
    columns.push_back(
        {{"name", s.names[k]},
         {"unit", u == s.units.end() ? std::string() : u->second},
         {"swept", std::find(s.swept.begin(), s.swept.end(), s.names[k]) != s.swept.end()},
         {"values", f64(s.columns[k])}});
  }
  j["columns"] = columns;

  // each run's error as an index into the distinct messages (0: it succeeded; k: messages[k−1])
  json messages = json::array();
  std::map<std::string, std::uint32_t, std::less<>> index;
  std::vector<std::uint32_t> error(runs, 0);
  std::size_t failed = 0;
  for (std::size_t r = 0; r < runs; ++r) {
    if (s.errors[r].empty()) continue;
    ++failed;
    auto it = index.find(s.errors[r]);
    if (it == index.end()) {
      it = index.emplace(s.errors[r], static_cast<std::uint32_t>(messages.size() + 1)).first;
      messages.push_back(escaped(s.errors[r]));
    }
    error[r] = it->second;
  }
  j["failures"] = failed;
  j["messages"] = messages;
  j["error"] = u32(error);

  const auto summary =
      json::parse(s.summary_json.empty() ? std::string("{}") : s.summary_json, nullptr, false);
  const bool ok = !summary.is_discarded() && summary.is_object();
  j["statistics"] = ok && summary.contains("results") ? summary["results"] : json::object();
  j["failure_groups"] =
      ok && summary.contains("failure_groups") ? summary["failure_groups"] : json::array();
  return j.dump();
}

std::string sweep_page(const SweepData& sweep) {
  if (!available()) return assemble_page("", "");  // refuses before the work
  return assemble_page("sweep " + sweep.title, sweep_json(sweep));
}

}  // namespace rigid::report
