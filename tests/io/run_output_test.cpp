#include "rigid/io/run_output.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

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
  r.summary.kind = "coordinates";
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
  EXPECT_RIGID_ERROR((void)write_run(file, sample_run(), csv), "cannot create the output directory");
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace rigid::io
