#include "rigid/io/run_output.hpp"

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/expect_error.hpp"

namespace rigid::io {
namespace {

RunResult sample_run() {
  RunResult r;
  r.trajectory = Table({"t", "x"});
  const double rows[3][2] = {{0.0, 1.0}, {0.5, 0.1}, {1.0, -0.2}};
  for (const auto& row : rows) r.trajectory.add_row(row);
  r.summary.scene = "s.toml";
  r.summary.kind = rigid::io::RunKind::kCoordinates;
  r.summary.integrator = "rk4";
  r.summary.t_end = 1.0;
  r.summary.dt = 0.1;
  r.summary.steps = 10;
  r.summary.samples = 3;
  r.summary.parameters = {{"m", 0.1}};
  r.summary.diagnostics = {{"energy_max_change", 1e-17}};
  r.summary.warnings = {"a warning"};
  return r;
}

TEST(RunOutput, SummaryJsonHoldsTheRunAndTheLastRow) {
  const auto j = nlohmann::json::parse(summary_json(sample_run()));
  EXPECT_EQ(j["scene"], "s.toml");
  EXPECT_EQ(j["integrator"], "rk4");
  EXPECT_EQ(j["steps"], 10);
  EXPECT_EQ(j["parameters"]["m"].get<double>(), 0.1);  // shortest round trip: exact
  EXPECT_EQ(j["diagnostics"]["energy_max_change"].get<double>(), 1e-17);
  EXPECT_EQ(j["final"]["x"].get<double>(), -0.2);
  EXPECT_EQ(j["columns"].size(), 2u);
  EXPECT_FALSE(j.contains("tolerance"));  // fixed-step: no tolerance
  EXPECT_EQ(j["warnings"][0], "a warning");
}

// Metrics in file order, each {value, unit}; an event that did not happen is null (JSON has no
// NaN) with its note; a run without metrics has no "metrics" key.
TEST(RunOutput, SummaryJsonHoldsTheMetricsWithUnitsAndNotes) {
  EXPECT_FALSE(nlohmann::json::parse(summary_json(sample_run())).contains("metrics"));
  RunResult r = sample_run();
  r.summary.metrics = {{"period", 1.75, "s", ""}, {"z", 0.5, "", ""},
                       {"third", std::numeric_limits<double>::quiet_NaN(), "s", "2 crossing(s)"}};
  const auto j = nlohmann::ordered_json::parse(summary_json(r));
  ASSERT_EQ(j["metrics"].size(), 3u);
  EXPECT_EQ(j["metrics"].begin().key(), "period");
  EXPECT_EQ(j["metrics"]["period"]["value"].get<double>(), 1.75);
  EXPECT_EQ(j["metrics"]["period"]["unit"], "s");
  EXPECT_FALSE(j["metrics"]["period"].contains("note"));
  EXPECT_EQ(j["metrics"]["z"]["unit"], "");
  EXPECT_TRUE(j["metrics"]["third"]["value"].is_null());
  EXPECT_EQ(j["metrics"]["third"]["note"], "2 crossing(s)");
}

TEST(RunOutput, WritesTheChosenFilesIntoANewDirectory) {
  const auto dir = std::filesystem::temp_directory_path() / "rigid_run_output_test" / "nested";
  std::filesystem::remove_all(dir.parent_path());
  const OutputFormat formats[] = {OutputFormat::kCsv, OutputFormat::kJson};
  const auto written = write_run(dir, sample_run(), formats);
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[0], dir / "trajectory.csv");
  EXPECT_TRUE(std::filesystem::exists(dir / "summary.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "trajectory.npy"));
  // the CSV reads back to the same numbers
  const Table back = read_csv(dir / "trajectory.csv");
  EXPECT_EQ(back.data(), sample_run().trajectory.data());
  std::filesystem::remove_all(dir.parent_path());
}

TEST(RunOutput, FormatNamesAndErrors) {
  EXPECT_EQ(parse_output_format("npy"), OutputFormat::kNpy);
  EXPECT_EQ(file_name(OutputFormat::kJson), "summary.json");
  EXPECT_RIGID_ERROR((void)parse_output_format("jsn"), "unknown output format 'jsn'; did you mean 'json'?");
  EXPECT_RIGID_ERROR((void)write_run("x", sample_run(), {}), "no output format selected");
  // a file where the directory should be
  const auto file = std::filesystem::temp_directory_path() / "rigid_run_output_file";
  std::ofstream(file) << "x";
  const OutputFormat csv[] = {OutputFormat::kCsv};
  EXPECT_RIGID_ERROR((void)write_run(file, sample_run(), csv), "is a file; expected a directory");
  EXPECT_RIGID_ERROR(check_output_directory(file), "is a file; expected a directory");
  EXPECT_RIGID_ERROR(check_output_directory(file / "below"), "is a file, not a directory");
  // the working directory would be replaced as a whole
  EXPECT_RIGID_ERROR(check_output_directory("."), "is the working directory or holds it");
  std::filesystem::remove(file);
}

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

RunResult other_run() {
  RunResult r = sample_run();
  r.summary.steps = 99;
  r.trajectory = Table({"t", "y"});
  const double row[] = {0.0, 7.0};
  r.trajectory.add_row(row);
  return r;
}

// A new set replaces the old one as a whole: a file of the old run that the new one does not
// write is gone with it (no new trajectory.csv beside an old summary.json); a user's own file
// stays; nothing temporary is left beside the directory.
TEST(RunOutput, ANewSetReplacesTheOldOneWhole) {
  const fs::path root = fs::temp_directory_path() / "rigid_run_set_test";
  fs::remove_all(root);
  const fs::path dir = root / "run";
  const OutputFormat all[] = {OutputFormat::kCsv, OutputFormat::kJson};
  (void)write_run(dir, sample_run(), all);
  std::ofstream(dir / "notes.txt") << "mine";
  const OutputFormat csv[] = {OutputFormat::kCsv};
  (void)write_run(dir, other_run(), csv);
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"notes.txt", "trajectory.csv"}));
  EXPECT_EQ(read(dir / "trajectory.csv"), to_csv(other_run().trajectory));
  EXPECT_EQ(read(dir / "notes.txt"), "mine");
  EXPECT_EQ(entries(root), std::vector<std::string>{"run"});
  fs::remove_all(root);
}

