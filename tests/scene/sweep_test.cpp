#include "rigid/scene/sweep.hpp"

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rigid/io/table.hpp"
#include "rigid/lagrange/symbolic_core.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "support/expect_error.hpp"
#include "support/scenes.hpp"

namespace rigid::scene {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  // one folder per test process: ctest -j runs several at once
  const fs::path dir = fs::temp_directory_path() / fmt::format("rigid_sweep_test_{}_{}", name, ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(SweepGrid, ValuesIncludeBothEndsAndAreEquallySpaced) {
  const GridAxis a = parse_grid_axis("theta.initial=0.1:2.5:25");
  EXPECT_EQ(a.name, "theta.initial");
  SweepSpec spec{.grid = {a}};
  check_spec(spec);
  ASSERT_EQ(run_count(spec), 25u);
  EXPECT_EQ(run_values(spec, 0)[0], 0.1);   // exact: the ends are the given numbers
  EXPECT_EQ(run_values(spec, 24)[0], 2.5);
  for (std::size_t j = 1; j < 24; ++j) {
    // 0.1 + 0.1·j, to the rounding of one product and one sum (2 ulps of 2.5)
    EXPECT_NEAR(run_values(spec, j)[0], 0.1 + 0.1 * static_cast<double>(j), 2 * 4.5e-16) << j;
  }
}

TEST(SweepGrid, CartesianOrderHasTheLastAxisFastest) {
  SweepSpec spec{.grid = {parse_grid_axis("a=0:1:2"), parse_grid_axis("b=10:30:3")}};
  ASSERT_EQ(run_count(spec), 6u);
  const std::vector<std::vector<double>> expected{{0, 10}, {0, 20}, {0, 30}, {1, 10}, {1, 20}, {1, 30}};
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(run_values(spec, i), expected[i]) << i;
  EXPECT_EQ(swept_names(spec), (std::vector<std::string>{"a", "b"}));
}

TEST(SweepSample, UniformNumbersDependOnlyOnSeedIndexAndAxis) {
  // the same (seed, index, axis) gives the same bits whatever was drawn before
  const double u = counter_uniform(7, 123, 1);
  for (std::uint64_t i = 0; i < 200; ++i) (void)counter_uniform(7, i, 0);
  EXPECT_EQ(counter_uniform(7, 123, 1), u);
  EXPECT_NE(counter_uniform(8, 123, 1), u);
  EXPECT_NE(counter_uniform(7, 124, 1), u);
  EXPECT_NE(counter_uniform(7, 123, 0), u);
  for (std::uint64_t i = 0; i < 1000; ++i) {
    const double v = counter_uniform(0, i, 0);
    EXPECT_GT(v, 0.0);
    EXPECT_LT(v, 1.0);
  }
}

TEST(SweepSample, MomentsMatchTheDistributions) {
  // n draws; the sample mean is within 5 standard errors (σ/√n) of the mean: a false alarm
  // has probability 6e-7, and the draws are fixed (seed 1), so the test is deterministic
  constexpr std::size_t n = 20000;
  SweepSpec spec{.sample = {parse_sample_axis("u=uniform(2,3)"), parse_sample_axis("x=normal(1,0.1)"),
                            parse_sample_axis("l=loguniform(1e-3,1e3)")},
                 .samples = n,
                 .seed = 1};
  check_spec(spec);
  std::vector<double> u, x, l;
  for (std::size_t i = 0; i < n; ++i) {
    const auto v = run_values(spec, i);
    u.push_back(v[0]);
    x.push_back(v[1]);
    l.push_back(std::log10(v[2]));
  }
  auto mean = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()); };
  const double se = 1 / std::sqrt(static_cast<double>(n));
  EXPECT_NEAR(mean(u), 2.5, 5 * se / std::sqrt(12.0));  // σ of uniform(2,3) = 1/√12
  EXPECT_NEAR(mean(x), 1.0, 5 * 0.1 * se);
  EXPECT_NEAR(mean(l), 0.0, 5 * 6 / std::sqrt(12.0) * se);  // log10 is uniform on (−3, 3)
  EXPECT_GE(*std::min_element(u.begin(), u.end()), 2.0);
  EXPECT_LT(*std::max_element(u.begin(), u.end()), 3.0);
  const double mx = mean(x);
  double ss = 0;
  for (double v : x) ss += (v - mx) * (v - mx);
  // the sample variance's standard error is σ²·√(2/(n−1)) for a normal
  EXPECT_NEAR(ss / (n - 1), 0.01, 5 * 0.01 * std::sqrt(2.0 / (n - 1)));
}

TEST(SweepSample, NormalIsTheInverseCdf) {
  const SampleAxis z = parse_sample_axis("z=normal(0,1)");
  // Φ⁻¹(0.975) = 1.959963984540054 (tables); to 4 ulps
  EXPECT_NEAR(sample_value(z, 0.975), 1.959963984540054, 4 * 2.2e-16 * 2);
  EXPECT_EQ(sample_value(z, 0.5), 0.0);
  // symmetry Φ⁻¹(1 − u) = −Φ⁻¹(u) (u and 1 − u both exact), to a few ulps of the value
  for (double u : {0x1p-30, 0x1p-7, 0.25}) EXPECT_NEAR(sample_value(z, 1 - u), -sample_value(z, u), 1e-14 * 7) << u;
  const SampleAxis s = parse_sample_axis("s=normal(10,2)");
  EXPECT_NEAR(sample_value(s, 0.975), 10 + 2 * 1.959963984540054, 4 * 2.2e-16 * 14);
}

