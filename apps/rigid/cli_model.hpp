#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11), through the cli_<verb>.hpp
// of the commands that take a scene.
// --pin-free-root, --inertia-from-geometry, --density and --symbolic-inertia: how a robot model
// file is read.
#include "model_flags.hpp"

inline void add_model_options(CLI::App* cmd, rigid::cli::ModelFlags& o) {
  cmd->add_flag("--pin-free-root", o.pin_free_root,
                "robot model file (the scene, or its [model] file): weld a free joint on a body "
                "of the world where it stands instead of refusing it");
  cmd->add_flag("--inertia-from-geometry", o.inertia_from_geometry,
                "robot model file: every link's inertial from its geometry (MJCF: MuJoCo's "
                "compiler's rules; URDF: its collision geometry at --density)");
  cmd->add_option("--density", o.density,
                  "with --inertia-from-geometry: the density of a URDF's collision geometry "
                  "(kg/m³, default 1000)")
      ->type_name("KG_PER_M3");
  cmd->add_flag("--symbolic-inertia", o.symbolic_inertia,
                "robot model file: each link's mass, COM and inertia as the parameters m_<link>, "
                "com_<link>_x.. and I_<link>_xx.. (the file's values), kept as symbols in the "
                "equations and code, changed by --set and sweeps");
}
