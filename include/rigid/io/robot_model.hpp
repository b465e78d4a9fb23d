#pragma once

/// Kinematic trees of robot model files (URDF, MJCF, SDFormat): the links, where each sits on
/// its parent, the joints that move it, and its inertial, as the file states them.
/// docs/robots.md has the conventions; rigid::robot turns a tree into its equations of motion.
///
/// Conventions (MuJoCo's, so that a model reads alike from URDF and MJCF):
///  - A link's frame L sits on its parent's frame (or the world's) at `position`, rotated by
///    `rotation` (columns: L's axes in the parent's frame), when every joint of the link is at
///    its reference value `ref`.
///  - A link's joints act in order, each in the frame left by the ones before it: a hinge turns
///    the link by (q − ref) about `axis` through `anchor` (right hand), a slide moves it by
///    (q − ref) along `axis`. A link without joints is welded to its parent.
///  - URDF: a joint's origin is the child link's frame; its axis is in that frame and passes
///    through its origin (anchor 0, ref 0). revolute and continuous are hinges, prismatic a
///    slide, fixed welds the child, floating is a free joint (only from the root link, which
///    then stands for the world: the child becomes a root of its own, placed by the origin).
///  - A ball joint turns the link about `anchor` by a unit quaternion (w, x, y, z) from the
///    frame left by the joints before it; a free joint places the link in the world directly.
///    A ball or free joint is its link's only joint, and a free joint's link is a root (parent
///    −1): an MJCF body of the world, or the child of a URDF floating joint from the root link.
///  - The state is MuJoCo's qpos/qvel: the joints in `links` order (depth first from the root,
///    children in file order) and, within a link, in file order. A joint has nq position and nv
///    velocity entries: hinge and slide 1 and 1 (the angle or the length; its rate); ball 4 and
///    3 (the quaternion parent side ← link; the link's angular velocity in the link frame);
///    free 7 and 6 (the world position of the link frame's origin and the quaternion
///    world ← link; the world velocity of that origin and the angular velocity in the link
///    frame). Names: a hinge or slide 'j' is "j" in both; a ball 'j' is j_qw j_qx j_qy j_qz
///    and j_wx j_wy j_wz; a free 'j' is j_x j_y j_z j_qw j_qx j_qy j_qz and j_vx j_vy j_vz
///    j_wx j_wy j_wz. The reference of a ball is the identity, of a free joint the link's
///    placement.
///  - Passive forces on a joint's coordinate: −damping q̇ − stiffness (q − springref); the
///    armature adds to the joint's diagonal entry of the mass matrix. A ball or free joint has
///    them on each of its velocity entries (MuJoCo's): damping −d ω, stiffness −k (p − p_ref)
///    on a free joint's position and −k r on a rotation, with r the rotation vector of
///    q_ref⁻¹ ⊗ q (ref and springref of a ball or free joint are not used, as in MuJoCo).
///  - URDF <dynamics friction> is Coulomb friction (a constraint force, not a passive force of
///    the equations): it is not read. A link without <inertial> has mass 0.
///  - MJCF: hinge ref and springref are in <compiler angle> units (degree by default, as
///    MuJoCo); inertials follow <compiler inertiafromgeom> ("auto": a body's <inertial>, else
///    its geoms). <include file> is relative to the main file's directory and a file is
///    included at most once (MuJoCo's XML reference); messages name the included file.
///  - SDF (SDFormat 1.4–1.10, sdformat.org/spec; src/io/sdf_model.cpp): the one <model> of the
///    file or of its one <world>. Link <pose>s are in the model frame (the model's <pose>
///    places it in the world); a joint's <pose> is its frame in the child link's frame, so
///    `anchor` is the joint frame's origin and the axis is <axis><xyz> in the joint frame
///    (the model frame with use_parent_model_frame, expressed_in="__model__" or version ≤
///    1.4); the file's poses are q = 0. revolute and continuous are hinges, prismatic a
///    slide, fixed welds the child; a root link without a joint to the world is welded where
///    it stands, as URDF's. Passive terms are <axis><dynamics> damping, spring_stiffness and
///    spring_reference. A link without <inertial> has SDFormat's default: 1 kg, unit inertia.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/io/inertial_xml.hpp"