TEST(SweepSpec, BadTextIsRefusedWithWhatWasExpected) {
  EXPECT_RIGID_ERROR((void)parse_grid_axis("L=1:2"), "expected NAME=START:STOP:COUNT");
  EXPECT_RIGID_ERROR((void)parse_grid_axis("L"), "is not an assignment");
  EXPECT_RIGID_ERROR((void)parse_grid_axis("L=1:2:0"), "COUNT must be a whole number");
  EXPECT_RIGID_ERROR((void)parse_grid_axis("L=1:2:2.5"), "COUNT must be a whole number");
  EXPECT_RIGID_ERROR((void)parse_grid_axis("L=a:2:3"), "START and STOP must be finite numbers");
  EXPECT_RIGID_ERROR((void)parse_grid_axis("L=nan:2:3"), "START and STOP must be finite numbers");
  EXPECT_RIGID_ERROR((void)parse_grid_axis("L=1:2:1"), "one point cannot span");
  EXPECT_RIGID_ERROR((void)parse_sample_axis("I2=gauss(1,2)"), "unknown distribution 'gauss'");
  EXPECT_RIGID_ERROR((void)parse_sample_axis("I2=normall(1,2)"), "did you mean 'normal'");
  EXPECT_RIGID_ERROR((void)parse_sample_axis("I2=normal(1,0)"), "sigma > 0");
  EXPECT_RIGID_ERROR((void)parse_sample_axis("I2=uniform(2,1)"), "a < b");
  EXPECT_RIGID_ERROR((void)parse_sample_axis("I2=loguniform(0,1)"), "0 < a < b");
  EXPECT_RIGID_ERROR((void)parse_sample_axis("I2=uniform(1)"), "two finite numbers");
  EXPECT_RIGID_ERROR((void)parse_shard("3/3"), "0 ≤ I < N");
  EXPECT_RIGID_ERROR((void)parse_shard("1"), "0 ≤ I < N");
  EXPECT_RIGID_ERROR(check_spec(SweepSpec{}), "needs a grid");
  EXPECT_RIGID_ERROR(check_spec(SweepSpec{.grid = {parse_grid_axis("a=0:1:2"), parse_grid_axis("a=0:1:3")}}),
                     "'a' is swept twice");
  EXPECT_RIGID_ERROR(check_spec(SweepSpec{.sample = {parse_sample_axis("a=uniform(0,1)")}}), "sample count");
  // 2^17 · 2^17 = 2^34 runs: more than the bound, refused before anything is allocated
  EXPECT_RIGID_ERROR(check_spec(SweepSpec{.grid = {parse_grid_axis("a=0:1:131072"), parse_grid_axis("b=0:1:131072")}}),
                     "more than");
}

TEST(SweepRow, JsonRoundTripsEveryBitAndText) {
  const double inf = std::numeric_limits<double>::infinity();
  const SweepRow row{.index = 17,
                     .values = {0.1, 1e-300, -2.5},
                     .results = {{"period", 1.7466013148237887}, {"t_flip", std::nan("")}, {"big", inf}},
                     .error = "a \"quoted\", two-line\nmessage"};
  const SweepRow back = row_from_json(row_to_json(row), "test");
  EXPECT_EQ(back.index, 17u);
  EXPECT_EQ(back.values, row.values);
  ASSERT_EQ(back.results.size(), 3u);
  EXPECT_EQ(back.results[0], row.results[0]);
  EXPECT_TRUE(std::isnan(back.results[1].second));
  EXPECT_EQ(back.results[2].second, inf);
  EXPECT_EQ(back.error, row.error);
  EXPECT_EQ(row_to_json(row).find('\n'), std::string::npos);  // one line
  EXPECT_RIGID_ERROR((void)row_from_json("{\"run\":1}", "journal:3"), "journal:3: not a row");
}

TEST(SweepOutputs, CsvHasOneRowPerRunInIndexOrderAndStatistics) {
  std::vector<SweepRow> rows;
  for (std::size_t i : {3u, 0u, 2u, 1u}) {
    SweepRow r{.index = i, .values = {static_cast<double>(i) / 2}};
    if (i == 2) {
      r.error = "diverged, at t = 1";
    } else {
      r.results = {{"x", static_cast<double>(i * i)}};
    }
    rows.push_back(r);
  }
  const SweepOutputs out = make_outputs({"a"}, 4, rows);
  EXPECT_EQ(io::to_csv(out.numbers, "error", out.errors),
            "run,a,x,error\n0,0,0,\n1,0.5,1,\n2,1,nan,\"diverged, at t = 1\"\n3,1.5,9,\n");
  // x over the runs that have it: 0, 1, 9 → mean 10/3, std (n−1) √((100/9 + 49/9 + 289/9)/2),
  // median 1, quantile 0.25 at h = 0.5 → 0.5 (numpy.quantile's linear rule)
  const auto j = nlohmann::json::parse(out.summary_json);
  EXPECT_EQ(j["count"], 4);
  EXPECT_EQ(j["failures"], 1);
  EXPECT_DOUBLE_EQ(j["results"]["x"]["mean"].get<double>(), 10.0 / 3);
  EXPECT_DOUBLE_EQ(j["results"]["x"]["std"].get<double>(), std::sqrt((100.0 / 9 + 49.0 / 9 + 289.0 / 9) / 2));
  EXPECT_EQ(j["results"]["x"]["quantiles"]["0.5"].get<double>(), 1.0);
  EXPECT_EQ(j["results"]["x"]["quantiles"]["0.25"].get<double>(), 0.5);
  EXPECT_EQ(j["results"]["x"]["max"].get<double>(), 9.0);
}

