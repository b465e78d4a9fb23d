#pragma once

/// The plot of a directory that `rigid run -o DIR` or `rigid sweep -o DIR` wrote: columns of the
/// run's trajectory against time (or another column), or a sweep's result columns against a
/// swept value, labelled with the units of the run's typed schema (`rigid plot`).

#include <filesystem>
#include <string>
#include <vector>

#include "rigid/report/svg_plot.hpp"

namespace rigid::report {

struct PlotRequest {
  std::vector<std::string> columns;  ///< the y columns, one series each (at least one)
  /// The x column; empty: `t` for a run, the first swept name for a sweep.
  std::string x;
};

/// The plot of `directory`:
/// - a run's directory (trajectory.csv and summary.json, read by read_run): lines, x default
///   `t`, units from summary.json's "schema" (none for a run written before runs carried one);
///   a non-finite value breaks the line and is counted in a note;
/// - a sweep's directory (runs.csv and summary.json with "swept"): a circle per run, x default
///   the first swept name; the runs that failed (a non-empty `error`) and the non-finite results
///   are left out and counted in a note; units from summary.json's "units" (run 0's schema),
///   or the schema of a run the sweep kept (--keep-trajectories: runs/NNNNN/summary.json), else
///   none (runs.csv states none).
/// The y label is the column's name and unit, or the names with their common unit.
/// @throws rigid::Error if `directory` is neither, a file is malformed, a column is not in it
///   (naming the closest and listing its columns), or no column has a finite point.
[[nodiscard]] Plot plot_of_directory(const std::filesystem::path& directory,
                                     const PlotRequest& request);

}  // namespace rigid::report
