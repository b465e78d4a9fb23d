#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "rigid/lie.hpp"
#include "support/expect_error.hpp"

namespace rigid {
namespace {

using std::numbers::pi;

// Rotation about one axis by an independent closed form (not through the code under test).
Eigen::Matrix3d elementary(int axis, double t) {
  const double c = std::cos(t), s = std::sin(t);
  Eigen::Matrix3d R;
  if (axis == 0) R << 1, 0, 0, 0, c, -s, 0, s, c;
  if (axis == 1) R << c, 0, s, 0, 1, 0, -s, 0, c;
  if (axis == 2) R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}

Eigen::Matrix3d reference(const Eigen::Vector3d& a, const EulerConvention& c) {
  const Eigen::Matrix3d r0 = elementary(c.axes[0], a(0)), r1 = elementary(c.axes[1], a(1)),
                        r2 = elementary(c.axes[2], a(2));
  return c.intrinsic ? Eigen::Matrix3d(r0 * r1 * r2) : Eigen::Matrix3d(r2 * r1 * r0);
}

TEST(Euler, AllTwelveConventionsBothWaysRoundTrip) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(-pi, pi);
  for (std::string_view seq : euler_sequences()) {
    for (bool intrinsic : {true, false}) {
      const EulerConvention c = EulerConvention::parse(seq, intrinsic);
      EXPECT_EQ(c.name(), seq);
      for (int n = 0; n < 2000; ++n) {
        const Eigen::Vector3d a(u(rng), u(rng), u(rng));
        const SO3d R = from_euler(a, c);
        // Against an independent product of elementary matrices; 1e-14 ≈ 50 ulps.
        ASSERT_LE((R.matrix() - reference(a, c)).cwiseAbs().maxCoeff(), 1e-14) << seq;
        const Eigen::Vector3d back = to_euler(R, c);
        ASSERT_LE((from_euler(back, c).matrix() - R.matrix()).cwiseAbs().maxCoeff(), 1e-13)
            << seq << " " << intrinsic << " " << a.transpose();
      }
    }
  }
}

TEST(Euler, AnglesRecoveredInPrincipalRange) {
  const EulerConvention zyx = EulerConvention::parse("ZYX", true);
  const Eigen::Vector3d a(0.3, -0.7, 2.0);
  EXPECT_LE((to_euler(from_euler(a, zyx), zyx) - a).cwiseAbs().maxCoeff(), 1e-14);
  const EulerConvention zxz = EulerConvention::parse("zxz", false);
  const Eigen::Vector3d p(-1.2, 2.5, 0.4);
  EXPECT_LE((to_euler(from_euler(p, zxz), zxz) - p).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Euler, GimbalLockAtAndNear) {
  for (std::string_view seq : euler_sequences()) {
    for (bool intrinsic : {true, false}) {
      const EulerConvention c = EulerConvention::parse(seq, intrinsic);
      const bool proper = c.axes[0] == c.axes[2];
      for (double lock : proper ? std::vector<double>{0.0, pi} : std::vector<double>{pi / 2, -pi / 2}) {
        for (double off : {0.0, 1e-12, 1e-9, 1e-6}) {
          const Eigen::Vector3d a(0.4, lock - off, -1.1);
          const SO3d R = from_euler(a, c);
          const Eigen::Vector3d back = to_euler(R, c);
          // The outer angles are ill-conditioned near the lock but the rotation they rebuild
          // must not be: 1e-13 ≈ 450 ulps allows the dozen products in from_euler/to_euler.
          EXPECT_LE((from_euler(back, c).matrix() - R.matrix()).cwiseAbs().maxCoeff(), 1e-13)
              << seq << " " << intrinsic << " off " << off;
          if (off == 0.0) {
            // Documented choice: third intrinsic angle (first extrinsic) is 0.
            EXPECT_EQ(back(intrinsic ? 2 : 0), 0.0) << seq;
          }
        }
      }
    }
  }
}

TEST(Euler, BadInput) {
  EXPECT_RIGID_ERROR((void)EulerConvention::parse("XXY", true),
                     "unknown Euler sequence 'XXY', expected one of XYZ, XZY, YXZ, YZX, ZXY, ZYX, XYX, XZX, "
                     "YXY, YZY, ZXZ, ZYZ");
  EXPECT_RIGID_ERROR((void)from_euler(Eigen::Vector3d(0, NAN, 0), EulerConvention{}),
                     "Euler angles [0, nan, 0] have a non-finite component");
}

TEST(Euler, FromEulerRefusesAnglesBeyondTheLimit) {
  // 1e300 rad: cos and sin of it are defined, but the fraction of a turn is long lost; the
  // rotation was NaN before this was refused (|ω|² overflowed in exp)
  EXPECT_RIGID_ERROR((void)from_euler(Eigen::Vector3d(1e300, 0, 0), EulerConvention::parse("ZYX", true)),
                     "from_euler(): Euler angles [1e+300, 0, 0] rad: an angle is too large, expected "
                     "|angle| <= kMaxAngle = 1e+15 rad");
  EXPECT_RIGID_ERROR((void)from_euler(Eigen::Vector3d(0, 0, -2e15), EulerConvention::parse("XYZ", false)),
                     "an angle is too large");
  // the limit itself is accepted: a unit quaternion (4 ulps)
  const SO3d R = from_euler(Eigen::Vector3d(kMaxAngle, -kMaxAngle, 0.5), EulerConvention::parse("ZYX", true));
  EXPECT_NEAR(R.quaternion().norm(), 1.0, 4 * std::numeric_limits<double>::epsilon());
}

}  // namespace
}  // namespace rigid
