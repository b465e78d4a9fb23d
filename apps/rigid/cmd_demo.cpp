#include "cmd_demo.hpp"

#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "rigid/common/format.hpp"
#include "rigid/lie.hpp"
#include "rigid/version.hpp"

namespace rigid::cli {

void run_demo() {
  using std::numbers::pi;
  fmt::print("rigid {}: a short tour of rotations (every number below is computed now).\n\n",
             RIGID_VERSION_STRING);

  const SO3d Rz = SO3d::from_axis_angle(Eigen::Vector3d(0, 0, 1), pi / 2);
  const SO3d Rx = SO3d::from_axis_angle(Eigen::Vector3d(1, 0, 0), pi / 2);
  fmt::print("Rz = 90 deg about z, Rx = 90 deg about x.\n");
  fmt::print("  Rz * (1, 0, 0)         = {}\n", to_string((Rz * Eigen::Vector3d(1, 0, 0)).transpose()));
  const SO3d A = Rz * Rx, B = Rx * Rz;
  fmt::print("  Rz*Rx rotation vector  = {}\n", to_string(A.log().transpose()));
  fmt::print("  Rx*Rz rotation vector  = {}   (rotations do not commute)\n", to_string(B.log().transpose()));
  fmt::print("  angle(Rz*Rx)           = {} deg (120 deg: the cube's body-diagonal turn)\n\n",
             A.angle() * 180 / pi);

  const double t = pi - 1e-9;
  const Eigen::Vector3d w = Eigen::Vector3d(1, 2, 2) / 3.0 * t;
  const double err = (SO3d::exp(w).log() - w).norm();
  fmt::print("exp/log round trip at angle pi - 1e-9: |log(exp(w)) - w| = {:.3g}\n", err);

  const EulerConvention zyx = EulerConvention::parse("ZYX", true);
  const Eigen::Vector3d e = to_euler(A, zyx) * 180 / pi;
  fmt::print("Rz*Rx as intrinsic ZYX Euler angles (deg): {}\n", to_string(e.transpose()));

  const SO3d mid = Rz.interpolate(Rx, 0.5);
  fmt::print("Geodesic midpoint of Rz and Rx: angle from each = {} deg and {} deg\n",
             (Rz.inverse() * mid).angle() * 180 / pi, (Rx.inverse() * mid).angle() * 180 / pi);
  fmt::print("\nTry: rigid rotation --euler 30,20,10 --convention ZYX --unit deg\n");
}

}  // namespace rigid::cli
