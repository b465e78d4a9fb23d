#include "cmd_sweep.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <thread>

#include <fmt/format.h>

#ifdef RIGID_HAVE_MPI
#include <mpi.h>
#endif

#include "cli_error.hpp"
#include "progress.hpp"
#include "scene_output.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/report/report.hpp"
#include "rigid/report/sweep_page.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "rigid/scene/sweep.hpp"

namespace rigid::cli {
namespace {

namespace fs = std::filesystem;


// Set by Ctrl-C: no run starts after it, the runs in flight stop (their march polls it), the
// finished ones are in the journal.
std::atomic<bool> g_interrupted{false};
extern "C" void on_sweep_interrupt(int /*signal*/) { g_interrupted = true; }

// Launched by mpirun (Open MPI or any PMIx launcher) — the only case where MPI is started, so
// a plain `rigid sweep` and every other command never touch MPI.
[[maybe_unused]] bool under_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
         std::getenv("PMI_RANK") != nullptr;
}

std::size_t env_size(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  if (v == nullptr) return fallback;
  const long n = std::strtol(v, nullptr, 10);
  return n > 0 ? static_cast<std::size_t>(n) : fallback;
}

// The ranks of the sweep: MPI's world when launched by mpirun, else one.
class Ranks {
 public:
  Ranks() {
#ifdef RIGID_HAVE_MPI
    if (under_mpirun()) {
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
      int r = 0, s = 1;
      MPI_Comm_rank(MPI_COMM_WORLD, &r);
      MPI_Comm_size(MPI_COMM_WORLD, &s);
      rank_ = static_cast<std::size_t>(r);
      size_ = static_cast<std::size_t>(s);
      mpi_ = true;
    }
#else
    if (env_size("OMPI_COMM_WORLD_SIZE", 1) > 1) {
      throw Error("this rigid was built without MPI, so the processes mpirun started would each run the whole "
                  "sweep into one directory; run it without mpirun (it uses the threads of its machine), with "
                  "--shard I/N per process, or build rigid with MPI (Debian libopenmpi-dev)");
    }
#endif
  }
  ~Ranks() {
#ifdef RIGID_HAVE_MPI
    if (mpi_) MPI_Finalize();
#endif
  }
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  // A rank that stops (an error, Ctrl-C) while the others may be waiting in a collective call
  // stops them all: the message, then MPI_Abort with the command's exit status. Without MPI (or
  // with one rank) it returns and the error takes the usual way out.
  void stop_all(const Error& e, int status) const {
#ifdef RIGID_HAVE_MPI
    if (mpi_ && size_ > 1) {
      std::fprintf(stderr, "rigid: %s (rank %zu): %s\n", status == 130 ? "interrupted" : "error", rank_,
                   word_for(Surface::kCli, e.what()).c_str());
      std::fflush(stderr);
      MPI_Abort(MPI_COMM_WORLD, status);
    }
#else
    (void)e;
    (void)status;
#endif
  }

  [[nodiscard]] std::size_t rank() const { return rank_; }
  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] bool root() const { return rank_ == 0; }

