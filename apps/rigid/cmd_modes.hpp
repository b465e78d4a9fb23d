#pragma once

#include <string>
#include <vector>

#include "model_flags.hpp"

namespace rigid::cli {

/// Options of `rigid modes SCENE`.
struct ModesOptions {
  std::string scene;              ///< the scene file (TOML)
  std::vector<std::string> set;   ///< name=value parameter overrides
  std::vector<std::string> at;    ///< name=value: coordinates held, rates of cyclic coordinates
  std::string output;             ///< JSON file to write (atomically); empty: none
  bool json = false;              ///< print the JSON document instead of the text
  ModelFlags model;               ///< how a robot model file is read
};

/// `rigid modes SCENE [--at name=value ...] [-o modes.json]`: finds (or takes) an equilibrium
/// or steady motion, linearises and prints the frequencies, mode shapes and stability.
void run_modes(const ModesOptions& opts);

}  // namespace rigid::cli
