// read_robot_model: URDF and MJCF kinematic trees. Expected values come from the files' own
// numbers with rotations built here independently (Eigen's AngleAxis products), and for
// MuJoCo's models from MuJoCo 2.2's own compiler (libmujoco loads the same file).
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "rigid/io/robot_model.hpp"
#include "support/mujoco_model.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;
using Eigen::AngleAxisd;
using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kPi = std::numbers::pi;
const fs::path kModels = "/usr/share/mujoco/model";

// the 1-based line of the first occurrence of `needle` (the messages' line numbers)
int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

std::string at(const std::string& file, const std::string& text, const std::string& needle) {
  return fmt::format("{}:{}: ", file, line_of(text, needle));
}

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / fmt::format("rigid_robot_{}_{}", name, ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const RobotLink& link_named(const RobotModel& m, const std::string& name) {
  for (const auto& l : m.links) {
    if (l.name == name) return l;
  }
  ADD_FAILURE() << "no link " << name;
  return m.links.front();
}

// ---------------------------------------------------------------------------------------------
// URDF

const std::string kArm = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="tip"/>
  <link name="base"/>
  <link name="upper">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 1.5707963267948966"/>
      <mass value="2"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>
    </inertial>
  </link>
  <link name="slider"/>
  <link name="wheel"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/>
    <origin xyz="0.1 0.2 0.3" rpy="0.3 -0.4 0.5"/>
    <axis xyz="0 3 4"/>
    <dynamics damping="0.7" friction="2"/>
  </joint>
  <joint name="rail" type="prismatic"><parent link="base"/><child link="slider"/></joint>
  <joint name="weld" type="fixed">
    <parent link="upper"/><child link="tip"/><origin xyz="0 0 1"/>
  </joint>
  <joint name="spin" type="continuous">
    <parent link="upper"/><child link="wheel"/><axis xyz="0 0 -2"/>
  </joint>
</robot>
)";

TEST(RobotModelUrdf, TreeOrderPlacementsAndJoints) {
  const RobotModel m = read_robot_model(kArm, "arm.urdf");
  EXPECT_EQ(m.format, InertialFormat::urdf);
  EXPECT_EQ(m.name, "arm");
  // depth first from the root, children in the order of their joints in the file
  ASSERT_EQ(m.links.size(), 5u);
  const std::vector<std::string> order = {"base", "upper", "tip", "wheel", "slider"};
  const std::vector<int> parents = {-1, 0, 1, 1, 0};
  for (std::size_t i = 0; i < order.size(); ++i) {
    EXPECT_EQ(m.links[i].name, order[i]);
    EXPECT_EQ(m.links[i].parent, parents[i]) << order[i];
  }
  EXPECT_EQ(m.dof(), 3u);
  EXPECT_EQ(m.coordinate_names(), (std::vector<std::string>{"shoulder", "spin", "rail"}));
  EXPECT_EQ(m.links[1].line, line_of(kArm, "<link name=\"upper\">"));

  // the joint origin is the child's placement: R = Rz(yaw) Ry(pitch) Rx(roll), composed here
  // with Eigen's AngleAxis; both sides round a few times: 8 ε on unit entries
  const RobotLink& upper = m.links[1];
  EXPECT_EQ(upper.position, Vector3d(0.1, 0.2, 0.3));
  const Matrix3d R = (AngleAxisd(0.5, Vector3d::UnitZ()) * AngleAxisd(-0.4, Vector3d::UnitY()) *
                      AngleAxisd(0.3, Vector3d::UnitX()))
                         .toRotationMatrix();
  EXPECT_LE((upper.rotation - R).cwiseAbs().maxCoeff(), test::ulps(8, 1.0));
  ASSERT_EQ(upper.joints.size(), 1u);
  const RobotJoint& shoulder = upper.joints[0];
  EXPECT_EQ(shoulder.type, RobotJointType::kHinge);
  // (0 3 4)/5 normalised: one division each, within an ulp
  EXPECT_LE((shoulder.axis - Vector3d(0, 0.6, 0.8)).cwiseAbs().maxCoeff(), test::ulps(1, 1.0));
  EXPECT_EQ(shoulder.anchor, Vector3d::Zero());
  EXPECT_EQ(shoulder.damping, 0.7);  // friction="2" is Coulomb friction, not read
  EXPECT_EQ(shoulder.stiffness, 0.0);
  EXPECT_EQ(shoulder.ref, 0.0);

  // the inertial's rpy is applied: Rz(π/2) diag(.1 .2 .3) Rz(π/2)ᵀ = diag(.2 .1 .3); cos(π/2)
  // is 6e-17, not 0: entries within a few ε of the moments
  EXPECT_EQ(upper.mass, 2.0);
  EXPECT_EQ(upper.com, Vector3d(0, 0, 0.1));
  EXPECT_LE((upper.inertia_com - Vector3d(0.2, 0.1, 0.3).asDiagonal().toDenseMatrix())
                .cwiseAbs()
                .maxCoeff(),
            test::ulps(4, 0.3));

  const RobotLink& tip = link_named(m, "tip");
  EXPECT_TRUE(tip.joints.empty());  // fixed: welded
  EXPECT_EQ(tip.position, Vector3d(0, 0, 1));
  EXPECT_EQ(tip.mass, 0.0);  // no <inertial>
  const RobotLink& wheel = link_named(m, "wheel");
  ASSERT_EQ(wheel.joints.size(), 1u);
  EXPECT_EQ(wheel.joints[0].type, RobotJointType::kHinge);  // continuous
  EXPECT_EQ(wheel.joints[0].axis, Vector3d(0, 0, -1));
  const RobotLink& slider = link_named(m, "slider");
  ASSERT_EQ(slider.joints.size(), 1u);
  EXPECT_EQ(slider.joints[0].type, RobotJointType::kSlide);
  EXPECT_EQ(slider.joints[0].axis, Vector3d::UnitX());  // URDF's default axis
  EXPECT_EQ(slider.rotation, Matrix3d::Identity());
  EXPECT_EQ(m.gravity, Vector3d(0, 0, -9.81));
}

