#include "rigid/mesh/mesh_mass.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "mesh/detail/accumulate.hpp"
#include "mesh/mesh_builders.hpp"
#include "rigid/mesh/repair.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid::mesh {
namespace {

using test::ulps;

mesh::MassSpec density(double rho) { return {std::nullopt, rho, false, std::nullopt}; }

// Exact polyhedra: the expected values are closed forms; the mesh sums a few dozen terms
// of size ~1, so 1e-12 (≈ 4500 ε) is far above round-off and far below any formula error.
constexpr double kExact = 1e-12;

TEST(MeshMass, BoxMatchesClosedForm) {
  const double a = 0.3, b = 0.5, c = 0.7, rho = 2700;
  const auto r = mesh_mass_properties(test::box_mesh(a, b, c), density(rho));
  const double m = rho * a * b * c;
  EXPECT_NEAR(r.measure, a * b * c, kExact * a * b * c);
  EXPECT_NEAR(r.properties.mass(), m, kExact * m);
  EXPECT_TRUE(r.properties.com().isApprox(Eigen::Vector3d(a / 2, b / 2, c / 2), kExact));
  const Eigen::Matrix3d I = r.properties.inertia_com();
  const double scale = m * (a * a + b * b + c * c);
  EXPECT_NEAR(I(0, 0), m * (b * b + c * c) / 12, kExact * scale);
  EXPECT_NEAR(I(1, 1), m * (a * a + c * c) / 12, kExact * scale);
  EXPECT_NEAR(I(2, 2), m * (a * a + b * b) / 12, kExact * scale);
  EXPECT_NEAR(I(0, 1), 0.0, kExact * scale);
  EXPECT_NEAR(I(0, 2), 0.0, kExact * scale);
  EXPECT_NEAR(I(1, 2), 0.0, kExact * scale);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(MeshMass, UnitTetrahedronMatchesClosedForm) {
  // Tetrahedron (0, e1, e2, e3), density 1: V = 1/6, COM = (1/4)(1,1,1),
  // ∫x² dV = 1/60, ∫xy dV = 1/120 ⇒ I_C: diagonal 1/30 − (1/6)(2/16) = 1/80,
  // off-diagonal −1/120 + (1/6)(1/16) = 1/480.
  const auto r = mesh_mass_properties(
      test::tetra_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                       Eigen::Vector3d::UnitZ()),
      density(1.0));
  EXPECT_NEAR(r.properties.mass(), 1.0 / 6, kExact);
  EXPECT_TRUE(r.properties.com().isApprox(Eigen::Vector3d::Constant(0.25), kExact));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(r.properties.inertia_com()(i, j), i == j ? 1.0 / 80 : 1.0 / 480, kExact);
    }
  }
}

TEST(MeshMass, SquarePyramidMatchesClosedForm) {
  // Base side s on z = 0, apex at height h: V = s²h/3, COM at h/4,
  // I_zz = m s²/10, I_xx = I_yy = m (s²/20 + 3h²/80).
  const double s = 2.0, h = 3.0;
  TriangleMesh p;
  p.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, h}};
  p.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  const auto r = mesh_mass_properties(p, density(1.0));
  const double m = s * s * h / 3;
  EXPECT_NEAR(r.properties.mass(), m, kExact * m);
  EXPECT_TRUE(r.properties.com().isApprox(Eigen::Vector3d(0, 0, h / 4), kExact));
  const Eigen::Matrix3d I = r.properties.inertia_com();
  EXPECT_NEAR(I(2, 2), m * s * s / 10, kExact * m * h * h);
  EXPECT_NEAR(I(0, 0), m * (s * s / 20 + 3 * h * h / 80), kExact * m * h * h);
  EXPECT_NEAR(I(1, 1), I(0, 0), kExact * m * h * h);
}

