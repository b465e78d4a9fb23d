#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rigid/scene/model.hpp"

namespace rigid::cli {

/// The scene a subcommand works on, with its `--set` overrides (an override's error starts
/// with `--set: `); its warnings are printed to standard error as `rigid: warning: …`.
[[nodiscard]] scene::Model load_scene(const std::string& file, const std::vector<std::string>& set);

/// The human summary `rigid run` prints.
[[nodiscard]] std::string describe_run(const std::string& scene_file, const scene::Model& model,
                                       const scene::RunResult& result);

/// What `rigid check` prints about a valid scene.
[[nodiscard]] std::string describe_model(const std::string& scene_file, const scene::Model& model,
                                         const std::string& integrator);

}  // namespace rigid::cli
