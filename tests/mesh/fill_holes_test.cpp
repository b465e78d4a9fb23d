#include "rigid/mesh/fill_holes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mesh/mesh_builders.hpp"
#include "rigid/mesh/mesh_mass.hpp"
#include "rigid/mesh/repair.hpp"
#include "support/expect_error.hpp"

namespace rigid::mesh {
namespace {

MassSpec unit_density() { return {std::nullopt, 1.0, false, {}}; }

// Exact polyhedra of size ~1 summed over a few dozen terms: 1e-12 (≈ 4500 ε) is far above
// round-off and far below any wrong patch (which changes the volume by ≥ 1e-3 here).
constexpr double kExact = 1e-12;

// Removes the triangles listed (indices into mesh.triangles).
TriangleMesh without(TriangleMesh m, std::initializer_list<std::size_t> drop) {
  TriangleMesh out;
  out.vertices = m.vertices;
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    if (std::find(drop.begin(), drop.end(), f) == drop.end())
      out.triangles.push_back(m.triangles[f]);
  }
  return out;
}

void expect_same_mass_properties(const MeshMassResult& a, const MeshMassResult& b, double tol) {
  EXPECT_NEAR(a.measure, b.measure, tol * b.measure);
  EXPECT_LT((a.properties.com() - b.properties.com()).norm(), tol);
  EXPECT_LT((a.properties.inertia_com() - b.properties.inertia_com()).norm(),
            tol * b.properties.inertia_com().norm());
}

TEST(FillHoles, MissingBoxFaceIsClosedExactly) {
  // Triangles 0 and 1 are the square face z = 0: a planar four-edge hole, fanned around the
  // face centre. The four fan triangles tile the square, so the box is exact again.
  const auto box = test::box_mesh(1, 2, 3);
  auto open = without(box, {0, 1});
  EXPECT_EQ(repair_mesh(open).boundary_edges, 4u);
  const HoleFillReport fill = fill_holes(open);
  ASSERT_EQ(fill.holes.size(), 1u);
  EXPECT_EQ(fill.holes[0].boundary_edges, 4u);
  EXPECT_EQ(fill.triangles_added, 4u);
  EXPECT_EQ(fill.vertices_added, 1u);
  EXPECT_NEAR(fill.area, 2.0, kExact);  // the 1 × 2 face
  const RepairReport again = repair_mesh(open);
  EXPECT_TRUE(again.closed());
  EXPECT_EQ(again.reoriented_triangles + again.inverted_components, 0u);  // wound outward
  const auto r = mesh_mass_properties(open, unit_density());
  // [0,1]×[0,2]×[0,3]: V = 6, I_xx = V (2² + 3²)/12 = 6.5, I_yy = 5, I_zz = 2.5.
  EXPECT_NEAR(r.measure, 6.0, kExact);
  EXPECT_NEAR(r.properties.inertia_com()(0, 0), 6.5, kExact);
  EXPECT_NEAR(r.properties.inertia_com()(1, 1), 5.0, kExact);
  EXPECT_NEAR(r.properties.inertia_com()(2, 2), 2.5, kExact);
  expect_same_mass_properties(r, mesh_mass_properties(box, unit_density()), kExact);
}

TEST(FillHoles, TriangularHoleGetsOneTriangle) {
  auto open = without(test::box_mesh(1, 1, 1), {5});
  const HoleFillReport fill = fill_holes(open);
  ASSERT_EQ(fill.holes.size(), 1u);
  EXPECT_EQ(fill.triangles_added, 1u);
  EXPECT_EQ(fill.vertices_added, 0u);
  EXPECT_NEAR(fill.area, 0.5, kExact);
  EXPECT_TRUE(repair_mesh(open).closed());
  EXPECT_NEAR(mesh_mass_properties(open, unit_density()).measure, 1.0, kExact);
}

TEST(FillHoles, SpherePoleCapBecomesAFlatPolygon) {
  // Remove the 2n triangles around the north pole of a UV sphere: the hole is ring 1, a
  // regular 2n-gon in the plane z = r cos(π/n). The fan closes it with that polygon, so the
  // filled volume is the sphere mesh's minus the pyramid from the pole over the polygon:
  // V_pyr = A h / 3, A = ½·2n·ρ² sin(2π/2n), ρ = r sin(π/n), h = r (1 − cos(π/n)).
  const double r = 0.5;
  const int n = 12;
  const auto sphere = test::uv_sphere(r, n);
  TriangleMesh open;
  open.vertices = sphere.vertices;
  open.triangles.assign(sphere.triangles.begin() + 2 * n, sphere.triangles.end());
  const HoleFillReport fill = fill_holes(open);
  ASSERT_EQ(fill.holes.size(), 1u);
  EXPECT_EQ(fill.holes[0].boundary_edges, static_cast<std::size_t>(2 * n));
  const double th = std::numbers::pi / n;
  const double rho = r * std::sin(th);
  const double area = 0.5 * 2 * n * rho * rho * std::sin(2 * std::numbers::pi / (2 * n));
  EXPECT_NEAR(fill.area, area, kExact);
  const double v_pyramid = area * r * (1 - std::cos(th)) / 3;
  EXPECT_TRUE(repair_mesh(open).closed());
  const double v_closed = mesh_mass_properties(sphere, unit_density()).measure;
  EXPECT_NEAR(mesh_mass_properties(open, unit_density()).measure, v_closed - v_pyramid, kExact);
}

TEST(FillHoles, ClosedMeshIsLeftAlone) {
  auto box = test::box_mesh(1, 1, 1);
  const HoleFillReport fill = fill_holes(box);
  EXPECT_TRUE(fill.holes.empty());
  EXPECT_EQ(box.triangles.size(), 12u);
}

TEST(FillHoles, HolesTouchingAtAVertexAreRefused) {
  // Triangles (0,2,3) and (0,5,4) share only vertex 0: two holes meeting there, so the
  // boundary through vertex 0 is not a simple loop.
  auto open = without(test::box_mesh(1, 1, 1), {0, 5});
  ASSERT_EQ(open.triangles.size(), 10u);
  EXPECT_RIGID_ERROR((void)fill_holes(open),
                     "boundary loop through vertex 0 at (0, 0, 0) m is not simple: the vertex is "
                     "on 4 boundary edges");
  EXPECT_EQ(open.triangles.size(), 10u);  // unchanged
}

TEST(FillHoles, UnrepairedMeshIsRefused) {
  // A triangle that repeats a vertex (which repair removes) made a loop of one edge that
  // tripped an internal check; inconsistent winding makes loops that are not holes.
  auto box = without(test::box_mesh(1, 1, 1), {0});
  box.triangles.push_back({1, 1, 2});
  EXPECT_RIGID_ERROR((void)fill_holes(box), "fill_holes(): triangle 11 (1, 1, 2) repeats a vertex: "
                                            "holes can be filled only in a repaired mesh; run "
                                            "repair_mesh(mesh) first");
  auto flipped = without(test::box_mesh(1, 1, 1), {0});
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  EXPECT_RIGID_ERROR((void)fill_holes(flipped), "edges are traversed twice in the same direction "
                                                "(inconsistent winding): holes can be filled only "
                                                "in a repaired mesh");
  EXPECT_EQ(flipped.triangles.size(), 11u);  // unchanged
  repair_mesh(flipped);
  EXPECT_EQ(fill_holes(flipped).holes.size(), 1u);
}
}  // namespace
}  // namespace rigid::mesh
