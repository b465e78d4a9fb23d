#include "cmd_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <array>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "cli_error.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/lagrange/function.hpp"
#include "rigid/mass/uncertainty.hpp"
#include "rigid/mesh.hpp"
#include "rigid/scene/density_field.hpp"

namespace rigid::cli {
namespace {

void warn(const std::string& s) {
  std::fputs(fmt::format("rigid: warning: {}\n", word_for(Surface::kCli, s)).c_str(), stderr);
}

// "0.02 × 0.03 × 0.01 m (read in mm)": the part's size next to every mesh result, so that a
// wrong unit shows
std::string box_size(const std::array<Eigen::Vector3d, 2>& box, const std::string& units) {
  const Eigen::Vector3d d = box[1] - box[0];
  return fmt::format("{:.6g} × {:.6g} × {:.6g} m (file read in {})", d.x(), d.y(), d.z(), units);
}

// The scale of --units (m, cm, mm, in): a unit outside them is a usage error, with a guess.
double units_scale(const std::string& units) {
  try {
    return mesh::unit_scale(units);
  } catch (const Error& e) {
    throw UsageError(fmt::format("--units: {}{}", e.what(), did_you_mean_hint(units, {"m", "cm", "mm", "in"})));
  }
}

}  // namespace

bool is_mesh_file(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return false;
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e == "stl" || e == "obj" || e == "ply" || e == "off";
}

void run_mesh_check(const MeshCheckOptions& opts) {
  mesh::TriangleMesh m = mesh::read_mesh(opts.file, units_scale(opts.units));
  mesh::RepairOptions ro;
  ro.weld_tolerance = opts.weld_tolerance;
  const mesh::RepairReport first = mesh::repair_mesh(m, ro);
  std::optional<mesh::HoleFillReport> filled;
  std::optional<mesh::RepairReport> after;
  if (opts.fill_holes && first.boundary_edges > 0) {
    filled = mesh::fill_holes(m);
    after = mesh::repair_mesh(m, ro);
  }
  const mesh::RepairReport& rep = after ? *after : first;
  const auto box = m.bounding_box();
  std::string out = fmt::format("{}\n", opts.file);
  out += fmt::format("bounding box: ({:.6g}, {:.6g}, {:.6g}) to ({:.6g}, {:.6g}, {:.6g}) m\n",
                     box[0].x(), box[0].y(), box[0].z(), box[1].x(), box[1].y(), box[1].z());
  out += fmt::format("size: {}\n", box_size(box, opts.units));
  out += mesh::describe(first);
  if (filled) out += mesh::describe(*filled) + "\nafter filling:\n" + mesh::describe(*after);
  for (const auto& w : rep.warnings) out += fmt::format("warning: {}\n", word_for(Surface::kCli, w));
  const std::vector<std::string> units = mesh::size_warnings(box);
  for (const auto& w : units) out += fmt::format("warning: {}\n", word_for(Surface::kCli, w));
  std::string problem;
  if (!rep.closed()) {
    problem = fmt::format("the mesh is not closed ({}, {}): "
                          "its volume is undefined; use `rigid inertia {} --shell --thickness M "
                          "--density KG_PER_M3` (or --areal-density KG_PER_M2) for a thin shell, or "
                          "--fill-holes to close simple holes",
                          counted(rep.boundary_edges, "boundary edge"),
                          counted(rep.non_manifold_edges, "non-manifold edge"), opts.file);
  } else {
    const double v = mesh::volume_moments(m).measure;
    out += fmt::format("volume: {:.9g} m³, area: {:.9g} m²\n", v,
                       mesh::surface_moments(m).measure);
    if (!(v > 0)) problem = fmt::format("the enclosed volume is {} m³: expected positive", v);
  }
  // a closed solid whose size is implausible for the unit: the geometry is sound, the mass
  // properties only if the unit is right (a warning, exit 0)
  out += !problem.empty() ? "mass properties: NOT trustworthy as a solid\n"
         : units.empty()  ? "mass properties: trustworthy as a solid\n"
                          : "mass properties: a closed solid, but its size is implausible for "
                            "the unit (see the warning above)\n";
  std::fputs(out.c_str(), stdout);
  std::fflush(stdout);
  if (!problem.empty()) CLI_THROW("{}: {}", opts.file, problem);
}

// --tolerance vertices=±…,density|mass=±…: the vertex noise through the exact gradient of the
// volume moments, the amount's (m and I scale with it, the COM does not) added in quadrature
static void run_inertia_mesh_uncertainty(const std::string& file, const MeshInertiaOptions& opts,
                                  const mesh::MassSpec& spec, const InertiaOutputOptions& out) {
  require_uncertainty_output(out);
  CLI_USAGE_REQUIRE(!opts.fill_holes, "--tolerance cannot be used with --fill-holes: the noise of the "
                                "filled patches' vertices is not modelled; close the mesh first");
  const std::string amount = opts.mass ? "mass" : "density";
  const double amount_value = opts.mass ? *opts.mass : spec.density.value_or(0.0);
  double vertex_sigma = 0.0, amount_relative = 0.0;
  std::vector<std::string> inputs;
  for (const mass::Tolerance& t : parse_tolerance_option(opts.tolerance)) {
    if (t.name == "vertices") {
      static const std::string kLengths[] = {"", "m", "cm", "mm", "um", "µm", "in"};
      CLI_USAGE_REQUIRE(!t.relative && std::find(std::begin(kLengths), std::end(kLengths), t.unit) != std::end(kLengths),
                  "tolerance vertices must be a length (e.g. ±0.05mm), got '{}{}'", t.sigma, t.unit);
      vertex_sigma = t.sigma;
      inputs.push_back("vertices");
    } else if (t.name == amount) {
      amount_relative = t.relative ? t.sigma : t.sigma / amount_value;
      inputs.push_back(amount);
    } else {
      CLI_USAGE_THROW("unknown tolerance '{}' for a mesh; it takes vertices=±LENGTH and {}=±… (the amount "
                "given), e.g. --tolerance vertices=±0.05mm,{}=±2%",
                t.name, amount, amount);
    }
  }
  mesh::TriangleMesh m = mesh::read_mesh(file, units_scale(opts.units));
  (void)mesh::repair_mesh(m);
  const std::optional<Eigen::Vector3d> about = uncertainty_about(out);
  const mesh::MeshUncertainty u = mesh::vertex_noise_uncertainty(m, spec, vertex_sigma, about);
  for (const auto& w : u.nominal.warnings) warn(fmt::format("{}: {}", file, w));
  Eigen::Matrix<double, 10, 1> scaled = u.value.cwiseAbs() * amount_relative;
  scaled.segment<3>(1).setZero();
  const Eigen::Matrix<double, 10, 1> sigma = (u.sigma.cwiseAbs2() + scaled.cwiseAbs2()).cwiseSqrt();
  emit_uncertain(u.value, sigma, inputs, about ? *about : u.nominal.properties.com(), out);
}

// The amount of a mesh body from the command line: exactly one of --mass, --density (a shell's
// with --thickness) and --areal-density (a shell's, per unit area). A shell's --density alone
// was once taken as kg/m², so 7850 (steel, kg/m³) made a sheet-metal cover weigh 97 kg: it is
// refused with both remedies.
mesh::MassSpec mesh_mass_spec(const MeshInertiaOptions& opts) {
  const int amounts = int{opts.mass.has_value()} + int{opts.density.has_value()} +
                      int{opts.areal_density.has_value()};
  CLI_USAGE_REQUIRE(amounts == 1,
                    "give exactly one of --mass (kg), --density (kg/m³) and --areal-density (kg/m², "
                    "a thin shell), got {}",
                    amounts == 0 ? "none" : "more than one");
  if (opts.areal_density) {
    CLI_USAGE_REQUIRE(!opts.thickness,
                      "--areal-density {} kg/m² is already per unit area: --thickness {} m would "
                      "count the wall twice; give --density (kg/m³) with --thickness, or "
                      "--areal-density alone",
                      *opts.areal_density, *opts.thickness);
    return {std::nullopt, opts.areal_density, true, std::nullopt};
  }
  if (opts.shell && opts.density) {
    CLI_USAGE_REQUIRE(opts.thickness.has_value(),
                      "--shell with --density {} needs --thickness: --density is the material's "
                      "density (kg/m³) and the wall thickness (m) makes it a mass per area; for a "
                      "mass per unit area give --areal-density {} (kg/m²) instead of --density",
                      *opts.density, *opts.density);
  }
  return {opts.mass, opts.density, opts.shell, opts.thickness};
}

namespace {

// `rigid inertia MESH --density-field EXPR`: the mesh read and repaired as for a uniform solid
// (the same refusals of an open or inside-out mesh, the same warnings), then ρ integrated over
// it; the cubature's estimated errors on stderr, as for a primitive.
void run_inertia_mesh_density_field(const std::string& file, const MeshInertiaOptions& opts,
                                    const InertiaOutputOptions& out) {
  CLI_USAGE_REQUIRE(!opts.mass && !opts.density && !opts.areal_density && !opts.shell &&
                        !opts.thickness && opts.tolerance.empty(),
                    "--density-field gives the density of a solid: it takes no --mass, --density, "
                    "--areal-density, --shell, --thickness or --tolerance");
  const auto rho = scene::compile_density_field(lagrange::Expression(opts.density_field), {},
                                                "--density-field");
  const mesh::PreparedMesh prepared =
      mesh::prepare_mesh_file(file, units_scale(opts.units), {}, opts.fill_holes);
  // a unit mass: the refusals of a solid (open, inconsistently wound, no volume) before ρ
  (void)mesh::measure_prepared_mesh(prepared, {1.0, std::nullopt, false, std::nullopt});
  const mass::DensityIntegration r = scene::integrate_density_field_over_mesh(
      prepared.mesh.vertices, prepared.mesh.triangles, rho, "--density-field");
  // the warnings of a solid of the field's mass: its size, and its mean density against real
  // materials
  const mesh::MeshFileMass solid = mesh::measure_prepared_mesh(
      prepared, {r.mass_properties.mass(), std::nullopt, false, std::nullopt});
  std::fputs(fmt::format("rigid: {}: size {}\n", file,
                         box_size(solid.mass.bounding_box, opts.units)).c_str(),
             stderr);
  for (const auto& w : solid.warnings()) warn(fmt::format("{}: {}", file, w));
  fmt::print(stderr, "density field: {}\n", scene::describe(r));
  emit_inertia(r.mass_properties, out);
}

}  // namespace

void run_inertia_mesh(const std::string& file, const MeshInertiaOptions& opts,
                      const InertiaOutputOptions& out) {
  if (!opts.density_field.empty()) {
    run_inertia_mesh_density_field(file, opts, out);
    return;
  }
  const mesh::MassSpec spec = mesh_mass_spec(opts);
  if (!opts.tolerance.empty()) {
    run_inertia_mesh_uncertainty(file, opts, spec, out);
    return;
  }
  const mesh::MeshFileMass r =
      mesh::mesh_mass_from_file(file, units_scale(opts.units), spec, {}, opts.fill_holes);
  std::fputs(fmt::format("rigid: {}: size {}\n", file,
                         box_size(r.mass.bounding_box, opts.units)).c_str(),
             stderr);
  for (const auto& w : r.warnings()) warn(fmt::format("{}: {}", file, w));
  emit_inertia(r.mass.properties, out);
}

}  // namespace rigid::cli
