#include "rigid/io/inertial_xml.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::io {
namespace {

using test::ulps;

// A body with no symmetry, in a rotated frame, with its COM off the origin.
MassProperties generic_body() {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  return mass::solid_box_with_mass(2.5, 0.3, 0.5, 0.7).transformed(R, Eigen::Vector3d(0.1, -0.2, 0.3));
}

void expect_same(const MassProperties& a, const MassProperties& b, double tol) {
  EXPECT_NEAR(a.mass(), b.mass(), ulps(1, a.mass()));
  EXPECT_TRUE((a.com() - b.com()).cwiseAbs().maxCoeff() <= tol) << a.com().transpose();
  EXPECT_TRUE((a.inertia_com() - b.inertia_com()).cwiseAbs().maxCoeff() <= tol * a.inertia_com().trace())
      << a.inertia_com() << "\nvs\n" << b.inertia_com();
}

TEST(InertialXml, RoundTripEveryFormatAndFrame) {
  const MassProperties mp = generic_body();
  for (const auto format : {InertialFormat::urdf, InertialFormat::mjcf, InertialFormat::sdf}) {
    for (const bool principal : {false, true}) {
      SCOPED_TRACE(fmt::format("{} principal={}", to_string(format), principal));
      const std::string doc = write_inertial_document(mp, format, {.name = "link1", .principal = principal});
      const auto entries = read_inertials(doc, "test");
      ASSERT_EQ(entries.size(), 1u);
      EXPECT_EQ(entries[0].name, "link1");
      EXPECT_FALSE(entries[0].problem.has_value()) << *entries[0].problem;
      // the body frame is written with shortest round-trip doubles: exact. The principal
      // frame goes through an eigen-decomposition and rpy/quaternion: a few hundred ε.
      expect_same(entries[0].mass_properties(), mp, principal ? ulps(512) : 0.0);
      EXPECT_EQ(detect_inertial_format(doc, "test"), format);
    }
  }
}

TEST(InertialXml, UrdfOffDiagonalsAreTensorElements) {
  // two unit masses at (1, 1, 0) and (−1, −1, 0): ∫xy dm = 2, so the tensor's ixy = −2.
  Eigen::Matrix3Xd pts(3, 2);
  pts << 1, -1, 1, -1, 0, 0;
  const double masses[] = {1.0, 1.0};
  const auto mp = mass::point_masses(masses, pts);
  const std::string urdf = write_inertial_document(mp, InertialFormat::urdf);
  EXPECT_NE(urdf.find("ixx=\"2\" ixy=\"-2\" ixz=\"0\" iyy=\"2\" iyz=\"0\" izz=\"4\""), std::string::npos)
      << urdf;
}

TEST(InertialXml, MjcfFullInertiaOrder) {
  Eigen::Matrix3d I;
  I << 4, -0.1, -0.2, -0.1, 5, -0.3, -0.2, -0.3, 6;
  const MassProperties mp(1.0, Eigen::Vector3d(1, 2, 3), I);
  const std::string mjcf = write_inertial_document(mp, InertialFormat::mjcf);
  EXPECT_NE(mjcf.find("pos=\"1 2 3\" mass=\"1\" fullinertia=\"4 5 6 -0.1 -0.2 -0.3\""),
            std::string::npos)
      << mjcf;
}

TEST(InertialXml, ReadersApplyTheInertialRotation) {
  // 90° yaw swaps x and y: diag(1, 2, 3) in the inertial frame is diag(2, 1, 3) in the link.
  const std::string urdf = R"(<robot name="r"><link name="a"><inertial>
      <origin xyz="1 2 3" rpy="0 0 1.5707963267948966"/><mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/></inertial></link></robot>)";
  const auto u = read_inertials(urdf, "a.urdf");
  ASSERT_EQ(u.size(), 1u);
  EXPECT_TRUE(u[0].inertia_com.isApprox(Eigen::Vector3d(2, 1, 3).asDiagonal().toDenseMatrix(), ulps(8)))
      << u[0].inertia_com;
  EXPECT_EQ(u[0].com, Eigen::Vector3d(1, 2, 3));
  // MJCF quat (w x y z) of the same yaw
  const std::string mjcf = R"(<mujoco><worldbody><body name="b">
      <inertial pos="0 0 0" mass="1" quat="0.7071067811865476 0 0 0.7071067811865476" diaginertia="1 2 3"/>
      </body></worldbody></mujoco>)";
  const auto m = read_inertials(mjcf, "b.xml");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_TRUE(m[0].inertia_com.isApprox(Eigen::Vector3d(2, 1, 3).asDiagonal().toDenseMatrix(), ulps(8)));
  // SDF pose roll 90° swaps y and z: diag(1, 3, 2)
  const std::string sdf = R"(<sdf version="1.7"><model name="m"><link name="c"><inertial>
      <pose>0 0 0 1.5707963267948966 0 0</pose><mass>1</mass>
      <inertia><ixx>1</ixx><iyy>2</iyy><izz>3</izz></inertia></inertial></link></model></sdf>)";
  const auto s = read_inertials(sdf, "c.sdf");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_TRUE(s[0].inertia_com.isApprox(Eigen::Vector3d(1, 3, 2).asDiagonal().toDenseMatrix(), ulps(8)));
}

