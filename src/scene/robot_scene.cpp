#include "rigid/scene/robot_scene.hpp"

#include <cctype>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"

namespace rigid::scene {

namespace {

// A rigid transform x ↦ R x + p.
struct Transform {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  [[nodiscard]] Transform operator*(const Transform& o) const { return {R * o.R, R * o.p + p}; }
};

// A moving body of the scene before it is written out: the link it stands for, its parent
// body (−1: the world), its placement in the parent's frame, its joints (each in the frame left
// by the ones before it) and its inertial in its own frame.
struct TreeBody {
  std::size_t link = 0;
  int parent = -1;
  Transform placement;
  std::vector<io::RobotJoint> joints;
  double mass = 0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();    // m c (kg·m)
  Eigen::Matrix3d inertia_origin = Eigen::Matrix3d::Zero();  // about the body origin
  bool merged_away = false;
};

// Adds an inertial given in a frame placed by X in the body's frame.
void add_inertial(TreeBody& b, const io::RobotLink& link, const Transform& X) {
  if (link.mass == 0) return;
  const Eigen::Vector3d c = X.R * link.com + X.p;
  const Eigen::Matrix3d I_c = X.R * link.inertia_com * X.R.transpose();
  // parallel axes: I_O = I_C + m (|c|² 1 − c cᵀ)
  b.inertia_origin +=
      I_c + link.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  b.first_moment += link.mass * c;
  b.mass += link.mass;
}

std::string number_text(double v) { return fmt::format("{}", v); }

Expression text(std::string t, const SourceLocation& where) {
  return Expression{std::move(t), where, std::nullopt, true};
}

SourceLocation where_of(const io::RobotModel& model, const io::RobotLink& link, int line) {
  return SourceLocation{link.file.empty() ? model.source : link.file, line, 0};
}

// The moving bodies: links with joints; welded links merged into the body they hang from (or
// dropped when they hang from the world).
std::vector<TreeBody> moving_bodies(const io::RobotModel& model) {
  std::vector<TreeBody> bodies;
  // per link: the body it belongs to (−1: the world) and its frame in that body's frame
  std::vector<int> owner(model.links.size(), -1);
  std::vector<Transform> in_owner(model.links.size());
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const io::RobotLink& link = model.links[i];
    const Transform placement{link.rotation, link.position};
    const int up = link.parent >= 0 ? owner[static_cast<std::size_t>(link.parent)] : -1;
    const Transform up_frame =
        link.parent >= 0 ? in_owner[static_cast<std::size_t>(link.parent)] : Transform{};
    if (link.joints.empty()) {
      owner[i] = up;
      in_owner[i] = up_frame * placement;
      if (up >= 0) add_inertial(bodies[static_cast<std::size_t>(up)], link, in_owner[i]);
      continue;
    }
    TreeBody b;
    b.link = i;
    b.parent = up;
    b.placement = up_frame * placement;
    b.joints = link.joints;
    add_inertial(b, link, Transform{});
    owner[i] = static_cast<int>(bodies.size());
    bodies.push_back(std::move(b));
  }
  return bodies;
}

// P⁻¹ J P for a joint J given in the frame before P: the same motion, described in the frame
// after P (a turn's axis and anchor, a slide's axis).
io::RobotJoint conjugate(io::RobotJoint j, const Transform& P) {
  j.axis = P.R.transpose() * j.axis;
  j.anchor = P.R.transpose() * (j.anchor - P.p);
  return j;
}

// A massless moving body carrying exactly one moving body is merged into it: T = P_B J_B P_C
// J_C = (P_B P_C) (P_C⁻¹ J_B P_C) J_C. Others are refused: their joints would move nothing.
void merge_massless(const io::RobotModel& model, std::vector<TreeBody>& bodies) {
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].mass > 0) continue;
    std::vector<std::size_t> children;
    for (std::size_t c = b + 1; c < bodies.size(); ++c) {
      if (bodies[c].parent == static_cast<int>(b)) children.push_back(c);
    }
    const io::RobotLink& link = model.links[bodies[b].link];
    if (children.size() != 1) {
      rigid::detail::throw_error_at(
          where_of(model, link, link.line),
          fmt::format("link '{}' has joints but no mass, and carries {} moving links; a massless "
                      "link between joints is supported when it carries exactly one (give it an "
                      "<inertial>)",
                      link.name, children.size()));
    }
    for (const io::RobotJoint& j : bodies[b].joints) {
      if (j.type == io::RobotJointType::kBall || j.type == io::RobotJointType::kFree) {
        rigid::detail::throw_error_at(
            where_of(model, link, j.line),
            fmt::format("joint '{}' ({}) turns link '{}', which has no mass: a ball or free joint "
                        "turns a link with an <inertial> (its quaternion is the link's orientation)",
                        j.name, j.type == io::RobotJointType::kBall ? "ball" : "free", link.name));
      }
    }
    TreeBody& child = bodies[children.front()];
    std::vector<io::RobotJoint> joints;
    for (const io::RobotJoint& j : bodies[b].joints) {
      joints.push_back(conjugate(j, child.placement));
    }
    joints.insert(joints.end(), child.joints.begin(), child.joints.end());
    child.joints = std::move(joints);
    child.placement = bodies[b].placement * child.placement;
    child.parent = bodies[b].parent;
    bodies[b].merged_away = true;
  }
}

