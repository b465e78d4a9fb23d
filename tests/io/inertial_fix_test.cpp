#include "rigid/io/inertial_fix.hpp"

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "support/expect_error.hpp"
#include "support/inertial_text.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;
using std::numbers::pi;

// Expected values from the textbook formulas, written here independently of rigid::mass:
// box m(b²+c²)/12, cylinder m(3r²+l²)/12 and m r²/2, sphere 2/5 m r², and the parallel-axis
// theorem I_C = Σ I_i + m_i (|d_i|² 1 − d_i d_iᵀ) with d_i = c_i − C.
struct Ref {
  double m;
  Eigen::Vector3d c;
  Eigen::Matrix3d I;
};

Ref box(double rho, const Eigen::Vector3d& s, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  const double m = rho * s.prod();
  const Eigen::Vector3d d(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                          s.x() * s.x() + s.y() * s.y());
  return {m, p, R * (m / 12 * d).asDiagonal() * R.transpose()};
}

Ref cylinder(double rho, double r, double l, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  const double m = rho * pi * r * r * l;
  const Eigen::Vector3d d(m * (3 * r * r + l * l) / 12, m * (3 * r * r + l * l) / 12, m * r * r / 2);
  return {m, p, R * d.asDiagonal() * R.transpose()};
}

Ref sphere(double rho, double r) {
  const double m = rho * 4.0 / 3.0 * pi * r * r * r;
  return {m, Eigen::Vector3d::Zero(), 0.4 * m * r * r * Eigen::Matrix3d::Identity()};
}

Ref combined(const std::vector<Ref>& parts) {
  Ref out{0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()};
  for (const auto& p : parts) {
    out.m += p.m;
    out.c += p.m * p.c;
  }
  out.c /= out.m;
  for (const auto& p : parts) {
    const Eigen::Vector3d d = p.c - out.c;
    out.I += p.I + p.m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return out;
}

// The mesh goes through the divergence-theorem sums and the scale map, the primitives through
// one formula and a rotation: a few hundred ulps of the largest term at most.
constexpr double kRelative = 1e-12;

void expect_entry(const InertialEntry& e, const Ref& ref) {
  SCOPED_TRACE(e.name);
  EXPECT_FALSE(e.problem) << *e.problem;
  EXPECT_NEAR(e.mass, ref.m, kRelative * ref.m);
  EXPECT_LE((e.com - ref.c).norm(), kRelative * std::max(1.0, ref.c.norm()));
  EXPECT_LE((e.inertia_com - ref.I).cwiseAbs().maxCoeff(), kRelative * ref.I.trace())
      << e.inertia_com << "\nvs\n" << ref.I;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class InertialFixFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("rigid_fix_{}_{}", ::testing::UnitTest::GetInstance()->current_test_info()->name(), ::getpid());
    fs::create_directories(dir_ / "parts" / "meshes");
    // a unit cube with a corner at the origin (its COM at (½, ½, ½)), outward faces
    write("parts/meshes/cube.obj",
          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
          "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
          "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  [[nodiscard]] InertialFixOptions with_package(InertialFixOptions o = {}) const {
    o.package_paths.emplace_back("parts", (dir_ / "parts").string());
    return o;
  }
  fs::path dir_;
};

// wrong inertials (a placeholder, an invalid one, a missing one), a link with no geometry, a
// massless frame, tab indentation, comments and a visual that must not count
constexpr const char* kRobot = R"(<?xml version="1.0"?>
<!-- a generated robot with wrong inertials -->
<robot name="r">
  <link name="base">
    <inertial>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision>
      <origin xyz="0.1 0 0.05" rpy="0 0 0.3"/>
      <geometry><box size="0.2 0.3 0.4"/></geometry>
    </collision>
    <visual><geometry><sphere radius="5"/></geometry></visual>
  </link>
  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
  <link name="arm">
	<!-- tab-indented; ixx > iyy + izz -->
	<inertial>
		<mass value="2"/>
		<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
	</inertial>
	<collision>
		<origin xyz="0 0 0.25" rpy="1.5707963267948966 0 0"/>
		<geometry><cylinder radius="0.05" length="0.5"/></geometry>
	</collision>
	<collision>
		<origin xyz="0.2 0 0"/>
		<geometry><mesh filename="package://parts/meshes/cube.obj" scale="0.1 0.2 0.3"/></geometry>
	</collision>
  </link>
  <link name="tip">
    <collision><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
  <link name="frame_only"/>
  <link name="sensor">
    <inertial><mass value="0.1"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="2e-5" iyz="0" izz="2.5e-5"/></inertial>
  </link>
</robot>
)";