TEST(SweepOutputs, UnitsAreStatedForTheColumnsThatHaveOne) {
  const std::vector<SweepRow> rows{{.index = 0, .values = {1}, .results = {{"x", 2}, {"a", 3}, {"n", 4}}}};
  // "x" has a unit, the swept "a" has one, its namesake result is "result.a"; "n" has none; a
  // unit of a name the sweep does not hold is not listed
  const SweepUnits units{{"x", "J"}, {"a", "s"}, {"result.a", "m"}, {"other", "kg"}};
  const auto j = nlohmann::json::parse(make_outputs({"a"}, 1, rows, units).summary_json);
  EXPECT_EQ(j["units"], nlohmann::json({{"a", "s"}, {"x", "J"}, {"result.a", "m"}}));
  EXPECT_FALSE(nlohmann::json::parse(make_outputs({"a"}, 1, rows).summary_json).contains("units"));
}

TEST(SweepJournal, TheHeaderKeepsTheUnitsOfTheSweepThatStartedIt) {
  const fs::path dir = temp_dir("units");
  const SweepUnits units{{"x", "J"}, {"simulation.t_end", "s"}};
  { Journal j(dir, "sweep A", {"a"}, 2, Shard{}, units); }
  EXPECT_EQ(read_journal(dir).units, units);
  // reopened (a resumed sweep) with other units: the journal's stay
  { Journal j(dir, "sweep A", {"a"}, 2, Shard{}, SweepUnits{{"x", "kJ"}}); }
  EXPECT_EQ(read_journal(dir).units, units);
  fs::remove_all(dir);
  // a journal without units (an older rigid's) has none
  { Journal j(dir, "sweep A", {"a"}, 2, Shard{}); }
  EXPECT_TRUE(read_journal(dir).units.empty());
  fs::remove_all(dir);
}

TEST(SweepOutputs, MissingOrConflictingRunsAreRefused) {
  std::vector<SweepRow> rows{{.index = 0}, {.index = 2}};
  EXPECT_RIGID_ERROR((void)make_outputs({}, 4, rows), "2 of the sweep's 4 runs are missing (runs 1, 3)");
  rows = {{.index = 0}, {.index = 0, .error = "x"}};
  EXPECT_RIGID_ERROR((void)make_outputs({}, 1, rows), "run 0 was recorded twice with different results");
}

TEST(SweepJournal, KeepsRowsRefusesAnotherSweepAndDropsACutLine) {
  const fs::path dir = temp_dir("journal");
  {
    Journal j(dir, "sweep A", {"a"}, 3, Shard{});
    EXPECT_TRUE(j.finished().empty());
    j.append(SweepRow{.index = 2, .values = {1.5}, .results = {{"x", 2}}});
  }
  // a kill in the middle of a write leaves a line without its newline
  {
    std::ofstream(dir / ".journal.jsonl", std::ios::app) << "{\"run\":0,\"val";
  }
  {
    Journal j(dir, "sweep A", {"a"}, 3, Shard{});
    ASSERT_EQ(j.finished().size(), 1u);
    EXPECT_EQ(j.finished()[0].index, 2u);
    j.append(SweepRow{.index = 0, .values = {0.5}});
  }
  EXPECT_EQ(read_journal(dir).rows.size(), 2u);  // the cut line is gone, the new one whole
  EXPECT_RIGID_ERROR(Journal(dir, "sweep B", {"a"}, 3, Shard{}), "holds another sweep (sweep A)");
  EXPECT_RIGID_ERROR(Journal(dir, "sweep A", {"a"}, 3, Shard{1, 2}), "holds shard 0/1 of this sweep, not shard 1/2");
  EXPECT_RIGID_ERROR((void)read_journal(dir / "nothing"), "holds no sweep journal");
  fs::remove_all(dir);
}

// Rows reach the file without a flush, within the writer's delay (0.1 s; waited for up to 5 s
// here, a loaded machine's margin), in the order appended; flush writes at once; rows appended
// from several threads are each one whole line.
TEST(SweepJournal, RowsReachTheFileSoonWithoutAFlushAndWholeFromManyThreads) {
  const fs::path dir = temp_dir("writer");
  const auto rows_on_disk = [&] {
    std::ifstream in(dir / ".journal.jsonl");
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);) ++lines;
    return lines - 1;  // the header
  };
  {
    Journal j(dir, "sweep A", {"a"}, 3998, Shard{});
    j.append(SweepRow{.index = 0, .values = {0.5}, .results = {{"x", 1}}});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (rows_on_disk() < 1 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    EXPECT_EQ(rows_on_disk(), 1u);
    j.append(SweepRow{.index = 1, .values = {1.5}});
    j.flush();
    EXPECT_EQ(rows_on_disk(), 2u);
    // 4 threads × 999 rows: more than one 64 KiB write, interleaved appends
    std::vector<std::jthread> pool;
    for (std::size_t t = 0; t < 4; ++t) {
      pool.emplace_back([&j, t] {
        for (std::size_t k = 0; k < 999; ++k) {
          const std::size_t index = 2 + t * 999 + k;
          j.append(SweepRow{.index = index, .values = {static_cast<double>(index) / 7},
                            .results = {{"energy_max_change", 1e-12 * static_cast<double>(index)}},
                            .error = index % 5 == 0 ? "a \"quoted\",\nline" : ""});
        }
      });
    }
  }  // joined, then the journal's destructor writes what waits
  const JournalContents c = read_journal(dir);
  ASSERT_EQ(c.rows.size(), 3998u);  // 2 + 4 × 999
  std::vector<std::size_t> seen;
  for (const auto& r : c.rows) {
    seen.push_back(r.index);
    if (r.index >= 2) {
      EXPECT_EQ(r.values.at(0), static_cast<double>(r.index) / 7) << r.index;
    }
  }
  std::sort(seen.begin(), seen.end());
  std::vector<std::size_t> all(3998);
  std::iota(all.begin(), all.end(), std::size_t{0});
  EXPECT_EQ(seen, all);
  fs::remove_all(dir);
}