TEST(InertialXml, RpyRoundTripIncludingGimbalLock) {
  for (const Eigen::Vector3d& rpy : {Eigen::Vector3d(0.1, -0.4, 2.9), Eigen::Vector3d(-3.0, 1.2, -0.3),
                                    Eigen::Vector3d(0.0, std::numbers::pi / 2, 0.7)}) {
    const Eigen::Matrix3d R = rotation_from_rpy(rpy);
    EXPECT_TRUE(rotation_from_rpy(rpy_from_rotation(R)).isApprox(R, ulps(16)));
  }
  // R = Rz Ry Rx: a pure yaw about z, checked against the textbook matrix
  const Eigen::Matrix3d Rz = rotation_from_rpy(Eigen::Vector3d(0, 0, 0.3));
  EXPECT_NEAR(Rz(1, 0), std::sin(0.3), ulps(2));
}

TEST(InertialXml, CheckReportsEachInvalidInertialWithLine) {
  const std::string urdf =
      "<robot name=\"r\">\n"
      "  <link name=\"good\"><inertial><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n"
      "  <link name=\"bad\">\n"
      "    <inertial><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"2\" iyz=\"0\" izz=\"4\"/></inertial></link>\n"
      "  <link name=\"typo\"><inertial><mass value=\"1x\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n"
      "  <link name=\"nomass\"><inertial><mass value=\"0\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n"
      "</robot>\n";
  const auto e = read_inertials(urdf, "r.urdf");
  ASSERT_EQ(e.size(), 4u);
  EXPECT_FALSE(e[0].problem.has_value());
  EXPECT_EQ(e[1].name, "bad");
  EXPECT_EQ(e[1].line, 4);
  ASSERT_TRUE(e[1].problem.has_value());
  EXPECT_THAT(*e[1].problem, ::testing::HasSubstr("violate I₁ + I₂ ≥ I₃ by 1 kg·m²"));
  EXPECT_THAT(*e[2].problem, ::testing::HasSubstr("<mass> attribute 'value': expected a number, got '1x'"));
  EXPECT_THAT(*e[3].problem, ::testing::HasSubstr("mass must be positive and finite, got 0 kg"));
  EXPECT_RIGID_ERROR((void)e[1].mass_properties(), "inertial of 'bad' (line 4) is not usable");
}

TEST(InertialXml, MjcfAndSdfProblems) {
  const std::string mjcf = R"(<mujoco><worldbody><body name="b">
      <inertial pos="0 0 0" mass="1" euler="0 0 90" diaginertia="1 1 1"/>
      <body name="c"><inertial pos="0 0" mass="1" diaginertia="1 1 1"/></body>
      <body name="d"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1" fullinertia="1 1 1 0 0 0"/></body>
      </body></worldbody></mujoco>)";
  const auto m = read_inertials(mjcf, "m.xml");
  ASSERT_EQ(m.size(), 3u);
  EXPECT_THAT(*m[0].problem, ::testing::HasSubstr("orientation attribute 'euler' is not supported"));
  EXPECT_EQ(m[1].name, "c");
  EXPECT_THAT(*m[1].problem, ::testing::HasSubstr("'pos': expected 3 numbers, got 2"));
  EXPECT_THAT(*m[2].problem, ::testing::HasSubstr("exactly one of 'diaginertia' and 'fullinertia'"));
  // SDF defaults: no <inertia> gives the unit tensor, no <mass> gives 1 kg
  const auto s = read_inertials("<sdf><model><link name=\"l\"><inertial/></link></model></sdf>", "s.sdf");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].mass, 1.0);
  EXPECT_EQ(s[0].inertia_com, Eigen::Matrix3d::Identity());
}

