#include "cmd_inertia_fix.hpp"

#include <cstdio>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/inertial_fix.hpp"

namespace rigid::cli {

void run_inertia_fix(const InertiaFixOptions& opts) {
  io::InertialFixOptions options;
  options.density = opts.density;
  options.keep_mass = opts.keep_mass;
  RIGID_REQUIRE(opts.from == "collision" || opts.from == "visual",
                "--from must be collision or visual, got '{}'", opts.from);
  options.from = opts.from == "visual" ? io::GeometrySource::kVisual : io::GeometrySource::kCollision;
  options.only = opts.only;
  for (const auto& p : opts.package_paths) {
    const auto eq = p.find('=');
    RIGID_REQUIRE(eq != std::string::npos && eq > 0 && eq + 1 < p.size(),
                  "--package-path expects NAME=DIR, got '{}'", p);
    options.package_paths.emplace_back(p.substr(0, eq), p.substr(eq + 1));
  }
  RIGID_REQUIRE(opts.format == "text" || opts.format == "json",
                "--format must be text or json, got '{}'", opts.format);

  const io::InertialFixResult result = io::fix_inertials_file(opts.file, options);
  const std::string table =
      opts.format == "json" ? io::fix_table_json(result) : io::fix_table_text(result);
  std::fputs(word_for(Surface::kCli, table).c_str(), stdout);
  std::fflush(stdout);
  if (!result.ok()) {
    const auto errors = result.errors();
    RIGID_THROW("{} problem{} left inertials unfixed; nothing was written:\n  {}", errors.size(),
                errors.size() == 1 ? "" : "s", fmt::join(errors, "\n  "));
  }
  if (!opts.output.empty()) io::write_file_atomically(opts.output, result.text);
}

}  // namespace rigid::cli