// The name of a free joint's slide k (along the world's x, y, z): j_x, j_y, j_z.
std::string free_part(const io::RobotJoint& j, std::size_t k) {
  constexpr std::array<const char*, 3> kAxes{"x", "y", "z"};
  return j.name + "_" + kAxes[k];
}

// q − ref as an expression of the coordinate
std::string joint_amount(const io::RobotJoint& j) {
  return j.ref == 0 ? j.name : fmt::format("{} - ({})", j.name, number_text(j.ref));
}

// `name` made an identifier: a character other than a letter, a digit or '_' becomes '_', a
// leading digit gains "n_"
std::string identifier(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  }
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name.front()))) name = "n_" + name;
  return name;
}

// The body's mass property `value` as written in the scene: the number, or with
// `symbolic_inertia` the parameter `name` holding it (added to the scene's parameters).
Expression mass_property(Scene& s, bool symbolic_inertia, const std::string& name, double value,
                         const SourceLocation& where) {
  if (!symbolic_inertia) return Expression::of(value, where);
  s.parameters.push_back(Parameter{name, Expression::of(value, where)});
  return text(name, where);
}

Body scene_body(const io::RobotModel& model, const std::vector<TreeBody>& bodies,
                const TreeBody& b, bool symbolic_inertia, Scene& s) {
  const io::RobotLink& link = model.links[b.link];
  const SourceLocation where = where_of(model, link, link.line);
  Body out;
  out.name = link.name;
  out.where = where;
  if (b.parent >= 0) out.parent = model.links[bodies[static_cast<std::size_t>(b.parent)].link].name;
  for (std::size_t k = 0; k < 3; ++k)
    out.position[k] = Expression::of(b.placement.p(static_cast<Eigen::Index>(k)), where);
  if (!b.placement.R.isIdentity(0.0)) {
    // entries of a quarter turn written as 1.5707963267948966 rad are ±1 and 6e-17: the latter
    // are the rounding of the file's angle, and kept they would fill M(q) with terms of 1e-17
    std::array<double, 9> O{};
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        const double v = b.placement.R(i, k);
        O[static_cast<std::size_t>(3 * i + k)] = std::abs(v) < 1e-15 ? 0.0 : v;
      }
    }
    out.orientation = O;
  }
  for (const io::RobotJoint& j : b.joints) {
    const SourceLocation jw = where_of(model, link, j.line);
    if (j.type == io::RobotJointType::kFree) {
      // three slides along the world's axes, then a ball about the link's origin: MuJoCo's
      // qpos (position, quaternion) and qvel (the origin's world velocity, then ω in the link
      // frame); the link's placement is the free joint's initial value, not a constant
      for (std::size_t k = 0; k < 3; ++k) {
        Joint slide;
        slide.kind = Joint::Kind::kSlide;
        slide.axis = {k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
        slide.amount = text(free_part(j, k), jw);
        slide.where = jw;
        out.joints.push_back(std::move(slide));
      }
      for (std::size_t k = 0; k < 3; ++k) out.position[k] = Expression::of(0, where);
      out.orientation.reset();
    }
    Joint joint;
    joint.kind = j.type == io::RobotJointType::kHinge   ? Joint::Kind::kTurn
                 : j.type == io::RobotJointType::kSlide ? Joint::Kind::kSlide
                                                        : Joint::Kind::kBall;
    joint.axis = {j.axis.x(), j.axis.y(), j.axis.z()};
    joint.anchor = {j.anchor.x(), j.anchor.y(), j.anchor.z()};
    if (j.type == io::RobotJointType::kFree) joint.anchor = {0, 0, 0};
    joint.amount = text(joint.kind == Joint::Kind::kBall ? j.name : joint_amount(j), jw);
    joint.where = jw;
    out.joints.push_back(std::move(joint));
  }
  // the inertial about the COM, from the sums about the body origin
  MassSpec& m = out.mass;
  m.kind = MassSpec::Kind::kExplicit;
  m.where = where;
  const std::string id = identifier(link.name);
  m.mass = mass_property(s, symbolic_inertia, "m_" + id, b.mass, where);
  const Eigen::Vector3d c = b.first_moment / b.mass;
  const Eigen::Matrix3d I_c =
      b.inertia_origin -
      b.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  constexpr std::array<const char*, 3> kAxes{"x", "y", "z"};
  for (std::size_t k = 0; k < 3; ++k) {
    m.com[k] = mass_property(s, symbolic_inertia, fmt::format("com_{}_{}", id, kAxes[k]),
                             c(static_cast<Eigen::Index>(k)), where);
  }
  constexpr std::array<std::array<int, 2>, 6> kElements{
      {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};
  for (std::size_t k = 0; k < 6; ++k) {
    const auto [row, col] = kElements[k];
    m.inertia[k] = mass_property(
        s, symbolic_inertia,
        fmt::format("I_{}_{}{}", id, kAxes[static_cast<std::size_t>(row)], kAxes[static_cast<std::size_t>(col)]),
        I_c(row, col), where);
  }
  return out;
}

// The joints' passive terms: damping as forces, stiffness as potentials, armature in L.
void add_passive_terms(const io::RobotModel& model, Scene& s) {
  std::string armature;
  auto add_armature = [&](double a, const std::string& velocity) {
    armature += fmt::format("{}{}/2*{}^2", armature.empty() ? "" : " + ", number_text(a), velocity);
  };
  for (const io::RobotLink& link : model.links) {
    for (const io::RobotJoint& j : link.joints) {
      const SourceLocation where = where_of(model, link, j.line);
      // the velocities a joint moves: a hinge's or slide's q̇; a ball's ω (named b_wx …, a force
      // on it by that name); a free joint's slides, then its ball
      std::vector<std::pair<std::string, std::string>> velocities;  // (force target, velocity)
      if (j.type == io::RobotJointType::kFree) {
        for (std::size_t k = 0; k < 3; ++k) velocities.emplace_back(free_part(j, k), free_part(j, k) + "_dot");
      }
      if (j.type == io::RobotJointType::kFree || j.type == io::RobotJointType::kBall) {
        for (const char* w : {"_wx", "_wy", "_wz"}) velocities.emplace_back(j.name + w, j.name + w);
      } else {
        velocities.emplace_back(j.name, j.name + "_dot");
      }
      for (const auto& [target, velocity] : velocities) {
        if (j.damping != 0) {
          s.forces.push_back({target, text(fmt::format("-{}*{}", number_text(j.damping), velocity), where)});
        }
        if (j.armature != 0) add_armature(j.armature, velocity);
      }
      // (a ball's or free joint's stiffness is refused where its coordinates are made)
      if (j.stiffness != 0 && j.type != io::RobotJointType::kFree && j.type != io::RobotJointType::kBall) {
        const std::string rest =
            j.springref == 0 ? j.name : fmt::format("{} - ({})", j.name, number_text(j.springref));
        s.potentials.push_back(
            {j.name + "_spring",
             text(fmt::format("{}/2*({})^2", number_text(j.stiffness), rest), where)});
      }
    }
  }
  if (!armature.empty()) s.lagrangian = text(armature, SourceLocation{model.source, 0, 0});
}

// A coordinate's name is its joint's, usable in expressions: an unnamed joint (MJCF allows
// them) is q<i> (its index), and a character other than a letter, a digit or '_' becomes '_'
// ("r-hip.x" → "r_hip_x"; a leading digit gains "q_"). Two joints whose names become one are
// refused, naming both.
io::RobotModel with_coordinate_names(io::RobotModel model) {
  std::map<std::string, std::pair<std::string, int>, std::less<>> taken;  // → the file's name, line
  std::size_t index = 0;
  for (io::RobotLink& link : model.links) {
    for (io::RobotJoint& j : link.joints) {
      std::string name = j.name.empty() ? fmt::format("q{}", index) : j.name;
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
      }
      if (std::isdigit(static_cast<unsigned char>(name.front()))) name = "q_" + name;
      if (const auto it = taken.find(name); it != taken.end()) {
        rigid::detail::throw_error_at(
            where_of(model, link, j.line),
            fmt::format("joint '{}' would be the coordinate '{}', the name of the joint '{}' (line "
                        "{}); give the joints names of letters, digits and '_' that differ",
                        j.name, name, it->second.first, it->second.second));
      }
      taken.emplace(name, std::make_pair(j.name, j.line));
      j.name = name;
      ++index;
    }
  }
  return model;
}

}  // namespace

