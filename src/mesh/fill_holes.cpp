#include "rigid/mesh/fill_holes.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cstdint>

#include "detail/edge_table.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"

namespace rigid::mesh {
namespace {

using Index = std::uint32_t;
constexpr Index kNone = 0xffffffffu;

}  // namespace

HoleFillReport fill_holes(TriangleMesh& mesh) {
  // a repaired mesh: holes are loops of boundary edges only once triangles repeat no vertex
  // and neighbours agree on the winding
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    RIGID_REQUIRE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2],
                  "triangle {} ({}, {}, {}) repeats a vertex: holes can be filled only in a "
                  "repaired mesh; run repair_mesh(mesh) first",
                  f, t[0], t[1], t[2]);
  }
  const detail::EdgeTable edges =
      detail::edge_table(mesh, {.mates = true, .lengths = false, .misoriented = true});
  RIGID_REQUIRE(edges.misoriented == 0,
                "{} edges are traversed twice in the same direction (inconsistent winding): "
                "holes can be filled only in a repaired mesh; run repair_mesh(mesh) first",
                edges.misoriented);
  HoleFillReport report;
  if (edges.boundary == 0) return report;

  // A boundary half-edge a → b of a face is crossed the other way, b → a, by the patch:
  // the patch's edges form the holes' loops. next[b] = a; a simple loop visits each of its
  // vertices once, so a vertex starting (or ending) two patch edges is refused.
  const std::size_t nv = mesh.vertices.size();
  std::vector<Index> next(nv, kNone);
  std::vector<std::uint32_t> starts(nv, 0), ends(nv, 0);
  for (std::size_t h = 0; h < edges.mate.size(); ++h) {
    if (edges.mate[h] != detail::EdgeTable::kBoundary) continue;
    const auto& t = mesh.triangles[h / 3];
    const Index a = t[h % 3];
    const Index b = t[(h % 3 + 1) % 3];
    next[b] = a;
    ++starts[b];
    ++ends[a];
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (starts[v] == ends[v] && starts[v] <= 1) continue;
    const Eigen::Vector3d& p = mesh.vertices[v];
    RIGID_THROW(
        "boundary loop through vertex {} at ({:.9g}, {:.9g}, {:.9g}) m is not simple: the vertex "
        "is on {} boundary edges (expected 2: holes that touch, or a non-manifold border); only "
        "simple holes can be filled: measure the open mesh as a thin shell ({} without {}), or "
        "repair the mesh in a modelling tool",
        v, p.x(), p.y(), p.z(), starts[v] + ends[v], setting("shell"), setting("fill_holes"));
  }

  // Walk each loop from its lowest vertex and close it.
  std::vector<std::uint8_t> done(nv, 0);
  std::vector<Index> loop;
  const auto twice_area = [&](Index a, Index b, Index c) {
    return (mesh.vertices[b] - mesh.vertices[a]).cross(mesh.vertices[c] - mesh.vertices[a]).norm();
  };
  for (std::size_t v0 = 0; v0 < nv; ++v0) {
    if (next[v0] == kNone || done[v0]) continue;
    loop.clear();
    for (Index v = static_cast<Index>(v0); !done[v]; v = next[v]) {
      done[v] = 1;
      loop.push_back(v);
    }
    // two boundary half-edges a→b, b→a would be one edge, a→a a repeated vertex (refused)
    RIGID_REQUIRE(loop.size() >= 3, "a boundary loop of {} edges through vertex {}: expected at "
                  "least 3; run repair_mesh(mesh) first", loop.size(), v0);
    FilledHole hole;
    hole.boundary_edges = loop.size();
    if (loop.size() == 3) {
      mesh.triangles.push_back({loop[0], loop[1], loop[2]});
      hole.area = 0.5 * twice_area(loop[0], loop[1], loop[2]);
      report.triangles_added += 1;
    } else {
      // mean of the loop's vertices, summed relative to the first for round-off
      const Eigen::Vector3d& p0 = mesh.vertices[loop[0]];
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      for (Index v : loop) d += mesh.vertices[v] - p0;
      const auto c = static_cast<Index>(mesh.vertices.size());
      RIGID_REQUIRE(c < kNone, "too many vertices to add a hole's centre ({})", c);
      mesh.vertices.push_back(p0 + d / static_cast<double>(loop.size()));
      report.vertices_added += 1;
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const Index a = loop[k];
        const Index b = loop[(k + 1) % loop.size()];
        mesh.triangles.push_back({a, b, c});
        hole.area += 0.5 * twice_area(a, b, c);
      }
      report.triangles_added += loop.size();
    }
    report.area += hole.area;
    report.holes.push_back(hole);
  }
  return report;
}

}  // namespace rigid::mesh
