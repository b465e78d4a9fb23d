// Build-time generator of the robot benchmark: the flat C++ export of a robot model file
// (`rigid eom MODEL --emit c++ --flat [--pin-free-root]`), through the library.
//   rigid_robot_codegen_gen OUT.hpp MODEL [pin]
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "rigid/io/atomic_file.hpp"
#include "rigid/io/robot_model.hpp"
#include "rigid/lagrange/export.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/robot_scene.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: rigid_robot_codegen_gen OUT.hpp MODEL [pin]\n");
    return 2;
  }
  try {
    rigid::io::RobotReadOptions o;
    o.pin_free_root = argc > 3 && std::string(argv[3]) == "pin";
    const std::string file = argv[2];
    const rigid::scene::Model model(
        rigid::scene::scene_from_robot(rigid::io::read_robot_model_file(file, o), file));
    rigid::lagrange::ExportOptions options;
    options.name = std::filesystem::path(argv[1]).stem().string();
    options.source = file;
    options.flat = true;
    rigid::io::write_file_atomically(argv[1], rigid::lagrange::emit_cpp(model.system(), options));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rigid_robot_codegen_gen: %s\n", e.what());
    return 1;
  }
  return 0;
}
