#pragma once

#include <optional>
#include <string>
#include <vector>

namespace rigid::cli {

/// Options of `rigid inertia fix MODEL`.
struct InertiaFixOptions {
  std::string file;
  std::string output;                       ///< the fixed model (atomically); empty: table only
  std::optional<double> density;            ///< kg/m³ (URDF/SDF)
  bool keep_mass = false;
  std::string from = "collision";           ///< "collision" or "visual"
  std::vector<std::string> only;            ///< link/body names
  std::vector<std::string> package_paths;   ///< NAME=DIR
  std::string format = "text";              ///< table: "text" or "json"
};

/// `rigid inertia fix MODEL`: prints the table of old vs new inertials; writes the model with
/// the new inertials to `output` only when every link could be fixed (else throws, listing
/// every link that could not be, and writes nothing).
void run_inertia_fix(const InertiaFixOptions& opts);

}  // namespace rigid::cli
