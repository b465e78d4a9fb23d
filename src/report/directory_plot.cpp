// The plot of a run's or a sweep's directory (rigid plot).
#include "rigid/report/directory_plot.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "rigid/common/edit_distance.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/io/run_schema.hpp"
#include "rigid/report/report.hpp"
#include "detail/sweep_files.hpp"

namespace rigid::report {
namespace {
using detail::read_text;
using detail::read_runs_csv;
using detail::RunsCsv;

namespace fs = std::filesystem;

constexpr std::size_t kListedColumns = 40;  // a refusal lists at most this many columns
constexpr std::size_t kCloseNames = 5;
constexpr std::size_t kLabelChars = 60;  // a y label of more names says how many instead

// a column's values, name and unit
struct Column {
  std::string name;
  std::string unit;
  std::vector<double> values;
};


// the names close to `word` (a few edits away, or containing it), closest first
std::vector<std::string> close_names(std::string_view word, const std::vector<std::string>& names) {
  std::vector<std::pair<std::size_t, std::string>> scored;
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  for (const std::string& n : names) {
    const std::size_t d = edit_distance(word, n);
    const bool contains = word.size() >= 2 && n.find(word) != std::string::npos;
    if (d <= limit || contains) scored.emplace_back(contains ? std::min(d, limit) : d, n);
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < scored.size() && i < kCloseNames; ++i)
    out.push_back(scored[i].second);
  return out;
}

// the refusal of a column `what` does not have: the close names, then its columns
[[noreturn]] void refuse_column(const std::string& option, const std::string& name,
                                const std::string& what, const std::vector<std::string>& names) {
  const std::vector<std::string> close = close_names(name, names);
  // "…; did you mean 'a', 'b'? Its columns are …" or "…; its columns are …"
  std::string hint = "; its";
  if (!close.empty()) hint = fmt::format("; did you mean '{}'? Its", fmt::join(close, "', '"));
  std::vector<std::string> listed(
      names.begin(),
      names.begin() + static_cast<std::ptrdiff_t>(std::min(names.size(), kListedColumns)));
  const std::string more = names.size() > kListedColumns
                               ? fmt::format(" and {} more", names.size() - kListedColumns)
                               : "";
  throw Error(fmt::format("{} '{}': {} has no such column{} columns are {}{}", option,
                          escaped(name), what, hint, fmt::join(listed, ", "), more));
}

std::string with_unit(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : fmt::format("{} ({})", name, unit);
}

// the y label: one column's name and unit; several with their common unit; or each with its own
std::string y_label(const std::vector<Column>& ys) {
  if (ys.size() == 1) return with_unit(ys[0].name, ys[0].unit);
  const bool same =
      std::all_of(ys.begin(), ys.end(), [&](const Column& c) { return c.unit == ys[0].unit; });
  std::vector<std::string> parts;
  for (const Column& c : ys) parts.push_back(same ? c.name : with_unit(c.name, c.unit));
  std::string names = fmt::format("{}", fmt::join(parts, ", "));
  if (names.size() > kLabelChars) {
    names = same ? fmt::format("{} columns", ys.size())
                 : fmt::format("{} columns (units in the legend)", ys.size());
  }
  return same ? with_unit(names, ys[0].unit) : names;
}

// "'col': K of N values are not finite …" for each column that has some
void note_non_finite(const Column& c, std::size_t of, std::string_view rows,
                     std::vector<std::string>& notes) {
  const auto bad = static_cast<std::size_t>(
      std::count_if(c.values.begin(), c.values.end(), [](double v) { return !std::isfinite(v); }));
  if (bad > 0) {
    notes.push_back(fmt::format("{}: {} of {} {} not finite (NaN or infinite), not drawn", c.name,
                                bad, of, rows));
  }
}

// ---- a run ----

Plot plot_run(const fs::path& dir, const PlotRequest& request) {
  const io::RunResult run = read_run(dir);
  const io::Table& t = run.trajectory;
  const std::string what = fmt::format("the run in '{}'", escaped(dir.string()));
  const auto column = [&](const std::string& option, const std::string& name) {
    const auto& names = t.columns();
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) refuse_column(option, name, what, names);
    Column c{name, "", {}};
    if (const io::Column* s = run.schema.find(name)) c.unit = s->unit;
    const auto k = static_cast<std::size_t>(it - names.begin());
    for (std::size_t r = 0; r < t.rows(); ++r) c.values.push_back(t(r, k));
    return c;
  };
  const Column x = column("--x", request.x.empty() ? std::string("t") : request.x);
  std::vector<Column> ys;
  for (const std::string& name : request.columns) ys.push_back(column("--column", name));