  // Rank 0's verdict (empty: go on; else the error every rank throws) and its list of finished
  // runs (their indices, ascending), sent to every rank.
  void broadcast(std::string& error, std::vector<std::uint64_t>& finished) const {
#ifdef RIGID_HAVE_MPI
    if (!mpi_) return;
    auto n = static_cast<unsigned long long>(error.size());
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    error.resize(n);
    MPI_Bcast(error.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
    auto m = static_cast<unsigned long long>(finished.size());
    MPI_Bcast(&m, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    finished.resize(m);
    // in pieces: an MPI count is an int
    constexpr std::size_t kPiece = std::size_t{1} << 27;
    for (std::size_t at = 0; at < m; at += kPiece) {
      MPI_Bcast(finished.data() + at, static_cast<int>(std::min<std::size_t>(kPiece, m - at)), MPI_UINT64_T, 0,
                MPI_COMM_WORLD);
    }
#else
    (void)error;
    (void)finished;
#endif
  }

  // Every rank's rows, as journal lines, gathered to rank 0 (MPI_Gatherv of the bytes); rank 0
  // gets the others' rows, the others get nothing.
  [[nodiscard]] std::vector<scene::SweepRow> gather(const std::vector<scene::SweepRow>& rows) const {
#ifdef RIGID_HAVE_MPI
    if (!mpi_) return {};
    std::string bytes;
    if (!root()) {
      for (const auto& r : rows) bytes += scene::row_to_json(r) + "\n";
    }
    if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
      throw Error(fmt::format("rank {}'s rows take {} bytes, more than one MPI message holds (2 GiB); use more "
                              "ranks or shards",
                              rank_, bytes.size()));
    }
    const int n = static_cast<int>(bytes.size());
    std::vector<int> sizes(root() ? size_ : 0), offsets(root() ? size_ : 0);
    MPI_Gather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::string all;
    if (root()) {
      long long total = 0;
      for (std::size_t r = 0; r < size_; ++r) {
        offsets[r] = static_cast<int>(total);
        total += sizes[r];
      }
      if (total > std::numeric_limits<int>::max()) throw Error("the gathered rows exceed 2 GiB; use shards");
      all.resize(static_cast<std::size_t>(total));
    }
    MPI_Gatherv(bytes.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
    std::vector<scene::SweepRow> out;
    std::size_t start = 0;
    while (start < all.size()) {
      const auto nl = all.find('\n', start);
      out.push_back(scene::row_from_json(std::string_view(all).substr(start, nl - start), "gathered rows"));
      start = nl + 1;
    }
    return out;
#else
    (void)rows;
    return {};
#endif
  }

 private:
  std::size_t rank_ = 0;
  std::size_t size_ = 1;
  bool mpi_ = false;
};

scene::SweepSpec parse_spec(const SweepOptions& opts) {
  // every refusal here is of the command line itself (a value none of the option's forms, a
  // missing or conflicting option): usage, exit 2
  scene::SweepSpec spec;
  try {
    for (const auto& g : opts.grid) spec.grid.push_back(scene::parse_grid_axis(g));
  } catch (const Error& e) {
    throw UsageError(fmt::format("--grid: {}", e.what()));
  }
  try {
    for (const auto& s : opts.sample) spec.sample.push_back(scene::parse_sample_axis(s));
  } catch (const Error& e) {
    throw UsageError(fmt::format("--sample: {}", e.what()));
  }
  spec.samples = unsigned_option(opts.samples, "-n", "the number of runs");
  spec.seed = unsigned_option(opts.seed, "--seed", "the seed");
  if (spec.grid.empty() && spec.sample.empty()) {
    throw UsageError("give the runs: --grid NAME=START:STOP:COUNT (repeatable) or --sample NAME=DIST(A,B) with -n N");
  }
  if (!spec.grid.empty() && !spec.sample.empty()) throw UsageError("--grid and --sample: give one of them");
  if (!spec.sample.empty() && spec.samples == 0) throw UsageError("--sample needs -n N, the number of runs");
  if (!spec.grid.empty() && spec.samples > 0) throw UsageError("-n is for --sample; a --grid axis has its own count");
  try {
    scene::check_spec(spec);
  } catch (const Error& e) {
    throw UsageError(fmt::format("{}: {}", spec.grid.empty() ? "--sample" : "--grid", e.what()));
  }
  return spec;
}

// Refuses, before any run, the names the scene does not have (one message, not N failed runs).
void check_names(const scene::SweepIdentity& id) {
  scene::Scene s = scene::load_scene(id.scene, id.model);
  try {
    scene::apply_overrides(s, id.set);
  } catch (const Error& e) {
    throw Error(fmt::format("--set: {}", e.what()));
  }
  try {
    scene::check_overrides(id);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", id.spec.grid.empty() ? "--sample" : "--grid", e.what()));
  }
}

std::string paths_text(const std::vector<fs::path>& paths) {
  std::vector<std::string> names;
  for (const auto& p : paths) names.push_back(p.string());
  return fmt::format("{}", fmt::join(names, ", "));
}

// The failed runs by message, one line per message (the most frequent first), as the summary
// prints them: "  N run(s): MESSAGE (runs i, j, …)".
constexpr std::size_t kFailureGroupsPrinted = 5;
std::string failures_text(const std::vector<scene::FailureGroup>& groups) {
  std::string text;
  std::size_t left_runs = 0;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const scene::FailureGroup& g = groups[k];
    if (k >= kFailureGroupsPrinted) {
      left_runs += g.count;
      continue;
    }
    text += fmt::format("  {} run{}: {} (run{} {}{})\n", g.count, g.count == 1 ? "" : "s", g.message,
                        g.runs.size() == 1 ? "" : "s", fmt::join(g.runs, ", "), g.count > g.runs.size() ? ", …" : "");
  }
  if (groups.size() > kFailureGroupsPrinted) {
    text += fmt::format("  and {} other message{} in {} run{} (summary.json: failure_groups)\n",
                        groups.size() - kFailureGroupsPrinted, groups.size() - kFailureGroupsPrinted == 1 ? "" : "s",
                        left_runs, left_runs == 1 ? "" : "s");
  }
  return text;
}

std::size_t failure_count(const scene::SweepOutputs& outputs) {
  std::size_t n = 0;
  for (const auto& g : outputs.failures) n += g.count;
  return n;
}

// A sweep whose every run failed is an error (exit 1, said on stderr even with -q): its outputs
// are written, and the message says why the runs failed. Empty when some run succeeded.
std::string all_failed(const scene::SweepOutputs& outputs, std::size_t runs, const fs::path& dir) {
  if (runs == 0 || failure_count(outputs) != runs) return {};
  return fmt::format("every one of the sweep's {} runs failed:\n{}the errors are in {}", runs,
                     failures_text(outputs.failures), (dir / "runs.csv").string());
}

// The runs of one process, made one at a time as the pool asks (no list of them is held, so the
// memory before the runs does not depend on the number of runs): the shard's runs i ≡ index
// (mod count) in ascending order, without those the journal holds (`finished`, ascending), dealt
// round robin to the ranks.
class RunsOfThisProcess {
 public:
  RunsOfThisProcess(std::size_t runs, scene::Shard shard, const Ranks& ranks, const std::vector<std::uint64_t>& finished)
      : runs_(runs), shard_(shard), rank_(ranks.rank()), ranks_(ranks.size()), finished_(finished), next_(shard.index) {
    // the shard's unfinished runs, dealt round robin: this rank gets every ranks-th of them
    const std::size_t in_shard = runs > shard.index ? (runs - shard.index + shard.count - 1) / shard.count : 0;
    const auto done = static_cast<std::size_t>(std::count_if(finished.begin(), finished.end(), [&](std::uint64_t i) {
      return i < runs && i % shard.count == shard.index;
    }));
    const std::size_t open = in_shard - std::min(done, in_shard);
    count_ = open > rank_ ? (open - rank_ + ranks_ - 1) / ranks_ : 0;
  }

