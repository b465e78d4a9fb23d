#pragma once

/// The uniform primitives of rigid/mass/primitives.hpp by name, for data-driven callers
/// (scene files, bindings): each entry names its sizes in order and builds the mass
/// properties from a mass or a density and those sizes.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/mass/mass_properties.hpp"

namespace rigid::mass {

/// How a primitive's amount of matter is given.
enum class Amount { kMass, kDensity };

struct PrimitiveEntry {
  std::string name;                ///< e.g. "solid_cylinder"
  std::string description;         ///< one line, with the frame
  std::vector<std::string> sizes;  ///< size names in argument order, e.g. {"radius", "height"} (m)
  std::string density_unit;        ///< kg/m³, kg/m² (shells, plates) or kg/m (rod)
  /// Builds the mass properties; `sizes` has one value per name of `sizes`.
  MassProperties (*make)(Amount amount, double value, std::span<const double> sizes);
};

/// Every primitive, in documentation order.
[[nodiscard]] const std::vector<PrimitiveEntry>& primitive_table();

/// The entry called `name`. @throws rigid::Error listing the known names (with the closest
/// one first when `name` looks like a typo of it).
[[nodiscard]] const PrimitiveEntry& find_primitive(std::string_view name);

/// Mass properties of primitive `name` with its sizes given by name.
/// @throws rigid::Error for an unknown primitive, a missing or unexpected size (naming the
///   expected ones), or sizes the primitive refuses (non-positive, inner ≥ outer, ...).
[[nodiscard]] MassProperties make_primitive(
    std::string_view name, Amount amount, double value,
    std::span<const std::pair<std::string, double>> sizes);

}  // namespace rigid::mass
