#include "rigid/mesh/read_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "mesh/mesh_builders.hpp"
#include "rigid/mesh/mesh_mass.hpp"
#include "rigid/mesh/repair.hpp"
#include "support/expect_error.hpp"

namespace rigid::mesh {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::path(testing::TempDir()) / ("rigid_mesh_" + name)).string();
}

std::string write(const std::string& name, const std::string& bytes) {
  const std::string p = temp_path(name);
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

// The box [0,1]×[0,2]×[0,3] in each format, written by hand from test::box_mesh's faces.
constexpr double kBoxVolume = 6.0;

double solid_volume(TriangleMesh m) {
  repair_mesh(m);
  return mesh_mass_properties(m, {std::nullopt, 1.0, false, {}}).measure;
}

std::string ascii_stl(const TriangleMesh& m, const std::string& name = "box") {
  std::string s = "solid " + name + "\n";
  for (const auto& t : m.triangles) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (auto i : t) {
      s += fmt::format("      vertex {} {} {}\n", m.vertices[i].x(), m.vertices[i].y(),
                       m.vertices[i].z());
    }
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid " + name + "\n";
}

std::string binary_stl(const TriangleMesh& m, const std::string& header) {
  std::string s(80, '\0');
  std::memcpy(s.data(), header.data(), std::min<std::size_t>(header.size(), 80));
  const auto n = static_cast<std::uint32_t>(m.triangles.size());
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.triangles) {
    float f[12] = {};
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) f[3 + 3 * k + c] = static_cast<float>(m.vertices[t[k]][c]);
    }
    s.append(reinterpret_cast<const char*>(f), 48);
    s.append(2, '\0');
  }
  return s;
}

// Box faces as quads (counter-clockwise from outside), for OBJ/OFF/PLY polygons.
const std::uint32_t kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

TEST(ReadMesh, AsciiAndBinaryStlAgree) {
  const auto box = test::box_mesh(1, 2, 3);
  const auto a = read_mesh(write("a.stl", ascii_stl(box)));
  const auto b = read_mesh(write("b.stl", binary_stl(box, "exported by a CAD tool")));
  // A binary file whose header starts with "solid", as several exporters write.
  const auto c = read_mesh(write("c.STL", binary_stl(box, "solid part")));
  EXPECT_EQ(a.triangles.size(), 12u);
  EXPECT_EQ(b.triangles.size(), 12u);
  EXPECT_EQ(c.triangles.size(), 12u);
  // Integer coordinates are exact in float32 and in text: the volumes are the polyhedron's.
  EXPECT_NEAR(solid_volume(a), kBoxVolume, 1e-12);
  EXPECT_NEAR(solid_volume(b), kBoxVolume, 1e-12);
  EXPECT_NEAR(solid_volume(c), kBoxVolume, 1e-12);
}

TEST(ReadMesh, UnitsScaleTheVertices) {
  const auto box = test::box_mesh(10, 20, 30);
  const auto m = read_mesh(write("mm.stl", ascii_stl(box)), unit_scale("mm"));
  EXPECT_NEAR(solid_volume(m), 6e-6, 1e-18);  // (10·20·30 mm³ = 6e-6 m³), exact up to round-off
  EXPECT_DOUBLE_EQ(unit_scale("in"), 0.0254);
  EXPECT_DOUBLE_EQ(unit_scale("cm"), 0.01);
  EXPECT_RIGID_ERROR((void)unit_scale("ft"), "unknown unit 'ft': expected m, cm, mm or in");
}

