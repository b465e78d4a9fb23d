#include "rigid/mass/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "mass/reference_quadrature.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using std::numbers::pi;
using test::BodyMap;
using test::MappedPoint;
using test::reference_moments;
using test::ReferenceMoments;

// Closed forms are checked to 1e-12 relative (the issue's bar; the formulas are a handful
// of flops, so the actual agreement is a few ε).
constexpr double kClosedFormRel = 1e-12;

void expect_closed_form(const MassProperties& mp, double m, const Eigen::Vector3d& com,
                        const Eigen::Vector3d& I_diag) {
  EXPECT_NEAR(mp.mass(), m, kClosedFormRel * m);
  const double length = std::sqrt(I_diag.maxCoeff() / m) + com.norm();
  EXPECT_TRUE((mp.com() - com).cwiseAbs().maxCoeff() <= kClosedFormRel * length)
      << mp.com().transpose() << " vs " << com.transpose();
  const Eigen::Matrix3d I = I_diag.asDiagonal();
  EXPECT_TRUE((mp.inertia_com() - I).cwiseAbs().maxCoeff() <= kClosedFormRel * I_diag.maxCoeff())
      << mp.inertia_com() << "\nvs\n" << I;
}

void expect_matches_reference(const MassProperties& mp, const ReferenceMoments& ref) {
  EXPECT_NEAR(mp.mass(), ref.mass, ref.mass_error);
  EXPECT_LE((mp.com() - ref.com).cwiseAbs().maxCoeff(), ref.com_error)
      << mp.com().transpose() << " vs " << ref.com.transpose();
  EXPECT_LE((mp.inertia_com() - ref.inertia_com).cwiseAbs().maxCoeff(), ref.inertia_error)
      << mp.inertia_com() << "\nvs\n" << ref.inertia_com;
  // the reference itself must be sharp enough to catch a wrong coefficient (≥ 1e-6 relative)
  EXPECT_LT(ref.inertia_error, 1e-9 * ref.inertia_com.trace());
}

// ball of radius s ∈ [s0, s1] (polar angle θ ∈ [θ0, θ1]) around c, density ρ.
BodyMap ball_map(double rho, double s0, double s1, double th0 = 0.0, double th1 = pi,
                 const Eigen::Vector3d& c = Eigen::Vector3d::Zero(),
                 const Eigen::Vector3d& scale = Eigen::Vector3d::Ones()) {
  return [=](const Eigen::Vector3d& u) {
    const double s = s0 + (s1 - s0) * u(0);
    const double th = th0 + (th1 - th0) * u(1);
    const double ph = 2.0 * pi * u(2);
    const Eigen::Vector3d dir(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                              std::cos(th));
    return MappedPoint{c + s * scale.cwiseProduct(dir),
                       rho * scale.prod() * (s1 - s0) * (th1 - th0) * 2.0 * pi * s * s *
                           std::sin(th)};
  };
}

// solid of revolution about z: radius from r_in(z) to r_out(z), z ∈ [z0, z1].
template <typename Rin, typename Rout>
BodyMap revolution_map(double rho, double z0, double z1, Rin r_in, Rout r_out) {
  return [=](const Eigen::Vector3d& u) {
    const double z = z0 + (z1 - z0) * u(2);
    const double a = r_in(z);
    const double b = r_out(z);
    const double s = a + (b - a) * u(0);
    const double th = 2.0 * pi * u(1);
    return MappedPoint{Eigen::Vector3d(s * std::cos(th), s * std::sin(th), z),
                       rho * (z1 - z0) * (b - a) * 2.0 * pi * s};
  };
}

TEST(Primitives, SolidSphere) {
  const double rho = 7.8;
  const double r = 0.3;
  const double m = rho * 4.0 / 3.0 * pi * r * r * r;
  const auto mp = mass::solid_sphere_with_density(rho, r);
  expect_closed_form(mp, m, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.4 * m * r * r));
  expect_matches_reference(mp, reference_moments({ball_map(rho, 0, r)}));
  expect_closed_form(mass::solid_sphere_with_mass(2.0, r), 2.0, Eigen::Vector3d::Zero(),
                     Eigen::Vector3d::Constant(0.4 * 2.0 * r * r));
}

