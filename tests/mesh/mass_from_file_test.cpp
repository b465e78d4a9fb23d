#include "rigid/mesh/mass_from_file.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "mesh/detail/read_mesh.hpp"
#include "mesh/mesh_builders.hpp"
#include "rigid/mesh/read_mesh.hpp"
#include "support/expect_error.hpp"

namespace rigid::mesh {
namespace {

std::string temp_file(const std::string& name) {
  return (std::filesystem::path(testing::TempDir()) / ("rigid_mass_from_file_" + name)).string();
}

MassSpec density(double rho) { return {std::nullopt, rho, false, std::nullopt}; }

// The step-by-step path the fast one must reproduce bit for bit.
struct FullPath {
  TriangleMesh mesh;
  RepairReport repair;
};

FullPath full_path(const std::string& file, double scale, const RepairOptions& options = {}) {
  FullPath f{read_mesh(file, scale), {}};
  f.repair = repair_mesh(f.mesh, options);
  return f;
}

// Every field of the two reports and of the two results, compared exactly.
void expect_identical(const MeshFileMass& fast, const RepairReport& repair,
                      const MeshMassResult& mass) {
  EXPECT_EQ(fast.repair.input_vertices, repair.input_vertices);
  EXPECT_EQ(fast.repair.input_triangles, repair.input_triangles);
  EXPECT_EQ(fast.repair.welded_vertices, repair.welded_vertices);
  EXPECT_EQ(fast.repair.degenerate_triangles, repair.degenerate_triangles);
  EXPECT_EQ(fast.repair.boundary_edges, repair.boundary_edges);
  EXPECT_EQ(fast.repair.non_manifold_edges, repair.non_manifold_edges);
  EXPECT_EQ(fast.repair.reoriented_triangles, repair.reoriented_triangles);
  EXPECT_EQ(fast.repair.inverted_components, repair.inverted_components);
  EXPECT_EQ(fast.repair.tolerance_weld, repair.tolerance_weld);
  EXPECT_EQ(fast.repair.warnings, repair.warnings);
  ASSERT_EQ(fast.repair.components.size(), repair.components.size());
  for (std::size_t i = 0; i < repair.components.size(); ++i) {
    EXPECT_EQ(fast.repair.components[i].triangles, repair.components[i].triangles);
    EXPECT_EQ(fast.repair.components[i].boundary_edges, repair.components[i].boundary_edges);
    EXPECT_EQ(fast.repair.components[i].signed_volume, repair.components[i].signed_volume);
    EXPECT_EQ(fast.repair.components[i].area, repair.components[i].area);
  }
  EXPECT_EQ(fast.mass.measure, mass.measure);
  EXPECT_EQ(fast.mass.properties.mass(), mass.properties.mass());
  EXPECT_EQ(fast.mass.properties.com(), mass.properties.com());
  EXPECT_EQ(fast.mass.properties.inertia_com(), mass.properties.inertia_com());
  EXPECT_EQ(fast.mass.warnings, mass.warnings);
}

// Binary STL of `m`, then both paths; bitwise the same whatever the options.
void expect_fast_equals_full(const TriangleMesh& m, const std::string& name, double scale,
                             const MassSpec& spec) {
  const std::string file = temp_file(name + ".stl");
  write_stl_binary(m, file);
  for (const bool exact_first : {true, false}) {
    SCOPED_TRACE(fmt::format("{}, exact_weld_first = {}", name, exact_first));
    const RepairOptions options{.exact_weld_first = exact_first};
    const FullPath f = full_path(file, scale, options);
    const MeshFileMass fast = mesh_mass_from_file(file, scale, spec, options);
    expect_identical(fast, f.repair, mesh_mass_properties(f.mesh, spec));
  }
}

TEST(MeshMassFromFile, BinaryStlVerticesAreDistinct) {
  // The property that lets the fast path skip the exact weld: no copies left to merge.
  const std::string file = temp_file("distinct.stl");
  write_stl_binary(test::uv_sphere(0.1, 16), file);
  detail::ReadResult r = detail::read_mesh(file, 1e-3);
  EXPECT_TRUE(r.vertices_distinct);
  EXPECT_EQ(r.mesh.vertices.size(), 2u + 15u * 32u);  // poles + (n − 1) rings of 2n
  EXPECT_EQ(repair_mesh(r.mesh).welded_vertices, 0u);
  // a scale that could map distinct float32 values to one double is not trusted
  EXPECT_FALSE(detail::read_mesh(file, 1e-300).vertices_distinct);
}

TEST(MeshMassFromFile, OtherFormatsAreNotMarkedDistinct) {
  const std::string file = temp_file("cube.off");
  {
    std::FILE* f = std::fopen(file.c_str(), "w");
    ASSERT_NE(f, nullptr);
    // a tetrahedron whose first vertex is repeated: an exact weld has work to do
    std::fputs("OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n"
               "3 0 2 1\n3 4 1 3\n3 1 2 3\n3 0 3 2\n", f);
    std::fclose(f);
  }
  EXPECT_FALSE(detail::read_mesh(file, 1.0).vertices_distinct);
  const FullPath f = full_path(file, 1.0);
  EXPECT_EQ(f.repair.welded_vertices, 1u);
  const MeshFileMass fast = mesh_mass_from_file(file, 1.0, density(6.0));
  expect_identical(fast, f.repair, mesh_mass_properties(f.mesh, density(6.0)));
  // the unit tetrahedron's volume 1/6 × 6 kg/m³; a few ulps of round-off (1/6 is inexact)
  EXPECT_NEAR(fast.mass.properties.mass(), 1.0, 4e-16);
}

TEST(MeshMassFromFile, GeneratedMeshesGiveTheStepByStepResultBitwise) {
  // closed spheres (lanes filled and not: 4n(n−1) triangles), far from the origin, in mm
  expect_fast_equals_full(test::uv_sphere(0.1, 24), "sphere24", 1.0, density(1000));
  expect_fast_equals_full(test::uv_sphere(0.1, 7), "sphere7", 1.0, density(1000));
  TriangleMesh far = test::uv_sphere(50.0, 20);
  far.translate(Eigen::Vector3d(1e4, -3e4, 2e4));
  expect_fast_equals_full(far, "far", 1e-3, {2.5, std::nullopt, false, std::nullopt});
  // inward normals (flipped whole) and a shuffled winding (flipped face by face)
  TriangleMesh inverted = test::uv_sphere(0.2, 12);
  inverted.reverse_winding();
  expect_fast_equals_full(inverted, "inverted", 1.0, density(7850));
  TriangleMesh shuffled = test::uv_sphere(0.2, 12);
  std::mt19937 rng(5);
  for (auto& t : shuffled.triangles) {
    if (rng() % 2 == 0) std::swap(t[1], t[2]);
  }
  expect_fast_equals_full(shuffled, "shuffled", 1.0, density(7850));
  // two components, one of them a box sharing no vertex with the sphere
  TriangleMesh two = test::uv_sphere(0.1, 10);
  TriangleMesh box = test::box_mesh(0.3, 0.2, 0.1);
  box.translate(Eigen::Vector3d(1, 0, 0));
  const auto offset = static_cast<std::uint32_t>(two.vertices.size());
  two.vertices.insert(two.vertices.end(), box.vertices.begin(), box.vertices.end());
  for (auto t : box.triangles) two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  expect_fast_equals_full(two, "two", 1.0, density(1000));
  // a thin shell of an open mesh (the sphere without its first triangle)
  TriangleMesh open = test::uv_sphere(0.1, 10);
  open.triangles.erase(open.triangles.begin());
  expect_fast_equals_full(open, "open", 1.0, {std::nullopt, 3.0, true, 0.002});
}

TEST(MeshMassFromFile, OpenSolidIsRefusedLikeTheStepByStepPath) {
  TriangleMesh open = test::uv_sphere(0.1, 10);
  open.triangles.erase(open.triangles.begin());
  const std::string file = temp_file("open.stl");
  write_stl_binary(open, file);
  // the first triangle of a UV sphere's polar fan: its three edges become boundary edges
  EXPECT_RIGID_ERROR((void)mesh_mass_from_file(file, 1.0, density(1000)),
                     "not closed (3 boundary edges, 0 non-manifold edges)");
}

TEST(MeshMassFromFile, ReportOverloadMatchesTheEdgeMatchingOne) {
  TriangleMesh m = test::uv_sphere(0.1, 9);
  m.reverse_winding();
  const RepairReport report = repair_mesh(m);
  const MeshMassResult a = mesh_mass_properties(m, density(1000));
  const MeshMassResult b = mesh_mass_properties(m, density(1000), report);
  EXPECT_EQ(a.properties.mass(), b.properties.mass());
  EXPECT_EQ(a.properties.com(), b.properties.com());
  EXPECT_EQ(a.properties.inertia_com(), b.properties.inertia_com());
  const EdgeCounts e = count_edges(m);
  EXPECT_EQ(e.boundary, report.boundary_edges);
  EXPECT_EQ(e.non_manifold, report.non_manifold_edges);
}

TEST(MeshMassFromFile, MissingFileNamesIt) {
  EXPECT_RIGID_ERROR((void)mesh_mass_from_file(temp_file("absent.stl"), 1.0, density(1)),
                     "absent.stl");
}

}  // namespace
}  // namespace rigid::mesh
