#include "rigid/scene/export.hpp"

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/lagrange/export.hpp"

namespace rigid::scene {

std::string emit_code(const Model& model, std::string_view language, const std::string& name,
                      bool flat, std::size_t max_stack_bytes, const std::string& flat_namespace) {
  const lagrange::Language lang = lagrange::parse_language(language);
  if (flat && lang != lagrange::Language::kCpp) {
    throw Error("--flat is a layout of the C++ export (global functions without t); the Python "
                "module has one layout: drop --flat or use --emit c++");
  }
  const std::string file = model.scene().file.string();
  if (model.kind() != SceneKind::kCoordinates) {
    throw Error(fmt::format("{}: code export needs generalized coordinates ([[coordinates]] with "
                            "bodies whose pose depends on them); this scene has free bodies, "
                            "whose Euler equations are not exported",
                            file.empty() ? "scene" : file));
  }
  lagrange::ExportOptions options;
  options.name = !name.empty() ? name : model.scene().file.stem().string();
  if (options.name.empty()) options.name = "model";
  options.source = file;
  options.flat = flat;
  options.max_stack_bytes = max_stack_bytes;
  options.flat_namespace = flat_namespace;
  return lagrange::emit(model.system(), lang, options);
}

}  // namespace rigid::scene