TEST(Primitives, ThickSphericalShell) {
  const double rho = 2.0;
  const double r1 = 0.2;
  const double r2 = 0.5;
  const double m = rho * 4.0 / 3.0 * pi * (std::pow(r2, 3) - std::pow(r1, 3));
  const double I = 0.4 * m * (std::pow(r2, 5) - std::pow(r1, 5)) / (std::pow(r2, 3) - std::pow(r1, 3));
  const auto mp = mass::thick_spherical_shell_with_density(rho, r1, r2);
  expect_closed_form(mp, m, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(I));
  expect_matches_reference(mp, reference_moments({ball_map(rho, r1, r2)}));
  // identity: a shell is a sphere minus a sphere
  const auto diff = subtract(mass::solid_sphere_with_density(rho, r2),
                             mass::solid_sphere_with_density(rho, r1));
  expect_closed_form(diff, m, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(I));
}

TEST(Primitives, ThinSphericalShell) {
  const double sigma = 3.0;
  const double r = 0.7;
  const double m = sigma * 4.0 * pi * r * r;
  const auto mp = mass::thin_spherical_shell_with_density(sigma, r);
  expect_closed_form(mp, m, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(2.0 / 3.0 * m * r * r));
  const BodyMap surface = [=](const Eigen::Vector3d& u) {
    const double th = pi * u(0);
    const double ph = 2.0 * pi * u(1);
    return MappedPoint{r * Eigen::Vector3d(std::sin(th) * std::cos(ph),
                                           std::sin(th) * std::sin(ph), std::cos(th)),
                       sigma * pi * 2.0 * pi * r * r * std::sin(th)};
  };
  expect_matches_reference(mp, reference_moments({surface}));
}

TEST(Primitives, SolidEllipsoid) {
  const double rho = 1.3;
  const double a = 0.5;
  const double b = 0.3;
  const double c = 0.2;
  const double m = rho * 4.0 / 3.0 * pi * a * b * c;
  const auto mp = mass::solid_ellipsoid_with_density(rho, a, b, c);
  expect_closed_form(mp, m, Eigen::Vector3d::Zero(),
                     m / 5.0 * Eigen::Vector3d(b * b + c * c, a * a + c * c, a * a + b * b));
  expect_matches_reference(
      mp, reference_moments({ball_map(rho, 0, 1, 0, pi, Eigen::Vector3d::Zero(),
                                      Eigen::Vector3d(a, b, c))}));
}

TEST(Primitives, SolidBox) {
  const double rho = 500.0;
  const double lx = 0.4;
  const double ly = 0.2;
  const double lz = 0.1;
  const double m = rho * lx * ly * lz;
  const auto mp = mass::solid_box_with_density(rho, lx, ly, lz);
  expect_closed_form(mp, m, Eigen::Vector3d::Zero(),
                     m / 12.0 * Eigen::Vector3d(ly * ly + lz * lz, lx * lx + lz * lz, lx * lx + ly * ly));
  const BodyMap map = [=](const Eigen::Vector3d& u) {
    return MappedPoint{(u - Eigen::Vector3d::Constant(0.5)).cwiseProduct(Eigen::Vector3d(lx, ly, lz)),
                       rho * lx * ly * lz};
  };
  expect_matches_reference(mp, reference_moments({map}));
}

TEST(Primitives, SolidCylinder) {
  const double rho = 2700.0;
  const double r = 0.1;
  const double h = 0.5;
  const double m = rho * pi * r * r * h;
  const auto mp = mass::solid_cylinder_with_density(rho, r, h);
  const double Ixx = m * (3 * r * r + h * h) / 12.0;
  expect_closed_form(mp, m, Eigen::Vector3d::Zero(), Eigen::Vector3d(Ixx, Ixx, m * r * r / 2.0));
  expect_matches_reference(
      mp, reference_moments({revolution_map(rho, -h / 2, h / 2, [](double) { return 0.0; },
                                            [=](double) { return r; })}));
}

