#include "rigid/mass/density.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

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

// ---- a closed triangle mesh (integrate_density_over_mesh) ----

struct PrismMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// The prism over a polygon (counter-clockwise, triangulated by `caps`) from z = 0 to z = h,
// outward oriented: top as given, bottom reversed, two triangles per side.
PrismMesh prism(const std::vector<Eigen::Vector2d>& polygon,
                const std::vector<std::array<std::uint32_t, 3>>& caps, double h) {
  PrismMesh m;
  const auto n = static_cast<std::uint32_t>(polygon.size());
  for (const Eigen::Vector2d& p : polygon) m.vertices.emplace_back(p.x(), p.y(), 0.0);
  for (const Eigen::Vector2d& p : polygon) m.vertices.emplace_back(p.x(), p.y(), h);
  for (const auto& c : caps) {
    m.triangles.push_back({n + c[0], n + c[1], n + c[2]});
    m.triangles.push_back({c[0], c[2], c[1]});
  }
  for (std::uint32_t a = 0; a < n; ++a) {
    const std::uint32_t b = (a + 1) % n;
    m.triangles.push_back({a, b, n + b});
    m.triangles.push_back({a, n + b, n + a});
  }
  return m;
}

// The box [lo, hi] as a prism mesh.
PrismMesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  PrismMesh m = prism({{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}},
                      {{0, 1, 2}, {0, 2, 3}}, hi.z() - lo.z());
  for (Eigen::Vector3d& v : m.vertices) v.z() += lo.z();
  return m;
}

// ρ over the box [lo, hi] by the box cubature (centred at the origin: ρ shifted), moved back.
mass::DensityIntegration over_box(const mass::DensityFunction& rho, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi) {
  const Eigen::Vector3d c = 0.5 * (lo + hi), size = hi - lo;
  mass::DensityIntegration r = mass::integrate_density_over_box(
      [&](const Eigen::Vector3d& p) { return rho(p + c); }, size.x(), size.y(), size.z());
  r.mass_properties = r.mass_properties.shifted(c);
  return r;
}

// Mass, COM and inertia within the sum of both estimates plus `slack` relative.
void expect_same(const mass::DensityIntegration& a, const MassProperties& b, double com_error,
                 double inertia_error, double slack) {
  const MassProperties& x = a.mass_properties;
  EXPECT_NEAR(x.mass(), b.mass(), a.mass_error + slack * b.mass());
  EXPECT_LE((x.com() - b.com()).cwiseAbs().maxCoeff(), com_error + slack * b.com().norm() + 1e-15);
  EXPECT_LE((x.inertia_com() - b.inertia_com()).cwiseAbs().maxCoeff(),
            inertia_error + slack * b.inertia_com().trace());
}

TEST(DensityMeshCubature, UniformCubeEqualsPrimitive) {
  // a cube away from the origin: the COM is the cube's centre, I = m a²/6 · 1; the rules are
  // exact for a constant (degree 2 in the moments), so only round-off remains
  const Eigen::Vector3d lo(1.0, -2.0, 0.5), hi = lo + Eigen::Vector3d::Constant(0.4);
  const PrismMesh m = box_mesh(lo, hi);
  const auto r = mass::integrate_density_over_mesh([](const Eigen::Vector3d&) { return 2700.0; },
                                                   m.vertices, m.triangles);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.cells, 12);  // one tetrahedron per triangle: nothing split
  const MassProperties expected =
      mass::solid_box_with_density(2700.0, 0.4, 0.4, 0.4).shifted(0.5 * (lo + hi));
  expect_same(r, expected, 0, 0, 1e-13);
}

