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
#include "scene_output.hpp"

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
  const std::size_t max_stack_bytes =
      emit.max_stack_bytes.empty()
          ? lagrange::ExportOptions::kDefaultMaxStackBytes
          : unsigned_option(emit.max_stack_bytes, "--max-stack-bytes", "the stack bound (bytes)");
  scene::Model model = load_scene(opts.scene, opts.set, opts.model);
  const std::filesystem::path out(emit.output);
  // the C++ namespace: the output file's stem, else the scene's
  const std::string code = about_scene(opts.scene, [&] {
    return scene::emit_code(model, emit.language, out.empty() ? "" : out.stem().string(), emit.flat,
                            max_stack_bytes, emit.flat_namespace);
  });
  if (out.empty()) {
    std::fwrite(code.data(), 1, code.size(), stdout);
    return;
  }
  io::write_file_atomically(out, code);
}

}  // namespace rigid::cli
