#include "rigid/scene/sweep.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rigid/common/escape.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/run_output.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"

namespace rigid::scene {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::optional<double> parse_double(std::string_view s) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// "name=rest": the name (trimmed, non-empty, no blanks inside) and the rest.
std::pair<std::string, std::string_view> split_assignment(std::string_view text, std::string_view expected) {
  const auto eq = text.find('=');
  const std::string_view name = eq == std::string_view::npos ? std::string_view{} : trim(text.substr(0, eq));
  if (eq == std::string_view::npos || name.empty() || name.find_first_of(" \t,") != std::string_view::npos) {
    throw Error(fmt::format("'{}' is not an assignment; expected {}", escaped(text), expected));
  }
  return {std::string(name), text.substr(eq + 1)};
}

// SplitMix64's output function (Steele, Lea and Flood 2014): a bijection of 64-bit words whose
// every output bit depends on every input bit.
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::string_view distribution_name(Distribution d) {
  switch (d) {
    case Distribution::kUniform: return "uniform";
    case Distribution::kNormal: return "normal";
    case Distribution::kLogUniform: return "loguniform";
  }
  return "uniform";
}

// FNV-1a, 64 bits, of a file's bytes: a content hash that is the same on every machine and
// every build (std::hash is not), for the fingerprint only (not a security measure).
std::string file_hash(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(fmt::format("cannot read the scene file '{}'", file.string()));
  std::uint64_t h = 0xcbf29ce484222325ULL;
  char buffer[1 << 14];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h = (h ^ static_cast<unsigned char>(buffer[i])) * 0x100000001b3ULL;
    }
  }
  return fmt::format("{:016x}", h);
}

Json number_json(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
}

// A journal's count or run number: a whole number ≥ 0, else std::invalid_argument (the
// caller's "edited or damaged"). nlohmann's get<std::size_t>() would turn −1 into 2⁶⁴ − 1 and
// 2.5 into 2, and of 5e66 (a float to it) is undefined behaviour.
std::uint64_t whole_number(const Json& j, const char* what) {
  if (!j.is_number_unsigned()) throw std::invalid_argument(what);
  return j.get<std::uint64_t>();
}

double number_from_json(const Json& j) {
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) {
    const auto s = j.get<std::string>();
    if (s == "nan") return kNaN;
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
  }
  throw Error("a value is neither a number nor nan/inf");
}

std::string shard_text(Shard s) { return fmt::format("{}/{}", s.index, s.count); }

Json header_json(const std::string& description, const std::vector<std::string>& names, std::size_t runs,
                 Shard shard, const SweepUnits& units) {
  Json j;
  j["rigid_sweep"] = 1;
  j["sweep"] = description;
  j["names"] = names;
  j["runs"] = runs;
  j["shard"] = shard_text(shard);
  if (!units.empty()) j["units"] = units;
  return j;
}

fs::path journal_path(const fs::path& directory) { return directory / ".journal.jsonl"; }

// The journal's text: the header and the complete lines (a line cut short by a kill has no
// newline and is dropped). Returns the byte count of the complete part.
struct JournalText {
  JournalContents contents;
  std::size_t complete_bytes = 0;
};

JournalText parse_journal(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("cannot read the sweep journal '{}'", path.string()));
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  JournalText out;
  std::size_t start = 0;
  int line_no = 0;
  while (start < text.size()) {
    const auto nl = text.find('\n', start);
    if (nl == std::string::npos) break;  // cut short: dropped
    ++line_no;
    const std::string_view line(text.data() + start, nl - start);
    const std::string where = fmt::format("{}:{}", path.string(), line_no);
    if (line_no == 1) {
      try {
        const Json h = Json::parse(line);
        out.contents.description = h.at("sweep").get<std::string>();
        out.contents.names = h.at("names").get<std::vector<std::string>>();
        out.contents.runs = whole_number(h.at("runs"), "runs");
        out.contents.shard = parse_shard(h.at("shard").get<std::string>());
        if (h.contains("units")) out.contents.units = h.at("units").get<SweepUnits>();
        if (whole_number(h.at("rigid_sweep"), "version") != 1) throw Error("version");
      } catch (const std::exception&) {
        throw Error(fmt::format("{}: not the header of a rigid sweep journal", where));
      }
    } else {
      out.contents.rows.push_back(row_from_json(line, where));
    }
    start = nl + 1;
    out.complete_bytes = start;
  }
  if (line_no == 0) throw Error(fmt::format("'{}' is empty; it is not a rigid sweep journal", path.string()));
  return out;
}

// the text of errno (thread-safe, unlike std::strerror: the journal's writer thread calls it)
std::string system_reason() { return std::error_code(errno, std::generic_category()).message(); }

void write_all(int fd, std::string_view bytes, const fs::path& path) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(fmt::format("cannot write the sweep journal '{}': {}", path.string(), system_reason()));
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

}  // namespace

