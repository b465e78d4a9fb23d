#include "rigid/mesh/repair.hpp"

#include <gtest/gtest.h>

#include "mesh/mesh_builders.hpp"
#include "rigid/mesh/mesh_mass.hpp"

namespace rigid::mesh {
namespace {

// A triangle soup (three private vertices per triangle), as an STL file stores it.
TriangleMesh soup(const TriangleMesh& m) {
  TriangleMesh s;
  for (const auto& t : m.triangles) {
    const auto n = static_cast<std::uint32_t>(s.vertices.size());
    for (auto i : t) s.vertices.push_back(m.vertices[i]);
    s.triangles.push_back({n, n + 1, n + 2});
  }
  return s;
}

TEST(Repair, ClosedBoxNeedsNothing) {
  auto box = test::box_mesh(1, 2, 3);
  const auto r = repair_mesh(box);
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(r.welded_vertices, 0u);
  EXPECT_EQ(r.reoriented_triangles, 0u);
  EXPECT_EQ(r.inverted_components, 0u);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_NEAR(r.components[0].signed_volume, 6.0, 1e-12);  // exact polyhedron, see mesh_mass_test
  EXPECT_NEAR(r.components[0].area, 22.0, 1e-12);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(Repair, SoupIsWeldedToEightVertices) {
  auto s = soup(test::box_mesh(1, 2, 3));
  ASSERT_EQ(s.vertices.size(), 36u);
  const auto r = repair_mesh(s);
  EXPECT_EQ(r.welded_vertices, 28u);
  EXPECT_EQ(s.vertices.size(), 8u);
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(count_edges(s).boundary, 0u);
}

TEST(Repair, NearDuplicatesWithinToleranceAreWelded) {
  auto s = soup(test::box_mesh(1, 1, 1));
  s.vertices[5] += Eigen::Vector3d(1e-9, 0, 0);  // 1e-9 of the 1.7 m diagonal: below 1e-7
  auto r = repair_mesh(s);
  EXPECT_EQ(s.vertices.size(), 8u);
  auto t = soup(test::box_mesh(1, 1, 1));
  t.vertices[5] += Eigen::Vector3d(1e-3, 0, 0);  // far above the tolerance: stays apart
  r = repair_mesh(t);
  EXPECT_EQ(t.vertices.size(), 9u);
  EXPECT_GT(r.boundary_edges, 0u);
}

TEST(Repair, FlippedFacesAreReoriented) {
  auto box = test::box_mesh(1, 2, 3);
  std::swap(box.triangles[3][1], box.triangles[3][2]);
  std::swap(box.triangles[7][1], box.triangles[7][2]);
  EXPECT_EQ(count_edges(box).misoriented, 6u);
  const auto r = repair_mesh(box);
  EXPECT_EQ(r.reoriented_triangles, 2u);
  EXPECT_EQ(count_edges(box).misoriented, 0u);
  EXPECT_NEAR(r.components[0].signed_volume, 6.0, 1e-12);
}

TEST(Repair, MostlyFlippedFacesEndOutward) {
  // Seed triangle flipped: the walk orients everything like it, then the negative volume
  // flips the whole component back.
  auto box = test::box_mesh(1, 2, 3);
  std::swap(box.triangles[0][1], box.triangles[0][2]);
  const auto r = repair_mesh(box);
  EXPECT_EQ(r.reoriented_triangles, 11u);
  EXPECT_EQ(r.inverted_components, 1u);
  EXPECT_NEAR(r.components[0].signed_volume, 6.0, 1e-12);
}

TEST(Repair, ComponentsAreListedWithTheirVolumes) {
  auto m = test::box_mesh(1, 1, 1);
  const auto b = test::box_mesh(2, 1, 1);
  const auto n = static_cast<std::uint32_t>(m.vertices.size());
  for (const auto& p : b.vertices) m.vertices.push_back(p + Eigen::Vector3d(5, 0, 0));
  for (const auto& t : b.triangles) m.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
  const auto r = repair_mesh(m);
  ASSERT_EQ(r.components.size(), 2u);
  EXPECT_NEAR(r.components[0].signed_volume, 1.0, 1e-12);
  EXPECT_NEAR(r.components[1].signed_volume, 2.0, 1e-12);
  EXPECT_NE(describe(r).find("component 2: 12 triangles, area 10 m², volume 2 m³"),
            std::string::npos);
}

TEST(Repair, DegenerateTrianglesAreRemoved) {
  auto box = test::box_mesh(1, 1, 1);
  box.triangles.push_back({0, 0, 1});
  box.vertices.emplace_back(0.5, 0, 0);  // on the edge 0–1: zero area with 0 and 1
  box.triangles.push_back({0, 1, 8});
  const auto r = repair_mesh(box);
  EXPECT_EQ(r.degenerate_triangles, 2u);
  EXPECT_EQ(box.triangles.size(), 12u);
  EXPECT_TRUE(r.closed());
}

TEST(Repair, BoundaryAndNonManifoldEdgesAreCounted) {
  auto box = test::box_mesh(1, 1, 1);
  box.triangles.pop_back();
  auto r = repair_mesh(box);
  EXPECT_EQ(r.boundary_edges, 3u);
  EXPECT_FALSE(r.closed());
  EXPECT_NE(describe(r).find("open (3 boundary edges)"), std::string::npos);
  // A fin: a third triangle on the edge 0–1.
  auto fin = test::box_mesh(1, 1, 1);
  fin.vertices.emplace_back(0.5, -1, -1);
  fin.triangles.push_back({0, 1, 8});
  r = repair_mesh(fin);
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.boundary_edges, 2u);
}

}  // namespace
}  // namespace rigid::mesh
