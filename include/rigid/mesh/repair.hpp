#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh {

/// One edge-connected component of a mesh after repair.
struct ComponentReport {
  std::size_t triangles = 0;
  std::size_t boundary_edges = 0;  ///< edges used by one triangle only
  double signed_volume = 0.0;      ///< m³ after orientation (meaningful when closed)
  double area = 0.0;               ///< m²
};

/// What repair_mesh found and changed.
struct RepairReport {
  std::size_t input_vertices = 0;
  std::size_t input_triangles = 0;
  std::size_t welded_vertices = 0;        ///< vertices merged into another
  std::size_t degenerate_triangles = 0;   ///< removed: repeated index or zero area
  std::size_t boundary_edges = 0;         ///< used by exactly one triangle
  std::size_t non_manifold_edges = 0;     ///< used by three or more triangles
  std::size_t reoriented_triangles = 0;   ///< flipped to agree with their neighbours
  std::size_t inverted_components = 0;    ///< closed components with negative volume, flipped
  bool tolerance_weld = false;            ///< the tolerance weld ran (see RepairOptions)
  std::vector<ComponentReport> components;
  std::vector<std::string> warnings;      ///< one sentence each

  /// True when the mesh bounds a solid: every edge shared by exactly two triangles.
  [[nodiscard]] bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0; }
};

/// Edge counts of a mesh by the number of triangles using each (undirected) edge.
struct EdgeCounts {
  std::size_t boundary = 0;      ///< edges used once
  std::size_t non_manifold = 0;  ///< edges used three or more times
  std::size_t misoriented = 0;   ///< edges two triangles traverse in the same direction
};

/// Counts boundary, non-manifold and misoriented edges (vertices compared by index).
[[nodiscard]] EdgeCounts count_edges(const TriangleMesh& mesh);

/// Options of repair_mesh.
struct RepairOptions {
  /// Vertices closer than weld_tolerance × (bounding box diagonal) are merged. Copies of one
  /// vertex stored as float32 agree exactly; 1e-7 is far below any feature of a real part.
  double weld_tolerance = 1e-7;
  /// Weld bitwise-equal positions first (a hash of the coordinates' bit patterns) and run the
  /// tolerance weld only when that leaves boundary edges or an edge no longer than the
  /// tolerance. An STL soup of a closed part takes only the exact weld; exact copies weld
  /// even with weld_tolerance = 0. false: only the tolerance weld, on every input vertex. Both give the same mesh unless distinct,
  /// non-adjacent vertices of a closed mesh lie within the tolerance (touching parts), which
  /// the exact path keeps apart.
  bool exact_weld_first = true;
};

/// Welds duplicate vertices (see RepairOptions), removes degenerate triangles, makes the
/// winding of each edge-connected component consistent (depth-first over manifold edges),
/// flips closed components whose volume is negative (with a warning), and reports boundary
/// and non-manifold edges and each component's volume. Modifies `mesh` in place.
RepairReport repair_mesh(TriangleMesh& mesh, const RepairOptions& options = {});

/// A multi-line human-readable summary of `report`.
[[nodiscard]] std::string describe(const RepairReport& report);

}  // namespace rigid::mesh
