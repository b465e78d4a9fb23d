#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rigid/scene/model.hpp"

namespace rigid::cli {

/// Writes the outputs of a run into `dir` (which exists): trajectory.csv, trajectory.npy
/// and summary.json as selected by `formats`. Each file is written atomically, so a reader
/// never sees a partial file. Returns the paths written.
std::vector<std::string> write_scene_outputs(const std::filesystem::path& dir,
                                             const std::string& scene_file,
                                             const scene::RunResult& result,
                                             const std::vector<std::string>& formats);

/// summary.json: scene, kind, integrator and its statistics, wall time, parameters,
/// diagnostics, the columns of the trajectory and the values of its last row.
[[nodiscard]] std::string summary_json(const std::string& scene_file, const scene::RunResult& result);

/// The human summary `rigid run` prints.
[[nodiscard]] std::string describe_run(const std::string& scene_file, const scene::Model& model,
                                       const scene::RunResult& result);

/// What `rigid check` prints about a valid scene.
[[nodiscard]] std::string describe_model(const std::string& scene_file, const scene::Model& model,
                                         const std::string& integrator);

}  // namespace rigid::cli
