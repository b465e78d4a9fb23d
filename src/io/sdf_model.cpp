// Kinematic trees of SDFormat files (include/rigid/io/robot_model.hpp has the conventions).
// Reference: the SDFormat specification, sdformat.org/spec (elements "model", "link",
// "joint", "inertial", "pose", versions 1.4 to 1.10) and its frame semantics
// (sdformat.org/tutorials?tut=pose_frame_semantics):
//  - a link's <pose> is its frame in the model frame (1.4–1.6; 1.7+ without relative_to);
//  - a joint's <pose> is the joint frame in its child link's frame;
//  - <axis><xyz> is in the joint frame, unless <use_parent_model_frame>true (1.5, 1.6) or
//    expressed_in="__model__" (1.7+) puts it in the model frame; 1.4 and earlier state it in
//    the model frame (the 1.4 → 1.5 conversion adds use_parent_model_frame = true);
//  - a link without <inertial> has libsdformat's default inertial, as the spec's defaults of
//    <mass> (1 kg) and <inertia> (ixx = iyy = izz = 1 kg·m², products 0).
#include "detail/sdf_model.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tinyxml2.h>

#include "detail/xml_numbers.hpp"
#include "rigid/common/error.hpp"
#include "rigid/io/inertial_fix.hpp"
#include "rigid/io/inertial_xml.hpp"
#include "rigid/lie/so3.hpp"
#include "rigid/mass/mass_properties.hpp"

namespace rigid::io::detail {
namespace {

using tinyxml2::XMLElement;

constexpr std::string_view kModelFrame = "__model__";

[[noreturn]] void refuse_at(const std::string& file, const XMLElement* e,
                            const std::string& message) {
  rigid::detail::throw_error_at(SourceLocation{file, e->GetLineNum(), 0}, message);
}

std::string element_name(const XMLElement* e) {
  const char* n = e->Attribute("name");
  return n == nullptr ? std::string() : std::string(n);
}

// an element's text without the whitespace around it
std::string_view trimmed_text(const XMLElement* e) {
  const char* t = e->GetText();
  std::string_view s = t == nullptr ? std::string_view{} : std::string_view(t);
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  s.remove_prefix(first);
  return s.substr(0, s.find_last_not_of(" \t\r\n") + 1);
}

std::vector<double> text_numbers(const std::string& file, const XMLElement* e,
                                 std::size_t expected) {
  XmlNumbers n = read_xml_numbers(e->GetText(), expected, fmt::format("<{}>", e->Name()), true);
  if (!n.problem.empty()) refuse_at(file, e, n.problem);
  return std::move(n.values);
}

// the number of the child element `name` of `parent`, or `fallback` when there is none
double child_number(const std::string& file, const XMLElement* parent, const char* name,
                    double fallback) {
  const XMLElement* e = parent->FirstChildElement(name);
  return e == nullptr ? fallback : text_numbers(file, e, 1)[0];
}

// SDFormat's bool: "true"/"1" or "false"/"0"
bool child_bool(const std::string& file, const XMLElement* parent, const char* name,
                bool fallback) {
  const XMLElement* e = parent->FirstChildElement(name);
  if (e == nullptr) return fallback;
  const std::string_view t = trimmed_text(e);
  if (t == "true" || t == "1") return true;
  if (t == "false" || t == "0") return false;
  refuse_at(file, e, fmt::format("<{}> '{}': expected true, false, 1 or 0", name, t));
}

// X_AB: frame B in frame A
struct Pose {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();

