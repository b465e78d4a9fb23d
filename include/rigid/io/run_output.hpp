#pragma once

/// The outputs of a simulation run, written by the library so that every front end (the
/// command line's `rigid run`, Python's Scene.run) writes the same files: trajectory.csv,
/// trajectory.npy and summary.json.

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigid/io/table.hpp"

namespace rigid::io {

/// What a run measured, for summary.json and the printed summary. Units SI.
struct RunSummary {
  std::string scene;       ///< the scene file (as given), or empty
  std::string kind;        ///< "coordinates" or "free_bodies"
  std::string integrator;  ///< the method that ran
  double t_end = 0;        ///< s
  double dt = 0;           ///< largest fixed step or initial adaptive step (s)
  double tolerance = 0;    ///< adaptive methods' tolerance (0 when fixed-step)
  std::size_t steps = 0;
  std::size_t rhs_evaluations = 0;  ///< 0 for the free-body methods (they count steps)
  std::size_t samples = 0;          ///< rows of the trajectory
  double wall_seconds = 0;
  std::vector<std::pair<std::string, double>> parameters;
  /// Conservation and constraint diagnostics, name → value (see docs/scene-format.md).
  std::vector<std::pair<std::string, double>> diagnostics;
  std::vector<std::string> warnings;
};

/// A run's trajectory (one row per output time, column `t` first) and its summary.
struct RunResult {
  Table trajectory{{"t"}};
  RunSummary summary;
};

/// The files a run can write.
enum class OutputFormat { kCsv, kNpy, kJson };

/// "csv", "npy", "json".
[[nodiscard]] std::string_view to_string(OutputFormat format);
/// Inverse of to_string. @throws rigid::Error naming the formats (with "did you mean").
[[nodiscard]] OutputFormat parse_output_format(std::string_view name);
/// The file name of a format in a run's directory: trajectory.csv, trajectory.npy, summary.json.
[[nodiscard]] std::string_view file_name(OutputFormat format);

/// summary.json: scene, kind, integrator and its statistics, wall time, parameters,
/// diagnostics, the columns of the trajectory and the values of its last row, warnings.
/// Doubles in their shortest round-trip form.
[[nodiscard]] std::string summary_json(const RunResult& result);

/// Writes the files of `formats` into `directory` (created with its parents if missing), each
/// atomically (rigid::io::write_file_atomically): a reader sees a whole old or a whole new
/// file. The set is not atomic: a failure on the second file leaves the first. Returns the
/// paths written, in the order of `formats`.
/// @throws rigid::Error if the directory cannot be created or a file cannot be written.
std::vector<std::filesystem::path> write_run(const std::filesystem::path& directory,
                                             const RunResult& result,
                                             std::span<const OutputFormat> formats);

}  // namespace rigid::io
