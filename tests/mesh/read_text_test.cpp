// What every reader checks before it reads: the kind of file, its size, and declared counts
// against the size (src/mesh/read_text.cpp and the readers' headers).
#include <sys/stat.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/tolerance.hpp"

#include "rigid/mesh/read_mesh.hpp"
#include "support/expect_error.hpp"

namespace rigid::mesh {
namespace {

namespace fs = std::filesystem;

std::string temp(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("rigid_limits_" + name);
  fs::remove_all(p);
  return p.string();
}

std::string write(const std::string& name, const std::string& bytes) {
  const std::string p = temp(name);
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

// Seconds that `f` takes.
template <class F>
double seconds(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(MeshFiles, DirectoriesDevicesAndFifosAreRefusedByType) {
  for (const std::string ext : {"stl", "obj", "ply", "off"}) {
    const std::string dir = temp("folder." + ext);
    fs::create_directory(dir);
    EXPECT_RIGID_ERROR((void)read_mesh(dir), dir + ": is a directory: expected a mesh file");
    // a link to /dev/zero (endless) and a FIFO (opening it would wait for a writer)
    const std::string zero = temp("zero." + ext);
    fs::create_symlink("/dev/zero", zero);
    const std::string fifo = temp("fifo." + ext);
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    const double t = seconds([&] {
      EXPECT_RIGID_ERROR((void)read_mesh(zero), zero + ": is not a regular file (a device, FIFO "
                                                       "or socket): expected a mesh file");
      EXPECT_RIGID_ERROR((void)read_mesh(fifo), fifo + ": is not a regular file");
      EXPECT_RIGID_ERROR((void)read_mesh("/dev/null"), "/dev/null: ");
    });
    // refused without reading: a generous bound on microseconds
    EXPECT_LT(t, rigid::test::hang_bound(2.0));
  }
}

TEST(MeshFiles, SizeLimit) {
  // a sparse file one byte over the limit: refused by its size, before it is opened
  const std::string p = temp("huge.stl");
  std::ofstream(p).close();
  fs::resize_file(p, kMaxMeshFileBytes + 1);
  EXPECT_RIGID_ERROR((void)read_mesh(p), fmt::format("{}: the file has {} bytes, more than the "
                                                     "limit of {} bytes (2 GiB)",
                                                     p, kMaxMeshFileBytes + 1, kMaxMeshFileBytes));
  fs::remove(p);
}

TEST(MeshFiles, PlyElementWithoutPropertiesEndsAtOnce) {
  // 10¹² rows of nothing, then a valid triangle: counting them would take hours
  const std::string ply =
      "ply\nformat ascii 1.0\nelement nothing 1000000000000\nelement vertex 3\nproperty float "
      "x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const auto p = write("empty_element.ply", ply);
  const double t = seconds([&] {
    EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":3: element nothing declares 1000000000000 rows "
                                               "but no properties");
  });
  EXPECT_LT(t, rigid::test::hang_bound(2.0));  // a generous bound on microseconds
}

TEST(MeshFiles, DeclaredCountsMustFitTheFile) {
  // PLY: 4·10⁹ binary vertices of 12 bytes in a file of 200 bytes, refused before allocation
  const std::string head =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float "
      "x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n";
  auto p = write("count.ply", head + std::string(64, '\0'));
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":3: element vertex declares 4000000000 rows of at "
                                             "least 12 bytes each, but only 64 bytes of data "
                                             "follow the header");
  // ASCII: 1000 faces of at least 2 bytes per property in 30 bytes
  p = write("count_ascii.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
            "y\nproperty float z\nelement face 1000\nproperty list uchar int "
            "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":7: element face declares 1000 rows");
  // OFF: 10⁹ vertices and faces in a file of 30 bytes
  p = write("count.off", "OFF\n1000000000 1000000000 0\n0 0 0\n");
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":2: the header declares 1000000000 vertices and "
                                             "1000000000 faces: expected counts from 0 that fit "
                                             "in the file's 34 bytes");
  p = write("negative.off", "OFF\n-3 1 0\n0 0 0\n");
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":2: the header declares -3 vertices");
  // binary STL: the count must be the size's (84 + 50 n), else it is not binary
  std::string stl(84, '\0');
  const std::uint32_t n = 0xffffffffu;
  std::memcpy(stl.data() + 80, &n, 4);
  p = write("count.stl", stl + std::string(50, '\0'));
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ": byte 80: binary STL triangle count 4294967295 "
                                             "needs 214748364834 bytes but the file has 134");
}

}  // namespace
}  // namespace rigid::mesh
