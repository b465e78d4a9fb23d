#include "mesh/detail/triangulate.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "rigid/mesh/mesh_mass.hpp"
#include "rigid/mesh/repair.hpp"

namespace rigid::mesh {
namespace {

using Tri = std::array<std::uint32_t, 3>;

// Σ |(b − a) × (c − a)| / 2 (unsigned, as a shell's area) and the vector area Σ (b − a) × (c − a) / 2.
double area(const std::vector<Eigen::Vector3d>& v, const std::vector<Tri>& t) {
  double s = 0;
  for (const auto& f : t) s += 0.5 * (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]).norm();
  return s;
}
Eigen::Vector3d vector_area(const std::vector<Eigen::Vector3d>& v, const std::vector<Tri>& t) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (const auto& f : t) s += 0.5 * (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]);
  return s;
}

std::vector<std::uint32_t> iota(std::uint32_t n) {
  std::vector<std::uint32_t> p(n);
  for (std::uint32_t i = 0; i < n; ++i) p[i] = i;
  return p;
}

// The chevron (0,0), (2,1), (0,2), (1,1): area 1 (shoelace: ½|0·1 − 2·0 + 2·2 − 0·1 + 0·1 − 1·2
// + 1·0 − 0·1| = ½·2 = 1). A fan from its first vertex covers 2 + 1 = 3 (its second
// triangle, (0,0), (0,2), (1,1), lies outside and turns the other way).
std::vector<Eigen::Vector3d> chevron(double z = 0) {
  return {{0, 0, z}, {2, 1, z}, {0, 2, z}, {1, 1, z}};
}

TEST(Triangulate, ConcaveFaceKeepsItsArea) {
  const auto v = chevron();
  std::vector<Tri> t;
  ASSERT_FALSE(detail::triangulate_polygon(v, iota(4), t));
  ASSERT_EQ(t.size(), 2u);
  // exact sums of dyadic numbers: the area is 1 to the last bit
  EXPECT_EQ(area(v, t), 1.0);
  EXPECT_EQ(vector_area(v, t), Eigen::Vector3d(0, 0, 1));  // turns like the polygon
}

TEST(Triangulate, CombInAnyPlaneKeepsItsArea) {
  // A comb: the spine [0, 2k − 1] × [0, 1] and k teeth [2i, 2i + 1] × [1, 2], counter-clockwise
  // from the origin; area = spine (2k − 1) + teeth k. Rotated into a tilted plane and moved
  // away from the origin.
  const int k = 7;
  std::vector<Eigen::Vector3d> p;
  p.emplace_back(0, 0, 0);
  p.emplace_back(2 * k - 1, 0, 0);
  for (int i = k - 1; i >= 0; --i) {
    p.emplace_back(2 * i + 1, 2, 0);
    p.emplace_back(2 * i, 2, 0);
    if (i > 0) {
      p.emplace_back(2 * i, 1, 0);
      p.emplace_back(2 * i - 1, 1, 0);
    }
  }
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  for (auto& q : p) q = R * q + Eigen::Vector3d(10, -20, 30);
  std::vector<Tri> t;
  ASSERT_FALSE(detail::triangulate_polygon(p, iota(static_cast<std::uint32_t>(p.size())), t));
  EXPECT_EQ(t.size(), p.size() - 2);
  const double expected = (2.0 * k - 1) * 1 + k * 1.0;
  // rotated coordinates of size ~30 carry ~30·ε each; the area sums ~2k triangles
  EXPECT_NEAR(area(p, t), expected, 1e-12 * expected);
  EXPECT_NEAR((vector_area(p, t) - R * Eigen::Vector3d(0, 0, expected)).norm(), 0.0, 1e-12 * expected);
}

TEST(Triangulate, ConvexPolygonWithCollinearVerticesHasNoDegenerateTriangle) {
  // the unit square with a vertex in the middle of each side: 8 vertices, 6 triangles of
  // positive area (a fan from a corner would make zero-area triangles along two sides)
  const std::vector<Eigen::Vector3d> v = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 0.5, 0},
                                          {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0}, {0, 0.5, 0}};
  std::vector<Tri> t;
  ASSERT_FALSE(detail::triangulate_polygon(v, iota(8), t));
  EXPECT_EQ(t.size(), 6u);
  for (const auto& f : t) EXPECT_GT((v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]).z(), 0.0);
  EXPECT_EQ(area(v, t), 1.0);
}

