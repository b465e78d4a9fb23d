// io::read_robot_model on SDFormat files (src/io/sdf_model.cpp): examples/arm7.sdf against
// examples/arm7.urdf (two files in two frame conventions, two readers, one robot: the same
// M(q), b(q, q̇) and p(q, q̇) from robot::TreeDynamics), the fields of a small model worked out
// by hand from the SDFormat spec's frame rules, and the refusals, each located by file:line.
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "rigid/common/error.hpp"
#include "rigid/io/robot_model.hpp"
#include "rigid/robot/tree_dynamics.hpp"
#include "support/expect_error.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(RIGID_TEST_DATA_DIR).parent_path().parent_path() / "examples";
constexpr double kPi = std::numbers::pi;

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

TEST(SdfModel, Arm7HasTheUrdfsJointsAndDynamics) {
  const RobotModel urdf = read_robot_model_file((kExamples / "arm7.urdf").string());
  const RobotModel sdf = read_robot_model_file((kExamples / "arm7.sdf").string());
  EXPECT_EQ(sdf.format, InertialFormat::sdf);
  EXPECT_EQ(sdf.name, "arm7");
  ASSERT_EQ(sdf.coordinate_names(), urdf.coordinate_names());
  ASSERT_EQ(sdf.links.size(), urdf.links.size());
  for (std::size_t i = 0; i < sdf.links.size(); ++i) {
    EXPECT_EQ(sdf.links[i].name, urdf.links[i].name);
    EXPECT_EQ(sdf.links[i].parent, urdf.links[i].parent);
  }
  const robot::TreeDynamics a(urdf), b(sdf);
  // The files place the frames differently (link poses composed in the model frame, joint4's
  // frame turned by π, joint6's axis in the model frame, link7's frame off its axis), so the two
  // trees agree up to the rounding of rpy angles such as π/2 (cos = 6e-17) and of the composed
  // placements: a few 1e-16 relative through seven links. 1e-12 leaves four orders of margin;
  // a wrong axis sign, anchor or inertial frame is an O(1) difference.
  constexpr double kRelative = 1e-12;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int state = 0; state < 24; ++state) {
    Eigen::VectorXd q(7), v(7);
    for (int i = 0; i < 7; ++i) {
      q(i) = kPi * u(rng);
      v(i) = 2 * u(rng);
    }
    const Eigen::MatrixXd M = a.mass_matrix(q);
    EXPECT_LE(max_abs(b.mass_matrix(q) - M), kRelative * max_abs(M)) << "state " << state;
    const Eigen::VectorXd bias = a.bias_forces(q, v);
    EXPECT_LE(max_abs(b.bias_forces(q, v) - bias), kRelative * max_abs(bias)) << "state " << state;
    const Eigen::VectorXd passive = a.passive_forces(q, v);
    EXPECT_LE(max_abs(b.passive_forces(q, v) - passive), kRelative * max_abs(passive));
  }
}

// A cart on a rail carrying a spinning arm with a tool welded to it; its model frame is
// turned a quarter turn about z and lifted to (1, 2, 3). `version` and `axis_extra` pick the
// frame that the spin axis "0 0 1" is expressed in.
std::string cart(const std::string& version, const std::string& axis_extra) {
  return fmt::format(
      R"(<sdf version="{}">
  <model name="cart">
    <pose>1 2 3 0 0 1.5707963267948966</pose>
    <link name="base">
      <pose>0 0 0.5 0 0 0</pose>
      <inertial><mass>0</mass><inertia><ixx>0</ixx><iyy>0</iyy><izz>0</izz></inertia></inertial>
    </link>
    <link name="carriage">
      <pose>0.2 0 0.5 0 0 0</pose>
      <inertial><pose>0 0 0.1 0 0 0</pose><mass>2</mass>
        <inertia><ixx>0.1</ixx><iyy>0.2</iyy><izz>0.3</izz></inertia></inertial>
    </link>
    <link name="arm">
      <pose>0.2 0 0.8 0 1.5707963267948966 0</pose>
      <inertial><pose>0.1 0 0 0 0 0.5</pose><mass>1</mass>
        <inertia><ixx>0.01</ixx><iyy>0.02</iyy><izz>0.03</izz></inertia></inertial>
    </link>
    <link name="tool">
      <pose>0.2 0.3 0.8 0 0 0</pose>
    </link>
    <joint name="weld" type="fixed"><parent>world</parent><child>base</child></joint>
    <joint name="rail" type="prismatic">
      <parent>base</parent><child>carriage</child>
      <axis><xyz>1 0 0</xyz>
        <dynamics><damping>2</damping><friction>5</friction><spring_stiffness>30</spring_stiffness>
          <spring_reference>0.1</spring_reference></dynamics></axis>
    </joint>
    <joint name="spin" type="continuous">
      <parent>carriage</parent><child>arm</child>
      <pose>0 0.05 0 0 0 0</pose>
      <axis><xyz>0 0 1</xyz>{}<dynamics><damping>0.3</damping></dynamics></axis>
    </joint>
    <joint name="tool_weld" type="fixed"><parent>arm</parent><child>tool</child></joint>
  </model>
</sdf>
)",
      version, axis_extra);
}

