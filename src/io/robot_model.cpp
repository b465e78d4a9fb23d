// Kinematic trees of URDF and MJCF files (include/rigid/io/robot_model.hpp has the
// conventions). URDF: the ROS URDF specification (wiki.ros.org/urdf/XML/joint, /link). MJCF:
// MuJoCo's XML reference ("body", "joint", "default", "compiler", "include"), MuJoCo 2.2's
// compiler being the check (tests/io/robot_model_test.cpp loads the same files in it).
#include "rigid/io/robot_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <utility>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tinyxml2.h>

#include "detail/fix_geometry.hpp"
#include "detail/xml_parse.hpp"
#include "detail/sdf_model.hpp"
#include "detail/xml_numbers.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/io/inertial_fix.hpp"

namespace rigid::io {
namespace {

using tinyxml2::XMLElement;

[[noreturn]] void refuse_at(const std::string& file, const XMLElement* e,
                            const std::string& message) {
  rigid::detail::throw_error_at(SourceLocation{file, e->GetLineNum(), 0}, message);
}

// `expected` numbers of an attribute (finite), or `fallback` when it is absent
std::vector<double> numbers(const std::string& file, const XMLElement* e, const char* attribute,
                            std::size_t expected, std::vector<double> fallback) {
  const char* text = e->Attribute(attribute);
  if (text == nullptr) return fallback;
  detail::XmlNumbers n = detail::read_xml_numbers(
      text, expected, fmt::format("<{}> attribute '{}'", e->Name(), attribute), true);
  if (!n.problem.empty()) refuse_at(file, e, n.problem);
  return std::move(n.values);
}

Eigen::Vector3d vector3(const std::string& file, const XMLElement* e, const char* attribute,
                        const Eigen::Vector3d& fallback) {
  const auto v = numbers(file, e, attribute, 3, {fallback.x(), fallback.y(), fallback.z()});
  return {v[0], v[1], v[2]};
}

// a joint axis as a unit vector; a zero axis has no direction
Eigen::Vector3d unit_axis(const std::string& file, const XMLElement* e, const char* attribute,
                          const Eigen::Vector3d& fallback) {
  const Eigen::Vector3d a = vector3(file, e, attribute, fallback);
  if (!(a.norm() > 0)) {
    refuse_at(file, e,
              fmt::format("<{}> axis \"{} {} {}\" has no direction; expected a "
                          "non-zero vector",
                          e->Name(), a.x(), a.y(), a.z()));
  }
  return a.normalized();
}

std::string element_name(const XMLElement* e) {
  const char* n = e->Attribute("name");
  return n == nullptr ? std::string() : std::string(n);
}

// the stated inertial checked as MassProperties is; a massless link must be massless
void require_valid_inertial(const std::string& file, const XMLElement* at, const RobotLink& link,
                            const char* kind) {
  if (link.mass == 0 && link.inertia_com.isZero(0)) return;
  if (const auto problem = MassProperties::check(link.mass, link.com, link.inertia_com)) {
    refuse_at(file, at,
              fmt::format("{} '{}': the inertial is not physical: {}; expected a "
                          "positive mass and a tensor that satisfies the triangle "
                          "inequality",
                          kind, link.name, *problem));
  }
}

// A ball or free joint is its link's only joint: its velocity's axes are the link's own (the
// frame after every joint of the link, as MuJoCo takes them), which another joint after it
// would turn away.
void require_lone_ball_or_free(const RobotLink& link) {
  if (link.joints.size() < 2) return;
  for (const RobotJoint& j : link.joints) {
    if (j.type != RobotJointType::kBall && j.type != RobotJointType::kFree) continue;
    rigid::detail::throw_error_at(
        SourceLocation{link.file, j.line, 0},
        fmt::format("joint '{}' (type {}) shares body '{}' with {} other joint(s); a ball or "
                    "free joint must be its body's only joint: put the others on a child body",
                    j.name, to_string(j.type), link.name, link.joints.size() - 1));
  }
}

// ---------------------------------------------------------------------------------------------
// URDF

struct UrdfJoint {
  const XMLElement* element = nullptr;
  std::string name, type;
  int parent = -1, child = -1;  // indices of link elements
};

struct UrdfTree {
  std::vector<const XMLElement*> links;  // in file order
  std::map<std::string, int, std::less<>> link_index;
  std::vector<UrdfJoint> joints;           // in file order
  std::vector<int> joint_of_child;         // per link: the joint whose child it is, or -1
  std::vector<std::vector<int>> children;  // per link: joints whose parent it is, file order
};

int urdf_link_of(const UrdfTree& tree, const std::string& file, const XMLElement* joint,
                 const char* role) {
  const XMLElement* e = joint->FirstChildElement(role);
  const char* link = e == nullptr ? nullptr : e->Attribute("link");
  if (link == nullptr) {
    refuse_at(file, joint,
              fmt::format("joint '{}' has no <{} link=\"...\">", element_name(joint), role));
  }
  const auto it = tree.link_index.find(std::string_view(link));
  if (it == tree.link_index.end()) {
    refuse_at(file, e,
              fmt::format("joint '{}': {} link '{}' does not exist; expected one of "
                          "the file's <link> names",
                          element_name(joint), role, link));
  }
  return it->second;
}

void check_urdf_joint_type(const std::string& file, const UrdfJoint& j) {
  const std::string_view t = j.type;
  if (t == "planar") {
    refuse_at(file, j.element,
              fmt::format("joint '{}' type=\"planar\": planar joints are not "
                          "supported; model them as two prismatic joints and "
                          "a revolute one",
                          j.name));
  }
  if (t != "revolute" && t != "continuous" && t != "prismatic" && t != "fixed" &&
      t != "floating") {
    refuse_at(file, j.element,
              fmt::format("joint '{}' type=\"{}\": expected revolute, "
                          "continuous, prismatic, fixed or floating",
                          j.name, t));
  }
  if (j.element->FirstChildElement("mimic") != nullptr) {
    refuse_at(file, j.element->FirstChildElement("mimic"),
              fmt::format("joint '{}' has <mimic>: a mimic joint is a constraint between "
                          "coordinates, not yet supported; remove <mimic> to make it an "
                          "independent joint",
                          j.name));
  }
}

UrdfTree urdf_tree(const XMLElement* robot, const std::string& file) {
  UrdfTree tree;
  for (const auto* l = robot->FirstChildElement("link"); l != nullptr;
       l = l->NextSiblingElement("link")) {
    const std::string name = element_name(l);
    if (name.empty()) refuse_at(file, l, "a <link> has no name");
    const int index = static_cast<int>(tree.links.size());
    if (!tree.link_index.emplace(name, index).second) {
      refuse_at(file, l,
                fmt::format("link '{}' is defined twice (first at line {}); link "
                            "names must be unique",
                            name, tree.links[tree.link_index.at(name)]->GetLineNum()));
    }
    tree.links.push_back(l);
  }
  if (tree.links.empty()) refuse_at(file, robot, "<robot> has no <link>; expected at least one");
  tree.joint_of_child.assign(tree.links.size(), -1);
  tree.children.resize(tree.links.size());
  for (const auto* j = robot->FirstChildElement("joint"); j != nullptr;
       j = j->NextSiblingElement("joint")) {
    UrdfJoint joint{j, element_name(j), j->Attribute("type") ? j->Attribute("type") : "", -1, -1};
    if (joint.type.empty()) refuse_at(file, j, fmt::format("joint '{}' has no type", joint.name));
    check_urdf_joint_type(file, joint);
    joint.parent = urdf_link_of(tree, file, j, "parent");
    joint.child = urdf_link_of(tree, file, j, "child");
    const int index = static_cast<int>(tree.joints.size());
    if (const int other = tree.joint_of_child[joint.child]; other >= 0) {
      refuse_at(file, j,
                fmt::format("link '{}' is the child of joint '{}' (line {}) and of "
                            "joint '{}'; a link of a tree has one parent joint",
                            element_name(tree.links[joint.child]), tree.joints[other].name,
                            tree.joints[other].element->GetLineNum(), joint.name));
    }
    tree.joint_of_child[joint.child] = index;
    tree.children[joint.parent].push_back(index);
    tree.joints.push_back(std::move(joint));
  }
  return tree;
}

int urdf_root(const UrdfTree& tree, const XMLElement* robot, const std::string& file) {
  std::vector<std::string> roots;
  int root = -1;
  for (std::size_t i = 0; i < tree.links.size(); ++i) {
    if (tree.joint_of_child[i] < 0) {
      roots.push_back(element_name(tree.links[i]));
      root = static_cast<int>(i);
    }
  }
  if (roots.empty()) {
    refuse_at(file, robot,
              "every link is the child of a joint: the joints form a loop; "
              "expected one root link that is no joint's child");
  }
  if (roots.size() > 1) {
    refuse_at(file, robot,
              fmt::format("{} root links ({}): expected one link that is no joint's "
                          "child; connect the others with joints",
                          roots.size(), fmt::join(roots, ", ")));
  }
  return root;
}

// the inertials as read_inertials reads them, by the line of their <inertial> element
std::map<int, InertialEntry> urdf_inertials(const std::string& xml, const std::string& file) {
  std::map<int, InertialEntry> out;
  for (auto& e : read_inertials(xml, file)) out.emplace(e.line, std::move(e));
  return out;
}

void set_urdf_inertial(const XMLElement* l, const std::map<int, InertialEntry>& inertials,
                       const std::string& file, RobotLink& link) {
  const XMLElement* in = l->FirstChildElement("inertial");
  if (in == nullptr) return;  // a frame only: mass 0
  if (const auto* again = in->NextSiblingElement("inertial")) {
    refuse_at(file, again,
              fmt::format("link '{}' has more than one <inertial>; expected one", link.name));
  }
  const auto it = inertials.find(in->GetLineNum());
  if (it == inertials.end() || it->second.name != link.name) {
    refuse_at(file, in,
              fmt::format("link '{}': its <inertial> shares a line with another; "
                          "expected one element per line",
                          link.name));
  }
  const InertialEntry& e = it->second;
  if (e.mass == 0 && e.inertia_com.isZero(0)) return;  // a massless frame, stated
  if (e.problem) {
    refuse_at(file, in,
              fmt::format("link '{}': the inertial is not usable: {}", link.name, *e.problem));
  }
  link.mass = e.mass;
  link.com = e.com;
  link.inertia_com = e.inertia_com;
}

RobotJoint urdf_joint(const UrdfJoint& j, const std::string& file) {
  RobotJoint joint;
  joint.name = j.name;
  joint.line = j.element->GetLineNum();
  joint.type = j.type == "prismatic" ? RobotJointType::kSlide : RobotJointType::kHinge;
  if (const auto* axis = j.element->FirstChildElement("axis")) {
    joint.axis = unit_axis(file, axis, "xyz", Eigen::Vector3d::UnitX());
  } else {
    joint.axis = Eigen::Vector3d::UnitX();  // URDF's default axis
  }
  // <dynamics friction> is Coulomb friction, a constraint force and not a passive force of
  // the equations of motion: it is not read
  if (const auto* dynamics = j.element->FirstChildElement("dynamics")) {
    joint.damping = numbers(file, dynamics, "damping", 1, {0.0})[0];
    if (joint.damping < 0) {
      refuse_at(file, dynamics,
                fmt::format("joint '{}': damping {} is negative; expected ≥ 0 "
                            "(N·m·s/rad or N·s/m)",
                            j.name, joint.damping));
    }
  }
  return joint;
}

void add_urdf_link(const UrdfTree& tree, int index, int parent, const std::string& file,
                   const std::map<int, InertialEntry>& inertials, const RobotReadOptions& options,
                   std::vector<RobotLink>& out) {
  const XMLElement* l = tree.links[index];
  RobotLink link;
  link.name = element_name(l);
  link.parent = parent;
  link.line = l->GetLineNum();
  link.file = file;
  if (const int j = tree.joint_of_child[index]; j >= 0) {
    const UrdfJoint& joint = tree.joints[j];
    if (const auto* origin = joint.element->FirstChildElement("origin")) {
      link.position = vector3(file, origin, "xyz", Eigen::Vector3d::Zero());
      link.rotation = rotation_from_rpy(vector3(file, origin, "rpy", Eigen::Vector3d::Zero()));
    }
    if (joint.type == "floating") {
      // URDF has no world link: a floating joint from the root link (out[0], at the world's
      // origin) is the child's free joint in the world, the child a root of its own
      if (parent != 0) {
        refuse_at(file, joint.element,
                  fmt::format("joint '{}' type=\"floating\": a floating joint is read as a free "
                              "joint only from the root link '{}' (which stands for the world); "
                              "its parent '{}' is not the root",
                              joint.name, out.front().name,
                              out[static_cast<std::size_t>(parent)].name));
      }
      if (!options.pin_free_root) {
        RobotJoint free = urdf_joint(joint, file);
        free.type = RobotJointType::kFree;
        free.axis = Eigen::Vector3d::UnitZ();
        link.joints.push_back(std::move(free));
        link.parent = -1;
      }
    } else if (joint.type != "fixed") {
      link.joints.push_back(urdf_joint(joint, file));
    }
  }
  set_urdf_inertial(l, inertials, file, link);
  const int self = static_cast<int>(out.size());
  out.push_back(std::move(link));
  for (const int c : tree.children[index]) {
    add_urdf_link(tree, tree.joints[c].child, self, file, inertials, options, out);
  }
}

RobotModel read_urdf(const XMLElement* robot, const std::string& xml, const std::string& file,
                     const RobotReadOptions& options) {
  RobotModel model;
  model.source = file;
  model.format = InertialFormat::urdf;
  model.name = element_name(robot);
  const UrdfTree tree = urdf_tree(robot, file);
  const int root = urdf_root(tree, robot, file);
  add_urdf_link(tree, root, -1, file, urdf_inertials(xml, file), options, model.links);
  if (model.links.size() != tree.links.size()) {
    std::vector<std::string> cut;
    for (const auto* l : tree.links) {
      const std::string n = element_name(l);
      if (std::none_of(model.links.begin(), model.links.end(),
                       [&](const RobotLink& k) { return k.name == n; })) {
        cut.push_back(n);
      }
    }
    refuse_at(file, robot,
              fmt::format("links {} are not reachable from the root link '{}': "
                          "their joints form a loop; expected a tree",
                          fmt::join(cut, ", "), model.links.front().name));
  }
  if (options.inertia_from_geometry) detail::set_geometry_inertials(xml, file, options, model.links);
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    require_valid_inertial(file, tree.links[tree.link_index.at(model.links[i].name)],
                           model.links[i], "link");
  }
  return model;
}

// ---------------------------------------------------------------------------------------------
// MJCF

struct Mjcf {
  const detail::MjcfDocument& doc;
  detail::MjcfCompiler compiler;
  detail::MjcfDefaults defaults;
  std::map<const XMLElement*, const detail::LinkGeometry*> geometry;
  const RobotReadOptions& options;
};

// `count` numbers of a joint's attribute: its own, else its class's (MuJoCo's defaults); empty
// when neither gives it
std::vector<double> mjcf_numbers(const Mjcf& m, const XMLElement* e, const detail::MjcfAttributes& def,
                                 const char* key, std::size_t count) {
  const char* text = e->Attribute(key);
  if (text == nullptr) {
    const auto it = def.find(key);
    if (it == def.end()) return {};
    text = it->second.c_str();
  }
  detail::XmlNumbers n =
      detail::read_xml_numbers(text, count, fmt::format("<{}> attribute '{}'", e->Name(), key), true);
  if (!n.problem.empty()) m.doc.refuse(e, n.problem);
  return n.values;
}

double mjcf_scalar(const Mjcf& m, const XMLElement* e, const detail::MjcfAttributes& def,
                   const char* key, double fallback) {
  const std::vector<double> v = mjcf_numbers(m, e, def, key, 1);
  return v.empty() ? fallback : v[0];
}

Eigen::Vector3d mjcf_vector(const Mjcf& m, const XMLElement* e, const detail::MjcfAttributes& def,
                            const char* key, const Eigen::Vector3d& fallback) {
  const std::vector<double> v = mjcf_numbers(m, e, def, key, 3);
  return v.empty() ? fallback : Eigen::Vector3d(v[0], v[1], v[2]);
}

const detail::MjcfAttributes& joint_class(const Mjcf& m, const XMLElement* j,
                                          const std::string& childclass) {
  const char* own = j->Attribute("class");
  const std::string cls = own != nullptr ? own : childclass;
  const auto it = m.defaults.joint.find(cls);
  if (it == m.defaults.joint.end()) {
    m.doc.refuse(j, fmt::format("joint '{}': unknown default class '{}'", element_name(j), cls));
  }
  return it->second;
}

// a joint of a body; nullopt for a free joint welded by pin_free_root
std::optional<RobotJoint> mjcf_joint(const Mjcf& m, const XMLElement* j,
                                     const std::string& childclass, bool world_child) {
  static const detail::MjcfAttributes kNone;
  const bool free_element = std::string_view(j->Name()) == "freejoint";
  const detail::MjcfAttributes& def = free_element ? kNone : joint_class(m, j, childclass);
  const char* type_text = j->Attribute("type");
  if (type_text == nullptr && def.count("type") != 0) type_text = def.at("type").c_str();
  const std::string type = free_element ? "free" : (type_text ? type_text : "hinge");
  const std::string name = element_name(j);
  if (type == "free" && world_child && m.options.pin_free_root) return std::nullopt;
  if (type == "free" && !world_child) {
    m.doc.refuse(j, fmt::format("joint '{}' (type free): a free joint must be on a body of the "
                                "world (MuJoCo's rule: its state is the body's world pose); "
                                "this body has a parent body; use a ball joint there",
                                name));
  }
  if (type != "hinge" && type != "slide" && type != "ball" && type != "free") {
    m.doc.refuse(
        j, fmt::format("joint '{}' type=\"{}\": expected hinge, slide, ball or free", name, type));
  }
  RobotJoint joint;
  joint.name = name;
  joint.line = j->GetLineNum();
  joint.type = type == "slide"  ? RobotJointType::kSlide
               : type == "ball" ? RobotJointType::kBall
               : type == "free" ? RobotJointType::kFree
                                : RobotJointType::kHinge;
  // a free joint's pos is unused (MuJoCo's: it places the body, about the body's origin)
  if (joint.type != RobotJointType::kFree) {
    joint.anchor = mjcf_vector(m, j, def, "pos", Eigen::Vector3d::Zero());
  }
  joint.axis = mjcf_vector(m, j, def, "axis", Eigen::Vector3d::UnitZ());
  if (!(joint.axis.norm() > 0)) {
    m.doc.refuse(j, fmt::format("joint '{}': axis has no direction; expected a non-zero "
                                "vector",
                                name));
  }
  joint.axis.normalize();
  // MuJoCo's XML reference: the ref and springref of hinge joints are angles in the unit of
  // <compiler angle> (degree by default); a slide's are lengths
  const double unit =
      joint.type == RobotJointType::kHinge && m.compiler.degrees ? std::numbers::pi / 180.0 : 1.0;
  if (joint.type == RobotJointType::kHinge || joint.type == RobotJointType::kSlide) {
    // a ball's or free joint's ref and springref are not used (MuJoCo's: their reference is
    // the identity, or the body's placement)
    joint.ref = unit * mjcf_scalar(m, j, def, "ref", 0.0);
    joint.springref = unit * mjcf_scalar(m, j, def, "springref", 0.0);
  }
  joint.damping = mjcf_scalar(m, j, def, "damping", 0.0);
  joint.stiffness = mjcf_scalar(m, j, def, "stiffness", 0.0);
  joint.armature = mjcf_scalar(m, j, def, "armature", 0.0);
  for (const auto& [key, v] :
       {std::pair{"damping", joint.damping}, std::pair{"stiffness", joint.stiffness},
        std::pair{"armature", joint.armature}}) {
    if (v < 0) {
      m.doc.refuse(j, fmt::format("joint '{}': {} {} is negative; expected ≥ 0", name, key, v));
    }
  }
  return joint;
}

// an <inertial> as MuJoCo reads it: pos, an orientation, mass, diaginertia or fullinertia
void read_mjcf_inertial(const Mjcf& m, const XMLElement* in, RobotLink& link) {
  static const detail::MjcfAttributes kNone;
  if (in->Attribute("pos") == nullptr) {
    m.doc.refuse(in,
                 fmt::format("body '{}': <inertial> has no 'pos' (MuJoCo requires it)", link.name));
  }
  link.com = mjcf_vector(m, in, kNone, "pos", Eigen::Vector3d::Zero());
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  try {
    R = detail::mjcf_orientation(in, m.compiler).value_or(R);
  } catch (const detail::GeometryProblem& p) {
    m.doc.refuse(in, fmt::format("body '{}': <inertial>: {}", link.name, p.text));
  }
  if (in->Attribute("mass") == nullptr) {
    m.doc.refuse(in, fmt::format("body '{}': <inertial> has no 'mass'", link.name));
  }
  link.mass = mjcf_scalar(m, in, kNone, "mass", 0.0);
  const char* diag = in->Attribute("diaginertia");
  const char* full = in->Attribute("fullinertia");
  if ((diag == nullptr) == (full == nullptr)) {
    m.doc.refuse(in, fmt::format("body '{}': <inertial> needs exactly one of 'diaginertia' and "
                                 "'fullinertia'",
                                 link.name));
  }
  Eigen::Matrix3d I;
  if (diag != nullptr) {
    I = mjcf_vector(m, in, kNone, "diaginertia", Eigen::Vector3d::Zero()).asDiagonal();
  } else {
    // MJCF order: xx yy zz xy xz yz
    detail::XmlNumbers n =
        detail::read_xml_numbers(full, 6, "<inertial> attribute 'fullinertia'", true);
    if (!n.problem.empty()) m.doc.refuse(in, n.problem);
    const auto& v = n.values;
    I << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  }
  link.inertia_com = R * I * R.transpose();
}

// MuJoCo's compiler: a body's own <inertial> with inertiafromgeom "auto" (the default) or
// "false"; its geoms with "true", or with "auto" when it has no <inertial>
void set_mjcf_inertial(const Mjcf& m, const XMLElement* b, RobotLink& link) {
  const auto inertials = m.doc.children(b, "inertial");
  if (inertials.size() > 1) {
    m.doc.refuse(inertials[1], fmt::format("body '{}' has more than one <inertial>", link.name));
  }
  const std::string& rule = m.compiler.inertiafromgeom;
  const bool from_geoms =
      m.options.inertia_from_geometry || rule == "true" || (rule == "auto" && inertials.empty());
  if (!from_geoms) {
    if (!inertials.empty()) read_mjcf_inertial(m, inertials.front(), link);
    return;
  }
  const detail::LinkGeometry& g = *m.geometry.at(b);
  if (!g.errors.empty()) {
    m.doc.refuse(b, fmt::format("body '{}': its inertial cannot be computed from its geoms: {}",
                                link.name, fmt::join(g.errors, "; ")));
  }
  if (g.parts.empty()) return;  // no geom with mass: a frame only
  const MassProperties mp = combine(g.parts);
  link.mass = mp.mass();
  link.com = mp.com();
  link.inertia_com = mp.inertia_com();
}

void add_mjcf_body(const Mjcf& m, const XMLElement* b, int parent, const std::string& childclass,
                   std::vector<RobotLink>& out) {
  static const detail::MjcfAttributes kNone;
  RobotLink link;
  link.name = element_name(b);
  link.parent = parent;
  link.line = b->GetLineNum();
  link.file = m.doc.file_of(b);
  const char* cc = b->Attribute("childclass");
  const std::string cls = cc != nullptr ? cc : childclass;
  link.position = mjcf_vector(m, b, kNone, "pos", Eigen::Vector3d::Zero());
  try {
    link.rotation = detail::mjcf_orientation(b, m.compiler).value_or(link.rotation);
  } catch (const detail::GeometryProblem& p) {
    m.doc.refuse(b, fmt::format("body '{}': {}", link.name, p.text));
  }
  for (const auto* c : m.doc.children(b)) {
    const std::string_view n = c->Name();
    if (n != "joint" && n != "freejoint") continue;
    if (auto joint = mjcf_joint(m, c, cls, parent < 0)) link.joints.push_back(std::move(*joint));
  }
  require_lone_ball_or_free(link);
  set_mjcf_inertial(m, b, link);
  require_valid_inertial(link.file, b, link, "body");
  const int self = static_cast<int>(out.size());
  out.push_back(std::move(link));
  for (const auto* c : m.doc.children(b, "body")) add_mjcf_body(m, c, self, cls, out);
}

// What MuJoCo adds to a tree's equations that a tree of links and joints does not say: the
// constraints of <equality> (closed loops, coupled joints), a tendon's spring and damper, the
// medium's drag. Refused by name rather than left out of M q̈ = τ + f.
void refuse_unmodelled(const Mjcf& m, const XMLElement* root) {
  static const detail::MjcfAttributes kNone;
  for (const auto* eq : m.doc.children(root, "equality")) {
    for (const auto* c = eq->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
      m.doc.refuse(c, fmt::format("<equality><{}>: closed loops and coupled joints are not yet "
                                  "supported; a tree's equations would leave the constraint out",
                                  c->Name()));
    }
  }
  for (const auto* tendons : m.doc.children(root, "tendon")) {
    for (const auto* t = tendons->FirstChildElement(); t != nullptr; t = t->NextSiblingElement()) {
      for (const char* key : {"stiffness", "damping"}) {
        if (mjcf_scalar(m, t, kNone, key, 0) != 0) {
          m.doc.refuse(t, fmt::format("<tendon><{}> with {}: a tendon's passive force is not yet "
                                      "part of the equations; expected no stiffness and damping",
                                      t->Name(), key));
        }
      }
    }
  }
  for (const auto* o : m.doc.children(root, "option")) {
    for (const char* key : {"density", "viscosity"}) {
      if (mjcf_scalar(m, o, kNone, key, 0) != 0) {
        m.doc.refuse(o, fmt::format("<option {}>: the medium's drag on the bodies is not part of "
                                    "the equations; expected 0",
                                    key));
      }
    }
  }
}

RobotModel read_mjcf(const XMLElement* root, const std::string& file,
                     const RobotReadOptions& options) {
  const detail::MjcfDocument doc(root, file, true);
  const std::vector<detail::LinkGeometry> geometry = detail::mjcf_links(doc);
  Mjcf m{doc, detail::read_mjcf_compiler(doc), detail::read_mjcf_defaults(doc), {}, options};
  for (const auto& g : geometry) m.geometry[g.element] = &g;
  RobotModel model;
  model.source = file;
  model.format = InertialFormat::mjcf;
  if (const char* n = root->Attribute("model")) model.name = n;
  refuse_unmodelled(m, root);
  static const detail::MjcfAttributes kNone;
  for (const auto* o : doc.children(root, "option")) {
    model.gravity = mjcf_vector(m, o, kNone, "gravity", model.gravity);
  }
  for (const auto* w : doc.children(root, "worldbody")) {
    for (const auto* b : doc.children(w, "body")) add_mjcf_body(m, b, -1, "main", model.links);
  }
  return model;
}

}  // namespace