  Plot plot;
  plot.marks = PlotMarks::kLines;
  const std::string scene = run.summary.scene.empty()
                                ? std::string("a run")
                                : fs::path(run.summary.scene).filename().string();
  plot.title = fmt::format("{} ({}, {} samples)", escaped(scene), escaped(dir.string()), t.rows());
  plot.x_label = with_unit(x.name, x.unit);
  plot.y_label = y_label(ys);
  note_non_finite(x, t.rows(), "values are", plot.notes);
  for (const Column& y : ys) {
    note_non_finite(y, t.rows(), "values are", plot.notes);
    plot.series.push_back({with_unit(y.name, y.unit), x.values, y.values});
  }
  return plot;
}

// ---- a sweep ----

Plot plot_sweep(const fs::path& dir, const PlotRequest& request) {
  const fs::path summary_file = dir / "summary.json";
  const auto summary = nlohmann::json::parse(
      read_text(summary_file, "the summary.json that rigid sweep writes"), nullptr, false);
  std::vector<std::string> swept;
  if (!summary.is_discarded() && summary.is_object() && summary.contains("swept") &&
      summary["swept"].is_array()) {
    for (const auto& s : summary["swept"]) {
      if (s.is_string()) swept.push_back(s.get<std::string>());
    }
  }
  if (swept.empty()) {
    throw Error(
        fmt::format("'{}' names no swept value (\"swept\"); expected the summary.json that "
                    "rigid sweep writes",
                    escaped(summary_file.string())));
  }
  const RunsCsv runs = read_runs_csv(dir / "runs.csv");
  const std::map<std::string, std::string> units = detail::sweep_directory_units(dir);
  const std::string what = fmt::format("the sweep in '{}'", escaped(dir.string()));
  const auto column = [&](const std::string& option, const std::string& name) {
    const auto it = std::find(runs.names.begin(), runs.names.end(), name);
    if (it == runs.names.end()) refuse_column(option, name, what, runs.names);
    Column c{name, "", runs.columns[static_cast<std::size_t>(it - runs.names.begin())]};
    if (const auto u = units.find(name); u != units.end()) c.unit = u->second;
    return c;
  };
  Column x = column("--x", request.x.empty() ? swept.front() : request.x);
  std::vector<Column> ys;
  for (const std::string& name : request.columns) ys.push_back(column("--column", name));

  // the failed runs are left out (NaN), and counted
  const std::size_t total = runs.errors.size();
  std::size_t failed = 0;
  for (std::size_t r = 0; r < total; ++r) {
    if (runs.errors[r].empty()) continue;
    ++failed;
    x.values[r] = NAN;
    for (Column& y : ys) y.values[r] = NAN;
  }
  Plot plot;
  plot.marks = PlotMarks::kPoints;
  plot.title = fmt::format("sweep {} ({} runs)", escaped(dir.string()), total);
  plot.x_label = with_unit(x.name, x.unit);
  plot.y_label = y_label(ys);
  if (failed > 0) {
    plot.notes.push_back(fmt::format(
        "{} of {} runs failed (see runs.csv's error column), not shown", failed, total));
  }
  const std::size_t succeeded = total - failed;
  const auto note = [&](const Column& c) {
    std::size_t bad = 0;
    for (std::size_t r = 0; r < total; ++r) {
      if (runs.errors[r].empty() && !std::isfinite(c.values[r])) ++bad;
    }
    if (bad > 0) {
      plot.notes.push_back(fmt::format(
          "{}: {} of the {} runs that succeeded have no finite value (NaN: e.g. an event that did "
          "not happen), not shown",
          c.name, bad, succeeded));
    }
  };
  note(x);
  for (const Column& y : ys) {
    note(y);
    plot.series.push_back({with_unit(y.name, y.unit), x.values, y.values});
  }
  return plot;
}

bool has_finite_point(const Plot& plot) {
  for (const PlotSeries& s : plot.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) return true;
    }
  }
  return false;
}

}  // namespace

Plot plot_of_directory(const fs::path& directory, const PlotRequest& request) {
  RIGID_REQUIRE(!request.columns.empty(), "expected at least one column to plot");
  const std::string dir = escaped(directory.string());
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    throw Error(
        fmt::format("'{}' is not a directory; expected the directory of a run (rigid run -o "
                    "DIR) or of a sweep (rigid sweep -o DIR)",
                    dir));
  }
  Plot plot;
  if (fs::exists(directory / "runs.csv", ec)) {
    plot = plot_sweep(directory, request);
  } else if (fs::exists(directory / io::file_name(io::OutputFormat::kCsv), ec) ||
             fs::exists(directory / io::file_name(io::OutputFormat::kJson), ec)) {
    plot = plot_run(directory, request);
  } else if (fs::exists(directory / ".journal.jsonl", ec)) {
    throw Error(
        fmt::format("'{}' holds a sweep's journal but no runs.csv: a shard's directory (join "
                    "the shards with rigid sweep merge DIR... -o OUT and plot OUT) or a "
                    "sweep that has not finished (run its command again)",
                    dir));
  } else {
    throw Error(
        fmt::format("'{}' is neither a run's directory (trajectory.csv and summary.json, from "
                    "rigid run -o DIR) nor a sweep's (runs.csv and summary.json, from rigid "
                    "sweep -o DIR)",
                    dir));
  }
  if (!has_finite_point(plot)) {
    std::vector<std::string> names;
    for (const PlotSeries& s : plot.series) names.push_back(s.label);
    throw Error(
        fmt::format("'{}': {} against {} has no point where both are finite; nothing to plot", dir,
                    fmt::join(names, ", "), plot.x_label));
  }
  return plot;
}

}  // namespace rigid::report
