// Meshes this project did not write: the data set of the CGAL demos (Debian libcgal-demo,
// /usr/share/doc/libcgal-demo/data.tar.gz; scripts/install-deps.sh installs it). The expected
// values come from the files' own geometry (a 2 m cube, a sphere of radius 0.5 m), not from
// this code.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "rigid/mesh.hpp"
#include "support/expect_error.hpp"

namespace rigid::mesh {
namespace {

constexpr const char* kArchive = "/usr/share/doc/libcgal-demo/data.tar.gz";

// Extracts the named members of data/meshes once per test process and returns the folder.
std::string cgal_meshes() {
  static const std::string dir = [] {
    // one folder per process: ctest runs the tests of this binary as parallel processes, and
    // two tar runs into one folder fail with "File exists"
    const std::string out =
        (std::filesystem::path(testing::TempDir()) / fmt::format("rigid_cgal_{}", ::getpid())).string();
    std::filesystem::create_directories(out);
    const std::string cmd = fmt::format(
        "tar -xzf {} -C {} data/meshes/cube.off data/meshes/cube-shuffled.off "
        "data/meshes/cube-ouvert.off data/meshes/blobby_3cc.off data/meshes/sphere.stl "
        "data/meshes/sphere.ply data/meshes/boeing.off data/meshes/bones.off",
        kArchive, out);
    return std::system(cmd.c_str()) == 0 ? out + "/data/meshes/" : std::string();
  }();
  return dir;
}

MassSpec unit_density() { return {std::nullopt, 1.0, false, {}}; }
MassSpec shell_density() { return {std::nullopt, 1.0, true, {}}; }

class RealFiles : public testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(cgal_meshes().empty())
        << kArchive << " could not be extracted: install libcgal-demo (scripts/install-deps.sh)";
  }
};

TEST_F(RealFiles, CubeIsExact) {
  auto m = read_mesh(cgal_meshes() + "cube.off");
  const auto rep = repair_mesh(m);
  EXPECT_TRUE(rep.closed());
  const auto r = mesh_mass_properties(m, unit_density());
  // [-1, 1]³: V = 8, I = m (2² + 2²)/12 = 16/3 about each axis.
  EXPECT_NEAR(r.measure, 8.0, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.properties.inertia_com()(i, i), 16.0 / 3, 1e-12);
}

TEST_F(RealFiles, ShuffledWindingIsRepaired) {
  // The same cube with its triangles' winding shuffled (comments before the header, too).
  auto m = read_mesh(cgal_meshes() + "cube-shuffled.off");
  EXPECT_GT(count_edges(m).misoriented, 0u);
  const auto rep = repair_mesh(m);
  EXPECT_GT(rep.reoriented_triangles, 0u);
  EXPECT_EQ(count_edges(m).misoriented, 0u);
  const auto r = mesh_mass_properties(m, unit_density());
  EXPECT_NEAR(r.measure, 8.0, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.properties.inertia_com()(i, i), 16.0 / 3, 1e-12);
}

TEST_F(RealFiles, OpenCubeIsRefusedAsASolid) {
  // cube-ouvert: the cube with one square face (two triangles) missing: the four edges of
  // that face are boundary edges (10 triangles in the file, read by hand).
  auto m = read_mesh(cgal_meshes() + "cube-ouvert.off");
  const auto rep = repair_mesh(m);
  EXPECT_EQ(rep.boundary_edges, 4u);
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(m, unit_density()),
                     "not closed (4 boundary edges, 0 non-manifold edges)");
  EXPECT_GT(mesh_mass_properties(m, {std::nullopt, 1.0, true, {}}).measure, 0.0);
}

TEST_F(RealFiles, MultiComponentMeshesListEachComponent) {
  auto blobby = read_mesh(cgal_meshes() + "blobby_3cc.off");
  EXPECT_EQ(repair_mesh(blobby).components.size(), 3u);  // "3cc": three connected components
  auto bones = read_mesh(cgal_meshes() + "bones.off");
  const auto rep = repair_mesh(bones);
  EXPECT_TRUE(rep.closed());
  ASSERT_GT(rep.components.size(), 1u);
  double sum = 0;
  for (const auto& c : rep.components) {
    EXPECT_GT(c.signed_volume, 0.0);
    sum += c.signed_volume;
  }
  // The whole mesh's volume is the sum of its components' (each summed about one point).
  EXPECT_NEAR(mesh_mass_properties(bones, unit_density()).measure, sum, 1e-12 * sum);
}

