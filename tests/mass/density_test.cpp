#include "rigid/mass/density.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using std::numbers::pi;

TEST(DensityCubature, UniformBoxEqualsPrimitive) {
  const auto res = mass::integrate_density_over_box([](const Eigen::Vector3d&) { return 7.0; }, 0.3,
                                                    0.5, 0.7);
  const auto expected = mass::solid_box_with_density(7.0, 0.3, 0.5, 0.7);
  EXPECT_TRUE(res.converged);
  EXPECT_NEAR(res.mass_properties.mass(), expected.mass(), res.mass_error + test::ulps(64, expected.mass()));
  EXPECT_TRUE((res.mass_properties.inertia_com() - expected.inertia_com()).cwiseAbs().maxCoeff() <=
              res.inertia_error + test::ulps(256, expected.inertia_com().trace()));
}

TEST(DensityCubature, LinearDensityBoxClosedForm) {
  // ρ = ρ₀ (1 + x/a) over [−a/2, a/2] × [−b/2, b/2] × [−c/2, c/2]:
  // m = ρ₀ abc, ∫ρx = ρ₀ bc a³/(12 a) → x_C = a/12; ∫ρ x² = ρ₀ a³bc/12 (the odd part drops).
  const double rho0 = 3.0;
  const double a = 0.6;
  const double b = 0.4;
  const double c = 0.2;
  const auto res = mass::integrate_density_over_box(
      [=](const Eigen::Vector3d& p) { return rho0 * (1 + p.x() / a); }, a, b, c);
  const double m = rho0 * a * b * c;
  EXPECT_NEAR(res.mass_properties.mass(), m, res.mass_error + test::ulps(64, m));
  EXPECT_NEAR(res.mass_properties.com().x(), a / 12, res.com_error + test::ulps(64, a));
  // I_xx (about the COM) = m (b² + c²)/12 (y, z uniform and centred)
  EXPECT_NEAR(res.mass_properties.inertia_com()(0, 0), m * (b * b + c * c) / 12,
              res.inertia_error + test::ulps(256, m * a * a));
  // I_yy = ∫ρ(x² + z²) − m x_C² = m a²/12 + m c²/12 − m a²/144
  EXPECT_NEAR(res.mass_properties.inertia_com()(1, 1), m * (a * a / 12 + c * c / 12 - a * a / 144),
              res.inertia_error + test::ulps(256, m * a * a));
}

TEST(DensityCubature, RadialDensitySphere) {
  // ρ = ρ₀ (1 − s²/R²): m = ρ₀ 4π (R³/3 − R³/5) = 8π ρ₀ R³/15;
  // I = (2/3) ∫ρ s² dV = (2/3) ρ₀ 4π (R⁵/5 − R⁵/7) = 16π ρ₀ R⁵/105.
  const double rho0 = 5.0;
  const double R = 0.4;
  const auto res = mass::integrate_density_over_sphere(
      [=](const Eigen::Vector3d& p) { return rho0 * (1 - p.squaredNorm() / (R * R)); }, R);
  EXPECT_TRUE(res.converged);
  const double m = 8 * pi * rho0 * std::pow(R, 3) / 15;
  const double I = 16 * pi * rho0 * std::pow(R, 5) / 105;
  EXPECT_NEAR(res.mass_properties.mass(), m, res.mass_error + test::ulps(64, m));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(res.mass_properties.inertia_com()(k, k), I, res.inertia_error + test::ulps(256, I));
  }
}

TEST(DensityCubature, CylinderWithAxialGradientAndSmoothBump) {
  // ρ = ρ₀ (1 + z/h) on the cylinder of radius r, height h: m = ρ₀ π r² h,
  // z_C = ∫ z²/h dV / (ρ₀ π r² h)·ρ₀ = h²/12 / h · ... = h/12.
  const double rho0 = 2.0;
  const double r = 0.2;
  const double h = 0.6;
  const auto res = mass::integrate_density_over_cylinder(
      [=](const Eigen::Vector3d& p) { return rho0 * (1 + p.z() / h); }, r, h);
  const double m = rho0 * pi * r * r * h;
  EXPECT_NEAR(res.mass_properties.mass(), m, res.mass_error + test::ulps(64, m));
  EXPECT_NEAR(res.mass_properties.com().z(), h / 12, res.com_error + test::ulps(64, h));
  EXPECT_NEAR(res.mass_properties.inertia_com()(2, 2), m * r * r / 2,
              res.inertia_error + test::ulps(256, m * h * h));
  // a Gaussian bump is not a polynomial: the adaptive loop must refine, and the estimate
  // must still bound the true error. Reference: ∫ exp(−s²/w²) over the disk = π w² (1 − e^{−r²/w²}).
  const double w = 0.05;
  const auto bump = mass::integrate_density_over_cylinder(
      [=](const Eigen::Vector3d& p) { return std::exp(-(p.x() * p.x() + p.y() * p.y()) / (w * w)); },
      r, h, {.relative_tolerance = 1e-9});
  EXPECT_TRUE(bump.converged);
  EXPECT_GT(bump.cells, 1);
  const double m_bump = pi * w * w * (1 - std::exp(-r * r / (w * w))) * h;
  EXPECT_NEAR(bump.mass_properties.mass(), m_bump, bump.mass_error + test::ulps(64, m_bump));
  EXPECT_LT(bump.mass_error, 1e-8 * m_bump);
}

TEST(DensityCubature, BadInput) {
  EXPECT_RIGID_ERROR((void)mass::integrate_density_over_box(
                         [](const Eigen::Vector3d& p) { return p.x(); }, 1, 1, 1),
                     "integrate_density_over_box(): density must be non-negative and finite, got -");
  EXPECT_RIGID_ERROR((void)mass::integrate_density_over_sphere(
                         [](const Eigen::Vector3d&) { return 1.0; }, -1),
                     "radius must be positive and finite, got -1 m");
  EXPECT_RIGID_ERROR((void)mass::integrate_density_over_box(
                         [](const Eigen::Vector3d&) { return 0.0; }, 1, 1, 1),
                     "the density integrates to a mass of 0 kg");
}

}  // namespace
}  // namespace rigid