// kArm with `from` replaced by `to` (once)
std::string arm_with(const std::string& from, const std::string& to) {
  std::string s = kArm;
  const auto i = s.find(from);
  EXPECT_NE(i, std::string::npos) << from;
  return s.replace(i, from.size(), to);
}

TEST(RobotModelUrdf, RefusesUnsupportedJoints) {
  const std::string mimic = arm_with("<dynamics damping=\"0.7\" friction=\"2\"/>",
                                     "<mimic joint=\"spin\" multiplier=\"2\"/>");
  EXPECT_RIGID_ERROR((void)read_robot_model(mimic, "a.urdf"), at("a.urdf", mimic, "<mimic"));
  EXPECT_RIGID_ERROR((void)read_robot_model(mimic, "a.urdf"),
                     "a mimic joint is a constraint between coordinates, not yet supported");
  // a floating joint is a free joint only from the root link (the world's stand-in): from
  // 'base' it is read, its child a root of its own; from 'upper' refused
  const std::string floating = arm_with("type=\"prismatic\"", "type=\"floating\"");
  const RobotModel free_rail = read_robot_model(floating, "a.urdf");
  const RobotLink& slider = link_named(free_rail, "slider");
  EXPECT_EQ(slider.parent, -1);
  ASSERT_EQ(slider.joints.size(), 1u);
  EXPECT_EQ(slider.joints[0].type, RobotJointType::kFree);
  EXPECT_EQ(free_rail.nq(), 9u);
  const RobotModel pinned = read_robot_model(floating, "a.urdf", {.pin_free_root = true});
  EXPECT_TRUE(link_named(pinned, "slider").joints.empty());
  const std::string deep = arm_with("type=\"continuous\"", "type=\"floating\"");
  EXPECT_RIGID_ERROR((void)read_robot_model(deep, "a.urdf"),
                     at("a.urdf", deep, "<joint name=\"spin\"") + "joint 'spin'");
  EXPECT_RIGID_ERROR((void)read_robot_model(deep, "a.urdf"),
                     "a floating joint is read as a free joint only from the root link 'base'");
  const std::string planar = arm_with("type=\"prismatic\"", "type=\"planar\"");
  EXPECT_RIGID_ERROR((void)read_robot_model(planar, "a.urdf"),
                     at("a.urdf", planar, "<joint name=\"rail\"") +
                         "joint 'rail' type=\"planar\": "
                         "planar joints are not supported");
  const std::string odd = arm_with("type=\"prismatic\"", "type=\"screw\"");
  EXPECT_RIGID_ERROR((void)read_robot_model(odd, "a.urdf"),
                     "expected revolute, continuous, prismatic, fixed or floating");
}

TEST(RobotModelUrdf, RefusesWhatIsNotOneTree) {
  // two roots: the link "extra" is no joint's child
  const std::string two =
      arm_with("<link name=\"wheel\"/>", "<link name=\"wheel\"/><link name=\"extra\"/>");
  EXPECT_RIGID_ERROR((void)read_robot_model(two, "a.urdf"),
                     "a.urdf:2: 2 root links (base, extra): expected one link");
  // a loop: base becomes the child of a joint from the wheel, no link is left as root
  const std::string loop = arm_with("</robot>",
                                    "<joint name=\"back\" type=\"fixed\"><parent "
                                    "link=\"wheel\"/><child link=\"base\"/></joint></robot>");
  EXPECT_RIGID_ERROR((void)read_robot_model(loop, "a.urdf"),
                     "a.urdf:2: every link is the child of a joint: the joints form a loop");
  // a loop beside the tree: the root is found, but two links are cut off from it
  const std::string side = arm_with(
      "</robot>",
      "<link name=\"p\"/><link name=\"q\"/>"
      "<joint name=\"pq\" type=\"fixed\"><parent link=\"p\"/><child link=\"q\"/></joint>"
      "<joint name=\"qp\" type=\"fixed\"><parent link=\"q\"/><child link=\"p\"/></joint></robot>");
  EXPECT_RIGID_ERROR((void)read_robot_model(side, "a.urdf"),
                     "links p, q are not reachable from the root link 'base'");
  const std::string unknown = arm_with("<parent link=\"base\"/><child link=\"slider\"/>",
                                       "<parent link=\"nope\"/><child link=\"slider\"/>");
  EXPECT_RIGID_ERROR((void)read_robot_model(unknown, "a.urdf"),
                     at("a.urdf", unknown, "<parent link=\"nope\"") +
                         "joint 'rail': parent link 'nope' does not exist");
  const std::string unknown_child = arm_with("<child link=\"slider\"/>", "<child link=\"slidr\"/>");
  EXPECT_RIGID_ERROR((void)read_robot_model(unknown_child, "a.urdf"),
                     "child link 'slidr' does not exist");
  const std::string twice = arm_with("<child link=\"slider\"/>", "<child link=\"wheel\"/>");
  EXPECT_RIGID_ERROR(
      (void)read_robot_model(twice, "a.urdf"),
      at("a.urdf", twice, "<joint name=\"spin\"") + "link 'wheel' is the child of joint 'rail'");
  const std::string dup = arm_with("<link name=\"slider\"/>", "<link name=\"tip\"/>");
  EXPECT_RIGID_ERROR((void)read_robot_model(dup, "a.urdf"),
                     "link 'tip' is defined twice (first at line 3)");
}

