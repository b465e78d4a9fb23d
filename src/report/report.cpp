#include "rigid/report/report.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "report/detail/assets.hpp"
#include "report/detail/connections.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/io/run_schema.hpp"
#include "rigid/io/table.hpp"
#include "rigid/mass/primitive_table.hpp"
#include "rigid/mesh/read_mesh.hpp"
#include "detail/sweep_files.hpp"

namespace rigid::report {
namespace {
using detail::base64;

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// Arrays of more than this many numbers are stored as base64 float32 (schema v1); smaller
// ones as plain JSON arrays.
constexpr std::size_t kPlainArrayMax = 16;


// Little-endian bytes of 32-bit words, whatever the machine's order.
void append_le(std::string& out, std::uint32_t w) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((w >> (8 * k)) & 0xFF));
}

// "f32:BASE64" of the values rounded to float32 (nearest), or a plain array when short.
json f32(const std::vector<double>& values) {
  if (values.size() <= kPlainArrayMax) return json(values);
  std::string bytes;
  bytes.reserve(4 * values.size());
  for (const double v : values) append_le(bytes, std::bit_cast<std::uint32_t>(static_cast<float>(v)));
  return "f32:" + base64(bytes);
}

json u32(const std::vector<std::uint32_t>& values) {
  if (values.size() <= kPlainArrayMax) return json(values);
  std::string bytes;
  bytes.reserve(4 * values.size());
  for (const std::uint32_t v : values) append_le(bytes, v);
  return "u32:" + base64(bytes);
}

json vec3(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json mat3_rows(const Eigen::Matrix3d& m) {
  json rows = json::array();
  for (int r = 0; r < 3; ++r) rows.push_back(json::array({m(r, 0), m(r, 1), m(r, 2)}));
  return rows;
}

json mat3_columns(const Eigen::Matrix3d& m) { return mat3_rows(m.transpose()); }

// 1st, 2nd, 3rd, 4th, … 11th, 12th, 13th, 21st
std::string ordinal(std::size_t n) {
  const std::size_t tens = n % 100, ones = n % 10;
  const char* suffix = (tens >= 11 && tens <= 13) ? "th" : ones == 1 ? "st" : ones == 2 ? "nd" : ones == 3 ? "rd" : "th";
  return fmt::format("{}{}", n, suffix);
}

// The leading comment lines of the scene file, without their '#'.
std::string description_of(const fs::path& file) {
  std::ifstream in(file);
  std::string line, text;
  while (std::getline(in, line)) {
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] != '#') break;
    std::string body = line.substr(start + 1);
    if (!body.empty() && body.front() == ' ') body.erase(0, 1);
    text += (text.empty() ? "" : "\n") + body;
  }
  return text;
}

// The shape the page draws: the catalogue's canonical primitive mapped onto the kinds the
// page knows; other primitives are drawn by their inertia only.
json shape_of(const scene::Body& b, const scene::ModelBody& mb, std::optional<std::size_t> mesh) {
  json shape;
  json sizes = json::object();
  for (const auto& [name, value] : mb.sizes) sizes[name] = value;
  std::string kind = "inertia_only";
  if (b.mass.kind == scene::MassSpec::Kind::kMesh) {
    kind = "mesh";
  } else if (b.mass.kind == scene::MassSpec::Kind::kPrimitive) {
    static const std::map<std::string, std::string, std::less<>> kKinds = {
        {"solid_box", "box"},           {"solid_cylinder", "cylinder"}, {"solid_sphere", "sphere"},
        {"solid_ellipsoid", "ellipsoid"}, {"solid_capsule", "capsule"},   {"solid_cone", "cone"}};
    const std::string& canonical = mass::find_primitive(b.mass.primitive).name;
    if (const auto it = kKinds.find(canonical); it != kKinds.end()) kind = it->second;
    shape["primitive"] = canonical;
  }
  shape["kind"] = kind;
  shape["sizes"] = sizes;
  shape["mesh"] = mesh ? json(*mesh) : json(nullptr);
  return shape;
}

