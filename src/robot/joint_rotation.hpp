#pragma once
// The quaternions of ball and free joints in q (MuJoCo's qpos), shared by the tree dynamics and
// the regressor (internal to the robot module): reading one, refusing one that is not of unit
// norm, a free joint's reference orientation and the rotation vector of the joints' springs.

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

}  // namespace rigid::robot::detail