GridAxis parse_grid_axis(std::string_view text) {
  constexpr std::string_view kExpected = "NAME=START:STOP:COUNT, e.g. theta.initial=0.1:2.5:25";
  auto [name, rest] = split_assignment(text, kExpected);
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const auto colon = rest.find(':', start);
    parts.push_back(rest.substr(start, colon - start));
    if (colon == std::string_view::npos) break;
    start = colon + 1;
  }
  if (parts.size() != 3) {
    throw Error(fmt::format("'{}' has {} field(s) after '='; expected {}", text, parts.size(), kExpected));
  }
  GridAxis axis{.name = name};
  const auto a = parse_double(parts[0]);
  const auto b = parse_double(parts[1]);
  if (!a || !b) {
    throw Error(fmt::format("'{}': START and STOP must be finite numbers, got '{}' and '{}'", text, trim(parts[0]),
                            trim(parts[1])));
  }
  axis.start = *a;
  axis.stop = *b;
  const std::string_view c = trim(parts[2]);
  std::uint64_t count = 0;
  const auto [end, ec] = std::from_chars(c.data(), c.data() + c.size(), count);
  if (c.empty() || ec != std::errc() || end != c.data() + c.size() || count < 1 || count > kMaxSweepRuns) {
    throw Error(fmt::format("'{}': COUNT must be a whole number from 1 to {}, got '{}'", text, kMaxSweepRuns, c));
  }
  axis.count = count;
  if (count == 1 && axis.start != axis.stop) {
    throw Error(fmt::format("'{}': one point cannot span {} to {}; give COUNT ≥ 2 or START = STOP", text,
                            axis.start, axis.stop));
  }
  return axis;
}

SampleAxis parse_sample_axis(std::string_view text) {
  constexpr std::string_view kExpected = "NAME=uniform(A,B), NAME=normal(MU,SIGMA) or NAME=loguniform(A,B)";
  auto [name, rest] = split_assignment(text, kExpected);
  rest = trim(rest);
  const auto open = rest.find('(');
  if (open == std::string_view::npos || rest.back() != ')') {
    throw Error(fmt::format("'{}' is not a distribution; expected {}", text, kExpected));
  }
  const std::string dist(trim(rest.substr(0, open)));
  const std::string_view args = rest.substr(open + 1, rest.size() - open - 2);
  SampleAxis axis{.name = name};
  if (dist == "uniform") {
    axis.distribution = Distribution::kUniform;
  } else if (dist == "normal") {
    axis.distribution = Distribution::kNormal;
  } else if (dist == "loguniform") {
    axis.distribution = Distribution::kLogUniform;
  } else {
    throw Error(fmt::format("'{}': unknown distribution '{}'; expected uniform, normal or loguniform{}", text, dist,
                            did_you_mean_hint(dist, {"uniform", "normal", "loguniform"})));
  }
  const auto comma = args.find(',');
  const auto a = comma == std::string_view::npos ? std::nullopt : parse_double(args.substr(0, comma));
  const auto b = comma == std::string_view::npos ? std::nullopt : parse_double(args.substr(comma + 1));
  if (!a || !b) throw Error(fmt::format("'{}': expected two finite numbers in {}(…, …)", text, dist));
  axis.a = *a;
  axis.b = *b;
  switch (axis.distribution) {
    case Distribution::kUniform:
      if (!(axis.a < axis.b)) throw Error(fmt::format("'{}': uniform(a, b) needs a < b", text));
      break;
    case Distribution::kNormal:
      if (!(axis.b > 0)) throw Error(fmt::format("'{}': normal(mu, sigma) needs sigma > 0", text));
      break;
    case Distribution::kLogUniform:
      if (!(axis.a > 0 && axis.a < axis.b)) throw Error(fmt::format("'{}': loguniform(a, b) needs 0 < a < b", text));
      break;
  }
  return axis;
}

void check_spec(const SweepSpec& spec) {
  if (spec.grid.empty() && spec.sample.empty()) {
    throw Error("a sweep needs a grid (NAME=START:STOP:COUNT) or a sample (NAME=DIST(A,B) and a sample count)");
  }
  if (!spec.grid.empty() && !spec.sample.empty()) {
    throw Error("a sweep is a grid or a sample, not both; give the grid axes or the sample axes");
  }
  if (!spec.sample.empty() && spec.samples < 1) throw Error("a sample needs a sample count of at least 1");
  if (!spec.grid.empty() && spec.samples > 0) throw Error("a sample count is for a sample; a grid has its counts");
  if (spec.samples > kMaxSweepRuns) throw Error(fmt::format("{} samples: at most {}", spec.samples, kMaxSweepRuns));
  const auto names = swept_names(spec);
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), names[i]) !=
        names.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw Error(fmt::format("'{}' is swept twice; give each name once", names[i]));
    }
    if (names[i] == "run" || names[i] == "error") {
      throw Error(fmt::format("'{}' names a column of runs.csv; a swept name cannot be 'run' or 'error'", names[i]));
    }
  }
  std::size_t total = 1;
  for (const auto& g : spec.grid) {
    if (g.count > kMaxSweepRuns / total) throw Error(fmt::format("the grid has more than {} runs", kMaxSweepRuns));
    total *= g.count;
  }
}

std::size_t run_count(const SweepSpec& spec) {
  if (!spec.sample.empty()) return spec.samples;
  std::size_t n = 1;
  for (const auto& g : spec.grid) n *= g.count;
  return spec.grid.empty() ? 0 : n;
}