TEST(Primitives, ThickTubeIsCylinderMinusCylinder) {
  const double rho = 800.0;
  const double r1 = 0.02;
  const double r2 = 0.06;
  const double h = 0.3;
  const double m = rho * pi * (r2 * r2 - r1 * r1) * h;
  const double Ixx = m * (3 * (r1 * r1 + r2 * r2) + h * h) / 12.0;
  const Eigen::Vector3d I(Ixx, Ixx, m * (r1 * r1 + r2 * r2) / 2.0);
  const auto mp = mass::thick_tube_with_density(rho, r1, r2, h);
  expect_closed_form(mp, m, Eigen::Vector3d::Zero(), I);
  expect_matches_reference(
      mp, reference_moments({revolution_map(rho, -h / 2, h / 2, [=](double) { return r1; },
                                            [=](double) { return r2; })}));
  const auto diff = subtract(mass::solid_cylinder_with_density(rho, r2, h),
                             mass::solid_cylinder_with_density(rho, r1, h));
  expect_closed_form(diff, m, Eigen::Vector3d::Zero(), I);
}

TEST(Primitives, ThinCylindricalShells) {
  const double sigma = 4.0;
  const double r = 0.25;
  const double h = 0.6;
  const BodyMap lateral = [=](const Eigen::Vector3d& u) {
    const double th = 2.0 * pi * u(0);
    return MappedPoint{Eigen::Vector3d(r * std::cos(th), r * std::sin(th), h * (u(1) - 0.5)),
                       sigma * 2.0 * pi * r * h};
  };
  const double m = sigma * 2.0 * pi * r * h;
  const auto open = mass::thin_cylindrical_shell_with_density(sigma, r, h);
  const double Ixx = m * (r * r / 2.0 + h * h / 12.0);
  expect_closed_form(open, m, Eigen::Vector3d::Zero(), Eigen::Vector3d(Ixx, Ixx, m * r * r));
  expect_matches_reference(open, reference_moments({lateral}));

  auto cap = [=](double z) -> BodyMap {
    return [=](const Eigen::Vector3d& u) {
      const double s = r * u(0);
      const double th = 2.0 * pi * u(1);
      return MappedPoint{Eigen::Vector3d(s * std::cos(th), s * std::sin(th), z),
                         sigma * r * 2.0 * pi * s};
    };
  };
  const auto capped = mass::capped_cylindrical_shell_with_density(sigma, r, h);
  const double m_cap = sigma * pi * r * r;
  const double Ixx_c = Ixx + 2.0 * m_cap * (r * r / 4.0 + h * h / 4.0);
  expect_closed_form(capped, m + 2 * m_cap, Eigen::Vector3d::Zero(),
                     Eigen::Vector3d(Ixx_c, Ixx_c, m * r * r + m_cap * r * r));
  expect_matches_reference(capped, reference_moments({lateral, cap(h / 2), cap(-h / 2)}));
}

TEST(Primitives, SolidConeComAtQuarterHeight) {
  const double rho = 1000.0;
  const double r = 0.3;
  const double h = 1.2;
  const double m = rho * pi * r * r * h / 3.0;
  const double Ixx = m * (3.0 * r * r / 20.0 + 3.0 * h * h / 80.0);
  const auto mp = mass::solid_cone_with_density(rho, r, h);
  expect_closed_form(mp, m, Eigen::Vector3d(0, 0, h / 4), Eigen::Vector3d(Ixx, Ixx, 0.3 * m * r * r));
  expect_matches_reference(
      mp, reference_moments({revolution_map(rho, 0, h, [](double) { return 0.0; },
                                            [=](double z) { return r * (1 - z / h); })}));
}

