#include "rigid/mesh/repair.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "mesh/mesh_builders.hpp"
#include "rigid/mesh/mesh_mass.hpp"
#include "support/expect_error.hpp"

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

// The exact-weld path and the tolerance-weld path must give the same mesh, bit for bit.
void expect_same_repair(TriangleMesh input) {
  TriangleMesh exact = input;
  TriangleMesh full = std::move(input);
  const auto a = repair_mesh(exact);
  const auto b = repair_mesh(full, {.exact_weld_first = false});
  EXPECT_EQ(exact.vertices, full.vertices);
  EXPECT_EQ(exact.triangles, full.triangles);
  EXPECT_EQ(a.welded_vertices, b.welded_vertices);
  EXPECT_EQ(a.degenerate_triangles, b.degenerate_triangles);
  EXPECT_EQ(a.boundary_edges, b.boundary_edges);
  EXPECT_EQ(a.non_manifold_edges, b.non_manifold_edges);
  EXPECT_EQ(a.reoriented_triangles, b.reoriented_triangles);
  EXPECT_EQ(a.inverted_components, b.inverted_components);
  EXPECT_EQ(a.warnings, b.warnings);
  ASSERT_EQ(a.components.size(), b.components.size());
  for (std::size_t i = 0; i < a.components.size(); ++i) {
    EXPECT_EQ(a.components[i].signed_volume, b.components[i].signed_volume);
    EXPECT_EQ(a.components[i].area, b.components[i].area);
  }
}

TEST(Repair, ExactWeldOfASoupTakesTheFastPath) {
  auto s = soup(test::uv_sphere(0.1, 24));
  const auto r = repair_mesh(s);
  EXPECT_FALSE(r.tolerance_weld);
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(s.vertices.size(), 2u + 23u * 48u);  // poles + (n − 1) rings of 2n
}

TEST(Repair, ExactAndToleranceWeldAgree) {
  expect_same_repair(soup(test::box_mesh(1, 2, 3)));
  expect_same_repair(soup(test::uv_sphere(0.1, 24)));
  // −0 and +0 are one position for both welds
  auto signed_zero = soup(test::box_mesh(1, 1, 1));
  for (auto& p : signed_zero.vertices) p = p.unaryExpr([](double x) { return x == 0 ? -0.0 : x; });
  signed_zero.vertices[0].x() = 0.0;
  expect_same_repair(signed_zero);
  // flipped faces, a flipped seed, an inverted whole, several components
  auto flipped = soup(test::uv_sphere(1.0, 10));
  for (std::size_t f = 0; f < flipped.triangles.size(); f += 7) {
    std::swap(flipped.triangles[f][1], flipped.triangles[f][2]);
  }
  expect_same_repair(flipped);
  auto inverted = soup(test::box_mesh(1, 2, 3));
  inverted.reverse_winding();
  expect_same_repair(inverted);
  auto two = soup(test::box_mesh(1, 1, 1));
  auto far = soup(test::uv_sphere(0.5, 8));
  far.translate(Eigen::Vector3d(10, 2, -3));
  const auto n = static_cast<std::uint32_t>(two.vertices.size());
  two.vertices.insert(two.vertices.end(), far.vertices.begin(), far.vertices.end());
  for (const auto& t : far.triangles) two.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
  expect_same_repair(two);
}

TEST(Repair, ExactPathKeepsClosedPartsThatAlmostTouchApart) {
  // Two closed unit boxes, the second 1e-9 m beyond x = 1: their facing corners are within
  // the tolerance (1e-7 × 3.3 m) but share no edge. The exact path (closed, no short edge)
  // keeps two boxes; the tolerance weld on every vertex merges the four corner pairs.
  auto two = soup(test::box_mesh(1, 1, 1));
  auto second = soup(test::box_mesh(1, 1, 1));
  second.translate(Eigen::Vector3d(1 + 1e-9, 0, 0));
  const auto n = static_cast<std::uint32_t>(two.vertices.size());
  two.vertices.insert(two.vertices.end(), second.vertices.begin(), second.vertices.end());
  for (const auto& t : second.triangles) two.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
  auto full = two;
  const auto a = repair_mesh(two);
  const auto b = repair_mesh(full, {.exact_weld_first = false});
  EXPECT_FALSE(a.tolerance_weld);
  EXPECT_EQ(two.vertices.size(), 16u);
  EXPECT_EQ(full.vertices.size(), 12u);
  EXPECT_EQ(a.components.size(), 2u);
  EXPECT_TRUE(a.closed());
}

TEST(Repair, NearDuplicatesFallBackToTheToleranceWeld) {
  // A copy of a vertex 1e-9 away (float rounding in a converter): the exact weld leaves
  // boundary edges, the tolerance weld closes them, and both paths agree.
  auto s = soup(test::uv_sphere(1.0, 12));
  s.vertices[4] += Eigen::Vector3d(1e-9, 0, 0);
  TriangleMesh copy = s;
  const auto r = repair_mesh(copy);
  EXPECT_TRUE(r.tolerance_weld);
  EXPECT_TRUE(r.closed());
  expect_same_repair(s);
  // An open mesh also takes the tolerance weld (it might close it), and stays open.
  auto open = soup(test::box_mesh(1, 1, 1));
  open.triangles.pop_back();
  const auto o = repair_mesh(open);
  EXPECT_TRUE(o.tolerance_weld);
  EXPECT_EQ(o.boundary_edges, 3u);
}

TEST(Repair, HighDegreeVertexAndLargeSoupAreFast) {
  // The pole of a UV sphere with n = 150 is the lower end of 300 edges (sorted, not scanned
  // pairwise); 89k soup vertices weld in one pass. No timing here: this checks the counts.
  auto s = soup(test::uv_sphere(1.0, 150));
  const auto r = repair_mesh(s);
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(s.vertices.size(), 2u + 149u * 300u);
  EXPECT_EQ(r.components.size(), 1u);
}

TEST(Repair, WeldToleranceMustBeAFraction) {
  // NaN would weld nothing silently, a negative tolerance makes no sense, infinity (or 1 and
  // more: the whole bounding-box diagonal) welds every vertex into one
  for (const double bad : {std::nan(""), -1.0, std::numeric_limits<double>::infinity(), 1.0}) {
    auto box = test::box_mesh(1, 1, 1);
    RepairOptions o;
    o.weld_tolerance = bad;
    EXPECT_RIGID_ERROR((void)repair_mesh(box, o),
                       fmt::format("repair_mesh(): weld tolerance {}: expected a finite number "
                                   "from 0 up to (not including) 1",
                                   bad));
    EXPECT_EQ(box.vertices.size(), 8u);
  }
  auto box = test::box_mesh(1, 1, 1);
  RepairOptions zero;
  zero.weld_tolerance = 0;
  EXPECT_TRUE(repair_mesh(box, zero).closed());
}
}  // namespace
}  // namespace rigid::mesh
