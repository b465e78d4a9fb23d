#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
// `rigid run`, `rigid check` and `rigid eom`: the commands that take a scene file.
#include <memory>

#include "cli_model.hpp"
#include "cmd_emit.hpp"
#include "cmd_run.hpp"
#include "cli_regressor.hpp"

inline void add_scene_options(CLI::App* cmd, rigid::cli::SceneOptions& o) {
  cmd->add_option("SCENE", o.scene, "scene file (TOML; see docs/scene-format.md)")->required();
  cmd->add_option("--set", o.set,
                  "override a value of the scene (repeatable): a parameter (m=2), a setting "
                  "(simulation.t_end=20, simulation.tolerance=1e-12), an initial condition "
                  "(theta.initial=0.2, theta.velocity=0, racket.omega=[0.01,1,0.01])")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  cmd->add_option("--integrator", o.integrator,
                  "coordinates: rk4, dopri5, implicit_midpoint, stormer_verlet; free bodies: rk4, "
                  "exact (closed form, no pivot), splitting2, splitting4, splitting6, midpoint, and "
                  "the further methods of docs/body.md");
  add_model_options(cmd, o.model);
}

inline void add_max_memory_option(CLI::App* cmd, rigid::cli::SceneOptions& o) {
  cmd->add_option("--max-memory", o.max_memory,
                  "most memory the trajectory may take (rows x columns x 8 bytes), checked before "
                  "the run: bytes or 512MiB, 4GiB (default: the scene's [output] max_memory, else "
                  "2GiB)")
      ->type_name("SIZE");
}

inline void add_run_command(CLI::App& app) {
  auto run = std::make_shared<rigid::cli::RunOptions>();
  auto* cmd = app.add_subcommand("run", "Simulate a scene and write its trajectory and summary");
  add_scene_options(cmd, run->scene);
  add_max_memory_option(cmd, run->scene);
  cmd->add_option("-o,--output", run->output_dir,
                  "output directory, replaced as a whole by the run's files (default: the scene's "
                  "[output] directory, else out/<scene file stem>)");
  cmd->add_option("--format", run->formats, "output files: csv, npy, json (repeatable; default: "
                  "the scene's [output] formats, else csv and json)");
  cmd->add_flag("-q,--quiet", run->quiet, "print nothing on success (no summary, no progress bar)");
  cmd->add_flag("--report", run->report, "also write report.html: one self-contained page with the "
                "3D motion, plots and equations (docs/report.md)");
  cmd->add_option("--report-frames", run->report_frames, "most frames the report keeps (every k-th "
                  "row and the last; default 2000)")
      ->type_name("N");
  cmd->callback([run] { rigid::cli::run_run(*run); });

  auto report = std::make_shared<rigid::cli::ReportOptions>();
  auto* r = app.add_subcommand("report", "Write the report page of an earlier run from its output "
                                         "directory (trajectory.csv, summary.json and the scene file), "
                                         "or the page of a sweep from its directory (runs.csv, summary.json)");
  r->add_option("DIR", report->directory, "the output directory of a `rigid run` or a `rigid sweep`")->required();
  r->add_option("-o,--output", report->output, "the page to write (default: DIR/report.html)")
      ->type_name("FILE");
  r->add_option("--report-frames", report->report_frames, "most frames a run's report keeps (default 2000)")
      ->type_name("N");
  r->callback([report] { rigid::cli::run_report(*report); });

  auto check = std::make_shared<rigid::cli::SceneOptions>();
  auto* c = app.add_subcommand("check", "Validate a scene (file, expressions, bodies, initial "
                                        "conditions) without running it");
  add_scene_options(c, *check);
  add_max_memory_option(c, *check);
  c->callback([check] { rigid::cli::run_check(*check); });

  auto eom = std::make_shared<rigid::cli::SceneOptions>();
  auto latex = std::make_shared<bool>(false);
  auto format = std::make_shared<std::string>();
  auto* e = app.add_subcommand("eom", "Print a scene's equations of motion");
  add_scene_options(e, *eom);
  e->add_option("--format", *format, "text (default), latex (align* environments) or json (every "
                                     "quantity as text and LaTeX, M as a nested array)")
      ->type_name("FORMAT");
  e->add_flag("--latex", *latex, "the same as --format latex");
  auto emit = std::make_shared<rigid::cli::EmitOptions>();
  auto* emit_opt = e->add_option("--emit", emit->language,
                                 "write the equations (M, f, G, gamma) as code instead: c++ (one "
                                 "header, <cmath> only) or python (one module, math only)")
                       ->type_name("LANG")
                       ->check(CLI::Validator(rigid::cli::check_emit_language, "c++|python", "language"));
  e->add_option("-o,--output", emit->output, "with --emit: the file to write (default: standard output)")
      ->needs(emit_opt)
      ->type_name("FILE");
  auto* flat_opt = e->add_flag("--flat", emit->flat,
                               "with --emit c++: the dynamics as robot code calls them, at global "
                               "scope and without t: mass_matrix, inverse_dynamics, "
                               "forward_dynamics (factored along the tree) and their derivatives")
                       ->needs(emit_opt);
  e->add_option("--max-stack-bytes", emit->max_stack_bytes,
                "with --flat: the most stack forward_dynamics_derivatives may take for M^-1 and "
                "its products, 16 n^2 + 8 n bytes for n degrees of freedom (default 66048: n <= "
                "64); above, it solves column by column with O(n) stack")
      ->needs(flat_opt)
      ->type_name("BYTES");
  e->add_option("--namespace", emit->flat_namespace,
                "with --flat: put the declarations in this C++ namespace instead of at global "
                "scope, so that the exports of two models can share one program")
      ->needs(flat_opt)
      ->type_name("NAME");
  auto regressor = std::make_shared<rigid::cli::RegressorOptions>();
  add_regressor_options(e, *regressor);
  e->callback([eom, latex, format, emit, regressor] {
    if (regressor->enabled) {
      rigid::cli::run_regressor(*eom, *regressor,
                                 {*latex, *format, emit->language, emit->output, emit->flat});
      return;
    }
    if (!emit->language.empty()) {
      if (*latex || !format->empty()) {
        throw rigid::Error("--latex and --format print the equations; --emit writes them as code: use one");
      }
      rigid::cli::run_emit(*eom, *emit);
      return;
    }
    rigid::cli::run_eom(*eom, *latex, *format);
  });
}
