#include "rigid/mass/placement.hpp"

#include <cmath>


#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/lie/euler.hpp"

namespace rigid::mass {

Eigen::Matrix3d rotation_z_to(const Eigen::Vector3d& axis) {
  const double n = axis.norm();
  RIGID_REQUIRE(axis.allFinite() && n > 1e-12,
                "axis must be a finite vector of length above 1e-12, got {}", to_string(axis.transpose()));
  const Eigen::Vector3d u = axis / n;
  // Rodrigues' formula R = c 1 + s [k]× + (1 − c) k kᵀ about k = z × u / |z × u|, with
  // c = cos θ = u_z and s = sin θ = |z × u| taken from the vector itself (no trigonometry),
  // so a coordinate axis gives an exact permutation matrix with signs
  const Eigen::Vector3d k_s(-u.y(), u.x(), 0.0);  // z × u, of length s
  const double s = k_s.norm();
  if (s == 0.0) {
    // ±z: the identity, or a half turn about x (x stays, y and z flip)
    return u.z() > 0 ? Eigen::Matrix3d::Identity() : Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix();
  }
  const Eigen::Vector3d k = k_s / s;
  const double c = u.z();
  Eigen::Matrix3d K;
  K << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
  return c * Eigen::Matrix3d::Identity() + s * K + (1.0 - c) * k * k.transpose();
}

Eigen::Matrix3d placement_rotation(const Placement& placement) {
  RIGID_REQUIRE(placement.rpy.allFinite(), "rpy must be finite, got {} rad",
                to_string(placement.rpy.transpose()));
  const Eigen::Matrix3d R_rpy = from_euler(placement.rpy, EulerConvention::parse("XYZ", false)).matrix();
  return R_rpy * rotation_z_to(placement.axis);
}

MassProperties place(const MassProperties& in_own_frame, const Eigen::Matrix3d& R_LS,
                     const Eigen::Vector3d& p_LS_L) {
  RIGID_REQUIRE(p_LS_L.allFinite(), "origin must be finite, got {} m", to_string(p_LS_L.transpose()));
  return in_own_frame.transformed(R_LS, p_LS_L);
}

MassProperties place(const MassProperties& in_own_frame, const Placement& placement) {
  return place(in_own_frame, placement_rotation(placement), placement.origin);
}

}  // namespace rigid::mass