std::string box_obj() {
  const auto box = test::box_mesh(1, 2, 3);
  std::string s = "# box\no box\n";
  for (const auto& p : box.vertices) s += fmt::format("v {} {} {}\n", p.x(), p.y(), p.z());
  for (const auto& q : kQuads) {
    s += fmt::format("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
  }
  return s;
}

TEST(ReadMesh, ObjQuadsAreTriangulated) {
  const auto m = read_mesh(write("box.obj", box_obj()));
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(solid_volume(m), kBoxVolume, 1e-12);
}

std::string box_off() {
  const auto box = test::box_mesh(1, 2, 3);
  std::string s = "OFF\n# a comment\n8 6 12\n";
  for (const auto& p : box.vertices) s += fmt::format("{} {} {}\n", p.x(), p.y(), p.z());
  for (const auto& q : kQuads) s += fmt::format("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
  return s;
}

TEST(ReadMesh, Off) {
  const auto m = read_mesh(write("box.off", box_off()));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(solid_volume(m), kBoxVolume, 1e-12);
}

template <class T>
void put(std::string& s, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string box_ply(const std::string& format) {
  const auto box = test::box_mesh(1, 2, 3);
  std::string s = "ply\nformat " + format +
                  " 1.0\ncomment made in a test\nelement vertex 8\nproperty float x\nproperty "
                  "float y\nproperty float z\nproperty uchar red\nelement face 6\nproperty list "
                  "uchar int vertex_indices\nend_header\n";
  if (format == "ascii") {
    for (const auto& p : box.vertices) s += fmt::format("{} {} {} 255\n", p.x(), p.y(), p.z());
    for (const auto& q : kQuads) s += fmt::format("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
    return s;
  }
  const bool big = format == "binary_big_endian";
  for (const auto& p : box.vertices) {
    for (int c = 0; c < 3; ++c) put(s, static_cast<float>(p[c]), big);
    put(s, std::uint8_t{255}, big);
  }
  for (const auto& q : kQuads) {
    put(s, std::uint8_t{4}, big);
    for (auto i : q) put(s, static_cast<std::int32_t>(i), big);
  }
  return s;
}

TEST(ReadMesh, PlyAsciiAndBothByteOrdersAgree) {
  for (const std::string f : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    const auto m = read_mesh(write(f + ".ply", box_ply(f)));
    EXPECT_EQ(m.triangles.size(), 12u) << f;
    EXPECT_NEAR(solid_volume(m), kBoxVolume, 1e-12) << f;
  }
}

// Malformed files: each error names the file and the line or byte.
TEST(ReadMesh, EmptyFile) {
  for (const std::string ext : {"stl", "obj", "ply", "off"}) {
    const auto p = write("empty." + ext, "");
    EXPECT_RIGID_ERROR((void)read_mesh(p), p + ": the file is empty");
  }
}

TEST(ReadMesh, MissingFileAndUnknownExtension) {
  EXPECT_RIGID_ERROR((void)read_mesh(temp_path("nope.stl")), "nope.stl: cannot open the file");
  EXPECT_RIGID_ERROR((void)read_mesh(write("x.dae", "x")), "x.dae: '.dae' is not a supported mesh format: the supported extensions are .stl, .obj, .ply and .off");
}

TEST(ReadMesh, TruncatedBinaryStl) {
  const auto box = test::box_mesh(1, 2, 3);
  std::string bytes = binary_stl(box, "binary");
  bytes.resize(84 + 50 * 5 + 17);
  const auto p = write("trunc.stl", bytes);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ": byte 80: binary STL triangle count 12 needs 684 "
                                             "bytes but the file has 351");
  const auto q = write("short.stl", std::string(40, 'x'));
  EXPECT_RIGID_ERROR((void)read_mesh(q), q + ": byte 40: truncated binary STL: 40 bytes");
}

TEST(ReadMesh, NaNCoordinates) {
  auto box = test::box_mesh(1, 2, 3);
  std::string bytes = binary_stl(box, "binary");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(bytes.data() + 84 + 50 * 2 + 12 + 4, &nan, 4);  // triangle 3, first vertex, y
  const auto p = write("nan.stl", bytes);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ": byte 200: coordinate of triangle 3 is nan");
  std::string off = box_off();
  off.replace(off.find("0 0 0"), 5, "0 nan 0");
  const auto q = write("nan.off", off);
  EXPECT_RIGID_ERROR((void)read_mesh(q), q + ":4: a vertex coordinate is nan");
  std::string ply = box_ply("ascii");
  ply.replace(ply.find("0 0 0 255"), 9, "0 0 inf 255");
  const auto r = write("nan.ply", ply);
  EXPECT_RIGID_ERROR((void)read_mesh(r), r + ":12: a vertex coordinate is inf");
  std::string stl = ascii_stl(box);
  stl.replace(stl.find("vertex 0 0 0"), 12, "vertex 0 0 NaN");
  const auto s = write("nan_ascii.stl", stl);
  EXPECT_RIGID_ERROR((void)read_mesh(s), s + ":4: a vertex coordinate is NaN");
}

TEST(ReadMesh, IndicesOutOfRange) {
  std::string off = box_off();
  off.replace(off.rfind("4 1 3 7 5"), 9, "4 1 3 7 8");
  const auto p = write("range.off", off);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":17: vertex index 8 out of range: the file has 8");
  std::string ply = box_ply("ascii");
  ply.replace(ply.rfind("4 1 3 7 5"), 9, "4 1 3 7 9");
  const auto q = write("range.ply", ply);
  EXPECT_RIGID_ERROR((void)read_mesh(q), q + ":25: face 6 uses vertex index 9: the file has 8");
  std::string obj = box_obj();
  obj.replace(obj.rfind("f 2 4 8 6"), 9, "f 2 4 8 60");
  const auto r = write("range.obj", obj);
  EXPECT_RIGID_ERROR((void)read_mesh(r), r + ":");
  std::string bin = box_ply("binary_little_endian");
  const std::int32_t big_index = 1000;
  std::memcpy(bin.data() + bin.size() - 4, &big_index, 4);
  const auto s = write("range_bin.ply", bin);
  EXPECT_RIGID_ERROR((void)read_mesh(s), s + ": byte " + std::to_string(bin.size() - 4) +
                                             ": face 6 uses vertex index 1000");
}

TEST(ReadMesh, CountMismatches) {
  std::string off = box_off();
  off.replace(off.find("8 6 12"), 6, "8 7 12");
  const auto p = write("count.off", off);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":18: unexpected end of file: expected a face's "
                                             "vertex count");
  std::string ply = box_ply("binary_big_endian");
  ply.resize(ply.size() - 10);
  const auto q = write("count.ply", ply);
  EXPECT_RIGID_ERROR((void)read_mesh(q), q + ": byte ");
  EXPECT_RIGID_ERROR((void)read_mesh(q), "truncated PLY: element face 6 of 6");
}

