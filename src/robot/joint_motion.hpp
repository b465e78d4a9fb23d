#pragma once
// The joints' motions and the quaternions of ball and free joints in q (MuJoCo's qpos), shared
// by the tree dynamics and the regressor (internal to the robot module): a joint moving its
// link's frame and its columns of motion, reading a quaternion, refusing one that is not of
// unit norm, a free joint's reference orientation, and what the joints' springs act on.

#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/io/robot_model.hpp"

namespace rigid::robot::detail {

inline Eigen::Quaterniond quaternion_at(const Eigen::VectorXd& q, Eigen::Index at) {
  return Eigen::Quaterniond(q(at), q(at + 1), q(at + 2), q(at + 3));
}

/// The quaternion of `joint` at q[at..at+3]; refused, naming the joint, unless its norm is 1
/// within 1e-6 (MuJoCo would normalise it; a q that drifted off the unit sphere is shown).
inline Eigen::Quaterniond unit_quaternion_at(const Eigen::VectorXd& q, Eigen::Index at,
                                             const io::RobotJoint& joint, const char* who) {
  const Eigen::Quaterniond Q = quaternion_at(q, at);
  if (!(std::abs(Q.norm() - 1) <= 1e-6)) {
    rigid::detail::throw_error(
        who, fmt::format("joint '{}' (type {}): its quaternion q[{}..{}] = ({}, {}, {}, {}) has "
                         "norm {}; expected a unit quaternion (norm 1 within 1e-6): normalise it",
                         joint.name, io::to_string(joint.type), at, at + 3, Q.w(), Q.x(), Q.y(),
                         Q.z(), Q.norm()));
  }
  return Q;
}

/// A free joint's reference orientation (MuJoCo's qpos0): its link's placement, w ≥ 0.
inline Eigen::Quaterniond reference_orientation(const io::RobotLink& link) {
  Eigen::Quaterniond r(link.rotation);
  if (r.w() < 0) r.coeffs() = -r.coeffs();
  return r;
}

/// The rotation vector r of a unit quaternion (angle |r| in [0, π] about r/|r|): MuJoCo's
/// mju_quat2Vel with dt = 1, as its ball-joint spring uses it (engine_util_spatial.c).
inline Eigen::Vector3d rotation_vector(const Eigen::Quaterniond& q) {
  Eigen::Vector3d axis = q.vec();
  const double s = axis.norm();
  if (!(s > 0)) return Eigen::Vector3d::Zero();
  double angle = 2 * std::atan2(s, q.w());
  if (angle > std::numbers::pi) angle -= 2 * std::numbers::pi;
  return angle / s * axis;
}

/// A joint moving a link frame (R, p: world ← link, the frame before the joint) by its entries of
/// q from e, calling column(S, fixed) for each of its columns of motion in order, in world
/// coordinates at the world origin (angular; linear): a hinge's (u, a × u) about its axis u
/// through its anchor a, a slide's (0, u); a free joint's three world-fixed translations of the
/// link origin, then for a free joint and a ball the link's own axes R e_k through the anchor (a
/// ball's pivot, a free joint's link origin), `fixed` in the link: those three all turn in the
/// frame as it was before them, the others in the frame as each finds it. A callback rather
/// than a returned list, for the hot paths of the tree's kinematics. `who` names the caller in
/// the refusal of a quaternion that is not of unit norm.
template <typename Column>
void move_joint(const io::RobotJoint& joint, const Eigen::VectorXd& q, Eigen::Index e,
                Eigen::Matrix3d& R, Eigen::Vector3d& p, const char* who, Column&& column) {
  Eigen::Matrix<double, 6, 1> S;
  switch (joint.type) {
    case io::RobotJointType::kHinge: {
      // a turn about the line through the anchor: the anchor stays where it is
      const Eigen::Vector3d u = R * joint.axis;
      const Eigen::Vector3d anchor = p + R * joint.anchor;
      S << u, anchor.cross(u);
      R = R * Eigen::AngleAxisd(q(e) - joint.ref, joint.axis).toRotationMatrix();
      p = anchor - R * joint.anchor;
      column(S, false);
      return;
    }
    case io::RobotJointType::kSlide: {
      const Eigen::Vector3d u = R * joint.axis;
      S << Eigen::Vector3d::Zero(), u;
      p += u * (q(e) - joint.ref);
      column(S, false);
      return;
    }
    case io::RobotJointType::kBall:
    case io::RobotJointType::kFree:
      break;
  }
  const bool free = joint.type == io::RobotJointType::kFree;
  const Eigen::Quaterniond Q = unit_quaternion_at(q, free ? e + 3 : e, joint, who);
  Eigen::Vector3d anchor;  // stays where it is
  if (free) {
    anchor = q.segment<3>(e);
    for (Eigen::Index k = 0; k < 3; ++k) {
      S << Eigen::Vector3d::Zero(), Eigen::Vector3d::Unit(k);
      column(S, false);
    }
    R = Q.toRotationMatrix();
    p = anchor;
  } else {
    anchor = p + R * joint.anchor;
    R = R * Q.toRotationMatrix();
    p = anchor - R * joint.anchor;
  }
  for (Eigen::Index k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = R.col(k);
    S << u, anchor.cross(u);
    column(S, true);
  }
}

/// What a joint's spring acts on, one entry per velocity (the first io::velocity_count): the
/// passive force is −stiffness times it and the spring's energy ½ stiffness |it|² (MuJoCo's
/// qfrc_passive): q − springref for a hinge or slide, the rotation vector of a ball's
/// quaternion, and for a free joint p − p₀ and the rotation vector of q₀⁻¹ ⊗ q, with p₀ and q₀
/// its link's placement (mju_subQuat).
inline Eigen::Matrix<double, 6, 1> spring_displacement(const io::RobotJoint& joint,
                                                       const io::RobotLink& link,
                                                       const Eigen::VectorXd& q, Eigen::Index e) {
  Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
  switch (joint.type) {
    case io::RobotJointType::kHinge:
    case io::RobotJointType::kSlide:
      d(0) = q(e) - joint.springref;
      break;
    case io::RobotJointType::kBall:
      d.head<3>() = rotation_vector(quaternion_at(q, e));
      break;
    case io::RobotJointType::kFree:
      d.head<3>() = q.segment<3>(e) - link.position;
      d.tail<3>() = rotation_vector(reference_orientation(link).conjugate() * quaternion_at(q, e + 3));
      break;
  }
  return d;
}

}  // namespace rigid::robot::detail
