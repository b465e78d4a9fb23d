#pragma once

#include <cstddef>
#include <vector>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh {

/// One hole closed by fill_holes.
struct FilledHole {
  std::size_t boundary_edges = 0;  ///< edges of the loop
  double area = 0.0;               ///< m², area of the patch that closes it
};

/// What fill_holes added.
struct HoleFillReport {
  std::vector<FilledHole> holes;  ///< in the order found (by lowest vertex index)
  std::size_t triangles_added = 0;
  std::size_t vertices_added = 0;
  double area = 0.0;  ///< m², total area of the patches
};

/// Closes every hole of a welded, consistently oriented mesh (see repair_mesh) whose boundary
/// is a simple closed polygon: each boundary vertex starts exactly one boundary edge and ends
/// exactly one. A loop of three edges becomes one triangle; a longer loop a fan of triangles
/// around the mean of its vertices (a new vertex), wound to agree with the neighbouring
/// faces. A planar hole is closed exactly: every fan triangle lies in the hole's plane and
/// their signed areas add up to the polygon, so the volume and moments are those of the
/// closed polyhedron. A non-planar hole gets a cap through the mean of its vertices (an
/// approximation; the patch area in the report tells how large it is). Run repair_mesh
/// again afterwards to orient the now closed components outward.
/// @throws rigid::Error naming the vertex, its position and its number of boundary edges if
/// a boundary loop is not simple (two holes touching at a vertex, or a non-manifold border);
/// nothing is changed then.
HoleFillReport fill_holes(TriangleMesh& mesh);

}  // namespace rigid::mesh
