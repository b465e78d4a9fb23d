#include "rigid/mesh/repair.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>
#include <utility>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "detail/edge_table.hpp"
#include "detail/repair.hpp"

namespace rigid::mesh {
namespace {

using Index = std::uint32_t;

using detail::EdgeTable;
using detail::edge_table;
constexpr std::uint32_t kNone = 0xffffffffu;

// Grid hash of quantized positions for the tolerance weld.
struct CellHash {
  std::size_t operator()(const std::array<std::int64_t, 3>& c) const {
    std::uint64_t h = 1469598103934665603ull;
    for (auto x : c) h = (h ^ static_cast<std::uint64_t>(x)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

// Replaces every vertex index by remap[index] and keeps `kept` as the vertices.
void apply_remap(TriangleMesh& mesh, const Index* remap) {
  for (auto& t : mesh.triangles) {
    for (auto& i : t) i = remap[i];
  }
}

// Tolerance weld: each vertex merges into the first earlier kept vertex within `tol`
// (grid of cell size tol, 27 neighbouring cells searched).
std::size_t weld_tolerance(TriangleMesh& mesh, double tol) {
  if (mesh.vertices.empty() || tol <= 0) return 0;
  std::vector<Index> remap(mesh.vertices.size());
  std::vector<Eigen::Vector3d> kept;
  kept.reserve(mesh.vertices.size());
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
    Index found = kNone;
    for (int dx = -1; dx <= 1 && found == kNone; ++dx) {
      for (int dy = -1; dy <= 1 && found == kNone; ++dy) {
        for (int dz = -1; dz <= 1 && found == kNone; ++dz) {
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
    if (found == kNone) {
      found = static_cast<Index>(kept.size());
      kept.push_back(p);
      grid[c].push_back(found);
    }
    remap[i] = found;
  }
  const std::size_t merged = mesh.vertices.size() - kept.size();
  apply_remap(mesh, remap.data());
  mesh.vertices = std::move(kept);
  return merged;
}

// Bit pattern of a coordinate for exact comparison; −0 and +0 are one position.
std::uint64_t coordinate_bits(double x) {
  return std::bit_cast<std::uint64_t>(x == 0.0 ? 0.0 : x);
}

// Exact weld: vertices with bitwise equal coordinates (−0 = +0) become one, the first
// occurrence, keeping the order of first occurrences. Open addressing with linear probing
// on a hash of the three coordinates' bit patterns; the table holds indices of kept
// vertices and doubles when it is half full. The kept vertices are compacted in place
// (kept index ≤ input index).
std::size_t weld_exact(TriangleMesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  if (n == 0) return 0;
  RIGID_REQUIRE_AS("repair_mesh", n < kNone, "{} vertices: at most 2³² − 2 are supported", n);
  auto& v = mesh.vertices;
  const auto hash = [&](const Eigen::Vector3d& p) {
    // multiply-xorshift mix of the three 64-bit patterns (constants: odd, well-mixed)
    std::uint64_t h = coordinate_bits(p.x()) * 0x9E3779B97F4A7C15ull;
    h ^= coordinate_bits(p.y()) * 0xC2B2AE3D27D4EB4Full;
    h ^= coordinate_bits(p.z()) * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 32);
  };
  const auto same = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
  };
  // Soup files repeat each position ~6 times: start at about n/3 slots, grow as needed.
  std::size_t capacity = 64;
  while (capacity < n / 3) capacity *= 2;
  std::vector<Index> table(capacity, kNone);
  const auto remap_storage = std::make_unique_for_overwrite<Index[]>(n);  // all written below
  Index* remap = remap_storage.get();
  Index kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t mask = capacity - 1;
    const Eigen::Vector3d p = v[i];
    std::size_t slot = hash(p) & mask;
    while (table[slot] != kNone && !same(v[table[slot]], p)) slot = (slot + 1) & mask;
    if (table[slot] != kNone) {
      remap[i] = table[slot];
      continue;
    }
    v[kept] = p;
    table[slot] = kept;
    remap[i] = kept++;
    if (2 * std::size_t{kept} > capacity) {  // rehash the kept vertices into twice the slots
      capacity *= 2;
      mask = capacity - 1;
      table.assign(capacity, kNone);
      for (Index k = 0; k < kept; ++k) {
        std::size_t s = hash(v[k]) & mask;
        while (table[s] != kNone) s = (s + 1) & mask;
        table[s] = k;
      }
    }
  }
  v.resize(kept);
  v.shrink_to_fit();
  apply_remap(mesh, remap);
  return n - kept;
}

// Twice the area of a triangle, squared: |(b − a) × (c − a)|².
double twice_area_squared(const TriangleMesh& mesh, const std::array<Index, 3>& t) {
  return (mesh.vertices[t[1]] - mesh.vertices[t[0]])
      .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
      .squaredNorm();
}

// Twice the area of a triangle: |(b − a) × (c − a)|.
double twice_area(const TriangleMesh& mesh, const std::array<Index, 3>& t) {
  return (mesh.vertices[t[1]] - mesh.vertices[t[0]])
      .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
      .norm();
}

}  // namespace

EdgeCounts count_edges(const TriangleMesh& mesh) {
  const EdgeTable e = edge_table(mesh, {.mates = false, .lengths = false, .misoriented = true});
  return {e.boundary, e.non_manifold, e.misoriented};
}

RepairReport repair_mesh(TriangleMesh& mesh, const RepairOptions& options) {
  return detail::repair_mesh(mesh, options, false);
}

RepairReport detail::repair_mesh(TriangleMesh& mesh, const RepairOptions& options,
                                 bool vertices_distinct) {
  RIGID_REQUIRE_AS("repair_mesh",
                   std::isfinite(options.weld_tolerance) && options.weld_tolerance >= 0 &&
                       options.weld_tolerance < 1,
                   "weld tolerance {}: expected a finite number from 0 up to (not including) 1, "
                   "the fraction of the bounding-box diagonal within which vertices merge "
                   "(default 1e-7; 1 or more would merge every vertex into one)",
                   options.weld_tolerance);
  RepairReport report;
  report.input_vertices = mesh.vertices.size();
  report.input_triangles = mesh.triangles.size();
  const auto input_box = mesh.bounding_box();
  const double diag = (input_box[1] - input_box[0]).norm();
  const double tol = options.weld_tolerance * diag;

  // Degenerate: a repeated index, or an area below round-off of the box size.
  const double min_area2 = 1e-14 * diag * diag;  // (twice the area) ~ 1e-7·diag squared
  // |n|² above 4·min_area2² means |n| > min_area2 whatever the rounding of the square and the
  // root (a factor 4 is far beyond either), so the root is taken only near the threshold;
  // always for a box so small that the square would underflow
  const double clearly_above = min_area2 > 1e-150 ? 4 * min_area2 * min_area2
                                                  : std::numeric_limits<double>::infinity();
  // Also finds the shortest edge of the kept triangles, squared, while their corners are at
  // hand (in file order): the same minimum the edge table would find edge by edge, since
  // |p − q|² = |q − p|² exactly.
  double min_edge2 = std::numeric_limits<double>::infinity();
  const auto remove_degenerate = [&] {
    std::size_t removed = 0;
    std::size_t out = 0;
    min_edge2 = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh.triangles) {
      const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
      if (repeated || (twice_area_squared(mesh, t) <= clearly_above &&
                       twice_area(mesh, t) <= min_area2)) {
        ++removed;
      } else {
        const Eigen::Vector3d& a = mesh.vertices[t[0]];
        const Eigen::Vector3d& b = mesh.vertices[t[1]];
        const Eigen::Vector3d& c = mesh.vertices[t[2]];
        min_edge2 = std::min({min_edge2, (b - a).squaredNorm(), (c - b).squaredNorm(),
                              (a - c).squaredNorm()});
        mesh.triangles[out++] = t;
      }
    }
    mesh.triangles.resize(out);
    return removed;
  };

