#include "rigid/mass/placement.hpp"

#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using test::ulps;

TEST(Placement, CylinderAlongXAtAnOffsetIsTheParallelAxisClosedForm) {
  const double m = 2.0, r = 0.05, h = 0.4, d = 0.1;
  const MassProperties placed = mass::place(
      mass::solid_cylinder_with_mass(m, r, h),
      mass::Placement{.axis = Eigen::Vector3d::UnitX(), .rpy = Eigen::Vector3d::Zero(),
                      .origin = Eigen::Vector3d(d, 0, 0)});
  // axis x: I_xx = m r²/2 about the COM; about the link origin, the parallel-axis terms
  // m d² add to I_yy and I_zz only (d along x)
  const double axial = m * r * r / 2, transverse = m * (3 * r * r + h * h) / 12;
  const Eigen::Matrix3d I_O = placed.inertia_about(Eigen::Vector3d::Zero());
  const Eigen::Matrix3d expected = Eigen::Vector3d(axial, transverse + m * d * d, transverse + m * d * d).asDiagonal();
  // the named axis is an exact signed permutation, so the only round-off is the formulas' few ε
  EXPECT_TRUE((I_O - expected).cwiseAbs().maxCoeff() <= ulps(8, expected.trace())) << I_O;
  EXPECT_EQ(placed.com(), Eigen::Vector3d(d, 0, 0));
  EXPECT_EQ(placed.inertia_com()(0, 2), 0.0);  // no round-off from a rotation by π/2
}

TEST(Placement, AxisRotationTakesZToTheAxisAndIsProper) {
  std::mt19937 gen(18);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                       -Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitZ(),
                                       Eigen::Vector3d(1e-9, 0, -1)};  // nearly −z
  for (int i = 0; i < 50; ++i) axes.emplace_back(n(gen), n(gen), n(gen));
  for (const auto& a : axes) {
    const Eigen::Matrix3d R = mass::rotation_z_to(3.0 * a);  // any length
    // orthonormality and the image of z to a few ε (Rodrigues' formula is a handful of flops)
    EXPECT_TRUE((R * Eigen::Vector3d::UnitZ() - a.normalized()).norm() <= ulps(8)) << a.transpose();
    EXPECT_TRUE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= ulps(16)) << a.transpose();
    EXPECT_NEAR(R.determinant(), 1.0, ulps(16));
    // the shortest rotation: its axis is perpendicular to both z and a
    if ((a.normalized() - Eigen::Vector3d::UnitZ()).norm() > 1e-6 && (a.normalized() + Eigen::Vector3d::UnitZ()).norm() > 1e-6) {
      const Eigen::AngleAxisd aa(R);
      EXPECT_NEAR(aa.axis().dot(Eigen::Vector3d::UnitZ()), 0.0, 1e-9);  // acos near 0: √ε scale
      EXPECT_NEAR(aa.axis().dot(a.normalized()), 0.0, 1e-9);
    }
  }
}

TEST(Placement, RpyIsUrdfFixedAxisXyzAfterTheAxis) {
  const Eigen::Vector3d rpy(0.3, -0.7, 1.9);
  // independent: Eigen's angle-axis products, R = Rz(y) Ry(p) Rx(r), then the x axis turn
  // Ry(π/2) that takes z to x
  const Eigen::Matrix3d R_rpy = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                    .toRotationMatrix();
  const Eigen::Matrix3d R_axis = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d R = mass::placement_rotation({.axis = Eigen::Vector3d::UnitX(), .rpy = rpy, .origin = Eigen::Vector3d::Zero()});
  EXPECT_TRUE((R - R_rpy * R_axis).cwiseAbs().maxCoeff() <= ulps(16)) << R;
  // placing a cone puts its base centre at the origin and its COM h/4 along the placed axis
  const MassProperties cone = mass::place(mass::solid_cone_with_mass(1.0, 0.2, 0.8),
                                          {.axis = Eigen::Vector3d::UnitX(), .rpy = rpy, .origin = Eigen::Vector3d(1, 2, 3)});
  EXPECT_TRUE((cone.com() - (Eigen::Vector3d(1, 2, 3) + 0.2 * R_rpy.col(0))).norm() <= ulps(16, 4.0));
}

TEST(Placement, BadInputIsRefused) {
  const auto mp = mass::solid_sphere_with_mass(1.0, 0.1);
  EXPECT_RIGID_ERROR((void)mass::rotation_z_to(Eigen::Vector3d::Zero()),
                     "axis must be a finite vector of length above 1e-12, got [0, 0, 0]");
  EXPECT_RIGID_ERROR((void)mass::placement_rotation({.axis = Eigen::Vector3d::UnitZ(), .rpy = Eigen::Vector3d(0, NAN, 0), .origin = Eigen::Vector3d::Zero()}),
                     "rpy must be finite");
  EXPECT_RIGID_ERROR((void)mass::place(mp, Eigen::Matrix3d::Identity(), Eigen::Vector3d(INFINITY, 0, 0)),
                     "origin must be finite");
}

}  // namespace
}  // namespace rigid
