#include "cmd_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "cli_error.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/report/report.hpp"
#include "rigid/report/sweep_page.hpp"
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


// Every integrator a scene may name: those of the coordinate scenes (integrate::parse_method)
// and of the free-body scenes (body::free_body_method_from_name, and the closed form "exact").
// A name outside both is a usage error with a guess; one of them that the scene's kind does not
// take is refused by the scene (status 1), with the kind's own list.
const std::vector<std::string> kIntegratorNames = {
    "rk4",        "dopri5",     "implicit_midpoint", "stormer_verlet", "exact",        "splitting2",
    "splitting4", "splitting6", "midpoint",          "rkmk4",          "moser_veselov"};

}  // namespace

void require_known_integrator(const std::string& name) {
  if (name.empty() || std::find(kIntegratorNames.begin(), kIntegratorNames.end(), name) != kIntegratorNames.end()) {
    return;
  }
  CLI_USAGE_THROW("--integrator: unknown integrator '{}'{}; expected one of {} (coordinates: rk4, dopri5, "
                  "implicit_midpoint, stormer_verlet; free bodies: exact, rk4, splitting2, splitting4, "
                  "splitting6, midpoint, rkmk4, moser_veselov)",
                  name, did_you_mean_hint(name, kIntegratorNames), fmt::join(kIntegratorNames, ", "));
}

