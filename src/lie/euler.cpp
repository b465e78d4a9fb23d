#include "rigid/lie/euler.hpp"

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/ranges.h>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"

namespace rigid {

namespace {

// Below this |cos b| (|sin b| for proper sequences) the outer angles are treated as locked; the
// information dropped is of this size, i.e. at rounding level.
constexpr double kGimbalLock = 1e-15;

// +1 if (i, j, k) is a cyclic permutation of (0, 1, 2), −1 otherwise.
double parity(int i, int j) { return ((j - i + 3) % 3 == 1) ? 1.0 : -1.0; }

SO3d axis_rotation(int axis, double angle) {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  w(axis) = angle;
  return SO3d::exp(w);
}

// Intrinsic angles (a, b, c) of R = R_i(a) R_j(b) R_k(c) (k = i for proper Euler sequences).
Eigen::Vector3d intrinsic_angles(const Eigen::Matrix3d& R, int i, int j, int k_seq) {
  const bool proper = (k_seq == i);
  const int k = 3 - i - j;  // the third axis
  const double s = parity(i, j);
  double b = 0, c = 0;
  if (!proper) {
    const double cb = std::hypot(R(i, i), R(i, j));
    b = std::atan2(s * R(i, k), cb);
    if (cb > kGimbalLock) c = std::atan2(-s * R(i, j), R(i, i));
  } else {
    const double sb = std::hypot(R(i, j), R(i, k));
    b = std::atan2(sb, R(i, i));
    if (sb > kGimbalLock) c = std::atan2(R(i, j), s * R(i, k));
  }
  // Near the lock c is ill-conditioned, so a is not taken from its own small entries but from
  // M = R R_last(c)ᵀ = R_i(a) R_j(b), whose column j is R_i(a) e_j (entries of order 1): a then
  // absorbs any error in c and the product reproduces R to rounding.
  const Eigen::Matrix3d M = R * axis_rotation(k_seq, c).matrix().transpose();
  const double a = std::atan2(s * M(k, j), M(j, j));
  return {a, b, c};
}

}  // namespace

const std::array<std::string_view, 12>& euler_sequences() {
  static const std::array<std::string_view, 12> k{"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX",
                                                   "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"};
  return k;
}

EulerConvention EulerConvention::parse(std::string_view sequence, bool intrinsic) {
  std::string up;
  for (char ch : sequence) up += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  for (std::string_view v : euler_sequences()) {
    if (up == v) {
      EulerConvention c;
      for (int n = 0; n < 3; ++n) c.axes[static_cast<std::size_t>(n)] = up[static_cast<std::size_t>(n)] - 'X';
      c.intrinsic = intrinsic;
      return c;
    }
  }
  RIGID_THROW("unknown Euler sequence '{}', expected one of {}{}", sequence, fmt::join(euler_sequences(), ", "),
              did_you_mean_hint(up, std::vector<std::string>(euler_sequences().begin(), euler_sequences().end())));
}

std::string EulerConvention::name() const {
  std::string n;
  for (int a : axes) n += static_cast<char>('X' + a);
  return n;
}

SO3d from_euler(const Eigen::Vector3d& angles, const EulerConvention& conv) {
  RIGID_REQUIRE(angles.allFinite(), "Euler angles {} have a non-finite component", to_string(angles.transpose()));
  RIGID_REQUIRE((angles.array().abs() <= kMaxAngle).all(),
                "Euler angles {} rad: an angle is too large, expected |angle| <= kMaxAngle = {:.0e} "
                "rad (beyond, rounding has lost the fraction of a turn)",
                to_string(angles.transpose()), kMaxAngle);
  const SO3d r0 = axis_rotation(conv.axes[0], angles(0));
  const SO3d r1 = axis_rotation(conv.axes[1], angles(1));
  const SO3d r2 = axis_rotation(conv.axes[2], angles(2));
  return conv.intrinsic ? r0 * r1 * r2 : r2 * r1 * r0;
}

Eigen::Vector3d to_euler(const SO3d& R, const EulerConvention& conv) {
  const Eigen::Matrix3d M = R.matrix();
  if (conv.intrinsic) return intrinsic_angles(M, conv.axes[0], conv.axes[1], conv.axes[2]);
  // Extrinsic (i, j, k) with angles (a, b, c) is intrinsic (k, j, i) with angles (c, b, a).
  const Eigen::Vector3d r = intrinsic_angles(M, conv.axes[2], conv.axes[1], conv.axes[0]);
  return {r(2), r(1), r(0)};
}

}  // namespace rigid