TEST(RobotModelUrdf, RefusesBadNumbersAndInertials) {
  const std::string bad = arm_with("xyz=\"0.1 0.2 0.3\"", "xyz=\"0.1 0.2 zero\"");
  EXPECT_RIGID_ERROR((void)read_robot_model(bad, "a.urdf"),
                     at("a.urdf", bad, "<origin xyz=\"0.1 0.2 zero\"") +
                         "<origin> attribute 'xyz': expected a finite number, got 'zero'");
  const std::string two = arm_with("xyz=\"0.1 0.2 0.3\"", "xyz=\"0.1 0.2\"");
  EXPECT_RIGID_ERROR((void)read_robot_model(two, "a.urdf"), "expected 3 numbers, got 2");
  const std::string zero_axis = arm_with("<axis xyz=\"0 3 4\"/>", "<axis xyz=\"0 0 0\"/>");
  EXPECT_RIGID_ERROR(
      (void)read_robot_model(zero_axis, "a.urdf"),
      at("a.urdf", zero_axis, "<axis xyz=\"0 0 0\"") + "<axis> axis \"0 0 0\" has no direction");
  const std::string damping = arm_with("damping=\"0.7\"", "damping=\"-1\"");
  EXPECT_RIGID_ERROR((void)read_robot_model(damping, "a.urdf"),
                     "joint 'shoulder': damping -1 is negative");
  // 0.1 + 0.2 < 0.5: no body has these principal moments
  const std::string inertia = arm_with("izz=\"0.3\"", "izz=\"0.5\"");
  EXPECT_RIGID_ERROR((void)read_robot_model(inertia, "a.urdf"),
                     at("a.urdf", inertia, "<inertial>") +
                         "link 'upper': the inertial is not usable: principal moments");
  EXPECT_RIGID_ERROR((void)read_robot_model(inertia, "a.urdf"), "violate I₁ + I₂ ≥ I₃");
  const std::string mass = arm_with("<mass value=\"2\"/>", "<mass value=\"-2\"/>");
  EXPECT_RIGID_ERROR((void)read_robot_model(mass, "a.urdf"),
                     "link 'upper': the inertial is not usable: mass must be positive");
}

TEST(RobotModelUrdf, MalformedXmlInPlainWords) {
  const std::string broken = "<robot name=\"r\">\n  <link name=\"a\">\n</robot>\n";
  try {
    (void)read_robot_model(broken, "b.urdf");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("b.urdf:"), std::string::npos) << what;
    EXPECT_NE(what.find("malformed XML: an end tag does not match its start tag"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find("ErrorID"), std::string::npos) << what;
  }
  EXPECT_RIGID_ERROR((void)read_robot_model("<model/>", "x.xml"),
                     "x.xml:1: root element <model>: expected <robot> (URDF), <mujoco> (MJCF) or "
                     "<sdf> (SDFormat)");
  // <sdf> goes to the SDF reader (tests/robot/sdf_model_test.cpp)
  EXPECT_RIGID_ERROR((void)read_robot_model("<sdf/>", "x.sdf"), "x.sdf:1: <sdf> has no 'version'");
  EXPECT_RIGID_ERROR((void)read_robot_model("", "e.urdf"), "e.urdf");
}

TEST(RobotModelUrdf, FileReaderRefusesWhatIsNotARegularFile) {
  const fs::path dir = scratch("files");
  EXPECT_RIGID_ERROR((void)read_robot_model_file(dir.string()), "is not a regular file");
  EXPECT_RIGID_ERROR((void)read_robot_model_file("/dev/zero"), "is not a regular file");
  const fs::path fifo = dir / "pipe.urdf";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_RIGID_ERROR((void)read_robot_model_file(fifo.string()),
                     "is not a regular file");  // does not block
  EXPECT_RIGID_ERROR((void)read_robot_model_file((dir / "none.urdf").string()), "does not exist");
  write(dir / "arm.urdf", kArm);
  const RobotModel m = read_robot_model_file((dir / "arm.urdf").string());
  EXPECT_EQ(m.source, (dir / "arm.urdf").string());
  EXPECT_EQ(m.links.front().file, (dir / "arm.urdf").string());
  fs::remove_all(dir);
}