  // Weld: exactly equal positions first (cheap, and all an STL soup usually needs); the
  // tolerance weld runs only if that leaves boundary edges or an edge within the tolerance
  // (which the tolerance weld would collapse), so the two paths give the same mesh.
  EdgeTable edges;
  if (options.exact_weld_first) {
    // distinct vertices: the exact weld would keep every vertex and every index
    report.welded_vertices = vertices_distinct ? 0 : weld_exact(mesh);
    report.degenerate_triangles = remove_degenerate();
    edges = edge_table(mesh, {.mates = true, .lengths = false, .misoriented = false});
    // checked edge by edge on small meshes only: the benchmarks run with asserts on
    RIGID_ASSERT(mesh.triangles.size() > 20000 ||
                 edge_table(mesh, {.mates = false, .lengths = true}).min_length2 == min_edge2);
    if (tol > 0 && (edges.boundary > 0 || min_edge2 <= tol * tol)) {
      report.tolerance_weld = true;
      report.welded_vertices += weld_tolerance(mesh, tol);
      report.degenerate_triangles += remove_degenerate();
      edges = edge_table(mesh, {.mates = true, .lengths = false, .misoriented = false});
    }
  } else {
    report.tolerance_weld = true;
    report.welded_vertices = weld_tolerance(mesh, tol);
    report.degenerate_triangles = remove_degenerate();
    edges = edge_table(mesh, {.mates = true, .lengths = false, .misoriented = false});
  }
  report.boundary_edges = edges.boundary;
  report.non_manifold_edges = edges.non_manifold;