// runs.csv formatted on several threads is the same bytes as on one (blocks of ≥ 4096 rows);
// the summary's order statistics, found by selection, are those of a full sort.
TEST(SweepOutputs, TheOutputsAreTheSameBytesOnAnyNumberOfThreads) {
  std::vector<SweepRow> rows;
  const std::size_t n = 3 * 4096 + 17;
  for (std::size_t i = 0; i < n; ++i) {
    // values with many repeats and a scatter of magnitudes, results in another order now and then
    const double x = std::ldexp(static_cast<double>((i * 2654435761U) % 1000), static_cast<int>(i % 40) - 20);
    SweepRow r{.index = n - 1 - i, .values = {static_cast<double>(i % 97)}};
    r.results = {{"x", x}, {"y", -x / 3}};
    if (i % 11 == 0) std::swap(r.results[0], r.results[1]);
    if (i % 13 == 0) r.error = "refused, \"here\"";
    if (i % 13 == 0) r.results.clear();
    rows.push_back(r);
  }
  const SweepOutputs out = make_outputs({"a"}, n, rows);
  const fs::path one = temp_dir("outputs_one"), four = temp_dir("outputs_four");
  (void)write_outputs(one, out, 1);
  (void)write_outputs(four, out, 4);
  for (const char* f : {"runs.csv", "runs.npy", "summary.json"}) {
    std::ifstream a(one / f, std::ios::binary), b(four / f, std::ios::binary);
    std::stringstream sa, sb;
    sa << a.rdbuf();
    sb << b.rdbuf();
    const std::string ta = sa.str(), tb = sb.str();
    EXPECT_FALSE(ta.empty()) << f;
    EXPECT_EQ(ta, tb) << f;
  }
  // min, max and the quantiles of x against a full sort (numpy.quantile's linear rule)
  std::vector<double> x;
  for (const auto& r : rows) {
    for (const auto& [name, v] : r.results) {
      if (name == "x") x.push_back(v);
    }
  }
  std::sort(x.begin(), x.end());
  const auto j = nlohmann::json::parse(out.summary_json)["results"]["x"];
  EXPECT_EQ(j["min"].get<double>(), x.front());
  EXPECT_EQ(j["max"].get<double>(), x.back());
  for (const double p : {0.05, 0.25, 0.5, 0.75, 0.95}) {
    const double h = static_cast<double>(x.size() - 1) * p;
    const auto lo = static_cast<std::size_t>(std::floor(h));
    const double expected = x[lo] + (h - static_cast<double>(lo)) * (x[lo + 1] - x[lo]);
    EXPECT_EQ(j["quantiles"][fmt::format("{}", p)].get<double>(), expected) << p;
  }
  fs::remove_all(one);
  fs::remove_all(four);
}

// A NaN result is one NaN in runs.npy whatever its sign: a row kept in memory (x86's 0/0 has the
// sign bit set) and the same row read back from the journal ("nan") give the same bytes.
TEST(SweepOutputs, ANaNIsTheSameBytesFromMemoryAndFromTheJournal) {
  const double negative_nan = -std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(std::signbit(negative_nan));
  const SweepRow row{.index = 0, .values = {negative_nan}, .results = {{"x", negative_nan}}};
  const SweepRow read_back = row_from_json(row_to_json(row), "j:2");
  const auto bytes = [](const SweepRow& r) { return io::to_npy(make_outputs({"a"}, 1, {r}).numbers); };
  EXPECT_EQ(bytes(row), bytes(read_back));
}

// A run number is a whole number ≥ 0: −1 and 2.5 are refused as damage, not read as 2⁶⁴ − 1 or 2.
TEST(SweepJournal, ARowsRunNumberIsAWholeNumber) {
  const auto row = [](std::string_view run) {
    return fmt::format(R"({{"run":{},"values":[1],"results":[],"error":""}})", run);
  };
  EXPECT_EQ(row_from_json(row("7"), "j:1").index, 7u);
  for (const char* run : {"-1", "2.5", "\"3\"", "1e3"}) {
    EXPECT_RIGID_ERROR((void)row_from_json(row(run), "j:2"), "j:2: not a row of a rigid sweep journal");
  }
}

constexpr const char* kRacket = R"toml(
[parameters]
I2 = 2
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = "I2", izz = 3}
angular_velocity = [0.01, 1, 0.01]
[simulation]
t_end = 2.0
output_dt = 0.1
)toml";

TEST(SweepRun, RowsAreBitwiseTheSameOnOneOrThreeThreadsAndFailuresAreRows) {
  const fs::path dir = temp_dir("run");
  const fs::path scene = dir / "racket.toml";
  std::ofstream(scene) << kRacket;
  // I2 from 2 to 4.5: valid up to I1 + I3 = 4 (the triangle inequality I2 ≤ I1 + I3)
  const SweepIdentity id{.scene = scene, .set = {}, .integrator = "", .spec = {.grid = {parse_grid_axis("I2=2:4.5:6")}}};
  check_overrides(id);
  std::vector<std::size_t> all(run_count(id.spec));
  std::iota(all.begin(), all.end(), 0);
  const auto one = run_sweep(id, all, {.threads = 1});
  const auto three = run_sweep(id, all, {.threads = 3});
  ASSERT_EQ(one.size(), 6u);
  for (std::size_t i = 0; i < one.size(); ++i) EXPECT_EQ(row_to_json(one[i]), row_to_json(three[i])) << i;
  // I2 = 4.5 > I1 + I3 = 4 violates the triangle inequality: that run is a row with its error
  EXPECT_THAT(one[5].error, ::testing::HasSubstr("violate I₁ + I₂ ≥ I₃"));
  EXPECT_TRUE(one[5].results.empty());
  for (std::size_t i = 0; i < 5; ++i) EXPECT_TRUE(one[i].error.empty()) << one[i].error;
  EXPECT_TRUE(one[0].error.empty());
  EXPECT_FALSE(one[0].results.empty());
  // a name the scene lacks is refused before any run
  const SweepIdentity bad{.scene = scene, .set = {}, .integrator = "", .spec = {.grid = {parse_grid_axis("I9=1:2:2")}}};
  EXPECT_RIGID_ERROR(check_overrides(bad), "I9");
  fs::remove_all(dir);
}