// A mesh as the page stores it: float32 positions (m, body frame) and uint32 indices.
json mesh_json(const mesh::TriangleMesh& m) {
  std::vector<double> positions;
  positions.reserve(3 * m.vertices.size());
  for (const Eigen::Vector3d& v : m.vertices) positions.insert(positions.end(), {v.x(), v.y(), v.z()});
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles) indices.insert(indices.end(), t.begin(), t.end());
  return json{{"positions", f32(positions)}, {"indices", u32(indices)}, {"triangles", m.triangles.size()},
              {"quantised", false}};
}

// Which plot a trajectory column belongs to, by its quantity.
std::string_view group_of(const io::Column& column) {
  using Q = io::Quantity;
  switch (column.quantity) {
    case Q::kCoordinate:
      return "coordinates";
    case Q::kCoordinateRate:
    case Q::kVelocity:
    case Q::kAngularVelocity:
      return "velocities";
    case Q::kMultiplier:
    case Q::kVelocityMultiplier:
      return "multipliers";
    case Q::kConstraintResidual:
    case Q::kVelocityConstraintResidual:
      return "residuals";
    default:
      return "other";
  }
}

// |x − x0| / |x0|, or |x − x0| (then `absolute` is set) when |x0| is not larger than the
// largest change: a relative change of 1 or more says nothing, and such an x0 is the round-off
// of a zero (a double pendulum released from rest at the potential's zero has E(0) ≈ −2e-15 J).
// The drift metrics (src/scene/model.cpp) use the same rule.
std::vector<double> relative_change(const std::vector<double>& x, bool& absolute) {
  const double x0 = x.front();
  double largest = 0.0;
  for (const double v : x) largest = std::max(largest, std::abs(v - x0));
  absolute = std::abs(x0) <= largest;
  std::vector<double> out(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) out[i] = std::abs(x[i] - x0) / (absolute ? 1.0 : std::abs(x0));
  return out;
}

std::string html_escape(std::string_view s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out.push_back(c);
    }
  }
  return out;
}

}  // namespace

bool available() { return !detail::kReportJs.empty(); }

Decimation decimate(std::size_t samples, std::size_t max_frames) {
  RIGID_REQUIRE(max_frames >= kMinMaxFrames && max_frames <= kMaxMaxFrames,
                "the number of report frames must be between {} and {}, got {}", kMinMaxFrames, kMaxMaxFrames,
                max_frames);
  RIGID_REQUIRE(samples > 0, "the run has no samples; a report needs at least one row of the trajectory");
  Decimation d;
  // rows 0, k, 2k, … ≤ n − 1, and n − 1: ⌊(n−1)/k⌋ + 1 rows, one more when k does not divide
  // n − 1 (then ⌊(n−1)/k⌋ < (n−1)/k ≤ M − 1); k = ⌈(n−1)/(M−1)⌉ keeps at most M
  d.stride = samples <= max_frames ? 1 : (samples - 1 + max_frames - 2) / (max_frames - 1);
  for (std::size_t r = 0; r < samples; r += d.stride) d.rows.push_back(r);
  const bool last = d.rows.back() != samples - 1;
  if (last) d.rows.push_back(samples - 1);
  if (d.stride == 1) {
    d.rule = fmt::format("every sample of {} (at most {} frames)", samples, max_frames);
  } else {
    d.rule = fmt::format("every {} of {} samples{} (at most {} frames)", ordinal(d.stride), samples,
                         last ? ", and the last" : "", max_frames);
  }
  return d;
}

