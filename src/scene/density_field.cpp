#include "rigid/scene/density_field.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include <fmt/format.h>

#include "rigid/common/error.hpp"

namespace rigid::scene {

bool takes_density_field(std::string_view primitive) {
  return primitive == "solid_box" || primitive == "solid_cylinder" || primitive == "solid_sphere";
}

lagrange::CompiledFunction compile_density_field(const lagrange::Expression& rho,
                                                 const std::vector<lagrange::Parameter>& parameters,
                                                 std::string_view what) {
  return lagrange::compile_function(rho, {"x", "y", "z"}, parameters, what);
}

namespace {

// The estimated errors against kDensityFieldRelativeError (relative to the mass, the shape's
// size `length` and tr I), and the moments within their error of zero set to 0.
mass::DensityIntegration checked(const mass::DensityIntegration& r, double length,
                                 const lagrange::CompiledFunction& rho, std::string_view what) {
  const MassProperties& mp = r.mass_properties;
  const double mass_rel = r.mass_error / mp.mass();
  const double com_rel = r.com_error / length;
  const double inertia_rel = r.inertia_error / mp.inertia_com().trace();
  if (!(r.converged && mass_rel <= kDensityFieldRelativeError &&
        com_rel <= kDensityFieldRelativeError && inertia_rel <= kDensityFieldRelativeError)) {
    throw Error(fmt::format(
        "{} '{}': the cubature {} (estimated relative errors: mass {:.2g}, COM {:.2g}, inertia "
        "{:.2g}; at most {:.0e} is taken as a result); a field with a jump or a singularity "
        "inside the shape needs the shape split where it jumps",
        what, rho.text(),
        r.converged ? "did not reach the bound" : fmt::format("did not converge in {} cells", r.cells),
        mass_rel, com_rel, inertia_rel, kDensityFieldRelativeError));
  }
  // A moment within its own estimated error of zero is not told apart from zero, and is zero:
  // a field symmetric about an axis gives its COM off that axis and its products of inertia as
  // ±1e-19 of round-off otherwise, with a sign that changes with the sizes.
  Eigen::Vector3d com = mp.com();
  Eigen::Matrix3d inertia = mp.inertia_com();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(com(i)) <= r.com_error) com(i) = 0.0;
    for (int j = 0; j < 3; ++j) {
      if (i != j && std::abs(inertia(i, j)) <= r.inertia_error) inertia(i, j) = 0.0;
    }
  }
  mass::DensityIntegration out = r;
  out.mass_properties = MassProperties(mp.mass(), com, inertia);
  return out;
}

}  // namespace

mass::DensityIntegration integrate_density_field(
    std::string_view primitive, const std::vector<std::pair<std::string, double>>& sizes,
    const lagrange::CompiledFunction& rho, std::string_view what) {
  RIGID_REQUIRE_AS("density field", takes_density_field(primitive),
                   "{}: a density field is integrated over a box, a cylinder or a sphere, not a "
                   "{}; give it a constant density",
                   what, primitive);
  const mass::DensityFunction f = [&rho](const Eigen::Vector3d& p) {
    return rho(std::span<const double>(p.data(), 3));
  };
  const auto size = [&](std::string_view key) {
    for (const auto& [k, v] : sizes) {
      if (k == key) return v;
    }
    return 0.0;
  };
  const bool box = primitive == "solid_box", cylinder = primitive == "solid_cylinder";
  const mass::DensityIntegration r = [&] {
    try {
      return box        ? mass::integrate_density_over_box(f, size("lx"), size("ly"), size("lz"))
             : cylinder ? mass::integrate_density_over_cylinder(f, size("radius"), size("height"))
                        : mass::integrate_density_over_sphere(f, size("radius"));
    } catch (const Error& e) {  // a negative or non-finite density at a point, no mass
      throw Error(fmt::format("{} '{}': {}", what, rho.text(), e.what()));
    }
  }();
  // the shape's size, for the COM's error
  const double length = box        ? std::max({size("lx"), size("ly"), size("lz")})
                        : cylinder ? std::max(2 * size("radius"), size("height"))
                                   : 2 * size("radius");
  return checked(r, length, rho, what);
}

mass::DensityIntegration integrate_density_field_over_mesh(
    const std::vector<Eigen::Vector3d>& vertices,
    const std::vector<std::array<std::uint32_t, 3>>& triangles,
    const lagrange::CompiledFunction& rho, std::string_view what) {
  const mass::DensityFunction f = [&rho](const Eigen::Vector3d& p) {
    return rho(std::span<const double>(p.data(), 3));
  };
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (const Eigen::Vector3d& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const mass::DensityIntegration r = [&] {
    try {
      return mass::integrate_density_over_mesh(f, vertices, triangles);
    } catch (const Error& e) {  // a negative or non-finite density at a point, no mass
      throw Error(fmt::format("{} '{}': {}", what, rho.text(), e.what()));
    }
  }();
  return checked(r, (hi - lo).norm(), rho, what);
}

std::string describe(const mass::DensityIntegration& r) {
  const std::string cells =
      r.points_per_cell == 3375
          ? fmt::format("{} cell{} of 15³ points", r.cells, r.cells == 1 ? "" : "s")
          : fmt::format("{} tetrahedr{} of {} points", r.cells, r.cells == 1 ? "on" : "a",
                        r.points_per_cell);
  return fmt::format(
      "{}; estimated errors: mass {:.2g} kg ({:.2g} of it), COM {:.2g} m, inertia {:.2g} kg·m²",
      cells, r.mass_error, r.mass_error / r.mass_properties.mass(), r.com_error, r.inertia_error);
}

}  // namespace rigid::scene