// A coordinate scene's runs share one derivation of its equations (and run it from several
// threads at once: also under ThreadSanitizer, `make test-tsan`). Each run uses its own values:
// its initial energy is the closed form E(0) = −m g (L/2) cos θ0 of its m and L (to 1e-12
// relative: one evaluation of the energy at t = 0). A refused value of a later run is that
// run's error row (the axis m runs down from 2 to −1: run 0 is valid).
TEST(SweepRun, ACoordinateScenesRunsShareItsEquationsAndUseTheirOwnValues) {
  const fs::path dir = temp_dir("rod");
  const fs::path scene = dir / "rod.toml";
  std::ofstream(scene) << test::kRodPendulum;
  for (const char* m_axis : {"m=0.5:2:3", "m=2:-1:4"}) {
    const SweepIdentity id{.scene = scene, .set = {"theta.initial=0.8", "simulation.t_end=0.5"}, .integrator = "",
                           .spec = {.grid = {parse_grid_axis("L=0.5:2:3"), parse_grid_axis(m_axis)}}};
    std::vector<std::size_t> all(run_count(id.spec));
    std::iota(all.begin(), all.end(), 0);
    const auto one = run_sweep(id, all, {.threads = 1});
    const auto three = run_sweep(id, all, {.threads = 3});
    ASSERT_EQ(one.size(), all.size());
    for (std::size_t i = 0; i < one.size(); ++i) EXPECT_EQ(row_to_json(one[i]), row_to_json(three[i])) << i;
    for (const SweepRow& row : one) {
      const double L = row.values[0], m = row.values[1];
      if (m <= 0) {
        EXPECT_THAT(row.error, ::testing::HasSubstr("mass")) << "m = " << m;
        continue;
      }
      ASSERT_TRUE(row.error.empty()) << row.error;
      double e0 = std::nan("");
      for (const auto& [name, value] : row.results) {
        if (name == "energy_initial") e0 = value;
      }
      const double expected = -m * 9.81 * (L / 2) * std::cos(0.8);
      EXPECT_NEAR(e0, expected, 1e-12 * std::abs(expected)) << "L = " << L << ", m = " << m;
    }
  }
  fs::remove_all(dir);
}

// The serial work of a sweep's run, bounded: no run enters the symbolic core (the one lock of
// the process), whatever the number of runs; only the prototype does (derivation, mesh-free
// here). Counted, not timed: entries of a 2-run and of an 8-run sweep are the same.
TEST(SweepRun, NoRunEntersTheSymbolicCore) {
  const fs::path dir = temp_dir("serial");
  std::ofstream(dir / "racket.toml") << kRacket;
  std::ofstream(dir / "rod.toml") << test::kRodPendulum;
  const std::vector<std::pair<fs::path, const char*>> cases{{dir / "racket.toml", "I2=2:2.5:"},
                                                            {dir / "rod.toml", "L=0.5:2:"}};
  for (const auto& [scene, axis] : cases) {
    std::vector<std::uint64_t> entries;
    for (int runs : {2, 8}) {
      const SweepIdentity id{.scene = scene, .set = {"simulation.t_end=0.2"}, .integrator = "",
                             .spec = {.grid = {parse_grid_axis(fmt::format("{}{}", axis, runs))}}};
      std::vector<std::size_t> all(run_count(id.spec));
      std::iota(all.begin(), all.end(), 0);
      const std::uint64_t before = lagrange::symbolic_core_usage().entries;
      const auto rows = run_sweep(id, all, {.threads = 2});
      for (const SweepRow& row : rows) EXPECT_TRUE(row.error.empty()) << row.error;
      entries.push_back(lagrange::symbolic_core_usage().entries - before);
    }
    EXPECT_EQ(entries[0], entries[1]) << scene;
  }
  fs::remove_all(dir);
}

