#pragma once
// Undirected edges of an indexed triangle mesh (private to the mesh module).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh::detail {

// Undirected edges of a mesh, found by bucketing the half-edges by their lower vertex (a
// counting sort, no hashing). Half-edge h = 3f + k runs from triangle f's corner k to
// corner k + 1.
struct EdgeTable {
  /// Per half-edge: the other half-edge of an edge used exactly twice; kBoundary or
  /// kNonManifold otherwise.
  std::vector<std::uint32_t> mate;
  std::size_t boundary = 0;
  std::size_t non_manifold = 0;
  std::size_t misoriented = 0;
  double min_length2 = std::numeric_limits<double>::infinity();  ///< shortest edge, squared

  static constexpr std::uint32_t kBoundary = 0xffffffffu;
  static constexpr std::uint32_t kNonManifold = 0xfffffffeu;
};

/// What edge_table computes beyond the counts.
struct EdgeTableOptions {
  bool mates = true;     ///< fill EdgeTable::mate (else it stays empty)
  bool lengths = false;  ///< find the shortest edge
  bool misoriented = true;  ///< count EdgeTable::misoriented (else it stays 0)
};

/// Builds the table. O(half-edges + vertices), plus
/// d log d for a vertex that is the lower end of d half-edges.
/// @throws rigid::Error for more than 1.4e9 triangles.
[[nodiscard]] EdgeTable edge_table(const TriangleMesh& mesh, EdgeTableOptions options);

}  // namespace rigid::mesh::detail
