#include "cmd_plot.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <fmt/format.h>

#include "cli_error.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/report/directory_plot.hpp"
#include "rigid/report/svg_plot.hpp"

namespace rigid::cli {
namespace {

namespace fs = std::filesystem;

bool ends_in_svg(const std::string& name) {
  if (name.size() < 4) return false;
  std::string tail = name.substr(name.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return tail == ".svg";
}

}  // namespace

void run_plot(const PlotOptions& opts) {
  // the command line first, then the output's place, then the data: nothing is read for a plot
  // that cannot be written
  CLI_USAGE_REQUIRE(ends_in_svg(opts.output),
                    "-o {}: the plot is an SVG file; give a name ending in .svg",
                    escaped(opts.output));
  const fs::path out(opts.output);
  // what is at -o (a directory, FIFO, socket or device is refused; a link is written through),
  // checked as the writer checks it
  (void)io::check_output_file(out);

  const report::Plot plot =
      report::plot_of_directory(opts.directory, {.columns = opts.columns, .x = opts.x});
  io::write_file_atomically(out, report::svg_plot(plot));
  fmt::print("wrote {}\n", escaped(opts.output));
}

}  // namespace rigid::cli
