#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
// `rigid modes`: linearisation and normal modes of a scene of coordinates.
#include <memory>

#include "cli_model.hpp"
#include "cmd_modes.hpp"

inline void add_modes_command(CLI::App& app) {
  auto o = std::make_shared<rigid::cli::ModesOptions>();
  auto* cmd = app.add_subcommand(
      "modes", "Linearise a scene about an equilibrium or steady motion: frequencies, mode "
               "shapes, stability");
  cmd->add_option("SCENE", o->scene, "scene file (TOML; see docs/scene-format.md)")->required();
  cmd->add_option("--set", o->set, "override a parameter: name=value (repeatable)")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  cmd->add_option("--at", o->at,
                  "hold a coordinate at a value (theta1=0, an expression of the parameters) or "
                  "give a cyclic coordinate's rate (psi_dot=60) (repeatable); the other "
                  "coordinates are found from the scene's initial values")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  cmd->add_option("-o,--output", o->output, "also write the modes as JSON to this file");
  cmd->add_flag("--json", o->json, "print the JSON document instead of the text");
  add_model_options(cmd, o->model);
  cmd->callback([o] { rigid::cli::run_modes(*o); });
}