// A run takes the prototype's result of a compound expression (here `inertia = m*L^2/3` and
// `half = L/2`, evaluated by the symbolic core) when the parameters it names keep their values:
// sweeping g, no run enters the core; sweeping L, each run evaluates the two expressions of L
// again. Either way every run's numbers are bit for bit those of a model built alone.
TEST(SweepRun, ACompoundExpressionIsEvaluatedAgainOnlyForASweptValue) {
  const fs::path dir = temp_dir("compound");
  std::string text = test::kRodPendulum;
  text.replace(text.find("L = 1.0\n"), 8, "L = 1.0\ninertia = \"m*L^2/3\"\nhalf = \"L/2\"\n");
  std::ofstream(dir / "rod.toml") << text;
  const std::vector<std::pair<const char*, std::uint64_t>> cases{{"g=9:10:", 0}, {"L=0.5:2:", 2}};
  for (const auto& [axis, per_run] : cases) {
    std::vector<std::uint64_t> entries;
    std::vector<SweepRow> rows;
    for (int runs : {2, 8}) {
      const SweepIdentity id{.scene = dir / "rod.toml", .set = {"simulation.t_end=0.05"}, .integrator = "",
                             .spec = {.grid = {parse_grid_axis(fmt::format("{}{}", axis, runs))}}};
      std::vector<std::size_t> all(run_count(id.spec));
      std::iota(all.begin(), all.end(), 0);
      const std::uint64_t before = lagrange::symbolic_core_usage().entries;
      rows = run_sweep(id, all, {.threads = 2});
      entries.push_back(lagrange::symbolic_core_usage().entries - before);
    }
    EXPECT_EQ(entries[1] - entries[0], 6 * per_run) << axis;
    for (const SweepRow& row : rows) {
      ASSERT_TRUE(row.error.empty()) << row.error;
      Scene alone = load_scene(dir / "rod.toml");
      const std::string name = std::string(axis).substr(0, 1);
      apply_overrides(alone, {"simulation.t_end=0.05", fmt::format("{}={}", name, row.values[0])});
      const RunResult r = Model(alone).run();
      ASSERT_EQ(row.results.size(), r.summary.diagnostics.size());
      for (std::size_t k = 0; k < row.results.size(); ++k) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(row.results[k].second),
                  std::bit_cast<std::uint64_t>(r.summary.diagnostics[k].second))
            << row.results[k].first;
      }
    }
  }
  fs::remove_all(dir);
}

// What every run would refuse is refused once, before any run: run 0 is built and checked as
// its run would be (an unknown integrator, a metric on a column the run does not have, a
// physically impossible fixed override or first axis value). No row is made.
TEST(SweepRun, WhatRunZeroRefusesStopsTheSweepBeforeAnyRun) {
  const fs::path dir = temp_dir("refused");
  const fs::path rod = dir / "rod.toml";
  std::ofstream(rod) << test::kRodPendulum;
  const fs::path bad_metric = dir / "bad_metric.toml";
  std::ofstream(bad_metric) << test::kRodPendulum
                            << "[[output.metrics]]\nname = \"peak\"\nkind = \"max\"\ncolumn = \"thetaa\"\n";
  struct Case {
    fs::path scene;
    std::vector<std::string> set;
    std::string integrator;
    const char* axis;
    const char* message;
  };
  const std::vector<Case> cases{
      {rod, {}, "rk5", "L=0.5:2:3", "unknown integrator 'rk5'"},
      {bad_metric, {}, "", "L=0.5:2:3", "the run has no column 'thetaa'"},
      {rod, {"m=-1"}, "", "L=0.5:2:3", "mass must be positive and finite, got -1 kg"},
      {rod, {}, "", "m=-1:1:3", "mass must be positive and finite, got -1 kg"},
  };
  for (const Case& c : cases) {
    const SweepIdentity id{
        .scene = c.scene, .set = c.set, .integrator = c.integrator, .spec = {.grid = {parse_grid_axis(c.axis)}}};
    EXPECT_RIGID_ERROR((void)check_first_run(id), "run 0 of the sweep (");
    EXPECT_RIGID_ERROR((void)check_first_run(id), c.message);
    std::size_t rows = 0;
    const std::vector<std::size_t> all{0, 1, 2};
    SweepRunOptions options{.threads = 2};
    options.on_row = [&rows](const SweepRow&) { ++rows; };
    EXPECT_RIGID_ERROR((void)run_sweep(id, all, options), c.message);
    EXPECT_EQ(rows, 0u) << c.message;
  }
  fs::remove_all(dir);
}

// x'' = c x'² with x(0) = 0, x'(0) = 1 (a force c·ẋ² on a unit mass): x'(t) = 1/(1 − c t),
// which is infinite at t = 1/c. Run 0 passes its check (the state at t = 0 is finite); with
// t_end = 1.5 s every run with c = 1 or 2 diverges during its run. The axis d names nothing the
// motion depends on, so the three runs of each c fail with one message: two groups of three.
constexpr const char* kBlowUp = R"toml(
lagrangian = "x_dot^2/2"
[parameters]
c = 1.0
d = 0.0
[[coordinates]]
name = "x"
initial = 0
velocity = 1
[[forces]]
coordinate = "x"
expression = "c*x_dot^2 + 0*d"
[simulation]
t_end = 1.5
integrator = "rk4"
dt = 1e-3
output_dt = 0.1
)toml";

TEST(SweepRun, RunsThatFailAfterTheFirstRunsCheckAreRowsGroupedByMessage) {
  const fs::path dir = temp_dir("blowup");
  const fs::path scene = dir / "blowup.toml";
  std::ofstream(scene) << kBlowUp;
  const SweepIdentity id{.scene = scene, .set = {}, .integrator = "",
                         .spec = {.grid = {parse_grid_axis("c=1:2:2"), parse_grid_axis("d=0:1:3")}}};
  EXPECT_NO_THROW((void)check_first_run(id));
  std::vector<std::size_t> all(run_count(id.spec));
  std::iota(all.begin(), all.end(), 0);
  const SweepOutputs out = make_outputs(swept_names(id.spec), all.size(), run_sweep(id, all, {.threads = 2}));
  ASSERT_EQ(out.failures.size(), 2u);
  for (std::size_t g = 0; g < 2; ++g) {
    EXPECT_EQ(out.failures[g].count, 3u);
    EXPECT_THAT(out.failures[g].message, ::testing::HasSubstr("diverged"));
    // c = 1 are runs 0, 1, 2 (the first axis varies slowest); c = 2 are runs 3, 4, 5
    EXPECT_EQ(out.failures[g].runs, (std::vector<std::size_t>{3 * g, 3 * g + 1, 3 * g + 2}));
  }
  const auto j = nlohmann::json::parse(out.summary_json);
  EXPECT_EQ(j["failures"], 6);
  ASSERT_EQ(j["failure_groups"].size(), 2u);
  EXPECT_EQ(j["failure_groups"][1]["message"], out.failures[1].message);
  EXPECT_EQ(j["failure_groups"][1]["count"], 3);
  EXPECT_EQ(j["failure_groups"][1]["runs"], nlohmann::json::array({3, 4, 5}));
  EXPECT_FALSE(j.contains("failure_groups_left_out"));
  fs::remove_all(dir);
}

