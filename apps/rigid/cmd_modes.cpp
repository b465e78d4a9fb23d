#include "cmd_modes.hpp"

#include <cstdio>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/lagrange/linearize.hpp"
#include "rigid/scene/model.hpp"
#include "scene_output.hpp"
#include "rigid/scene/modes.hpp"

namespace rigid::cli {

void run_modes(const ModesOptions& opts) {
  const scene::Model model = load_scene(opts.scene, opts.set, opts.model);
  const lagrange::NormalModes modes = about_scene(opts.scene, [&] {
    try {
      return scene::normal_modes(model, opts.at);
    } catch (const Error& e) {
      const std::string what = e.what();
      if (what.starts_with("point '")) throw Error("--at: " + what);
      throw;
    }
  });
  const std::string json = scene::modes_json(modes, opts.scene);
  if (!opts.output.empty()) io::write_file_atomically(opts.output, json);
  if (opts.json) {
    fmt::print("{}", json);
  } else {
    fmt::print("{}: normal modes of {} coordinate{}\n{}", opts.scene, modes.coordinate_names.size(),
               modes.coordinate_names.size() == 1 ? "" : "s", lagrange::to_text(modes));
    if (!opts.output.empty()) fmt::print("wrote {}\n", opts.output);
  }
}

}  // namespace rigid::cli
