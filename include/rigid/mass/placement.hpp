#pragma once

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"

namespace rigid::mass {

/// Where a shape S sits in a link frame L. The shape is built in its own frame (the catalogue's
/// frame: axis of revolution along z, origin at its centre, or the cone's base centre), then
///   1. turned so that its own z axis points along `axis` (the shortest rotation from z to the
///      axis: about z × axis; a half turn about x for −z),
///   2. rotated by `rpy` (URDF convention: fixed-axis roll, pitch, yaw, R = Rz(y) Ry(p) Rx(r)),
///   3. moved so that its own origin is at `origin`.
/// So R_LS = R_rpy · R_axis and p_LS_L = origin; a point s of the shape is at R_LS s + origin.
struct Placement {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< direction in L (any length > 0)
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();    ///< roll, pitch, yaw (rad)
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(); ///< p_LS_L (m)
};

/// The shortest rotation taking the unit z axis to axis/|axis| (a half turn about x for −z).
/// @throws rigid::Error if axis is not finite or its length is not above 1e-12.
[[nodiscard]] Eigen::Matrix3d rotation_z_to(const Eigen::Vector3d& axis);

/// R_LS of a placement: Rz(yaw) Ry(pitch) Rx(roll) · rotation_z_to(axis).
/// @throws rigid::Error for a bad axis or a non-finite rpy.
[[nodiscard]] Eigen::Matrix3d placement_rotation(const Placement& placement);

/// The body `in_own_frame` (mass properties in the shape's frame S) expressed in the link
/// frame L where S has the pose (R_LS, p_LS_L): p_LC_L = R_LS p_SC_S + p_LS_L,
/// I_C_L = R_LS I_C_S R_LSᵀ (MassProperties::transformed).
/// @throws rigid::Error if R_LS is not a rotation within 1e-9 or p_LS_L is not finite.
[[nodiscard]] MassProperties place(const MassProperties& in_own_frame, const Eigen::Matrix3d& R_LS,
                                   const Eigen::Vector3d& p_LS_L);

/// place(in_own_frame, placement_rotation(placement), placement.origin).
[[nodiscard]] MassProperties place(const MassProperties& in_own_frame, const Placement& placement);

}  // namespace rigid::mass