TEST(MeshMass, RegularHexagonalPrismMatchesClosedForm) {
  // Regular hexagon of circumradius R, height h: A = (3√3/2) R², I_zz = (5/12) m R²,
  // I_xx = m (5R²/24 + h²/12).
  const double R = 0.4, h = 1.1;
  TriangleMesh p;
  for (int z = 0; z < 2; ++z) {
    for (int k = 0; k < 6; ++k) {
      const double t = std::numbers::pi * k / 3;
      p.vertices.emplace_back(R * std::cos(t), R * std::sin(t), z * h);
    }
  }
  for (std::uint32_t k = 1; k + 1 < 6; ++k) {
    p.triangles.push_back({0, k + 1, k});              // bottom, normal −z
    p.triangles.push_back({6, 6 + k, 6 + k + 1});      // top, normal +z
  }
  for (std::uint32_t k = 0; k < 6; ++k) {
    const std::uint32_t n = (k + 1) % 6;
    p.triangles.push_back({k, n, 6 + n});
    p.triangles.push_back({k, 6 + n, 6 + k});
  }
  const auto r = mesh_mass_properties(p, density(1.0));
  const double m = 1.5 * std::sqrt(3.0) * R * R * h;
  EXPECT_NEAR(r.properties.mass(), m, kExact * m);
  const Eigen::Matrix3d I = r.properties.inertia_com();
  EXPECT_NEAR(I(2, 2), 5.0 / 12 * m * R * R, kExact * m);
  EXPECT_NEAR(I(0, 0), m * (5 * R * R / 24 + h * h / 12), kExact * m);
  EXPECT_NEAR(I(1, 1), I(0, 0), kExact * m);
}

TEST(MeshMass, TessellatedSphereConvergesQuadratically) {
  // Inscribed UV sphere: the volume error falls as 1/n² (chord sagitta ∝ (π/n)²), so
  // doubling n divides it by ≈ 4. Analytic: V = 4/3 π r³, I = 2/5 m r².
  const double r = 1.0;
  double prev_v = 0, prev_i = 0;
  for (int n : {16, 32, 64, 128}) {
    const auto res = mesh_mass_properties(test::uv_sphere(r, n), density(1.0));
    const double ev = std::abs(res.measure - 4.0 / 3 * std::numbers::pi);
    const double ei =
        std::abs(res.properties.inertia_com()(2, 2) - 0.4 * (4.0 / 3 * std::numbers::pi));
    if (prev_v > 0) {
      EXPECT_NEAR(prev_v / ev, 4.0, 0.3) << "n = " << n;
      EXPECT_NEAR(prev_i / ei, 4.0, 0.3) << "n = " << n;
    }
    prev_v = ev;
    prev_i = ei;
  }
  // Leading term: relative volume error ≈ (π/n)²/4 for the inscribed UV sphere; 0.5·(π/n)²
  // bounds it with margin at n = 128.
  EXPECT_LT(prev_v / (4.0 / 3 * std::numbers::pi), 0.5 * std::pow(std::numbers::pi / 128, 2));
}

TEST(MeshMass, CubeShellMatchesClosedForm) {
  // Thin cube shell of side a and mass m: I = 5 m a² / 18 about every axis through the centre.
  const double a = 0.2, m = 3.0;
  const auto r = mesh_mass_properties(test::box_mesh(a, a, a), {m, std::nullopt, true, {}});
  EXPECT_NEAR(r.measure, 6 * a * a, kExact);
  EXPECT_NEAR(r.properties.mass(), m, ulps(8, m));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r.properties.inertia_com()(i, i), 5.0 / 18 * m * a * a, kExact);
  }
  // thickness × density gives the surface density.
  const auto t = mesh_mass_properties(test::box_mesh(a, a, a), {std::nullopt, 2000.0, true, 0.002});
  EXPECT_NEAR(t.properties.mass(), 6 * a * a * 0.002 * 2000.0, kExact);
}

TEST(MeshMass, FarFromOriginKeepsPrecision) {
  // A part 1 m across placed 10⁶ m from the origin: its vertices themselves round to
  // ulp(10⁶) ≈ 1.2e-10 m, so 1e-9 relative is what the data allow.
  const auto sphere = test::uv_sphere(0.5, 24);
  const auto near = mesh_mass_properties(sphere, density(7800));
  auto moved = sphere;
  const Eigen::Vector3d d(1e6, -1e6, 1e6);
  moved.translate(d);
  const auto far = mesh_mass_properties(moved, density(7800));
  // The bound: relative error below 1e-9 after a 10⁶ m translation.
  EXPECT_NEAR(far.properties.mass(), near.properties.mass(), 1e-9 * near.properties.mass());
  const double s = near.properties.inertia_com().norm();
  EXPECT_LT((far.properties.inertia_com() - near.properties.inertia_com()).norm(), 1e-9 * s);
  // The COM is stored as an absolute position of magnitude 1.7e6 m: a few ulps of that.
  EXPECT_LT((far.properties.com() - d - near.properties.com()).norm(), ulps(8, 2e6));
}