TEST(RobotModelUrdf, InertiaFromCollisionGeometry) {
  // a box 0.1 × 0.2 × 0.3 m at 500 kg/m³ placed at z = 0.5: m = 3 kg, I = m/12 (b² + c², ...)
  const std::string urdf = R"(<robot name="b">
  <link name="base"><collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.2 0.3"/></geometry></collision></link>
</robot>)";
  const RobotModel m =
      read_robot_model(urdf, "b.urdf", {.inertia_from_geometry = true, .density = 500});
  ASSERT_EQ(m.links.size(), 1u);
  const double mass = 500 * 0.1 * 0.2 * 0.3;
  // the product of three decimals and the catalogue's own formula: a few ε relative
  EXPECT_NEAR(m.links[0].mass, mass, test::ulps(8, mass));
  EXPECT_LE((m.links[0].com - Vector3d(0, 0, 0.5)).norm(), test::ulps(4, 0.5));
  const Vector3d I = mass / 12 * Vector3d(0.04 + 0.09, 0.01 + 0.09, 0.01 + 0.04);
  EXPECT_LE((m.links[0].inertia_com.diagonal() - I).cwiseAbs().maxCoeff(),
            test::ulps(16, I.maxCoeff()));
  // read as stated, the link has no inertial
  EXPECT_EQ(read_robot_model(urdf, "b.urdf").links[0].mass, 0.0);
}

// ---------------------------------------------------------------------------------------------
// MJCF

TEST(RobotModelMjcf, DefaultClassesNestAndChildclassApplies) {
  const std::string xml = R"(<mujoco model="classes">
  <compiler angle="radian"/>
  <option gravity="0 0 -1.62"/>
  <default>
    <joint damping="1" armature="0.5"/>
    <default class="a">
      <joint stiffness="2"/>
      <default class="b">
        <joint damping="3"/>
      </default>
    </default>
    <default class="c"><joint armature="7" type="slide"/></default>
  </default>
  <worldbody>
    <body name="p" childclass="b" pos="1 2 3">
      <joint name="j1"/>
      <joint name="j2" class="a" pos="0 0 0.5" axis="0 2 0"/>
      <body name="q">
        <joint name="j3" class="main"/>
        <joint name="j4" damping="9"/>
      </body>
      <body name="r" childclass="c"><joint name="j5"/></body>
    </body>
  </worldbody>
</mujoco>)";
  const RobotModel m = read_robot_model(xml, "c.xml");
  EXPECT_EQ(m.format, InertialFormat::mjcf);
  EXPECT_EQ(m.name, "classes");
  EXPECT_EQ(m.gravity, Vector3d(0, 0, -1.62));
  ASSERT_EQ(m.links.size(), 3u);
  EXPECT_EQ(m.coordinate_names(), (std::vector<std::string>{"j1", "j2", "j3", "j4", "j5"}));
  struct Expected {
    double damping, stiffness, armature;
    RobotJointType type;
  };
  const std::vector<Expected> expected = {
      {3, 2, 0.5, RobotJointType::kHinge},  // j1: childclass b (b ⊂ a ⊂ main)
      {1, 2, 0.5, RobotJointType::kHinge},  // j2: its own class a
      {1, 0, 0.5, RobotJointType::kHinge},  // j3: class main
      {9, 2, 0.5, RobotJointType::kHinge},  // j4: childclass b inherited, own damping
      {1, 0, 7, RobotJointType::kSlide}};   // j5: childclass c
  std::size_t k = 0;
  for (const auto& l : m.links) {
    for (const auto& j : l.joints) {
      SCOPED_TRACE(j.name);
      EXPECT_EQ(j.damping, expected[k].damping);
      EXPECT_EQ(j.stiffness, expected[k].stiffness);
      EXPECT_EQ(j.armature, expected[k].armature);
      EXPECT_EQ(j.type, expected[k].type);
      ++k;
    }
  }
  EXPECT_EQ(m.links[0].position, Vector3d(1, 2, 3));
  EXPECT_EQ(m.links[0].joints[1].anchor, Vector3d(0, 0, 0.5));
  EXPECT_EQ(m.links[0].joints[1].axis, Vector3d(0, 1, 0));
  EXPECT_EQ(m.links[0].joints[0].axis, Vector3d(0, 0, 1));  // MuJoCo's default
  EXPECT_EQ(m.links[1].parent, 0);
  EXPECT_EQ(m.links[2].parent, 0);
  EXPECT_EQ(m.links[0].mass, 0.0);  // no geoms, no inertial
  EXPECT_RIGID_ERROR(
      (void)read_robot_model(
          std::string(xml).replace(xml.find("class=\"a\" pos"), 9, "class=\"z\""), "c.xml"),
      "c.xml:17: joint 'j2': unknown default class 'z'");
}

std::string angle_model(const std::string& angle) {
  return fmt::format(R"(<mujoco>
  <compiler angle="{}"/>
  <worldbody>
    <body name="a" euler="90 0 0">
      <joint name="h" ref="90" springref="45"/>
      <joint name="s" type="slide" ref="0.5" springref="0.25"/>
      <body name="b" axisangle="0 0 1 90"/>
    </body>
  </worldbody>
</mujoco>)",
                     angle);
}

