#include "rigid/mass/primitive_table.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::mass {
namespace {

using Sizes = std::vector<std::pair<std::string, double>>;

// Sizes reach the factories in the right order: closed forms of the shapes whose sizes
// differ in role (tolerance: a few ulps of the moments).
TEST(PrimitiveTable, SizesReachTheFactoriesInOrder) {
  const double m = 2.0;
  const MassProperties box = make_primitive("solid_box", Amount::kMass, m, Sizes{{"size_0", 0.1}, {"size_1", 0.2}, {"size_2", 0.3}});
  EXPECT_NEAR(box.inertia_com()(0, 0), m * (0.04 + 0.09) / 12, 1e-16);
  EXPECT_NEAR(box.inertia_com()(2, 2), m * (0.01 + 0.04) / 12, 1e-16);
  const MassProperties tube = make_primitive("thick_tube", Amount::kMass, m,
                                             Sizes{{"height", 0.3}, {"outer_radius", 0.05}, {"inner_radius", 0.03}});
  EXPECT_NEAR(tube.inertia_com()(2, 2), m * (0.0009 + 0.0025) / 2, 1e-16);
  const MassProperties cone = make_primitive("solid_frustum", Amount::kMass, m,
                                             Sizes{{"bottom_radius", 0.2}, {"top_radius", 1e-9}, {"height", 0.4}});
  EXPECT_NEAR(cone.com().z(), 0.1, 1e-9);  // nearly a cone: COM at h/4 above the wide end
  const MassProperties torus = make_primitive("solid_torus", Amount::kMass, m, Sizes{{"major_radius", 1.0}, {"minor_radius", 0.2}});
  EXPECT_NEAR(torus.inertia_com()(2, 2), m * (1.0 + 0.75 * 0.04), 1e-15);
  const MassProperties plate = make_primitive("thin_rectangular_plate", Amount::kDensity, 3.0,
                                              Sizes{{"size_0", 0.5}, {"size_1", 2.0}});
  EXPECT_NEAR(plate.mass(), 3.0, 1e-15);
  EXPECT_NEAR(plate.inertia_com()(0, 0), 3.0 * 4.0 / 12, 1e-15);  // m ly²/12
}

// Sizes 1, 2, 3 m in declared order satisfy every ordering rule (inner < outer; a ≤ R fails for
// the torus with minor 2 > major 1, so the torus gets its own), and a non-degenerate
// tetrahedron for the points.
PrimitiveArguments sample_arguments(const PrimitiveEntry& e) {
  PrimitiveArguments args;
  for (std::size_t i = 0; i < e.sizes.size(); ++i) {
    args.sizes.emplace_back(e.sizes[i].name, e.name == "solid_torus" ? 2.0 - static_cast<double>(i)
                                                                      : 1.0 + static_cast<double>(i));
  }
  const Eigen::Vector3d v[4] = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
  for (std::size_t i = 0; i < e.points.size(); ++i) args.points.emplace_back(e.points[i].name, v[i]);
  return args;
}

TEST(PrimitiveTable, EveryEntryBuildsWithMassAndDensity) {
  for (const PrimitiveEntry& e : primitive_table()) {
    const PrimitiveArguments args = sample_arguments(e);
    const MassProperties by_mass = make_primitive(e.name, Amount::kMass, 5.0, args);
    EXPECT_DOUBLE_EQ(by_mass.mass(), 5.0) << e.name;
    const MassProperties by_density = make_primitive(e.name, Amount::kDensity, 7.0, args);
    // same shape: inertia per unit mass agrees
    EXPECT_TRUE((by_density.inertia_com() / by_density.mass()).isApprox(by_mass.inertia_com() / 5.0, 1e-12)) << e.name;
  }
}

TEST(PrimitiveTable, EveryNameAndAliasFindsItsEntryAndNoOther) {
  std::vector<std::string> seen;
  for (const PrimitiveEntry& e : primitive_table()) {
    for (const std::string& n : e.names()) {
      EXPECT_EQ(&find_primitive(n), &e) << n;
      std::string dashed = n;
      std::replace(dashed.begin(), dashed.end(), '_', '-');
      EXPECT_EQ(&find_primitive(dashed), &e) << dashed;  // '-' and '_' alike
      EXPECT_EQ(std::count(seen.begin(), seen.end(), n), 0) << n << " names two entries";
      seen.push_back(n);
    }
    // aliases of sizes reach the same size
    for (std::size_t i = 0; i < e.sizes.size(); ++i) {
      EXPECT_EQ(e.size_index(e.sizes[i].name), i);
      for (const std::string& a : e.sizes[i].aliases) EXPECT_EQ(e.size_index(a), i) << e.name << " " << a;
    }
  }
  // the command line's short names and the scene's older spellings
  EXPECT_EQ(find_primitive("cylinder").name, "solid_cylinder");
  EXPECT_EQ(find_primitive("rod").name, "thin_rod");
  EXPECT_EQ(find_primitive("tube").name, "thick_tube");
  EXPECT_EQ(find_primitive("thick-spherical-shell").name, "thick_spherical_shell");
  EXPECT_EQ(find_primitive("tetrahedron").name, "solid_tetrahedron");
}

TEST(PrimitiveTable, BadNamesAndSizesAreReported) {
  EXPECT_RIGID_ERROR((void)find_primitive("cube"), "unknown primitive 'cube'; did you mean 'tube'?; expected one of: solid_sphere");
  EXPECT_RIGID_ERROR((void)find_primitive("thin_rd"), "did you mean 'thin_rod'?");
  EXPECT_RIGID_ERROR((void)make_primitive("solid_cylinder", Amount::kMass, 1, Sizes{{"radius", 1}}),
                     "primitive 'solid_cylinder' is missing its size 'height' (height, m); it takes radius, height (m)");
  EXPECT_RIGID_ERROR((void)make_primitive("solid_cylinder", Amount::kMass, 1, Sizes{{"radius", 1}, {"heigth", 2}}),
                     "primitive 'solid_cylinder' has no size 'heigth'; did you mean 'height'?");
  EXPECT_RIGID_ERROR((void)make_primitive("solid_sphere", Amount::kMass, 1, Sizes{{"radius", 1}, {"radius", 2}}),
                     "size 'radius' is given twice");
  EXPECT_RIGID_ERROR((void)make_primitive("solid_sphere", Amount::kMass, 1, Sizes{{"radius", -1}}), "-1");
}

}  // namespace
}  // namespace rigid::mass