TEST_F(RealFiles, InvertedClosedMeshIsFlipped) {
  auto m = read_mesh(cgal_meshes() + "boeing.off");
  const auto rep = repair_mesh(m);
  EXPECT_TRUE(rep.closed());
  EXPECT_GT(rep.reoriented_triangles + rep.inverted_components, 0u);
  EXPECT_GT(mesh_mass_properties(m, unit_density()).measure, 0.0);
}

TEST_F(RealFiles, BinaryStlAndAsciiPlyOfOneSphereAgree) {
  auto stl = read_mesh(cgal_meshes() + "sphere.stl");  // binary, float32
  auto ply = read_mesh(cgal_meshes() + "sphere.ply");  // ASCII, doubles
  repair_mesh(stl);
  repair_mesh(ply);
  EXPECT_EQ(stl.vertices.size(), ply.vertices.size());
  const auto a = mesh_mass_properties(stl, unit_density());
  const auto b = mesh_mass_properties(ply, unit_density());
  // float32 storage: relative 6e-8 per coordinate, so 1e-6 on volume and inertia.
  EXPECT_NEAR(a.measure, b.measure, 1e-6 * b.measure);
  EXPECT_LT((a.properties.inertia_com() - b.properties.inertia_com()).norm(),
            1e-6 * b.properties.inertia_com().norm());
  // An inscribed polyhedron of a sphere of radius 0.5: below 4/3 π r³ and within 5% of it.
  const double v = 4.0 / 3 * 3.141592653589793 * 0.125;
  EXPECT_LT(b.measure, v);
  EXPECT_GT(b.measure, 0.95 * v);
}

TEST_F(RealFiles, ExactWeldPathMatchesTheToleranceWeldPath) {
  // Every file of the set through both repair paths: the same mesh bit for bit, hence the
  // same mass properties.
  for (const char* name : {"cube.off", "cube-shuffled.off", "cube-ouvert.off", "blobby_3cc.off",
                           "sphere.stl", "sphere.ply", "boeing.off", "bones.off"}) {
    SCOPED_TRACE(name);
    auto exact = read_mesh(cgal_meshes() + name);
    auto full = exact;
    const auto a = repair_mesh(exact);
    const auto b = repair_mesh(full, {.exact_weld_first = false});
    EXPECT_EQ(exact.vertices, full.vertices);
    EXPECT_EQ(exact.triangles, full.triangles);
    EXPECT_EQ(a.welded_vertices, b.welded_vertices);
    EXPECT_EQ(a.boundary_edges, b.boundary_edges);
    EXPECT_EQ(a.reoriented_triangles, b.reoriented_triangles);
    EXPECT_EQ(a.inverted_components, b.inverted_components);
    EXPECT_EQ(a.components.size(), b.components.size());
    if (a.closed()) {
      const auto ma = mesh_mass_properties(exact, unit_density());
      const auto mb = mesh_mass_properties(full, unit_density());
      EXPECT_EQ(ma.measure, mb.measure);
      EXPECT_EQ(ma.properties.inertia_com(), mb.properties.inertia_com());
    }
  }
  // The binary STL soup of a closed sphere welds exactly: the fast path.
  auto stl = read_mesh(cgal_meshes() + "sphere.stl");
  EXPECT_FALSE(repair_mesh(stl).tolerance_weld);
}

TEST_F(RealFiles, MassFromFileMatchesTheStepByStepPath) {
  // mesh_mass_from_file skips the exact weld of a binary STL and the second edge matching:
  // the same report and the same mass properties, bit for bit, on every file of the set.
  for (const char* name : {"cube.off", "cube-shuffled.off", "cube-ouvert.off", "blobby_3cc.off",
                           "sphere.stl", "sphere.ply", "boeing.off", "bones.off"}) {
    SCOPED_TRACE(name);
    auto m = read_mesh(cgal_meshes() + name);
    const RepairReport rep = repair_mesh(m);
    // as a shell (open meshes too)
    const MeshFileMass shell = mesh_mass_from_file(cgal_meshes() + name, 1.0, shell_density());
    EXPECT_EQ(shell.repair.welded_vertices, rep.welded_vertices);
    EXPECT_EQ(shell.repair.boundary_edges, rep.boundary_edges);
    EXPECT_EQ(shell.repair.reoriented_triangles, rep.reoriented_triangles);
    EXPECT_EQ(shell.repair.inverted_components, rep.inverted_components);
    EXPECT_EQ(shell.repair.components.size(), rep.components.size());
    EXPECT_EQ(shell.repair.warnings, rep.warnings);
    const MeshMassResult full_shell = mesh_mass_properties(m, shell_density());
    EXPECT_EQ(shell.mass.measure, full_shell.measure);
    EXPECT_EQ(shell.mass.properties.inertia_com(), full_shell.properties.inertia_com());
    if (!rep.closed()) {  // refused as a solid by both, with one message
      std::string message;
      try {
        (void)mesh_mass_properties(m, unit_density());
      } catch (const Error& e) {
        message = e.what();
      }
      ASSERT_FALSE(message.empty());
      // the path without repair's report adds the remedy for a mesh that skipped repair
      message = message.substr(0, message.find(" (if the mesh has not been through"));
      EXPECT_RIGID_ERROR((void)mesh_mass_from_file(cgal_meshes() + name, 1.0, unit_density()),
                         message);
      continue;
    }
    const MeshFileMass fast = mesh_mass_from_file(cgal_meshes() + name, 1.0, unit_density());
    const MeshMassResult full = mesh_mass_properties(m, unit_density());
    EXPECT_EQ(fast.mass.measure, full.measure);
    EXPECT_EQ(fast.mass.properties.mass(), full.properties.mass());
    EXPECT_EQ(fast.mass.properties.com(), full.properties.com());
    EXPECT_EQ(fast.mass.properties.inertia_com(), full.properties.inertia_com());
  }
}