// An extra file (the report page) is part of the set: written with the others, and an older
// run's copy is not carried into a set that does not write one (it would describe another run).
TEST(RunOutput, AnExtraFileIsPartOfTheSet) {
  const fs::path root = fs::temp_directory_path() / "rigid_run_extra_test";
  fs::remove_all(root);
  const fs::path dir = root / "run";
  const OutputFormat csv[] = {OutputFormat::kCsv};
  const ExtraFile page[] = {{std::string(kReportFileName), "<!doctype html>page"}};
  const auto written = write_run(dir, sample_run(), csv, page);
  EXPECT_EQ(written, (std::vector<fs::path>{dir / "trajectory.csv", dir / "report.html"}));
  EXPECT_EQ(read(dir / "report.html"), "<!doctype html>page");
  (void)write_run(dir, other_run(), csv);
  EXPECT_EQ(entries(dir), std::vector<std::string>{"trajectory.csv"});
  EXPECT_EQ(entries(root), std::vector<std::string>{"run"});
  fs::remove_all(root);
}

// trajectory.npy has no column names: summary.json (which lists them) comes with it.
TEST(RunOutput, NpyComesWithItsColumnNames) {
  const fs::path dir = fs::temp_directory_path() / "rigid_run_npy_test";
  fs::remove_all(dir);
  const OutputFormat npy[] = {OutputFormat::kNpy};
  const auto written = write_run(dir, sample_run(), npy);
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[1], dir / "summary.json");
  const auto j = nlohmann::json::parse(read(dir / "summary.json"));
  EXPECT_EQ(j["columns"], nlohmann::json::array({"t", "x"}));
  fs::remove_all(dir);
}

// A write that fails half way (the disk full: here the file size limit, EFBIG) leaves the old
// set exactly as it was and no temporary behind; a temporary of a killed run (a process that no
// longer exists) is removed by the next write, one of a live process is left alone.
TEST(RunOutput, AFailedWriteLeavesTheOldSetAndStaleTemporariesAreRemoved) {
  const fs::path root = fs::temp_directory_path() / "rigid_run_fail_test";
  fs::remove_all(root);
  const fs::path dir = root / "run";
  const OutputFormat all[] = {OutputFormat::kCsv, OutputFormat::kJson};
  (void)write_run(dir, sample_run(), all);
  const std::string csv_before = read(dir / "trajectory.csv");
  const std::string json_before = read(dir / "summary.json");

  RunResult big = other_run();
  const double row[] = {1.0, 2.0};
  for (int k = 0; k < 20000; ++k) big.trajectory.add_row(row);
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 64 * 1024;  // the CSV of `big` is larger; summary.json is smaller
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  EXPECT_RIGID_ERROR((void)write_run(dir, big, all), "cannot write");
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  EXPECT_EQ(read(dir / "trajectory.csv"), csv_before);
  EXPECT_EQ(read(dir / "summary.json"), json_before);
  EXPECT_EQ(entries(root), std::vector<std::string>{"run"});

  // pid 2^22 + 1 is above the kernel's pid_max (4194304): no such process
  fs::create_directories(root / ".run.rigid-tmp-4194305-0000abcd");
  std::ofstream(root / ".run.rigid-tmp-4194305-0000abcd" / "trajectory.csv") << "partial";
  const std::string live = ".run.rigid-tmp-" + std::to_string(::getppid()) + "-00001234";
  fs::create_directories(root / live);
  (void)write_run(dir, other_run(), all);
  EXPECT_EQ(entries(root), (std::vector<std::string>{live, "run"}));
  fs::remove_all(root);
}

}  // namespace
}  // namespace rigid::io
