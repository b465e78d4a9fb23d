#pragma once

/// Sweeps: one scene run many times, each run with its own overrides (`name=value`, as
/// `--set` takes them), over a cartesian grid or a Monte Carlo sample. A run is the scene (read
/// once) with `set` and its overrides applied, built into a Model, then `Model::run`; its row
/// holds the swept values, the metrics and diagnostics of its summary, or the error that stopped
/// it. Overrides change values only, so a coordinate scene's equations are derived once, for the
/// first of the runs, and shared by the models of all (Model(scene, like)).
///
/// What makes a sweep reproducible, byte for byte, whatever the threads, processes or shards:
///  - a run's values depend only on (spec, seed, run index) — counter-based sampling;
///  - the outputs (runs.csv, runs.npy, summary.json) are made from the rows sorted by index;
///  - doubles are printed in their shortest round-trip form.
/// What makes it resumable: each finished run is one line appended to the journal
/// DIR/.journal.jsonl, whose first line is the sweep's fingerprint; a sweep started again on the
/// same DIR skips the runs the journal holds and refuses a journal of another sweep.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigid/common/wording.hpp"
#include "rigid/io/run_schema.hpp"
#include "rigid/io/table.hpp"
#include "rigid/scene/scene.hpp"

namespace rigid::scene {

class Model;

/// One axis of a grid: `count` equally spaced values from `start` to `stop`, both included
/// (count 1: start alone).
struct GridAxis {
  std::string name{};
  double start = 0;
  double stop = 0;
  std::size_t count = 1;
};

enum class Distribution { kUniform, kNormal, kLogUniform };

/// One sampled value: uniform(a, b) on [a, b); normal(mu = a, sigma = b); loguniform(a, b),
/// whose logarithm is uniform on [log a, log b).
struct SampleAxis {
  std::string name{};
  Distribution distribution = Distribution::kUniform;
  double a = 0;
  double b = 1;
};

/// What a sweep runs: a grid (every combination of the axes, the first axis varying slowest)
/// or `samples` Monte Carlo draws of the sample axes with `seed`; never both.
struct SweepSpec {
  std::vector<GridAxis> grid{};
  std::vector<SampleAxis> sample{};
  std::size_t samples = 0;
  std::uint64_t seed = 0;
};

/// Parses `name=start:stop:count` (count ≥ 1 whole; start, stop finite; count 1 needs start == stop).
/// @throws rigid::Error naming the text and what was expected.
[[nodiscard]] GridAxis parse_grid_axis(std::string_view text);
/// Parses `name=uniform(a,b)`, `name=normal(mu,sigma)` or `name=loguniform(a,b)` (a < b;
/// sigma > 0; 0 < a for loguniform). @throws rigid::Error naming the text and what was expected.
[[nodiscard]] SampleAxis parse_sample_axis(std::string_view text);

/// Checks a spec: a grid or a sample (not both, not neither), samples ≥ 1 with a sample, no
/// name twice, at most kMaxSweepRuns runs. @throws rigid::Error saying what is wrong.
void check_spec(const SweepSpec& spec);

/// Most runs of one sweep (2^32): a bound on the journal and the outputs.
inline constexpr std::size_t kMaxSweepRuns = std::size_t{1} << 32;

/// The number of runs of a (checked) spec: the product of the grid counts, or `samples`.
[[nodiscard]] std::size_t run_count(const SweepSpec& spec);
/// The swept names in column order: the grid's axes, or the sample's.
[[nodiscard]] std::vector<std::string> swept_names(const SweepSpec& spec);
/// The swept values of run `index` (< run_count), in the order of swept_names.
[[nodiscard]] std::vector<double> run_values(const SweepSpec& spec, std::size_t index);
/// A uniform number in (0, 1) that depends only on (seed, run index, axis index): the 53 high
/// bits of a SplitMix64 hash chain of the three, plus half an ulp (so never 0 or 1).
[[nodiscard]] double counter_uniform(std::uint64_t seed, std::uint64_t index, std::uint64_t axis);
/// The value of `axis` at the uniform number u in (0, 1): its distribution's inverse CDF.
[[nodiscard]] double sample_value(const SampleAxis& axis, double u);
/// `name=value` with the value in its shortest round-trip form: what a run passes as override.
[[nodiscard]] std::string override_text(std::string_view name, double value);

/// The part of a sweep a process runs: the runs whose index i satisfies i ≡ index (mod count)
/// (round robin, so a grid's slow corner is shared by every shard).
struct Shard {
  std::size_t index = 0;
  std::size_t count = 1;
};
/// Parses `i/N` (0 ≤ i < N). @throws rigid::Error naming the text.
[[nodiscard]] Shard parse_shard(std::string_view text);

/// The result of one run.
struct SweepRow {
  std::size_t index = 0;
  std::vector<double> values{};  ///< the swept values (swept_names order)
  /// The run's summary metrics, then its diagnostics (name, value); empty for a failed run.
  std::vector<std::pair<std::string, double>> results{};
  std::string error{};  ///< empty when the run succeeded
};

/// A row as one line of JSON (no newline): {"run":…,"values":[…],"results":[[name,value],…],
/// "error":…}; doubles in their shortest round-trip form, non-finite ones as strings.
[[nodiscard]] std::string row_to_json(const SweepRow& row);
/// Inverse of row_to_json. @throws rigid::Error naming `where` if the line is not a row.
[[nodiscard]] SweepRow row_from_json(std::string_view line, std::string_view where);

/// What identifies a sweep: its scene file (bytes), the fixed overrides, the integrator and the
/// spec. Two commands with the same description compute the same rows.
struct SweepIdentity {
  std::filesystem::path scene{};
  std::vector<std::string> set{};  ///< overrides every run gets (before its own)
  std::string integrator{};      ///< empty: the scene's
  SweepSpec spec{};
  ModelOptions model{};          ///< how a robot model file of the scene is read (load_scene)
};
/// A readable, canonical description: the scene's content hash (FNV-1a 64, hex), the set, the
/// integrator, the model options set, the axes, samples and seed. @throws rigid::Error if the scene cannot be read.
[[nodiscard]] std::string describe(const SweepIdentity& identity);

/// The units of a sweep's columns, from run 0's schema: its scalars (parameters, diagnostics,
/// metrics, and "result.NAME" for a result named like a swept name), the initial values a
/// sweep can set (COORDINATE.initial, COORDINATE.velocity) and the [simulation] times (t_end,
/// dt, output_dt: s), for the names whose unit is known (not a scene's own parameters, nor a
/// coordinate that the scene does not say is a length or an angle).
using SweepUnits = std::map<std::string, std::string>;
[[nodiscard]] SweepUnits sweep_units(const io::RunSchema& schema);

/// The journal of a sweep's directory, DIR/.journal.jsonl: a header line
/// {"rigid_sweep":1,"sweep":<describe()>,"names":[…],"runs":N,"shard":"i/N","units":{…}} ("units"
/// only when known: sweep_units of run 0) then one row per finished run. Rows are gathered in
/// memory and written (write(2), O_APPEND) at most 0.1 s after they were appended, or at once
/// when 64 KiB are waiting, so that a sweep of many short runs does not make a system call per
/// run under a lock: a killed process loses the runs in flight and those finished in the last
/// 0.1 s, which the next start runs again (a last line cut short is dropped when the journal is
/// opened again).
class Journal {
 public:
  /// Opens DIR/.journal.jsonl (making DIR if needed) for the sweep `description` of `runs` runs,
  /// shard `shard`: a new journal gets its header, with `units`; an existing one must have the
  /// same header (its units are kept: read_journal gives them).
  /// @throws rigid::Error if DIR cannot be made or written, or holds the journal of another
  ///   sweep or shard (saying which, with the remedy: another directory).
  Journal(const std::filesystem::path& directory, const std::string& description,
          const std::vector<std::string>& names, std::size_t runs, Shard shard,
          const SweepUnits& units = {});
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// The rows the journal held when opened, in the order they finished.
  [[nodiscard]] const std::vector<SweepRow>& finished() const { return finished_; }
  /// The units of its header (those it was started with, for a journal opened again).
  [[nodiscard]] const SweepUnits& units() const { return units_; }
  /// Appends a row (thread-safe; the line is made outside the lock). @throws rigid::Error if a
  /// write failed (disk full), this one or an earlier one made in the background.
  void append(const SweepRow& row);
  /// Writes the rows waiting. @throws rigid::Error as append.
  void flush();

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::vector<SweepRow> finished_;
  SweepUnits units_;
  struct Writer;  // the rows waiting and the thread that writes them
  std::unique_ptr<Writer> writer_;
};

/// The journal's header and rows, read without opening it for appending (rigid sweep merge).
struct JournalContents {
  std::string description;
  std::vector<std::string> names;
  std::size_t runs = 0;
  Shard shard;
  std::vector<SweepRow> rows;
  SweepUnits units;  ///< the header's, empty when it has none
};
/// @throws rigid::Error if DIR holds no journal or it is not one.
[[nodiscard]] JournalContents read_journal(const std::filesystem::path& directory);

/// How the runs of a sweep are run.
/// Most runs of a free-body sweep that one thread marches together (Model::run_batch): one
/// block of the four-body kernel for a scene of one body.
inline constexpr std::size_t kSweepBatch = 4;

struct SweepRunOptions {
  std::size_t threads = 1;
  /// Called after each run (from the worker thread that ran it; calls are serialized).
  std::function<void(const SweepRow&)> on_row{};
  /// When set, each row is appended to it by the worker that ran it, outside on_row's lock (the
  /// serial part of a run is then only on_row's).
  Journal* journal = nullptr;
  /// When set and true, no further run starts and the runs in flight stop (rigid::Cancelled,
  /// not recorded).
  const std::atomic<bool>* cancel = nullptr;
  /// When not empty, each run's trajectory and summary go to keep_trajectories/NNNNN
  /// (io::write_run with the scene's output formats).
  std::filesystem::path keep_trajectories{};
  /// How error texts are worded in the rows.
  Surface wording = Surface::kLibrary;
  /// When false, run_sweep returns no rows (on_row saw each, e.g. into the journal), so that
  /// the memory of a long sweep does not grow with the runs made.
  bool keep_rows = true;
  /// Run 0's model as check_first_run returned it, when the caller checked it already; empty:
  /// run_sweep builds and checks it.
  std::shared_ptr<const Model> first_run{};
  /// When true, runs of a free-body scene that Model::batches() march kSweepBatch at a time
  /// (fewer when the sweep has fewer than kSweepBatch runs per thread) through
  /// Model::run_batch: the rows are the same bytes either way (tested); false runs them one by
  /// one (the benchmark's comparison).
  bool batch = true;
};

/// Checks, before running, that every swept and fixed name is one the scene accepts (the
/// overrides of run 0 applied to the parsed scene). @throws rigid::Error from the overrides.
void check_overrides(const SweepIdentity& identity);

/// Builds the model of run 0 (the scene with `set` and the first value of every axis, or the
/// first draw of a sample) and checks it as its run would before stepping (Model::check with the
/// sweep's integrator): what every run of the sweep shares — the integrator's name, the metrics'
/// columns, the fixed overrides — is refused here once instead of by each run. Returns the
/// model, which the runs share as their prototype (Model(scene, like)).
/// @throws rigid::Error "run 0 of the sweep (NAME=VALUE, …) is refused, so no run was started:
///   <the model's message>".
[[nodiscard]] std::shared_ptr<const Model> check_first_run(const SweepIdentity& identity);

/// Runs the runs `indices` on a pool of options.threads threads (each takes the next index from
/// an atomic counter; up to kSweepBatch at a time when they batch, see SweepRunOptions::batch) and
/// returns their rows sorted by index. A run that throws rigid::Error is a row with its error.
/// Runs go in parallel, each model built by the thread that runs it from the prototype's
/// equations. Before any run, run 0 is built and checked
/// (check_first_run, unless options.first_run holds it): a coordinate scene is derived once,
/// there, and every run's model shares its equations.
/// @throws rigid::Error from check_first_run when there is a run to make; rigid::Cancelled when
///   options.cancel stopped it (rows already passed to on_row stay).
[[nodiscard]] std::vector<SweepRow> run_sweep(const SweepIdentity& identity, std::span<const std::size_t> indices,
                                              const SweepRunOptions& options);

/// The runs to run, one index at a time, made as they are asked for (a grid's run k from its
/// mixed-radix digits, a sample's from (seed, k): run_values), so that no list of them is held:
/// returns the next index, or nothing when there is none left. Called by one thread at a time.
using RunIndexSource = std::function<std::optional<std::size_t>()>;

/// run_sweep over the indices `next` gives (`count` of them, for messages). The memory before
/// the runs does not depend on `count`; the rows returned are those of the runs made.
[[nodiscard]] std::vector<SweepRow> run_sweep(const SweepIdentity& identity, const RunIndexSource& next,
                                              std::size_t count, const SweepRunOptions& options);

/// The failed runs of one error message: how many, and the first of them.
struct FailureGroup {
  std::string message{};
  std::size_t count = 0;
  std::vector<std::size_t> runs{};  ///< the first kFailureGroupRuns run indices, ascending
};
/// Run indices a FailureGroup lists.
inline constexpr std::size_t kFailureGroupRuns = 5;
/// Failure groups summary.json lists (the most frequent).
inline constexpr std::size_t kFailureGroupsListed = 20;

/// The failed runs grouped by their message (exactly equal texts): `errors` holds each run's
/// error ("" when it succeeded) in run order, as SweepOutputs::errors. The groups come most
/// frequent first, ties by their first run.
[[nodiscard]] std::vector<FailureGroup> group_failures(const std::vector<std::string>& errors);

/// The outputs of a whole sweep made from its rows (all indices 0 … runs-1, any order, each once):
/// runs.csv (run, swept names, result columns, error), runs.npy (the same without error; NaN
/// for a failed run's results) and summary.json (count, failures, failure_groups: the first
/// kFailureGroupsListed of group_failures as {"message", "count", "runs"}, with
/// failure_groups_left_out {"groups", "runs"} when there are more; npy columns; per result
/// column: mean, std (n−1), min, max, quantiles 0.05 0.25 0.5 0.75 0.95 by linear
/// interpolation, over the runs where it is finite; "units" {column: unit} for the swept and
/// result columns `units` names, when any). Result columns are the union of the rows' result
/// names in index order; a name equal to an earlier column is prefixed "result.".
struct SweepOutputs {
  io::Table numbers{{"run"}};
  std::vector<std::string> errors{};
  std::string summary_json{};
  std::vector<FailureGroup> failures{};  ///< group_failures(errors), every group
};
/// @throws rigid::Error if an index is missing, repeated (with different rows) or out of range.
/// `names` are the swept names, `runs` the sweep's run count.
[[nodiscard]] SweepOutputs make_outputs(const std::vector<std::string>& names, std::size_t runs,
                                        std::vector<SweepRow> rows, const SweepUnits& units = {});
/// Writes runs.csv, runs.npy and summary.json into `directory`, each atomically; runs.csv is
/// formatted on `threads` threads (io::to_csv: the same bytes). Returns the paths written.
std::vector<std::filesystem::path> write_outputs(const std::filesystem::path& directory, const SweepOutputs& outputs,
                                                 std::size_t threads = 1);

}  // namespace rigid::scene