  Pose operator*(const Pose& X_BC) const { return {p + R * X_BC.p, R * X_BC.R}; }
  [[nodiscard]] Pose inverse() const { return {-R.transpose() * p, R.transpose()}; }
};

// An element's <pose> and the frame it is relative to ("" for the element's default frame).
struct StatedPose {
  Pose X;
  std::string relative_to;
  const XMLElement* element = nullptr;  // the <pose>, or nullptr when there is none
};

// <pose>x y z roll pitch yaw</pose> (rad; degrees="true" of 1.9+: deg), or with
// rotation_format="quat_xyzw" (1.9+) x y z qx qy qz qw; an empty <pose/> is the identity
StatedPose pose_of(const std::string& file, const XMLElement* owner) {
  StatedPose out;
  const XMLElement* e = owner->FirstChildElement("pose");
  if (e == nullptr) return out;
  out.element = e;
  for (const char* key : {"relative_to", "frame"}) {  // "frame": 1.5–1.6's name of it
    if (const char* r = e->Attribute(key); r != nullptr && *r != '\0') out.relative_to = r;
  }
  if (trimmed_text(e).empty()) return out;
  const char* format = e->Attribute("rotation_format");
  const std::string_view rotation = format == nullptr ? "euler_rpy" : format;
  if (rotation == "quat_xyzw") {
    const auto v = text_numbers(file, e, 7);
    const double norm = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6]);
    if (!(norm >= 1e-12)) {
      refuse_at(file, e, "<pose> quaternion is zero; expected a unit quaternion qx qy qz qw");
    }
    out.X.p = Eigen::Vector3d(v[0], v[1], v[2]);
    out.X.R = SO3d::from_quaternion(v[6], v[3], v[4], v[5]).matrix();  // normalised
    return out;
  }
  if (rotation != "euler_rpy") {
    refuse_at(
        file, e,
        fmt::format("<pose rotation_format=\"{}\">: expected euler_rpy or quat_xyzw", rotation));
  }
  const auto v = text_numbers(file, e, 6);
  const char* degrees = e->Attribute("degrees");
  const std::string_view deg = degrees == nullptr ? "false" : degrees;
  if (deg != "true" && deg != "1" && deg != "false" && deg != "0") {
    refuse_at(file, e, fmt::format("<pose degrees=\"{}\">: expected true or false", deg));
  }
  const double unit = deg == "true" || deg == "1" ? std::numbers::pi / 180.0 : 1.0;
  out.X.p = Eigen::Vector3d(v[0], v[1], v[2]);
  out.X.R = rotation_from_rpy(unit * Eigen::Vector3d(v[3], v[4], v[5]));
  return out;
}

struct SdfJoint {
  const XMLElement* element = nullptr;
  std::string name, type;
  int parent = -1;  // index of the parent link; -1: the world
  int child = -1;
};

struct SdfTree {
  std::string file;
  int version_minor = 0;  // 1.x
  const XMLElement* model = nullptr;
  std::string model_name;
  Pose X_WM;                             // the model frame in the world
  std::vector<const XMLElement*> links;  // in file order
  std::vector<Pose> X_ML;                // per link: its frame in the model frame
  std::map<std::string, int, std::less<>> link_index;
  std::vector<SdfJoint> joints;            // in file order
  std::vector<int> joint_of_child;         // per link: the joint whose child it is, or -1
  std::vector<std::vector<int>> children;  // per link: joints whose parent it is, file order
};

// "1.x" → x (the spec's versions are 1.0 to 1.11)
int sdf_version_minor(const std::string& file, const XMLElement* sdf) {
  const char* v = sdf->Attribute("version");
  if (v == nullptr) {
    refuse_at(file, sdf,
              "<sdf> has no 'version'; expected version=\"1.x\" (a joint axis's frame depends "
              "on it)");
  }
  const std::string_view s(v);
  int minor = -1;
  if (s.starts_with("1.")) {
    const auto [ptr, ec] = std::from_chars(s.data() + 2, s.data() + s.size(), minor);
    if (ec != std::errc() || ptr != s.data() + s.size()) minor = -1;
  }
  if (minor < 0) {
    refuse_at(file, sdf, fmt::format("<sdf version=\"{}\">: expected version 1.x", s));
  }
  return minor;
}

