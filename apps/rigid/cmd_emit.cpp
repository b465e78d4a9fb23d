#include "cmd_emit.hpp"

#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "cli_error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/lagrange/export.hpp"
#include "rigid/scene/export.hpp"
#include "rigid/scene/model.hpp"

namespace rigid::cli {

std::string check_emit_language(const std::string& language) {
  try {
    (void)lagrange::parse_language(language);
    return {};
  } catch (const Error& e) {
    return e.what();
  }
}

void run_emit(const SceneOptions& opts, const EmitOptions& emit) {
  scene::Model model = [&] {
    try {
      return scene::load_model(opts.scene, opts.set);
    } catch (const Error& e) {
      const std::string what = e.what();
      if (what.starts_with("parameter override")) throw Error("--set: " + what);
      throw;
    }
  }();
  for (const auto& w : model.warnings()) {
    std::fprintf(stderr, "rigid: warning: %s\n", word_for(Surface::kCli, w).c_str());
  }
  const std::filesystem::path out(emit.output);
  // the C++ namespace: the output file's stem, else the scene's
  const std::string code = scene::emit_code(model, emit.language, out.empty() ? "" : out.stem().string());
  if (out.empty()) {
    std::fwrite(code.data(), 1, code.size(), stdout);
    return;
  }
  io::write_file_atomically(out, code);
}

}  // namespace rigid::cli
