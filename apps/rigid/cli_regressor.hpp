#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11), through cli_run.hpp.
// `rigid eom MODEL --regressor [--json | --emit LANG [-o FILE]]`: the flags of the base
// parameters of a robot model.
#include "cmd_regressor.hpp"

inline void add_regressor_options(CLI::App* eom, rigid::cli::RegressorOptions& o) {
  auto* regressor =
      eom->add_flag("--regressor", o.enabled,
                    "robot model file: print the base (identifiable) parameters of its inverse "
                    "dynamics tau = Y(q, q_dot, q_ddot) pi, each as a combination of the standard "
                    "parameters (docs/robots.md#regressor-and-base-parameters); with --emit c++|python, "
                    "Y, Y_b and beta = C pi as code");
  eom->add_flag("--json", o.json, "with --regressor: the JSON document instead of the text")
      ->needs(regressor);
}
