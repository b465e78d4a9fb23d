#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model_flags.hpp"

namespace rigid::cli {

/// Options of `rigid sweep SCENE`.
struct SweepOptions {
  std::string scene;
  std::vector<std::string> set;     ///< overrides every run gets
  std::string integrator;           ///< overrides [simulation] integrator
  std::vector<std::string> grid;    ///< NAME=START:STOP:COUNT
  std::vector<std::string> sample;  ///< NAME=DIST(A,B)
  std::string samples;              ///< -n: the number of Monte Carlo runs, as given (empty: 0)
  std::string seed;                 ///< --seed as given (empty: 0)
  std::string output;               ///< the sweep's directory (default out/<scene stem>-sweep)
  unsigned threads = 0;             ///< 0: the cores (shared by the MPI ranks of a node)
  bool keep_trajectories = false;   ///< each run's files in DIR/runs/NNNNN/
  std::string shard;                ///< I/N: the runs i ≡ I (mod N)
  bool quiet = false;
  ModelFlags model;                 ///< how a robot model file is read
  bool report = false;              ///< --report: also write the sweep's page
  std::string report_path;          ///< --report PATH as given (empty: DIR/report.html)
};

/// Options of `rigid sweep merge DIR... -o OUT`.
struct SweepMergeOptions {
  std::vector<std::string> directories;
  std::string output;
  bool quiet = false;
};

/// `rigid sweep SCENE --grid … | --sample … -n N`: runs the sweep (on threads; on MPI ranks when
/// launched by mpirun), resuming from DIR's journal, and writes runs.csv, runs.npy and
/// summary.json (a shard writes its journal only), and with --report the sweep's page (units from
/// the schema of run 0). Before DIR is made, run 0 is built and
/// checked (scene::check_first_run); the summary lists the failed runs by message.
/// @throws rigid::Error when run 0 is refused (nothing written), and after the outputs are
///   written when every run failed (even with quiet).
void run_sweep(const SweepOptions& opts);

/// `rigid sweep merge DIR... -o OUT`: joins the journals of the shards of one sweep and writes
/// the outputs the unsharded sweep writes.
void run_sweep_merge(const SweepMergeOptions& opts);

}  // namespace rigid::cli