std::vector<std::string> swept_names(const SweepSpec& spec) {
  std::vector<std::string> names;
  for (const auto& g : spec.grid) names.push_back(g.name);
  for (const auto& s : spec.sample) names.push_back(s.name);
  return names;
}

std::vector<double> run_values(const SweepSpec& spec, std::size_t index) {
  if (!spec.grid.empty()) {
    // mixed radix, the last axis fastest (the order of nested loops, of numpy's meshgrid
    // with indexing="ij" flattened in C order)
    std::vector<double> values(spec.grid.size(), 0.0);
    std::size_t rest = index;
    for (std::size_t k = spec.grid.size(); k-- > 0;) {
      const GridAxis& g = spec.grid[k];
      const std::size_t j = rest % g.count;
      rest /= g.count;
      // both ends exact; between them start + (stop − start)·j/(count − 1)
      if (j == 0) {
        values[k] = g.start;
      } else if (j + 1 == g.count) {
        values[k] = g.stop;
      } else {
        values[k] = g.start + (g.stop - g.start) * static_cast<double>(j) / static_cast<double>(g.count - 1);
      }
    }
    return values;
  }
  std::vector<double> values;
  values.reserve(spec.sample.size());
  for (std::size_t k = 0; k < spec.sample.size(); ++k) {
    values.push_back(sample_value(spec.sample[k], counter_uniform(spec.seed, index, k)));
  }
  return values;
}

