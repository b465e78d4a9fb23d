#include "cmd_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/common/error.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/table.hpp"
#include "rigid/scene/model.hpp"
#include "scene_output.hpp"

namespace rigid::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::atomic<bool> g_interrupted{false};
extern "C" void on_interrupt(int /*signal*/) { g_interrupted = true; }

scene::Model load_model(const SceneOptions& opts) {
  scene::Scene s = scene::load_scene(opts.scene);
  scene::apply_overrides(s, opts.set);
  return scene::Model(s);
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::fprintf(stderr, "rigid: warning: %s\n", w.c_str());
}

// A one-line progress bar on standard error, redrawn at most ten times a second, shown only
// when standard error is a terminal and the run has taken more than half a second. Ctrl-C
// stops the run through it (nothing is written).
class Progress {
 public:
  Progress(double t_end, bool enabled) : t_end_(t_end), enabled_(enabled && isatty(STDERR_FILENO) != 0) {}
  ~Progress() { clear(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void operator()(double t) {
    if (g_interrupted) {
      clear();
      throw Error(fmt::format("interrupted at t = {:.6g} s of {:.6g} s; no output was written", t, t_end_));
    }
    if (!enabled_) return;
    const auto now = Clock::now();  // ~20 ns: small next to a step or a right-hand side
    if (now - start_ < std::chrono::milliseconds(500) || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const double f = std::clamp(t / t_end_, 0.0, 1.0);
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(f * kWidth);
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r[%s%s] %3.0f%%  t = %.4g / %.4g s  %.1f s elapsed ",
                 std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kWidth - filled), ' ').c_str(), 100 * f, t, t_end_,
                 elapsed);
    drawn_ = true;
  }

 private:
  void clear() {
    if (drawn_) std::fputs("\r\033[K", stderr);
    drawn_ = false;
  }
  double t_end_;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point start_ = Clock::now(), last_ = start_;
};

}  // namespace

void run_run(const RunOptions& opts) {
  const scene::Model model = load_model(opts.scene);
  print_warnings(model.warnings());
  const scene::Scene& s = model.scene();
  std::vector<std::string> formats = opts.formats.empty() ? s.output.formats : opts.formats;
  for (const auto& f : formats) {
    RIGID_REQUIRE(f == "csv" || f == "npy" || f == "json",
                  "--format '{}' is not an output format; expected csv, npy or json", f);
  }
  RIGID_REQUIRE(!formats.empty(), "no output format selected; expected csv, npy or json");
  const fs::path dir = !opts.output_dir.empty()         ? fs::path(opts.output_dir)
                       : !s.output.directory.empty()    ? s.output.directory
                                                        : fs::path("out");

  g_interrupted = false;
  const auto previous = std::signal(SIGINT, on_interrupt);
  scene::RunResult result;
  {
    Progress progress(model.t_end(), !opts.quiet);
    scene::RunOptions ro;
    ro.integrator = opts.scene.integrator;
    ro.progress = [&progress](double t) { progress(t); };
    try {
      result = model.run(ro);
    } catch (...) {
      std::signal(SIGINT, previous);
      throw;
    }
  }
  std::signal(SIGINT, previous);

  std::error_code ec;
  fs::create_directories(dir, ec);
  RIGID_REQUIRE(!ec && fs::is_directory(dir), "cannot create the output directory '{}': {}",
                dir.string(), ec ? ec.message() : "a file of that name exists");
  const std::vector<std::string> written = write_scene_outputs(dir, s.file.string(), result, formats);
  if (opts.quiet) return;
  fmt::print("{}", describe_run(s.file.string(), model, result));
  fmt::print("wrote {}\n", fmt::join(written, ", "));
}

void run_check(const SceneOptions& opts) {
  const scene::Model model = load_model(opts);
  print_warnings(model.warnings());
  scene::RunOptions ro;
  ro.integrator = opts.integrator;
  model.check(ro);
  fmt::print("{}", describe_model(opts.scene, model, opts.integrator));
  fmt::print("ok: {} is a valid scene\n", opts.scene);
}

void run_eom(const SceneOptions& opts, bool latex) {
  const scene::Model model = load_model(opts);
  print_warnings(model.warnings());
  fmt::print("{}", model.equations(latex));
}

}  // namespace rigid::cli
