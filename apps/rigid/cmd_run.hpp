#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "model_flags.hpp"

namespace rigid::cli {

/// Options shared by `rigid run`, `rigid check` and `rigid eom`.
struct SceneOptions {
  std::string scene;               ///< the scene file (TOML)
  std::vector<std::string> set;    ///< name=value parameter overrides
  std::string integrator;          ///< overrides [simulation] integrator
  std::string max_memory;          ///< overrides [output] max_memory (bytes or "512MiB")
  ModelFlags model;                ///< how a robot model file is read
};

/// Options of `rigid run SCENE`.
struct RunOptions {
  SceneOptions scene;
  std::string output_dir;             ///< overrides [output] directory
  std::vector<std::string> formats;   ///< overrides [output] formats: csv, npy, json
  bool quiet = false;                 ///< no summary and no progress bar
  bool report = false;                ///< also write report.html (docs/report.md)
  std::string report_frames;          ///< most frames of the report, as given; empty: the default (2000)
};

/// Options of `rigid report DIR`.
struct ReportOptions {
  std::string directory;              ///< an earlier run's (or sweep's) output directory
  std::string output;                 ///< the page; empty: DIR/report.html
  std::string report_frames;          ///< most frames, as given; empty: the default (2000)
};

/// Refuses (rigid::cli::UsageError, exit status 2) an --integrator that no scene kind takes,
/// with the closest name; an empty name (none given) passes.
void require_known_integrator(const std::string& name);

/// `rigid report DIR`: the report page of an earlier run, from its trajectory.csv, its
/// summary.json and the scene file summary.json names; or, when DIR holds runs.csv, the page of
/// the sweep (report::read_sweep, report::sweep_page). A directory that is neither is refused.
void run_report(const ReportOptions& opts);

/// `rigid run SCENE`: simulates and writes trajectory.csv / trajectory.npy / summary.json
/// (each atomically, and only after the run succeeded), then prints a short summary.
void run_run(const RunOptions& opts);

/// `rigid check SCENE`: builds the model and runs the checks of a run without integrating.
void run_check(const SceneOptions& opts);

/// `rigid eom SCENE [--format text|latex|json] [--latex]`: prints the equations of motion
/// (`--latex` is `--format latex`; with another --format it is refused).
void run_eom(const SceneOptions& opts, bool latex, const std::string& format);

}  // namespace rigid::cli
