#pragma once

#include <string>

#include "cmd_run.hpp"

namespace rigid::cli {

/// Options of `rigid eom SCENE --emit c++|python [-o FILE]`.
struct EmitOptions {
  std::string language;  ///< c++ or python; empty: print the equations instead
  std::string output;    ///< the file to write (atomically); empty: standard output
  bool flat = false;     ///< C++: the flat layout (lagrange::ExportOptions::flat)
  /// --max-stack-bytes as given (a whole number; empty: the default of
  /// lagrange::ExportOptions::max_stack_bytes)
  std::string max_stack_bytes{};
  /// --namespace: the flat layout's namespace (lagrange::ExportOptions::flat_namespace)
  std::string flat_namespace{};
};

/// "" for a known --emit language, else the reason (an unknown name, with a close match).
[[nodiscard]] std::string check_emit_language(const std::string& language);

/// `rigid eom SCENE --emit LANG [-o FILE]`: writes the scene's equations of motion as one
/// dependency-free C++ header or Python module (rigid::scene::emit_code).
void run_emit(const SceneOptions& scene, const EmitOptions& emit);

}  // namespace rigid::cli