std::string report_json(const scene::Model& model, const io::RunResult& result, const ReportOptions& options) {
  const io::Table& table = result.trajectory;
  const Decimation dec = decimate(table.rows(), options.max_frames);
  const io::RunSummary& s = result.summary;
  const scene::Scene& sc = model.scene();
  auto column = [&](const std::string& name) -> std::vector<double> {
    const auto& cols = table.columns();
    if (std::find(cols.begin(), cols.end(), name) == cols.end()) {
      throw Error(fmt::format("the report needs the trajectory column '{}', which the run does not have; "
                              "the scene's [output] quantities leaves it out: keep it (or remove quantities)",
                              name));
    }
    const std::size_t c = table.column(name);
    std::vector<double> out;
    out.reserve(dec.rows.size());
    for (const std::size_t r : dec.rows) out.push_back(table(r, c));
    return out;
  };
  auto has = [&](const std::string& name) {
    return std::find(table.columns().begin(), table.columns().end(), name) != table.columns().end();
  };

  // what each column is: the run's own schema (summary.json's, or the model's for a run made
  // here), every column of the table in it
  const io::RunSchema& schema = result.schema.columns.empty() ? model.schema() : result.schema;
  auto info = [&](const std::string& name) -> const io::Column& {
    const io::Column* c = schema.find(name);
    if (c == nullptr) {
      throw Error(fmt::format(
          "the run's column '{}' is not one the scene '{}' makes (its columns: {}); the "
          "scene changed since the run: run it again",
          name, sc.file.string(), fmt::join(schema.column_names(), ", ")));
    }
    return *c;
  };
  for (const std::string& c : table.columns()) (void)info(c);
  using Q = io::Quantity;

  json j;
  j["rigid_report"] = 1;
  // names of any bytes (0xff) escaped: the JSON writer needs UTF-8
  const std::string name = escaped(sc.file.stem().string());
  j["scene"] = {{"name", name}, {"file", s.scene.empty() ? escaped(sc.file.string()) : s.scene},
                {"description", description_of(sc.file)}};
  j["kind"] = io::to_string(model.kind());
  json params = json::array();
  const std::vector<io::Scalar>& units = model.schema().parameters;
  for (std::size_t k = 0; k < model.parameters().size(); ++k) {
    const lagrange::Parameter& p = model.parameters()[k];
    params.push_back({{"name", p.name}, {"value", p.value}, {"unit", units.at(k).unit}});
  }
  j["parameters"] = params;
  j["integrator"] = {{"method", s.integrator}, {"dt", s.dt},       {"tolerance", s.tolerance},
                     {"steps", s.steps},       {"rhs_evaluations", s.rhs_evaluations},
                     {"t_end", s.t_end},       {"samples", table.rows()}, {"wall_time_s", s.wall_seconds}};
  json diag = json::object();
  for (const auto& [k, v] : s.diagnostics) diag[k] = v;
  j["diagnostics"] = diag;
  j["warnings"] = s.warnings;
  j["equations_latex"] = model.equations(true);

  // bodies, and their meshes once per (file, unit)
  json bodies = json::array(), meshes = json::array();
  std::map<std::pair<std::string, std::string>, std::size_t> mesh_index;
  for (std::size_t i = 0; i < model.bodies().size(); ++i) {
    const scene::ModelBody& mb = model.bodies()[i];
    const scene::Body& b = sc.bodies[i];
    std::optional<std::size_t> mesh;
    if (b.mass.kind == scene::MassSpec::Kind::kMesh) {
      std::error_code ec;
      const fs::path canonical = fs::weakly_canonical(b.mass.mesh_file, ec);
      const auto key = std::make_pair((ec ? b.mass.mesh_file : canonical).string(), b.mass.units);
      auto it = mesh_index.find(key);
      if (it == mesh_index.end()) {
        const mesh::TriangleMesh m = mesh::read_mesh(b.mass.mesh_file.string(), mesh::unit_scale(b.mass.units));
        it = mesh_index.emplace(key, meshes.size()).first;
        meshes.push_back(mesh_json(m));
      }
      mesh = it->second;
    }
    const PrincipalAxes pa = mb.mass.principal_axes();
    bodies.push_back({{"name", mb.name},
                      {"mass", mb.mass.mass()},
                      {"com", vec3(mb.mass.com())},
                      {"inertia_com", mat3_rows(mb.mass.inertia_com())},
                      {"principal_moments", vec3(pa.moments)},
                      {"principal_axes", mat3_columns(pa.R_BP)},
                      {"shape", shape_of(b, mb, mesh)},
                      {"free", mb.free}});
  }
  j["bodies"] = bodies;
  j["meshes"] = meshes;

  // frames: each body's COM and orientation in the world, from its pose columns
  // (p_WC = p_WB + R_WB c_B), ω and L in the world for free bodies
  json frames;
  frames["count"] = dec.rows.size();
  frames["rule"] = dec.rule;
  frames["t"] = f32(column("t"));
  json frame_bodies = json::array();
  std::vector<detail::BodyPoses> poses;
  for (const scene::ModelBody& mb : model.bodies()) {
    const std::string& n = mb.name;
    static constexpr const char* kXyz[3] = {"x", "y", "z"};
    static constexpr const char* kWxyz[4] = {"w", "x", "y", "z"};
    std::array<std::vector<double>, 7> pose;
    for (std::size_t k = 0; k < 3; ++k) {
      pose[k] = column(io::body_column(Q::kPosition, n, kXyz[k]).name);
    }
    for (std::size_t k = 0; k < 4; ++k) {
      pose[3 + k] = column(io::body_column(Q::kOrientation, n, kWxyz[k]).name);
    }
    const io::Column* wx = schema.find(Q::kAngularVelocity, n, "x");
    const bool twist = wx != nullptr && has(wx->name);
    std::array<std::vector<double>, 3> w, L;
    if (twist) {
      for (std::size_t k = 0; k < 3; ++k) {
        w[k] = column(io::body_column(Q::kAngularVelocity, n, kXyz[k]).name);
        const std::string Lk = io::body_column(Q::kAngularMomentum, n, kXyz[k]).name;
        L[k] = has(Lk) ? column(Lk) : std::vector<double>{};
      }
    }
    std::vector<double> position, quaternion, omega, momentum;
    detail::BodyPoses& X_WB = poses.emplace_back();
    for (std::size_t f = 0; f < dec.rows.size(); ++f) {
      const Eigen::Quaterniond q(pose[3][f], pose[4][f], pose[5][f], pose[6][f]);
      const Eigen::Matrix3d R_WB = q.normalized().toRotationMatrix();
      const Eigen::Vector3d p_WB(pose[0][f], pose[1][f], pose[2][f]);
      X_WB.p_WB.push_back(p_WB);
      X_WB.R_WB.push_back(q.normalized());
      const Eigen::Vector3d p_WC = p_WB + R_WB * mb.mass.com();
      position.insert(position.end(), {p_WC.x(), p_WC.y(), p_WC.z()});
      quaternion.insert(quaternion.end(), {pose[3][f], pose[4][f], pose[5][f], pose[6][f]});
      if (twist) {
        const Eigen::Vector3d w_W = R_WB * Eigen::Vector3d(w[0][f], w[1][f], w[2][f]);
        omega.insert(omega.end(), {w_W.x(), w_W.y(), w_W.z()});
        if (!L[0].empty()) momentum.insert(momentum.end(), {L[0][f], L[1][f], L[2][f]});
      }
    }
    frame_bodies.push_back({{"position", f32(position)},
                            {"quaternion", f32(quaternion)},
                            {"omega", twist ? f32(omega) : json(nullptr)},
                            {"L", !momentum.empty() ? f32(momentum) : json(nullptr)}});
  }
  frames["bodies"] = frame_bodies;
  j["frames"] = frames;

  // what connects the bodies: rods to the bodies they hang from, and pivots in the world
  json links = json::array();
  for (const detail::Link& l : detail::find_links(model, poses)) {
    links.push_back({{"body", l.body},
                     {"point", vec3(l.point_B)},
                     {"to", l.to ? json(*l.to) : json(nullptr)},
                     {"to_point", vec3(l.point_to)},
                     {"rule", l.rule}});
  }
  j["links"] = links;

  // the scene's metrics; an instant (a crossing, the time of an extremum) is marked on the plots
  json metrics = json::array();
  for (const io::Metric& m : s.metrics) {
    bool instant = false;
    for (const scene::MetricSpec& spec : sc.output.metrics) {
      if (spec.name != m.name) continue;
      using K = scene::MetricSpec::Kind;
      instant = m.unit == "s" && (spec.kind == K::kCrossing || (spec.kind == K::kExtremum && !spec.report_value));
    }
    metrics.push_back({{"name", m.name},
                       {"value", std::isfinite(m.value) ? json(m.value) : json(nullptr)},
                       {"unit", m.unit},
                       {"note", m.note},
                       {"instant", instant}});
  }
  j["metrics"] = metrics;

  // series: every trajectory column but t and the poses, on the frames' times; then the
  // relative changes of the energy and of each free body's |L|
  json series = json::array();
  const io::Column* energy = nullptr;
  for (const std::string& c : table.columns()) {
    const io::Column& col = info(c);
    if (col.quantity == Q::kEnergy) energy = &col;
    if (col.quantity == Q::kTime || col.quantity == Q::kPosition || col.quantity == Q::kOrientation) {
      continue;
    }
    series.push_back({{"group", group_of(col)},
                      {"name", c},
                      {"quantity", io::to_string(col.quantity)},
                      {"unit", col.unit},
                      {"column", c},
                      {"values", f32(column(c))}});
  }
  if (energy != nullptr) {
    bool absolute = false;
    const std::vector<double> e = relative_change(column(energy->name), absolute);
    series.push_back({{"group", "energy_error"},
                      {"name", absolute ? "|E − E(0)|" : "|E − E(0)| / |E(0)|"},
                      {"quantity", absolute ? "energy_change" : "relative_change"},
                      {"unit", absolute ? energy->unit : ""},
                      {"column", energy->name},
                      {"values", f32(e)}});
  }
  for (const scene::ModelBody& mb : model.bodies()) {
    const std::string& n = mb.name;
    // |L| about the COM is conserved for a free body in uniform gravity; a top's L is about its
    // pivot and turns with gravity's torque, so it has no such series
    bool top = false;
    for (const scene::Body& b : sc.bodies) top = top || (b.name == n && b.pivot.has_value());
    const io::Column* Lc = schema.find(Q::kAngularMomentum, n, "x");
    if (!mb.free || top || Lc == nullptr || !has(Lc->name)) continue;
    const std::vector<double> Lx = column(Lc->name),
                              Ly = column(schema.find(Q::kAngularMomentum, n, "y")->name),
                              Lz = column(schema.find(Q::kAngularMomentum, n, "z")->name);
    std::vector<double> norm(Lx.size());
    for (std::size_t f = 0; f < norm.size(); ++f) norm[f] = std::sqrt(Lx[f] * Lx[f] + Ly[f] * Ly[f] + Lz[f] * Lz[f]);
    bool absolute = false;
    const std::vector<double> e = relative_change(norm, absolute);
    series.push_back({{"group", "L_error"},
                      {"name", n + (absolute ? " |L − L(0)|" : " ||L| − |L(0)|| / |L(0)|")},
                      {"quantity", absolute ? "angular_momentum_change" : "relative_change"},
                      {"unit", absolute ? Lc->unit : ""},
                      {"column", n + ".L"},
                      {"values", f32(e)}});
  }
  j["series"] = series;
  j["size"] = {{"max_frames", options.max_frames},
               {"bytes_note", fmt::format("float32 (base64), {}; meshes stored once", dec.rule)}};
  return j.dump();
}