bool looks_like_xml(std::string_view t) {
  const std::size_t first = t.find_first_not_of(" \t\r\n\xef\xbb\xbf");
  return first != std::string_view::npos && t[first] == '<';
}

io::RobotReadOptions robot_read_options(const ModelOptions& options,
                                        const std::filesystem::path& file) {
  io::RobotReadOptions ro;
  ro.pin_free_root = options.pin_free_root.value_or(false);
  ro.inertia_from_geometry = options.inertia_from_geometry.value_or(false);
  if (options.density) {
    const double rho = *options.density;
    if (!(std::isfinite(rho) && rho > 0)) {
      throw Error(fmt::format("{}: density {} kg/m³ is not a density; expected a finite number > 0 "
                              "(kg/m³)",
                              file.string(), rho));
    }
    if (!ro.inertia_from_geometry) {
      throw Error(fmt::format("{}: density {} kg/m³ is the density of the links' collision geometry "
                              "when their inertials are computed from it: give {} with it (without "
                              "it, the links keep the inertials the file states)",
                              file.string(), rho, setting("inertia_from_geometry")));
    }
    ro.density = rho;
  }
  return ro;
}

Scene scene_from_robot_file(const std::string& xml, const std::filesystem::path& file,
                            const ModelOptions& options, const std::filesystem::path& scene_file) {
  const io::RobotReadOptions ro = robot_read_options(options, file);
  const io::RobotModel model = io::read_robot_model(xml, file.string(), ro);
  if (options.density && model.format != io::InertialFormat::urdf) {
    throw Error(fmt::format("{}: density {} kg/m³ applies to a URDF's collision geometry; this is "
                            "an {} model, whose geoms carry their own density (MJCF: geom density, "
                            "default 1000 kg/m³)",
                            file.string(), *options.density, io::to_string(model.format)));
  }
  return scene_from_robot(model, scene_file, options.symbolic_inertia.value_or(false));
}

