// Uses the installed headers and libraries; exits non-zero if anything is off.
#include <cmath>
#include <cstdio>

#include <rigid/common/error.hpp>
#include <rigid/lie.hpp>
#include <rigid/version.hpp>

int main() {
  // A quarter turn about z maps x to y.
  const rigid::SO3d R = rigid::SO3d::exp(Eigen::Vector3d(0, 0, std::acos(-1.0) / 2));
  const Eigen::Vector3d y = R * Eigen::Vector3d(1, 0, 0);
  if ((y - Eigen::Vector3d(0, 1, 0)).norm() > 1e-15) return 1;
  try {
    (void)rigid::SO3d::from_axis_angle(Eigen::Vector3d::Zero(), 1.0);
  } catch (const rigid::Error& e) {
    std::printf("rigid %s: caught \"%s\"\n", RIGID_VERSION_STRING, e.what());
    return 0;
  }
  return 1;
}
