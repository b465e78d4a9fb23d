// The catalogue's closed forms as expressions (what a scene's equations print) against the
// C++ factories of rigid/mass/primitives.hpp (derived independently, each tested against its
// own closed form and a quadrature in tests/mass): same mass, COM and inertia.
#include <algorithm>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "rigid/lagrange/system.hpp"
#include "rigid/mass/primitive_table.hpp"

namespace rigid::mass {
namespace {

TEST(PrimitiveFormulas, EvaluateToTheFactoriesNumbers) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.2, 1.5);
  int checked = 0;
  for (const PrimitiveEntry& e : primitive_table()) {
    if (e.formulas.mass.empty()) continue;  // the tetrahedron is given by points
    for (int trial = 0; trial < 20; ++trial) {
      // sizes as parameters s0, s1, … (the expressions name them; their values are random)
      std::vector<lagrange::Parameter> params;
      std::vector<std::string> size_names;
      std::vector<std::pair<std::string, double>> sizes;
      std::vector<double> z;
      for (std::size_t i = 0; i < e.sizes.size(); ++i) z.push_back(u(rng));
      if (e.name == "thick_spherical_shell" || e.name == "thick_tube") std::sort(z.begin(), z.begin() + 2);
      if (e.name == "solid_torus") std::sort(z.begin(), z.end(), std::greater<>());
      for (std::size_t i = 0; i < z.size(); ++i) {
        params.push_back({fmt::format("s{}", i), z[i]});
        size_names.push_back(fmt::format("s{}", i));
        sizes.emplace_back(e.sizes[i].name, z[i]);
      }
      params.push_back({"amount", 1.0 + u(rng)});
      for (const Amount amount : {Amount::kMass, Amount::kDensity}) {
        const MassProperties expected = make_primitive(e.name, amount, params.back().value, sizes);
        const std::array<std::string, 10> text = primitive_expressions(e, amount, "amount", size_names);
        double v[10];
        for (std::size_t k = 0; k < 10; ++k) v[k] = lagrange::evaluate_constant(lagrange::Expression(text[k]), params, e.name);
        const Eigen::Matrix3d& I = expected.inertia_com();
        const double want[10] = {expected.mass(), expected.com().x(), expected.com().y(), expected.com().z(),
                                 I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)};
        // the expressions are evaluated in exact arithmetic and rounded once, the factories in
        // double with cancellation-free forms: agreement to 1e-13 relative to the largest entry
        // of each group (the frustum's Ixx subtracts m z_c² from the base moment, losing a digit)
        const double mass_scale = expected.mass();
        const double length_scale = 3.0;
        const double inertia_scale = I.cwiseAbs().maxCoeff();
        for (std::size_t k = 0; k < 10; ++k) {
          const double scale = k == 0 ? mass_scale : k < 4 ? length_scale : inertia_scale;
          EXPECT_NEAR(v[k], want[k], 1e-13 * scale)
              << e.name << " output " << k << " (" << text[k] << ") amount " << (amount == Amount::kMass ? "mass" : "density");
        }
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 20 * 17);  // every entry but the tetrahedron (17 with the thin ring)
}

TEST(PrimitiveFormulas, SubstituteWholeNamesOnly) {
  const PrimitiveEntry& tube = find_primitive("thick_tube");
  // size names that contain each other ("radius" inside "inner_radius") and a mass formula
  const std::array<std::string, 10> t =
      primitive_expressions(tube, Amount::kDensity, "rho_steel", std::vector<std::string>{"r_in", "r_out", "L"});
  EXPECT_EQ(t[0], "(rho_steel)*pi*((r_out)^2 - (r_in)^2)*(L)");
  EXPECT_EQ(t[6], "((rho_steel)*pi*((r_out)^2 - (r_in)^2)*(L))*((r_in)^2 + (r_out)^2)/2");
}

}  // namespace
}  // namespace rigid::mass
