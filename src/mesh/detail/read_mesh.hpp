#pragma once
// read_mesh that also says whether the vertices it returns are distinct (private to the mesh
// module).

#include <string>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh::detail {

/// A mesh as read, and whether the reader guarantees that no two of its vertices have
/// bitwise equal coordinates (−0 = +0).
struct ReadResult {
  TriangleMesh mesh;
  bool vertices_distinct = false;
};

/// read_mesh(path, scale). vertices_distinct is true for binary STL (whose reader shares
/// float32-identical copies) when the scale keeps distinct float32 values distinct as
/// doubles: 1e-250 ≤ scale ≤ 1e250, so that every scaled coordinate is zero or a normal
/// double (products of distinct floats differ by ≥ 2⁻²⁴ relative, rounding moves them by
/// ≤ 2⁻⁵³).
[[nodiscard]] ReadResult read_mesh(const std::string& path, double scale);

}  // namespace rigid::mesh::detail