// Counter-based rather than a stream (std::mt19937 and a std:: distribution): a run's numbers
// must not depend on which runs came before it in this process (threads, ranks and shards take
// runs in any order, a resumed sweep skips some), and the std:: distributions are
// implementation-defined (libstdc++ and libc++ give different normals from the same engine).
// A hash of (seed, index, axis) fed to the inverse CDF depends on nothing else.
double counter_uniform(std::uint64_t seed, std::uint64_t index, std::uint64_t axis) {
  const std::uint64_t h = splitmix64(splitmix64(splitmix64(seed) ^ index) ^ (axis + 0x632be59bd9b4e019ULL));
  // the 53 high bits as k·2⁻⁵³, moved by half a step: (k + ½)·2⁻⁵³ ∈ (0, 1), symmetric about ½
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

double sample_value(const SampleAxis& axis, double u) {
  switch (axis.distribution) {
    case Distribution::kUniform: return axis.a + (axis.b - axis.a) * u;
    case Distribution::kNormal:
      // boost's quantile is the inverse of the normal CDF to a few ulps, and the same on every
      // platform (it is computed, not drawn)
      return boost::math::quantile(boost::math::normal_distribution<double>(axis.a, axis.b), u);
    case Distribution::kLogUniform: {
      const double la = std::log(axis.a), lb = std::log(axis.b);
      return std::exp(la + (lb - la) * u);
    }
  }
  return kNaN;
}

std::string override_text(std::string_view name, double value) { return fmt::format("{}={}", name, value); }

Shard parse_shard(std::string_view text) {
  const auto slash = text.find('/');
  std::size_t i = 0, n = 0;
  bool ok = slash != std::string_view::npos;
  if (ok) {
    const auto a = text.substr(0, slash), b = text.substr(slash + 1);
    const auto ra = std::from_chars(a.data(), a.data() + a.size(), i);
    const auto rb = std::from_chars(b.data(), b.data() + b.size(), n);
    ok = !a.empty() && !b.empty() && ra.ec == std::errc() && ra.ptr == a.data() + a.size() &&
         rb.ec == std::errc() && rb.ptr == b.data() + b.size() && n >= 1 && i < n;
  }
  if (!ok) throw Error(fmt::format("shard '{}' is not I/N with 0 ≤ I < N (e.g. 0/3, 1/3, 2/3)", text));
  return {i, n};
}

std::string row_to_json(const SweepRow& row) {
  Json j;
  j["run"] = row.index;
  j["values"] = Json::array();
  for (double v : row.values) j["values"].push_back(number_json(v));
  j["results"] = Json::array();
  for (const auto& [name, v] : row.results) j["results"].push_back(Json::array({name, number_json(v)}));
  j["error"] = row.error;
  // nlohmann prints doubles in their shortest round-trip form, and escapes line breaks
  return j.dump();
}

SweepRow row_from_json(std::string_view line, std::string_view where) {
  try {
    const Json j = Json::parse(line);
    SweepRow row;
    row.index = whole_number(j.at("run"), "run");
    for (const auto& v : j.at("values")) row.values.push_back(number_from_json(v));
    for (const auto& r : j.at("results")) {
      row.results.emplace_back(r.at(0).get<std::string>(), number_from_json(r.at(1)));
    }
    row.error = j.at("error").get<std::string>();
    return row;
  } catch (const std::exception&) {
    throw Error(fmt::format("{}: not a row of a rigid sweep journal (the journal was edited or damaged; start "
                            "the sweep in another directory)",
                            where));
  }
}

std::string describe(const SweepIdentity& id) {
  std::string d = fmt::format("scene {} (fnv1a64 {})", id.scene.filename().string(), file_hash(id.scene));
  for (const auto& s : id.set) d += fmt::format("; set {}", s);
  if (!id.integrator.empty()) d += fmt::format("; integrator {}", id.integrator);
  if (id.model.pin_free_root) d += fmt::format("; pin_free_root {}", *id.model.pin_free_root);
  if (id.model.inertia_from_geometry) {
    d += fmt::format("; inertia_from_geometry {}", *id.model.inertia_from_geometry);
  }
  if (id.model.density) d += fmt::format("; density {}", *id.model.density);
  if (id.model.symbolic_inertia) d += fmt::format("; symbolic_inertia {}", *id.model.symbolic_inertia);
  for (const auto& g : id.spec.grid) d += fmt::format("; grid {}={}:{}:{}", g.name, g.start, g.stop, g.count);
  for (const auto& s : id.spec.sample) {
    d += fmt::format("; sample {}={}({},{})", s.name, distribution_name(s.distribution), s.a, s.b);
  }
  if (!id.spec.sample.empty()) d += fmt::format("; n {}; seed {}", id.spec.samples, id.spec.seed);
  return d;
}

// The rows waiting to be written, and the thread that writes them at most kDelay after the
// first of them came (a write per row, under a lock, was the serial part of a sweep of short
// runs: ~3 µs a row, 1.3% of a 0.2 ms run, 84% efficiency at 16 threads by itself). Rows come
// in under `mutex` and go out under it: each write(2) is of whole lines, in the order appended.
struct Journal::Writer {
  static constexpr std::size_t kWriteAt = 64 * 1024;                    // bytes waiting
  static constexpr std::chrono::milliseconds kDelay{100};             // the longest a row waits
  int fd;
  const fs::path& path;
  std::mutex mutex;
  std::condition_variable wake;
  std::string waiting;
  std::string failed;  // a write's error, thrown by the next append or flush
  bool closing = false;
  std::jthread thread;

  Writer(int fd_in, const fs::path& path_in) : fd(fd_in), path(path_in) {
    thread = std::jthread([this] { loop(); });
  }
  ~Writer() {
    {
      std::lock_guard lock(mutex);
      closing = true;
    }
    wake.notify_one();
    thread.join();  // the loop writes what is waiting before it returns
  }
  // under `mutex`
  void write_waiting() {
    if (waiting.empty() || !failed.empty()) return;
    try {
      write_all(fd, waiting, path);
    } catch (const Error& e) {
      failed = e.what();
    }
    waiting.clear();
  }
  void throw_if_failed() const {
    if (!failed.empty()) throw Error(failed);
  }
  void loop() {
    std::unique_lock lock(mutex);
    while (true) {
      wake.wait(lock, [&] { return closing || !waiting.empty(); });
      if (!closing) wake.wait_for(lock, kDelay, [&] { return closing; });
      write_waiting();
      if (closing) return;
    }
  }
};

Journal::Journal(const fs::path& directory, const std::string& description, const std::vector<std::string>& names,
                 std::size_t runs, Shard shard, const SweepUnits& units)
    : path_(journal_path(directory)), units_(units) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec || !fs::is_directory(directory)) {
    throw Error(fmt::format("cannot make the sweep directory '{}': {}", directory.string(),
                            ec ? ec.message() : "a file of that name is in the way"));
  }
  const std::string header = header_json(description, names, runs, shard, units).dump() + "\n";
  if (fs::exists(path_)) {
    const JournalText j = parse_journal(path_);
    const JournalContents& c = j.contents;
    if (c.description != description || c.names != names || c.runs != runs) {
      throw Error(fmt::format("'{}' holds another sweep ({}); this one is {}. Give another output directory, or "
                              "remove that one to start again",
                              directory.string(), c.description, description));
    }
    if (c.shard.index != shard.index || c.shard.count != shard.count) {
      throw Error(fmt::format("'{}' holds shard {} of this sweep, not shard {}; give each shard its own directory",
                              directory.string(), shard_text(c.shard), shard_text(shard)));
    }
    finished_ = c.rows;
    units_ = c.units;
    fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    // a line cut short by a kill is cut off, so the next row starts a line of its own
    if (fd_ >= 0 && ::ftruncate(fd_, static_cast<off_t>(j.complete_bytes)) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  } else {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ >= 0) write_all(fd_, header, path_);
  }
  if (fd_ < 0) throw Error(fmt::format("cannot write the sweep journal '{}': {}", path_.string(), system_reason()));
  writer_ = std::make_unique<Writer>(fd_, path_);
}

