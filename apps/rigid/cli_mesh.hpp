#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
#include <memory>

#include "cmd_mesh.hpp"

inline void add_mesh_command(CLI::App& app) {
  auto* mesh = app.add_subcommand("mesh", "Inspect triangle meshes (STL, OBJ, PLY, OFF)");
  mesh->require_subcommand(1);
  auto opts = std::make_shared<rigid::cli::MeshCheckOptions>();
  auto* check = mesh->add_subcommand(
      "check", "Report defects of a mesh and whether its mass properties can be trusted "
               "(exit 1 when they cannot)");
  check->add_option("FILE", opts->file, "mesh file: .stl, .obj, .ply or .off")->required();
  check->add_option("--units", opts->units, "length unit of the file: m, cm, mm or in")
      ->default_str("m");
  check->add_option("--weld-tolerance", opts->weld_tolerance,
                    "merge vertices closer than this fraction of the bounding-box diagonal")
      ->default_str("1e-7");
  check->add_flag("--fill-holes", opts->fill_holes,
                  "close holes whose border is a simple loop (fan around its centre) before "
                  "judging the mesh");
  check->callback([opts] { rigid::cli::run_mesh_check(*opts); });
}