TEST(InertialXml, MalformedAndUnknownDocuments) {
  EXPECT_RIGID_ERROR((void)read_inertials("<robot>\n<link name=\"a\">\n</robot>", "bad.urdf"),
                     "bad.urdf:2: malformed XML");
  EXPECT_RIGID_ERROR((void)read_inertials("<model/>", "x.xml"),
                     "x.xml:1: unknown root element <model>; expected <robot> (URDF), <mujoco> "
                     "(MJCF) or <sdf> (SDF)");
  EXPECT_RIGID_ERROR((void)read_inertials_file("/nonexistent/file.urdf"),
                     "'/nonexistent/file.urdf' does not exist");
  EXPECT_RIGID_ERROR((void)write_inertial_document(generic_body(), InertialFormat::urdf, {.name = "a<b"}),
                     "name must be non-empty and free of XML special characters");
}

// The message of the rigid::Error that `f` throws ("" if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Every reader refuses malformed XML at the file and line, in plain words: never tinyxml2's
// own error text (its error names, "ErrorID", "Line number").
TEST(InertialXml, MalformedXmlIsRefusedInPlainWords) {
  struct Case {
    const char* xml;
    const char* expected;  // the whole message
  };
  const Case cases[] = {
      // truncated: the file ends inside an element, named with its line
      {"<mujoco>\n  <worldbody>\n    <body name=\"b\">\n",
       "m.xml:3: malformed XML: the file ends inside the element <body> of line 3: it is cut "
       "short, or </body> is missing"},
      {"<robot name=\"r\">\n  <link name=\"a\">\n    <inertial>\n      <mass valu",
       "m.xml:4: malformed XML: the file ends inside the element <inertial> of line 3, in the "
       "middle of the start tag <mass: it is cut short, or </inertial> is missing"},
      {"<robot", "m.xml:1: malformed XML: the file ends in the middle of the start tag <robot: it "
                 "is cut short"},
      // an element not closed before its parent's end tag
      {"<robot>\n<link name=\"a\">\n</robot>\n",
       "m.xml:2: malformed XML: an end tag does not match its start tag: </robot> on line 3 comes "
       "while <link> of line 2 is open (expected </link> first, or <link .../> for an element "
       "without content)"},
      {"hello", "m.xml:1: malformed XML: text where a tag was expected"},
      {"<robot/>\ntrailing words", "m.xml:2: malformed XML: text where a tag was expected"},
      {"<robot>\n  <link name=a/>\n</robot>", "m.xml:2: malformed XML: an attribute is badly formed"},
      {"<robot>\n  <link name=\"a\"\n</robot>", "m.xml:2: malformed XML: a tag is badly formed or not closed"},
      {"<robot>\n<!-- a comment\n</robot>\n", "m.xml:2: malformed XML: a comment is not closed (expected -->)"},
      {"", "m.xml:1: malformed XML: the file is empty"},
      // a name is quoted escaped: a control character and a byte that is not UTF-8
      {"<ro\x1b\xff" "bot", "m.xml:1: malformed XML: the file ends in the middle of the start tag "
                         "<ro\\x1b\\xffbot: it is cut short"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.xml);
    const std::string inertials = error_of([&] { (void)read_inertials(c.xml, "m.xml"); });
    EXPECT_THAT(inertials, ::testing::HasSubstr(c.expected));
    for (const char* raw : {"XML_ERROR", "ErrorID", "Line number", "Error="}) {
      EXPECT_EQ(inertials.find(raw), std::string::npos) << inertials;
    }
    // the same words from the fix and detect readers
    EXPECT_EQ(error_of([&] { (void)detect_inertial_format(c.xml, "m.xml"); }), inertials);
  }
}

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rigid_inertial_xml_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "parts");
  return dir;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// MJCF <include file=...> is followed as MuJoCo follows it (relative to the main file's