Journal::~Journal() {
  writer_.reset();  // what waits is written (an error now has no one to go to)
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(const SweepRow& row) {
  // whole lines, O_APPEND: a kill mid-write leaves a piece without its newline, which the next
  // open drops
  std::string line = row_to_json(row);
  line += '\n';
  bool first = false;
  {
    std::lock_guard lock(writer_->mutex);
    writer_->throw_if_failed();
    first = writer_->waiting.empty();
    writer_->waiting += line;
    if (writer_->waiting.size() >= Writer::kWriteAt) writer_->write_waiting();
    writer_->throw_if_failed();
  }
  if (first) writer_->wake.notify_one();
}

void Journal::flush() {
  std::lock_guard lock(writer_->mutex);
  writer_->write_waiting();
  writer_->throw_if_failed();
}

JournalContents read_journal(const fs::path& directory) {
  const fs::path p = journal_path(directory);
  if (!fs::is_regular_file(p)) {
    throw Error(fmt::format("'{}' holds no sweep journal (.journal.jsonl); expected the output directory of a "
                            "sweep or shard",
                            directory.string()));
  }
  return parse_journal(p).contents;
}

namespace {

// The overrides of one run: the sweep's `set`, then each swept name with the run's value.
std::vector<std::string> run_overrides(const SweepIdentity& id, const std::vector<std::string>& names,
                                       const std::vector<double>& values) {
  std::vector<std::string> set = id.set;
  for (std::size_t k = 0; k < names.size(); ++k) set.push_back(override_text(names[k], values[k]));
  return set;
}

}  // namespace

void check_overrides(const SweepIdentity& id) {
  check_spec(id.spec);
  Scene s = load_scene(id.scene, id.model);
  apply_overrides(s, run_overrides(id, swept_names(id.spec), run_values(id.spec, 0)));
}

namespace {

// Run 0 built and checked from the scene as read (`base`).
std::shared_ptr<const Model> first_run_model(const SweepIdentity& id, const Scene& base) {
  const auto names = swept_names(id.spec);
  const auto values = run_values(id.spec, 0);
  const std::vector<std::string> overrides = run_overrides(id, names, values);
  try {
    Scene first = base;
    apply_overrides(first, overrides);
    auto model = std::make_shared<const Model>(first);
    RunOptions ro;
    ro.integrator = id.integrator;
    model->check(ro);
    return model;
  } catch (const Error& e) {
    std::vector<std::string> what = overrides;
    if (!id.integrator.empty()) what.insert(what.begin(), fmt::format("integrator {}", id.integrator));
    throw Error(fmt::format("run 0 of the sweep ({}) is refused, so no run was started: {}",
                            what.empty() ? std::string("no overrides") : fmt::format("{}", fmt::join(what, ", ")),
                            e.what()));
  }
}

}  // namespace

std::shared_ptr<const Model> check_first_run(const SweepIdentity& id) {
  check_spec(id.spec);
  return first_run_model(id, load_scene(id.scene, id.model));
}

std::vector<SweepRow> run_sweep(const SweepIdentity& id, std::span<const std::size_t> indices,
                                const SweepRunOptions& options) {
  std::size_t at = 0;
  const RunIndexSource next = [&]() -> std::optional<std::size_t> {
    if (at == indices.size()) return std::nullopt;
    return indices[at++];
  };
  return run_sweep(id, next, indices.size(), options);
}

std::vector<SweepRow> run_sweep(const SweepIdentity& id, const RunIndexSource& next_index, std::size_t count,
                                const SweepRunOptions& options) {
  const auto names = swept_names(id.spec);
  // the rows of the runs made, as they finish (nothing is allocated per requested run: the
  // indices come from next_index one at a time)
  std::vector<SweepRow> rows;
  std::size_t made = 0;
  std::mutex take;  // next_index, and the first index held back for the prototype
  std::optional<std::size_t> first_index = next_index();
  bool first_taken = false;
  std::atomic<bool> stopped{false};
  std::mutex report;
  auto overrides_of = [&](const std::vector<double>& values) { return run_overrides(id, names, values); };

  // The scene is read once; a run is that scene with its overrides. The overrides change values
  // only (apply_overrides), so a coordinate scene's equations are derived once, before the runs,
  // for run 0 (whatever the slice: a shard or a resumed sweep shares the same prototype), and
  // every run's model shares them (Model(scene, like)), as it shares every mesh file as read: no
  // run pays for the derivation or reads a mesh. Run 0 is checked as its run would be; a
  // refusal there (an unknown integrator, a metric's missing column, a refused --set) is
  // every run's, so the sweep stops before any run.
  const Scene base = load_scene(id.scene, id.model);
  std::shared_ptr<const Model> prototype;
  if (first_index) prototype = options.first_run ? options.first_run : first_run_model(id, base);
  // The runs a worker takes at once. Runs of a free-body scene stepped by a splitting march
  // together (Model::run_batch: their rotations four bodies at a time in vector registers, each
  // run's result the bits of its run alone); up to kSweepBatch of them, fewer when the sweep is
  // short against its threads, so that every thread has runs. Other runs go one at a time.
  const std::size_t threads = std::clamp<std::size_t>(options.threads, 1, std::max<std::size_t>(count, 1));
  RunOptions run_options;
  run_options.integrator = id.integrator;
  run_options.control.cancel = options.cancel;
  const std::size_t batch = options.batch && prototype && prototype->batches(run_options)
                                ? std::clamp<std::size_t>(count / threads, 1, kSweepBatch)
                                : 1;
  auto take_indices = [&](std::vector<std::size_t>& indices) {
    indices.clear();
    std::lock_guard lock(take);
    while (indices.size() < batch) {
      std::optional<std::size_t> index;
      if (!first_taken) {
        first_taken = true;
        index = first_index;
      } else if (first_index) {
        index = next_index();
      }
      if (!index) break;
      indices.push_back(*index);
    }
  };
  auto fail = [&](SweepRow& row, std::string_view what) {
    row.results.clear();
    row.error = word_for(options.wording, what);
    if (row.error.empty()) row.error = "failed";
  };
  // one run asked for more memory than there is (its trajectory): that run fails, the sweep
  // goes on with the memory freed
  constexpr std::string_view kOutOfMemory =
      "out of memory: the run needs more memory than is available; lower its trajectory's size";
  // a run's row from its result (and its trajectory written when asked)
  auto record = [&](SweepRow& row, const Model& model, const RunResult& result) {
    try {
      for (const auto& m : result.summary.metrics) row.results.emplace_back(m.name, m.value);
      for (const auto& [n, v] : result.summary.diagnostics) row.results.emplace_back(n, v);
      if (!options.keep_trajectories.empty()) {
        const auto formats = model.output_formats();
        (void)io::write_run(options.keep_trajectories / fmt::format("{:05}", row.index), result, formats);
      }
    } catch (const Error& e) {
      fail(row, e.what());
    } catch (const std::bad_alloc&) {
      fail(row, kOutOfMemory);
    }
  };
  auto run_alone = [&](SweepRow& row, const Model& model) {
    try {
      record(row, model, model.run(run_options));
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      fail(row, e.what());
    } catch (const std::bad_alloc&) {
      fail(row, kOutOfMemory);
    }
  };
  auto run_indices = [&](std::span<const std::size_t> indices) {
    std::vector<SweepRow> done(indices.size());
    std::vector<std::optional<Model>> models(indices.size());
    std::vector<const Model*> built;
    std::vector<std::size_t> built_at;
    for (std::size_t i = 0; i < indices.size(); ++i) {
      SweepRow& row = done[i];
      row.index = indices[i];
      row.values = run_values(id.spec, row.index);
      try {
        Scene scene = base;
        apply_overrides(scene, overrides_of(row.values));
        models[i].emplace(scene, *prototype);
        built.push_back(&*models[i]);
        built_at.push_back(i);
      } catch (const Error& e) {
        fail(row, e.what());
      } catch (const std::bad_alloc&) {
        fail(row, kOutOfMemory);
      }
    }
    std::optional<std::vector<Model::BatchedRun>> batched;
    if (built.size() > 1) {
      try {
        batched = Model::run_batch(built, run_options);
      } catch (const std::bad_alloc&) {
        // the batch's memory at once is too much: each run alone, as without batching
      }
    }
    for (std::size_t j = 0; j < built.size(); ++j) {
      SweepRow& row = done[built_at[j]];
      if (!batched) {
        run_alone(row, *built[j]);
      } else if (Model::BatchedRun& b = (*batched)[j]; b.result) {
        record(row, *built[j], *b.result);
      } else {
        fail(row, b.error);
      }
    }
    batched.reset();
    models.clear();
    for (SweepRow& row : done) {
      if (options.journal) options.journal->append(row);
      std::lock_guard lock(report);
      if (options.on_row) options.on_row(row);
      if (options.keep_rows) rows.push_back(std::move(row));
      ++made;
    }
  };

  std::exception_ptr failure;
  std::mutex failure_lock;
  auto worker = [&] {
    std::vector<std::size_t> indices;
    while (true) {
      if (stopped || (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed))) return;
      try {
        take_indices(indices);
        if (indices.empty()) return;
        run_indices(indices);
      } catch (...) {
        // a cancellation, or an error outside a run (the journal cannot be written): stop all
        stopped = true;
        std::lock_guard lock(failure_lock);
        if (!failure) failure = std::current_exception();
        return;
      }
    }
  };
  {
    std::vector<std::jthread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
  }  // joined
  if (options.cancel != nullptr && options.cancel->load()) {
    throw Cancelled(fmt::format("the sweep stopped after {} of {} runs", made, count));
  }
  if (failure) std::rethrow_exception(failure);
  std::sort(rows.begin(), rows.end(), [](const SweepRow& a, const SweepRow& b) { return a.index < b.index; });
  return rows;
}