TEST(DensityMeshCubature, PolynomialDensityOverANonConvexPrismEqualsItsBoxes) {
  // A U-shaped prism: the vertices' centroid (1.5, 1.25) lies in the notch, outside the solid,
  // so tetrahedra reach outside and cancel. ρ of degree 3 (moments of degree 5): both rules
  // exact, nothing split. The reference: the U as three boxes by the box cubature.
  const std::vector<Eigen::Vector2d> u = {{0, 0}, {3, 0}, {3, 2}, {2, 2},
                                          {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const PrismMesh m = prism(u, {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {0, 4, 5}, {0, 5, 6}, {0, 6, 7}},
                            0.5);
  const auto rho = [](const Eigen::Vector3d& p) { return 1.0 + p.x() + p.y() * p.y() * p.z(); };
  const auto r = mass::integrate_density_over_mesh(rho, m.vertices, m.triangles);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.cells, static_cast<int>(m.triangles.size()));
  const auto a = over_box(rho, {0, 0, 0}, {1, 2, 0.5});
  const auto b = over_box(rho, {1, 0, 0}, {2, 1, 0.5});
  const auto c = over_box(rho, {2, 0, 0}, {3, 2, 0.5});
  const std::array<MassProperties, 3> parts = {a.mass_properties, b.mass_properties,
                                               c.mass_properties};
  // the box cubature of a cubic is exact too: only round-off (1e-12 relative) separates them
  expect_same(r, rigid::combine(parts), 1e-12, 1e-12 * rigid::combine(parts).inertia_com().trace(),
              1e-12);
}

TEST(DensityMeshCubature, SmoothDensityIsRefinedToItsEstimate) {
  // exp(x) (1 + y z) is no polynomial: the worst tetrahedra are split until the estimate meets
  // 1e-10, and the result agrees with the box cubature (its own estimate 1e-10) within the two
  // estimates
  const Eigen::Vector3d lo(-0.5, 0.0, 0.2), hi(1.5, 0.8, 1.0);
  const PrismMesh m = box_mesh(lo, hi);
  const auto rho = [](const Eigen::Vector3d& p) { return std::exp(2 * p.x()) * (1 + p.y() * p.z()); };
  const auto r = mass::integrate_density_over_mesh(rho, m.vertices, m.triangles);
  const auto ref = over_box(rho, lo, hi);
  EXPECT_TRUE(r.converged);
  EXPECT_GT(r.cells, 12);
  expect_same(r, ref.mass_properties, r.com_error + ref.com_error,
              r.inertia_error + ref.inertia_error, 1e-12);
  EXPECT_LT(r.mass_error, 1e-9 * r.mass_properties.mass());
}

TEST(DensityMeshCubature, SplitTetrahedraTileTheirParent) {
  // ρ = 1 + x⁸ (moments of degree 10): the degree-9 rule is not exact, so tetrahedra are split;
  // the closed form over the cube [0, 1]³: m = 1 + 1/9, ∫ρx = 1/2 + 1/10, so a wrong tiling
  // (a child missing, overlapping or mis-weighted) would show as an error far above 1e-10
  const PrismMesh m = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  const auto r = mass::integrate_density_over_mesh(
      [](const Eigen::Vector3d& p) { return 1.0 + std::pow(p.x(), 8); }, m.vertices, m.triangles);
  EXPECT_GT(r.cells, 12);
  const double mass = 1.0 + 1.0 / 9;
  EXPECT_NEAR(r.mass_properties.mass(), mass, r.mass_error + 1e-14);
  EXPECT_NEAR(r.mass_properties.com().x(), (0.5 + 0.1) / mass, r.com_error + 1e-14);
  EXPECT_NEAR(r.mass_properties.com().y(), 0.5, r.com_error + 1e-14);
}

TEST(DensityMeshCubature, BadInput) {
  const PrismMesh m = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  EXPECT_RIGID_ERROR((void)mass::integrate_density_over_mesh(
                         [](const Eigen::Vector3d& p) { return p.x() - 0.5; }, m.vertices,
                         m.triangles),
                     "integrate_density_over_mesh(): density must be non-negative and finite, got -");
  EXPECT_RIGID_ERROR((void)mass::integrate_density_over_mesh(
                         [](const Eigen::Vector3d&) { return 0.0; }, m.vertices, m.triangles),
                     "the density integrates to a mass of 0 kg");
  PrismMesh open = m;
  open.triangles.pop_back();
  EXPECT_RIGID_ERROR((void)mass::integrate_density_over_mesh(
                         [](const Eigen::Vector3d&) { return 1.0; }, open.vertices, open.triangles),
                     "the mesh is not closed and consistently oriented");
  PrismMesh flipped = m;
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_RIGID_ERROR((void)mass::integrate_density_over_mesh(
                         [](const Eigen::Vector3d&) { return 1.0; }, flipped.vertices,
                         flipped.triangles),
                     "is used twice in the same direction");
  const std::vector<std::array<std::uint32_t, 3>> missing = {{0, 1, 99}};
  EXPECT_RIGID_ERROR((void)mass::integrate_density_over_mesh(
                         [](const Eigen::Vector3d&) { return 1.0; }, m.vertices, missing),
                     "a triangle names vertex 99; the mesh has 8");
}

}  // namespace
}  // namespace rigid