TEST(Primitives, FrustumPlusSmallConeIsCone) {
  const double rho = 1000.0;
  const double r = 0.3;
  const double h = 1.2;
  const double cut = 0.5;  // frustum from z = 0 to z = cut
  const double r_top = r * (1 - cut / h);
  const auto frustum = mass::solid_frustum_with_density(rho, r, r_top, cut);
  expect_matches_reference(
      frustum, reference_moments({revolution_map(rho, 0, cut, [](double) { return 0.0; },
                                                 [=](double z) { return r * (1 - z / h); })}));
  const auto tip = mass::solid_cone_with_density(rho, r_top, h - cut).shifted(Eigen::Vector3d(0, 0, cut));
  const auto whole = mass::solid_cone_with_density(rho, r, h);
  const auto sum = combine(frustum, tip);
  EXPECT_NEAR(sum.mass(), whole.mass(), test::ulps(16, whole.mass()));
  EXPECT_TRUE(sum.com().isApprox(whole.com(), 1e-14));
  EXPECT_TRUE(sum.inertia_com().isApprox(whole.inertia_com(), 1e-13));
  // an inverted frustum (wider at the top) and the r₁ = r₂ cylinder limit
  const auto inverted = mass::solid_frustum_with_density(rho, 0.1, 0.4, 0.7);
  expect_matches_reference(
      inverted, reference_moments({revolution_map(rho, 0, 0.7, [](double) { return 0.0; },
                                                  [](double z) { return 0.1 + 0.3 * z / 0.7; })}));
  const auto cyl = mass::solid_frustum_with_density(rho, 0.2, 0.2, 0.4);
  const double m = rho * pi * 0.04 * 0.4;
  const double Ixx = m * (3 * 0.04 + 0.16) / 12.0;
  expect_closed_form(cyl, m, Eigen::Vector3d(0, 0, 0.2), Eigen::Vector3d(Ixx, Ixx, m * 0.02));
}

TEST(Primitives, SolidCapsule) {
  const double rho = 900.0;
  const double r = 0.1;
  const double l = 0.4;
  const auto mp = mass::solid_capsule_with_density(rho, r, l);
  const double m_c = rho * pi * r * r * l;
  const double m_h = rho * 2.0 / 3.0 * pi * r * r * r;
  const double Ixx = m_c * (l * l / 12 + r * r / 4) + 2 * m_h * (0.4 * r * r + l * l / 4 + 3 * l * r / 8);
  expect_closed_form(mp, m_c + 2 * m_h, Eigen::Vector3d::Zero(),
                     Eigen::Vector3d(Ixx, Ixx, m_c * r * r / 2 + 2 * m_h * 0.4 * r * r));
  expect_matches_reference(
      mp, reference_moments({revolution_map(rho, -l / 2, l / 2, [](double) { return 0.0; },
                                            [=](double) { return r; }),
                             ball_map(rho, 0, r, 0, pi / 2, Eigen::Vector3d(0, 0, l / 2)),
                             ball_map(rho, 0, r, pi / 2, pi, Eigen::Vector3d(0, 0, -l / 2))}));
  // l = 0 is a sphere
  const auto sphere = mass::solid_capsule_with_density(rho, r, 0.0);
  const auto expected = mass::solid_sphere_with_density(rho, r);
  EXPECT_NEAR(sphere.inertia_com()(0, 0), expected.inertia_com()(0, 0), test::ulps(16, expected.inertia_com()(0, 0)));
}

