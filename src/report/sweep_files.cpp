// What the report's readers and writers share (detail/sweep_files.hpp).
#include "detail/sweep_files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <system_error>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/io/run_schema.hpp"
#include "rigid/scene/sweep.hpp"

namespace rigid::report::detail {

namespace fs = std::filesystem;

std::string read_text(const fs::path& file, std::string_view what) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    throw Error(
        fmt::format("'{}' is not a regular file; expected {}", escaped(file.string()), what));
  }
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in.good() && !in.eof()) {
    throw Error(fmt::format("'{}' cannot be read; expected {}", escaped(file.string()), what));
  }
  return text.str();
}

RunsCsv read_runs_csv(const fs::path& file) {
  const std::string text = read_text(file, "the runs.csv that rigid sweep writes");
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"' && field.empty()) {
      quoted = true;
    } else if (c == ',') {
      row.push_back(std::move(field));
      field.clear();
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      row.push_back(std::move(field));
      field.clear();
      rows.push_back(std::move(row));
      row.clear();
    } else {
      field += c;
    }
  }
  if (quoted) {
    throw Error(
        fmt::format("'{}' ends inside a quoted field; expected the runs.csv that rigid sweep "
                    "writes (cut short?)",
                    escaped(file.string())));
  }
  if (!field.empty() || !row.empty()) {
    row.push_back(std::move(field));
    rows.push_back(std::move(row));
  }
  if (rows.empty() || rows[0].size() < 2 || rows[0].back() != "error") {
    throw Error(
        fmt::format("'{}' has no header line ending in 'error'; expected the runs.csv that "
                    "rigid sweep writes",
                    escaped(file.string())));
  }
  RunsCsv out;
  out.names = rows[0];
  out.names.pop_back();  // `error`
  out.columns.resize(out.names.size());
  for (std::size_t r = 1; r < rows.size(); ++r) {
    if (rows[r].size() == 1 && rows[r][0].empty()) continue;  // a blank line
    if (rows[r].size() != rows[0].size()) {
      throw Error(fmt::format("'{}': run row {} has {} fields, expected {} (one per column)",
                              escaped(file.string()), r, rows[r].size(), rows[0].size()));
    }
    for (std::size_t k = 0; k < out.names.size(); ++k) {
      const std::string& f = rows[r][k];
      double v = NAN;  // a failed run's results may be empty
      if (!f.empty()) {
        const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
        if (ec != std::errc() || end != f.data() + f.size()) {
          throw Error(fmt::format("'{}': run row {}, column '{}': '{}' is not a number",
                                  escaped(file.string()), r, out.names[k], escaped(f)));
        }
      }
      out.columns[k].push_back(v);
    }
    out.errors.push_back(rows[r].back());
  }
  return out;
}

std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  auto byte = [&](std::size_t k) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[k]));
  };
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    for (int s = 18; s >= 0; s -= 6) out.push_back(kAlphabet[(v >> s) & 63]);
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    const std::uint32_t v = byte(i) << 16 | (rest == 2 ? byte(i + 1) << 8 : 0);
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(rest == 2 ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

std::map<std::string, std::string> sweep_directory_units(const fs::path& directory) {
  std::map<std::string, std::string> units;
  std::error_code ec;
  const fs::path runs = directory / "runs";
  if (fs::is_directory(runs, ec)) {
    std::vector<fs::path> kept;
    for (fs::directory_iterator it(runs, ec), end; !ec && it != end; it.increment(ec)) {
      if (fs::is_regular_file(it->path() / "summary.json", ec)) kept.push_back(it->path());
    }
    if (!kept.empty()) {
      const fs::path file = *std::min_element(kept.begin(), kept.end()) / "summary.json";
      const auto j = nlohmann::json::parse(read_text(file, "a run's summary.json"), nullptr, false);
      if (!j.is_discarded() && j.is_object() && j.contains("schema")) {
        units = scene::sweep_units(io::parse_schema_json(j["schema"].dump(), file.string()));
      }
    }
  }
  const fs::path summary_file = directory / "summary.json";
  if (!fs::is_regular_file(summary_file, ec)) return units;
  const auto summary = nlohmann::json::parse(
      read_text(summary_file, "the summary.json that rigid sweep writes"), nullptr, false);
  if (!summary.is_discarded() && summary.is_object() && summary.contains("units") &&
      summary["units"].is_object()) {
    for (const auto& [name, unit] : summary["units"].items()) {
      if (unit.is_string()) units[name] = unit.get<std::string>();
    }
  }
  return units;
}

}  // namespace rigid::report::detail
