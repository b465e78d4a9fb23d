#include "rigid/report/report.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rigid/mesh/read_mesh.hpp"
#include "rigid/scene/model.hpp"
#include "rigid/scene/scene.hpp"
#include "support/expect_error.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using rigid::report::decimate;
using rigid::report::report_json;

// float32 rounding to nearest: |float(x) − x| ≤ 2^-24 |x|; the tests allow 2^-23 (one more
// bit for the values the library computes in double before rounding, such as R c_B + p).
constexpr double kF32 = 0x1p-23;

// An independent base64 decoder (RFC 4648), to read what the library encoded.
std::string unbase64(const std::string& text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::string out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    const int v = value(c);
    EXPECT_GE(v, 0) << "not a base64 character: " << c;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((acc >> bits) & 0xFF));
    }
  }
  return out;
}

std::vector<std::uint32_t> words(const json& j, const std::string& prefix) {
  const std::string s = j.get<std::string>();
  EXPECT_EQ(s.substr(0, prefix.size()), prefix);
  const std::string bytes = unbase64(s.substr(prefix.size()));
  EXPECT_EQ(bytes.size() % 4, 0u);
  std::vector<std::uint32_t> w(bytes.size() / 4);
  for (std::size_t i = 0; i < w.size(); ++i) {
    for (std::size_t k = 0; k < 4; ++k) w[i] |= std::uint32_t{static_cast<unsigned char>(bytes[4 * i + k])} << (8 * k);
  }
  return w;
}

// A numeric array of the schema: a plain JSON array (≤ 16 numbers) or "f32:BASE64".
std::vector<double> floats(const json& j) {
  if (j.is_array()) return j.get<std::vector<double>>();
  std::vector<double> out;
  for (const std::uint32_t w : words(j, "f32:")) out.push_back(std::bit_cast<float>(w));
  return out;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rigid_report_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A free cone (COM at h/4 on its axis) and a free box, 301 samples.
constexpr const char* kFreeScene = R"(# Two free bodies.
# Second line.
[[bodies]]
name = "cone"
free = true
primitive = "cone"
radius = 0.1
height = 0.4
mass = 2.0
angular_velocity = [0.3, 2.0, 0.1]

[[bodies]]
name = "box"
free = true
primitive = "box"
size = [0.1, 0.2, 0.3]
mass = 1.0
initial_position = [1, 0, 0]
initial_velocity = [0, 0, 1]
angular_velocity = [0.01, 1, 0.01]

[simulation]
t_end = 3.0
dt = 0.001
output_dt = 0.01
)";

}  // namespace

