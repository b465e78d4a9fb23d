#pragma once

/// One self-contained HTML page of a run (docs/report.md): the run's data as JSON (schema
/// version 1: scene, parameters, integrator, diagnostics, equations, every body's inertia and
/// shape, meshes stored once, poses and plotted series decimated to at most `max_frames`
/// frames, numbers as base64 float32), and the page's script and style, which are bundled at
/// build time (web/, esbuild) and embedded in the library. The page loads nothing.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/io/run_output.hpp"
#include "rigid/scene/model.hpp"

namespace rigid::report {

/// The default and the bounds of the number of frames a report keeps.
inline constexpr std::size_t kDefaultMaxFrames = 2000;
inline constexpr std::size_t kMinMaxFrames = 2;
inline constexpr std::size_t kMaxMaxFrames = 1'000'000;

struct ReportOptions {
  /// Most frames (rows of the trajectory) kept: every k-th row, k the smallest stride that
  /// keeps at most this many, and the last row. Between kMinMaxFrames and kMaxMaxFrames.
  std::size_t max_frames = kDefaultMaxFrames;
};

/// True when the page's script and style were embedded at build time (CMake option
/// RIGID_REPORT); false in builds without node (the sanitizer and fuzz presets).
[[nodiscard]] bool available();

/// The rows a report keeps of `samples` rows: 0, k, 2k, … and the last, with k the smallest
/// stride that keeps at most `max_frames`; and the rule in words ("every 5th of 2001 samples
/// (at most 2000 frames)").
struct Decimation {
  std::size_t stride = 1;
  std::vector<std::size_t> rows;
  std::string rule;
};
[[nodiscard]] Decimation decimate(std::size_t samples, std::size_t max_frames);

/// The report's data (schema version 1) of a run of `model`, as JSON text (not yet escaped for
/// the page).
/// @throws rigid::Error if max_frames is out of bounds, the trajectory has no rows, lacks a
///   column the report needs (a body's pose, when [output] quantities left it out), or a
///   body's mesh file cannot be read.
[[nodiscard]] std::string report_json(const scene::Model& model, const io::RunResult& result,
                                      const ReportOptions& options = {});

/// The page: `<!doctype html>…<script type="application/json" id="rigid-report-data">JSON
/// </script><script>JS</script>…`, with `</` in the JSON written `<\/` (and `<!--` as
/// `\u003c!--`) so the data cannot end its element, and the title HTML-escaped.
/// @throws rigid::Error if the page's script is not in this build (available() is false).
[[nodiscard]] std::string assemble_page(std::string_view title, std::string_view json);

/// report_json wrapped by assemble_page: what `rigid run --report` writes as report.html.
[[nodiscard]] std::string report_page(const scene::Model& model, const io::RunResult& result,
                                      const ReportOptions& options = {});

/// The run an earlier `rigid run` wrote into `directory`: trajectory.csv (or trajectory.npy
/// with summary.json's column names) and summary.json's statistics, parameters, diagnostics.
/// @throws rigid::Error naming the missing or malformed file.
[[nodiscard]] io::RunResult read_run(const std::filesystem::path& directory);

/// The scene file an earlier run names in its summary.json ("scene"), resolved against the
/// working directory, then against `directory`'s parent.
/// @throws rigid::Error if summary.json names none or the file is gone.
[[nodiscard]] std::filesystem::path scene_of_run(const std::filesystem::path& directory);

}  // namespace rigid::report
