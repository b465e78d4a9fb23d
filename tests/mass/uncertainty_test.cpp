#include "rigid/mass/uncertainty.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "rigid/mass/primitives.hpp"
#include "support/expect_error.hpp"
#include "support/tolerance.hpp"

namespace rigid {
namespace {

using std::numbers::pi;

TEST(Uncertainty, ParsesTolerancesWithUnits) {
  const auto t = mass::parse_tolerances("dims=±0.1mm, density=±2%,mass=+-5g,radius=0.002");
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0].name, "dims");
  EXPECT_DOUBLE_EQ(t[0].sigma, 1e-4);
  EXPECT_FALSE(t[0].relative);
  EXPECT_EQ(t[1].name, "density");
  EXPECT_DOUBLE_EQ(t[1].sigma, 0.02);
  EXPECT_TRUE(t[1].relative);
  EXPECT_DOUBLE_EQ(t[2].sigma, 5e-3);
  EXPECT_EQ(t[3].unit, "");
  EXPECT_DOUBLE_EQ(t[3].sigma, 0.002);
  EXPECT_RIGID_ERROR((void)mass::parse_tolerances("dims=±0.1furlong"), "unknown unit 'furlong'");
  EXPECT_RIGID_ERROR((void)mass::parse_tolerances("dims"), "tolerance 'dims' (at character 1 of 'dims'): expected name=±value[unit]");
  EXPECT_RIGID_ERROR((void)mass::parse_tolerances("mass=1%,dims=-1mm"),
                     "tolerance 'dims=-1mm' (at character 9 of 'mass=1%,dims=-1mm'): expected a non-negative finite number");
}

TEST(Uncertainty, LinearFunctionsPropagateExactly) {
  // y = A x: central differences are exact for a linear map, σ_y = sqrt(Σ A² σ²)
  Eigen::Matrix<double, 2, 3> A;
  A << 1, -2, 3, 0.5, 0, -1;
  const Eigen::Vector3d x(1, 2, 3), s(0.1, 0.2, 0.0);
  const auto p = mass::propagate([&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return A * v; }, x, s);
  const Eigen::Vector2d expected = (A.array().square().rowwise() * s.array().square().transpose()).rowwise().sum().sqrt();
  // the step h ~ 6e-6·|x| divides a difference of a few ε: relative round-off ~ ε/6e-6 ≈ 4e-11
  EXPECT_NEAR(p.sigma(0), expected(0), 1e-9 * expected(0));
  EXPECT_NEAR(p.sigma(1), expected(1), 1e-9 * expected(1));
}

TEST(Uncertainty, CylinderMassMatchesTheDifferentiatedClosedForm) {
  // m = ρπr²h: ∂m/∂r = 2ρπrh, ∂m/∂h = ρπr², ∂m/∂ρ = πr²h
  const double rho = 2700, r = 0.05, h = 0.4, sr = 1e-4, sh = 1e-4, srho = 0.02 * rho;
  const auto u = mass::primitive_uncertainty(
      "cylinder", mass::Amount::kDensity, rho, {{{"radius", r}, {"height", h}}, {}}, mass::Placement{},
      mass::parse_tolerances("dims=±0.1mm,density=±2%"));
  const double expected =
      std::sqrt(std::pow(2 * rho * pi * r * h * sr, 2) + std::pow(rho * pi * r * r * sh, 2) + std::pow(pi * r * r * h * srho, 2));
  // central differences of a cubic: truncation h²·m'''/6 and round-off ε/h, both ~1e-10 relative
  EXPECT_NEAR(u.sigma(0), expected, 1e-8 * expected);
  EXPECT_EQ(u.inputs, (std::vector<std::string>{"radius", "height", "density"}));
  EXPECT_EQ(u.value(0), u.nominal.mass());
}

TEST(Uncertainty, MonteCarloAgreesWithThePropagatedSigma) {
  // a rotated cylinder about a fixed point (every element of the tensor varies), with
  // relative σ of 1% on the sizes and 2% on the density
  const mass::Placement placement{.axis = Eigen::Vector3d(1, 1, 0), .rpy = Eigen::Vector3d(0.3, 0.2, 0.1),
                                  .origin = Eigen::Vector3d(0.1, 0, 0)};
  const Eigen::Vector3d about(0.0, 0.05, 0.0);
  const double rho = 1000, r = 0.05, h = 0.4;
  const auto u = mass::primitive_uncertainty("cylinder", mass::Amount::kDensity, rho,
                                             {{{"radius", r}, {"height", h}}, {}}, placement,
                                             mass::parse_tolerances("dims=±1%,density=±2%"), about);
  const int n = 10000;
  std::mt19937 gen(18);
  std::normal_distribution<double> z(0.0, 1.0);
  Eigen::Matrix<double, 10, 1> sum = Eigen::Matrix<double, 10, 1>::Zero(), sum2 = sum;
  for (int k = 0; k < n; ++k) {
    const double rk = r * (1 + 0.01 * z(gen)), hk = h * (1 + 0.01 * z(gen)), rhok = rho * (1 + 0.02 * z(gen));
    const auto y = mass::mass_properties_vector(mass::place(mass::solid_cylinder_with_density(rhok, rk, hk), placement), about);
    sum += y;
    sum2 += y.cwiseAbs2();
  }
  const Eigen::Matrix<double, 10, 1> mean = sum / n;
  const Eigen::Matrix<double, 10, 1> sd = ((sum2 - n * mean.cwiseAbs2()) / (n - 1)).cwiseMax(0.0).cwiseSqrt();
  // the relative error of a σ estimated from n normal samples is 1/√(2(n − 1)) ≈ 0.71%; a 5σ
  // bound on it is 3.5%. The first-order σ differs from the true one by O(σ_rel²) ~ 1e-4.
  const double bound = 5.0 / std::sqrt(2.0 * (n - 1));
  for (int i = 0; i < 10; ++i) {
    if (u.sigma(i) == 0.0) {
      EXPECT_LE(sd(i), 1e-12 * (std::abs(mean(i)) + 1e-12)) << i;  // COM: fixed by the placement
      continue;
    }
    EXPECT_NEAR(sd(i) / u.sigma(i), 1.0, bound) << "element " << i << ": MC " << sd(i) << ", propagated " << u.sigma(i);
  }
}

TEST(Uncertainty, BadTolerancesAreRefused) {
  const mass::PrimitiveArguments args{{{"radius", 0.05}, {"height", 0.4}}, {}};
  const auto with = [&](const char* text) {
    return mass::primitive_uncertainty("cylinder", mass::Amount::kMass, 2.0, args, mass::Placement{},
                                       mass::parse_tolerances(text));
  };
  EXPECT_RIGID_ERROR((void)with("density=±2%"), "tolerance density cannot be used: the solid_cylinder primitive is given by its mass, so give mass=±…");
  EXPECT_RIGID_ERROR((void)with("radios=±1mm"), "unknown tolerance 'radios'; did you mean 'radius'?");
  EXPECT_RIGID_ERROR((void)with("mass=±1mm"), "tolerance mass: 'mm' is not a unit of mass");
  EXPECT_RIGID_ERROR((void)with("dims=1%,dims=2%"), "tolerance dims is given twice");
}

}  // namespace
}  // namespace rigid
