#include "cmd_inertia.hpp"
#include "cmd_mesh.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <span>

#include <fmt/format.h>

#include "cli_error.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/atomic_file.hpp"
#include "rigid/io/inertial_xml.hpp"
#include "rigid/lie/so3.hpp"
#include "rigid/mass/placement.hpp"
#include "rigid/mass/primitive_table.hpp"
#include "rigid/mass/pseudo_inertia.hpp"
#include "rigid/mass/uncertainty.hpp"
#include "rigid/scene/density_field.hpp"

namespace rigid::cli {
namespace {

// "x,y,z" in metres; `what` names the option in the message, `expected` the form
Eigen::Vector3d parse_xyz(const std::string& text, const std::string& what,
                          const char* expected = "a point 'x,y,z' in metres") {
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
      CLI_USAGE_THROW("{} must be {}, got '{}'", what, expected, text);
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
    CLI_USAGE_THROW("--about must be 'com', 'origin' or a point 'x,y,z' in metres, got '{}'{}", about,
                    did_you_mean_hint(about, {"com", "origin"}));
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

// --format pseudo | log-cholesky: the body about a frame origin, as JSON. Like urdf/mjcf/sdf
// these state the COM (h = m c), so --about com or origin keeps the link origin and
// --about x,y,z moves it to that point.
std::string format_identification(const MassProperties& mp, const InertiaOutputOptions& out) {
  CLI_USAGE_REQUIRE(out.frame == "body",
              "--frame {} cannot be used with --format {}: it states the body in the link frame "
              "about the link origin (or the --about point); leave --frame at body",
              out.frame, out.format);
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  if (out.about != "com" && out.about != "origin") p = parse_about(out.about, mp);
  const MassProperties stated = mp.shifted(-p);
  if (out.format == "pseudo") {
    const Eigen::Matrix4d J = mass::pseudo_inertia(stated);
    std::string rows;
    for (int i = 0; i < 4; ++i) {
      rows += fmt::format("{}[{}, {}, {}, {}]", i ? ", " : "", J(i, 0) + 0.0, J(i, 1) + 0.0, J(i, 2) + 0.0,
                          J(i, 3) + 0.0);
    }
    return fmt::format("{{\n  \"about\": {},\n  \"pseudo_inertia\": [{}]\n}}\n", json_vec(p), rows);
  }
  const mass::LogCholesky th = mass::log_cholesky(stated);
  return fmt::format(
      "{{\n  \"about\": {},\n  \"log_cholesky\": {{\"alpha\": {}, \"d\": [{}, {}, {}], \"s12\": {}, "
      "\"s23\": {}, \"s13\": {}, \"t\": [{}, {}, {}]}},\n  \"theta\": [{}]\n}}\n",
      json_vec(p), th(0), th(1), th(2), th(3), th(4), th(5), th(6), th(7), th(8), th(9),
      fmt::join(th.data(), th.data() + 10, ", "));
}

}  // namespace

std::string cli_name(const std::string& catalogue_name) {
  std::string n = catalogue_name;
  std::replace(n.begin(), n.end(), '_', '-');
  return n;
}

std::string format_inertia(const MassProperties& mp, const InertiaOutputOptions& out) {
  CLI_USAGE_REQUIRE(out.frame == "body" || out.frame == "principal",
                    "--frame must be 'body' or 'principal', got '{}'{}", out.frame,
                    did_you_mean_hint(out.frame, {"body", "principal"}));
  const bool principal = out.frame == "principal";
  if (out.format == "pseudo" || out.format == "log-cholesky") return format_identification(mp, out);
  for (const auto format : {io::InertialFormat::urdf, io::InertialFormat::mjcf, io::InertialFormat::sdf}) {
    if (out.format == io::to_string(format)) {
      // the file states the inertia about the COM and the COM from the link origin, which
      // fixes the inertia about any point: about a point p, the link origin goes to p
      MassProperties stated = mp;
      if (out.about != "com" && out.about != "origin") {
        const Eigen::Vector3d p = parse_about(out.about, mp);
        CLI_USAGE_REQUIRE(!principal,
                    "--frame principal with --about {} cannot be written as {}: {} gives the "
                    "principal axes of the inertia about the center of mass, and those of the "
                    "tensor about {} differ; use --frame body (the file then states the inertia "
                    "about the point exactly, with the link origin there) or --format text/json",
                    out.about, out.format, out.format, out.about);
        stated = mp.shifted(-p);
      }
      return io::write_inertial_document(
          stated, format, {.name = out.name, .principal = principal}, out.inertial_frame);
    }
  }
  CLI_USAGE_REQUIRE(out.format == "text" || out.format == "json",
                    "--format must be one of text, json, urdf, mjcf, sdf, pseudo, log-cholesky; got '{}'{}",
                    out.format,
                    did_you_mean_hint(out.format, {"text", "json", "urdf", "mjcf", "sdf", "pseudo", "log-cholesky"}));
  const Eigen::Vector3d about = parse_about(out.about, mp);
  const Eigen::Matrix3d I = mp.inertia_about(about);
  // principal axes of the tensor about the chosen point (a physical tensor, so it can be
  // wrapped as the inertia of a body)
  const PrincipalAxes pa = MassProperties(mp.mass(), mp.com(), I).principal_axes();
  const SO3d q = SO3d::from_matrix(pa.R_BP);
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

namespace {

// `rigid inertia box|cylinder|sphere ... --density-field EXPR`: ρ(x, y, z) over the shape in
// its own frame (scene::integrate_density_field), the cubature's estimated errors on stderr.
MassProperties density_field_mass(const mass::PrimitiveEntry& e, const mass::PrimitiveArguments& args,
                                  const InertiaPrimitiveOptions& opts) {
  const auto rho = scene::compile_density_field(lagrange::Expression(opts.density_field), {}, "--density-field");
  const mass::DensityIntegration r = scene::integrate_density_field(e.name, args.sizes, rho, "--density-field");
  fmt::print(stderr, "density field: {}\n", scene::describe(r));
  return r.mass_properties;
}

}  // namespace

void run_inertia_primitive(const InertiaPrimitiveOptions& opts) {
  const mass::PrimitiveEntry& e = mass::find_primitive(opts.primitive);
  const std::string name = cli_name(e.name);
  if (!opts.density_field.empty()) {
    CLI_USAGE_REQUIRE(!opts.mass && !opts.density && opts.tolerance.empty(),
                      "--density-field gives the density: it takes no --mass, --density or --tolerance");
  } else {
  CLI_USAGE_REQUIRE(opts.mass.has_value() != opts.density.has_value(),
                "give exactly one of --mass (kg) and --density ({}), got {}", e.density_unit,
                opts.mass ? "both" : "neither");
  }
  mass::PrimitiveArguments args;
  for (const auto& sz : e.sizes) {
    const auto it = opts.sizes.find(sz.name);
    CLI_USAGE_REQUIRE(it != opts.sizes.end(), "{} needs --{} ({}, {})", name, cli_name(sz.name), sz.help, sz.unit);
    args.sizes.emplace_back(sz.name, it->second);
  }
  for (const auto& pt : e.points) {
    const auto it = opts.points.find(pt.name);
    CLI_USAGE_REQUIRE(it != opts.points.end(), "{} needs --{} ({} as x,y,z in m)", name, pt.name, pt.help);
    args.points.emplace_back(pt.name, parse_xyz(it->second, "--" + pt.name));
  }
  if (!opts.tolerance.empty()) {
    emit_uncertain_primitive(e, args, opts);
    return;
  }
  const MassProperties own =
      !opts.density_field.empty()
          ? density_field_mass(e, args, opts)
          : mass::make_primitive(e.name, opts.mass ? mass::Amount::kMass : mass::Amount::kDensity,
                                 opts.mass ? *opts.mass : *opts.density, args);
  const PlacedPrimitive placed = place_primitive(own, opts);
  InertiaOutputOptions out = opts.output;
  // the shape's own frame is principal (every catalogue shape but the tetrahedron, whose
  // vertices are given in the link frame already): urdf/mjcf/sdf --frame principal write the
  // placement's rotation exactly, so the given rpy is what the file says
  if (placed.R_LS && e.points.empty()) out.inertial_frame = placed.R_LS;
  emit_inertia(placed.mp, out);
}

mass::Placement parse_placement(const InertiaPrimitiveOptions& opts) {
  mass::Placement placement;
  if (!opts.axis.empty()) {
    static const std::pair<const char*, Eigen::Vector3d> kNamed[] = {
        {"x", Eigen::Vector3d::UnitX()},  {"y", Eigen::Vector3d::UnitY()},  {"z", Eigen::Vector3d::UnitZ()},
        {"-x", -Eigen::Vector3d::UnitX()}, {"-y", -Eigen::Vector3d::UnitY()}, {"-z", -Eigen::Vector3d::UnitZ()}};
    const auto* named = std::find_if(std::begin(kNamed), std::end(kNamed),
                                     [&](const auto& n) { return opts.axis == n.first; });
    if (named != std::end(kNamed)) {
      placement.axis = named->second;
    } else {
      placement.axis = parse_xyz(opts.axis, "--axis", "x, y, z, -x, -y, -z or a direction 'vx,vy,vz'");
      CLI_USAGE_REQUIRE(placement.axis.norm() > 1e-12, "--axis must be a non-zero direction, got '{}'", opts.axis);
    }
  }
  if (!opts.origin.empty()) placement.origin = parse_xyz(opts.origin, "--origin");
  if (!opts.rpy.empty()) {
    placement.rpy = parse_xyz(opts.rpy, "--rpy", "roll,pitch,yaw in radians 'r,p,y'");
  }
  return placement;
}

PlacedPrimitive place_primitive(const MassProperties& own, const InertiaPrimitiveOptions& opts) {
  if (opts.axis.empty() && opts.origin.empty() && opts.rpy.empty()) return {own, std::nullopt};
  const mass::Placement placement = parse_placement(opts);
  const Eigen::Matrix3d R_LS = mass::placement_rotation(placement);
  return {mass::place(own, R_LS, placement.origin), R_LS};
}

void emit_uncertain_primitive(const mass::PrimitiveEntry& e, const mass::PrimitiveArguments& args,
                              const InertiaPrimitiveOptions& opts) {
  const InertiaOutputOptions& out = opts.output;
  require_uncertainty_output(out);
  const std::optional<Eigen::Vector3d> about = uncertainty_about(out);
  const auto u = mass::primitive_uncertainty(e.name, opts.mass ? mass::Amount::kMass : mass::Amount::kDensity,
                                             opts.mass ? *opts.mass : *opts.density, args,
                                             parse_placement(opts), parse_tolerance_option(opts.tolerance), about);
  emit_uncertain(u.value, u.sigma, u.inputs, about ? *about : u.nominal.com(), out);
}

std::vector<mass::Tolerance> parse_tolerance_option(const std::string& text) {
  try {
    return mass::parse_tolerances(text);
  } catch (const Error& e) {
    throw UsageError(fmt::format("--tolerance: {}", e.what()));
  }
}

void require_uncertainty_output(const InertiaOutputOptions& out) {
  CLI_USAGE_REQUIRE(out.format == "text" || out.format == "json",
              "--tolerance is printed with --format text or json (each value ± its 1σ); {} has no "
              "place for a standard deviation; got --format {}",
              out.format, out.format);
  CLI_USAGE_REQUIRE(out.frame == "body",
              "--tolerance gives the 1σ of the tensor's elements in the body frame; use --frame "
              "body, got --frame {}", out.frame);
}

std::optional<Eigen::Vector3d> uncertainty_about(const InertiaOutputOptions& out) {
  if (out.about == "com") return std::nullopt;
  if (out.about == "origin") return Eigen::Vector3d::Zero();
  CLI_USAGE_REQUIRE(out.about.find(',') != std::string::npos,
                    "--about must be 'com', 'origin' or a point 'x,y,z' in metres, got '{}'{}", out.about,
                    did_you_mean_hint(out.about, {"com", "origin"}));
  return parse_xyz(out.about, "--about");
}

void emit_uncertain(const Eigen::Matrix<double, 10, 1>& value, const Eigen::Matrix<double, 10, 1>& sigma,
                    const std::vector<std::string>& inputs, const Eigen::Vector3d& p,
                    const InertiaOutputOptions& out) {
  const auto tensor = [](const Eigen::Matrix<double, 10, 1>& y) {
    Eigen::Matrix3d I;
    I << y(4), y(7), y(8), y(7), y(5), y(9), y(8), y(9), y(6);
    return I;
  };
  const Eigen::Matrix3d I = tensor(value), sI = tensor(sigma);
  const Eigen::Vector3d c = value.segment<3>(1), sc = sigma.segment<3>(1);
  std::string text;
  if (out.format == "json") {
    // the inputs are the primitive's own argument names (checked against its list), so quoting suffices
    std::vector<std::string> quoted;
    for (const std::string& s : inputs) quoted.push_back("\"" + s + "\"");
    text = fmt::format(
        "{{\n  \"mass\": {},\n  \"com\": {},\n  \"about\": {},\n  \"frame\": \"body\",\n"
        "  \"inertia\": {},\n  \"sigma\": {{\"mass\": {}, \"com\": {}, \"inertia\": {}}},\n"
        "  \"uncertainty\": \"1 standard deviation, first-order propagation, inputs independent\",\n"
        "  \"uncertain_inputs\": [{}]\n}}\n",
        value(0), json_vec(c), json_vec(p), json_mat(I), sigma(0), json_vec(sc), json_mat(sI),
        fmt::join(quoted, ", "));
  } else {
    const std::string where = out.about == "com" ? "the center of mass" : fmt::format("{} m", json_vec(p));
    text = fmt::format("mass            {:.10g} ± {:.3g} kg\n", value(0), sigma(0));
    text += fmt::format("center of mass  [{:.10g} ± {:.3g}, {:.10g} ± {:.3g}, {:.10g} ± {:.3g}] m\n", c(0), sc(0),
                        c(1), sc(1), c(2), sc(2));
    text += fmt::format("inertia tensor about {}, body frame (kg·m²), each element ± 1σ\n", where);
    for (int i = 0; i < 3; ++i) {
      text += fmt::format("  [{:>14.7g} ± {:<9.3g} {:>14.7g} ± {:<9.3g} {:>14.7g} ± {:<9.3g} ]\n", I(i, 0), sI(i, 0),
                          I(i, 1), sI(i, 1), I(i, 2), sI(i, 2));
    }
    text += fmt::format("± is 1 standard deviation (first-order propagation, inputs independent) of: {}\n",
                        fmt::join(inputs, ", "));
  }
  if (out.output.empty()) {
    std::fputs(text.c_str(), stdout);
  } else {
    io::write_file_atomically(out.output, text);
  }
}

void run_inertia_source(const InertiaSourceOptions& opts) {
  std::vector<std::string> names;
  for (const auto& e : mass::primitive_table()) names.push_back(cli_name(e.name));
  CLI_USAGE_REQUIRE(!opts.source.empty(), "give a primitive ({}), a mesh file or `check FILE`", fmt::join(names, ", "));
  // a path (an existing file, or a name with an extension or a folder; primitive names have
  // neither): the mesh library reads it or says it is not a supported mesh format
  std::error_code ec;
  const bool path_like = is_mesh_file(opts.source) || std::filesystem::exists(opts.source, ec) ||
                         opts.source.find_first_of("./\\") != std::string::npos;
  if (path_like) {
    run_inertia_mesh(
        opts.source,
        {opts.mass, opts.density, opts.areal_density, opts.units, opts.shell, opts.thickness,
         opts.fill_holes, opts.tolerance, opts.density_field},
        opts.output);
    return;
  }
  // not a subcommand: a typo of a primitive, or a file of an unknown kind
  std::vector<std::string> all;
  for (const auto& e : mass::primitive_table()) {
    for (const auto& n : e.names()) all.push_back(cli_name(n));
  }
  CLI_USAGE_THROW("unknown primitive '{}'{}; expected one of {} (each with the short names of `rigid "
            "inertia --help`), a mesh file (.stl, .obj, .ply, .off) or `check FILE`",
            opts.source, did_you_mean_hint(cli_name(opts.source), all), fmt::join(names, ", "));
}

void run_inertia_check(const InertiaCheckOptions& opts) {
  // a FIFO or device is refused before it is opened; MJCF <include>s are followed, and each
  // inertial is reported at its own file and line
  const auto entries = io::read_inertials_file(opts.file);
  int invalid = 0;
  std::vector<std::string> included;
  for (const auto& e : entries) {
    if (e.file != opts.file && std::find(included.begin(), included.end(), e.file) == included.end()) {
      included.push_back(e.file);
    }
    if (e.problem) {
      ++invalid;
      std::fputs(fmt::format("{}:{}: '{}': {}\n", e.file, e.line, e.name, *e.problem).c_str(), stdout);
    }
  }
  const std::string with = included.empty() ? "" : fmt::format(" (with {})", fmt::join(included, ", "));
  std::fputs(fmt::format("{}{}: {} inertial{}, {} invalid\n", opts.file, with, entries.size(),
                         entries.size() == 1 ? "" : "s", invalid)
                 .c_str(),
             stdout);
  std::fflush(stdout);
  CLI_REQUIRE(invalid == 0, "{} of {} in {} {} invalid (listed above)", invalid,
              counted(entries.size(), "inertial"), opts.file, invalid == 1 ? "is" : "are");
}

}  // namespace rigid::cli