  // the next index of this process, or nothing
  std::optional<std::size_t> operator()() {
    while (next_ < runs_) {
      const std::size_t i = next_;
      next_ += shard_.count;
      while (at_ < finished_.size() && finished_[at_] < i) ++at_;
      if (at_ < finished_.size() && finished_[at_] == i) continue;
      if (dealt_++ % ranks_ == rank_) return i;
    }
    return std::nullopt;
  }

  [[nodiscard]] std::size_t count() const { return count_; }

 private:
  std::size_t runs_;
  scene::Shard shard_;
  std::size_t rank_, ranks_;
  const std::vector<std::uint64_t>& finished_;
  std::size_t next_;
  std::size_t at_ = 0;     // the first finished index not below next_
  std::size_t dealt_ = 0;  // unfinished runs of the shard seen so far
  std::size_t count_ = 0;
};

// The runs of this process (its shard's unfinished runs, its rank's share), the gather to rank 0
// and rank 0's outputs. Returns all_failed's text (rank 0 of an unsharded sweep).
std::string sweep_on_ranks(const SweepOptions& opts, const scene::SweepIdentity& id, scene::Shard shard,
                           const fs::path& dir, const Ranks& ranks, scene::Journal* journal,
                           const std::vector<std::uint64_t>& finished,
                           const std::shared_ptr<const scene::Model>& first_run) {
  const std::size_t runs = scene::run_count(id.spec);
  const auto names = scene::swept_names(id.spec);
  RunsOfThisProcess mine(runs, shard, ranks, finished);
  const std::size_t planned = mine.count();

  scene::SweepRunOptions ro;
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  ro.threads = opts.threads > 0 ? opts.threads
                                : std::max<std::size_t>(1, cores / env_size("OMPI_COMM_WORLD_LOCAL_SIZE", 1));
  ro.wording = Surface::kCli;
  ro.first_run = first_run;
  if (opts.keep_trajectories) ro.keep_trajectories = dir / "runs";
  // rank 0's rows go to the journal as they come (appended by the worker that ran the run).
  // The other ranks keep theirs for the gather; rank 0 of an unsharded sweep of at most
  // kRowsKeptInMemory runs keeps them for the outputs, which then need not read the journal
  // back (a few µs a row, after the runs, serially); a longer sweep runs in bounded memory and
  // reads its journal back at the end
  constexpr std::size_t kRowsKeptInMemory = 1'000'000;
  const bool outputs_from_memory = shard.count == 1 && planned <= kRowsKeptInMemory;
  ro.journal = journal;
  ro.keep_rows = journal == nullptr || outputs_from_memory;
  g_interrupted = false;
  ro.cancel = &g_interrupted;
  std::size_t done = 0;
  ProgressBar bar(!opts.quiet && ranks.root());
  ro.on_row = [&](const scene::SweepRow&) {
    ++done;
    bar.update(static_cast<double>(done) / static_cast<double>(planned),
               [&] { return fmt::format("{} / {} runs", done, planned); });
  };
  const auto start = std::chrono::steady_clock::now();
  const auto previous = std::signal(SIGINT, on_sweep_interrupt);
  std::vector<scene::SweepRow> rows;
  try {
    rows = scene::run_sweep(id, std::ref(mine), planned, ro);
  } catch (const Cancelled& e) {
    bar.clear();
    std::signal(SIGINT, previous);
    throw Cancelled(fmt::format("{}; the {} finished runs are kept in {}: run the same command again to go on",
                                e.what(), journal ? journal->finished().size() + done : done,
                                (dir / ".journal.jsonl").string()));
  } catch (...) {
    bar.clear();
    std::signal(SIGINT, previous);
    throw;
  }
  bar.clear();
  std::signal(SIGINT, previous);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<scene::SweepRow> others = ranks.gather(rows);
  if (!ranks.root()) return {};
  for (const auto& r : others) journal->append(r);
  journal->flush();  // the journal is whole before any output is written

  const std::size_t before = journal->finished().size();
  const std::size_t ran = done + others.size();
  if (shard.count > 1) {
    if (!opts.quiet) {
      fmt::print("shard {}/{}: {} runs now ({} before) in {}; join the shards with rigid sweep merge\n", shard.index,
                 shard.count, ran, before, (dir / ".journal.jsonl").string());
    }
    return {};
  }
  // every row the journal now holds: those it held when opened, this process's and the other
  // ranks' (the same numbers as read back: a row's doubles are written in their round-trip
  // form), or read back from it; the units its header holds (run 0's, as when the journal was
  // started)
  const auto outputs_start = std::chrono::steady_clock::now();
  std::vector<scene::SweepRow> all;
  if (outputs_from_memory) {
    all = journal->finished();
    all.reserve(all.size() + rows.size() + others.size());
    std::move(rows.begin(), rows.end(), std::back_inserter(all));
    std::move(others.begin(), others.end(), std::back_inserter(all));
  } else {
    all = scene::read_journal(dir).rows;
  }
  const scene::SweepOutputs outputs = scene::make_outputs(names, runs, std::move(all), journal->units());
  auto written = scene::write_outputs(dir, outputs, ro.threads);
  const double output_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - outputs_start).count();
  if (opts.report) {
    // the page of the files just written (summary.json's units), with every unit of run 0's
    // schema for names it does not list
    report::SweepData data = report::read_sweep(dir);
    if (first_run) data.units.merge(scene::sweep_units(first_run->schema()));
    const fs::path page = opts.report_path.empty() ? dir / io::kReportFileName : fs::path(opts.report_path);
    io::write_file_atomically(page, report::sweep_page(data));
    written.push_back(page);
  }
  if (!opts.quiet) {
    const std::size_t failures = failure_count(outputs);
    fmt::print("sweep: {} runs ({} now in {:.3g} s on {} thread(s) x {} rank(s), {} from the journal; outputs in "
               "{:.2g} s), {} failed{}\n",
               runs, ran, seconds, ro.threads, ranks.size(), before, output_seconds, failures, failures > 0 ? ":" : "");
    fmt::print("{}", failures_text(outputs.failures));
    fmt::print("wrote {}\n", paths_text(written));
    std::fflush(stdout);
  }
  return all_failed(outputs, runs, dir);
}

}  // namespace