TEST(Triangulate, NonPlanarPolygonIsRefused) {
  // a square with one corner lifted by 1e-3 of its size: 1e3 times the tolerance
  std::vector<Eigen::Vector3d> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 1e-3}, {0, 1, 0}};
  std::vector<Tri> t;
  const auto e = detail::triangulate_polygon(v, iota(4), t);
  ASSERT_TRUE(e);
  EXPECT_NE(e->find("is not planar: its vertex"), std::string::npos) << *e;
  EXPECT_NE(e->find("from the plane of the polygon, more than the tolerance"), std::string::npos);
  EXPECT_TRUE(t.empty());
  // within the tolerance (1e-6 × (extent √2 + largest coordinate 1) ≈ 2.4e-6 m): accepted
  v[2].z() = 1e-7;
  EXPECT_FALSE(detail::triangulate_polygon(v, iota(4), t));
}

TEST(Triangulate, SelfIntersectingPolygonsAreRefused) {
  std::vector<Tri> t;
  // a bow tie: two lobes of opposite turn (signed area 0)
  const std::vector<Eigen::Vector3d> bow = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  const auto a = detail::triangulate_polygon(bow, iota(4), t);
  ASSERT_TRUE(a);
  EXPECT_NE(a->find("crosses itself"), std::string::npos) << *a;
  // a pentagram: every turn to the left, but it winds twice
  std::vector<Eigen::Vector3d> star;
  for (int k = 0; k < 5; ++k) {
    const double phi = 2 * std::numbers::pi * (2 * k) / 5;
    star.emplace_back(std::cos(phi), std::sin(phi), 0);
  }
  const auto b = detail::triangulate_polygon(star, iota(5), t);
  ASSERT_TRUE(b);
  EXPECT_NE(b->find("intersects itself"), std::string::npos) << *b;
  // a bow tie with unequal lobes (non-zero signed area)
  const std::vector<Eigen::Vector3d> bow2 = {{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 1, 0}};
  const auto c = detail::triangulate_polygon(bow2, iota(4), t);
  ASSERT_TRUE(c);
  EXPECT_NE(c->find("intersects itself"), std::string::npos) << *c;
  EXPECT_TRUE(t.empty());
}

TEST(Triangulate, CollinearPolygonBecomesDegenerateTriangles) {
  const std::vector<Eigen::Vector3d> v = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  std::vector<Tri> t;
  EXPECT_FALSE(detail::triangulate_polygon(v, iota(4), t));
  EXPECT_EQ(area(v, t), 0.0);
}

TEST(Triangulate, PrismWithConcaveEndsIsExactAsSolidAndShell) {
  // The chevron extruded by h = 3 with quads on the sides: V = 1 · 3, surface = 2 · 1 +
  // perimeter (2√5 + 2√2) · 3.
  const double h = 3;
  std::vector<Eigen::Vector3d> v = chevron(0);
  for (const auto& p : chevron(h)) v.push_back(p);
  std::vector<Tri> t;
  // bottom seen from below (reversed), top as is, sides (i, i+1, i+5, i+4) outward
  ASSERT_FALSE(detail::triangulate_polygon(v, std::vector<std::uint32_t>{3, 2, 1, 0}, t));
  ASSERT_FALSE(detail::triangulate_polygon(v, std::vector<std::uint32_t>{4, 5, 6, 7}, t));
  for (std::uint32_t i = 0; i < 4; ++i) {
    const std::uint32_t j = (i + 1) % 4;
    ASSERT_FALSE(detail::triangulate_polygon(v, std::vector<std::uint32_t>{i, j, j + 4, i + 4}, t));
  }
  TriangleMesh m{v, t};
  const auto rep = repair_mesh(m);
  EXPECT_TRUE(rep.closed());
  EXPECT_EQ(rep.reoriented_triangles, 0u);
  const auto solid = mesh_mass_properties(m, {std::nullopt, 1.0, false, {}});
  EXPECT_NEAR(solid.measure, 3.0, 1e-14);  // dyadic inputs: a few ulps of round-off
  const auto shell = mesh_mass_properties(m, {std::nullopt, 1.0, true, {}});
  const double surface = 2.0 + (2 * std::sqrt(5.0) + 2 * std::sqrt(2.0)) * h;
  EXPECT_NEAR(shell.measure, surface, 1e-14 * surface);
}

}  // namespace
}  // namespace rigid::mesh
