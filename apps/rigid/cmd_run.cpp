#include "cmd_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/scene/model.hpp"
#include "progress.hpp"
#include "scene_output.hpp"

namespace rigid::cli {
namespace {

namespace fs = std::filesystem;

// Set by Ctrl-C; the run polls it (integrate::MarchControl::cancel) and stops with
// rigid::Cancelled, so nothing is written.
std::atomic<bool> g_interrupted{false};
extern "C" void on_interrupt(int /*signal*/) { g_interrupted = true; }


// The run options of a scene command: the integrator and --max-memory.
scene::RunOptions run_options(const SceneOptions& opts) {
  scene::RunOptions ro;
  ro.integrator = opts.integrator;
  if (!opts.max_memory.empty()) {
    try {
      ro.max_memory = io::parse_memory_size(opts.max_memory);
    } catch (const Error& e) {
      throw Error(fmt::format("--max-memory: {}", e.what()));
    }
  }
  return ro;
}


// The progress bar of a run: the simulated time against t_end.
class Progress {
 public:
  Progress(double t_end, bool enabled) : t_end_(t_end), bar_(enabled) {}
  void operator()(double t) {
    bar_.update(t / t_end_, [&] { return fmt::format("t = {:.4g} / {:.4g} s", t, t_end_); });
  }
  void clear() { bar_.clear(); }

 private:
  double t_end_;
  ProgressBar bar_;
};

}  // namespace

void run_run(const RunOptions& opts) {
  const scene::Model model = load_scene(opts.scene.scene, opts.scene.set);
  const std::vector<io::OutputFormat> formats = [&] {
    try {
      return model.output_formats(opts.formats);
    } catch (const Error& e) {
      if (opts.formats.empty()) throw;
      throw Error(fmt::format("--format: {}", e.what()));
    }
  }();
  const fs::path dir = model.output_directory(opts.output_dir);
  // a run that cannot be written, or would not fit in memory, is refused before it runs
  io::check_output_directory(dir);
  scene::RunOptions ro = run_options(opts.scene);

  g_interrupted = false;
  const auto previous = std::signal(SIGINT, on_interrupt);
  io::RunResult result;
  {
    Progress progress(model.t_end(), !opts.quiet);
    ro.control.progress = [&progress](double t) { progress(t); };
    ro.control.cancel = &g_interrupted;
    try {
      result = model.run(ro);
    } catch (...) {
      progress.clear();
      std::signal(SIGINT, previous);
      throw;
    }
  }
  std::signal(SIGINT, previous);

  const std::vector<fs::path> written = io::write_run(dir, result, formats);
  if (opts.quiet) return;
  fmt::print("{}", describe_run(opts.scene.scene, model, result));
  std::vector<std::string> names;
  for (const auto& p : written) names.push_back(p.string());
  fmt::print("wrote {}\n", fmt::join(names, ", "));
}

void run_check(const SceneOptions& opts) {
  const scene::Model model = load_scene(opts.scene, opts.set);
  model.check(run_options(opts));
  fmt::print("{}", describe_model(opts.scene, model, opts.integrator));
  fmt::print("ok: {} is a valid scene\n", opts.scene);
}

void run_eom(const SceneOptions& opts, bool latex, const std::string& format) {
  // the format first: a bad --format is refused before the scene is derived
  lagrange::EquationFormat f = latex ? lagrange::EquationFormat::kLatex : lagrange::EquationFormat::kText;
  if (!format.empty()) {
    try {
      f = lagrange::parse_equation_format(format);
    } catch (const Error& e) {
      throw Error(fmt::format("--format: {}", e.what()));
    }
    if (latex && f != lagrange::EquationFormat::kLatex) {
      throw Error(fmt::format("--latex and --format {} ask for two formats; give one", format));
    }
  }
  const scene::Model model = load_scene(opts.scene, opts.set);
  fmt::print("{}", model.equations(f));
}

}  // namespace rigid::cli
