#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rigid/scene/model.hpp"

namespace rigid::cli {

/// The human summary `rigid run` prints.
[[nodiscard]] std::string describe_run(const std::string& scene_file, const scene::Model& model,
                                       const scene::RunResult& result);

/// What `rigid check` prints about a valid scene.
[[nodiscard]] std::string describe_model(const std::string& scene_file, const scene::Model& model,
                                         const std::string& integrator);

}  // namespace rigid::cli
