#pragma once

#include <array>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "rigid/lie/so3.hpp"

namespace rigid {

/// One of the 12 Euler-angle conventions: an axis sequence (6 Tait–Bryan such as ZYX, 6 proper
/// Euler such as ZXZ) and whether the axes move with the body (intrinsic) or stay fixed
/// (extrinsic). Intrinsic "XYZ" with angles (a, b, c) is R = Rx(a) Ry(b) Rz(c); extrinsic
/// "XYZ" is R = Rz(c) Ry(b) Rx(a) (first angle applied first, about the fixed x axis).
struct EulerConvention {
  std::array<int, 3> axes{2, 1, 0};  ///< 0 = x, 1 = y, 2 = z; default ZYX
  bool intrinsic = true;

  /// Parses "XYZ", "zyx", "ZXZ", … @throws rigid::Error naming the valid sequences.
  [[nodiscard]] static EulerConvention parse(std::string_view sequence, bool intrinsic);
  /// "ZYX" etc.
  [[nodiscard]] std::string name() const;
};

/// The 12 valid axis sequences, in the order listed by error messages.
[[nodiscard]] const std::array<std::string_view, 12>& euler_sequences();

/// Rotation from Euler angles (radians). @throws rigid::Error if an angle is not finite or
/// exceeds kMaxAngle in magnitude.
[[nodiscard]] SO3d from_euler(const Eigen::Vector3d& angles, const EulerConvention& convention);

/// Euler angles (radians) of R. The middle angle is in [−π/2, π/2] (Tait–Bryan) or [0, π]
/// (proper Euler); the others in (−π, π]. Gimbal lock (middle-angle cosine, resp. sine, below
/// 1e-15 in magnitude, where only the sum or difference of the outer angles is defined): the
/// third intrinsic angle (for extrinsic conventions: the first angle) is set to 0 and the
/// other outer angle carries the whole rotation.
[[nodiscard]] Eigen::Vector3d to_euler(const SO3d& R, const EulerConvention& convention);

}  // namespace rigid