TEST_F(RealFiles, OpenCubeIsFilledExactly) {
  // cube-ouvert's missing square face is a planar hole: filled, it is the cube again.
  auto m = read_mesh(cgal_meshes() + "cube-ouvert.off");
  repair_mesh(m);
  const HoleFillReport fill = fill_holes(m);
  ASSERT_EQ(fill.holes.size(), 1u);
  EXPECT_EQ(fill.holes[0].boundary_edges, 4u);
  EXPECT_NEAR(fill.area, 4.0, 1e-12);  // a 2 m × 2 m face
  EXPECT_TRUE(repair_mesh(m).closed());
  const auto r = mesh_mass_properties(m, unit_density());
  EXPECT_NEAR(r.measure, 8.0, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.properties.inertia_com()(i, i), 16.0 / 3, 1e-12);
}

// Debian's assimp-testmodels (scripts/install-deps.sh installs it): meshes from many
// exporters, a good part of them broken on purpose. Each one is read, repaired and measured
// (as a solid, and as a shell) or refused with a rigid::Error naming the file; nothing else
// may escape (no other exception, no crash, no hang: the whole set takes well under a second).
constexpr const char* kAssimp = "/usr/share/assimp/models";

TEST(ThirdPartyFiles, AssimpModelsLoadOrAreRefused) {
  namespace fs = std::filesystem;
  ASSERT_TRUE(fs::is_directory(kAssimp))
      << kAssimp << " is missing: install assimp-testmodels (scripts/install-deps.sh)";
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(kAssimp)) {
    std::string ext = e.path().extension().string();
    for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (e.is_regular_file() && (ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off")) {
      files.push_back(e.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  EXPECT_GE(files.size(), 47u);  // the package's 5.2.5 set
  std::size_t measured = 0, refused = 0;
  for (const auto& f : files) {
    try {
      const MeshFileMass shell = mesh_mass_from_file(f, 1.0, shell_density());
      EXPECT_TRUE(std::isfinite(shell.mass.properties.mass()) && shell.mass.properties.mass() > 0) << f;
      ++measured;
      try {
        (void)mesh_mass_from_file(f, 1.0, unit_density());
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("mesh_mass_properties(): "), std::string::npos) << e.what();
      }
    } catch (const Error& e) {
      ++refused;
      // the reader's refusals start with the file; an area of zero (a degenerate mesh) with
      // the function
      const std::string what = e.what();
      EXPECT_TRUE(what.starts_with(f + ":") || what.starts_with("mesh_mass_properties(): ")) << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << f << ": not a rigid::Error: " << e.what();
    }
  }
  // the files whose content is known: a cube, a box, the triangles of several solids
  EXPECT_GT(measured, 25u);
  EXPECT_GT(refused, 10u);
  const auto two = read_mesh(std::string(kAssimp) + "/STL/triangle_with_two_solids.stl");
  EXPECT_EQ(two.triangles.size(), 2u);  // one per `solid` block
  auto cube = read_mesh(std::string(kAssimp) + "/OFF/Cube.off");
  ASSERT_TRUE(repair_mesh(cube).closed());
  EXPECT_GT(mesh_mass_properties(cube, unit_density()).measure, 0.0);
  EXPECT_RIGID_ERROR((void)read_mesh(std::string(kAssimp) + "/invalid/OutOfMemory.off"),
                     "OutOfMemory.off:2: the header declares 353535235358 vertices");
}

}  // namespace
}  // namespace rigid::mesh
