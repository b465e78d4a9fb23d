#include "detail/edge_table.hpp"

#include <algorithm>
#include <memory>
#include <utility>

#include "rigid/common/error.hpp"

namespace rigid::mesh::detail {

using Index = std::uint32_t;

EdgeTable edge_table(const TriangleMesh& mesh, EdgeTableOptions options) {
  const std::size_t nf = mesh.triangles.size();
  const std::size_t nh = 3 * nf;
  const std::size_t nv = mesh.vertices.size();
  RIGID_REQUIRE_AS("repair_mesh", nh < EdgeTable::kNonManifold, "{} triangles: at most 1.4e9 are supported", nf);
  const auto* tri = mesh.triangles.data();
  // bucket the half-edges by their lower vertex, each entry (upper vertex << 32 | h), in
  // increasing h within a bucket (counting sort)
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = tri[f];
    ++start[std::min(t[0], t[1]) + 1];
    ++start[std::min(t[1], t[2]) + 1];
    ++start[std::min(t[2], t[0]) + 1];
  }
  for (std::size_t i = 0; i < nv; ++i) start[i + 1] += start[i];
  // every entry is written below: no zero-filling of fresh memory
  const auto bucket_storage = std::make_unique_for_overwrite<std::uint64_t[]>(nh);
  std::uint64_t* bucket = bucket_storage.get();
  {
    const auto fill = std::make_unique_for_overwrite<std::uint32_t[]>(nv);
    std::copy(start.begin(), start.end() - 1, fill.get());
    for (std::size_t f = 0; f < nf; ++f) {
      const auto& t = tri[f];
      for (std::size_t k = 0; k < 3; ++k) {
        const Index a = t[k], b = t[k == 2 ? 0 : k + 1];
        const Index lo = std::min(a, b), hi = std::max(a, b);
        bucket[fill[lo]++] = (std::uint64_t{hi} << 32) | (3 * f + k);
      }
    }
  }
  EdgeTable e;
  if (options.mates) e.mate.assign(nh, EdgeTable::kBoundary);
  std::uint32_t* mate = e.mate.data();
  const auto tail = [&](std::uint32_t h) { return tri[h / 3][h % 3]; };
  for (std::size_t lo = 0; lo < nv; ++lo) {
    std::uint64_t* first = bucket + start[lo];
    std::uint64_t* last = bucket + start[lo + 1];
    // sorted by (upper vertex, h): insertion sort for the usual handful, std::sort for a
    // vertex of high degree (d log d, not d²)
    if (last - first > 16) {
      std::sort(first, last);
    } else {
      for (std::uint64_t* i = first + 1; i < last; ++i) {
        const std::uint64_t x = *i;
        std::uint64_t* j = i;
        for (; j > first && *(j - 1) > x; --j) *j = *(j - 1);
        *j = x;
      }
    }
    // runs of one upper vertex are the uses of one edge
    for (std::uint64_t* g = first; g < last;) {
      const std::uint64_t hi = *g >> 32;
      std::uint64_t* end = g + 1;
      while (end < last && (*end >> 32) == hi) ++end;
      const auto h0 = static_cast<std::uint32_t>(*g);
      if (end - g == 1) {
        ++e.boundary;
      } else if (end - g == 2) {
        const auto h1 = static_cast<std::uint32_t>(g[1]);
        if (options.mates) {
          mate[h0] = h1;
          mate[h1] = h0;
        }
        if (options.misoriented && tail(h0) == tail(h1)) ++e.misoriented;
      } else {
        ++e.non_manifold;
        for (std::uint64_t* u = g; options.mates && u < end; ++u) {
          mate[static_cast<std::uint32_t>(*u)] = EdgeTable::kNonManifold;
        }
      }
      if (options.lengths) {
        e.min_length2 = std::min(e.min_length2,
                                 (mesh.vertices[hi] - mesh.vertices[lo]).squaredNorm());
      }
      g = end;
    }
  }
  return e;
}

}  // namespace rigid::mesh::detail