Scene scene_from_robot(const io::RobotModel& file_model, const std::filesystem::path& file,
                       bool symbolic_inertia) {
  const io::RobotModel model = with_coordinate_names(file_model);
  Scene s;
  s.file = file;
  const SourceLocation top{model.source, 0, 0};
  std::vector<TreeBody> bodies = moving_bodies(model);
  merge_massless(model, bodies);
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const io::RobotLink& link = model.links[l];
    for (const io::RobotJoint& j : link.joints) {
      const SourceLocation where = where_of(model, link, j.line);
      if (j.type == io::RobotJointType::kFree || j.type == io::RobotJointType::kBall) {
        if (j.stiffness != 0) {
          rigid::detail::throw_error_at(
              where, fmt::format("joint '{}' ({}) has stiffness {}: the symbolic equations do not "
                                 "take a ball's or free joint's spring yet (MuJoCo's, about the "
                                 "rotation vector from the reference); rigid.robot.Robot(file) "
                                 "has it in numbers",
                                 j.name, j.type == io::RobotJointType::kBall ? "ball" : "free", j.stiffness));
        }
        Transform placement;  // a free joint's initial value: its link's placement in the world
        if (j.type == io::RobotJointType::kFree) {
          for (const TreeBody& b : bodies) {
            if (b.link == l) placement = b.placement;
          }
          for (std::size_t k = 0; k < 3; ++k) {
            s.coordinates.push_back(Coordinate{free_part(j, k), Expression::of(placement.p(static_cast<Eigen::Index>(k)), where),
                                               Expression::of(0, where), where});
          }
        }
        const Eigen::Quaterniond quat(placement.R);
        Coordinate ball{j.name, Expression::of(0, where), Expression::of(0, where), where};
        ball.kind = Coordinate::Kind::kBall;
        ball.orientation = {Expression::of(quat.w(), where), Expression::of(quat.x(), where), Expression::of(quat.y(), where),
                            Expression::of(quat.z(), where)};
        ball.angular_velocity = {Expression::of(0, where), Expression::of(0, where), Expression::of(0, where)};
        s.coordinates.push_back(std::move(ball));
        continue;
      }
      s.coordinates.push_back(Coordinate{j.name, Expression::of(j.ref, where), Expression::of(0, where), where});
    }
  }
  if (s.coordinates.empty()) {
    rigid::detail::throw_error_at(top, "the model has no joint (every link is fixed), so it has no "
                                       "equations of motion");
  }
  for (const TreeBody& b : bodies) {
    if (!b.merged_away) s.bodies.push_back(scene_body(model, bodies, b, symbolic_inertia, s));
  }
  for (std::size_t k = 0; k < 3; ++k)
    s.gravity[k] = Expression::of(model.gravity(static_cast<Eigen::Index>(k)), top);
  add_passive_terms(model, s);
  s.simulation.t_end = Expression::of(5, top);
  s.simulation.where = top;
  return s;
}

}  // namespace rigid::scene
