#include "rigid/scene/export.hpp"

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/lagrange/export.hpp"

namespace rigid::scene {

std::string emit_code(const Model& model, std::string_view language, const std::string& name) {
  const lagrange::Language lang = lagrange::parse_language(language);
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
  return lagrange::emit(model.system(), lang, options);
}

}  // namespace rigid::scene