void expect_near(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected) {
  // exact in exact arithmetic; cos(π/2) = 6e-17 and products of such: 1e-15
  EXPECT_LE(max_abs(actual - expected), 1e-15) << "actual\n"
                                               << actual << "\nexpected\n"
                                               << expected;
}

TEST(SdfModel, CartFieldsFollowTheSpecsFrames) {
  const RobotModel m = read_robot_model(cart("1.6", ""), "cart.sdf");
  EXPECT_EQ(m.name, "cart");
  EXPECT_EQ(m.gravity, Eigen::Vector3d(0, 0, -9.81));  // no <world>: the library's default
  ASSERT_EQ(m.links.size(), 4u);
  EXPECT_EQ(m.coordinate_names(), (std::vector<std::string>{"rail", "spin"}));
  const Eigen::Matrix3d Rz90 = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Matrix3d Ry90 = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()).matrix();

  // base: welded to the world by the fixed joint, at X_WM X_MB: (1, 2, 3) + Rz90 (0, 0, 0.5)
  const RobotLink& base = m.links[0];
  EXPECT_EQ(base.name, "base");
  EXPECT_EQ(base.parent, -1);
  EXPECT_TRUE(base.joints.empty());
  expect_near(base.position, Eigen::Vector3d(1, 2, 3.5));
  expect_near(base.rotation, Rz90);
  EXPECT_EQ(base.mass, 0);  // stated massless
  EXPECT_EQ(base.line, 4);

  // carriage: 0.2 along the base's x; the rail along it, with its dynamics (friction not read)
  const RobotLink& carriage = m.links[1];
  EXPECT_EQ(carriage.parent, 0);
  expect_near(carriage.position, Eigen::Vector3d(0.2, 0, 0));
  expect_near(carriage.rotation, Eigen::Matrix3d::Identity());
  ASSERT_EQ(carriage.joints.size(), 1u);
  const RobotJoint& rail = carriage.joints[0];
  EXPECT_EQ(rail.name, "rail");
  EXPECT_EQ(rail.type, RobotJointType::kSlide);
  EXPECT_EQ(rail.axis, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(rail.anchor, Eigen::Vector3d::Zero());
  EXPECT_EQ(rail.ref, 0);
  EXPECT_EQ(rail.damping, 2);
  EXPECT_EQ(rail.stiffness, 30);
  EXPECT_EQ(rail.springref, 0.1);
  EXPECT_EQ(rail.armature, 0);
  EXPECT_EQ(rail.line, 22);
  EXPECT_EQ(carriage.mass, 2);
  expect_near(carriage.com, Eigen::Vector3d(0, 0, 0.1));
  expect_near(carriage.inertia_com, Eigen::Vector3d(0.1, 0.2, 0.3).asDiagonal().toDenseMatrix());

  // arm: 0.3 above the carriage, pitched a quarter turn; the joint frame's origin 0.05 along
  // the arm's y is the anchor; "0 0 1" in the joint frame (1.5+, no use_parent_model_frame)
  const RobotLink& arm = m.links[2];
  EXPECT_EQ(arm.parent, 1);
  expect_near(arm.position, Eigen::Vector3d(0, 0, 0.3));
  expect_near(arm.rotation, Ry90);
  ASSERT_EQ(arm.joints.size(), 1u);
  const RobotJoint& spin = arm.joints[0];
  EXPECT_EQ(spin.type, RobotJointType::kHinge);
  expect_near(spin.anchor, Eigen::Vector3d(0, 0.05, 0));
  expect_near(spin.axis, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(spin.damping, 0.3);
  EXPECT_EQ(spin.stiffness, 0);
  // the inertial frame turned by 0.5 rad about z: I_L = Rz diag Rzᵀ
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).matrix();
  expect_near(arm.com, Eigen::Vector3d(0.1, 0, 0));
  expect_near(arm.inertia_com,
              Rz * Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal() * Rz.transpose());

  // tool: welded; no <inertial>, so SDFormat's default: 1 kg, unit inertia about its origin
  const RobotLink& tool = m.links[3];
  EXPECT_EQ(tool.parent, 2);
  EXPECT_TRUE(tool.joints.empty());
  expect_near(tool.position, Ry90.transpose() * Eigen::Vector3d(0, 0.3, 0));
  expect_near(tool.rotation, Ry90.transpose());
  EXPECT_EQ(tool.mass, 1);
  EXPECT_EQ(tool.com, Eigen::Vector3d::Zero());
  EXPECT_EQ(tool.inertia_com, Eigen::Matrix3d::Identity());
}

