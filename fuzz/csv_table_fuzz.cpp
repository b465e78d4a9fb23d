// Fuzz target: the CSV files `rigid report` and `rigid plot` read back from an output directory.
// Every input goes three ways:
//  1. io::read_csv, a run's trajectory.csv (what report::read_run reads): a table it reads must
//     write back (io::to_csv) to text that reads to the same table, bit for bit (NaN as NaN);
//  2. the input as the trajectory.csv of a run's directory (with a fixed summary.json):
//     report::plot_of_directory, the columns named by the input's header line (x the first, y
//     the last), then the SVG (report::svg_plot);
//  3. the input as the runs.csv of a sweep's directory (summary.json naming a swept value):
//     plot_of_directory through the sweep's reader (quoted error texts, RFC 4180), x the header's
//     second name (after `run`), y the one before `error`, then the SVG.
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "rigid/io/table.hpp"
#include "rigid/report/directory_plot.hpp"
#include "rigid/report/svg_plot.hpp"

namespace {

namespace fs = std::filesystem;

// a run's and a sweep's directory, each with its summary.json (written once)
fs::path make_directory(const char* name, const char* summary) {
  const fs::path dir = rigid::fuzz::scratch_dir() / name;
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json", std::ios::binary) << summary;
  return dir;
}

// the names of the input's first line, split at commas (as both readers split a header)
std::vector<std::string> header_names(std::string_view input) {
  std::string_view line = input.substr(0, input.find('\n'));
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::vector<std::string> names;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    names.emplace_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return names;
}

bool same(double a, double b) {
  return std::isnan(a) ? std::isnan(b)
                       : std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

void check_round_trip(const rigid::io::Table& table) try {
  const std::string path = (rigid::fuzz::scratch_dir() / "round_trip.csv").string();
  const std::string text = rigid::io::to_csv(table);
  (void)rigid::fuzz::write_scratch(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(),
                                   "round_trip.csv");
  const rigid::io::Table back = rigid::io::read_csv(path);
  bool equal = back.columns() == table.columns() && back.data().size() == table.data().size();
  for (std::size_t i = 0; equal && i < table.data().size(); ++i)
    equal = same(back.data()[i], table.data()[i]);
  if (!equal) {
    std::fprintf(stderr, "rigid fuzz: a CSV table does not read back as written\n");
    std::abort();
  }
} catch (const rigid::Error& e) {
  std::fprintf(stderr, "rigid fuzz: a CSV table written back is refused: %s\n", e.what());
  std::abort();
}

void plot(const fs::path& dir, std::string x, std::string y) {
  rigid::report::PlotRequest request;
  request.x = std::move(x);
  request.columns = {std::move(y)};
  (void)rigid::report::svg_plot(rigid::report::plot_of_directory(dir, request));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fs::path run_dir = make_directory(
      "csv_run", R"({"scene": "s.toml", "kind": "coordinates", "integrator": "rk4"})");
  static const fs::path sweep_dir = make_directory("csv_sweep", R"({"swept": ["a"]})");
  const std::string_view input = rigid::fuzz::as_text(data, size);
  const std::vector<std::string> names = header_names(input);

  const std::string trajectory = rigid::fuzz::write_scratch(data, size, "csv_run/trajectory.csv");
  std::optional<rigid::io::Table> table;
  rigid::fuzz::refuse_or_return(input, [&] { table = rigid::io::read_csv(trajectory); });
  if (table) check_round_trip(*table);
  rigid::fuzz::refuse_or_return(input, [&] { plot(run_dir, names.front(), names.back()); });

  (void)rigid::fuzz::write_scratch(data, size, "csv_sweep/runs.csv");
  const std::string x = names.size() > 1 ? names[1] : names.front();
  const std::string y = names.size() > 2 ? names[names.size() - 2] : names.front();
  rigid::fuzz::refuse_or_return(input, [&] { plot(sweep_dir, x, y); });
  return 0;
}