namespace {

// The quantiles summary.json gives of each result.
constexpr std::array<double, 5> kQuantiles{0.05, 0.25, 0.5, 0.75, 0.95};

// Quantile q of values by linear interpolation between order statistics (the default of
// numpy.quantile and R's type 7): h = (n − 1) q, x[⌊h⌋] + (h − ⌊h⌋)(x[⌊h⌋+1] − x[⌊h⌋]), x
// holding at ⌊h⌋ and ⌊h⌋ + 1 what a sort would put there.
double quantile_sorted(const std::vector<double>& x, double q) {
  const double h = static_cast<double>(x.size() - 1) * q;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, x.size() - 1);
  return x[lo] + (h - static_cast<double>(lo)) * (x[hi] - x[lo]);
}

// Puts the order statistics `at` (ascending positions in x) in place, as a full sort would,
// by selection (O(n log k) for k positions, against O(n log n): the summary of a sweep of many
// runs is made after the runs, serially, and needs seven of them per column).
void select_positions(std::vector<double>& x, std::span<const std::size_t> at, std::size_t begin, std::size_t end) {
  if (at.empty() || end - begin < 2) return;
  const std::size_t mid = at.size() / 2;
  const std::size_t k = at[mid];
  std::nth_element(x.begin() + static_cast<std::ptrdiff_t>(begin), x.begin() + static_cast<std::ptrdiff_t>(k),
                   x.begin() + static_cast<std::ptrdiff_t>(end));
  // x[begin, k) ≤ x[k] ≤ x(k, end): the positions below k are found in the left part alone
  select_positions(x, at.first(mid), begin, k);
  select_positions(x, at.subspan(mid + 1), k + 1, end);
}

}  // namespace

