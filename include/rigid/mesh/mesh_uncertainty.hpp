#pragma once

#include <optional>

#include <Eigen/Core>

#include "rigid/mesh/mesh_mass.hpp"
#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh {

/// Mass properties of a solid mesh with their 1σ when every vertex coordinate carries an
/// independent error of standard deviation `sigma` (m), to first order (see
/// rigid/mass/uncertainty.hpp): σ_y² = σ² Σ_v,d (∂y/∂x_vd)². The gradient of the volume
/// moments with respect to each vertex is exact (differentiated per triangle: with
/// det = a·(b×c), ∂det/∂a = b×c and cyclic); the map from the moments to (m, c, I) is
/// differentiated by central differences. Costs O(triangles).
struct MeshUncertainty {
  MeshMassResult nominal;
  Eigen::Matrix<double, 10, 1> value;  ///< mass, COM (3), inertia xx yy zz xy xz yz about `about`
  Eigen::Matrix<double, 10, 1> sigma;  ///< 1σ of each
};

/// @param about the point the inertia is about (the COM when nullopt), p_OQ_M (m).
/// @throws rigid::Error as mesh_mass_properties does, for a shell (vertex noise is propagated
///   for solids only), or for a negative or non-finite sigma.
[[nodiscard]] MeshUncertainty vertex_noise_uncertainty(const TriangleMesh& mesh, const MassSpec& spec,
                                                       double sigma,
                                                       const std::optional<Eigen::Vector3d>& about = std::nullopt);

}  // namespace rigid::mesh