const char* to_string(RobotJointType type) {
  switch (type) {
    case RobotJointType::kHinge:
      return "hinge";
    case RobotJointType::kSlide:
      return "slide";
    case RobotJointType::kBall:
      return "ball";
    case RobotJointType::kFree:
      return "free";
  }
  return "?";
}

int position_count(RobotJointType type) {
  return type == RobotJointType::kFree ? 7 : type == RobotJointType::kBall ? 4 : 1;
}

int velocity_count(RobotJointType type) {
  return type == RobotJointType::kFree ? 6 : type == RobotJointType::kBall ? 3 : 1;
}

std::size_t RobotModel::nq() const {
  std::size_t n = 0;
  for (const auto& l : links) {
    for (const auto& j : l.joints) n += static_cast<std::size_t>(position_count(j.type));
  }
  return n;
}

std::size_t RobotModel::nv() const {
  std::size_t n = 0;
  for (const auto& l : links) {
    for (const auto& j : l.joints) n += static_cast<std::size_t>(velocity_count(j.type));
  }
  return n;
}

bool RobotModel::has_ball_or_free_joint() const {
  for (const auto& l : links) {
    for (const auto& j : l.joints) {
      if (j.type == RobotJointType::kBall || j.type == RobotJointType::kFree) return true;
    }
  }
  return false;
}