TEST(Primitives, SolidTorus) {
  const double rho = 1100.0;
  const double R = 0.5;
  const double a = 0.1;
  const double m = rho * 2 * pi * pi * R * a * a;
  const auto mp = mass::solid_torus_with_density(rho, R, a);
  const double Ixx = m * (R * R / 2 + 5 * a * a / 8);
  expect_closed_form(mp, m, Eigen::Vector3d::Zero(), Eigen::Vector3d(Ixx, Ixx, m * (R * R + 0.75 * a * a)));
  const BodyMap map = [=](const Eigen::Vector3d& u) {
    const double s = a * u(0);
    const double al = 2 * pi * u(1);
    const double ph = 2 * pi * u(2);
    const double w = R + s * std::cos(al);
    return MappedPoint{Eigen::Vector3d(w * std::cos(ph), w * std::sin(ph), s * std::sin(al)),
                       rho * a * 4 * pi * pi * s * w};
  };
  expect_matches_reference(mp, reference_moments({map}));
}

TEST(Primitives, ThinRodPlateDisk) {
  const double lambda = 0.5;
  const double l = 2.0;
  const auto rod = mass::thin_rod_with_density(lambda, l);
  const double m_rod = lambda * l;
  expect_closed_form(rod, m_rod, Eigen::Vector3d::Zero(),
                     Eigen::Vector3d(m_rod * l * l / 12, m_rod * l * l / 12, 0));
  expect_matches_reference(rod, reference_moments({[=](const Eigen::Vector3d& u) {
                             return MappedPoint{Eigen::Vector3d(0, 0, l * (u(0) - 0.5)), lambda * l};
                           }}));

  const double sigma = 10.0;
  const double lx = 0.3;
  const double ly = 0.2;
  const auto plate = mass::thin_rectangular_plate_with_density(sigma, lx, ly);
  const double m_p = sigma * lx * ly;
  expect_closed_form(plate, m_p, Eigen::Vector3d::Zero(),
                     m_p / 12 * Eigen::Vector3d(ly * ly, lx * lx, lx * lx + ly * ly));
  expect_matches_reference(plate, reference_moments({[=](const Eigen::Vector3d& u) {
                             return MappedPoint{Eigen::Vector3d(lx * (u(0) - 0.5), ly * (u(1) - 0.5), 0),
                                                sigma * lx * ly};
                           }}));

  const double r = 0.4;
  const auto disk = mass::thin_disk_with_density(sigma, r);
  const double m_d = sigma * pi * r * r;
  expect_closed_form(disk, m_d, Eigen::Vector3d::Zero(),
                     m_d * r * r * Eigen::Vector3d(0.25, 0.25, 0.5));
  expect_matches_reference(disk, reference_moments({[=](const Eigen::Vector3d& u) {
                             const double s = r * u(0);
                             const double th = 2 * pi * u(1);
                             return MappedPoint{Eigen::Vector3d(s * std::cos(th), s * std::sin(th), 0),
                                                sigma * r * 2 * pi * s};
                           }}));
}

TEST(Primitives, ThinRingIsACircleOfMatter) {
  // closed form: every element at distance r from z, I_zz = m r², I_xx = I_yy = m r²/2
  const double lambda = 0.7;
  const double r = 0.5;
  const auto hoop = mass::thin_ring_with_density(lambda, r);
  const double m = lambda * 2 * pi * r;
  expect_closed_form(hoop, m, Eigen::Vector3d::Zero(), m * r * r * Eigen::Vector3d(0.5, 0.5, 1.0));
  // the line integral ∫ λ (…) ds over the circle, by the reference quadrature
  expect_matches_reference(hoop, reference_moments({[=](const Eigen::Vector3d& u) {
                             const double th = 2 * pi * u(0);
                             return MappedPoint{Eigen::Vector3d(r * std::cos(th), r * std::sin(th), 0),
                                                lambda * 2 * pi * r};
                           }}));
  // the acceptance numbers of `rigid inertia hoop --radius 0.5 --mass 2`
  expect_closed_form(mass::thin_ring_with_mass(2.0, 0.5), 2.0, Eigen::Vector3d::Zero(),
                     Eigen::Vector3d(0.25, 0.25, 0.5));
  // the thin limit of the solid torus: a → 0 gives the ring (relative difference 5a²/(4R²))
  const auto torus = mass::solid_torus_with_mass(2.0, 0.5, 1e-4);
  EXPECT_NEAR(torus.inertia_com()(2, 2), 0.5, 0.5 * 1e-7);  // 3a²/(4R²) = 3e-8
  EXPECT_RIGID_ERROR((void)mass::thin_ring_with_mass(1.0, 0.0), "radius must be positive and finite, got 0 m");
}