namespace rigid::io {

enum class RobotJointType { kHinge, kSlide, kBall, kFree };

/// "hinge", "slide", "ball" or "free".
[[nodiscard]] const char* to_string(RobotJointType type);

/// Entries of a joint in qpos: 1 (hinge, slide), 4 (ball), 7 (free).
[[nodiscard]] int position_count(RobotJointType type);
/// Entries of a joint in qvel: 1 (hinge, slide), 3 (ball), 6 (free).
[[nodiscard]] int velocity_count(RobotJointType type);

/// One joint: a degree of freedom (hinge, slide), or three (ball) or six (free). `axis`, `ref`
/// and `springref` are a hinge's or slide's.
struct RobotJoint {
  std::string name;
  RobotJointType type = RobotJointType::kHinge;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();    ///< unit, in the link frame
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();   ///< a hinge's or ball's pivot, link frame (m)
  double ref = 0;        ///< q (rad or m) at which the link sits at its placement
  double damping = 0;    ///< N·m·s/rad or N·s/m
  double stiffness = 0;  ///< N·m/rad or N/m
  double springref = 0;  ///< q (rad or m) at which the spring is relaxed
  double armature = 0;   ///< kg·m² or kg, added to the mass matrix's diagonal
  int line = 0;          ///< the element's line in `source`
};

/// One link (URDF) or body (MJCF).
struct RobotLink {
  std::string name;
  int parent = -1;  ///< index into RobotModel::links; −1: the world
  Eigen::Vector3d position = Eigen::Vector3d::Zero();     ///< m, in the parent's frame
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< parent ← link, proper rotation
  std::vector<RobotJoint> joints;  ///< empty: welded to the parent
  /// The inertial in the link frame: mass (kg), COM (m), inertia about the COM (kg·m²). A link
  /// with no inertial has mass 0 (a frame only); a positive mass passed
  /// rigid::MassProperties::check.
  double mass = 0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_com = Eigen::Matrix3d::Zero();
  int line = 0;  ///< the element's line in the file that holds it
  std::string file;  ///< that file (an MJCF <include>d file, or `source`)
};

/// A robot model: the links in depth-first order from the root (a parent before its
/// children, children in file order), and the gravity.
struct RobotModel {
  std::string source;  ///< the file read
  InertialFormat format = InertialFormat::urdf;
  std::string name;    ///< URDF robot name, MJCF model name
  std::vector<RobotLink> links;
  Eigen::Vector3d gravity{0, 0, -9.81};  ///< m/s²: MJCF <option gravity>, else MuJoCo's default

  /// Degrees of freedom: nv (the joints of a hinge/slide tree).
  [[nodiscard]] std::size_t dof() const { return nv(); }
  /// Entries of qpos (the sum of the joints' nq).
  [[nodiscard]] std::size_t nq() const;
  /// Entries of qvel (the sum of the joints' nv).
  [[nodiscard]] std::size_t nv() const;
  /// True if a joint is a ball or free joint (then nq ≠ nv).
  [[nodiscard]] bool has_ball_or_free_joint() const;
  /// The names of qpos's entries (the joints' names for a hinge/slide tree; see above).
  [[nodiscard]] std::vector<std::string> coordinate_names() const;
  /// The names of qvel's entries.
  [[nodiscard]] std::vector<std::string> velocity_names() const;
};

/// How a model is read.
struct RobotReadOptions {
  /// A free joint (MJCF <freejoint>, <joint type="free">, URDF floating) on a root is welded
  /// there at its placement: the robot pinned at its root. Otherwise it is read as a free joint.
  bool pin_free_root = false;
  /// Every link's inertial from its geometry with the rules of `rigid inertia fix` (MJCF:
  /// MuJoCo's compiler's, as inertiafromgeom="true", a body without geoms massless; URDF:
  /// collision geometry at `density`, a link without collision keeps its stated inertial).
  bool inertia_from_geometry = false;
  double density = 1000;  ///< kg/m³, URDF geometry with inertia_from_geometry
};

/// The tree of a URDF, MJCF or SDF document (detected from the root element, as
/// read_inertials does); `source` names it in messages and is the base of relative paths
/// (<include>, meshes).
/// @throws rigid::Error "file:line: ..." for malformed XML, a missing or unknown parent, a
///   loop, several roots (URDF, SDF), an unsupported joint (a free joint below a root, a URDF
///   floating joint not from the root link, planar, mimic; SDF ball, universal, revolute2,
///   screw, gearbox), a ball or free joint sharing its link with other joints, SDF <include>, nested
///   models, a world of several models, an unusable attribute or an invalid inertial (naming
///   the link and MassProperties::check's reason).
[[nodiscard]] RobotModel read_robot_model(const std::string& xml, const std::string& source,
                                          const RobotReadOptions& options = {});

/// read_robot_model on a file's contents. @throws rigid::Error if it is not a regular,
/// readable file.
[[nodiscard]] RobotModel read_robot_model_file(const std::string& path,
                                               const RobotReadOptions& options = {});

}  // namespace rigid::io
