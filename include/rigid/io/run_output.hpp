#pragma once

/// The outputs of a simulation run, written by the library so that every front end (the
/// command line's `rigid run`, Python's Scene.run) writes the same files: trajectory.csv,
/// trajectory.npy and summary.json, as one set (a reader sees the old set or the new one).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigid/io/run_schema.hpp"
#include "rigid/io/table.hpp"

namespace rigid::io {

/// A scalar a run reports (a scene's [outputs] metric): name, value (NaN when the event did not
/// happen in the run, with `note` saying so), SI unit ("" when dimensionless).
struct Metric {
  std::string name;
  double value = 0;
  std::string unit;
  std::string note;
};

/// What a run measured, for summary.json and the printed summary. Units SI.
struct RunSummary {
  std::string scene;       ///< the scene file (as given), or empty
  RunKind kind = RunKind::kCoordinates;
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
  std::vector<Metric> metrics;  ///< the scene's [outputs] metrics, in file order
};

/// A run's trajectory (one row per output time, column `t` first), its summary, and its schema
/// (what each column is; empty columns when the run was not made by a model).
struct RunResult {
  Table trajectory{{"t"}};
  RunSummary summary;
  RunSchema schema;
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
/// diagnostics, metrics (`"metrics": {name: {"value": v, "unit": u}}`, plus `"note"` when the
/// value is NaN because its event did not happen; a NaN value is written as null), the columns
/// of the trajectory and the values of its last row, warnings, and the run's schema
/// (schema_json) when it has one.
/// @throws rigid::Error when the schema's columns are not the trajectory's.
/// Doubles in their shortest round-trip form.
[[nodiscard]] std::string summary_json(const RunResult& result);

/// The default cap on the memory of a run's trajectory (rows × columns × 8 bytes): 2 GiB.
inline constexpr std::uint64_t kDefaultMaxMemory = std::uint64_t{2} << 30;

/// A byte count for people: "512 B", "1.5 KiB", "2 GiB" (binary units, 3 significant digits).
[[nodiscard]] std::string format_bytes(std::uint64_t bytes);

/// A memory size: a whole number of bytes ("2147483648"), or a number with a unit: KiB MiB
/// GiB TiB (and K M G T, the same binary units) or kB MB GB TB (powers of 1000), with or
/// without a space ("2GiB", "1.5 G", "512MB").
/// @throws rigid::Error for anything else, zero, or a size beyond 2^63 bytes.
[[nodiscard]] std::uint64_t parse_memory_size(std::string_view text);

/// Checks, before a run, that a trajectory of `rows` × `columns` doubles fits in `max_memory`
/// bytes. @throws rigid::Error naming the rows, columns, bytes and the limit, with the
/// remedies (a larger output spacing, a shorter run, or `max_memory` raised).
void check_trajectory_memory(std::size_t rows, std::size_t columns, std::uint64_t max_memory);

/// Checks, before a run, that write_run can write into `directory`: it is an existing
/// directory (a symbolic link to one counts) or it can be created (its nearest existing
/// ancestor is a directory), and the directory that holds it is writable.
/// @throws rigid::Error naming the path and the problem (a file of that name, no permission).
void check_output_directory(const std::filesystem::path& directory);

/// A file written with a run's set that is not one of its formats (the report page,
/// "report.html"): its name in the run's directory (no separator) and its bytes.
struct ExtraFile {
  std::string name;
  std::string contents;
};

/// The report page's name in a run's directory; like the formats' files, an older run's copy
/// is not carried into a new set.
inline constexpr std::string_view kReportFileName = "report.html";

/// Writes the files of `formats` (and `extra`) into `directory` as one set: the files are written (and
/// flushed) into a new temporary directory beside it, `.NAME.rigid-tmp-PID-XXXXXXXX`, which then
/// takes the place of `directory` in one rename (an exchange when it exists). A reader sees the
/// whole old set or the whole new set, never a mix; an interruption leaves the old set. Other
/// files a user kept in `directory` stay (they are linked into the new set); files of an older
/// run that are not in this set are gone with it. Temporaries left by runs that were killed are
/// removed. trajectory.npy holds no column names, so summary.json (which lists them) is always
/// written with it. Returns the paths written (the extra files last).
/// @throws rigid::Error if `directory` cannot be written (check_output_directory), holds a
///   subdirectory of its own (a run's directory holds files only), or a file cannot be written
///   (the disk is full): then the old set is left as it was.
std::vector<std::filesystem::path> write_run(const std::filesystem::path& directory,
                                             const RunResult& result,
                                             std::span<const OutputFormat> formats,
                                             std::span<const ExtraFile> extra = {});

}  // namespace rigid::io
