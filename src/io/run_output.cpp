#include "rigid/io/run_output.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "detail/schema_json.hpp"
#include "detail/temporary.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"

namespace rigid::io {
namespace {

constexpr std::array<std::pair<OutputFormat, std::string_view>, 3> kFormats{{
    {OutputFormat::kCsv, "csv"}, {OutputFormat::kNpy, "npy"}, {OutputFormat::kJson, "json"}}};

}  // namespace

std::string_view to_string(OutputFormat format) {
  for (const auto& [f, name] : kFormats) {
    if (f == format) return name;
  }
  return "?";
}

OutputFormat parse_output_format(std::string_view name) {
  for (const auto& [f, n] : kFormats) {
    if (n == name) return f;
  }
  const std::vector<std::string> names = {"csv", "npy", "json"};
  throw Error(fmt::format("unknown output format '{}'{}; expected csv, npy or json", name,
                          did_you_mean_hint(name, names)));
}

std::string_view file_name(OutputFormat format) {
  switch (format) {
    case OutputFormat::kCsv: return "trajectory.csv";
    case OutputFormat::kNpy: return "trajectory.npy";
    case OutputFormat::kJson: return "summary.json";
  }
  return "?";
}

std::string summary_json(const RunResult& result) {
  const RunSummary& s = result.summary;
  nlohmann::ordered_json j;
  j["scene"] = s.scene;
  j["kind"] = to_string(s.kind);
  j["integrator"] = s.integrator;
  j["t_end"] = s.t_end;
  j["dt"] = s.dt;
  if (s.tolerance > 0) j["tolerance"] = s.tolerance;
  j["steps"] = s.steps;
  if (s.rhs_evaluations > 0) j["rhs_evaluations"] = s.rhs_evaluations;
  j["samples"] = s.samples;
  j["wall_time_s"] = s.wall_seconds;
  j["parameters"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : s.parameters) j["parameters"][name] = value;
  j["diagnostics"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : s.diagnostics) j["diagnostics"][name] = value;
  if (!s.metrics.empty()) {
    j["metrics"] = nlohmann::ordered_json::object();
    for (const Metric& m : s.metrics) {
      nlohmann::ordered_json e;
      // JSON has no NaN: an event that did not happen is null, with its note
      if (std::isfinite(m.value)) {
        e["value"] = m.value;
      } else {
        e["value"] = nullptr;
      }
      e["unit"] = m.unit;
      if (!m.note.empty()) e["note"] = m.note;
      j["metrics"][m.name] = std::move(e);
    }
  }
  const Table& t = result.trajectory;
  j["columns"] = t.columns();
  j["final"] = nlohmann::ordered_json::object();
  if (t.rows() > 0) {
    for (std::size_t c = 0; c < t.columns().size(); ++c) j["final"][t.columns()[c]] = t(t.rows() - 1, c);
  }
  j["warnings"] = s.warnings;
  if (!result.schema.columns.empty()) {
    RIGID_REQUIRE(result.schema.column_names() == t.columns(),
                  "the run's schema names the columns {}, its trajectory has {}",
                  fmt::join(result.schema.column_names(), ", "), fmt::join(t.columns(), ", "));
    j["schema"] = detail::schema_to_json(result.schema);
  }
  // nlohmann prints doubles in their shortest round-trip form
  return j.dump(2) + "\n";
}

std::string format_bytes(std::uint64_t bytes) {
  static constexpr const char* kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double v = static_cast<double>(bytes);
  std::size_t u = 0;
  while (v >= 1024.0 && u + 1 < std::size(kUnits)) {
    v /= 1024.0;
    ++u;
  }
  return u == 0 ? fmt::format("{} B", bytes) : fmt::format("{:.3g} {}", v, kUnits[u]);
}

std::uint64_t parse_memory_size(std::string_view text) {
  auto refuse = [&]() -> std::uint64_t {
    throw Error(fmt::format("memory size '{}' is not a size; expected bytes (2147483648) or a number "
                            "with a unit: KiB, MiB, GiB, TiB (or K, M, G, T), kB, MB, GB, TB "
                            "(e.g. 512MiB, 2GiB)",
                            text));
  };
  std::size_t i = 0;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) != 0 || text[i] == '.')) ++i;
  double number = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + i, number);
  if (i == 0 || ec != std::errc() || end != text.data() + i) return refuse();
  std::string_view unit = text.substr(i);
  while (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);
  static constexpr std::pair<std::string_view, double> kUnits[] = {
      {"", 1.0},      {"B", 1.0},      {"K", 0x1p10},   {"KiB", 0x1p10}, {"M", 0x1p20},
      {"MiB", 0x1p20}, {"G", 0x1p30},  {"GiB", 0x1p30}, {"T", 0x1p40},   {"TiB", 0x1p40},
      {"kB", 1e3},    {"KB", 1e3},     {"MB", 1e6},     {"GB", 1e9},     {"TB", 1e12}};
  for (const auto& [name, scale] : kUnits) {
    if (unit != name) continue;
    const double bytes = std::floor(number * scale);
    if (!(bytes >= 1.0)) {
      throw Error(fmt::format("memory size '{}' is zero; expected at least 1 byte", text));
    }
    if (!(bytes <= 0x1p63)) {
      throw Error(fmt::format("memory size '{}' is more than 2^63 bytes", text));
    }
    return static_cast<std::uint64_t>(bytes);
  }
  return refuse();
}

