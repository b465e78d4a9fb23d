#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
// `rigid plot DIR --column NAME... -o FILE.svg`: a plot without a browser.
#include <memory>

#include "cmd_plot.hpp"

inline void add_plot_command(CLI::App& app) {
  auto o = std::make_shared<rigid::cli::PlotOptions>();
  auto* cmd = app.add_subcommand(
      "plot",
      "Plot columns of a run's trajectory or of a sweep's runs.csv as an SVG file (no "
      "browser; see docs/report.md)");
  cmd->add_option("DIR", o->directory,
                  "a run's directory (rigid run -o DIR) or a sweep's (rigid sweep -o DIR)")
      ->required();
  cmd->add_option("--column", o->columns,
                  "a column to plot (repeatable: one line, or one set of points, each, with a "
                  "legend)")
      ->type_name("NAME")
      ->required()
      ->allow_extra_args(false);
  cmd->add_option("--x", o->x,
                  "the column along the x axis (default: t for a run, the first swept name for a "
                  "sweep)")
      ->type_name("NAME");
  cmd->add_option("-o,--output", o->output, "the SVG file to write")
      ->type_name("FILE.svg")
      ->required();
  cmd->callback([o] { rigid::cli::run_plot(*o); });
}
