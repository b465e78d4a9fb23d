#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
#include <memory>

#include "cmd_demo.hpp"

inline void add_demo_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("demo", "Run a short tour of what rigid computes");
  auto no_report = std::make_shared<bool>(false);
  cmd->add_flag("--no-report", *no_report, "do not write rigid-demo/report.html");
  cmd->callback([no_report] { rigid::cli::run_demo(!*no_report); });
}
