#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"

/// Mass properties of bodies with a continuous, non-uniform density ρ(x), by adaptive
/// tensor-product Gauss–Kronrod cubature (7-point Gauss nested in 15-point Kronrod on
/// each axis) with an error estimate.
namespace rigid::mass {

/// Density ρ(p_O) in kg/m³ at a point given from the region's origin O (m).
using DensityFunction = std::function<double(const Eigen::Vector3d& p_O)>;

/// Options of the adaptive cubature (designated initializers: {.relative_tolerance = 1e-8}).
struct CubatureOptions {
  /// Stop when the estimated error of every moment is below this fraction of its scale
  /// (mass, m·size, m·size²).
  double relative_tolerance = 1e-10;
  /// Upper bound on the number of cells (each costs 15³ = 3375 density evaluations).
  int max_cells = 2000;
};

/// Result of a density cubature: the mass properties and estimated absolute errors.
struct DensityIntegration {
  MassProperties mass_properties;
  double mass_error;     ///< kg
  double com_error;      ///< m (bound on every component)
  double inertia_error;  ///< kg·m² (bound on every element of the inertia about the COM)
  int cells;             ///< cells used (a mesh: tetrahedra)
  bool converged;        ///< false if max_cells was reached first
  /// The density evaluations per cell: 15³ = 3375 for a box, a cylinder or a sphere; 105 (the
  /// two simplex rules) per tetrahedron of a mesh.
  int points_per_cell = 3375;
};

/// ρ over the box [−lx/2, lx/2] × [−ly/2, ly/2] × [−lz/2, lz/2].
/// @throws rigid::Error if a size is not positive and finite, ρ is negative or not finite
/// at a sample point (the message gives the point), or the total mass is not positive.
[[nodiscard]] DensityIntegration integrate_density_over_box(const DensityFunction& rho, double lx,
                                                            double ly, double lz,
                                                            const CubatureOptions& options = {});

/// ρ over the solid cylinder of radius r, axis z, z ∈ [−h/2, h/2], in cylindrical
/// coordinates (s, θ, z) with Jacobian s.
[[nodiscard]] DensityIntegration integrate_density_over_cylinder(
    const DensityFunction& rho, double r, double h, const CubatureOptions& options = {});

/// ρ over the solid ball of radius r centred at O, in spherical coordinates (s, θ, φ) with
/// Jacobian s² sin θ.
[[nodiscard]] DensityIntegration integrate_density_over_sphere(const DensityFunction& rho,
                                                               double r,
                                                               const CubatureOptions& options = {});

/// ρ (at points from the world origin, m) over the solid a closed, consistently oriented
/// (outward) triangle mesh bounds: the signed tetrahedra from the vertices' centroid O to each
/// triangle, each by Grundmann–Möller rules of degree 9 (70 points) and 7 (35 points, for the
/// error estimate), the worst split into eight until the estimates meet
/// options.relative_tolerance, within triangles + 32 × options.max_cells tetrahedra. For a
/// convex solid the tetrahedra lie inside it; for a non-convex one some reach outside, where ρ
/// is sampled too (and must be finite and non-negative there) and cancels.
/// The COM is in the mesh's frame (from the world origin); `cells` counts the tetrahedra.
/// @throws rigid::Error if ρ is negative or not finite at a sample point (the message gives the
///   point), a vertex is not finite, a triangle names a missing vertex, the mesh has no
///   triangles, or the total mass is not positive.
[[nodiscard]] DensityIntegration integrate_density_over_mesh(
    const DensityFunction& rho, std::span<const Eigen::Vector3d> vertices,
    std::span<const std::array<std::uint32_t, 3>> triangles, const CubatureOptions& options = {});

}  // namespace rigid::mass