std::vector<FailureGroup> group_failures(const std::vector<std::string>& errors) {
  std::vector<FailureGroup> groups;
  std::map<std::string_view, std::size_t> at;  // message → its group
  for (std::size_t i = 0; i < errors.size(); ++i) {
    if (errors[i].empty()) continue;
    const auto [it, added] = at.try_emplace(errors[i], groups.size());
    if (added) groups.push_back({.message = errors[i], .count = 0, .runs = {}});
    FailureGroup& g = groups[it->second];
    ++g.count;
    if (g.runs.size() < kFailureGroupRuns) g.runs.push_back(i);
  }
  // most frequent first; groups were made in order of their first run, which breaks the ties
  std::stable_sort(groups.begin(), groups.end(),
                   [](const FailureGroup& a, const FailureGroup& b) { return a.count > b.count; });
  return groups;
}

SweepUnits sweep_units(const io::RunSchema& schema) {
  // the settings a sweep can set that are times (docs/scene-format.md, [simulation])
  SweepUnits units = {{"simulation.t_end", "s"}, {"simulation.dt", "s"}, {"simulation.output_dt", "s"}};
  // a unit "" is not known (a coordinate that may be a length or an angle, a scene's parameter)
  for (const io::Column& c : schema.columns) {
    if (c.unit.empty()) continue;
    if (c.quantity == io::Quantity::kCoordinate) units[c.owner + ".initial"] = c.unit;
    if (c.quantity == io::Quantity::kCoordinateRate) units[c.owner + ".velocity"] = c.unit;
  }
  for (const auto* group : {&schema.parameters, &schema.diagnostics, &schema.metrics}) {
    for (const io::Scalar& s : *group) {
      if (s.unit.empty()) continue;
      units[s.name] = s.unit;
      units["result." + s.name] = s.unit;  // a metric named like a swept name
    }
  }
  return units;
}

