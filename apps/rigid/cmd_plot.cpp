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
  std::error_code ec;
  const fs::file_status status = fs::status(out, ec);
  CLI_REQUIRE(!fs::is_directory(status), "-o {}: is a directory; expected the SVG file to write",
              escaped(opts.output));
  // the rename would replace a FIFO, socket or device with the file: refused instead
  CLI_REQUIRE(!fs::exists(status) || fs::is_regular_file(status),
              "-o {}: is not a regular file (a FIFO, socket or device); expected the SVG file to "
              "write (a new name, or a file to replace)",
              escaped(opts.output));

  const report::Plot plot =
      report::plot_of_directory(opts.directory, {.columns = opts.columns, .x = opts.x});
  io::write_file_atomically(out, report::svg_plot(plot));
  fmt::print("wrote {}\n", escaped(opts.output));
}

}  // namespace rigid::cli
