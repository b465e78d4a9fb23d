#pragma once

/// The page of a sweep (docs/report.md, "A sweep's page"): one self-contained HTML page of the
/// runs that `rigid sweep` (or rigid.sweep) made, with the same embedded script and style as a
/// run's page. Its data (JSON, "rigid_sweep_page": 1) hold every column of runs.csv as a
/// little-endian float64 array in base64 ("f64:…", exact: the page reads the same doubles), the
/// runs' errors as one index per run into a list of distinct messages, the swept names and
/// whether they form a grid (and its axes) or a sample, the units known, and summary.json's
/// statistics and failure groups.

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "rigid/io/run_schema.hpp"

namespace rigid::report {

/// The runs of a sweep, as runs.csv holds them.
struct SweepData {
  std::vector<std::string> names;            ///< the columns: run, the swept names, the results
  std::vector<std::vector<double>> columns;  ///< one per name, one value per run (NaN: none)
  std::vector<std::string> errors;           ///< one per run, "" when it succeeded
  std::vector<std::string> swept;            ///< the swept names (summary.json's "swept")
  std::string summary_json;                  ///< summary.json's text ("" when there is none)
  std::map<std::string, std::string> units;  ///< name → unit, for the names whose unit is known
  std::string description;                   ///< the sweep in words (its journal's), or ""
  std::string title;                         ///< the page's title: the directory or the scene
};

/// True when `directory` holds runs.csv (a sweep's directory).
[[nodiscard]] bool is_sweep_directory(const std::filesystem::path& directory);

/// The sweep `directory` holds: runs.csv, summary.json ("swept"; "units" {name: unit} when it has
/// them), its journal's description, and the units of a run it kept (--keep-trajectories) for
/// the names summary.json gives none.
/// @throws rigid::Error naming the missing or malformed file, or a directory that is neither a
///   sweep's nor a run's.
[[nodiscard]] SweepData read_sweep(const std::filesystem::path& directory);

/// The page's data (JSON text, not yet escaped for the page).
/// @throws rigid::Error if the columns and errors do not all have one value per run.
[[nodiscard]] std::string sweep_json(const SweepData& sweep);

/// sweep_json wrapped by assemble_page: what `rigid sweep --report` and `rigid report
/// SWEEP_DIR` write.
/// @throws rigid::Error if this build has no page (available() is false).
[[nodiscard]] std::string sweep_page(const SweepData& sweep);

}  // namespace rigid::report
