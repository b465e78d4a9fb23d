#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/tolerance.hpp"

#include "rigid/mesh/mass_from_file.hpp"
#include "rigid/mesh/read_mesh.hpp"
#include "support/expect_error.hpp"

namespace rigid::mesh {
namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string p = (std::filesystem::path(testing::TempDir()) / ("rigid_obj_" + name)).string();
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// A box a × b × c with its corner at (x0, 0, 0), six quads wound outward, with the header
// lines `extra` first.
std::string box_obj(double x0, double a, double b, double c, const std::string& extra = "") {
  std::string s = extra;
  for (int i = 0; i < 8; ++i) {
    s += fmt::format("v {:.17g} {:.17g} {:.17g}\n", x0 + (i & 1) * a, ((i >> 1) & 1) * b,
                     ((i >> 2) & 1) * c);
  }
  s += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return s;
}

MassSpec density(double rho) { return {std::nullopt, rho, false, {}}; }

TEST(ReadObj, CoordinatesAreDoubles) {
  // 0.2 × 0.3 × 0.1 m of density 2700: 16.2 kg wherever it is. Read as float32, 1000 km from
  // the origin, 0.2 m became 0.25 m (float spacing there: 0.0625 m) and the box 20.25 kg.
  // In double the corner 1e6 + 0.2 is off by at most half a spacing (2⁻³⁴ m ≈ 5.8e-11 m),
  // 2.9e-10 of 0.2 m: 1e-9 relative bounds the mass.
  for (const double x0 : {0.0, 1e3, 1e6}) {
    const auto p = write("far.obj", box_obj(x0, 0.2, 0.3, 0.1));
    const auto r = mesh_mass_from_file(p, 1.0, density(2700));
    EXPECT_NEAR(r.mass.properties.mass(), 16.2, 1e-9 * 16.2) << "corner at x = " << x0;
    EXPECT_NEAR(r.mass.properties.com().x(), x0 + 0.1, 1e-9) << "corner at x = " << x0;
  }
}

TEST(ReadObj, NonFiniteCoordinatesAreRefusedWithTheirLine) {
  for (const std::string bad : {"nan", "-nan", "inf", "-inf", "infinity", "1e999"}) {
    std::string text = box_obj(0, 1, 1, 1, "# a box\n");
    text.replace(text.find("v 1 0 0"), 7, "v 1 " + bad + " 0");  // vertex 2, line 3
    const auto p = write("nan.obj", text);
    EXPECT_RIGID_ERROR((void)read_mesh(p), fmt::format("{}:3: a coordinate of vertex 2 is {}: "
                                                       "expected a finite number",
                                                       p, bad));
  }
}

TEST(ReadObj, ErrorsNameTheLine) {
  const std::string box = box_obj(0, 1, 1, 1, "o box\n");  // faces on lines 10 to 15
  std::string t = box;
  t.replace(t.find("f 1 5 7 3"), 9, "f 1 5 x 3");
  auto p = write("word.obj", t);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":14: 'x' is not a vertex reference");
  t = box;
  t.replace(t.find("f 1 5 7 3"), 9, "f 1 5 70 3");
  p = write("range.obj", t);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":14: face 5 uses vertex 70: the file has 8 vertices");
  t = box;
  t.replace(t.find("f 1 5 7 3"), 9, "f 1 -9 7 3");
  p = write("before.obj", t);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":14: face 5 refers to vertex -9, before the first");
  t = box;
  t.replace(t.find("v 1 0 0"), 7, "v 1 0");
  p = write("short.obj", t);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":3: a vertex with 2 coordinates: expected 'v x y z'");
  t = box;
  t.replace(t.find("f 1 5 7 3"), 9, "f 1 5");
  p = write("two.obj", t);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":14: face 5 with 2 vertices: expected at least 3");
  // a quad whose fourth corner leaves its plane by 0.1 of its size
  t = box;
  t.replace(t.find("v 1 1 0"), 7, "v 1 1 0.1");
  p = write("bent.obj", t);
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ":10: face 1: the polygon of 4 vertices is not planar");
}

TEST(ReadObj, IndexFormsNegativeIndicesAndContinuedLines) {
  // v/vt/vn, v//vn, negative (relative) indices, a face continued over two lines, records a
  // mass does not need
  std::string t = "mtllib none.mtl\ng box\ns off\nvt 0 0\nvn 0 0 1\n";
  for (int i = 0; i < 8; ++i) {
    t += fmt::format("v {} {} {} 1\n", (i & 1) * 1, ((i >> 1) & 1) * 2, ((i >> 2) & 1) * 3);
  }
  t += "usemtl steel\nf 1/1/1 3/1/1 4/1/1 2/1/1\nf 5//1 6//1 8//1 7//1\nf -8 -7 -3 -4\n"
       "f 3 7 \\\n  8 4\nf 1/1 5/1 7/1 3/1\nf 2 4 8 6\nl 1 2\n";
  const auto p = write("forms.obj", t);
  const auto r = mesh_mass_from_file(p, 1.0, density(1));
  EXPECT_EQ(r.repair.input_triangles, 12u);
  EXPECT_EQ(r.repair.reoriented_triangles, 0u);
  EXPECT_NEAR(r.mass.measure, 6.0, 1e-14);  // 1 × 2 × 3, a few ulps
}

TEST(ReadObj, MaterialsAreNeverOpened) {
  // mtllib naming a device that never ends (a link named like a material file, an absolute
  // path): the reader needs no materials and opens neither
  const std::filesystem::path dir = testing::TempDir();
  const std::filesystem::path link = dir / "rigid_obj_zero.mtl";
  std::filesystem::remove(link);
  std::filesystem::create_symlink("/dev/zero", link);
  const auto p = write("mtl.obj", box_obj(0, 1, 1, 1, "mtllib rigid_obj_zero.mtl\nmtllib /dev/zero\n"));
  const auto start = std::chrono::steady_clock::now();
  const auto r = mesh_mass_from_file(p, 1.0, density(1));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NEAR(r.mass.measure, 1.0, 1e-15);
  // a generous bound: reading the 10 lines takes microseconds
  EXPECT_LT(seconds, rigid::test::hang_bound(2.0));
}

TEST(ReadObj, NoFaces) {
  const auto p = write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
  EXPECT_RIGID_ERROR((void)read_mesh(p), p + ": no faces: not a mesh OBJ file");
}

}  // namespace
}  // namespace rigid::mesh
