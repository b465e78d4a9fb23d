// Build-time generator of the scene tests: the exported C++ of each example scene given,
// written to DIR/<stem>.hpp (namespace <stem>), through rigid::scene::emit_code as
// `rigid eom SCENE --emit c++` does.
//   rigid_export_examples_gen DIR SCENE...
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "rigid/io/atomic_file.hpp"
#include "rigid/scene/export.hpp"
#include "rigid/scene/model.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: rigid_export_examples_gen DIR SCENE...\n");
    return 2;
  }
  try {
    for (int k = 2; k < argc; ++k) {
      const std::filesystem::path scene(argv[k]);
      const auto model = rigid::scene::load_model(scene);
      rigid::io::write_file_atomically(std::filesystem::path(argv[1]) / (scene.stem().string() + ".hpp"),
                                       rigid::scene::emit_code(model, "c++"));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rigid_export_examples_gen: %s\n", e.what());
    return 1;
  }
  return 0;
}
