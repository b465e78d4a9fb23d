#pragma once

#include <string>
#include <vector>

namespace rigid::cli {

/// Options of `rigid plot DIR --column NAME... [--x NAME] -o FILE.svg`.
struct PlotOptions {
  std::string directory;             ///< a run's or a sweep's directory
  std::vector<std::string> columns;  ///< the y columns (repeatable)
  std::string x;                     ///< the x column; empty: t (a run), the first swept name
  std::string output;                ///< the SVG file to write (atomically)
};

/// `rigid plot DIR --column NAME... -o FILE.svg`: the columns of a run's trajectory or of a
/// sweep's runs.csv as one SVG (report::plot_of_directory, report::svg_plot), written
/// atomically.
/// @throws UsageError for an -o that does not end in .svg; rigid::Error for an -o that is an
///   existing directory or not a regular file (a FIFO, a device), and whatever
///   plot_of_directory refuses.
void run_plot(const PlotOptions& opts);

}  // namespace rigid::cli
