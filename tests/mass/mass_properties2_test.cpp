#include "rigid/mass/mass_properties2.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mass/reference_quadrature.hpp"
#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using std::numbers::pi;
using test::ulps;

TEST(MassProperties2, LaminaeClosedForms) {
  const double sigma = 2.0;
  const auto disk = mass::disk_lamina_with_density(sigma, 0.5);
  EXPECT_NEAR(disk.mass(), sigma * pi * 0.25, ulps(4, 2));
  EXPECT_NEAR(disk.moment_com(), 0.5 * disk.mass() * 0.25, ulps(4));
  const auto ring = mass::annulus_lamina_with_mass(3.0, 0.1, 0.3);
  EXPECT_NEAR(ring.moment_com(), 1.5 * (0.01 + 0.09), ulps(4));
  const auto rect = mass::rectangle_lamina_with_mass(3.0, 0.4, 0.2);
  EXPECT_NEAR(rect.moment_com(), 3.0 * (0.16 + 0.04) / 12, ulps(4));
}

TEST(MassProperties2, LaminaeAgainstQuadrature) {
  // the lamina's polar moment is I_zz of the same planar region mapped into z = 0
  const double sigma = 3.0;
  const double r1 = 0.1;
  const double r2 = 0.4;
  const auto ring = mass::annulus_lamina_with_density(sigma, r1, r2);
  const auto ref = test::reference_moments({[=](const Eigen::Vector3d& u) {
    const double s = r1 + (r2 - r1) * u(0);
    const double th = 2 * pi * u(1);
    return test::MappedPoint{Eigen::Vector3d(s * std::cos(th), s * std::sin(th), 0),
                             sigma * (r2 - r1) * 2 * pi * s};
  }});
  EXPECT_NEAR(ring.mass(), ref.mass, ref.mass_error);
  EXPECT_NEAR(ring.moment_com(), ref.inertia_com(2, 2), ref.inertia_error);
  // an L-shaped (non-convex) polygon: two rectangles [0,2]×[0,1] and [0,1]×[1,3]
  Eigen::Matrix2Xd L(2, 6);
  L << 0, 2, 2, 1, 1, 0,  //
      0, 0, 1, 1, 3, 3;
  const auto poly = mass::polygon_lamina_with_density(sigma, L);
  const auto refL = test::reference_moments(
      {[=](const Eigen::Vector3d& u) {
         return test::MappedPoint{Eigen::Vector3d(2 * u(0), u(1), 0), sigma * 2};
       },
       [=](const Eigen::Vector3d& u) {
         return test::MappedPoint{Eigen::Vector3d(u(0), 1 + 2 * u(1), 0), sigma * 2};
       }});
  EXPECT_NEAR(poly.mass(), refL.mass, refL.mass_error);
  EXPECT_NEAR(poly.com().x(), refL.com.x(), refL.com_error);
  EXPECT_NEAR(poly.com().y(), refL.com.y(), refL.com_error);
  EXPECT_NEAR(poly.moment_com(), refL.inertia_com(2, 2), refL.inertia_error);
}

TEST(MassProperties2, PerpendicularAxisTheorem) {
  // a lamina's polar moment equals I_zz = I_xx + I_yy of the same thin plate in 3D
  const auto rect = mass::rectangle_lamina_with_mass(3.0, 0.4, 0.2);
  const auto plate = mass::thin_rectangular_plate_with_mass(3.0, 0.4, 0.2);
  EXPECT_NEAR(rect.moment_com(), plate.inertia_com()(0, 0) + plate.inertia_com()(1, 1), ulps(4));
  const auto disk = mass::disk_lamina_with_mass(1.0, 0.3);
  const auto plate_disk = mass::thin_disk_with_mass(1.0, 0.3);
  EXPECT_NEAR(disk.moment_com(), plate_disk.inertia_com()(0, 0) + plate_disk.inertia_com()(1, 1),
              ulps(4));
}

TEST(MassProperties2, PolygonMatchesRectangleAndTriangle) {
  // a rectangle given as a polygon far from the origin, clockwise
  Eigen::Matrix2Xd rect(2, 4);
  rect << 100.0, 100.0, 100.4, 100.4,  //
      50.0, 50.2, 50.2, 50.0;
  const auto poly = mass::polygon_lamina_with_mass(3.0, rect);
  EXPECT_TRUE(poly.com().isApprox(Eigen::Vector2d(100.2, 50.1), 1e-15));
  // local origin at vertex 0 keeps the error at ε·(size² · m), not ε·(100² · m)
  EXPECT_NEAR(poly.moment_com(), 3.0 * (0.16 + 0.04) / 12, 1e-12);
  // right triangle legs a (x) and b (y): about the centroid J_xx = A a²/18,
  // J_yy = A b²/18, J_xy = −A a b/36 (textbook second moments of area)
  const double a = 0.6;
  const double b = 0.3;
  Eigen::Matrix2Xd tri(2, 3);
  tri << 0, a, 0, 0, 0, b;
  const auto pm = mass::polygon_moments(tri);
  const double A = a * b / 2;
  EXPECT_NEAR(pm.area, A, ulps(4));
  EXPECT_TRUE(pm.centroid.isApprox(Eigen::Vector2d(a / 3, b / 3), ulps(8)));
  EXPECT_NEAR(pm.J_C(0, 0), A * a * a / 18, ulps(16, A));
  EXPECT_NEAR(pm.J_C(1, 1), A * b * b / 18, ulps(16, A));
  EXPECT_NEAR(pm.J_C(0, 1), -A * a * b / 36, ulps(16, A));
}

TEST(MassProperties2, PolygonErrors) {
  Eigen::Matrix2Xd bowtie(2, 4);
  bowtie << 0, 1, 1, 0, 0, 1, 0, 1;
  EXPECT_RIGID_ERROR((void)mass::polygon_moments(bowtie),
                     "polygon_moments(): the polygon is not simple: edge 0 (vertices 0–1) touches "
                     "edge 2");
  Eigen::Matrix2Xd two(2, 2);
  two << 0, 1, 0, 1;
  EXPECT_RIGID_ERROR((void)mass::polygon_moments(two), "at least 3 vertices, got 2");
  Eigen::Matrix2Xd line(2, 3);
  line << 0, 1, 2, 0, 1, 2;
  EXPECT_RIGID_ERROR((void)mass::polygon_moments(line), "the polygon has zero area (0 m²)");
}

TEST(MassProperties2, ShiftCombineRotate) {
  const auto a = MassProperties2(1.0, Eigen::Vector2d(1, 0), 0.1);
  const auto b = MassProperties2(1.0, Eigen::Vector2d(-1, 0), 0.1);
  const auto c = combine(a, b);
  EXPECT_NEAR(c.moment_com(), 0.2 + 2.0, ulps(4, 2));
  EXPECT_NEAR(a.moment_about(Eigen::Vector2d::Zero()), 1.1, ulps(4));
  const auto r = a.rotated(pi / 2);
  EXPECT_TRUE(r.com().isApprox(Eigen::Vector2d(0, 1), ulps(4)) || r.com().x() < ulps(4));
  EXPECT_NEAR(r.com().y(), 1.0, ulps(4));
  EXPECT_EQ(r.moment_com(), 0.1);
  EXPECT_RIGID_ERROR(MassProperties2(1.0, Eigen::Vector2d::Zero(), -1.0),
                     "moment of inertia must be non-negative and finite, got -1 kg·m²");
  EXPECT_EQ(fmt::format("{}", a), "MassProperties2{mass: 1 kg, com: [1, 0] m, moment_com: 0.1 kg·m²}");
}

}  // namespace
}  // namespace rigid
