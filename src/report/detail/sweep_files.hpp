#pragma once

// What the report's readers and writers share: a regular file's text, a sweep's runs.csv and
// the base64 of the pages' binary arrays. Used by the run page (report.cpp), rigid plot
// (directory_plot.cpp) and the sweep page (sweep_page.cpp).
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::report::detail {

/// The text of a regular file; a FIFO, device or directory is refused before it is opened.
/// @throws rigid::Error naming the file and `what` was expected.
[[nodiscard]] std::string read_text(const std::filesystem::path& file, std::string_view what);

/// A sweep's runs.csv: a header of names ending in `error`, then a row per run of numbers (empty:
/// NaN, a failed run's results) and the quoted error text (RFC 4180: a field in double quotes
/// may hold commas, line breaks and doubled quotes).
struct RunsCsv {
  std::vector<std::string> names;            ///< without `error`
  std::vector<std::vector<double>> columns;  ///< one per name
  std::vector<std::string> errors;           ///< one per run ('' where it succeeded)
};

/// @throws rigid::Error naming the file, the row and the column of what is not runs.csv.
[[nodiscard]] RunsCsv read_runs_csv(const std::filesystem::path& file);

/// The units of a sweep directory's columns: summary.json's "units" (run 0's schema, written by
/// the sweep), and for the names it does not list (a sweep of an older rigid), those of the
/// schema of the first run it kept (--keep-trajectories: runs/NNNNN/summary.json).
[[nodiscard]] std::map<std::string, std::string> sweep_directory_units(const std::filesystem::path& directory);

/// RFC 4648 base64 with padding. Written here because none of the project's libraries has a
/// public encoder (Boost's is in beast::detail, fmt and nlohmann have none).
[[nodiscard]] std::string base64(std::string_view bytes);

}  // namespace rigid::report::detail
