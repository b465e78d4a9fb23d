// Build-time generator of the scene and robot tests: the exported C++ of each example scene
// given, written to DIR/<stem>.hpp (namespace <stem>), through rigid::scene::emit_code as
// `rigid eom SCENE --emit c++` does; with --flat, the flat layout to DIR/<stem>_flat.hpp
// (`rigid eom SCENE --emit c++ --flat`).
//   rigid_export_examples_gen [--flat] DIR SCENE...
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "rigid/io/atomic_file.hpp"
#include "rigid/scene/export.hpp"
#include "rigid/scene/model.hpp"

int main(int argc, char** argv) {
  const bool flat = argc > 1 && std::string(argv[1]) == "--flat";
  const int first = flat ? 2 : 1;
  if (argc < first + 2) {
    std::fprintf(stderr, "usage: rigid_export_examples_gen [--flat] DIR SCENE...\n");
    return 2;
  }
  try {
    for (int k = first + 1; k < argc; ++k) {
      const std::filesystem::path scene(argv[k]);
      const auto model = rigid::scene::load_model(scene);
      const std::string stem = scene.stem().string();
      rigid::io::write_file_atomically(
          std::filesystem::path(argv[first]) / (stem + (flat ? "_flat.hpp" : ".hpp")),
          rigid::scene::emit_code(model, "c++", flat ? stem : "", flat));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rigid_export_examples_gen: %s\n", e.what());
    return 1;
  }
  return 0;
}