TEST(MeshMass, RotationRotatesTheTensor) {
  const auto box = test::box_mesh(0.3, 0.5, 0.7);
  const Eigen::Matrix3d R_AB =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  auto rotated = box;
  for (auto& p : rotated.vertices) p = R_AB * p;
  const auto a = mesh_mass_properties(box, density(1000));
  const auto b = mesh_mass_properties(rotated, density(1000));
  const Eigen::Matrix3d expected = R_AB * a.properties.inertia_com() * R_AB.transpose();
  // Round-off of rotating 8 vertices and the tensor: a few hundred ε of the tensor's scale.
  EXPECT_LT((b.properties.inertia_com() - expected).norm(),
            ulps(500, a.properties.inertia_com().norm()));
  EXPECT_NEAR(b.properties.mass(), a.properties.mass(), ulps(100, a.properties.mass()));
}

TEST(MeshMass, RetriangulationDoesNotChangeTheResult) {
  auto box = test::box_mesh(0.3, 0.5, 0.7);
  auto other = box;
  // Split every quad along its other diagonal: (q0,q1,q2),(q0,q2,q3) → (q0,q1,q3),(q1,q2,q3).
  for (std::size_t f = 0; f < other.triangles.size(); f += 2) {
    const auto t0 = box.triangles[f];
    const auto t1 = box.triangles[f + 1];
    other.triangles[f] = {t0[0], t0[1], t1[2]};
    other.triangles[f + 1] = {t0[1], t0[2], t1[2]};
  }
  const auto a = mesh_mass_properties(box, density(1000));
  const auto b = mesh_mass_properties(other, density(1000));
  EXPECT_NEAR(b.properties.mass(), a.properties.mass(), ulps(100, a.properties.mass()));
  EXPECT_LT((b.properties.inertia_com() - a.properties.inertia_com()).norm(),
            ulps(500, a.properties.inertia_com().norm()));
}

TEST(MeshMass, ReversedWindingIsRepairedWithAWarning) {
  auto box = test::box_mesh(0.3, 0.5, 0.7);
  box.reverse_winding();
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(box, density(1000)), "volume is -0.105");
  const RepairReport rep = repair_mesh(box);
  EXPECT_EQ(rep.inverted_components, 1u);
  ASSERT_FALSE(rep.warnings.empty());
  EXPECT_NE(rep.warnings[0].find("inward normals"), std::string::npos);
  const auto r = mesh_mass_properties(box, density(1000));
  EXPECT_NEAR(r.measure, 0.3 * 0.5 * 0.7, kExact);
}

TEST(MeshMass, OpenMeshIsRefusedAsASolid) {
  auto box = test::box_mesh(1, 1, 1);
  box.triangles.pop_back();
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(box, density(1000)),
                     "not closed (3 boundary edges, 0 non-manifold edges), so it bounds no "
                     "solid: use `shell = true`");
  // As a shell it is fine: area 6 − 1/2.
  const auto r = mesh_mass_properties(box, {std::nullopt, 1.0, true, {}});
  EXPECT_NEAR(r.measure, 5.5, kExact);
}

