#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
// `rigid sweep SCENE …` and `rigid sweep merge DIR… -o OUT`.
#include <memory>

#include "cli_model.hpp"
#include "cmd_sweep.hpp"

inline void add_sweep_command(CLI::App& app) {
  auto opts = std::make_shared<rigid::cli::SweepOptions>();
  auto* cmd = app.add_subcommand(
      "sweep", "Run a scene many times: a grid or a Monte Carlo sample of its parameters, settings and "
               "initial conditions (see docs/sweep.md)");
  cmd->add_option("SCENE", opts->scene, "scene file (TOML; see docs/scene-format.md)");
  cmd->add_option("--grid", opts->grid,
                  "an axis of the grid: NAME=START:STOP:COUNT, COUNT values from START to STOP inclusive "
                  "(repeatable: every combination, the first axis slowest)")
      ->type_name("NAME=START:STOP:COUNT")
      ->allow_extra_args(false);
  cmd->add_option("--sample", opts->sample,
                  "a sampled value: NAME=uniform(A,B), NAME=normal(MU,SIGMA) or NAME=loguniform(A,B) "
                  "(repeatable; with -n)")
      ->type_name("NAME=DIST(A,B)")
      ->allow_extra_args(false);
  cmd->add_option("-n,--samples", opts->samples, "the number of Monte Carlo runs (with --sample)")
      ->type_name("N");
  cmd->add_option("--seed", opts->seed,
                  "the seed of the sample: an integer from 0 to 2^64 - 1 (default 0); a run's "
                  "values depend only on the seed and its index")
      ->type_name("SEED");
  cmd->add_option("--set", opts->set, "an override every run gets: name=value (repeatable)")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  cmd->add_option("--integrator", opts->integrator, "overrides [simulation] integrator (see rigid run --help)");
  cmd->add_option("-o,--output", opts->output,
                  "the sweep's directory: runs.csv, runs.npy, summary.json and the journal that lets the same "
                  "command resume (default: out/<scene file stem>-sweep)");
  cmd->add_option("--threads", opts->threads, "runs at once (default: the cores, shared by MPI ranks on a node)");
  cmd->add_flag("--keep-trajectories", opts->keep_trajectories,
                "also write each run's files (trajectory, summary) into DIR/runs/NNNNN/");
  cmd->add_option("--shard", opts->shard,
                  "run only the runs i = I (mod N) into the directory, for a job array; join the shards with "
                  "rigid sweep merge")
      ->type_name("I/N");
  cmd->add_flag("-q,--quiet", opts->quiet,
                "print nothing on success (no summary, no progress bar); a sweep whose every run failed "
                "is still an error (stderr, exit status 1)");
  auto* report = cmd->add_option("--report", opts->report_path,
                                 "also write the sweep's page: plots of the results against the swept values "
                                 "(a heatmap for two grid axes, histograms for a sample) and the failed runs; "
                                 "PATH defaults to DIR/report.html (docs/report.md)")
                      ->expected(0, 1)
                      ->type_name("[PATH]");
  add_model_options(cmd, opts->model);

  auto merge = std::make_shared<rigid::cli::SweepMergeOptions>();
  auto* m = cmd->add_subcommand("merge", "Join the directories of a sweep's shards into the outputs of the "
                                         "whole sweep");
  m->add_option("DIRS", merge->directories, "the shards' directories")->required();
  m->add_option("-o,--output", merge->output, "the merged sweep's directory")->required();
  m->add_flag("-q,--quiet", merge->quiet, "print nothing on success");
  m->callback([merge] { rigid::cli::run_sweep_merge(*merge); });

  cmd->callback([opts, m, report] {
    if (m->parsed()) return;
    opts->report = report->count() > 0;
    if (opts->scene.empty()) throw CLI::RequiredError("SCENE (or: rigid sweep merge DIR... -o OUT)");
    rigid::cli::run_sweep(*opts);
  });
}
