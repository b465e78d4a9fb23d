#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
#include "cmd_demo.hpp"

inline void add_demo_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("demo", "Run a short tour of what rigid computes");
  cmd->callback([] { rigid::cli::run_demo(); });
}