TEST(SweepOutputs, FailuresAreGroupedByMessageMostFrequentFirst) {
  // messages by run: b at 1, 4; a at 2, 3, 5, 6, 7, 8, 9 (7 runs: 5 listed); c at 10
  std::vector<std::string> errors(11);
  for (std::size_t i : {2u, 3u, 5u, 6u, 7u, 8u, 9u}) errors[i] = "a";
  errors[1] = errors[4] = "b";
  errors[10] = "c";
  const auto groups = group_failures(errors);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].message, "a");
  EXPECT_EQ(groups[0].count, 7u);
  EXPECT_EQ(groups[0].runs, (std::vector<std::size_t>{2, 3, 5, 6, 7}));
  EXPECT_EQ(groups[1].message, "b");
  EXPECT_EQ(groups[1].runs, (std::vector<std::size_t>{1, 4}));
  EXPECT_EQ(groups[2].message, "c");
  EXPECT_EQ(groups[2].count, 1u);
  EXPECT_TRUE(group_failures(std::vector<std::string>(3)).empty());

  // more messages than summary.json lists: the rest counted, groups and runs
  std::vector<SweepRow> rows;
  const std::size_t n = kFailureGroupsListed + 3;
  for (std::size_t i = 0; i < n; ++i) rows.push_back({.index = i, .values = {}, .results = {}, .error = fmt::format("e{}", i)});
  rows.push_back({.index = n, .values = {}, .results = {}, .error = "e0"});
  const auto j = nlohmann::json::parse(make_outputs({}, n + 1, rows).summary_json);
  ASSERT_EQ(j["failure_groups"].size(), kFailureGroupsListed);
  EXPECT_EQ(j["failure_groups"][0]["message"], "e0");
  EXPECT_EQ(j["failure_groups"][0]["runs"], nlohmann::json::array({0, n}));
  EXPECT_EQ(j["failure_groups_left_out"]["groups"], 3);
  EXPECT_EQ(j["failure_groups_left_out"]["runs"], 3);
}

// Two free bodies in gravity, one of them not principal in its own frame (stepped in P), with
// the metrics that observe every step: what a free-body sweep marches in batches.
constexpr const char* kTwoFreeBodies = R"toml(
gravity = [0, 0, "-g"]
[parameters]
I2 = 2
g = 9.81
[[bodies]]
name = "racket"
free = true
inertia = {mass = 0.35, ixx = 1, iyy = "I2", izz = 3}
angular_velocity = [0.01, 1, 0.01]
[[bodies]]
name = "brick"
free = true
inertia = {mass = 2, ixx = 0.5, iyy = 0.7, izz = 0.9, ixy = 0.1, ixz = -0.05, iyz = 0.02}
initial_velocity = [1, 0, 2]
initial_position = [1, 2, 3]
angular_velocity = [0.3, -2, 1.5]
[simulation]
t_end = 2.0
output_dt = 0.1
[[output.metrics]]
name = "first_flip"
kind = "crossing"
column = "racket.wy"
k = 1
[[output.metrics]]
name = "energy_drift"
kind = "drift"
column = "energy"
)toml";

void expect_same_run(const Model::BatchedRun& batched, const Model& model, const RunOptions& options,
                     const std::string& what) {
  std::optional<RunResult> alone;
  std::string error;
  try {
    alone = model.run(options);
  } catch (const Error& e) {
    error = e.what();
  }
  ASSERT_EQ(batched.result.has_value(), alone.has_value()) << what << ": " << batched.error << " / " << error;
  EXPECT_EQ(batched.error, error) << what;
  if (!alone) return;
  const RunResult& b = *batched.result;
  EXPECT_EQ(b.trajectory.columns(), alone->trajectory.columns()) << what;
  ASSERT_EQ(b.trajectory.data().size(), alone->trajectory.data().size()) << what;
  for (std::size_t i = 0; i < b.trajectory.data().size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint64_t>(b.trajectory.data()[i]), std::bit_cast<std::uint64_t>(alone->trajectory.data()[i]))
        << what << ": value " << i << " of the trajectory";
  }
  ASSERT_EQ(b.summary.diagnostics.size(), alone->summary.diagnostics.size()) << what;
  for (std::size_t i = 0; i < b.summary.diagnostics.size(); ++i) {
    EXPECT_EQ(b.summary.diagnostics[i].first, alone->summary.diagnostics[i].first) << what;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(b.summary.diagnostics[i].second),
              std::bit_cast<std::uint64_t>(alone->summary.diagnostics[i].second))
        << what << ": " << b.summary.diagnostics[i].first;
  }
  ASSERT_EQ(b.summary.metrics.size(), alone->summary.metrics.size()) << what;
  for (std::size_t i = 0; i < b.summary.metrics.size(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(b.summary.metrics[i].value),
              std::bit_cast<std::uint64_t>(alone->summary.metrics[i].value))
        << what << ": " << b.summary.metrics[i].name;
    EXPECT_EQ(b.summary.metrics[i].note, alone->summary.metrics[i].note) << what;
  }
  EXPECT_EQ(b.summary.steps, alone->summary.steps) << what;
  EXPECT_EQ(b.summary.integrator, alone->summary.integrator) << what;
  EXPECT_EQ(b.summary.samples, alone->summary.samples) << what;
}