namespace {

// The run options of a scene command: the integrator and --max-memory.
scene::RunOptions run_options(const SceneOptions& opts) {
  scene::RunOptions ro;
  require_known_integrator(opts.integrator);
  ro.integrator = opts.integrator;
  if (!opts.max_memory.empty()) {
    try {
      ro.max_memory = io::parse_memory_size(opts.max_memory);
    } catch (const Error& e) {
      throw UsageError(fmt::format("--max-memory: {}", e.what()));
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

// The report's options from --report-frames as given (empty: the default), refused before any
// work when this build has no page.
report::ReportOptions report_options(const std::string& frames_text) {
  if (!report::available()) {
    throw Error("this rigid was built without the report page (CMake option RIGID_REPORT=OFF, a "
                "build without node): rebuild with the ci or release preset to write reports");
  }
  report::ReportOptions o;
  if (!frames_text.empty()) {
    const std::uint64_t frames = unsigned_option(frames_text, "--report-frames", "the number of frames");
    if (frames < report::kMinMaxFrames || frames > report::kMaxMaxFrames) {
      throw UsageError(fmt::format("--report-frames {}: expected a number of frames from {} to {}", frames,
                              report::kMinMaxFrames, report::kMaxMaxFrames));
    }
    o.max_frames = static_cast<std::size_t>(frames);
  }
  return o;
}

}  // namespace

void run_run(const RunOptions& opts) {
  // the options' own forms first: a misspelt one is refused before the scene is derived
  for (const std::string& f : opts.formats) {
    try {
      (void)io::parse_output_format(f);
    } catch (const Error& e) {
      throw UsageError(fmt::format("--format: {}", e.what()));
    }
  }
  if (!opts.report && !opts.report_frames.empty()) {
    throw UsageError("--report-frames sets the frames of the report: give --report with it");
  }
  (void)run_options(opts.scene);
  const scene::Model model = load_scene(opts.scene.scene, opts.scene.set, opts.scene.model);
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
  std::optional<report::ReportOptions> report_opts;
  if (opts.report) {
    report_opts = report_options(opts.report_frames);
  }

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

  std::vector<io::ExtraFile> extra;
  if (report_opts) extra.push_back({std::string(io::kReportFileName), report::report_page(model, result, *report_opts)});
  const std::vector<fs::path> written = io::write_run(dir, result, formats, extra);
  if (opts.quiet) return;
  fmt::print("{}", describe_run(opts.scene.scene, model, result));
  std::vector<std::string> names;
  for (const auto& p : written) names.push_back(p.string());
  fmt::print("wrote {}\n", fmt::join(names, ", "));
}

void run_report(const ReportOptions& opts) {
  const report::ReportOptions ro = report_options(opts.report_frames);
  const fs::path dir = opts.directory;
  const std::string shown = escaped(dir.string());
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw Error(fmt::format("'{}' is not a directory; expected the directory of a run (rigid run -o DIR) or of a "
                            "sweep (rigid sweep -o DIR)",
                            shown));
  }
  if (report::is_sweep_directory(dir)) {
    if (!opts.report_frames.empty()) {
      throw UsageError(fmt::format("--report-frames: '{}' is a sweep's directory, whose page shows every run "
                                   "(frames are a run's page's)",
                                   shown));
    }
    const fs::path out = opts.output.empty() ? dir / io::kReportFileName : fs::path(opts.output);
    io::write_file_atomically(out, report::sweep_page(report::read_sweep(dir)));
    fmt::print("wrote {}\n", out.string());
    return;
  }
  const bool run_files = fs::exists(dir / "summary.json", ec) ||
                         fs::exists(dir / io::file_name(io::OutputFormat::kCsv), ec) ||
                         fs::exists(dir / io::file_name(io::OutputFormat::kNpy), ec) ||
                         fs::exists(dir / io::file_name(io::OutputFormat::kJson), ec);
  // a directory with none of a run's files is named neither, with what read_run missed
  io::RunResult result;
  try {
    result = report::read_run(dir);
  } catch (const Error& e) {
    if (run_files) throw;
    throw Error(fmt::format(
        "'{}' is neither a run's directory (trajectory.csv and summary.json, from rigid run -o DIR) nor a "
        "sweep's (runs.csv and summary.json, from rigid sweep -o DIR){}: {}",
        shown,
        fs::exists(dir / ".journal.jsonl", ec)
            ? "; it holds a sweep's journal but no runs.csv (a shard's directory: join the shards with rigid "
              "sweep merge; or a sweep that has not finished: run its command again)"
            : "",
        e.what()));
  }
  const fs::path scene_file = report::scene_of_run(dir);
  // the run's own parameter values (a run made with --set): those of the scene's parameters
  scene::Scene sc = scene::load_scene(scene_file);
  std::vector<std::string> set;
  for (const auto& [name, value] : result.summary.parameters) {
    for (const scene::Parameter& p : sc.parameters) {
      if (p.name == name) set.push_back(fmt::format("{}={}", name, value));
    }
  }
  const scene::Model model = load_scene(scene_file.string(), set);
  const fs::path out = opts.output.empty() ? dir / io::kReportFileName : fs::path(opts.output);
  io::write_file_atomically(out, report::report_page(model, result, ro));
  fmt::print("wrote {}\n", out.string());
}

void run_check(const SceneOptions& opts) {
  (void)run_options(opts);
  const scene::Model model = load_scene(opts.scene, opts.set, opts.model);
  model.check(run_options(opts));
  fmt::print("{}", describe_model(opts.scene, model, opts.integrator));
  fmt::print("ok: {} is a valid scene\n", opts.scene);
}

void run_eom(const SceneOptions& opts, bool latex, const std::string& format) {
  require_known_integrator(opts.integrator);
  // the format first: a bad --format is refused before the scene is derived
  lagrange::EquationFormat f = latex ? lagrange::EquationFormat::kLatex : lagrange::EquationFormat::kText;
  if (!format.empty()) {
    try {
      f = lagrange::parse_equation_format(format);
    } catch (const Error& e) {
      throw UsageError(fmt::format("--format: {}{}", e.what(),
                                   did_you_mean_hint(format, {"text", "latex", "json"})));
    }
    if (latex && f != lagrange::EquationFormat::kLatex) {
      throw UsageError(fmt::format("--latex and --format {} ask for two formats; give one", format));
    }
  }
  const scene::Model model = load_scene(opts.scene, opts.set, opts.model);
  fmt::print("{}", model.equations(f));
}

}  // namespace rigid::cli