std::vector<std::string> RobotModel::coordinate_names() const {
  std::vector<std::string> out;
  for (const auto& l : links) {
    for (const auto& j : l.joints) {
      if (j.type == RobotJointType::kFree) {
        for (const char* s : {"x", "y", "z"}) out.push_back(fmt::format("{}_{}", j.name, s));
      }
      if (j.type == RobotJointType::kFree || j.type == RobotJointType::kBall) {
        for (const char* s : {"qw", "qx", "qy", "qz"}) {
          out.push_back(fmt::format("{}_{}", j.name, s));
        }
      } else {
        out.push_back(j.name);
      }
    }
  }
  return out;
}

std::vector<std::string> RobotModel::velocity_names() const {
  std::vector<std::string> out;
  for (const auto& l : links) {
    for (const auto& j : l.joints) {
      if (j.type == RobotJointType::kFree) {
        for (const char* s : {"vx", "vy", "vz"}) out.push_back(fmt::format("{}_{}", j.name, s));
      }
      if (j.type == RobotJointType::kFree || j.type == RobotJointType::kBall) {
        for (const char* s : {"wx", "wy", "wz"}) out.push_back(fmt::format("{}_{}", j.name, s));
      } else {
        out.push_back(j.name);
      }
    }
  }
  return out;
}

