#include "cmd_inertia.hpp"
#include "cmd_mesh.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/inertial_xml.hpp"
#include "rigid/mass/primitives.hpp"

namespace rigid::cli {
namespace {

using Sizes = std::map<std::string, double>;
using Points = std::map<std::string, Eigen::Vector3d>;
using Factory = std::function<MassProperties(double, const Sizes&, const Points&)>;

struct Primitive {
  PrimitiveSpec spec;
  Factory with_mass;
  Factory with_density;
};

const std::vector<Primitive>& primitives() {
  static const std::vector<Primitive> table = [] {
    std::vector<Primitive> t;
    const std::string V = "kg/m³";
    const std::string A = "kg/m²";
    auto add = [&](std::string name, std::string help,
                   std::vector<std::pair<std::string, std::string>> sizes, std::string unit,
                   Factory m, Factory d,
                   std::vector<std::pair<std::string, std::string>> points = {}) {
      t.push_back(Primitive{PrimitiveSpec{std::move(name), std::move(help), std::move(sizes),
                                          std::move(unit), std::move(points)},
                            std::move(m), std::move(d)});
    };
    auto s = [](const Sizes& z, const char* k) { return z.at(k); };
    add("sphere", "solid sphere, centred", {{"radius", "radius (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::solid_sphere_with_mass(m, s(z, "radius")); },
        [=](double d, const Sizes& z, const Points&) { return mass::solid_sphere_with_density(d, s(z, "radius")); });
    add("thick-spherical-shell", "solid shell between two spheres, centred",
        {{"inner-radius", "inner radius (m)"}, {"outer-radius", "outer radius (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::thick_spherical_shell_with_mass(m, s(z, "inner-radius"), s(z, "outer-radius")); },
        [=](double d, const Sizes& z, const Points&) { return mass::thick_spherical_shell_with_density(d, s(z, "inner-radius"), s(z, "outer-radius")); });
    add("thin-spherical-shell", "spherical surface, centred (density in kg/m²)",
        {{"radius", "radius (m)"}}, A,
        [=](double m, const Sizes& z, const Points&) { return mass::thin_spherical_shell_with_mass(m, s(z, "radius")); },
        [=](double d, const Sizes& z, const Points&) { return mass::thin_spherical_shell_with_density(d, s(z, "radius")); });
    add("ellipsoid", "solid ellipsoid, semi-axes along x, y, z, centred",
        {{"semi-x", "semi-axis along x (m)"}, {"semi-y", "semi-axis along y (m)"}, {"semi-z", "semi-axis along z (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::solid_ellipsoid_with_mass(m, s(z, "semi-x"), s(z, "semi-y"), s(z, "semi-z")); },
        [=](double d, const Sizes& z, const Points&) { return mass::solid_ellipsoid_with_density(d, s(z, "semi-x"), s(z, "semi-y"), s(z, "semi-z")); });
    add("box", "solid box, edges along x, y, z, centred",
        {{"lx", "edge along x (m)"}, {"ly", "edge along y (m)"}, {"lz", "edge along z (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::solid_box_with_mass(m, s(z, "lx"), s(z, "ly"), s(z, "lz")); },
        [=](double d, const Sizes& z, const Points&) { return mass::solid_box_with_density(d, s(z, "lx"), s(z, "ly"), s(z, "lz")); });
    add("cylinder", "solid cylinder, axis z, centred", {{"radius", "radius (m)"}, {"height", "height (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::solid_cylinder_with_mass(m, s(z, "radius"), s(z, "height")); },
        [=](double d, const Sizes& z, const Points&) { return mass::solid_cylinder_with_density(d, s(z, "radius"), s(z, "height")); });
    add("tube", "thick-walled tube, axis z, centred",
        {{"inner-radius", "inner radius (m)"}, {"outer-radius", "outer radius (m)"}, {"height", "height (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::thick_tube_with_mass(m, s(z, "inner-radius"), s(z, "outer-radius"), s(z, "height")); },
        [=](double d, const Sizes& z, const Points&) { return mass::thick_tube_with_density(d, s(z, "inner-radius"), s(z, "outer-radius"), s(z, "height")); });
    add("cylindrical-shell", "thin open cylindrical surface, axis z, centred (density in kg/m²)",
        {{"radius", "radius (m)"}, {"height", "height (m)"}}, A,
        [=](double m, const Sizes& z, const Points&) { return mass::thin_cylindrical_shell_with_mass(m, s(z, "radius"), s(z, "height")); },
        [=](double d, const Sizes& z, const Points&) { return mass::thin_cylindrical_shell_with_density(d, s(z, "radius"), s(z, "height")); });
    add("capped-cylindrical-shell", "thin cylindrical surface with end disks, axis z, centred (kg/m²)",
        {{"radius", "radius (m)"}, {"height", "height (m)"}}, A,
        [=](double m, const Sizes& z, const Points&) { return mass::capped_cylindrical_shell_with_mass(m, s(z, "radius"), s(z, "height")); },
        [=](double d, const Sizes& z, const Points&) { return mass::capped_cylindrical_shell_with_density(d, s(z, "radius"), s(z, "height")); });
    add("cone", "solid cone, base at z = 0, apex at z = height", {{"radius", "base radius (m)"}, {"height", "height (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::solid_cone_with_mass(m, s(z, "radius"), s(z, "height")); },
        [=](double d, const Sizes& z, const Points&) { return mass::solid_cone_with_density(d, s(z, "radius"), s(z, "height")); });
    add("frustum", "solid conical frustum, bottom at z = 0, top at z = height",
        {{"bottom-radius", "radius at z = 0 (m)"}, {"top-radius", "radius at z = height (m)"}, {"height", "height (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::solid_frustum_with_mass(m, s(z, "bottom-radius"), s(z, "top-radius"), s(z, "height")); },
        [=](double d, const Sizes& z, const Points&) { return mass::solid_frustum_with_density(d, s(z, "bottom-radius"), s(z, "top-radius"), s(z, "height")); });
    add("capsule", "solid capsule, axis z, centred (total length = length + 2 radius)",
        {{"radius", "radius (m)"}, {"length", "length of the cylindrical part (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::solid_capsule_with_mass(m, s(z, "radius"), s(z, "length")); },
        [=](double d, const Sizes& z, const Points&) { return mass::solid_capsule_with_density(d, s(z, "radius"), s(z, "length")); });
    add("torus", "solid torus, axis z, centred",
        {{"major-radius", "radius of the centre circle (m)"}, {"minor-radius", "radius of the tube (m)"}}, V,
        [=](double m, const Sizes& z, const Points&) { return mass::solid_torus_with_mass(m, s(z, "major-radius"), s(z, "minor-radius")); },
        [=](double d, const Sizes& z, const Points&) { return mass::solid_torus_with_density(d, s(z, "major-radius"), s(z, "minor-radius")); });
    add("rod", "thin rod along z, centred (density in kg/m)", {{"length", "length (m)"}}, "kg/m",
        [=](double m, const Sizes& z, const Points&) { return mass::thin_rod_with_mass(m, s(z, "length")); },
        [=](double d, const Sizes& z, const Points&) { return mass::thin_rod_with_density(d, s(z, "length")); });
    add("plate", "thin rectangular plate in the xy-plane, centred (kg/m²)",
        {{"lx", "edge along x (m)"}, {"ly", "edge along y (m)"}}, A,
        [=](double m, const Sizes& z, const Points&) { return mass::thin_rectangular_plate_with_mass(m, s(z, "lx"), s(z, "ly")); },
        [=](double d, const Sizes& z, const Points&) { return mass::thin_rectangular_plate_with_density(d, s(z, "lx"), s(z, "ly")); });
    add("disk", "thin disk in the xy-plane, centred (kg/m²)", {{"radius", "radius (m)"}}, A,
        [=](double m, const Sizes& z, const Points&) { return mass::thin_disk_with_mass(m, s(z, "radius")); },
        [=](double d, const Sizes& z, const Points&) { return mass::thin_disk_with_density(d, s(z, "radius")); });
    auto v = [](const Points& z, const char* k) { return z.at(k); };
    add("tetrahedron", "solid tetrahedron with the given vertices (coordinates kept)", {}, V,
        [=](double m, const Sizes&, const Points& z) { return mass::solid_tetrahedron_with_mass(m, v(z, "v0"), v(z, "v1"), v(z, "v2"), v(z, "v3")); },
        [=](double d, const Sizes&, const Points& z) { return mass::solid_tetrahedron_with_density(d, v(z, "v0"), v(z, "v1"), v(z, "v2"), v(z, "v3")); },
        {{"v0", "vertex 0 as x,y,z (m)"}, {"v1", "vertex 1 as x,y,z (m)"}, {"v2", "vertex 2 as x,y,z (m)"}, {"v3", "vertex 3 as x,y,z (m)"}});
    return t;
  }();
  return table;
}

// "x,y,z" in metres; `what` names the option in the message
Eigen::Vector3d parse_xyz(const std::string& text, const std::string& what) {
  Eigen::Vector3d p;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t end = i < 2 ? text.find(',', start) : text.size();
    const bool ok_sep = end != std::string::npos;
    double value = 0.0;
    const char* first = text.data() + start;
    const char* last = text.data() + (ok_sep ? end : text.size());
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (!ok_sep || ec != std::errc() || ptr != last || !std::isfinite(value)) {
      RIGID_THROW("{} must be a point 'x,y,z' in metres, got '{}'", what, text);
    }
    p(i) = value;
    start = end + 1;
  }
  return p;
}

Eigen::Vector3d parse_about(const std::string& about, const MassProperties& mp) {
  if (about == "com") return mp.com();
  if (about == "origin") return Eigen::Vector3d::Zero();
  if (about.find(',') == std::string::npos) {
    RIGID_THROW("--about must be 'com', 'origin' or a point 'x,y,z' in metres, got '{}'", about);
  }
  return parse_xyz(about, "--about");
}

std::string json_vec(const Eigen::Vector3d& v) {
  return fmt::format("[{}, {}, {}]", v(0) + 0.0, v(1) + 0.0, v(2) + 0.0);
}

std::string json_mat(const Eigen::Matrix3d& m) {
  return fmt::format("[{}, {}, {}]", json_vec(m.row(0)), json_vec(m.row(1)), json_vec(m.row(2)));
}

// a matrix with its columns aligned, for people
std::string text_mat(const Eigen::Matrix3d& m, const char* indent) {
  std::string out;
  for (int i = 0; i < 3; ++i) {
    out += fmt::format("{}[{:>14.7g} {:>14.7g} {:>14.7g} ]\n", indent, m(i, 0), m(i, 1), m(i, 2));
  }
  return out;
}

}  // namespace

const std::vector<PrimitiveSpec>& inertia_primitives() {
  static const std::vector<PrimitiveSpec> specs = [] {
    std::vector<PrimitiveSpec> s;
    for (const auto& p : primitives()) s.push_back(p.spec);
    return s;
  }();
  return specs;
}

std::string format_inertia(const MassProperties& mp, const InertiaOutputOptions& out) {
  RIGID_REQUIRE(out.frame == "body" || out.frame == "principal",
                "--frame must be 'body' or 'principal', got '{}'", out.frame);
  const bool principal = out.frame == "principal";
  for (const auto format : {io::InertialFormat::urdf, io::InertialFormat::mjcf, io::InertialFormat::sdf}) {
    if (out.format == io::to_string(format)) {
      RIGID_REQUIRE(out.about == "com",
                    "--about {} cannot be used with --format {}: {} stores the inertia about the "
                    "center of mass; leave --about at 'com'",
                    out.about, out.format, out.format);
      return io::write_inertial_document(mp, format, {.name = out.name, .principal = principal});
    }
  }
  RIGID_REQUIRE(out.format == "text" || out.format == "json",
                "--format must be one of text, json, urdf, mjcf, sdf; got '{}'", out.format);
  const Eigen::Vector3d about = parse_about(out.about, mp);
  const Eigen::Matrix3d I = mp.inertia_about(about);
  // principal axes of the tensor about the chosen point (a physical tensor, so it can be
  // wrapped as the inertia of a body)
  const PrincipalAxes pa = MassProperties(mp.mass(), mp.com(), I).principal_axes();
  const Eigen::Quaterniond q(pa.R_BP);
  if (out.format == "json") {
    std::string j = fmt::format("{{\n  \"mass\": {},\n  \"com\": {},\n  \"about\": {},\n", mp.mass(),
                                json_vec(mp.com()), json_vec(about));
    if (principal) {
      j += fmt::format(
          "  \"frame\": \"principal\",\n  \"principal_moments\": {},\n  \"R_BP\": {},\n"
          "  \"quat_wxyz\": [{}, {}, {}, {}]\n}}\n",
          json_vec(pa.moments), json_mat(pa.R_BP), q.w(), q.x(), q.y(), q.z());
    } else {
      j += fmt::format("  \"frame\": \"body\",\n  \"inertia\": {}\n}}\n", json_mat(I));
    }
    return j;
  }
  const std::string where = out.about == "com" ? "the center of mass" : fmt::format("{} m", json_vec(about));
  std::string t = fmt::format("mass            {:.10g} kg\n", mp.mass());
  t += fmt::format("center of mass  [{:.10g}, {:.10g}, {:.10g}] m\n", mp.com()(0), mp.com()(1), mp.com()(2));
  if (principal) {
    t += fmt::format("principal moments about {} (ascending)\n  [{:.10g}, {:.10g}, {:.10g}] kg·m²\n",
                     where, pa.moments(0), pa.moments(1), pa.moments(2));
    t += "principal axes (columns, in the body frame)\n" + text_mat(pa.R_BP, "  ");
    t += fmt::format("as quaternion (w, x, y, z)  [{:.10g}, {:.10g}, {:.10g}, {:.10g}]\n", q.w(), q.x(),
                     q.y(), q.z());
  } else {
    t += fmt::format("inertia tensor about {}, body frame (kg·m²)\n", where) + text_mat(I, "  ");
  }
  return t;
}

void emit_inertia(const MassProperties& mp, const InertiaOutputOptions& out) {
  const std::string text = format_inertia(mp, out);
  if (out.output.empty()) {
    std::fputs(text.c_str(), stdout);
  } else {
    io::write_file_atomically(out.output, text);
  }
}

void run_inertia_primitive(const InertiaPrimitiveOptions& opts) {
  const Primitive* prim = nullptr;
  for (const auto& p : primitives()) {
    if (p.spec.name == opts.primitive) prim = &p;
  }
  RIGID_REQUIRE(prim != nullptr, "unknown primitive '{}'", opts.primitive);
  RIGID_REQUIRE(opts.mass.has_value() != opts.density.has_value(),
                "give exactly one of --mass (kg) and --density ({}), got {}",
                prim->spec.density_unit, opts.mass ? "both" : "neither");
  for (const auto& [name, help] : prim->spec.sizes) {
    RIGID_REQUIRE(opts.sizes.count(name) == 1, "{} needs --{} ({})", opts.primitive, name, help);
  }
  Points points;
  for (const auto& [name, help] : prim->spec.points) {
    const auto it = opts.points.find(name);
    RIGID_REQUIRE(it != opts.points.end(), "{} needs --{} ({})", opts.primitive, name, help);
    points[name] = parse_xyz(it->second, "--" + name);
  }
  const MassProperties mp = opts.mass ? prim->with_mass(*opts.mass, opts.sizes, points)
                                      : prim->with_density(*opts.density, opts.sizes, points);
  emit_inertia(mp, opts.output);
}

void run_inertia_source(const InertiaSourceOptions& opts) {
  std::string names;
  for (const auto& p : primitives()) names += (names.empty() ? "" : ", ") + p.spec.name;
  RIGID_REQUIRE(!opts.source.empty(), "give a primitive ({}) or `check FILE`", names);
  if (is_mesh_file(opts.source)) {
    run_inertia_mesh(
        opts.source,
        {opts.mass, opts.density, opts.units, opts.shell, opts.thickness, opts.fill_holes},
        opts.output);
    return;
  }
  RIGID_THROW("unknown primitive '{}'; expected one of {}, or `check FILE`", opts.source, names);
}

void run_inertia_check(const InertiaCheckOptions& opts) {
  const auto entries = io::read_inertials_file(opts.file);
  int invalid = 0;
  for (const auto& e : entries) {
    if (e.problem) {
      ++invalid;
      std::fputs(fmt::format("{}:{}: '{}': {}\n", opts.file, e.line, e.name, *e.problem).c_str(), stdout);
    }
  }
  std::fputs(fmt::format("{}: {} inertial{}, {} invalid\n", opts.file, entries.size(),
                         entries.size() == 1 ? "" : "s", invalid)
                 .c_str(),
             stdout);
  std::fflush(stdout);
  RIGID_REQUIRE(invalid == 0, "{} of {} inertials in {} are invalid (listed above)", invalid,
                entries.size(), opts.file);
}

}  // namespace rigid::cli