TEST(SdfModel, AxisInTheModelFrameBy14OrUseParentModelFrameOrExpressedIn) {
  // "0 0 1" of the model frame, in the arm's frame: Ry90ᵀ (0, 0, 1) = (−1, 0, 0)
  const Eigen::Vector3d model_z(-1, 0, 0);
  for (const auto& [version, extra] : {std::pair{"1.4", ""},
                                       std::pair{"1.5",
                                                 "<use_parent_model_frame>true"
                                                 "</use_parent_model_frame>"},
                                       std::pair{"1.6",
                                                 "<use_parent_model_frame>1"
                                                 "</use_parent_model_frame>"}}) {
    const RobotModel m = read_robot_model(cart(version, extra), "cart.sdf");
    expect_near(m.links[2].joints[0].axis, model_z);
  }
  const RobotModel joint_frame =
      read_robot_model(cart("1.5", "<use_parent_model_frame>false</use_parent_model_frame>"), "c");
  expect_near(joint_frame.links[2].joints[0].axis, Eigen::Vector3d(0, 0, 1));
  std::string expressed = cart("1.7", "");
  const std::string xyz = "<axis><xyz>0 0 1</xyz>";
  expressed.replace(expressed.rfind(xyz), xyz.size(),
                    "<axis><xyz expressed_in=\"__model__\">0 0 1</xyz>");
  expect_near(read_robot_model(expressed, "c").links[2].joints[0].axis, model_z);
}

TEST(SdfModel, PoseInDegreesAndQuaternionAreTheRpyPose) {
  const auto placed = [](const std::string& pose) {
    const std::string xml = fmt::format(
        "<sdf version=\"1.9\"><model name=\"m\"><link name=\"a\"/><link name=\"b\">{}</link>"
        "<joint name=\"j\" type=\"revolute\"><parent>a</parent><child>b</child></joint>"
        "</model></sdf>",
        pose);
    return read_robot_model(xml, "p.sdf").links[1];
  };
  const RobotLink rpy = placed("<pose>0.1 0.2 0.3 0.4 -0.5 0.6</pose>");
  const RobotLink deg = placed(fmt::format("<pose degrees=\"true\">0.1 0.2 0.3 {} {} {}</pose>",
                                           0.4 * 180 / kPi, -0.5 * 180 / kPi, 0.6 * 180 / kPi));
  // R = Rz(yaw) Ry(pitch) Rx(roll), as a quaternion (x y z w)
  const Eigen::Quaterniond q = Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX());
  const RobotLink quat =
      placed(fmt::format("<pose rotation_format=\"quat_xyzw\">0.1 0.2 0.3 {} {} {} {}</pose>",
                         q.x(), q.y(), q.z(), q.w()));
  expect_near(rpy.rotation, q.toRotationMatrix());
  for (const RobotLink* l : {&deg, &quat}) {
    expect_near(l->position, rpy.position);
    expect_near(l->rotation, rpy.rotation);
  }
}

