#include "rigid/mass/primitive_table.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/mass/primitives.hpp"

namespace rigid::mass {
namespace {

// One row per primitive: its _with_mass and _with_density factories applied to the sizes
// in the order of the row's size names.
template <auto WithMass, auto WithDensity, std::size_t N>
MassProperties make_n(Amount amount, double value, std::span<const double> z) {
  RIGID_ASSERT(z.size() == N);
  auto call = [&](auto f) {
    if constexpr (N == 1) return f(value, z[0]);
    else if constexpr (N == 2) return f(value, z[0], z[1]);
    else return f(value, z[0], z[1], z[2]);
  };
  return amount == Amount::kMass ? call(WithMass) : call(WithDensity);
}

}  // namespace

const std::vector<PrimitiveEntry>& primitive_table() {
  static const std::vector<PrimitiveEntry> table = {
      {"solid_sphere", "solid sphere, centred", {"radius"}, "kg/m³",
       &make_n<&solid_sphere_with_mass, &solid_sphere_with_density, 1>},
      {"thick_spherical_shell", "solid shell between two spheres, centred",
       {"inner_radius", "outer_radius"}, "kg/m³",
       &make_n<&thick_spherical_shell_with_mass, &thick_spherical_shell_with_density, 2>},
      {"thin_spherical_shell", "spherical surface, centred", {"radius"}, "kg/m²",
       &make_n<&thin_spherical_shell_with_mass, &thin_spherical_shell_with_density, 1>},
      {"solid_ellipsoid", "solid ellipsoid, semi-axes along x, y, z, centred",
       {"semi_axes_0", "semi_axes_1", "semi_axes_2"}, "kg/m³",
       &make_n<&solid_ellipsoid_with_mass, &solid_ellipsoid_with_density, 3>},
      {"solid_box", "solid box, edges along x, y, z, centred", {"size_0", "size_1", "size_2"},
       "kg/m³", &make_n<&solid_box_with_mass, &solid_box_with_density, 3>},
      {"solid_cylinder", "solid cylinder, axis z, centred", {"radius", "height"}, "kg/m³",
       &make_n<&solid_cylinder_with_mass, &solid_cylinder_with_density, 2>},
      {"thick_tube", "thick-walled tube, axis z, centred", {"inner_radius", "outer_radius", "height"},
       "kg/m³", &make_n<&thick_tube_with_mass, &thick_tube_with_density, 3>},
      {"thin_cylindrical_shell", "open cylindrical surface, axis z, centred", {"radius", "height"},
       "kg/m²", &make_n<&thin_cylindrical_shell_with_mass, &thin_cylindrical_shell_with_density, 2>},
      {"capped_cylindrical_shell", "cylindrical surface with end disks, axis z, centred",
       {"radius", "height"}, "kg/m²",
       &make_n<&capped_cylindrical_shell_with_mass, &capped_cylindrical_shell_with_density, 2>},
      {"solid_cone", "solid cone, base at z = 0, apex at z = height", {"radius", "height"}, "kg/m³",
       &make_n<&solid_cone_with_mass, &solid_cone_with_density, 2>},
      {"solid_frustum", "solid conical frustum, bottom at z = 0, top at z = height",
       {"bottom_radius", "top_radius", "height"}, "kg/m³",
       &make_n<&solid_frustum_with_mass, &solid_frustum_with_density, 3>},
      {"solid_capsule", "solid capsule, axis z, centred (total length = length + 2 radius)",
       {"radius", "length"}, "kg/m³", &make_n<&solid_capsule_with_mass, &solid_capsule_with_density, 2>},
      {"solid_torus", "solid torus, axis z, centred", {"major_radius", "minor_radius"}, "kg/m³",
       &make_n<&solid_torus_with_mass, &solid_torus_with_density, 2>},
      {"thin_rod", "thin rod along z, centred", {"length"}, "kg/m",
       &make_n<&thin_rod_with_mass, &thin_rod_with_density, 1>},
      {"thin_rectangular_plate", "thin plate in the xy-plane, edges size_0 along x and size_1 along y, centred",
       {"size_0", "size_1"}, "kg/m²",
       &make_n<&thin_rectangular_plate_with_mass, &thin_rectangular_plate_with_density, 2>},
      {"thin_disk", "thin disk in the xy-plane, centred", {"radius"}, "kg/m²",
       &make_n<&thin_disk_with_mass, &thin_disk_with_density, 1>},
  };
  return table;
}

const PrimitiveEntry& find_primitive(std::string_view name) {
  const auto& table = primitive_table();
  auto it = std::find_if(table.begin(), table.end(), [&](const PrimitiveEntry& e) { return e.name == name; });
  if (it != table.end()) return *it;
  std::vector<std::string> names;
  for (const auto& e : table) names.push_back(e.name);
  RIGID_THROW("unknown primitive '{}'; expected one of: {}", name, fmt::join(names, ", "));
}

MassProperties make_primitive(std::string_view name, Amount amount, double value,
                              std::span<const std::pair<std::string, double>> sizes) {
  const PrimitiveEntry& e = find_primitive(name);
  std::vector<double> z(e.sizes.size());
  std::vector<bool> given(e.sizes.size(), false);
  for (const auto& [key, v] : sizes) {
    auto it = std::find(e.sizes.begin(), e.sizes.end(), key);
    RIGID_REQUIRE(it != e.sizes.end(), "primitive '{}' has no size '{}'; it takes {} (m)", name,
                  key, fmt::join(e.sizes, ", "));
    const auto i = static_cast<std::size_t>(it - e.sizes.begin());
    RIGID_REQUIRE(!given[i], "primitive '{}': size '{}' is given twice", name, key);
    z[i] = v;
    given[i] = true;
  }
  for (std::size_t i = 0; i < z.size(); ++i) {
    RIGID_REQUIRE(given[i], "primitive '{}' is missing its size '{}'; it takes {} (m)", name,
                  e.sizes[i], fmt::join(e.sizes, ", "));
  }
  return e.make(amount, value, z);
}

}  // namespace rigid::mass