std::string assemble_page(std::string_view title, std::string_view json_text) {
  if (!available()) {
    throw Error("this build of rigid has no report page (it was built without node: CMake option "
                "RIGID_REPORT=OFF); rebuild with RIGID_REPORT=ON (the ci and release presets) to write reports");
  }
  // the data may not end its script element: "</" becomes "<\/" (the same JSON string) and
  // "<!--" becomes "\u003c!--" (the HTML parser's script-data escape states)
  std::string data;
  data.reserve(json_text.size() + 64);
  for (std::size_t i = 0; i < json_text.size(); ++i) {
    if (json_text[i] == '<' && i + 1 < json_text.size() && json_text[i + 1] == '/') {
      data += "<\\";
    } else if (json_text.substr(i).starts_with("<!--")) {
      data += "\\u003c";
    } else {
      data.push_back(json_text[i]);
    }
  }
  std::string page;
  page.reserve(data.size() + detail::kReportJs.size() + detail::kReportCss.size() + 512);
  page += "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>rigid — ";
  page += html_escape(title);
  page += "</title><style>";
  page += detail::kReportCss;
  page += "</style></head><body><script type=\"application/json\" id=\"rigid-report-data\">";
  page += data;
  page += "</script><script>";
  page += detail::kReportJs;
  page += "</script></body></html>\n";
  return page;
}

std::string report_page(const scene::Model& model, const io::RunResult& result, const ReportOptions& options) {
  if (!available()) return assemble_page("", "");  // refuses before the work
  return assemble_page(model.scene().file.stem().string(), report_json(model, result, options));
}

}  // namespace rigid::report
