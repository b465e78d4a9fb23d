#include "rigid/mesh/repair.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <utility>

#include <Eigen/Geometry>
#include <fmt/format.h>


namespace rigid::mesh {
namespace {

using Index = std::uint32_t;

std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t{a} << 32) | b;
}

// Per undirected edge: the triangles using it and whether each goes low→high.
struct EdgeUse {
  std::uint32_t count = 0;
  std::uint32_t forward = 0;  // uses going from the lower to the higher index
  std::uint32_t first_face = 0;
  std::uint32_t second_face = 0;
};

std::unordered_map<std::uint64_t, EdgeUse> edge_uses(const TriangleMesh& mesh) {
  std::unordered_map<std::uint64_t, EdgeUse> uses;
  uses.reserve(mesh.triangles.size() * 3 / 2 + 1);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k];
      const Index b = t[(k + 1) % 3];
      EdgeUse& u = uses[edge_key(a, b)];
      if (u.count == 0) u.first_face = static_cast<std::uint32_t>(f);
      if (u.count == 1) u.second_face = static_cast<std::uint32_t>(f);
      ++u.count;
      if (a < b) ++u.forward;
    }
  }
  return uses;
}

// Grid hash of quantized positions for welding.
struct CellHash {
  std::size_t operator()(const std::array<std::int64_t, 3>& c) const {
    std::uint64_t h = 1469598103934665603ull;
    for (auto x : c) h = (h ^ static_cast<std::uint64_t>(x)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

std::size_t weld(TriangleMesh& mesh, double tol) {
  if (mesh.vertices.empty()) return 0;
  std::vector<Index> remap(mesh.vertices.size());
  std::vector<Eigen::Vector3d> kept;
  kept.reserve(mesh.vertices.size());
  if (tol <= 0) {
    std::iota(remap.begin(), remap.end(), Index{0});
    return 0;
  }
  const Eigen::Vector3d lo = mesh.bounding_box()[0];
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<Index>, CellHash> grid;
  grid.reserve(mesh.vertices.size());
  const double tol2 = tol * tol;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& p = mesh.vertices[i];
    const Eigen::Vector3d q = (p - lo) / tol;
    const std::array<std::int64_t, 3> c{static_cast<std::int64_t>(std::floor(q.x())),
                                         static_cast<std::int64_t>(std::floor(q.y())),
                                         static_cast<std::int64_t>(std::floor(q.z()))};
    Index found = static_cast<Index>(-1);
    for (int dx = -1; dx <= 1 && found == static_cast<Index>(-1); ++dx) {
      for (int dy = -1; dy <= 1 && found == static_cast<Index>(-1); ++dy) {
        for (int dz = -1; dz <= 1 && found == static_cast<Index>(-1); ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (Index j : it->second) {
            if ((kept[j] - p).squaredNorm() <= tol2) {
              found = j;
              break;
            }
          }
        }
      }
    }
    if (found == static_cast<Index>(-1)) {
      found = static_cast<Index>(kept.size());
      kept.push_back(p);
      grid[c].push_back(found);
    }
    remap[i] = found;
  }
  const std::size_t merged = mesh.vertices.size() - kept.size();
  for (auto& t : mesh.triangles) {
    for (auto& i : t) i = remap[i];
  }
  mesh.vertices = std::move(kept);
  return merged;
}

}  // namespace

EdgeCounts count_edges(const TriangleMesh& mesh) {
  EdgeCounts counts;
  for (const auto& [key, u] : edge_uses(mesh)) {
    if (u.count == 1) ++counts.boundary;
    if (u.count >= 3) ++counts.non_manifold;
    if (u.count == 2 && u.forward != 1) ++counts.misoriented;
  }
  return counts;
}

RepairReport repair_mesh(TriangleMesh& mesh, const RepairOptions& options) {
  RepairReport report;
  report.input_vertices = mesh.vertices.size();
  report.input_triangles = mesh.triangles.size();
  const double diag = mesh.bounding_box_diagonal();
  report.welded_vertices = weld(mesh, options.weld_tolerance * diag);

  // Degenerate: a repeated index, or an area below round-off of the box size.
  const double min_area2 = 1e-14 * diag * diag;  // (twice the area) ~ 1e-7·diag squared
  std::vector<std::array<Index, 3>> kept;
  kept.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    const double area2 =
        repeated ? 0.0
                 : (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                       .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
                       .norm();
    if (repeated || area2 <= min_area2) {
      ++report.degenerate_triangles;
    } else {
      kept.push_back(t);
    }
  }
  mesh.triangles = std::move(kept);

  // Consistent winding per component: breadth-first over edges shared by exactly two faces.
  const std::size_t nf = mesh.triangles.size();
  std::vector<std::vector<std::uint32_t>> faces_of_edge;
  std::vector<std::uint64_t> edge_keys;
  std::unordered_map<std::uint64_t, std::uint32_t> edge_id;
  edge_id.reserve(nf * 3 / 2 + 1);
  std::vector<std::array<std::uint32_t, 3>> face_edges(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto key = edge_key(mesh.triangles[f][k], mesh.triangles[f][(k + 1) % 3]);
      auto [it, inserted] = edge_id.try_emplace(key, static_cast<std::uint32_t>(faces_of_edge.size()));
      if (inserted) {
        faces_of_edge.emplace_back();
        edge_keys.push_back(key);
      }
      faces_of_edge[it->second].push_back(static_cast<std::uint32_t>(f));
      face_edges[f][k] = it->second;
    }
  }
  for (const auto& fs : faces_of_edge) {
    if (fs.size() == 1) ++report.boundary_edges;
    if (fs.size() >= 3) ++report.non_manifold_edges;
  }
  // Does face f traverse edge (a, b) from a to b?
  auto goes = [&](std::uint32_t f, Index a, Index b) {
    const auto& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a && t[(k + 1) % 3] == b) return true;
    }
    return false;
  };
  const auto box = mesh.bounding_box();
  const Eigen::Vector3d centre = 0.5 * (box[0] + box[1]);
  std::vector<int> component(nf, -1);
  std::vector<std::uint32_t> queue;
  int ncomp = 0;
  for (std::size_t seed = 0; seed < nf; ++seed) {
    if (component[seed] >= 0) continue;
    const int id = ncomp++;
    component[seed] = id;
    queue.assign(1, static_cast<std::uint32_t>(seed));
    ComponentReport comp;
    std::vector<std::uint32_t> members;
    while (!queue.empty()) {
      const std::uint32_t f = queue.back();
      queue.pop_back();
      members.push_back(f);
      for (int k = 0; k < 3; ++k) {
        const auto& fs = faces_of_edge[face_edges[f][k]];
        if (fs.size() == 1) ++comp.boundary_edges;
        if (fs.size() != 2) continue;  // non-manifold edges do not propagate orientation
        const std::uint32_t g = fs[0] == f ? fs[1] : fs[0];
        if (component[g] >= 0) continue;
        component[g] = id;
        // The edge's endpoints from its key (face_edges[f][k] was numbered before any flip).
        const auto key = edge_keys[face_edges[f][k]];
        Index a = static_cast<Index>(key >> 32);
        Index b = static_cast<Index>(key & 0xffffffffu);
        if (!goes(f, a, b)) std::swap(a, b);
        if (goes(g, a, b)) {  // same direction as f: flip g
          std::swap(mesh.triangles[g][1], mesh.triangles[g][2]);
          ++report.reoriented_triangles;
        }
        queue.push_back(g);
      }
    }
    comp.triangles = members.size();
    // Volume (signed tetrahedra with the box centre) and area of this component's faces.
    for (auto f : members) {
      const auto& t = mesh.triangles[f];
      const Eigen::Vector3d a = mesh.vertices[t[0]] - centre;
      const Eigen::Vector3d b = mesh.vertices[t[1]] - centre;
      const Eigen::Vector3d c = mesh.vertices[t[2]] - centre;
      comp.signed_volume += a.dot(b.cross(c)) / 6.0;
      comp.area += 0.5 * (b - a).cross(c - a).norm();
    }
    if (comp.boundary_edges == 0 && comp.signed_volume < 0) {
      for (auto f : members) std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
      comp.signed_volume = -comp.signed_volume;
      ++report.inverted_components;
    }
    report.components.push_back(comp);
  }

  if (report.degenerate_triangles > 0) {
    report.warnings.push_back(
        fmt::format("removed {} degenerate triangles (repeated vertex or zero area)",
                    report.degenerate_triangles));
  }
  if (report.reoriented_triangles > 0) {
    report.warnings.push_back(fmt::format(
        "flipped {} triangles whose winding disagreed with their neighbours",
        report.reoriented_triangles));
  }
  if (report.inverted_components > 0) {
    report.warnings.push_back(fmt::format(
        "{} closed component(s) had inward normals (negative volume): flipped",
        report.inverted_components));
  }
  if (report.boundary_edges > 0) {
    report.warnings.push_back(fmt::format(
        "the mesh is open: {} boundary edges; as a solid its volume is undefined (use --shell)",
        report.boundary_edges));
  }
  if (report.non_manifold_edges > 0) {
    report.warnings.push_back(fmt::format(
        "{} non-manifold edges (shared by three or more triangles)", report.non_manifold_edges));
  }
  if (report.components.size() > 1) {
    report.warnings.push_back(
        fmt::format("{} separate components (listed above); their volumes add",
                    report.components.size()));
  }
  return report;
}

std::string describe(const RepairReport& r) {
  std::string s = fmt::format(
      "vertices: {} read, {} after welding\ntriangles: {} read, {} degenerate removed\n"
      "boundary edges: {}\nnon-manifold edges: {}\nre-oriented triangles: {}\n"
      "inverted components flipped: {}\ncomponents: {}\n",
      r.input_vertices, r.input_vertices - r.welded_vertices, r.input_triangles,
      r.degenerate_triangles, r.boundary_edges, r.non_manifold_edges, r.reoriented_triangles,
      r.inverted_components, r.components.size());
  for (std::size_t i = 0; i < r.components.size(); ++i) {
    const auto& c = r.components[i];
    s += fmt::format("  component {}: {} triangles, area {:.9g} m², ", i + 1, c.triangles, c.area);
    s += c.boundary_edges == 0 ? fmt::format("volume {:.9g} m³\n", c.signed_volume)
                               : fmt::format("open ({} boundary edges)\n", c.boundary_edges);
  }
  return s;
}

}  // namespace rigid::mesh
