#pragma once

// Conversions between rigid::SO3d and Eigen's quaternion for tests that compare the library
// with references written independently on Eigen::Quaterniond / Eigen::AngleAxisd.

#include <Eigen/Geometry>

#include "rigid/lie/so3.hpp"

namespace rigid::test {

inline Eigen::Quaterniond to_eigen(const SO3d& R) { return {R.w(), R.x(), R.y(), R.z()}; }

inline SO3d from_eigen(const Eigen::Quaterniond& q) {
  return SO3d::from_quaternion(q.w(), q.x(), q.y(), q.z());
}

/// The angle (rad) of the rotation a⁻¹ b.
inline double angle_between(const SO3d& a, const SO3d& b) { return (a.inverse() * b).angle(); }

}  // namespace rigid::test