TEST(RobotModelMjcf, HingeAnglesFollowCompilerAngle) {
  // degree is MuJoCo's default: with no <compiler> the file reads as with angle="degree"
  std::string no_compiler = angle_model("degree");
  no_compiler.erase(no_compiler.find("  <compiler"),
                    std::string("  <compiler angle=\"degree\"/>\n").size());
  for (const std::string& xml : {angle_model("degree"), no_compiler}) {
    const RobotModel m = read_robot_model(xml, "deg.xml");
    const auto& j = m.links[0].joints;
    ASSERT_EQ(j.size(), 2u);
    // 90 · π/180 is rounded once: an ulp of π/2
    EXPECT_NEAR(j[0].ref, kPi / 2, test::ulps(1, kPi / 2));
    EXPECT_NEAR(j[0].springref, kPi / 4, test::ulps(1, kPi / 4));
    EXPECT_EQ(j[1].ref, 0.5);  // a slide's are lengths
    EXPECT_EQ(j[1].springref, 0.25);
    // euler 90 0 0 (rotating x y z) = Rx(π/2); axisangle z 90° = Rz(π/2): a few ε
    EXPECT_LE((m.links[0].rotation - AngleAxisd(kPi / 2, Vector3d::UnitX()).toRotationMatrix())
                  .cwiseAbs()
                  .maxCoeff(),
              test::ulps(4, 1.0));
    EXPECT_LE((m.links[1].rotation - AngleAxisd(kPi / 2, Vector3d::UnitZ()).toRotationMatrix())
                  .cwiseAbs()
                  .maxCoeff(),
              test::ulps(4, 1.0));
  }
  const RobotModel r = read_robot_model(angle_model("radian"), "rad.xml");
  EXPECT_EQ(r.links[0].joints[0].ref, 90.0);
  EXPECT_EQ(r.links[0].joints[0].springref, 45.0);
  EXPECT_LE((r.links[0].rotation - AngleAxisd(90, Vector3d::UnitX()).toRotationMatrix())
                .cwiseAbs()
                .maxCoeff(),
            test::ulps(4, 1.0));
}

// What MuJoCo would add to the tree's equations is refused by name, not left out: an
// <equality> constraint (a closed loop), a tendon's spring or damper, the medium's drag.
TEST(RobotModelMjcf, RefusesWhatTheTreeWouldLeaveOut) {
  const std::string body = R"(<worldbody><body name="a"><joint name="j"/>
<geom type="sphere" size="0.1"/></body></worldbody>
)";
  EXPECT_RIGID_ERROR((void)read_robot_model("<mujoco>" + body + R"(<equality>
<connect body1="a" anchor="0 0 0"/></equality></mujoco>)", "e.xml"),
                     "e.xml:4: <equality><connect>: closed loops and coupled joints are not yet "
                     "supported");
  EXPECT_RIGID_ERROR((void)read_robot_model("<mujoco>" + body + R"(<tendon>
<fixed name="t" stiffness="3"><joint joint="j" coef="1"/></fixed></tendon></mujoco>)", "t.xml"),
                     "t.xml:4: <tendon><fixed> with stiffness: a tendon's passive force is not yet "
                     "part of the equations");
  EXPECT_RIGID_ERROR((void)read_robot_model(R"(<mujoco><option viscosity="0.5"/>
)" + body + "</mujoco>", "o.xml"),
                     "o.xml:1: <option viscosity>: the medium's drag on the bodies is not part of "
                     "the equations");
  // a tendon without stiffness or damping changes nothing of M q̈ = τ + f: read
  EXPECT_NO_THROW((void)read_robot_model("<mujoco>" + body + R"(<tendon>
<fixed name="t"><joint joint="j" coef="1"/></fixed></tendon></mujoco>)", "ok.xml"));
}