TEST(MeshMass, MillimetresReadAsMetresAreFlagged) {
  // A 50 mm cube of steel with its coordinates read as metres: 50 m across.
  const auto cube = test::box_mesh(50, 50, 50);
  const auto by_mass = mesh_mass_properties(cube, {0.98, std::nullopt, false, {}});
  // the size (50 m > 10 m) and the density
  ASSERT_EQ(by_mass.warnings.size(), 2u);
  EXPECT_NE(by_mass.warnings[0].find("the part is 50 × 50 × 50 m, more than 10 m long"),
            std::string::npos);
  EXPECT_NE(by_mass.warnings[1].find("implied density 7.84e-06 kg/m³"), std::string::npos);
  // the remedy in library terms (the command line words it --units mm, see wording.hpp)
  EXPECT_NE(by_mass.warnings[1].find("`units = \"mm\"`"), std::string::npos);
  const auto huge = test::box_mesh(200, 200, 200);
  const auto by_density = mesh_mass_properties(huge, density(7850));
  // the size and the mass: 200³ m³ × 7850 kg/m³ = 6.28e7 t
  ASSERT_EQ(by_density.warnings.size(), 2u);
  EXPECT_NE(by_density.warnings[0].find("the part is 200 × 200 × 200 m, more than 10 m long: if "
                                        "the file's numbers are millimetres, use "
                                        "`units = \"mm\"`"),
            std::string::npos);
  EXPECT_NE(by_density.warnings[1].find("the implied mass 6.28e+07 t is more than 1000 t"),
            std::string::npos);
}

TEST(MeshMass, BadSpecsAreNamed) {
  const auto box = test::box_mesh(1, 1, 1);
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(box, {1.0, 2.0, false, {}}),
                     "give exactly one of mass and density (got both)");
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(box, {}),
                     "give exactly one of mass and density (got neither)");
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(box, {-1.0, std::nullopt, false, {}}),
                     "mass -1 kg: expected a positive finite value");
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(box, {std::nullopt, 1.0, false, 0.1}),
                     "thickness 0.1 m given for a solid");
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(TriangleMesh{}, density(1)),
                     "the mesh has no triangles");
}

// The baseline (SSE2) and AVX2 compilations of the volume sums: the same operations in the
// same order, so every sum is bitwise equal; on meshes whose triangle count is and is not a
// multiple of the four lanes, near and far from the reference point, and on random soups
// (cancellation-heavy, arbitrary bit patterns).
TEST(MeshMass, AccumulationVariantsAreBitwiseEqual) {
  if (!detail::avx2_available()) GTEST_SKIP() << "this CPU has no AVX2";
  std::vector<TriangleMesh> meshes = {test::uv_sphere(0.1, 24), test::uv_sphere(0.1, 7),
                                      test::box_mesh(0.3, 0.5, 0.7)};
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const std::size_t n : {1u, 2u, 3u, 5u, 1001u, 4096u}) {
    TriangleMesh soup;
    for (std::size_t i = 0; i < 3 * n; ++i) {
      soup.vertices.emplace_back(u(rng), 1e3 * u(rng), 1e-3 * u(rng));
    }
    for (std::size_t f = 0; f < n; ++f) {
      const auto i = static_cast<std::uint32_t>(3 * f);
      soup.triangles.push_back({i, i + 1, i + 2});
    }
    meshes.push_back(soup);
  }
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    SCOPED_TRACE(k);
    for (const Eigen::Vector3d& p_OR :
         {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.01, -0.02, 0.03),
          Eigen::Vector3d(1e6, 2e6, -3e6)}) {
      const detail::VolumeSums a = detail::accumulate_volume_baseline(meshes[k], p_OR);
      const detail::VolumeSums b = detail::accumulate_volume_avx2(meshes[k], p_OR);
      EXPECT_NE(a.measure, 0.0);  // non-trivial sums
      EXPECT_EQ(a.measure, b.measure);
      EXPECT_EQ(a.fx, b.fx);
      EXPECT_EQ(a.fy, b.fy);
      EXPECT_EQ(a.fz, b.fz);
      EXPECT_EQ(a.xx, b.xx);
      EXPECT_EQ(a.yy, b.yy);
      EXPECT_EQ(a.zz, b.zz);
      EXPECT_EQ(a.xy, b.xy);
      EXPECT_EQ(a.xz, b.xz);
      EXPECT_EQ(a.yz, b.yz);
    }
  }
  // volume_moments uses the variant for this CPU: the AVX2 sums
  const TriangleMesh& m = meshes[0];
  const Eigen::Vector3d p_OR(0.01, -0.02, 0.03);
  EXPECT_EQ(volume_moments(m, p_OR).measure,
            detail::accumulate_volume_avx2(m, p_OR).measure / 6.0);
}