TEST(ReadMesh, TextThatIsNotAMesh) {
  const std::string text = "Dear user,\nthis is a letter, not a mesh.\n";
  const auto p = write("letter.stl", text);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ": byte 41: truncated binary STL: 41 bytes, expected at least 84");
  const auto q = write("letter.off", text);
  EXPECT_RIGID_ERROR((void)read_mesh(q), q + ":1: 'Dear': expected the OFF header 'OFF'");
  const auto r = write("letter.ply", text);
  EXPECT_RIGID_ERROR((void)read_mesh(r), r + ":1: missing 'ply' magic line");
  const auto s = write("letter.obj", text);
  EXPECT_RIGID_ERROR((void)read_mesh(s), s + ": no faces: not a mesh OBJ file");
  const auto t = write("solid.stl", "solid thing\n  facet normal 0 0 1\n  outer loop\n  oops\n");
  EXPECT_RIGID_ERROR((void)read_mesh(t), t + ":4: 'oops': expected 'vertex' or 'endloop'");
}

TEST(ReadMesh, BinaryStlSharesExactCopiesOfAVertex) {
  // The reader shares float32-identical copies; the result must be what repair_mesh's exact
  // weld makes of the per-corner soup, so the repaired meshes are the same bit for bit.
  const std::string file = temp_path("sphere.stl");
  write_stl_binary(test::uv_sphere(0.1, 12), file);
  auto shared = read_mesh(file);
  EXPECT_EQ(shared.vertices.size(), 2u + 11u * 24u);
  TriangleMesh soup;
  for (const auto& t : shared.triangles) {
    const auto n = static_cast<std::uint32_t>(soup.vertices.size());
    for (auto i : t) soup.vertices.push_back(shared.vertices[i]);
    soup.triangles.push_back({n, n + 1, n + 2});
  }
  repair_mesh(shared);
  repair_mesh(soup);
  EXPECT_EQ(shared.vertices, soup.vertices);
  EXPECT_EQ(shared.triangles, soup.triangles);
  // −0 and +0 are one position: the box with every zero coordinate negative in one face.
  auto box = test::box_mesh(1, 2, 3);
  std::string bytes = binary_stl(box, "signed zeros");
  for (int k = 0; k < 9; ++k) {  // first triangle's nine coordinates: +0 → −0
    float f = 0;
    std::memcpy(&f, bytes.data() + 84 + 12 + 4 * k, 4);
    if (f == 0) f = -0.0f;
    std::memcpy(bytes.data() + 84 + 12 + 4 * k, &f, 4);
  }
  EXPECT_EQ(read_mesh(write("signed_zero.stl", bytes)).vertices.size(), 8u);
}