void check_trajectory_memory(std::size_t rows, std::size_t columns, std::uint64_t max_memory) {
  // as doubles first: rows × columns × 8 may not fit in 64 bits
  const double bytes = static_cast<double>(rows) * static_cast<double>(columns) * 8.0;
  if (bytes <= static_cast<double>(max_memory)) return;
  const auto needed = bytes < 0x1p63 ? static_cast<std::uint64_t>(bytes) : std::uint64_t{1} << 63;
  throw Error(fmt::format(
      "the trajectory would take {} rows × {} columns × 8 bytes = {} ({}), more than the memory "
      "limit of {}; use a larger [simulation] output_dt or a shorter t_end, or raise the limit "
      "with {}",
      rows, columns, needed, format_bytes(needed), format_bytes(max_memory),
      setting("max_memory", fmt::format("{:.0f}MiB", std::ceil(bytes / 0x1p20)))));
}

namespace {

namespace fs = std::filesystem;

// Text of the last system error.
std::string system_reason() { return std::strerror(errno); }

// `directory` made absolute with its symbolic links resolved (as far as it exists), so that
// the new set replaces the directory a link points to, not the link.
fs::path resolved(const fs::path& directory) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(directory, ec), ec);
  if (ec) p = fs::absolute(directory);
  // "out/" has an empty file name; the set is named by its last component
  if (!p.has_filename()) p = p.parent_path();
  return p;
}

// Removes a directory tree when it goes out of scope, unless released.
class RemoveOnExit {
 public:
  explicit RemoveOnExit(fs::path p) : path_(std::move(p)) {}
  RemoveOnExit(const RemoveOnExit&) = delete;
  RemoveOnExit& operator=(const RemoveOnExit&) = delete;
  ~RemoveOnExit() {
    if (path_.empty()) return;
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  void release() { path_.clear(); }

 private:
  fs::path path_;
};

void write_file(const fs::path& path, std::string_view contents) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw Error(fmt::format("cannot write '{}': {}", path.string(), system_reason()));
  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = n < 0 ? system_reason() : "nothing written";
      ::close(fd);
      throw Error(fmt::format("cannot write '{}': {}", path.string(), why));
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  const bool synced = ::fsync(fd) == 0;
  const std::string why = synced ? std::string() : system_reason();
  if (::close(fd) != 0 || !synced) {
    throw Error(fmt::format("cannot write '{}': {}", path.string(), synced ? system_reason() : why));
  }
}

void sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the data itself is already on disk
  (void)::fsync(fd);
  ::close(fd);
}

bool is_run_file(const std::string& name) {
  if (name == kReportFileName) return true;
  for (const auto& [f, _] : kFormats) {
    if (name == file_name(f)) return true;
  }
  return false;
}

}  // namespace

void check_output_directory(const fs::path& directory) {
  if (directory.empty()) throw Error("the output directory is empty; expected a path");
  const fs::path target = resolved(directory);
  std::error_code ec;
  const fs::file_status st = fs::status(target, ec);
  if (fs::exists(st) && !fs::is_directory(st)) {
    throw Error(fmt::format("the output directory '{}' is a file; expected a directory (or a path "
                            "where one can be made)",
                            directory.string()));
  }
  // the set replaces the directory as a whole: never the working directory or one holding it
  const fs::path cwd = fs::current_path(ec);
  if (!ec) {
    const fs::path here = fs::weakly_canonical(cwd, ec);
    if (std::mismatch(target.begin(), target.end(), here.begin(), here.end()).first == target.end()) {
      throw Error(fmt::format("the output directory '{}' is the working directory or holds it; a run "
                              "replaces its output directory as a whole: choose a directory of its "
                              "own, such as out/NAME",
                              directory.string()));
    }
  }
  // the new set is made beside the target: the nearest existing ancestor must be a writable
  // directory (the target's parent, or where the missing parents will be made)
  fs::path ancestor = target.parent_path();
  while (!ancestor.empty() && !fs::exists(ancestor, ec)) ancestor = ancestor.parent_path();
  if (ancestor.empty()) ancestor = "/";
  if (!fs::is_directory(ancestor, ec)) {
    throw Error(fmt::format("cannot make the output directory '{}': '{}' is a file, not a directory",
                            directory.string(), ancestor.string()));
  }
  if (::access(ancestor.c_str(), W_OK | X_OK) != 0) {
    throw Error(fmt::format("cannot write the output directory '{}': '{}' is not writable ({})",
                            directory.string(), ancestor.string(), system_reason()));
  }
}

