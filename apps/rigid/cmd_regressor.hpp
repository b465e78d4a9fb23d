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
  std::string language;  ///< --emit: the regressor as code (c++ or python)
  std::string output;    ///< -o with --emit: the file (default: standard output)
  bool flat = false;     ///< --flat (the dynamics' layout; refused here)
};

/// `rigid eom MODEL --regressor`: the base parameters of a robot model file's inverse dynamics
/// (robot::base_parameters), each as a combination of the named standard parameters with its
/// value for the model, the rank and the unidentifiable parameters; text or JSON. With --emit,
/// the regressor and the base parameters as code instead (robot::emit_regressor), to -o FILE
/// or standard output; the C++ namespace is the output file's stem, else the model file's.
/// @throws rigid::Error for a file that is not a robot model (a TOML scene), or a flag that
///   does not apply (--set, --integrator, --symbolic-inertia, --latex, --format other than
///   text or json, --json or --flat with --emit).
void run_regressor(const SceneOptions& scene, const RegressorOptions& opts, const EomFlags& eom);

}  // namespace rigid::cli