// k = ⌈(n−1)/(M−1)⌉ keeps rows 0, k, 2k, … and the last: at most M rows, both ends kept.
TEST(ReportDecimation, KeepsBothEndsAndAtMostMaxFrames) {
  const auto all = decimate(5, 2000);
  EXPECT_EQ(all.stride, 1u);
  EXPECT_EQ(all.rows, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(all.rule, "every sample of 5 (at most 2000 frames)");
  const auto two = decimate(2001, 2000);  // ⌈2000/1999⌉ = 2: 0, 2, …, 2000
  EXPECT_EQ(two.stride, 2u);
  EXPECT_EQ(two.rows.size(), 1001u);
  EXPECT_EQ(two.rows.back(), 2000u);
  EXPECT_EQ(two.rule, "every 2nd of 2001 samples (at most 2000 frames)");
  const auto odd = decimate(10, 3);  // ⌈9/2⌉ = 5: 0, 5 and the last, 9
  EXPECT_EQ(odd.rows, (std::vector<std::size_t>{0, 5, 9}));
  EXPECT_EQ(odd.rule, "every 5th of 10 samples, and the last (at most 3 frames)");
  for (std::size_t n : {2u, 3u, 7u, 100u, 1001u, 100001u}) {
    for (std::size_t m : {2u, 3u, 10u, 2000u}) {
      const auto d = decimate(n, m);
      EXPECT_LE(d.rows.size(), m) << n << " " << m;
      EXPECT_EQ(d.rows.front(), 0u);
      EXPECT_EQ(d.rows.back(), n - 1);
    }
  }
  EXPECT_RIGID_ERROR((void)decimate(10, 1), "between 2 and 1000000, got 1");
  EXPECT_RIGID_ERROR((void)decimate(10, 1000001), "between 2 and 1000000");
  EXPECT_RIGID_ERROR((void)decimate(0, 10), "no samples");
}

// The data of a free-body run: every body's COM in the world is p_WB + R_WB c_B (the cone's
// COM at h/4 on its axis: Rz(h/4) from the pose columns), ω in the world is R_WB ω_B, the
// frames are the decimated rows, and the schema's keys are there.
TEST(ReportJson, FreeBodiesFramesAreTheTrajectoryRows) {
  const fs::path dir = scratch("free");
  std::ofstream(dir / "two.toml") << kFreeScene;
  const rigid::scene::Model model(rigid::scene::load_scene(dir / "two.toml"));
  const rigid::io::RunResult run = model.run();
  ASSERT_EQ(run.trajectory.rows(), 301u);
  const json j = json::parse(report_json(model, run, {.max_frames = 100}));
  EXPECT_EQ(j["rigid_report"], 1);
  EXPECT_EQ(j["kind"], "free_bodies");
  EXPECT_EQ(j["scene"]["name"], "two");
  EXPECT_EQ(j["scene"]["description"], "Two free bodies.\nSecond line.");
  for (const char* key : {"parameters", "integrator", "diagnostics", "equations_latex", "bodies", "meshes",
                          "frames", "series", "size"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["size"]["max_frames"], 100);
  const auto d = decimate(301, 100);  // ⌈300/99⌉ = 4: 0, 4, …, 300 (76 rows)
  ASSERT_EQ(j["frames"]["count"], d.rows.size());
  EXPECT_EQ(j["frames"]["rule"], d.rule);
  const rigid::io::Table& tr = run.trajectory;
  const std::vector<double> t = floats(j["frames"]["t"]);
  ASSERT_EQ(t.size(), d.rows.size());
  for (std::size_t f = 0; f < t.size(); ++f) EXPECT_NEAR(t[f], tr(d.rows[f], tr.column("t")), kF32 * 3.0);

  // the cone: a closed form of its COM (h/4 = 0.1 m along its axis) against the frames
  const json& body = j["bodies"][0];
  EXPECT_EQ(body["shape"]["kind"], "cone");
  EXPECT_EQ(body["shape"]["sizes"]["radius"], 0.1);
  EXPECT_EQ(body["shape"]["sizes"]["height"], 0.4);
  EXPECT_NEAR(body["com"][2].get<double>(), 0.1, 1e-15);  // h/4
  // principal moments of a solid cone about its COM: 3/10 m r² (axis), 3/80 m (4 r² + h²)
  const double m = 2.0, r = 0.1, h = 0.4;
  const std::vector<double> I = body["principal_moments"].get<std::vector<double>>();
  EXPECT_NEAR(I[0], 3.0 / 10 * m * r * r, 1e-14);
  EXPECT_NEAR(I[1], 3.0 / 80 * m * (4 * r * r + h * h), 1e-14);
  EXPECT_NEAR(I[2], 3.0 / 80 * m * (4 * r * r + h * h), 1e-14);
  const std::vector<double> p = floats(j["frames"]["bodies"][0]["position"]);
  const std::vector<double> q = floats(j["frames"]["bodies"][0]["quaternion"]);
  const std::vector<double> w = floats(j["frames"]["bodies"][0]["omega"]);
  ASSERT_EQ(p.size(), 3 * d.rows.size());
  ASSERT_EQ(q.size(), 4 * d.rows.size());
  for (std::size_t f = 0; f < d.rows.size(); ++f) {
    const std::size_t row = d.rows[f];
    const Eigen::Quaterniond R(tr(row, tr.column("cone.qw")), tr(row, tr.column("cone.qx")),
                               tr(row, tr.column("cone.qy")), tr(row, tr.column("cone.qz")));
    const Eigen::Vector3d c = Eigen::Vector3d(tr(row, tr.column("cone.x")), tr(row, tr.column("cone.y")),
                                              tr(row, tr.column("cone.z"))) +
                              R * Eigen::Vector3d(0, 0, h / 4);
    // the COM of a free body in no gravity and at rest stays where it started: (0, 0, h/4)
    EXPECT_NEAR(c.z(), h / 4, 1e-12);
    const Eigen::Vector3d w_W = R * Eigen::Vector3d(tr(row, tr.column("cone.wx")), tr(row, tr.column("cone.wy")),
                                                    tr(row, tr.column("cone.wz")));
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(p[3 * f + k], c[k], kF32 * 1.0) << f;  // |c| ≤ 1 m
      EXPECT_NEAR(w[3 * f + k], w_W[k], kF32 * 3.0) << f;  // |ω| ≤ 3 rad/s
    }
    EXPECT_NEAR(q[4 * f], R.w(), kF32);
  }
  // the series: every column but t and the poses, then the relative energy and |L| errors
  std::vector<std::string> names;
  for (const json& s : j["series"]) names.push_back(s["name"]);
  EXPECT_THAT(names, ::testing::Contains("box.wy"));
  EXPECT_THAT(names, ::testing::Not(::testing::Contains("box.qw")));
  for (const json& s : j["series"]) {
    if (s["name"] == "box.wy") {
      const std::vector<double> v = floats(s["values"]);
      ASSERT_EQ(v.size(), d.rows.size());
      for (std::size_t f = 0; f < v.size(); ++f) {
        const double x = tr(d.rows[f], tr.column("box.wy"));
        EXPECT_NEAR(v[f], x, kF32 * std::abs(x));
      }
    }
  }
  std::size_t l_error = 0;
  for (const json& s : j["series"]) l_error += s["group"] == "L_error" ? 1 : 0;
  EXPECT_EQ(l_error, 2u);
  fs::remove_all(dir);
}

// A coordinate scene: the page does no kinematics, so each body's world pose comes from the
// coordinates (here a pendulum bob at (l sin θ, 0, −l cos θ)); ω and L are null.
TEST(ReportJson, CoordinateScenePosesComeFromTheCoordinates) {
  const fs::path dir = scratch("pendulum");
  const rigid::scene::Model model(rigid::scene::parse_scene(R"toml(gravity = [0, 0, -9.81]
[parameters]
l = 0.5
[[coordinates]]
name = "theta"
initial = 0.3
[[bodies]]
name = "bob"
point_masses = [{mass = 1.0, position = [0, 0, 0]}]
position = ["l*sin(theta)", 0, "-l*cos(theta)"]
[simulation]
t_end = 1.0
integrator = "rk4"
dt = 0.001
output_dt = 0.01
)toml", dir / "pendulum.toml"));
  const rigid::io::RunResult run = model.run();
  const json j = json::parse(report_json(model, run));
  EXPECT_EQ(j["kind"], "coordinates");
  EXPECT_TRUE(j["frames"]["bodies"][0]["omega"].is_null());
  EXPECT_TRUE(j["frames"]["bodies"][0]["L"].is_null());
  EXPECT_THAT(j["equations_latex"].get<std::string>(), ::testing::HasSubstr("theta"));
  const rigid::io::Table& tr = run.trajectory;
  ASSERT_EQ(j["frames"]["count"], tr.rows());  // 101 rows: all kept
  const std::vector<double> p = floats(j["frames"]["bodies"][0]["position"]);
  for (std::size_t f = 0; f < tr.rows(); ++f) {
    const double theta = tr(f, tr.column("theta"));
    EXPECT_NEAR(p[3 * f], 0.5 * std::sin(theta), kF32 * 0.5 + 1e-12) << f;
    EXPECT_NEAR(p[3 * f + 2], -0.5 * std::cos(theta), kF32 * 0.5 + 1e-12) << f;
  }
  std::vector<std::string> groups;
  for (const json& s : j["series"]) groups.push_back(s["group"]);
  EXPECT_THAT(groups, ::testing::Contains("coordinates"));
  EXPECT_THAT(groups, ::testing::Contains("velocities"));
  EXPECT_THAT(groups, ::testing::Contains("energy_error"));
  EXPECT_EQ(j["parameters"][0]["name"], "l");
  fs::remove_all(dir);
}

// What connects the bodies: a double pendulum posed by expressions alone (no `parent`) hangs
// bob1 from a pivot at the world origin and bob2 from bob1 (their distances are the rods'
// lengths at every frame); a weight that slides along a line hangs from nothing.
TEST(ReportJson, LinksOfADoublePendulumAreAPivotAndTwoRods) {
  const fs::path dir = scratch("double");
  const rigid::scene::Model model(rigid::scene::parse_scene(R"toml(gravity = [0, 0, -9.81]
[[coordinates]]
name = "a"
initial = 1.0
[[coordinates]]
name = "b"
initial = 0.5
[[coordinates]]
name = "y"
velocity = 1.0
[[bodies]]
name = "bob1"
point_masses = [{mass = 1.0, position = [0, 0, 0]}]
position = ["0.7*sin(a)", 0, "-0.7*cos(a)"]
[[bodies]]
name = "bob2"
point_masses = [{mass = 1.0, position = [0, 0, 0]}]
position = ["0.7*sin(a) + 0.4*sin(b)", 0, "-0.7*cos(a) - 0.4*cos(b)"]
[[bodies]]
name = "weight"
point_masses = [{mass = 1.0, position = [0, 0, 0]}]
position = [3, 0, "y"]
[simulation]
t_end = 0.5
integrator = "rk4"
dt = 0.001
output_dt = 0.01

[[output.metrics]]
name = "a_zero"
kind = "crossing"
column = "a"
)toml", dir / "double.toml"));
  const rigid::io::RunResult run = model.run();
  const json j = json::parse(report_json(model, run));
  ASSERT_EQ(j["links"].size(), 2u) << j["links"].dump();
  EXPECT_EQ(j["links"][0]["body"], 0);
  EXPECT_TRUE(j["links"][0]["to"].is_null());
  EXPECT_EQ(j["links"][0]["to_point"], json::array({0.0, 0.0, 0.0}));
  EXPECT_EQ(j["links"][1]["body"], 1);
  EXPECT_EQ(j["links"][1]["to"], 0);
  EXPECT_EQ(j["links"][1]["rule"], "constant distance");
  // the metric is an instant (a crossing, in s), so the plots mark it
  ASSERT_EQ(j["metrics"].size(), 1u);
  EXPECT_EQ(j["metrics"][0]["name"], "a_zero");
  EXPECT_EQ(j["metrics"][0]["unit"], "s");
  EXPECT_TRUE(j["metrics"][0]["instant"]);
  ASSERT_EQ(run.summary.metrics.size(), 1u);
  EXPECT_EQ(j["metrics"][0]["value"], run.summary.metrics[0].value);
  // and a page made again from the run's files (rigid report DIR) has the same metric
  const std::vector<rigid::io::OutputFormat> formats = {rigid::io::OutputFormat::kCsv,
                                                        rigid::io::OutputFormat::kJson};
  (void)rigid::io::write_run(dir / "out", run, formats);
  const json again = json::parse(report_json(model, rigid::report::read_run(dir / "out")));
  EXPECT_EQ(again["metrics"], j["metrics"]);
  EXPECT_EQ(again["links"].size(), 2u);
  fs::remove_all(dir);
}

// A top: one rod from its COM to its pivot, fixed in the world where the initial pose puts it
// (p_W = p_WB(0) + R_WB(0) pivot_B: here the rotation is a half turn about x, so (0, 0, 0.2)
// goes to (0, 0, −0.2) from the initial position (1, 2, 3)).
TEST(ReportJson, ATopHangsFromItsPivot) {
  const fs::path dir = scratch("top");
  const rigid::scene::Model model(rigid::scene::parse_scene(R"toml(gravity = [0, 0, -9.81]
[[bodies]]
name = "top"
free = true
primitive = "solid_cone"
radius = 0.05
height = 0.2
mass = 1.0
initial_position = [1, 2, 3]
initial_rotation = {axis = [1, 0, 0], angle = 3.141592653589793}
pivot = [0, 0, 0.2]
angular_velocity = [0, 0, 50]
[simulation]
t_end = 0.01
dt = 0.001
)toml", dir / "top.toml"));
  const rigid::io::RunResult run = model.run();
  const json j = json::parse(report_json(model, run));
  ASSERT_EQ(j["links"].size(), 1u) << j["links"].dump();
  EXPECT_EQ(j["links"][0]["rule"], "pivot");
  const std::vector<double> pivot = j["links"][0]["to_point"];
  // the initial pose is read back from the trajectory's first row: round-off only (1e-12 m)
  EXPECT_NEAR(pivot[0], 1.0, 1e-12);
  EXPECT_NEAR(pivot[1], 2.0, 1e-12);
  EXPECT_NEAR(pivot[2], 2.8, 1e-12);
  fs::remove_all(dir);
}

// Two bodies of one mesh file store it once; its positions are the file's vertices (float32)
// and its indices its triangles.
TEST(ReportJson, MeshesAreStoredOnce) {
  const fs::path dir = scratch("mesh");
  // a regular octahedron: a closed mesh of 8 triangles
  rigid::mesh::TriangleMesh oct;
  oct.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  oct.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  rigid::mesh::write_stl_binary(oct, (dir / "oct.stl").string());
  const rigid::scene::Model model(rigid::scene::parse_scene(R"([[bodies]]
name = "a"
free = true
mesh = "oct.stl"
density = 1000
angular_velocity = [0, 0, 1]
[[bodies]]
name = "b"
free = true
mesh = "oct.stl"
density = 1000
initial_position = [3, 0, 0]
[simulation]
t_end = 0.1
dt = 0.01
)", dir / "meshes.toml"));
  const json j = json::parse(report_json(model, model.run()));
  ASSERT_EQ(j["meshes"].size(), 1u);
  EXPECT_EQ(j["bodies"][0]["shape"]["kind"], "mesh");
  EXPECT_EQ(j["bodies"][0]["shape"]["mesh"], 0);
  EXPECT_EQ(j["bodies"][1]["shape"]["mesh"], 0);
  const json& mesh = j["meshes"][0];
  EXPECT_EQ(mesh["triangles"], 8);
  const rigid::mesh::TriangleMesh back = rigid::mesh::read_mesh((dir / "oct.stl").string());
  const std::vector<double> pos = floats(mesh["positions"]);
  ASSERT_EQ(pos.size(), 3 * back.vertices.size());
  for (std::size_t v = 0; v < back.vertices.size(); ++v) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(pos[3 * v + static_cast<std::size_t>(k)], back.vertices[v][k]);  // ±1, 0: exact
  }
  const std::vector<std::uint32_t> idx = words(mesh["indices"], "u32:");
  ASSERT_EQ(idx.size(), 24u);
  for (std::size_t t = 0; t < 8; ++t) {
    for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(idx[3 * t + k], back.triangles[t][k]);
  }
  fs::remove_all(dir);
}

// The page: the data's "</" cannot end its script element, the title is escaped, and the
// page names no network resource.
TEST(ReportPage, DataCannotEndItsElement) {
  if (!rigid::report::available()) {
    EXPECT_RIGID_ERROR((void)rigid::report::assemble_page("x", "{}"), "RIGID_REPORT=OFF");
    return;
  }
  const std::string page = rigid::report::assemble_page("a<b", R"({"s": "</script><!-- x"})");
  EXPECT_THAT(page, ::testing::StartsWith("<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\">"
                                          "<title>rigid — a&lt;b</title><style>"));
  EXPECT_THAT(page, ::testing::HasSubstr(
                        R"(<script type="application/json" id="rigid-report-data">{"s": "<\/script>\u003c!-- x"}</script><script>)"));
  EXPECT_THAT(page, ::testing::EndsWith("</script></body></html>\n"));
  // the JSON text in the page still parses to the same value
  const std::size_t start = page.find("rigid-report-data\">") + 19;
  const std::string data = page.substr(start, page.find("</script>", start) - start);
  EXPECT_EQ(json::parse(data)["s"], "</script><!-- x");
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
}

// An earlier run read back: a missing summary.json or trajectory.csv is named.
TEST(ReportReadRun, MissingFilesAreNamed) {
  const fs::path dir = scratch("read");
  EXPECT_RIGID_ERROR((void)rigid::report::read_run(dir / "nowhere"), "is not a directory");
  EXPECT_RIGID_ERROR((void)rigid::report::read_run(dir), "summary.json' is missing");
  std::ofstream(dir / "summary.json") << R"({"scene": "gone.toml", "kind": "free_bodies", "integrator": "rk4"})";
  EXPECT_RIGID_ERROR((void)rigid::report::read_run(dir), "trajectory.csv' is missing");
  EXPECT_RIGID_ERROR((void)rigid::report::scene_of_run(dir), "the scene 'gone.toml'");
  std::ofstream(dir / "summary.json") << "[1, 2]";
  EXPECT_RIGID_ERROR((void)rigid::report::read_run(dir), "is not a run summary");
  fs::remove_all(dir);
}

namespace {

// The units on the page are the schema's (by quantity), and a run read back from its
// directory carries the schema summary.json holds: a summary whose schema is not its
// trajectory's is refused, one written before runs carried a schema takes the model's.
TEST(ReportReadRun, TheSchemaTravelsWithTheRunAndMustBeItsTrajectorys) {
  const fs::path dir = scratch("schema");
  std::ofstream(dir / "two.toml") << kFreeScene;
  const rigid::scene::Model model(rigid::scene::load_scene(dir / "two.toml"));
  const rigid::io::RunResult run = model.run();
  const std::vector<rigid::io::OutputFormat> formats = {rigid::io::OutputFormat::kCsv,
                                                        rigid::io::OutputFormat::kJson};
  (void)rigid::io::write_run(dir / "out", run, formats);
  const rigid::io::RunResult back = rigid::report::read_run(dir / "out");
  EXPECT_EQ(back.schema, model.schema());
  EXPECT_EQ(back.summary.kind, rigid::io::RunKind::kFreeBodies);
  const json page = json::parse(report_json(model, back, {.max_frames = 50}));
  std::size_t checked = 0;
  for (const json& s : page["series"]) {
    if (s["group"] == "energy_error" || s["group"] == "L_error") continue;  // relative changes
    const rigid::io::Column* c = model.schema().find(s["column"].get<std::string>());
    ASSERT_NE(c, nullptr) << s["column"];
    EXPECT_EQ(s["unit"], c->unit) << s["column"];
    if (c->quantity == rigid::io::Quantity::kAngularVelocity) {
      EXPECT_EQ(s["unit"], "rad/s");
    }
    ++checked;
  }
  EXPECT_GT(checked, 10u);

  // a schema that disagrees with the trajectory
  json summary = json::parse(std::ifstream(dir / "out" / "summary.json"));
  summary["schema"]["columns"][1]["name"] = "cone.xx";
  std::ofstream(dir / "out" / "summary.json") << summary.dump();
  EXPECT_RIGID_ERROR((void)rigid::report::read_run(dir / "out"), "disagree: the schema names the columns t, cone.xx");
  summary["schema"]["columns"][1]["quantity"] = "place";
  std::ofstream(dir / "out" / "summary.json") << summary.dump();
  EXPECT_RIGID_ERROR((void)rigid::report::read_run(dir / "out"), "unknown quantity 'place'");
  summary["kind"] = "free_body";
  std::ofstream(dir / "out" / "summary.json") << summary.dump();
  EXPECT_RIGID_ERROR((void)rigid::report::read_run(dir / "out"), "\"kind\": unknown run kind 'free_body'");

  // an older summary without a schema: the page takes the model's
  summary.erase("schema");
  summary["kind"] = "free_bodies";
  std::ofstream(dir / "out" / "summary.json") << summary.dump();
  const rigid::io::RunResult old = rigid::report::read_run(dir / "out");
  EXPECT_TRUE(old.schema.columns.empty());
  EXPECT_EQ(json::parse(report_json(model, old, {.max_frames = 50}))["series"], page["series"]);
  fs::remove_all(dir);
}

}  // namespace