void refuse_include(const std::string& file, const XMLElement* parent) {
  if (const XMLElement* inc = parent->FirstChildElement("include")) {
    const XMLElement* uri = inc->FirstChildElement("uri");
    refuse_at(
        file, inc,
        fmt::format("<include>{}: including models is not supported; paste the "
                    "included model's links and joints into the <model>",
                    uri == nullptr ? std::string() : fmt::format(" of '{}'", trimmed_text(uri))));
  }
}

std::vector<const XMLElement*> children_named(const XMLElement* parent, const char* name) {
  std::vector<const XMLElement*> out;
  for (const auto* e = parent->FirstChildElement(name); e != nullptr;
       e = e->NextSiblingElement(name)) {
    out.push_back(e);
  }
  return out;
}

// The one <model> of the document: <sdf><model>, or <sdf><world> holding exactly one model;
// `gravity` receives the world's (<world><gravity>, 1.4's <world><physics><gravity>).
const XMLElement* the_model(const std::string& file, const XMLElement* sdf,
                            Eigen::Vector3d& gravity) {
  refuse_include(file, sdf);
  const auto worlds = children_named(sdf, "world");
  const auto models = children_named(sdf, "model");
  if (worlds.size() + models.size() > 1) {
    const XMLElement* second = worlds.size() > 1 ? worlds[1] : models.back();
    refuse_at(file, second,
              fmt::format("<sdf> holds {} <world> and {} <model> elements; expected one model "
                          "(or one world with one model)",
                          worlds.size(), models.size()));
  }
  if (!models.empty()) return models.front();
  if (worlds.empty()) {
    refuse_at(file, sdf, "<sdf> has no <model> and no <world>; expected one <model>");
  }
  const XMLElement* world = worlds.front();
  refuse_include(file, world);
  if (const XMLElement* j = world->FirstChildElement("joint")) {
    refuse_at(file, j,
              fmt::format("<world> joint '{}': joints between a world's models are not "
                          "supported; put the joint in the model",
                          element_name(j)));
  }
  const auto in_world = children_named(world, "model");
  if (in_world.size() != 1) {
    refuse_at(file, in_world.size() > 1 ? in_world[1] : world,
              fmt::format("<world> '{}' holds {} models; expected exactly one <model> (a world "
                          "of several models is not a tree)",
                          element_name(world), in_world.size()));
  }
  for (const auto* physics : children_named(world, "physics")) {
    if (const XMLElement* g = physics->FirstChildElement("gravity")) {
      const auto v = text_numbers(file, g, 3);
      gravity = Eigen::Vector3d(v[0], v[1], v[2]);
    }
  }
  if (const XMLElement* g = world->FirstChildElement("gravity")) {
    const auto v = text_numbers(file, g, 3);
    gravity = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  return in_world.front();
}

// what a model holds that a tree of links and joints cannot say
void refuse_unmodelled(const std::string& file, const XMLElement* model) {
  refuse_include(file, model);
  if (const XMLElement* nested = model->FirstChildElement("model")) {
    refuse_at(file, nested,
              fmt::format("nested <model> '{}' in model '{}': nested models are not supported; "
                          "write its links and joints in the outer model",
                          element_name(nested), element_name(model)));
  }
  if (child_bool(file, model, "static", false)) {
    refuse_at(file, model->FirstChildElement("static"),
              fmt::format("model '{}' is <static>: none of its links moves, so it has no "
                          "equations of motion; expected a model that is not static",
                          element_name(model)));
  }
  if (model->Attribute("placement_frame") != nullptr) {
    refuse_at(file, model,
              fmt::format("model '{}': 'placement_frame' is not supported; give the model's "
                          "<pose> of its model frame",
                          element_name(model)));
  }
}

void read_links(SdfTree& tree) {
  const std::string& file = tree.file;
  for (const auto* l : children_named(tree.model, "link")) {
    const std::string name = element_name(l);
    if (name.empty()) refuse_at(file, l, "a <link> has no name");
    const int index = static_cast<int>(tree.links.size());
    if (!tree.link_index.emplace(name, index).second) {
      refuse_at(file, l,
                fmt::format("link '{}' is defined twice (first at line {}); link names must be "
                            "unique",
                            name, tree.links[tree.link_index.at(name)]->GetLineNum()));
    }
    const StatedPose pose = pose_of(file, l);
    if (!pose.relative_to.empty() && pose.relative_to != kModelFrame) {
      refuse_at(file, pose.element,
                fmt::format("link '{}': <pose relative_to=\"{}\">: a link pose relative to a "
                            "frame other than the model's is not supported; give it in the "
                            "model frame (no relative_to)",
                            name, pose.relative_to));
    }
    if (child_bool(file, l, "kinematic", false)) {
      refuse_at(file, l->FirstChildElement("kinematic"),
                fmt::format("link '{}' is <kinematic>: a link that forces do not move is not "
                            "supported",
                            name));
    }
    if (!child_bool(file, l, "gravity", true)) {
      refuse_at(file, l->FirstChildElement("gravity"),
                fmt::format("link '{}' has <gravity>false: a link exempt from gravity is not "
                            "supported; the equations apply gravity to every link",
                            name));
    }
    tree.links.push_back(l);
    tree.X_ML.push_back(pose.X);
  }
  if (tree.links.empty()) {
    refuse_at(file, tree.model,
              fmt::format("model '{}' has no <link>; expected at least one", tree.model_name));
  }
}

void check_joint_type(const std::string& file, const SdfJoint& j) {
  const std::string_view t = j.type;
  if (t == "revolute" || t == "continuous" || t == "prismatic" || t == "fixed") return;
  std::string why;
  if (t == "ball") {
    why =
        "ball joints are not yet read from SDFormat (MJCF <joint type=\"ball\"> is); "
        "model one as three revolute joints with massless links between them";
  } else if (t == "universal" || t == "revolute2") {
    why = fmt::format(
        "{} joints are not supported; model one as two revolute joints with a "
        "massless link between them",
        t);
  } else if (t == "screw") {
    why = "screw joints (rotation coupled to translation) are not supported";
  } else if (t == "gearbox") {
    why = "gearbox joints (a constraint between two joints) are not supported";
  } else {
    why = "expected revolute, continuous, prismatic or fixed";
  }
  refuse_at(file, j.element, fmt::format("joint '{}' type=\"{}\": {}", j.name, t, why));
}

// the link index that the joint's <parent>/<child> names; -1 for the world (parent only)
int joint_link(const SdfTree& tree, const XMLElement* joint, const char* role) {
  const XMLElement* e = joint->FirstChildElement(role);
  if (e == nullptr || trimmed_text(e).empty()) {
    refuse_at(tree.file, joint,
              fmt::format("joint '{}' has no <{}>; expected the name of a link",
                          element_name(joint), role));
  }
  const std::string_view name = trimmed_text(e);
  if (name == "world" && std::string_view(role) == "parent") return -1;
  const auto it = tree.link_index.find(name);
  if (it == tree.link_index.end()) {
    refuse_at(tree.file, e,
              fmt::format("joint '{}': <{}> '{}' names no link of model '{}'; expected one of "
                          "its <link> names{}",
                          element_name(joint), role, name, tree.model_name,
                          std::string_view(role) == "parent" ? " or world" : ""));
  }
  return it->second;
}

void read_joints(SdfTree& tree) {
  const std::string& file = tree.file;
  tree.joint_of_child.assign(tree.links.size(), -1);
  tree.children.resize(tree.links.size());
  for (const auto* j : children_named(tree.model, "joint")) {
    SdfJoint joint{j, element_name(j), j->Attribute("type") ? j->Attribute("type") : "", -1, -1};
    if (joint.type.empty()) refuse_at(file, j, fmt::format("joint '{}' has no type", joint.name));
    check_joint_type(file, joint);
    joint.parent = joint_link(tree, j, "parent");
    joint.child = joint_link(tree, j, "child");
    if (joint.parent == joint.child) {
      refuse_at(file, j,
                fmt::format("joint '{}' joins link '{}' to itself; expected two links", joint.name,
                            element_name(tree.links[joint.child])));
    }
    const int index = static_cast<int>(tree.joints.size());
    if (const int other = tree.joint_of_child[joint.child]; other >= 0) {
      refuse_at(file, j,
                fmt::format("link '{}' is the child of joint '{}' (line {}) and of joint '{}'; a "
                            "link of a tree has one parent joint (a closed loop is not supported)",
                            element_name(tree.links[joint.child]), tree.joints[other].name,
                            tree.joints[other].element->GetLineNum(), joint.name));
    }
    tree.joint_of_child[joint.child] = index;
    if (joint.parent >= 0) tree.children[joint.parent].push_back(index);
    tree.joints.push_back(std::move(joint));
  }
}

// the link that is no joint's child, or the child of a joint to the world
int root_link(const SdfTree& tree) {
  std::vector<std::string> roots;
  int root = -1;
  for (std::size_t i = 0; i < tree.links.size(); ++i) {
    const int j = tree.joint_of_child[i];
    if (j < 0 || tree.joints[j].parent < 0) {
      roots.push_back(element_name(tree.links[i]));
      root = static_cast<int>(i);
    }
  }
  if (roots.empty()) {
    refuse_at(tree.file, tree.model,
              "every link is the child of a joint: the joints form a loop; expected one root "
              "link that is no joint's child (or the child of a joint to the world)");
  }
  if (roots.size() > 1) {
    refuse_at(tree.file, tree.model,
              fmt::format("{} root links ({}): expected one link that is no joint's child or "
                          "is jointed to the world (SDFormat makes each such link a free body, "
                          "which is not yet read from SDFormat); connect the others with joints",
                          roots.size(), fmt::join(roots, ", ")));
  }
  return root;
}

// The frame named by a pose's or an axis's relative_to/expressed_in, in the model frame:
// the model frame or a link's.
std::optional<Pose> named_frame(const SdfTree& tree, std::string_view name) {
  if (name == kModelFrame) return Pose{};
  const auto it = tree.link_index.find(name);
  if (it == tree.link_index.end()) return std::nullopt;
  return tree.X_ML[it->second];
}

RobotJoint make_joint(const SdfTree& tree, const SdfJoint& j) {
  const std::string& file = tree.file;
  const Pose& X_ML = tree.X_ML[j.child];
  // the joint frame J in the child link's frame L
  const StatedPose stated = pose_of(file, j.element);
  Pose X_LJ = stated.X;
  if (!stated.relative_to.empty()) {
    const auto X_MF = named_frame(tree, stated.relative_to);
    if (!X_MF) {
      refuse_at(file, stated.element,
                fmt::format("joint '{}': <pose relative_to=\"{}\">: expected the name of a link "
                            "or __model__",
                            j.name, stated.relative_to));
    }
    X_LJ = X_ML.inverse() * *X_MF * stated.X;
  }
  RobotJoint joint;
  joint.name = j.name;
  joint.line = j.element->GetLineNum();
  joint.type = j.type == "prismatic" ? RobotJointType::kSlide : RobotJointType::kHinge;
  joint.anchor = X_LJ.p;
  if (!joint.anchor.allFinite()) {
    refuse_at(file, j.element,
              fmt::format("joint '{}': its frame's origin overflows (poses of about 1e308 m); "
                          "expected poses of a robot's size",
                          j.name));
  }
  Eigen::Vector3d xyz = Eigen::Vector3d::UnitZ();  // SDFormat's default axis
  Eigen::Matrix3d R_LE = X_LJ.R;                   // the frame E the axis is expressed in
  if (const XMLElement* axis = j.element->FirstChildElement("axis")) {
    bool in_model = child_bool(file, axis, "use_parent_model_frame", tree.version_minor <= 4);
    if (const XMLElement* x = axis->FirstChildElement("xyz")) {
      const auto v = text_numbers(file, x, 3);
      xyz = Eigen::Vector3d(v[0], v[1], v[2]);
      if (const char* in = x->Attribute("expressed_in"); in != nullptr && *in != '\0') {
        const auto X_MF = named_frame(tree, in);
        if (!X_MF) {
          refuse_at(file, x,
                    fmt::format("joint '{}': <xyz expressed_in=\"{}\">: expected the name of a "
                                "link or __model__",
                                j.name, in));
        }
        in_model = false;
        R_LE = X_ML.R.transpose() * X_MF->R;
      }
    }
    if (in_model) R_LE = X_ML.R.transpose();
    if (!(xyz.stableNorm() > 0)) {
      refuse_at(file, axis,
                fmt::format("joint '{}': <axis><xyz> \"{} {} {}\" has no direction; expected a "
                            "non-zero vector",
                            j.name, xyz.x(), xyz.y(), xyz.z()));
    }
    // <dynamics><friction> is Coulomb friction, a constraint force and not a passive force
    // of the equations of motion: it is not read (as URDF's)
    if (const XMLElement* d = axis->FirstChildElement("dynamics")) {
      joint.damping = child_number(file, d, "damping", 0.0);
      joint.stiffness = child_number(file, d, "spring_stiffness", 0.0);
      joint.springref = child_number(file, d, "spring_reference", 0.0);
      for (const auto& [key, v] :
           {std::pair{"damping", joint.damping}, std::pair{"spring_stiffness", joint.stiffness}}) {
        if (v < 0) {
          refuse_at(file, d->FirstChildElement(key),
                    fmt::format("joint '{}': <{}> {} is negative; expected ≥ 0", j.name, key, v));
        }
      }
    }
  }
  joint.axis = (R_LE * xyz.stableNormalized()).normalized();
  return joint;
}

// the link's <inertial> in its frame; SDFormat's defaults where elements are left out
void set_inertial(const SdfTree& tree, const XMLElement* l, RobotLink& link) {
  const std::string& file = tree.file;
  const auto inertials = children_named(l, "inertial");
  if (inertials.size() > 1) {
    refuse_at(file, inertials[1],
              fmt::format("link '{}' has more than one <inertial>; expected one", link.name));
  }
  link.mass = 1.0;
  link.inertia_com = Eigen::Matrix3d::Identity();
  if (inertials.empty()) return;
  const XMLElement* in = inertials.front();
  if (const XMLElement* added = in->FirstChildElement("fluid_added_mass")) {
    refuse_at(file, added,
              fmt::format("link '{}': <fluid_added_mass> is not part of the equations; expected "
                          "none",
                          link.name));
  }
  const StatedPose pose = pose_of(file, in);
  if (!pose.relative_to.empty() && pose.relative_to != link.name) {
    refuse_at(file, pose.element,
              fmt::format("link '{}': <inertial><pose relative_to=\"{}\">: expected the pose in "
                          "the link frame (no relative_to)",
                          link.name, pose.relative_to));
  }
  link.mass = child_number(file, in, "mass", 1.0);
  Eigen::Matrix3d I_C = Eigen::Matrix3d::Identity();  // about the COM, in the inertial frame C
  if (const XMLElement* i = in->FirstChildElement("inertia")) {
    const double xx = child_number(file, i, "ixx", 1.0), yy = child_number(file, i, "iyy", 1.0),
                 zz = child_number(file, i, "izz", 1.0), xy = child_number(file, i, "ixy", 0.0),
                 xz = child_number(file, i, "ixz", 0.0), yz = child_number(file, i, "iyz", 0.0);
    I_C << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  }
  link.com = pose.X.p;
  link.inertia_com = pose.X.R * I_C * pose.X.R.transpose();
}

// `index` and its subtree, depth first, children in the file order of their joints
void add_link(const SdfTree& tree, int index, int parent, std::vector<RobotLink>& out) {
  const XMLElement* l = tree.links[index];
  RobotLink link;
  link.name = element_name(l);
  link.parent = parent;
  link.line = l->GetLineNum();
  link.file = tree.file;
  // its placement on its parent link (or on the world): X_PL = X_MP⁻¹ X_ML
  const Pose X_PL =
      parent < 0 ? tree.X_WM * tree.X_ML[index]
                 : tree.X_ML[tree.link_index.at(out[parent].name)].inverse() * tree.X_ML[index];
  if (!X_PL.p.allFinite()) {
    refuse_at(tree.file, l,
              fmt::format("link '{}': its placement on its parent overflows (poses of about "
                          "1e308 m); expected poses of a robot's size",
                          link.name));
  }
  link.position = X_PL.p;
  link.rotation = X_PL.R;
  if (const int j = tree.joint_of_child[index]; j >= 0 && tree.joints[j].type != "fixed") {
    link.joints.push_back(make_joint(tree, tree.joints[j]));
  }
  set_inertial(tree, l, link);
  const int self = static_cast<int>(out.size());
  out.push_back(std::move(link));
  for (const int c : tree.children[index]) add_link(tree, tree.joints[c].child, self, out);
}

}  // namespace