TEST(SdfModel, AWorldWithOneModelIsReadWithItsGravity) {
  const std::string xml =
      "<sdf version=\"1.7\"><world name=\"moon\"><gravity>0 0 -1.62</gravity>"
      "<model name=\"m\"><link name=\"a\"/><link name=\"b\"/>"
      "<joint name=\"j\" type=\"revolute\"><parent>a</parent><child>b</child></joint>"
      "</model></world></sdf>";
  const RobotModel m = read_robot_model(xml, "w.sdf");
  EXPECT_EQ(m.name, "m");
  EXPECT_EQ(m.gravity, Eigen::Vector3d(0, 0, -1.62));
  EXPECT_EQ(m.coordinate_names(), std::vector<std::string>{"j"});
}

// read_robot_model for its refusals only
void read_only(const std::string& xml, const std::string& source) {
  (void)read_robot_model(xml, source);
}

// Lines 1-4 are the same in every case; `rest` starts on line 5.
std::string two_links(const std::string& rest) {
  return "<sdf version=\"1.7\">\n<model name=\"m\">\n<link name=\"a\"/>\n<link name=\"b\"/>\n" +
         rest + "\n</model>\n</sdf>\n";
}

std::string joint(const std::string& type, const std::string& parent, const std::string& child,
                  const std::string& name = "j") {
  return fmt::format(
      "<joint name=\"{}\" type=\"{}\"><parent>{}</parent><child>{}</child>"
      "</joint>",
      name, type, parent, child);
}

TEST(SdfModel, UnsupportedJointsAreRefusedByType) {
  for (const char* type : {"ball", "universal", "screw", "gearbox", "revolute2", "hinge"}) {
    EXPECT_RIGID_ERROR(read_only(two_links(joint(type, "a", "b")), "t.sdf"),
                       fmt::format("t.sdf:5: joint 'j' type=\"{}\"", type));
  }
  EXPECT_RIGID_ERROR(read_only(two_links(joint("ball", "a", "b")), "t.sdf"),
                     "ball joints are not yet read from SDFormat");
  EXPECT_RIGID_ERROR(read_only(two_links(joint("universal", "a", "b")), "t.sdf"),
                     "two revolute joints");
  EXPECT_RIGID_ERROR(read_only(two_links(joint("hinge", "a", "b")), "t.sdf"),
                     "expected revolute, continuous, prismatic or fixed");
}

TEST(SdfModel, IncludesNestedModelsAndWorldsOfSeveralModelsAreRefused) {
  EXPECT_RIGID_ERROR(read_only(two_links("<include><uri>model://gripper</uri></include>"), "t.sdf"),
                     "t.sdf:5: <include> of 'model://gripper': including models is not supported");
  EXPECT_RIGID_ERROR(
      read_only(two_links("<model name=\"inner\"><link name=\"c\"/></model>"), "t.sdf"),
      "t.sdf:5: nested <model> 'inner' in model 'm'");
  const std::string world =
      "<sdf version=\"1.7\">\n<world name=\"w\">\n<model name=\"a\"><link name=\"l\"/></model>\n"
      "<model name=\"b\"><link name=\"l\"/></model>\n</world>\n</sdf>\n";
  EXPECT_RIGID_ERROR(read_only(world, "w.sdf"), "w.sdf:4: <world> 'w' holds 2 models");
  const std::string included =
      "<sdf version=\"1.7\">\n<world name=\"w\">\n<include><uri>model://arm</uri></include>\n"
      "</world>\n</sdf>\n";
  EXPECT_RIGID_ERROR(read_only(included, "w.sdf"), "w.sdf:3: <include> of 'model://arm'");
  EXPECT_RIGID_ERROR(read_only("<sdf version=\"1.7\">\n</sdf>\n", "e.sdf"),
                     "e.sdf:1: <sdf> has no <model>");
  EXPECT_RIGID_ERROR(read_only("<sdf>\n<model name=\"m\"/>\n</sdf>\n", "v.sdf"),
                     "v.sdf:1: <sdf> has no 'version'");
  EXPECT_RIGID_ERROR(read_only(two_links("<static>true</static>"), "t.sdf"),
                     "t.sdf:5: model 'm' is <static>");
}