void run_sweep(const SweepOptions& opts) {
  scene::SweepIdentity id{.scene = opts.scene,
                          .set = opts.set,
                          .integrator = opts.integrator,
                          .spec = parse_spec(opts),
                          .model = model_options(opts.model)};
  const scene::Shard shard = [&] {
    if (opts.shard.empty()) return scene::Shard{};
    try {
      return scene::parse_shard(opts.shard);
    } catch (const Error& e) {
      throw UsageError(fmt::format("--shard: {}", e.what()));
    }
  }();
  if (opts.report) {
    if (!report::available()) {
      throw Error("--report: this rigid was built without the report page (CMake option RIGID_REPORT=OFF, a "
                  "build without node): rebuild with the ci or release preset to write reports");
    }
    if (shard.count > 1) {
      throw UsageError("--report with --shard: a shard writes no runs.csv; merge the shards (rigid sweep merge) "
                       "and write the page with rigid report DIR");
    }
    if (!opts.report_path.empty()) (void)io::check_output_file(opts.report_path);
  }
  check_names(id);
  // run 0 built and checked as its run would be (integrator, metrics' columns, values), before
  // the directory is made: a sweep every run of which would be refused is refused once
  const std::shared_ptr<const scene::Model> first_run = scene::check_first_run(id);
  const std::size_t runs = scene::run_count(id.spec);
  const auto names = scene::swept_names(id.spec);
  const std::string description = scene::describe(id);
  const fs::path dir = opts.output.empty() ? fs::path("out") / (fs::path(opts.scene).stem().string() + "-sweep")
                                           : fs::path(opts.output);

  const Ranks ranks;
  // rank 0 owns the directory: it opens the journal and tells the others what is finished
  std::unique_ptr<scene::Journal> journal;
  std::string refused;
  std::vector<std::uint64_t> finished;  // the journal's runs, ascending (none allocated per requested run)
  if (ranks.root()) {
    try {
      journal = std::make_unique<scene::Journal>(dir, description, names, runs, shard,
                                                 scene::sweep_units(first_run->schema()));
      for (const auto& r : journal->finished()) finished.push_back(r.index);
      std::sort(finished.begin(), finished.end());
      finished.erase(std::unique(finished.begin(), finished.end()), finished.end());
    } catch (const Error& e) {
      refused = e.what();
    }
  }
  ranks.broadcast(refused, finished);
  if (!refused.empty()) throw Error(refused);
  std::string failed;
  try {
    failed = sweep_on_ranks(opts, id, shard, dir, ranks, journal.get(), finished, first_run);
  } catch (const Cancelled& e) {
    ranks.stop_all(e, 130);
    throw;
  } catch (const Error& e) {
    ranks.stop_all(e, 1);
    throw;
  }
  // every rank is done: an error now stops none of them
  if (!failed.empty()) throw Error(failed);
}

