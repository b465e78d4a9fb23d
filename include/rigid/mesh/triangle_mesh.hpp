#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace rigid::mesh {

/// An indexed triangle mesh: vertex positions p_OV_M (m, in the mesh frame M) and
/// triangles as three vertex indices, counter-clockwise seen from outside (outward normal
/// by the right-hand rule) once a mesh has been oriented.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;             ///< p_OV_M (m)
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< vertex indices

  /// Number of triangles.
  [[nodiscard]] std::size_t size() const { return triangles.size(); }
  /// Axis-aligned bounding box corners (min, max) of the vertices; zeros when empty.
  [[nodiscard]] std::array<Eigen::Vector3d, 2> bounding_box() const;
  /// Length of the bounding box diagonal (m).
  [[nodiscard]] double bounding_box_diagonal() const;
  /// Multiplies every vertex by `factor` (e.g. 1e-3 for millimetres).
  void scale(double factor);
  /// Moves every vertex by d_M (m).
  void translate(const Eigen::Vector3d& d_M);
  /// Reverses the winding of every triangle (flips all normals).
  void reverse_winding();
};

}  // namespace rigid::mesh