TEST(ReadMesh, MultiSolidAsciiStlReadsEverySolid) {
  // Two closed unit cubes, one `solid … endsolid` block each (as exporters write one block per
  // part), and an empty block between them: V = 2, two components.
  auto first = test::box_mesh(1, 1, 1);
  auto second = test::box_mesh(1, 1, 1);
  second.translate(Eigen::Vector3d(3, 0, 0));
  const std::string text = ascii_stl(first, "first") + "solid empty\nendsolid empty\n" +
                           ascii_stl(second, "second part");
  const auto p = write("two_solids.stl", text);
  auto m = read_mesh(p);
  EXPECT_EQ(m.triangles.size(), 24u);
  const auto rep = repair_mesh(m);
  EXPECT_TRUE(rep.closed());
  EXPECT_EQ(rep.components.size(), 2u);
  EXPECT_NEAR(mesh_mass_properties(m, {std::nullopt, 1.0, false, {}}).measure, 2.0, 1e-15);
  // something other than a solid after the first is an error with its line
  const auto q = write("trailing.stl", ascii_stl(first) + "garbage\n");
  EXPECT_RIGID_ERROR((void)read_mesh(q), q + ":87: 'garbage': expected 'solid' or the end of "
                                             "the file");
}

TEST(ReadMesh, NonFiniteCoordinatesAreRefusedInEveryFormat) {
  // every text format, each spelling a strtod or from_chars reads as non-finite (OBJ: see
  // read_obj_test.cpp)
  for (const std::string bad : {"nan", "-inf", "Infinity", "1e400"}) {
    std::string off = box_off();
    off.replace(off.find("1 2 3"), 5, "1 " + bad + " 3");  // the last vertex, line 11
    const auto p = write("bad.off", off);
    EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":11: a vertex coordinate is " + bad);
    std::string ply = box_ply("ascii");
    ply.replace(ply.find("1 2 3 255"), 9, bad + " 2 3 255");  // line 19
    const auto q = write("bad.ply", ply);
    EXPECT_RIGID_ERROR((void)read_mesh(q), q + ":19: a vertex coordinate is " + bad);
    std::string stl = ascii_stl(test::box_mesh(1, 2, 3));
    const std::size_t at = stl.find("vertex 1 2 3");
    stl.replace(at, 12, "vertex 1 2 " + bad);
    const auto r = write("bad.stl", stl);
    const int line = 1 + static_cast<int>(std::count(stl.begin(), stl.begin() + at, '\n'));
    EXPECT_RIGID_ERROR((void)read_mesh(r), fmt::format("{}:{}: a vertex coordinate is {}", r, line, bad));
  }
  // non-finite values of properties that are not coordinates are not used: accepted
  std::string ply = box_ply("ascii");
  ply.replace(ply.find("property uchar red"), 18, "property float nx");
  ply.replace(ply.find("1 2 3 255"), 9, "1 2 3 nan");
  EXPECT_EQ(read_mesh(write("normal.ply", ply)).triangles.size(), 12u);
  // binary PLY, both byte orders and float and double, and binary STL
  for (const std::string format : {"binary_little_endian", "binary_big_endian"}) {
    std::string bin = box_ply(format);
    const std::size_t data = bin.find("end_header\n") + 11;
    const bool big = format == "binary_big_endian";
    std::string value;
    put(value, std::numeric_limits<float>::infinity(), big);
    bin.replace(data + 13 * 7 + 4, 4, value);  // vertex 8, y
    const auto p = write("bad_bin.ply", bin);
    EXPECT_RIGID_ERROR((void)read_mesh(p), fmt::format("{}: byte {}: y of vertex 8 is inf: "
                                                       "expected a finite number",
                                                       p, data + 13 * 7 + 4));
  }
  std::string stl = binary_stl(test::box_mesh(1, 2, 3), "inf");
  const float inf = -std::numeric_limits<float>::infinity();
  std::memcpy(stl.data() + 84 + 50 * 11 + 12 + 4 * 8, &inf, 4);  // triangle 12, third z
  const auto s = write("inf.stl", stl);
  EXPECT_RIGID_ERROR((void)read_mesh(s), fmt::format("{}: byte {}: coordinate of triangle 12 is "
                                                     "-inf",
                                                     s, 84 + 50 * 11 + 12 + 4 * 8));
}