void run_sweep_merge(const SweepMergeOptions& opts) {
  if (opts.directories.empty()) throw Error("rigid sweep merge: give the shards' directories");
  std::vector<scene::JournalContents> parts;
  for (const auto& d : opts.directories) parts.push_back(scene::read_journal(d));
  const auto& first = parts.front();
  std::vector<std::string> shards;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto& p = parts[i];
    if (p.description != first.description || p.names != first.names || p.runs != first.runs) {
      throw Error(fmt::format("'{}' holds another sweep ({}) than '{}' ({}); merge the shards of one sweep",
                              opts.directories[i], p.description, opts.directories.front(), first.description));
    }
    shards.push_back(fmt::format("{}/{}", p.shard.index, p.shard.count));
  }
  // the units the shards' headers state (run 0's schema; a journal of an older rigid has none)
  scene::SweepUnits units;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].units.empty()) continue;
    if (units.empty()) {
      units = parts[i].units;
    } else if (parts[i].units != units) {
      throw Error(fmt::format("'{}' states other units for the sweep's columns than the shards before it: its "
                              "scene file's schema changed between shards; run every shard on one version of "
                              "the scene and of rigid",
                              opts.directories[i]));
    }
  }
  std::vector<scene::SweepRow> all;
  for (const auto& p : parts) all.insert(all.end(), p.rows.begin(), p.rows.end());
  const scene::SweepOutputs outputs = [&] {
    try {
      return scene::make_outputs(first.names, first.runs, all, units);
    } catch (const Error& e) {
      throw Error(fmt::format("rigid sweep merge of shards {}: {}; run the missing shards (or finish them: the "
                              "same command again) and merge again",
                              fmt::join(shards, ", "), e.what()));
    }
  }();
  // the merged directory is an unsharded sweep's: its journal holds every run, so the sweep's
  // own command on it finds everything done
  const fs::path out = opts.output.empty() ? fs::path("out/sweep-merged") : fs::path(opts.output);
  scene::Journal journal(out, first.description, first.names, first.runs, scene::Shard{}, units);
  std::set<std::size_t> have;
  for (const auto& r : journal.finished()) have.insert(r.index);
  for (const auto& r : all) {
    if (have.insert(r.index).second) journal.append(r);
  }
  journal.flush();  // the journal is whole before any output is written
  const auto written = scene::write_outputs(out, outputs);
  if (!opts.quiet) {
    const std::size_t failures = failure_count(outputs);
    fmt::print("merged {} runs from shards {}, {} failed{}\n{}wrote {}\n", first.runs, fmt::join(shards, ", "),
               failures, failures > 0 ? ":" : "", failures_text(outputs.failures), paths_text(written));
    std::fflush(stdout);
  }
  if (const std::string failed = all_failed(outputs, first.runs, out); !failed.empty()) throw Error(failed);
}

}  // namespace rigid::cli