TEST(MeshMass, UnrepairedMeshWithAFlippedTriangleIsRefused) {
  // 0.2 × 0.3 × 0.1 m, 2700 kg/m³: 16.2 kg. One triangle flipped: closed, but its signed
  // tetrahedra no longer cancel (the sum gave 13.5 kg). Without repair's report the edges are
  // matched: three are traversed twice the same way, so it is refused with the remedy.
  auto box = test::box_mesh(0.2, 0.3, 0.1);
  std::swap(box.triangles[4][1], box.triangles[4][2]);
  EXPECT_EQ(count_edges(box).misoriented, 3u);
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(box, density(2700)),
                     "mesh_mass_properties(): the mesh's triangles are not consistently "
                     "oriented (3 edges are traversed twice in the same direction), so its "
                     "volume would be wrong: run repair_mesh(mesh) first");
  // as a shell the winding does not matter
  EXPECT_NEAR(mesh_mass_properties(box, {std::nullopt, 1.0, true, {}}).measure, 0.22, kExact);
  const RepairReport rep = repair_mesh(box);
  EXPECT_EQ(rep.reoriented_triangles, 1u);
  // 16.2 kg: the closed form, to the round-off of a few dozen terms
  EXPECT_NEAR(mesh_mass_properties(box, density(2700)).properties.mass(), 16.2, 16.2 * kExact);
  // an unwelded soup is "not closed": the message says repair welds it
  TriangleMesh soup;
  for (const auto& t : test::box_mesh(1, 1, 1).triangles) {
    const auto n = static_cast<std::uint32_t>(soup.vertices.size());
    for (auto i : t) soup.vertices.push_back(test::box_mesh(1, 1, 1).vertices[i]);
    soup.triangles.push_back({n, n + 1, n + 2});
  }
  EXPECT_RIGID_ERROR((void)mesh_mass_properties(soup, density(1)),
                     "(if the mesh has not been through repair_mesh(mesh), run it first: it "
                     "welds duplicate vertices and orients the triangles)");
}

TEST(MeshMass, UnitsPlausibility) {
  // A 20 × 30 × 10 mm part whose numbers are read as metres: 20 × 30 × 10 m, 16 200 t of
  // aluminium. Both the size and the mass say so, with the remedy.
  const auto part = test::box_mesh(20, 30, 10);
  const auto r = mesh_mass_properties(part, density(2700));
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_EQ(r.warnings[0],
            "the part is 20 × 30 × 10 m, more than 10 m long: if the file's numbers are "
            "millimetres, use `units = \"mm\"`");
  EXPECT_EQ(r.warnings[1],
            "the implied mass 1.62e+04 t is more than 1000 t: if the file's numbers are "
            "millimetres, use `units = \"mm\"`");
  EXPECT_EQ(r.bounding_box[1], Eigen::Vector3d(20, 30, 10));
  // numbers in metres read as millimetres: 20 µm
  auto tiny = test::box_mesh(0.02, 0.03, 0.01);
  tiny.scale(1e-3);
  const auto t = mesh_mass_properties(tiny, density(2700));
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_NE(t.warnings[0].find("less than 0.001 m long: check the length unit "
                               "(`units = \"m\"` reads the numbers as metres)"),
            std::string::npos);
  // real parts from 1 cm to 10 m, in steel, aluminium, plastic and foam: no warning. The
  // heaviest, a 10 × 1 × 1 m steel beam, is 78.5 t.
  for (const Eigen::Vector3d& size : {Eigen::Vector3d(0.01, 0.01, 0.01), Eigen::Vector3d(0.02, 0.03, 0.01),
                                     Eigen::Vector3d(0.5, 0.2, 0.1), Eigen::Vector3d(1, 1, 1),
                                     Eigen::Vector3d(10, 1, 1), Eigen::Vector3d(10, 2, 0.02)}) {
    for (const double rho : {7850.0, 2700.0, 1100.0, 30.0}) {
      const auto ok = mesh_mass_properties(test::box_mesh(size.x(), size.y(), size.z()), density(rho));
      EXPECT_TRUE(ok.warnings.empty()) << size.transpose() << " m, " << rho << " kg/m³: "
                                       << (ok.warnings.empty() ? "" : ok.warnings[0]);
    }
  }
}
}  // namespace
}  // namespace rigid::mesh