  // Consistent winding per component: depth-first over edges shared by exactly two faces.
  // Flips are recorded and applied at the end, so half-edge h = 3f + k keeps naming the
  // edge from the input corner k of f to corner k + 1.
  const std::size_t nf = mesh.triangles.size();
  std::vector<std::uint8_t> flipped(nf, 0);
  const auto tail = [&](std::uint32_t h) { return mesh.triangles[h / 3][h % 3]; };
  // no vertex merged: the same vertices, the same box
  const auto box = report.welded_vertices == 0 ? input_box : mesh.bounding_box();
  const Eigen::Vector3d centre = 0.5 * (box[0] + box[1]);
  // one byte per face marks it visited (a walk only needs to know whether a face has been
  // reached; the components are reported in the order of their seeds); the member list is
  // reserved once: at most every face, and no copying as it grows
  std::vector<std::uint8_t> visited(nf, 0);
  std::vector<std::uint32_t> queue;
  std::vector<std::uint32_t> members;
  members.reserve(nf);
  for (std::size_t seed = 0; seed < nf; ++seed) {
    if (visited[seed] != 0) continue;
    visited[seed] = 1;
    queue.assign(1, static_cast<std::uint32_t>(seed));
    ComponentReport comp;
    members.clear();
    while (!queue.empty()) {
      const std::uint32_t f = queue.back();
      queue.pop_back();
      members.push_back(f);
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t h = 3 * f + k;
        const std::uint32_t m = edges.mate[h];
        if (m == EdgeTable::kBoundary) ++comp.boundary_edges;
        if (m >= EdgeTable::kNonManifold) continue;  // non-manifold edges do not propagate
        const std::uint32_t g = m / 3;
        if (visited[g] != 0) continue;
        visited[g] = 1;
        // f as it stands traverses h forward unless flipped; g likewise with m. The same
        // direction on both sides of the edge means g disagrees with f: flip g.
        const bool same_input_direction = tail(h) == tail(m);
        if (same_input_direction != (flipped[f] != 0)) {
          flipped[g] = 1;
          ++report.reoriented_triangles;
        }
        queue.push_back(g);
      }
    }
    comp.triangles = members.size();
    // Volume (signed tetrahedra with the box centre) and area of this component's faces;
    // a flipped face's determinant is exactly the negative of the input face's.
    for (auto f : members) {
      const auto& t = mesh.triangles[f];
      const Eigen::Vector3d a = mesh.vertices[t[0]] - centre;
      const Eigen::Vector3d b = mesh.vertices[t[1]] - centre;
      const Eigen::Vector3d c = mesh.vertices[t[2]] - centre;
      const double v = flipped[f] ? a.dot(c.cross(b)) : a.dot(b.cross(c));
      comp.signed_volume += v / 6.0;
      comp.area += 0.5 * (b - a).cross(c - a).norm();
    }
    if (comp.boundary_edges == 0 && comp.signed_volume < 0) {
      for (auto f : members) flipped[f] ^= 1;
      comp.signed_volume = -comp.signed_volume;
      ++report.inverted_components;
    }
    report.components.push_back(comp);
  }
  for (std::size_t f = 0; f < nf; ++f) {
    if (flipped[f]) std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
  }

  if (report.degenerate_triangles > 0) {
    report.warnings.push_back(
        fmt::format("removed {} (repeated vertex or zero area)",
                    counted(report.degenerate_triangles, "degenerate triangle")));
  }
  if (report.reoriented_triangles > 0) {
    report.warnings.push_back(fmt::format(
        "flipped {} whose winding disagreed with their neighbours",
        counted(report.reoriented_triangles, "triangle")));
  }
  if (report.inverted_components > 0) {
    report.warnings.push_back(fmt::format(
        "{} inward normals (negative volume): flipped",
        report.inverted_components == 1 ? "1 closed component had"
                                        : fmt::format("{} closed components had", report.inverted_components)));
  }
  if (report.boundary_edges > 0) {
    report.warnings.push_back(fmt::format(
        "the mesh is open: {}; as a solid its volume is undefined (use {}, or {} "
        "to close simple holes)",
        counted(report.boundary_edges, "boundary edge"), setting("shell"), setting("fill_holes")));
  }
  if (report.non_manifold_edges > 0) {
    report.warnings.push_back(fmt::format(
        "{} (shared by three or more triangles)", counted(report.non_manifold_edges, "non-manifold edge")));
  }
  if (report.components.size() > 1) {
    // the components themselves, in the warning (not every front end prints describe()'s list);
    // the first kListed of them, the rest counted
    constexpr std::size_t kListed = 8;
    std::string list;
    for (std::size_t i = 0; i < std::min(report.components.size(), kListed); ++i) {
      const auto& c = report.components[i];
      list += fmt::format("{}{}: {}, ", i == 0 ? "" : "; ", i + 1, counted(c.triangles, "triangle"));
      list += c.boundary_edges == 0 ? fmt::format("volume {:.6g} m³", c.signed_volume)
                                    : fmt::format("open, area {:.6g} m²", c.area);
    }
    if (report.components.size() > kListed) {
      list += fmt::format("; and {} more", report.components.size() - kListed);
    }
    report.warnings.push_back(fmt::format("{} separate components ({}); their volumes add",
                                          report.components.size(), list));
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
    s += fmt::format("  component {}: {}, area {:.9g} m², ", i + 1, counted(c.triangles, "triangle"),
                     c.area);
    s += c.boundary_edges == 0 ? fmt::format("volume {:.9g} m³\n", c.signed_volume)
                               : fmt::format("open ({})\n", counted(c.boundary_edges, "boundary edge"));
  }
  return s;
}

}  // namespace rigid::mesh