TEST(ReadMesh, ConcaveFacesAreTriangulatedInTheirPlane) {
  // The chevron (0,0), (2,1), (0,2), (1,1) (area 1) extruded by 3, as an OFF and a PLY file
  // of 4-gons: V = 3, area 2 + 3 (2√5 + 2√2). A fan from each face's first vertex covered 3
  // instead of 1 per end face (its second triangle lies outside the chevron).
  const double xy[4][2] = {{0, 0}, {2, 1}, {0, 2}, {1, 1}};
  std::string verts;
  for (double z : {0.0, 3.0}) {
    for (const auto& p : xy) verts += fmt::format("{} {} {}\n", p[0], p[1], z);
  }
  const std::string faces = "4 3 2 1 0\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
  const auto off = write("chevron.off", "OFF\n8 6 0\n" + verts + faces);
  const auto ply = write("chevron.ply",
                         "ply\nformat ascii 1.0\nelement vertex 8\nproperty double x\nproperty "
                         "double y\nproperty double z\nelement face 6\nproperty list uchar int "
                         "vertex_indices\nend_header\n" + verts + faces);
  const double surface = 2 + 3 * (2 * std::sqrt(5.0) + 2 * std::sqrt(2.0));
  for (const auto& p : {off, ply}) {
    auto m = read_mesh(p);
    ASSERT_TRUE(repair_mesh(m).closed());
    // sums of a few dozen terms of size ≤ 20: a few ulps
    EXPECT_NEAR(mesh_mass_properties(m, {std::nullopt, 1.0, false, {}}).measure, 3.0, 1e-14);
    EXPECT_NEAR(mesh_mass_properties(m, {std::nullopt, 1.0, true, {}}).measure, surface,
                1e-14 * surface);
  }
  // the top face (face 2, line 12) bent out of its plane: refused with the face and its line
  const auto bent = write("bent.off", "OFF\n8 6 0\n" + verts.substr(0, verts.rfind("1 1 3")) +
                                          "1 1 3.5\n" + faces);
  EXPECT_RIGID_ERROR((void)read_mesh(bent), bent + ":12: face 2: the polygon of 4 vertices is not planar");
}

}  // namespace
}  // namespace rigid::mesh
