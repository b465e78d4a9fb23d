#pragma once
// Triangulation of the polygon faces of OBJ, PLY, OFF (and ASCII STL facets with more than
// three vertices), private to the mesh module.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/mesh/triangle_mesh.hpp"

namespace rigid::mesh::detail {

/// A polygon may leave its plane by this fraction of (its diameter + its largest coordinate
/// magnitude): a vertex farther from the plane fitted to the polygon (centroid, Newell normal)
/// makes the polygon non-planar, and its triangulation (hence the volume) ambiguous. The
/// coordinate term admits files written with six significant digits (%g).
inline constexpr double kPlanarityTolerance = 1e-6;

/// Non-convex polygons with more vertices than this are refused: their simplicity check and
/// ear clipping cost O(n²). Convex polygons of any size are triangulated in O(n).
inline constexpr std::size_t kMaxConcavePolygon = 4096;

/// Appends the triangles of the polygon `poly` (vertex indices into `vertices`, in order, the
/// outward side by the right-hand rule) to `out`. A triangle is appended as it is. A longer
/// polygon is triangulated by ear clipping in its own plane (Newell normal), so that a
/// concave face keeps its area and the solid its volume exactly; every triangle turns the way
/// the polygon does. Consecutive repeated indices are dropped first; a polygon with every
/// vertex on one line (zero area) becomes the fan of its degenerate triangles, which
/// repair_mesh removes.
/// @return nothing on success, or why the polygon was refused (nothing appended then):
/// non-planar beyond kPlanarityTolerance (with the distance and the tolerance, m),
/// self-intersecting or self-touching, or non-convex with more than kMaxConcavePolygon
/// vertices.
[[nodiscard]] std::optional<std::string> triangulate_polygon(
    const std::vector<Eigen::Vector3d>& vertices, std::span<const std::uint32_t> poly,
    std::vector<std::array<std::uint32_t, 3>>& out);

}  // namespace rigid::mesh::detail