std::vector<fs::path> write_run(const fs::path& directory, const RunResult& result,
                                std::span<const OutputFormat> formats, std::span<const ExtraFile> extra) {
  if (formats.empty()) throw Error("no output format selected; expected csv, npy or json");
  for ([[maybe_unused]] const ExtraFile& e : extra) {  // (unused where asserts are off: the bench build)
    RIGID_ASSERT(!e.name.empty() && e.name.find('/') == std::string::npos && e.name != "." && e.name != "..");
  }
  check_output_directory(directory);
  const fs::path target = resolved(directory);
  const fs::path parent = target.parent_path();
  const std::string name = target.filename().string();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) {
    throw Error(fmt::format("cannot create the output directory '{}': {}", directory.string(), ec.message()));
  }
  detail::remove_stale_temporaries(parent, name);

  // the set: the chosen files, and summary.json with trajectory.npy (it names the columns)
  std::vector<OutputFormat> chosen;
  for (const OutputFormat f : formats) {
    if (std::find(chosen.begin(), chosen.end(), f) == chosen.end()) chosen.push_back(f);
  }
  const bool npy = std::find(chosen.begin(), chosen.end(), OutputFormat::kNpy) != chosen.end();
  if (npy && std::find(chosen.begin(), chosen.end(), OutputFormat::kJson) == chosen.end()) {
    chosen.push_back(OutputFormat::kJson);
  }

  const fs::path temporary = parent / detail::temporary_name(name);
  if (::mkdir(temporary.c_str(), 0755) != 0) {
    throw Error(fmt::format("cannot create the output directory '{}': {}", directory.string(), system_reason()));
  }
  RemoveOnExit cleanup(temporary);

  // files a user keeps in the directory stay (hard links into the new set); a subdirectory is
  // refused, since the set replaces the directory as a whole
  const bool exists = fs::is_directory(target, ec);
  if (exists) {
    for (fs::directory_iterator it(target, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string entry = it->path().filename().string();
      if (is_run_file(entry)) continue;
      // temporaries of the old per-file writer (.trajectory.csv.tmpXXXXXXXX) are not carried
      if (entry.starts_with('.') && entry.find(".tmp") != std::string::npos) continue;
      if (it->is_directory(ec) && !it->is_symlink(ec)) {
        throw Error(fmt::format("the output directory '{}' holds the directory '{}'; a run replaces "
                                "its output directory as a whole, so it may hold files only: choose "
                                "a new or empty directory",
                                directory.string(), entry));
      }
      const fs::path copy = temporary / entry;
      std::error_code link_ec;
      if (it->is_symlink(ec)) {
        fs::copy_symlink(it->path(), copy, link_ec);
      } else {
        fs::create_hard_link(it->path(), copy, link_ec);
        if (link_ec) fs::copy_file(it->path(), copy, link_ec);
      }
      if (link_ec) {
        throw Error(fmt::format("cannot keep '{}' in the output directory '{}': {}", entry,
                                directory.string(), link_ec.message()));
      }
    }
    if (ec) throw Error(fmt::format("cannot read the output directory '{}': {}", directory.string(), ec.message()));
  }

  std::vector<fs::path> written;
  for (const OutputFormat f : chosen) {
    const fs::path path = temporary / file_name(f);
    switch (f) {
      case OutputFormat::kCsv: write_file(path, to_csv(result.trajectory)); break;
      case OutputFormat::kNpy: write_file(path, to_npy(result.trajectory)); break;
      case OutputFormat::kJson: write_file(path, summary_json(result)); break;
    }
    written.push_back(directory / file_name(f));
  }
  for (const ExtraFile& e : extra) {
    write_file(temporary / e.name, e.contents);
    written.push_back(directory / e.name);
  }
  sync_directory(temporary);

  // into place in one step: a new directory by rename, an existing one by an exchange (the
  // old set then sits at the temporary's name and is removed)
  if (!exists) {
    if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, target.c_str(), RENAME_NOREPLACE) == 0) {
      cleanup.release();
      sync_directory(parent);
      return written;
    }
    if (errno != EEXIST && errno != EINVAL && errno != ENOSYS) {
      throw Error(fmt::format("cannot write the output directory '{}': {}", directory.string(), system_reason()));
    }
    if (errno != EEXIST && ::rename(temporary.c_str(), target.c_str()) == 0) {
      cleanup.release();
      sync_directory(parent);
      return written;
    }
    // made by another process meanwhile: exchange below
  }
  if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno != EINVAL && errno != ENOSYS) {
      throw Error(fmt::format("cannot write the output directory '{}': {}", directory.string(), system_reason()));
    }
    // a file system without the exchange: the old set steps aside, the new one takes its
    // place (a reader in between finds no set, never a mix)
    const fs::path old = parent / detail::temporary_name(name);
    if (::rename(target.c_str(), old.c_str()) != 0) {
      throw Error(fmt::format("cannot write the output directory '{}': {}", directory.string(), system_reason()));
    }
    if (::rename(temporary.c_str(), target.c_str()) != 0) {
      const std::string why = system_reason();
      (void)::rename(old.c_str(), target.c_str());  // the old set back in its place
      throw Error(fmt::format("cannot write the output directory '{}': {}", directory.string(), why));
    }
    cleanup.release();
    RemoveOnExit remove_old(old);
    sync_directory(parent);
    return written;
  }
  // `temporary` now holds the old set; `cleanup` removes it
  sync_directory(parent);
  return written;
}

}  // namespace rigid::io