TEST(SdfModel, TreesThatAreNotTreesAreRefused) {
  EXPECT_RIGID_ERROR(read_only(two_links(""), "t.sdf"), "t.sdf:2: 2 root links (a, b)");
  EXPECT_RIGID_ERROR(read_only(two_links(joint("revolute", "a", "b", "j1") + "\n" +
                                         joint("revolute", "b", "a", "j2")),
                               "t.sdf"),
                     "t.sdf:2: every link is the child of a joint: the joints form a loop");
  // a root (a) and a cycle b → c → b that hangs from nothing
  EXPECT_RIGID_ERROR(
      read_only(two_links("<link name=\"c\"/>\n" + joint("revolute", "b", "c", "j1") + "\n" +
                          joint("revolute", "c", "b", "j2")),
                "t.sdf"),
      "t.sdf:2: links b, c are not reachable from the root link 'a'");
  EXPECT_RIGID_ERROR(read_only(two_links(joint("revolute", "a", "b", "j1") + "\n" +
                                         joint("revolute", "world", "b", "j2")),
                               "t.sdf"),
                     "t.sdf:6: link 'b' is the child of joint 'j1' (line 5) and of joint 'j2'");
  EXPECT_RIGID_ERROR(read_only(two_links(joint("revolute", "nowhere", "b")), "t.sdf"),
                     "t.sdf:5: joint 'j': <parent> 'nowhere' names no link of model 'm'");
  EXPECT_RIGID_ERROR(read_only(two_links(joint("revolute", "a", "world")), "t.sdf"),
                     "t.sdf:5: joint 'j': <child> 'world' names no link of model 'm'");
  EXPECT_RIGID_ERROR(read_only(two_links(joint("revolute", "a", "a")), "t.sdf"),
                     "t.sdf:5: joint 'j' joins link 'a' to itself");
}

TEST(SdfModel, FramesOtherThanTheModelsAreRefusedByName) {
  const std::string relative =
      "<sdf version=\"1.8\">\n<model name=\"m\">\n<link name=\"a\"/>\n<link name=\"b\">\n"
      "<pose relative_to=\"a\">0 0 1 0 0 0</pose>\n</link>\n" +
      joint("revolute", "a", "b") + "\n</model>\n</sdf>\n";
  EXPECT_RIGID_ERROR(read_only(relative, "r.sdf"), "r.sdf:5: link 'b': <pose relative_to=\"a\">");
  EXPECT_RIGID_ERROR(
      read_only(two_links("<joint name=\"j\" type=\"revolute\"><parent>a</parent><child>b"
                          "</child><axis><xyz expressed_in=\"f\">1 0 0</xyz></axis>"
                          "</joint>"),
                "t.sdf"),
      "t.sdf:5: joint 'j': <xyz expressed_in=\"f\">: expected the name of a link or __model__");
}

TEST(SdfModel, JointPoseRelativeToTheModelIsInTheChildFrame) {
  // the joint frame given in the model frame at (0, 0, 1.5): b sits at (0, 0, 1), turned about
  // x by a quarter turn, so the anchor is R_MBᵀ (0, 0, 0.5) = (0, 0.5, 0) in b's frame
  const std::string xml =
      "<sdf version=\"1.8\"><model name=\"m\"><link name=\"a\"/><link name=\"b\">"
      "<pose>0 0 1 1.5707963267948966 0 0</pose></link>"
      "<joint name=\"j\" type=\"revolute\"><parent>a</parent><child>b</child>"
      "<pose relative_to=\"__model__\">0 0 1.5 0 0 0</pose></joint></model></sdf>";
  const RobotJoint j = read_robot_model(xml, "t.sdf").links[1].joints[0];
  expect_near(j.anchor, Eigen::Vector3d(0, 0.5, 0));
}

}  // namespace
}  // namespace rigid::io