std::vector<Ref> robot_expected(double rho) {
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d Rx = Eigen::AngleAxisd(pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  return {box(rho, {0.2, 0.3, 0.4}, Rz, {0.1, 0, 0.05}),
          combined({cylinder(rho, 0.05, 0.5, Rx, {0, 0, 0.25}),
                    box(rho, {0.1, 0.2, 0.3}, I3, Eigen::Vector3d(0.2, 0, 0) + Eigen::Vector3d(0.05, 0.1, 0.15))}),
          sphere(rho, 0.03)};
}

TEST_F(InertialFixFiles, UrdfWrongInertialsAreFixedAndPassTheCheck) {
  const fs::path model = write("robot.urdf", kRobot);
  const InertialFixResult r = fix_inertials_file(model.string(), with_package({.density = 2700}));
  ASSERT_TRUE(r.ok()) << fmt::format("{}", fmt::join(r.errors(), "\n"));
  ASSERT_EQ(r.links.size(), 5u);
  EXPECT_EQ(r.links[0].reason, "placeholder");
  EXPECT_EQ(r.links[1].reason, "invalid");
  EXPECT_EQ(r.links[2].reason, "missing");
  EXPECT_EQ(r.links[3].reason, "kept");  // no geometry, no inertial: a massless frame
  EXPECT_EQ(r.links[4].reason, "kept");  // no geometry: its inertial stays
  EXPECT_TRUE(r.warnings.empty());       // the density was given

  // `rigid inertia check` reads every inertial of the new file as valid, with the values of
  // the closed forms
  const auto entries = read_inertials(r.text, "fixed");
  ASSERT_EQ(entries.size(), 4u);  // base, arm, tip (inserted), sensor
  const auto expected = robot_expected(2700);
  for (int i = 0; i < 3; ++i) expect_entry(entries[i], expected[i]);
  EXPECT_FALSE(entries[3].problem);

  // every byte outside the inertials is the original's
  EXPECT_EQ(test::without_inertials(r.text), test::without_inertials(kRobot));
  // the inserted inertial has the indentation of its siblings
  EXPECT_NE(r.text.find("  <link name=\"tip\">\n    <inertial>\n      <origin"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("\t<inertial>\n\t\t<origin"), std::string::npos) << r.text;
}

TEST_F(InertialFixFiles, DensityIsAssumedWithAWarningAndMassesCanBeKept) {
  const fs::path model = write("robot.urdf", kRobot);
  const InertialFixResult assumed = fix_inertials_file(model.string(), with_package());
  ASSERT_EQ(assumed.warnings.size(), 1u);
  EXPECT_NE(assumed.warnings[0].find("1000 kg/m³ (water) assumed"), std::string::npos);
  expect_entry(read_inertials(assumed.text, "fixed")[2], robot_expected(1000)[2]);

  // --keep-mass: the stated 1 kg of base and 2 kg of arm, distributed by the geometry
  const InertialFixResult kept = fix_inertials_file(model.string(), with_package({.keep_mass = true}));
  ASSERT_TRUE(kept.ok());
  const auto entries = read_inertials(kept.text, "fixed");
  for (const auto& [i, mass] : {std::pair{0, 1.0}, std::pair{1, 2.0}}) {
    Ref ref = robot_expected(1000)[i];
    const double k = mass / ref.m;
    expect_entry(entries[i], {mass, ref.c, k * ref.I});
  }
}

TEST_F(InertialFixFiles, ImplausibleDensityIsNamed) {
  // 1 kg in a 0.1 m cube is 1000 kg/m³; 1000 kg in it is 10⁶ kg/m³
  const fs::path model = write("dense.urdf", R"(<robot name="d"><link name="l">
  <inertial><mass value="1000"/><inertia ixx="1.7" ixy="0" ixz="0" iyy="1.7" iyz="0" izz="1.7"/></inertial>
  <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
</link></robot>)");
  const InertialFixResult r = fix_inertials_file(model.string(), {.density = 1000});
  ASSERT_EQ(r.links.size(), 1u);
  EXPECT_EQ(r.links[0].reason, "implausible density");
  EXPECT_NE(r.links[0].detail.find("1e+06 kg/m³"), std::string::npos) << r.links[0].detail;
  // the old inertial was on a line of its own: so is the new one, on one line (MJCF style
  // would be one element; URDF's children follow the indentation)
  EXPECT_EQ(test::without_inertials(r.text), test::without_inertials(
      read_text(model)));
}

TEST_F(InertialFixFiles, EveryLinkThatCannotBeFixedIsNamed) {
  write("parts/meshes/huge.obj",
        "v 0 0 0\nv 1000 0 0\nv 1000 1000 0\nv 0 1000 0\nv 0 0 1000\nv 1000 0 1000\nv 1000 1000 1000\nv 0 1000 1000\n"
        "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
        "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
  const fs::path model = write("bad.urdf", R"(<robot name="bad">
  <link name="no_file">
    <collision><geometry><mesh filename="meshes/nowhere.stl"/></geometry></collision>
  </link>
  <link name="odd_shape">
    <collision><geometry><capsule radius="0.1" length="0.2"/></geometry></collision>
  </link>
  <link name="millimetres">
    <collision><geometry><mesh filename="package://parts/meshes/huge.obj"/></geometry></collision>
  </link>
  <link name="nothing">
    <inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <link name="unknown_package">
    <collision><geometry><mesh filename="package://other/m.stl"/></geometry></collision>
  </link>
  <link name="fine"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
</robot>
)");
  const InertialFixResult r = fix_inertials_file(model.string(), with_package({.density = 1000}));
  EXPECT_FALSE(r.ok());
  const auto errors = r.errors();
  ASSERT_EQ(errors.size(), 5u) << fmt::format("{}", fmt::join(errors, "\n"));
  const std::string file = model.string();
  EXPECT_NE(errors[0].find(file + ":2: link 'no_file': <collision> mesh (line 3): mesh file"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("nowhere.stl' does not exist"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find(":5: link 'odd_shape'"), std::string::npos) << errors[1];
  EXPECT_NE(errors[1].find("unknown geometry <capsule>; expected box, cylinder, sphere or mesh"), std::string::npos) << errors[1];
  EXPECT_NE(errors[2].find(":8: link 'millimetres'"), std::string::npos) << errors[2];
  EXPECT_NE(errors[2].find("is 1000 m long"), std::string::npos) << errors[2];
  EXPECT_NE(errors[2].find("plausibly millimetres"), std::string::npos) << errors[2];
  EXPECT_NE(errors[3].find(":11: link 'nothing': invalid inertial"), std::string::npos) << errors[3];
  EXPECT_NE(errors[3].find("no geometry"), std::string::npos) << errors[3];
  EXPECT_NE(errors[4].find("names package 'other', whose directory is not known; give it with `package_path = \"other=DIR\"`"),
            std::string::npos) << errors[4];
  EXPECT_TRUE(r.links[5].fixed.has_value());  // the others are still computed and listed
}

TEST_F(InertialFixFiles, SdfShapesIncludingCapsuleAndEllipsoid) {
  const fs::path model = write("m.sdf", R"(<?xml version="1.0"?>
<sdf version="1.9">
  <model name="m">
    <link name="body">
      <collision name="c1">
        <pose>0 0 0.1 0 0 0</pose>
        <geometry><capsule><radius>0.05</radius><length>0.2</length></capsule></geometry>
      </collision>
      <collision name="c2">
        <pose degrees="true">0.3 0 0 90 0 0</pose>
        <geometry><box><size>0.1 0.2 0.3</size></box></geometry>
      </collision>
      <collision name="c3">
        <geometry><ellipsoid><radii>0.1 0.2 0.05</radii></ellipsoid></geometry>
      </collision>
      <visual name="v"><geometry><sphere><radius>3</radius></sphere></geometry></visual>
    </link>
  </model>
</sdf>
)");
  const InertialFixResult r = fix_inertials_file(model.string(), {.density = 500});
  ASSERT_TRUE(r.ok()) << fmt::format("{}", fmt::join(r.errors(), "\n"));
  // capsule: cylinder + two hemispheres = cylinder + a sphere split at the ends; the
  // hemisphere's COM is 3r/8 from its flat face, its inertia about its own COM
  // 2/5 m r² − m (3r/8)² across the axis (parallel axis from the sphere's centre)
  const double rho = 500, r0 = 0.05, l = 0.2;
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Ref cyl = cylinder(rho, r0, l, I3, {0, 0, 0.1});
  const double mh = rho * 2.0 / 3.0 * pi * r0 * r0 * r0;
  const double across = 0.4 * mh * r0 * r0 - mh * std::pow(3 * r0 / 8, 2);
  const Eigen::Matrix3d Ih = Eigen::Vector3d(across, across, 0.4 * mh * r0 * r0).asDiagonal();
  const Ref top{mh, {0, 0, 0.1 + l / 2 + 3 * r0 / 8}, Ih};
  const Ref bottom{mh, {0, 0, 0.1 - l / 2 - 3 * r0 / 8}, Ih};
  const Eigen::Matrix3d Rx = Eigen::AngleAxisd(pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Ref b = box(rho, {0.1, 0.2, 0.3}, Rx, {0.3, 0, 0});
  // ellipsoid: m = 4/3 π abc ρ, I_xx = m (b² + c²)/5
  const double me = rho * 4.0 / 3.0 * pi * 0.1 * 0.2 * 0.05;
  const Ref e{me, Eigen::Vector3d::Zero(),
              Eigen::Vector3d(me * (0.04 + 0.0025) / 5, me * (0.01 + 0.0025) / 5, me * (0.01 + 0.04) / 5).asDiagonal()};
  const auto entries = read_inertials(r.text, "fixed");
  ASSERT_EQ(entries.size(), 1u);
  expect_entry(entries[0], combined({cyl, top, bottom, b, e}));
  EXPECT_EQ(test::without_inertials(r.text), test::without_inertials(
      read_text(model)));
}

// MJCF <include>s are followed (relative to the main file, as MuJoCo reads them): their bodies
// are fixed with the main file's defaults, reported at their own file and line, and the fixed
// model is one file with each include replaced by its file's elements; the included files are
// left as they are.
TEST_F(InertialFixFiles, MjcfIncludesAreFollowedAndWrittenInline) {
  const std::string defaults =
      "<mujoco>\n  <default>\n    <geom density=\"500\"/>\n  </default>\n</mujoco>\n";
  const std::string arm =
      "<mujoco>\n"
      "  <body name=\"arm\" pos=\"0 0 0.5\">\n"
      "    <inertial pos=\"0 0 0\" mass=\"2\" diaginertia=\"1 2 4\"/>\n"
      "    <geom type=\"box\" size=\"0.1 0.2 0.3\"/>\n"
      "  </body>\n"
      "</mujoco>\n";
  write("parts/defaults.xml", defaults);
  write("parts/arm.xml", arm);
  const fs::path model = write("main.xml",
                               "<mujoco model=\"m\">\n"
                               "  <include file=\"parts/defaults.xml\"/>\n"
                               "  <worldbody>\n"
                               "    <body name=\"base\">\n"
                               "      <geom type=\"sphere\" size=\"0.1\"/>\n"
                               "      <include file=\"parts/arm.xml\"/>\n"
                               "    </body>\n"
                               "  </worldbody>\n"
                               "</mujoco>\n");
  const InertialFixResult r = fix_inertials_file(model.string());
  ASSERT_TRUE(r.ok()) << fmt::format("{}", fmt::join(r.errors(), "\n"));
  ASSERT_EQ(r.links.size(), 2u);
  EXPECT_EQ(r.links[0].file, model.string());
  EXPECT_EQ(r.links[0].line, 4);
  EXPECT_EQ(r.links[0].reason, "missing");
  EXPECT_EQ(r.links[1].file, (dir_ / "parts" / "arm.xml").string());
  EXPECT_EQ(r.links[1].line, 2);
  EXPECT_EQ(r.links[1].reason, "invalid");  // 1 + 2 < 4
  ASSERT_TRUE(r.links[1].old.has_value());
  EXPECT_EQ(r.links[1].old->file, r.links[1].file);
  EXPECT_EQ(r.links[1].old->line, 3);
  // the included default's density 500 kg/m³; MJCF sizes are half sizes
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const std::vector<Ref> expected = {sphere(500, 0.1), box(500, {0.2, 0.4, 0.6}, I3, {0, 0, 0})};
  // one self-contained file: the includes' elements in their place, the inertials fixed
  EXPECT_EQ(r.text.find("<include"), std::string::npos) << r.text;
  EXPECT_EQ(test::without_inertials(r.text),
            "<mujoco model=\"m\">\n"
            "  <default>\n    <geom density=\"500\"/>\n  </default>\n"
            "  <worldbody>\n"
            "    <body name=\"base\">\n"
            "      <geom type=\"sphere\" size=\"0.1\"/>\n"
            "      <body name=\"arm\" pos=\"0 0 0.5\">\n"
            "    <geom type=\"box\" size=\"0.1 0.2 0.3\"/>\n"
            "  </body>\n"
            "    </body>\n"
            "  </worldbody>\n"
            "</mujoco>\n");
  const auto entries = read_inertials(r.text, "fixed.xml");
  ASSERT_EQ(entries.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) expect_entry(entries[i], expected[i]);
  EXPECT_EQ(read_text(dir_ / "parts" / "arm.xml"), arm);
  EXPECT_EQ(read_text(dir_ / "parts" / "defaults.xml"), defaults);
  const std::string warnings = fmt::format("{}", fmt::join(r.warnings, "\n"));
  EXPECT_NE(warnings.find(model.string() + ":6: <include file=\"parts/arm.xml\">: the fixed model is "
                          "written as one file"), std::string::npos) << warnings;
  // an error of an included body names its file; a missing include is refused naming it
  write("parts/arm.xml", "<mujoco>\n  <body name=\"arm\">\n    <geom type=\"hfield\" size=\"1 1 1\"/>\n  </body>\n</mujoco>\n");
  const auto errors = fix_inertials_file(model.string()).errors();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find((dir_ / "parts" / "arm.xml").string() + ":2: body 'arm': geom (line 3)"),
            std::string::npos) << errors[0];
  fs::remove(dir_ / "parts" / "arm.xml");
  EXPECT_RIGID_ERROR((void)fix_inertials_file(model.string()),
                     model.string() + ":6: <include file=\"parts/arm.xml\">: '" +
                         (dir_ / "parts" / "arm.xml").string() + "' does not exist");
  // a FIFO is refused before it is opened (opening it would wait for a writer)
  const fs::path fifo = dir_ / "fifo.xml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_RIGID_ERROR((void)fix_inertials_file(fifo.string()), "is not a regular file");
}

TEST(InertialFix, UnknownOnlyAndMalformedAreRefused) {
  EXPECT_RIGID_ERROR((void)fix_inertials("<robot name=\"r\"><link name=\"a\"/></robot>", "r.urdf",
                                         {.only = {"b"}}),
                     "no link named 'b'; the file has: a");
  EXPECT_RIGID_ERROR((void)fix_inertials("<robot", "r.urdf"), "r.urdf:1: malformed XML");
}

TEST(InertialFix, MjcfGeomProblemsNameTheBodyAndLine) {
  const InertialFixResult r = fix_inertials(R"(<mujoco>
  <worldbody>
    <body name="b">
      <geom type="hfield" size="1 1 1"/>
      <geom type="sphere" fromto="0 0 0 1 0 0" size="0.1"/>
      <geom type="box" size="0.1 0.1 0.1" class="nope"/>
      <geom type="capsule" size="0.1 0.2" quat="1 0 0 0" euler="0 0 1"/>
    </body>
  </worldbody>
</mujoco>)", "m.xml");
  const auto errors = r.errors();
  ASSERT_EQ(errors.size(), 4u) << fmt::format("{}", fmt::join(errors, "\n"));
  EXPECT_NE(errors[0].find("m.xml:3: body 'b': geom (line 4): type=\"hfield\" has no volume"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find("fromto works with capsule, cylinder, box and ellipsoid geoms, not type=\"sphere\""), std::string::npos) << errors[1];
  EXPECT_NE(errors[2].find("geom (line 6): unknown default class 'nope'"), std::string::npos) << errors[2];
  EXPECT_NE(errors[3].find("more than one orientation attribute"), std::string::npos) << errors[3];
}

}  // namespace
}  // namespace rigid::io
