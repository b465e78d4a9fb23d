#include "cmd_inertia_fix.hpp"

#include <cstdio>

#include <fmt/format.h>

#include "cli_error.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/inertial_fix.hpp"

namespace rigid::cli {

void run_inertia_fix(const InertiaFixOptions& opts) {
  io::InertialFixOptions options;
  options.density = opts.density;
  options.keep_mass = opts.keep_mass;
  CLI_USAGE_REQUIRE(opts.from == "collision" || opts.from == "visual",
                    "--from must be collision or visual, got '{}'{}", opts.from,
                    did_you_mean_hint(opts.from, {"collision", "visual"}));
  options.from = opts.from == "visual" ? io::GeometrySource::kVisual : io::GeometrySource::kCollision;
  options.only = opts.only;
  CLI_USAGE_REQUIRE(opts.format == "text" || opts.format == "json",
                    "--format must be text or json, got '{}'{}", opts.format,
                    did_you_mean_hint(opts.format, {"text", "json"}));
  for (const auto& p : opts.package_paths) {
    try {
      options.package_paths.push_back(io::parse_package_path(p));
    } catch (const Error& e) {
      throw UsageError(fmt::format("--package-path: {}", e.what()));
    }
  }

  const io::InertialFixResult result = io::fix_inertials_file(opts.file, options);
  const std::string table =
      opts.format == "json" ? io::fix_table_json(result) : io::fix_table_text(result);
  std::fputs(word_for(Surface::kCli, table).c_str(), stdout);
  std::fflush(stdout);
  result.require_ok();
  if (!opts.output.empty()) io::write_file_atomically(opts.output, result.text);
}

}  // namespace rigid::cli
