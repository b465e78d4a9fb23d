#pragma once

#include <string>

#include "cmd_run.hpp"

namespace rigid::cli {

/// Options of `rigid eom MODEL --regressor [--json]`.
struct RegressorOptions {
  bool enabled = false;  ///< --regressor
  bool json = false;     ///< --json: the JSON document instead of the text
};

/// What else `rigid eom` was given, so that a flag --regressor does not use is refused.
struct EomFlags {
  bool latex = false;
  std::string format;    ///< --format; "json" is --json, "text" the default
  std::string language;  ///< --emit
};

/// `rigid eom MODEL --regressor`: the base parameters of a robot model file's inverse dynamics
/// (robot::base_parameters), each as a combination of the named standard parameters with its
/// value for the model, the rank and the unidentifiable parameters; text or JSON.
/// @throws rigid::Error for a file that is not a robot model (a TOML scene), or a flag that
///   does not apply (--set, --integrator, --symbolic-inertia, --emit, --latex, --format other
///   than text or json).
void run_regressor(const SceneOptions& scene, const RegressorOptions& opts, const EomFlags& eom);

}  // namespace rigid::cli
