// Fuzz target: a sweep's journal, DIR/.journal.jsonl: scene::read_journal (what `rigid sweep
// merge` reads) and scene::Journal opening an existing journal (what a sweep started again on
// DIR does to resume). The input is written as the journal of a scratch directory, then:
//  1. read_journal(DIR): refused, or a header and the complete lines' rows;
//  2. the merge: make_outputs(names, runs, rows, units) of the journal's own header, when it declares
//     at most kMaxRuns runs (the outputs are made per run: a header of 2^32 runs would be a
//     finding of the target's memory, not of the reader);
//  3. the resume of a small sweep (kGrid, described once by scene::describe): Journal(DIR, …)
//     refuses the journal of another sweep or shard, or holds its rows, which make_outputs
//     checks as those of a finished sweep;
//  4. the resume with the journal's own header: a journal read_journal accepts is one Journal
//     reopens, with the same rows, and a row appended to it reads back after them (a last line
//     cut short is cut off first).
// Seeds (fuzz/make_seeds.py) use the small sweep's description, so that they reach step 3's
// rows; its scene text (kScene) is written the same there.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "rigid/scene/sweep.hpp"

namespace {

namespace fs = std::filesystem;
namespace sc = rigid::scene;

constexpr std::size_t kMaxRuns = 4096;
// the small sweep: its scene file's bytes (hashed by describe) and its grid
constexpr const char* kScene = "# the scene of the sweep_journal fuzz target\n";
constexpr const char* kGrid = "a=0:1:3";

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "rigid fuzz: sweep journal: %s\n", what);
  std::abort();
}

struct SmallSweep {
  std::string description;
  std::vector<std::string> names;
  std::size_t runs = 0;
};

const SmallSweep& small_sweep() {
  static const SmallSweep sweep = [] {
    const fs::path scene = rigid::fuzz::scratch_dir() / "sweep.toml";
    std::ofstream(scene, std::ios::binary) << kScene;
    sc::SweepIdentity id{.scene = scene, .set = {}, .integrator = {}, .spec = {}, .model = {}};
    id.spec.grid.push_back(sc::parse_grid_axis(kGrid));
    return SmallSweep{sc::describe(id), sc::swept_names(id.spec), sc::run_count(id.spec)};
  }();
  return sweep;
}

std::vector<std::string> as_json(const std::vector<sc::SweepRow>& rows) {
  std::vector<std::string> out;
  for (const auto& r : rows) out.push_back(sc::row_to_json(r));
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = rigid::fuzz::as_text(data, size);
  const SmallSweep& small = small_sweep();
  const fs::path dir = rigid::fuzz::scratch_dir() / "sweep";
  fs::create_directories(dir);
  const auto reset = [&] { (void)rigid::fuzz::write_scratch(data, size, "sweep/.journal.jsonl"); };
  reset();

  sc::JournalContents contents;
  bool read = false;
  rigid::fuzz::refuse_or_return(input, [&] {
    contents = sc::read_journal(dir);
    read = true;
  });
  if (!read) return 0;
  if (contents.runs <= kMaxRuns) {
    rigid::fuzz::refuse_or_return(
        input, [&] { (void)sc::make_outputs(contents.names, contents.runs, contents.rows, contents.units); });
  }
  rigid::fuzz::refuse_or_return(input, [&] {
    const sc::Journal journal(dir, small.description, small.names, small.runs, sc::Shard{});
    (void)sc::make_outputs(small.names, small.runs, journal.finished());
  });

  reset();
  try {
    sc::Journal journal(dir, contents.description, contents.names, contents.runs, contents.shard);
    if (as_json(journal.finished()) != as_json(contents.rows))
      fail("reopened, it holds other rows");
    const sc::SweepRow row{.index = 0, .values = {0.5}, .results = {{"x", 1.0}}, .error = {}};
    journal.append(row);
    journal.flush();  // appended rows are written by the journal's thread; flush waits for them
    std::vector<std::string> expected = as_json(contents.rows);
    expected.push_back(sc::row_to_json(row));
    if (as_json(sc::read_journal(dir).rows) != expected)
      fail("an appended row does not read back after the rows");
  } catch (const rigid::Error& e) {
    std::fprintf(stderr, "rigid fuzz: sweep journal: read, but refused when reopened: %s\n",
                 e.what());
    std::abort();
  }
  return 0;
}