RobotModel read_robot_model(const std::string& xml, const std::string& source,
                            const RobotReadOptions& options) {
  tinyxml2::XMLDocument doc;
  detail::parse_xml(doc, xml, source);
  const XMLElement* root = doc.RootElement();
  const std::string_view name = root->Name();
  if (name == "robot") return read_urdf(root, xml, source, options);
  if (name == "mujoco") return read_mjcf(root, source, options);
  if (name == "sdf") return detail::read_sdf_model(root, xml, source, options);  // sdf_model.cpp
  refuse_at(source, root,
            fmt::format("root element <{}>: expected <robot> (URDF), <mujoco> (MJCF) or <sdf> "
                        "(SDFormat)",
                        name));
}

RobotModel read_robot_model_file(const std::string& path, const RobotReadOptions& options) {
  return read_robot_model(detail::read_model_file(path), path, options);
}

namespace detail {

// (declared in detail/sdf_model.hpp)
void set_geometry_inertials(const std::string& xml, const std::string& file,
                            const RobotReadOptions& options, std::vector<RobotLink>& links) {
  RIGID_REQUIRE_AS("read_robot_model", options.density > 0 && std::isfinite(options.density),
                   "density must be positive and finite, got {} kg/m³", options.density);
  InertialFixOptions fix;
  fix.density = options.density;
  const InertialFixResult r = fix_inertials(xml, file, fix);
  r.require_ok();
  for (const auto& f : r.links) {
    if (!f.fixed) continue;
    for (auto& link : links) {
      if (link.name != f.name) continue;
      link.mass = f.fixed->mass();
      link.com = f.fixed->com();
      link.inertia_com = f.fixed->inertia_com();
    }
  }
}

}  // namespace detail

}  // namespace rigid::io