// folder): the included inertials are read, each with its own file and line.
TEST(InertialXml, MjcfIncludesAreFollowedWithTheirFileAndLine) {
  const fs::path dir = scratch("include");
  write(dir / "main.xml",
        "<mujoco>\n"
        "  <worldbody>\n"
        "    <body name=\"base\">\n"
        "      <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/>\n"
        "      <include file=\"parts/arm.xml\"/>\n"
        "    </body>\n"
        "  </worldbody>\n"
        "</mujoco>\n");
  write(dir / "parts" / "arm.xml",
        "<mujoco>\n"
        "  <body name=\"arm\">\n"
        "    <inertial pos=\"0 0 0\" mass=\"2\" diaginertia=\"1 2 4\"/>\n"
        "  </body>\n"
        "</mujoco>\n");
  const std::string main = (dir / "main.xml").string(), arm = (dir / "parts" / "arm.xml").string();
  const auto e = read_inertials_file(main);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].file, main);
  EXPECT_EQ(e[0].line, 4);
  EXPECT_FALSE(e[0].problem.has_value());
  EXPECT_EQ(e[1].name, "arm");
  EXPECT_EQ(e[1].file, arm);
  EXPECT_EQ(e[1].line, 3);
  ASSERT_TRUE(e[1].problem.has_value());
  // 1 + 2 < 4: the triangle inequality fails by 1 kg·m²
  EXPECT_THAT(*e[1].problem, ::testing::HasSubstr("violate I₁ + I₂ ≥ I₃ by 1 kg·m²"));
  // an included file that does not parse: its own file and line
  write(dir / "parts" / "arm.xml", "<mujoco>\n  <body name=\"arm\">\n");
  EXPECT_RIGID_ERROR((void)read_inertials_file(main),
                     arm + ":2: malformed XML: the file ends inside the element <body> of line 2");
  // a missing one: the include's place, naming the file
  fs::remove(dir / "parts" / "arm.xml");
  EXPECT_RIGID_ERROR((void)read_inertials_file(main),
                     main + ":5: <include file=\"parts/arm.xml\">: '" + arm + "' does not exist");
  fs::remove_all(dir);
}

// A FIFO (or device) is refused before it is opened: opening a FIFO would wait for a writer.
TEST(InertialXml, FifoIsRefusedWithoutOpeningIt) {
  const fs::path dir = scratch("fifo");
  const fs::path fifo = dir / "model.urdf";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // the message built with fmt: "'" + std::string trips GCC 12's -Wrestrict at -O3
  const std::string expected =
      fmt::format("'{}' is not a regular file (a directory, FIFO or device)", fifo.string());
  EXPECT_RIGID_ERROR((void)read_inertials_file(fifo.string()), expected);
  EXPECT_RIGID_ERROR((void)read_inertials_file(dir.string()), "is not a regular file");
  fs::remove_all(dir);
}

// a placed shape written in its own frame (the given rotation) instead of an eigen-decomposition
TEST(InertialXml, GivenInertialFrameWritesTheGivenRpyAndReadsBack) {
  const Eigen::Vector3d rpy(0.1, 0.2, 0.3);
  const Eigen::Matrix3d R = rotation_from_rpy(rpy);
  const MassProperties own = mass::solid_cylinder_with_mass(2.0, 0.05, 0.4);
  const MassProperties placed = own.transformed(R, Eigen::Vector3d(0.1, 0, 0));
  for (const auto format : {InertialFormat::urdf, InertialFormat::sdf, InertialFormat::mjcf}) {
    SCOPED_TRACE(to_string(format));
    const std::string doc = write_inertial_document(placed, format, {.name = "l", .principal = true}, R);
    if (format != InertialFormat::mjcf) {
      // the rpy of the file is the given one to the round-off of R → quaternion → rpy (a few ε)
      Eigen::Vector3d got, xyz;
      if (format == InertialFormat::urdf) {
        const auto at = doc.find("rpy=\"");
        ASSERT_NE(at, std::string::npos) << doc;
        ASSERT_EQ(std::sscanf(doc.c_str() + at + 5, "%lf %lf %lf", &got(0), &got(1), &got(2)), 3);
      } else {
        const auto at = doc.find("<pose>");
        ASSERT_NE(at, std::string::npos) << doc;
        ASSERT_EQ(std::sscanf(doc.c_str() + at + 6, "%lf %lf %lf %lf %lf %lf", &xyz(0), &xyz(1), &xyz(2),
                              &got(0), &got(1), &got(2)), 6);
      }
      EXPECT_TRUE((got - rpy).cwiseAbs().maxCoeff() <= ulps(16)) << doc;
    }
    const auto entries = read_inertials(doc, "test");
    ASSERT_EQ(entries.size(), 1u);
    // in the shape's own frame the tensor read back is the diagonal one (m r²/2 about z)
    const Eigen::Matrix3d I_own = R.transpose() * entries[0].inertia_com * R;
    EXPECT_TRUE((I_own - own.inertia_com()).cwiseAbs().maxCoeff() <= ulps(64, own.inertia_com().trace())) << I_own;
    expect_same(entries[0].mass_properties(), placed, ulps(64));
  }
  // a frame that does not diagonalise the tensor is refused
  const MassProperties box = mass::solid_box_with_mass(1.0, 0.1, 0.2, 0.3);
  EXPECT_RIGID_ERROR((void)write_inertial_document(box, InertialFormat::urdf, {.name = "l", .principal = true}, R),
                     "the given inertial frame is not a principal frame");
}

}  // namespace
}  // namespace rigid::io