TEST(RobotModelMjcf, ReadsBallAndFreeJointsAndRefusesAFreeJointBelowTheWorld) {
  const std::string xml = R"(<mujoco>
  <worldbody>
    <body name="a" pos="0 0 1">
      <freejoint name="root"/>
      <body name="b"><joint name="ball" type="ball" pos="0 0 0.5" damping="2"/></body>
    </body>
  </worldbody>
</mujoco>)";
  const RobotModel floating = read_robot_model(xml, "f.xml");
  ASSERT_EQ(floating.links[0].joints.size(), 1u);
  EXPECT_EQ(floating.links[0].joints[0].type, RobotJointType::kFree);
  EXPECT_EQ(floating.links[1].joints[0].type, RobotJointType::kBall);
  EXPECT_EQ(floating.links[1].joints[0].anchor, Vector3d(0, 0, 0.5));
  EXPECT_EQ(floating.links[1].joints[0].damping, 2.0);
  EXPECT_EQ(floating.nq(), 11u);
  EXPECT_EQ(floating.nv(), 9u);
  EXPECT_EQ(floating.dof(), 9u);
  EXPECT_EQ(floating.coordinate_names(),
            (std::vector<std::string>{"root_x", "root_y", "root_z", "root_qw", "root_qx",
                                      "root_qy", "root_qz", "ball_qw", "ball_qx", "ball_qy",
                                      "ball_qz"}));
  EXPECT_EQ(floating.velocity_names(),
            (std::vector<std::string>{"root_vx", "root_vy", "root_vz", "root_wx", "root_wy",
                                      "root_wz", "ball_wx", "ball_wy", "ball_wz"}));
  std::string free_inside = xml;
  free_inside.replace(free_inside.find("type=\"ball\""), 11, "type=\"free\"");
  free_inside.replace(free_inside.find("<freejoint name=\"root\"/>"), 24, "");
  EXPECT_RIGID_ERROR((void)read_robot_model(free_inside, "f.xml", {.pin_free_root = true}),
                     "f.xml:5: joint 'ball' (type free): a free joint must be on a body of the "
                     "world");
  std::string shared = xml;
  shared.replace(shared.find("damping=\"2\"/>"), 13,
                 "damping=\"2\"/><joint name=\"h\" axis=\"1 0 0\"/>");
  EXPECT_RIGID_ERROR((void)read_robot_model(shared, "f.xml"),
                     "f.xml:5: joint 'ball' (type ball) shares body 'b' with 1 other joint(s)");
  std::string pinned = xml;
  pinned.replace(pinned.find("type=\"ball\""), 11, "");
  const RobotModel m = read_robot_model(pinned, "f.xml", {.pin_free_root = true});
  EXPECT_TRUE(m.links[0].joints.empty());
  EXPECT_EQ(m.coordinate_names(), std::vector<std::string>{"ball"});
  std::string bad = pinned;
  bad.replace(bad.find("pos=\"0 0 1\""), 11, "pos=\"0 0\" quat=\"1 0 0 0\" euler=\"0 0 0\"");
  EXPECT_RIGID_ERROR((void)read_robot_model(bad, "f.xml", {.pin_free_root = true}),
                     "f.xml:3: <body> attribute 'pos': expected 3 numbers");
}

TEST(RobotModelMjcf, IncludesFollowedAndTheirErrorsNamed) {
  const fs::path dir = scratch("include");
  const std::string main = R"(<mujoco model="inc">
  <compiler angle="radian"/>
  <include file="parts/defaults.xml"/>
  <worldbody>
    <body name="base">
      <geom type="sphere" size="0.1"/>
      <include file="parts/arm.xml"/>
    </body>
  </worldbody>
</mujoco>)";
  write(dir / "main.xml", main);
  write(dir / "parts" / "defaults.xml",
        "<mujoco>\n  <default><joint damping=\"4\"/></default>\n</mujoco>\n");
  write(dir / "parts" / "arm.xml", R"(<mujoco>
  <body name="arm" pos="0 0 -0.5">
    <joint name="elbow" axis="0 1 0" ref="0.25"/>
    <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.05"/>
  </body>
</mujoco>
)");
  const RobotModel m = read_robot_model_file((dir / "main.xml").string());
  ASSERT_EQ(m.links.size(), 2u);
  EXPECT_EQ(m.links[1].name, "arm");
  EXPECT_EQ(m.links[1].parent, 0);
  EXPECT_EQ(m.links[1].file, (dir / "parts" / "arm.xml").string());
  EXPECT_EQ(m.links[1].line, 2);
  ASSERT_EQ(m.links[1].joints.size(), 1u);
  EXPECT_EQ(m.links[1].joints[0].damping, 4.0);  // the included default
  EXPECT_EQ(m.links[1].joints[0].ref, 0.25);
  EXPECT_GT(m.links[1].mass, 0.0);  // from the included geom

  // MuJoCo reads the same files to the same tree
  char error[1000] = "";
  mjModel* mj = mj_loadXML((dir / "main.xml").c_str(), nullptr, error, sizeof error);
  ASSERT_NE(mj, nullptr) << error;
  EXPECT_EQ(mj->nbody, 3);
  EXPECT_EQ(mj->dof_damping[0], 4.0);
  EXPECT_NEAR(mj->body_mass[2], m.links[1].mass,
              1e-12 * m.links[1].mass);  // relative: same formula, rounding only
  mj_deleteModel(mj);

  // an error inside the included file names that file and line
  write(dir / "parts" / "arm.xml",
        "<mujoco>\n  <body name=\"arm\">\n    <joint name=\"elbow\" type=\"free\"/>\n  "
        "</body>\n</mujoco>\n");
  EXPECT_RIGID_ERROR((void)read_robot_model_file((dir / "main.xml").string()),
                     (dir / "parts" / "arm.xml").string() + ":3: joint 'elbow' (type free)");
  write(dir / "parts" / "arm.xml",
        "<mujoco>\n  <body name=\"arm\">\n    <joint name=\"elbow\"\n  </body>\n</mujoco>\n");
  EXPECT_RIGID_ERROR((void)read_robot_model_file((dir / "main.xml").string()),
                     (dir / "parts" / "arm.xml").string() + ":3: malformed XML");
  // a missing file: the include's own place; a file included twice
  fs::remove(dir / "parts" / "arm.xml");
  EXPECT_RIGID_ERROR((void)read_robot_model_file((dir / "main.xml").string()),
                     (dir / "main.xml").string() + ":7: <include file=\"parts/arm.xml\">: '" +
                         (dir / "parts" / "arm.xml").string() + "' does not exist");
  write(dir / "parts" / "arm.xml",
        "<mujoco>\n  <include file=\"parts/defaults.xml\"/>\n</mujoco>\n");
  EXPECT_RIGID_ERROR(
      (void)read_robot_model_file((dir / "main.xml").string()),
      (dir / "parts" / "arm.xml").string() + ":2: <include file=\"parts/defaults.xml\">: '" +
          (dir / "parts" / "defaults.xml").string() + "' is already part of the model");
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// MJCF against MuJoCo's compiler