TEST(Primitives, PerpendicularAxisTheoremForPlates) {
  // thin bodies in the xy-plane: I_zz = I_xx + I_yy exactly.
  for (const auto& mp : {mass::thin_rectangular_plate_with_mass(1.5, 0.3, 0.7),
                         mass::thin_disk_with_mass(2.0, 0.4)}) {
    const Eigen::Matrix3d& I = mp.inertia_com();
    EXPECT_NEAR(I(2, 2), I(0, 0) + I(1, 1), test::ulps(4, I(2, 2)));
  }
}

TEST(Primitives, Tetrahedron) {
  // the unit corner tetrahedron has known moments: V = 1/6, COM (1/4, 1/4, 1/4), and about
  // the origin ∫x² dV = 1/60, ∫x y dV = 1/120 (so per unit density I_O,xx = 2/60, −1/120).
  const Eigen::Vector3d o(0, 0, 0);
  const Eigen::Vector3d ex(1, 0, 0);
  const Eigen::Vector3d ey(0, 1, 0);
  const Eigen::Vector3d ez(0, 0, 1);
  const auto tet = mass::solid_tetrahedron_with_density(6.0, o, ex, ey, ez);  // mass 1
  EXPECT_NEAR(tet.mass(), 1.0, test::ulps(8));
  EXPECT_TRUE(tet.com().isApprox(Eigen::Vector3d::Constant(0.25), test::ulps(8)));
  Eigen::Matrix3d I_O;
  I_O << 0.2, -0.05, -0.05, -0.05, 0.2, -0.05, -0.05, -0.05, 0.2;  // 6·(2/60), −6·(1/120)
  EXPECT_TRUE(tet.inertia_about(o).isApprox(I_O, test::ulps(32))) << tet.inertia_about(o);
  // a general tetrahedron against quadrature (Duffy map from the cube onto the simplex)
  const Eigen::Vector3d v0(0.1, -0.2, 0.3);
  const Eigen::Vector3d v1(1.1, 0.2, 0.0);
  const Eigen::Vector3d v2(-0.3, 0.9, 0.4);
  const Eigen::Vector3d v3(0.2, 0.1, 1.3);
  const double rho = 3.0;
  const auto mp = mass::solid_tetrahedron_with_density(rho, v3, v1, v2, v0);  // other orientation
  Eigen::Matrix3d E;
  E << v1 - v0, v2 - v0, v3 - v0;
  const double det = std::abs(E.determinant());
  const BodyMap duffy = [=](const Eigen::Vector3d& u) {
    const Eigen::Vector3d abc(u(0), (1 - u(0)) * u(1), (1 - u(0)) * (1 - u(1)) * u(2));
    return MappedPoint{v0 + E * abc, rho * det * (1 - u(0)) * (1 - u(0)) * (1 - u(1))};
  };
  expect_matches_reference(mp, reference_moments({duffy}));
  EXPECT_RIGID_ERROR((void)mass::solid_tetrahedron_with_mass(1.0, o, ex, ey, ex + ey),
                     "solid_tetrahedron_with_mass(): the tetrahedron is degenerate");
}

