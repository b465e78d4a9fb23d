#include "rigid/mesh/mesh_uncertainty.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "mesh/mesh_builders.hpp"
#include "rigid/mass/uncertainty.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

// Monte Carlo over noisy copies of the mesh, measured by mesh_mass_properties (not the
// propagation code), against the first-order σ
void expect_monte_carlo_agrees(const mesh::TriangleMesh& m, const mesh::MassSpec& spec, double sigma,
                               const std::optional<Eigen::Vector3d>& about) {
  const auto u = mesh::vertex_noise_uncertainty(m, spec, sigma, about);
  EXPECT_LE((u.value - mass::mass_properties_vector(u.nominal.properties, about)).cwiseAbs().maxCoeff(),
            1e-12 * u.value.cwiseAbs().maxCoeff());  // the same moments, summed in another order
  const int n = 10000;
  std::mt19937 gen(5);
  std::normal_distribution<double> z(0.0, sigma);
  Eigen::Matrix<double, 10, 1> sum = Eigen::Matrix<double, 10, 1>::Zero(), sum2 = sum;
  for (int k = 0; k < n; ++k) {
    mesh::TriangleMesh noisy = m;
    for (auto& v : noisy.vertices) v += Eigen::Vector3d(z(gen), z(gen), z(gen));
    const auto y = mass::mass_properties_vector(mesh::mesh_mass_properties(noisy, spec).properties, about);
    sum += y;
    sum2 += y.cwiseAbs2();
  }
  const Eigen::Matrix<double, 10, 1> mean = sum / n;
  const Eigen::Matrix<double, 10, 1> sd = ((sum2 - n * mean.cwiseAbs2()) / (n - 1)).cwiseMax(0.0).cwiseSqrt();
  // σ from n normal samples: relative error 1/√(2(n − 1)) ≈ 0.71%, bounded by 5 of those
  // (3.5%); σ/size = 1e-3 keeps the first-order error O(1e-3) below that
  const double bound = 5.0 / std::sqrt(2.0 * (n - 1));
  for (int i = 0; i < 10; ++i) {
    if (u.sigma(i) == 0.0) {  // the mass, when it is given: exact in every sample
      EXPECT_LE(sd(i), 1e-12 * std::abs(mean(i))) << i;
      continue;
    }
    EXPECT_NEAR(sd(i) / u.sigma(i), 1.0, bound) << "element " << i << ": MC " << sd(i) << ", propagated " << u.sigma(i);
  }
}

TEST(MeshUncertainty, VertexNoiseAgreesWithMonteCarloOnABox) {
  expect_monte_carlo_agrees(test::box_mesh(0.3, 0.2, 0.1), mesh::MassSpec{std::nullopt, 2700.0, false, std::nullopt}, 3e-4,
                            std::nullopt);
}

TEST(MeshUncertainty, VertexNoiseAgreesWithMonteCarloOnASphereAboutAPoint) {
  expect_monte_carlo_agrees(test::uv_sphere(0.1, 3), mesh::MassSpec{2.0, std::nullopt, false, std::nullopt}, 1e-4,
                            Eigen::Vector3d(0.05, 0.0, -0.1));
}

TEST(MeshUncertainty, ShellsAndBadSigmaAreRefused) {
  const auto box = test::box_mesh(1, 1, 1);
  EXPECT_RIGID_ERROR((void)mesh::vertex_noise_uncertainty(box, mesh::MassSpec{1.0, std::nullopt, true, std::nullopt}, 1e-3),
                     "vertex noise is propagated for solid meshes only");
  EXPECT_RIGID_ERROR((void)mesh::vertex_noise_uncertainty(box, mesh::MassSpec{1.0, std::nullopt, false, std::nullopt}, -1.0),
                     "the vertex standard deviation must be finite and non-negative, got -1 m");
}

}  // namespace
}  // namespace rigid