SweepOutputs make_outputs(const std::vector<std::string>& names, std::size_t runs, std::vector<SweepRow> rows,
                          const SweepUnits& units) {
  // the rows in run order, through a permutation (moving whole rows cost more than the rest of
  // the summary); each index once (a row run twice, e.g. by two shards that overlap, must agree)
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rows[a].index < rows[b].index; });
  std::vector<const SweepRow*> unique;
  unique.reserve(rows.size());
  for (const std::size_t at : order) {
    SweepRow& r = rows[at];
    if (r.index >= runs) throw Error(fmt::format("run {} is beyond the sweep's {} runs", r.index, runs));
    // a row of an edited or damaged journal: its swept values are the sweep's names, one each
    if (r.values.size() != names.size()) {
      throw Error(fmt::format("run {} holds {} swept value{}; the sweep has {} ({}): the journal was edited "
                              "or damaged; start the sweep again in a new directory",
                              r.index, r.values.size(), r.values.size() == 1 ? "" : "s", names.size(),
                              fmt::join(names, ", ")));
    }
    // one NaN whatever its sign and payload (x86's 0/0 has the sign bit set): a row read back
    // from the journal ("nan") and the same row kept in memory give the same runs.npy bytes
    for (double& v : r.values) v = std::isnan(v) ? kNaN : v;
    for (auto& [name, v] : r.results) v = std::isnan(v) ? kNaN : v;
    if (!unique.empty() && unique.back()->index == r.index) {
      if (row_to_json(*unique.back()) != row_to_json(r)) {
        throw Error(fmt::format("run {} was recorded twice with different results", r.index));
      }
      continue;
    }
    unique.push_back(&r);
  }
  if (unique.size() != runs) {
    std::vector<std::size_t> missing;
    std::size_t k = 0;
    for (std::size_t i = 0; i < runs && missing.size() < 10; ++i) {
      if (k < unique.size() && unique[k]->index == i) {
        ++k;
      } else {
        missing.push_back(i);
      }
    }
    throw Error(fmt::format("{} of the sweep's {} runs are missing (runs {}{})", runs - unique.size(), runs,
                            fmt::join(missing, ", "), runs - unique.size() > missing.size() ? ", …" : ""));
  }

  // the result columns: every name in index order of first appearance
  std::vector<std::string> columns{"run"};
  for (const auto& n : names) columns.push_back(n);
  std::vector<std::string> result_names;
  // where result i of a run, called n, is in result_names (its size when absent); a run's
  // results come in the order of the others', as a rule: position i is looked at first
  const auto result_position = [&](std::size_t i, const std::string& n) {
    if (i < result_names.size() && result_names[i] == n) return i;
    return static_cast<std::size_t>(std::find(result_names.begin(), result_names.end(), n) - result_names.begin());
  };
  for (const SweepRow* r : unique) {
    for (std::size_t i = 0; i < r->results.size(); ++i) {
      if (result_position(i, r->results[i].first) == result_names.size()) result_names.push_back(r->results[i].first);
    }
  }
  std::vector<std::string> result_columns;
  for (const auto& n : result_names) {
    const bool taken = std::find(columns.begin(), columns.end(), n) != columns.end() || n == "error";
    result_columns.push_back(taken ? "result." + n : n);
    columns.push_back(result_columns.back());
  }

  SweepOutputs out{.numbers = io::Table(columns), .errors = {}, .summary_json = {}, .failures = {}};
  std::vector<double> line(columns.size());
  std::vector<std::vector<double>> per_column(result_names.size());
  for (auto& c : per_column) c.reserve(unique.size());
  out.numbers.reserve_rows(unique.size());
  out.errors.reserve(unique.size());
  std::size_t failures = 0;
  for (const SweepRow* row : unique) {
    const SweepRow& r = *row;
    std::fill(line.begin(), line.end(), kNaN);
    line[0] = static_cast<double>(r.index);
    std::copy(r.values.begin(), r.values.end(), line.begin() + 1);
    for (std::size_t i = 0; i < r.results.size(); ++i) {
      line[1 + names.size() + result_position(i, r.results[i].first)] = r.results[i].second;
    }
    for (std::size_t k = 0; k < result_names.size(); ++k) {
      const double v = line[1 + names.size() + k];
      if (std::isfinite(v)) per_column[k].push_back(v);
    }
    out.numbers.add_row(line);
    out.errors.push_back(r.error);
    if (!r.error.empty()) ++failures;
  }

  out.failures = group_failures(out.errors);

  Json j;
  j["count"] = runs;
  j["failures"] = failures;
  j["failure_groups"] = Json::array();
  for (std::size_t k = 0; k < std::min(out.failures.size(), kFailureGroupsListed); ++k) {
    const FailureGroup& g = out.failures[k];
    j["failure_groups"].push_back(Json{{"message", g.message}, {"count", g.count}, {"runs", g.runs}});
  }
  if (out.failures.size() > kFailureGroupsListed) {
    std::size_t left_runs = 0;
    for (std::size_t k = kFailureGroupsListed; k < out.failures.size(); ++k) left_runs += out.failures[k].count;
    j["failure_groups_left_out"] = Json{{"groups", out.failures.size() - kFailureGroupsListed}, {"runs", left_runs}};
  }
  j["columns"] = columns;
  j["swept"] = names;
  // the units of the columns whose unit run 0's schema knows
  Json known = Json::object();
  for (std::size_t c = 1; c < columns.size(); ++c) {
    const auto u = units.find(columns[c]);
    if (u != units.end()) known[columns[c]] = u->second;
  }
  if (!known.empty()) j["units"] = known;
  j["results"] = Json::object();
  for (std::size_t k = 0; k < result_names.size(); ++k) {
    std::vector<double>& x = per_column[k];
    Json s;
    s["count"] = x.size();
    if (!x.empty()) {
      // sums in index order: the same bits whatever the threads or shards
      double sum = 0;
      for (double v : x) sum += v;
      const double mean = sum / static_cast<double>(x.size());
      double ss = 0;
      for (double v : x) ss += (v - mean) * (v - mean);
      s["mean"] = mean;
      s["std"] = x.size() > 1 ? Json(std::sqrt(ss / static_cast<double>(x.size() - 1))) : Json(nullptr);
      // the positions quantile_sorted reads, the first and the last: in place as if sorted
      std::vector<std::size_t> at{0, x.size() - 1};
      for (double p : kQuantiles) {
        const auto lo = static_cast<std::size_t>(std::floor(static_cast<double>(x.size() - 1) * p));
        at.push_back(lo);
        at.push_back(std::min(lo + 1, x.size() - 1));
      }
      std::sort(at.begin(), at.end());
      at.erase(std::unique(at.begin(), at.end()), at.end());
      select_positions(x, at, 0, x.size());
      s["min"] = x.front();
      s["max"] = x.back();
      Json q;
      for (double p : kQuantiles) q[fmt::format("{}", p)] = quantile_sorted(x, p);
      s["quantiles"] = q;
    }
    j["results"][result_columns[k]] = s;
  }
  out.summary_json = j.dump(2) + "\n";
  return out;
}

std::vector<fs::path> write_outputs(const fs::path& directory, const SweepOutputs& outputs, std::size_t threads) {
  io::write_file_atomically(directory / "runs.csv", io::to_csv(outputs.numbers, "error", outputs.errors, threads));
  io::write_file_atomically(directory / "runs.npy", io::to_npy(outputs.numbers));
  io::write_file_atomically(directory / "summary.json", outputs.summary_json);
  return {directory / "runs.csv", directory / "runs.npy", directory / "summary.json"};
}

}  // namespace rigid::scene
