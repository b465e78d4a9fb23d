#pragma once

/// A density that varies in space, ρ(x, y, z), over a catalogue primitive or a closed mesh: the
/// scenes' `density_field` and `rigid inertia … --density-field`. ρ is an expression of x, y, z (m, in
/// the shape's own frame) compiled once (lagrange::compile_function) and integrated by the
/// adaptive cubature of rigid/mass/density.hpp.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigid/lagrange/function.hpp"
#include "rigid/mass/density.hpp"

namespace rigid::scene {

/// The largest estimated error of the cubature that is taken as a result: relative to the mass,
/// to the shape's size for the COM and to tr I for the inertia's elements. The cubature's own
/// target is 1e-10; a field it cannot resolve this well (a jump or a singularity inside a cell)
/// is refused rather than used with digits it lacks.
inline constexpr double kDensityFieldRelativeError = 1e-8;

/// True for the canonical primitive names a field is integrated over: solid_box,
/// solid_cylinder, solid_sphere.
[[nodiscard]] bool takes_density_field(std::string_view primitive);

/// ρ compiled as a function of x, y, z with the parameters by value. @throws rigid::Error at the
/// expression's location for a name that is neither a coordinate x, y, z nor a parameter.
[[nodiscard]] lagrange::CompiledFunction compile_density_field(
    const lagrange::Expression& rho, const std::vector<lagrange::Parameter>& parameters,
    std::string_view what);

/// ρ over `primitive` (a canonical name that takes_density_field) with its `sizes` (canonical
/// size name → m). `what` names the field in messages ("body 'rod' density_field"). A COM
/// component or a product of inertia within its estimated error of zero is returned as 0.
/// @throws rigid::Error if ρ is negative or not finite at a sample point (naming it), the mass
///         is not positive, or an estimated error exceeds kDensityFieldRelativeError.
[[nodiscard]] mass::DensityIntegration integrate_density_field(
    std::string_view primitive, const std::vector<std::pair<std::string, double>>& sizes,
    const lagrange::CompiledFunction& rho, std::string_view what);

/// ρ over the solid a closed, outward-oriented triangle mesh bounds (vertices in m, the mesh's
/// frame; mass::integrate_density_over_mesh), refused as integrate_density_field is: a negative
/// or non-finite ρ at a sample point, no mass, or an estimated error above
/// kDensityFieldRelativeError (relative to the mass, the bounding-box diagonal and tr I). The
/// caller gives a closed mesh (a repaired one: mesh::repair_mesh says whether it is).
[[nodiscard]] mass::DensityIntegration integrate_density_field_over_mesh(
    const std::vector<Eigen::Vector3d>& vertices,
    const std::vector<std::array<std::uint32_t, 3>>& triangles,
    const lagrange::CompiledFunction& rho, std::string_view what);

/// One line for the user: the cells and the estimated errors of an integration.
[[nodiscard]] std::string describe(const mass::DensityIntegration& r);

}  // namespace rigid::scene
