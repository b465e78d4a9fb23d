#pragma once

#include <filesystem>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigid/common/error.hpp"
#include "model_flags.hpp"
#include "rigid/scene/model.hpp"

namespace rigid::cli {

/// The model options of the flags. @throws rigid::Error for a --density that is not a finite
/// number > 0.
[[nodiscard]] scene::ModelOptions model_options(const ModelFlags& flags);

/// The scene a subcommand works on, with its `--set` overrides (an override's error starts
/// with `--set: `) and its model flags; its warnings are printed to standard error as
/// `rigid: warning: …`.
[[nodiscard]] scene::Model load_scene(const std::string& file, const std::vector<std::string>& set,
                                      const ModelFlags& model = {});

/// Runs `work` on the scene in `file`; a rigid::Error it throws that does not already name a place
/// is rethrown with the scene file in front (`FILE: message`), as load_scene's errors are.
template <class Work>
decltype(auto) about_scene(const std::string& file, Work&& work) {
  try {
    return std::forward<Work>(work)();
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    const std::string_view what = e.what();
    if (what.starts_with(file) || what.starts_with("--")) throw;
    throw Error(file + ": " + std::string(what));
  }
}

/// An option's whole number as given: decimal digits only, 0 to 2^64 − 1 (CLI11 would wrap −1
/// to 2^64 − 1 and saturate 2^64 to it); empty: 0. `what` names it in the refusal.
/// @throws rigid::Error "OPTION TEXT: WHAT must be a whole number from 0 to …".
[[nodiscard]] std::uint64_t unsigned_option(const std::string& text, const char* option, const char* what);

/// The human summary `rigid run` prints.
[[nodiscard]] std::string describe_run(const std::string& scene_file, const scene::Model& model,
                                       const scene::RunResult& result);

/// What `rigid check` prints about a valid scene.
[[nodiscard]] std::string describe_model(const std::string& scene_file, const scene::Model& model,
                                         const std::string& integrator);

}  // namespace rigid::cli