using Model = test::MjModelPtr;
using test::load_mujoco;

Matrix3d rotation(const mjtNum* q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

// Tolerances. Positions, axes and joint parameters are the file's decimals parsed by both
// readers to the same doubles; rotations and unit axes pass through a normalisation and a
// quaternion ↔ matrix conversion on one side only: a few ε. 1e-12 relative is far above that
// and far below any real difference (a wrong class, unit or frame moves them by > 1e-3).
constexpr double kGeometry = 1e-12;
// MuJoCo stores each body's inertia as principal moments and iquat (its own eigen
// decomposition); R diag Rᵀ rebuilt here loses ~1e-13 of tr I (tests/io/
// inertial_fix_mujoco_test.cpp measured it on the humanoid): 1e-12 of tr I.
constexpr double kInertia = 1e-12;

void expect_body(const mjModel* mj, int b, const RobotLink& link) {
  SCOPED_TRACE(link.name);
  EXPECT_EQ(link.parent + 1, mj->body_parentid[b]);
  EXPECT_LE((Vector3d(mj->body_pos + 3 * b) - link.position).norm(),
            kGeometry * std::max(1.0, link.position.norm()));
  EXPECT_LE((rotation(mj->body_quat + 4 * b) - link.rotation).cwiseAbs().maxCoeff(), kGeometry);
  const double mass = mj->body_mass[b];
  EXPECT_NEAR(link.mass, mass, kInertia * mass);
  if (mass == 0) return;
  const Vector3d d(mj->body_inertia + 3 * b);
  const Matrix3d R = rotation(mj->body_iquat + 4 * b);
  const Matrix3d I = R * d.asDiagonal() * R.transpose();
  EXPECT_LE((link.inertia_com - I).cwiseAbs().maxCoeff(), kInertia * I.trace())
      << link.inertia_com << "\nvs\n"
      << I;
  const double size = std::sqrt(I.trace() / mass);  // radius of gyration: the COM's scale
  EXPECT_LE((link.com - Vector3d(mj->body_ipos + 3 * b)).norm(),
            kGeometry * std::max(size, link.com.norm()));
}

void expect_joint(const mjModel* mj, int j, const RobotJoint& joint) {
  SCOPED_TRACE(joint.name);
  EXPECT_EQ(joint.name, std::string(mj->names + mj->name_jntadr[j]));
  EXPECT_EQ(joint.type == RobotJointType::kHinge ? mjJNT_HINGE : mjJNT_SLIDE, mj->jnt_type[j]);
  EXPECT_LE((Vector3d(mj->jnt_axis + 3 * j) - joint.axis).cwiseAbs().maxCoeff(), kGeometry);
  EXPECT_LE((Vector3d(mj->jnt_pos + 3 * j) - joint.anchor).norm(),
            kGeometry * std::max(1.0, joint.anchor.norm()));
  const int dof = mj->jnt_dofadr[j], q = mj->jnt_qposadr[j];
  EXPECT_NEAR(joint.damping, mj->dof_damping[dof], kGeometry * joint.damping);
  EXPECT_NEAR(joint.armature, mj->dof_armature[dof], kGeometry * joint.armature);
  EXPECT_NEAR(joint.stiffness, mj->jnt_stiffness[j], kGeometry * joint.stiffness);
  EXPECT_NEAR(joint.springref, mj->qpos_spring[q],
              kGeometry * std::max(1.0, std::abs(joint.springref)));
  EXPECT_NEAR(joint.ref, mj->qpos0[q], kGeometry * std::max(1.0, std::abs(joint.ref)));
}

// every body and every hinge/slide joint, in MuJoCo's order (free joints are skipped: the
// pinned model welds them)
void expect_same_tree(const mjModel* mj, const RobotModel& m) {
  ASSERT_EQ(static_cast<int>(m.links.size()), mj->nbody - 1);
  int j = 0;
  for (int b = 1; b < mj->nbody; ++b) {
    const RobotLink& link = m.links[b - 1];
    const char* name = mj->names + mj->name_bodyadr[b];
    EXPECT_EQ(link.name, std::string(name));
    expect_body(mj, b, link);
    std::size_t k = 0;
    for (; j < mj->njnt && mj->jnt_bodyid[j] == b; ++j) {
      if (mj->jnt_type[j] == mjJNT_FREE) continue;
      ASSERT_LT(k, link.joints.size()) << name;
      expect_joint(mj, j, link.joints[k++]);
    }
    EXPECT_EQ(k, link.joints.size()) << name;
  }
}

TEST(RobotModelMujoco, HumanoidPinnedMatchesMujoco) {
  const fs::path path = kModels / "humanoid" / "humanoid.xml";
  ASSERT_TRUE(fs::exists(path)) << "install libmujoco-samples (scripts/install-deps.sh)";
  // unpinned, the torso carries the free joint (tests/robot/floating_base_test.cpp has its
  // dynamics against MuJoCo's)
  const RobotModel floating = read_robot_model_file(path.string());
  ASSERT_EQ(floating.links[0].joints.size(), 1u);
  EXPECT_EQ(floating.links[0].joints[0].type, RobotJointType::kFree);
  EXPECT_EQ(floating.links[0].joints[0].name, "root");
  const RobotModel m = read_robot_model_file(path.string(), {.pin_free_root = true});
  // MuJoCo's pinned humanoid: the same file without its free joint
  std::string text = read_text(path);
  const std::string free = "<freejoint name=\"root\"/>";
  ASSERT_NE(text.find(free), std::string::npos);
  text.replace(text.find(free), free.size(), "");
  const fs::path dir = scratch("humanoid");
  write(dir / "humanoid.xml", text);
  const Model mj = load_mujoco(dir / "humanoid.xml");
  ASSERT_TRUE(mj);
  EXPECT_EQ(mj->njnt, 21);
  EXPECT_EQ(m.dof(), 21u);
  expect_same_tree(mj.get(), m);
  EXPECT_EQ(m.gravity, Vector3d(mj->opt.gravity));
  fs::remove_all(dir);
}

TEST(RobotModelMujoco, TendonArmMatchesMujoco) {
  const fs::path path = kModels / "tendon_arm" / "arm26.xml";
  ASSERT_TRUE(fs::exists(path));
  const RobotModel m = read_robot_model_file(path.string());
  const Model mj = load_mujoco(path);
  ASSERT_TRUE(mj);
  EXPECT_EQ(m.dof(), 2u);
  expect_same_tree(mj.get(), m);
}

TEST(RobotModelMujoco, Humanoid100FollowsItsIncludeAndMatchesMujoco) {
  // the humanoid (in the included humanoid_body.xml) and 100 free objects, all pinned
  const fs::path path = kModels / "humanoid100" / "humanoid100.xml";
  ASSERT_TRUE(fs::exists(path));
  const RobotModel m = read_robot_model_file(path.string(), {.pin_free_root = true});
  const Model mj = load_mujoco(path);
  ASSERT_TRUE(mj);
  EXPECT_EQ(static_cast<int>(m.links.size()), mj->nbody - 1);
  EXPECT_EQ(m.dof(), 21u);  // the humanoid's hinges; every free joint welded
  EXPECT_EQ(m.links.front().file, (kModels / "humanoid100" / "humanoid_body.xml").string());
  expect_same_tree(mj.get(), m);
}

TEST(RobotModelMujoco, InertiaFromGeometryIgnoresStatedInertials) {
  // inertiafromgeom="true" (the option) replaces the stated inertial by the geoms'; MuJoCo
  // compiles the same file with <compiler inertiafromgeom="true">
  const fs::path dir = scratch("fromgeom");
  const std::string xml = R"(<mujoco>
  <worldbody>
    <body name="a" quat="0.9 0.1 0.3 0.2">
      <joint name="h" axis="1 1 0" pos="0.1 0 0" damping="0.5" stiffness="3" springref="30" ref="10"/>
      <inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>
      <geom type="box" size="0.1 0.2 0.3" pos="0.1 0 0" euler="10 20 30"/>
      <geom type="cylinder" fromto="0 0 0 0.3 0.1 0" size="0.05" density="300"/>
    </body>
  </worldbody>
</mujoco>)";
  const RobotModel stated = read_robot_model(xml, "s.xml");
  EXPECT_EQ(stated.links[0].mass, 1.0);
  const RobotModel m = read_robot_model(xml, "s.xml", {.inertia_from_geometry = true});
  std::string compiled = xml;
  compiled.replace(compiled.find("<mujoco>"), 8, "<mujoco><compiler inertiafromgeom=\"true\"/>");
  write(dir / "m.xml", compiled);
  const Model mj = load_mujoco(dir / "m.xml");
  ASSERT_TRUE(mj);
  // MuJoCo 2.2 combines several rotated geoms with ~5e-8 of tr I of round-off (measured in
  // tests/io/inertial_fix_mujoco_test.cpp): the inertia is compared to 1e-7 there
  const Vector3d d(mj->body_inertia + 3);
  const Matrix3d R = rotation(mj->body_iquat + 4);
  const Matrix3d I = R * d.asDiagonal() * R.transpose();
  EXPECT_NEAR(m.links[0].mass, mj->body_mass[1], 1e-12 * mj->body_mass[1]);
  EXPECT_LE((m.links[0].inertia_com - I).cwiseAbs().maxCoeff(), 1e-7 * I.trace());
  ASSERT_EQ(m.links[0].joints.size(), 1u);
  expect_joint(mj.get(), 0, m.links[0].joints[0]);
  EXPECT_LE((rotation(mj->body_quat + 4) - m.links[0].rotation).cwiseAbs().maxCoeff(), kGeometry);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rigid::io