TEST(Primitives, PointMasses) {
  const double masses[] = {1.0, 2.0, 3.0};
  Eigen::Matrix3Xd pts(3, 3);
  pts << 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const auto mp = mass::point_masses(masses, pts);
  EXPECT_EQ(mp.mass(), 6.0);
  EXPECT_TRUE(mp.com().isApprox(Eigen::Vector3d(1, 2, 3) / 6.0, test::ulps(4)));
  // about the origin: I_O = Σ m (|p|² 1 − p pᵀ) = diag(2+3, 1+3, 1+2)
  EXPECT_TRUE(mp.inertia_about(Eigen::Vector3d::Zero())
                  .isApprox(Eigen::Vector3d(5, 4, 3).asDiagonal().toDenseMatrix(), test::ulps(16)));
  EXPECT_RIGID_ERROR((void)mass::point_masses(std::span<const double>(masses, 2), pts),
                     "got 2 masses but 3 points");
  EXPECT_RIGID_ERROR((void)mass::point_mass(-1, Eigen::Vector3d::Zero()),
                     "point_mass(): mass must be positive and finite, got -1 kg");
}

TEST(Primitives, RotationInvarianceOfPrincipalMoments) {
  const auto box = mass::solid_box_with_mass(2.0, 0.3, 0.5, 0.7);
  const Eigen::Vector3d expected = box.inertia_com().diagonal();
  for (double angle : {0.3, 1.7, 3.0}) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(angle, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
    const auto rotated = box.rotated(R).shifted(Eigen::Vector3d(1, 2, 3));
    Eigen::Vector3d sorted = expected;
    std::sort(sorted.data(), sorted.data() + 3);
    EXPECT_TRUE(rotated.principal_axes().moments.isApprox(sorted, test::ulps(64)));
    // the principal frame maps back onto the box axes (up to order and sign)
    const Eigen::Matrix3d R_BP = rotated.principal_axes().R_BP;
    EXPECT_TRUE((R_BP.transpose() * R).cwiseAbs().rowwise().maxCoeff().isApprox(
        Eigen::Vector3d::Ones(), 1e-12));
  }
}

TEST(Primitives, BadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_RIGID_ERROR((void)mass::solid_cylinder_with_mass(1.0, -0.5, 1.0),
                     "solid_cylinder_with_mass(): radius must be positive and finite, got -0.5 m");
  EXPECT_RIGID_ERROR((void)mass::solid_cylinder_with_mass(1.0, 0.5, 0.0),
                     "height must be positive and finite, got 0 m");
  EXPECT_RIGID_ERROR((void)mass::solid_box_with_density(1.0, nan, 1, 1),
                     "lx must be positive and finite, got nan m");
  EXPECT_RIGID_ERROR((void)mass::solid_sphere_with_mass(1.0, inf),
                     "radius must be positive and finite, got inf m");
  EXPECT_RIGID_ERROR((void)mass::solid_sphere_with_mass(0.0, 1.0),
                     "solid_sphere_with_mass(): mass must be positive and finite, got 0 kg");
  EXPECT_RIGID_ERROR((void)mass::solid_sphere_with_density(-2.0, 1.0),
                     "density must be positive and finite, got -2 kg/m³");
  EXPECT_RIGID_ERROR((void)mass::thin_disk_with_density(-2.0, 1.0),
                     "density must be positive and finite, got -2 kg/m²");
  EXPECT_RIGID_ERROR((void)mass::thick_tube_with_mass(1.0, 0.2, 0.1, 1.0),
                     "inner radius must be less than outer radius, got inner radius = 0.2 m and "
                     "outer radius = 0.1 m");
  EXPECT_RIGID_ERROR((void)mass::thick_spherical_shell_with_mass(1.0, 0.2, 0.2),
                     "inner radius must be less than outer radius");
  EXPECT_RIGID_ERROR((void)mass::solid_torus_with_mass(1.0, 0.1, 0.2),
                     "minor radius a must not exceed major radius R");
  EXPECT_RIGID_ERROR((void)mass::solid_capsule_with_mass(1.0, 0.1, -1.0),
                     "length must be non-negative and finite, got -1 m");
  EXPECT_RIGID_ERROR((void)mass::solid_frustum_with_mass(1.0, 0.1, 0.0, 1.0),
                     "top radius must be positive and finite, got 0 m");
}

}  // namespace
}  // namespace rigid