RobotModel read_sdf_model(const XMLElement* sdf, const std::string& xml, const std::string& file,
                          const RobotReadOptions& options) {
  RobotModel model;
  model.source = file;
  model.format = InertialFormat::sdf;
  SdfTree tree;
  tree.file = file;
  tree.version_minor = sdf_version_minor(file, sdf);
  tree.model = the_model(file, sdf, model.gravity);
  tree.model_name = element_name(tree.model);
  model.name = tree.model_name;
  refuse_unmodelled(file, tree.model);
  const StatedPose model_pose = pose_of(file, tree.model);
  if (!model_pose.relative_to.empty() && model_pose.relative_to != "world") {
    refuse_at(file, model_pose.element,
              fmt::format("model '{}': <pose relative_to=\"{}\">: expected the pose in the world "
                          "frame (no relative_to)",
                          tree.model_name, model_pose.relative_to));
  }
  tree.X_WM = model_pose.X;
  read_links(tree);
  read_joints(tree);
  add_link(tree, root_link(tree), -1, model.links);
  if (model.links.size() != tree.links.size()) {
    std::vector<std::string> cut;
    for (const auto* l : tree.links) {
      const std::string n = element_name(l);
      if (std::none_of(model.links.begin(), model.links.end(),
                       [&](const RobotLink& k) { return k.name == n; })) {
        cut.push_back(n);
      }
    }
    refuse_at(file, tree.model,
              fmt::format("links {} are not reachable from the root link '{}': their joints "
                          "form a loop; expected a tree",
                          fmt::join(cut, ", "), model.links.front().name));
  }
  if (options.inertia_from_geometry) detail::set_geometry_inertials(xml, file, options, model.links);
  for (const RobotLink& link : model.links) {
    if (link.mass == 0 && link.inertia_com.isZero(0)) continue;  // a massless frame, stated
    if (const auto problem = MassProperties::check(link.mass, link.com, link.inertia_com)) {
      refuse_at(file, tree.links[tree.link_index.at(link.name)],
                fmt::format("link '{}': the inertial is not physical: {}; expected a positive "
                            "mass and a tensor that satisfies the triangle inequality",
                            link.name, *problem));
    }
  }
  return model;
}

}  // namespace rigid::io::detail
