#pragma once

#include <string>

namespace rigid::cli {

/// How the scene commands (eom, modes, run, sweep, check) read a robot model file: the one given
/// as the scene, or the one its `[model]` section names (whose settings the flags override).
/// Refused for a TOML scene without `[model]`.
struct ModelFlags {
  bool pin_free_root = false;          ///< --pin-free-root
  bool inertia_from_geometry = false;  ///< --inertia-from-geometry
  std::string density;                 ///< --density KG_PER_M3 as given; empty: not given
  bool symbolic_inertia = false;       ///< --symbolic-inertia
};

}  // namespace rigid::cli