// Free-body runs marched together (Model::run_batch: every body's rotation through the
// four-body kernel) are, bit for bit, the runs alone: trajectories, diagnostics, metrics and
// the error of a run that diverges (g = 1.7e308: a position overflows at step 1058) while the
// others of its batch go on. With each splitting, and with a batch whose runs differ in dt
// (run one after the other).
TEST(SweepRun, FreeBodyRunsMarchedTogetherAreTheBitsOfEachRunAlone) {
  const fs::path dir = temp_dir("batch");
  const fs::path file = dir / "two.toml";
  std::ofstream(file) << kTwoFreeBodies;
  const Scene base = load_scene(file);
  const Model prototype(base);
  for (const char* integrator : {"splitting2", "splitting4", "splitting6"}) {
    RunOptions options;
    options.integrator = integrator;
    ASSERT_TRUE(prototype.batches(options)) << integrator;
    std::vector<Model> models;
    for (const char* g : {"9.81", "1.7e308", "3", "9.81", "1.7e308"}) {
      for (const char* I2 : {"2", "2.5", "3.1"}) {
        Scene s = base;
        apply_overrides(s, {fmt::format("g={}", g), fmt::format("I2={}", I2)});
        models.emplace_back(s, prototype);
      }
    }
    std::vector<const Model*> all;
    for (const Model& m : models) all.push_back(&m);
    const auto batched = Model::run_batch(all, options);
    ASSERT_EQ(batched.size(), models.size());
    std::size_t diverged = 0;
    for (std::size_t i = 0; i < models.size(); ++i) {
      expect_same_run(batched[i], models[i], options, fmt::format("{} run {}", integrator, i));
      if (!batched[i].result) {
        EXPECT_THAT(batched[i].error, ::testing::HasSubstr("non-finite state at step 1058"));
        ++diverged;
      }
    }
    EXPECT_EQ(diverged, 6u) << integrator;
    // they marched as one batch: the runs that finished report the batch's wall time
    std::set<double> walls;
    for (const auto& b : batched) {
      if (b.result) walls.insert(b.result->summary.wall_seconds);
    }
    EXPECT_EQ(walls.size(), 1u) << integrator;
  }
  // not marched together: different steps, a method that is not a splitting
  Scene finer = base;
  apply_overrides(finer, {"simulation.dt=0.0005"});
  const Model a(base, prototype), b(finer, prototype);
  const std::vector<const Model*> mixed{&a, &b};
  const auto apart = Model::run_batch(mixed, {});
  expect_same_run(apart[0], a, {}, "dt 1e-3");
  expect_same_run(apart[1], b, {}, "dt 5e-4");
  RunOptions rk4;
  rk4.integrator = "rk4";
  EXPECT_FALSE(prototype.batches(rk4));
  // a body on a pivot (a heavy top's gravity splitting) is stepped alone
  std::ofstream(dir / "top.toml") << R"toml(
[[bodies]]
name = "top"
free = true
primitive = "solid_cone"
radius = 0.05
height = 0.2
mass = 1.0
pivot = [0, 0, 0.2]
angular_velocity = [0, 0, 50]
[simulation]
t_end = 0.1
)toml";
  EXPECT_FALSE(Model(load_scene(dir / "top.toml")).batches());
  fs::remove_all(dir);
}

// A sweep of a free-body scene marches its runs in batches: its rows are the same bytes batched
// or not, on one or three threads, failures (a refused inertia, a diverged run) included.
TEST(SweepRun, AFreeBodySweepsRowsAreTheSameBatchedOrNot) {
  const fs::path dir = temp_dir("batchsweep");
  const fs::path scene = dir / "two.toml";
  std::ofstream(scene) << kTwoFreeBodies;
  // I2 from 2 to 4.5: valid up to I1 + I3 = 4; g = 1.7e308 diverges
  const SweepIdentity id{.scene = scene, .set = {}, .integrator = "",
                         .spec = {.grid = {parse_grid_axis("I2=2:4.5:6"), parse_grid_axis("g=9.81:1.7e308:2")}}};
  std::vector<std::size_t> all(run_count(id.spec));
  std::iota(all.begin(), all.end(), 0);
  const auto apart = run_sweep(id, all, {.threads = 1, .batch = false});
  ASSERT_EQ(apart.size(), 12u);
  for (std::size_t threads : {1, 3}) {
    const auto together = run_sweep(id, all, {.threads = threads});
    ASSERT_EQ(together.size(), apart.size());
    for (std::size_t i = 0; i < apart.size(); ++i) {
      EXPECT_EQ(row_to_json(together[i]), row_to_json(apart[i])) << threads << " threads, run " << i;
    }
  }
  std::size_t refused = 0, diverged = 0, ran = 0;
  for (const SweepRow& row : apart) {
    refused += row.error.find("violate") != std::string::npos;
    diverged += row.error.find("non-finite state") != std::string::npos;
    ran += row.error.empty();
  }
  EXPECT_EQ(refused, 2u);
  EXPECT_EQ(diverged, 5u);
  EXPECT_EQ(ran, 5u);
  fs::remove_all(dir);
}

TEST(SweepRun, ACancelledSweepStopsWithCancelled) {
  const fs::path dir = temp_dir("cancel");
  const fs::path scene = dir / "racket.toml";
  std::ofstream(scene) << kRacket;
  const SweepIdentity id{.scene = scene, .set = {}, .integrator = "", .spec = {.grid = {parse_grid_axis("I2=2:2.5:5")}}};
  std::vector<std::size_t> all{0, 1, 2, 3, 4};
  std::atomic<bool> cancel{true};
  EXPECT_THROW((void)run_sweep(id, all, {.threads = 2, .cancel = &cancel}), Cancelled);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rigid::scene
