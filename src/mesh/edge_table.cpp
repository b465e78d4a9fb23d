#include "detail/edge_table.hpp"

#include <algorithm>
#include <utility>

#include "rigid/common/error.hpp"

namespace rigid::mesh::detail {

using Index = std::uint32_t;

EdgeTable edge_table(const TriangleMesh& mesh, bool lengths) {
  const std::size_t nf = mesh.triangles.size();
  const std::size_t nh = 3 * nf;
  const std::size_t nv = mesh.vertices.size();
  RIGID_REQUIRE(nh < EdgeTable::kNonManifold, "{} triangles: at most 1.4e9 are supported", nf);
  const auto* tri = mesh.triangles.data();
  const auto tail = [&](std::size_t h) { return tri[h / 3][h % 3]; };
  const auto head = [&](std::size_t h) { return tri[h / 3][(h % 3 + 1) % 3]; };
  // bucket the half-edges by min(tail, head), in increasing h within a bucket
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (std::size_t h = 0; h < nh; ++h) ++start[std::min(tail(h), head(h)) + 1];
  for (std::size_t i = 0; i < nv; ++i) start[i + 1] += start[i];
  std::vector<std::uint32_t> bucket(nh);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t h = 0; h < nh; ++h) {
      bucket[fill[std::min(tail(h), head(h))]++] = static_cast<std::uint32_t>(h);
    }
  }
  EdgeTable e;
  e.mate.assign(nh, EdgeTable::kBoundary);
  std::vector<std::uint32_t> group;                             // half-edges of one edge
  std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted;  // (other vertex, h)
  const auto close_group = [&](Index lo) {
    if (group.size() == 1) {
      ++e.boundary;
    } else if (group.size() == 2) {
      e.mate[group[0]] = group[1];
      e.mate[group[1]] = group[0];
      if (tail(group[0]) == tail(group[1])) ++e.misoriented;
    } else {
      ++e.non_manifold;
      for (auto h : group) e.mate[h] = EdgeTable::kNonManifold;
    }
    if (lengths) {
      const Index hi = tail(group[0]) == lo ? head(group[0]) : tail(group[0]);
      e.min_length2 =
          std::min(e.min_length2, (mesh.vertices[hi] - mesh.vertices[lo]).squaredNorm());
    }
  };
  for (std::size_t lo = 0; lo < nv; ++lo) {
    const std::uint32_t b = start[lo], end = start[lo + 1];
    if (b == end) continue;
    // (other vertex, h) pairs sorted: a vertex of high degree costs d log d, not d²
    sorted.clear();
    for (std::uint32_t j = b; j < end; ++j) {
      const std::uint32_t h = bucket[j];
      sorted.emplace_back(tail(h) == lo ? head(h) : tail(h), h);
    }
    std::sort(sorted.begin(), sorted.end());
    group.clear();
    for (std::size_t j = 0; j < sorted.size(); ++j) {
      if (j > 0 && sorted[j].first != sorted[j - 1].first) {
        close_group(static_cast<Index>(lo));
        group.clear();
      }
      group.push_back(sorted[j].second);
    }
    close_group(static_cast<Index>(lo));
  }
  return e;
}

}  // namespace rigid::mesh::detail
