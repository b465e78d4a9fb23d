// Polygon faces to triangles: ear clipping in the polygon's plane. Written here rather than
// taken from a library: of the project's dependencies only CGAL-sized libraries triangulate
// polygons, and the readers need a few hundred lines with their own refusals (planarity,
// self-intersection) reported with the file's line.
#include "detail/triangulate.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Geometry>

namespace rigid::mesh::detail {
namespace {

using Index = std::uint32_t;
using Vec2 = Eigen::Vector2d;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// orientation of (a, b, c): > 0 counter-clockwise, < 0 clockwise, 0 collinear
double orient(const Vec2& a, const Vec2& b, const Vec2& c) { return cross(b - a, c - a); }

// p on the closed segment [a, b], given that a, b, p are collinear
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

// the closed segments [a, b] and [c, d] share a point (crossing or touching)
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d);
  const double o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
    return true;
  }
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

}  // namespace

std::optional<std::string> triangulate_polygon(const std::vector<Eigen::Vector3d>& vertices,
                                               std::span<const Index> poly,
                                               std::vector<std::array<Index, 3>>& out) {
  const auto fan = [&](std::span<const Index> p) {
    for (std::size_t k = 1; k + 1 < p.size(); ++k) out.push_back({p[0], p[k], p[k + 1]});
  };
  if (poly.size() == 3) {
    out.push_back({poly[0], poly[1], poly[2]});
    return std::nullopt;
  }
  // consecutive repeats (and a last vertex repeating the first) carry no area
  std::vector<Index> idx;
  idx.reserve(poly.size());
  for (Index i : poly) {
    if (idx.empty() || idx.back() != i) idx.push_back(i);
  }
  while (idx.size() > 1 && idx.back() == idx.front()) idx.pop_back();
  const std::size_t n = idx.size();
  if (n < 3) {  // no area at all: degenerate triangles, which repair_mesh removes
    fan(poly);
    return std::nullopt;
  }
  if (n == 3) {
    out.push_back({idx[0], idx[1], idx[2]});
    return std::nullopt;
  }

  // centroid c, summed relative to the first vertex for round-off; Newell's normal
  // N = Σ (p_i − c) × (p_i+1 − c), twice the vector area, along the right-hand side of the
  // polygon's turn (exact for a planar polygon whatever its shape)
  const Eigen::Vector3d& p0 = vertices[idx[0]];
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  double max_coordinate = 0;
  for (Index i : idx) {
    d += vertices[i] - p0;
    max_coordinate = std::max(max_coordinate, vertices[i].cwiseAbs().maxCoeff());
  }
  const Eigen::Vector3d c = p0 + d / static_cast<double>(n);
  std::vector<Eigen::Vector3d> r(n);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (std::size_t k = 0; k < n; ++k) {
    r[k] = vertices[idx[k]] - c;
    lo = lo.cwiseMin(r[k]);
    hi = hi.cwiseMax(r[k]);
  }
  Eigen::Vector3d N = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < n; ++k) N += r[k].cross(r[(k + 1) % n]);
  const double diameter = (hi - lo).norm();
  const double tol = kPlanarityTolerance * (diameter + max_coordinate);
  const double norm = N.norm();

  if (!(norm > 2 * tol * diameter)) {
    // area below that of a sliver as thin as the tolerance: every vertex on one line (the
    // fan's triangles are degenerate), or a figure of eight whose lobes cancel (refused)
    std::size_t far = 0;  // the vertex farthest from the first
    for (std::size_t k = 1; k < n; ++k) {
      if ((r[k] - r[0]).squaredNorm() > (r[far] - r[0]).squaredNorm()) far = k;
    }
    const Eigen::Vector3d axis = (r[far] - r[0]).normalized();
    for (std::size_t k = 0; k < n && diameter > 0; ++k) {
      const Eigen::Vector3d off = (r[k] - r[0]) - axis * axis.dot(r[k] - r[0]);
      if (off.norm() > tol) {
        return fmt::format(
            "the polygon of {} vertices crosses itself (its signed area is {:.3g} m², its "
            "extent {:.3g} m): expected a simple polygon",
            n, 0.5 * norm, diameter);
      }
    }
    fan(poly);
    return std::nullopt;
  }

  // planarity: distance of each vertex from the plane through c with normal N
  const Eigen::Vector3d nz = N / norm;
  for (std::size_t k = 0; k < n; ++k) {
    const double dist = std::abs(nz.dot(r[k]));
    if (dist > tol) {
      return fmt::format(
          "the polygon of {} vertices is not planar: its vertex {} (position {} of the face) "
          "is {:.3g} m from the plane of the polygon, more than the tolerance {:.3g} m "
          "({} × (extent + largest coordinate)); split it into triangles in the modelling tool",
          n, idx[k] + 1, k + 1, dist, tol, kPlanarityTolerance);
    }
  }

  // 2D coordinates in the plane, (u, v, nz) right-handed: the polygon turns counter-clockwise
  const Eigen::Vector3d u = nz.unitOrthogonal();
  const Eigen::Vector3d v = nz.cross(u);
  std::vector<Vec2> q(n);
  for (std::size_t k = 0; k < n; ++k) q[k] = Vec2(u.dot(r[k]), v.dot(r[k]));

  // convex (every turn left, up to round-off, and one turn in all) or not
  const auto prev_of = [n](std::size_t k) { return (k + n - 1) % n; };
  bool convex = true;
  double winding = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 e1 = q[k] - q[prev_of(k)];
    const Vec2 e2 = q[(k + 1) % n] - q[k];
    const double t = cross(e1, e2);
    const double scale = e1.norm() * e2.norm();
    if (std::abs(t) <= 1e-12 * scale && e1.dot(e2) < 0) {
      return fmt::format("the polygon of {} vertices folds back on itself at its vertex {} "
                         "(position {} of the face): expected a simple polygon",
                         n, idx[k] + 1, k + 1);
    }
    if (t < -1e-12 * scale) convex = false;
    winding += std::atan2(t, e1.dot(e2));
  }
  if (std::abs(winding - 2 * std::numbers::pi) > 1e-6) convex = false;
  if (!convex) {
    if (n > kMaxConcavePolygon) {
      return fmt::format("non-convex polygon of {} vertices: at most {} are supported", n,
                         kMaxConcavePolygon);
    }
    // simple: no two edges that are not neighbours meet
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 2; j < n; ++j) {
        if (i == 0 && j == n - 1) continue;  // neighbours through the closing edge
        if (segments_meet(q[i], q[i + 1], q[j], q[(j + 1) % n])) {
          return fmt::format(
              "the polygon of {} vertices intersects itself: its edges from vertex {} and from "
              "vertex {} (positions {} and {} of the face) meet; expected a simple polygon",
              n, idx[i] + 1, idx[j] + 1, i + 1, j + 1);
        }
      }
    }
  }

  // ear clipping: a vertex whose turn is left and whose triangle with its neighbours holds
  // no other vertex that turns right or not at all (only those can lie inside) is an ear;
  // cutting it off leaves a simple polygon, and a simple polygon has an ear [Meisters1975]
  std::vector<std::size_t> prev(n), next(n);
  for (std::size_t k = 0; k < n; ++k) {
    prev[k] = prev_of(k);
    next[k] = (k + 1) % n;
  }
  std::vector<std::uint8_t> alive(n, 1);
  const auto turn = [&](std::size_t k) { return orient(q[prev[k]], q[k], q[next[k]]); };
  std::vector<std::size_t> reflex;
  for (std::size_t k = 0; k < n; ++k) {
    if (turn(k) <= 0) reflex.push_back(k);
  }
  const auto is_ear = [&](std::size_t b) {
    if (turn(b) <= 0) return false;
    const std::size_t a = prev[b], e = next[b];
    for (std::size_t j : reflex) {
      if (!alive[j] || j == a || j == b || j == e || turn(j) > 0) continue;
      if (orient(q[a], q[b], q[j]) >= 0 && orient(q[b], q[e], q[j]) >= 0 &&
          orient(q[e], q[a], q[j]) >= 0) {
        return false;
      }
    }
    return true;
  };
  const std::size_t first_out = out.size();
  std::size_t remaining = n;
  std::size_t k = 0;
  std::size_t misses = 0;
  while (remaining > 3) {
    if (is_ear(k)) {
      out.push_back({idx[prev[k]], idx[k], idx[next[k]]});
      alive[k] = 0;
      next[prev[k]] = next[k];
      prev[next[k]] = prev[k];
      --remaining;
      k = prev[k];
      misses = 0;
      continue;
    }
    k = next[k];
    if (++misses > remaining) {
      out.resize(first_out);
      return fmt::format("the polygon of {} vertices touches itself and cannot be cut into "
                         "triangles: expected a simple polygon",
                         n);
    }
  }
  out.push_back({idx[prev[k]], idx[k], idx[next[k]]});
  return std::nullopt;
}

}  // namespace rigid::mesh::detail
