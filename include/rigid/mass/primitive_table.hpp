#pragma once

/// The primitive catalogue: the one vocabulary of shapes. Every front end derives its names
/// from it: the command line's `rigid inertia <shape>` subcommands and their options, the
/// scene file's `primitive = "<shape>"` with its size keys, and Python's rigid.mass.<shape>()
/// factories. Each entry has a canonical name, aliases (older or shorter spellings), sizes
/// with units, help text, the C++ factories of rigid/mass/primitives.hpp, and the closed forms
/// as expressions (for symbolic equations that keep a scene's parameter names).
///
/// Names are matched with '-' and '_' as the same character ("solid-cylinder" is
/// "solid_cylinder"), so each surface may use its own spelling.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"

namespace rigid::mass {

/// How a primitive's amount of matter is given.
enum class Amount { kMass, kDensity };

/// One size of a primitive (a length).
struct PrimitiveSize {
  std::string name;                  ///< canonical, e.g. "inner_radius"
  std::string help;                  ///< e.g. "inner radius"
  std::vector<std::string> aliases;  ///< other accepted names, e.g. "size_0" for "lx"
  std::string unit = "m";
};

/// One vertex of a primitive given by points (the tetrahedron), as x, y, z in metres.
struct PrimitivePoint {
  std::string name;  ///< e.g. "v0"
  std::string help;
};

/// The closed forms of a primitive as expression text (the grammar of rigid::lagrange) in the
/// size names, `rho` (the density) and `m` (the mass): its mass from the density, its COM and
/// its inertia about the COM (xx, yy, zz, xy, xz, yz tensor elements) in the primitive's frame.
/// Empty `mass` when the shape has no such form (the tetrahedron, given by points).
struct PrimitiveFormulas {
  std::string mass;
  std::array<std::string, 3> com{"0", "0", "0"};
  std::array<std::string, 6> inertia{"0", "0", "0", "0", "0", "0"};
};

struct PrimitiveEntry {
  std::string name;                    ///< canonical, e.g. "solid_cylinder"
  std::vector<std::string> aliases;    ///< e.g. {"cylinder"}
  std::string description;             ///< one line, with the frame
  std::vector<PrimitiveSize> sizes;    ///< in argument order
  std::vector<PrimitivePoint> points;  ///< vertices (tetrahedron), after the sizes
  std::string density_unit;            ///< kg/m³, kg/m² (shells, plates) or kg/m (rod)
  PrimitiveFormulas formulas;
  /// Builds the mass properties from one value per size and per point, in order.
  MassProperties (*make)(Amount amount, double value, std::span<const double> sizes,
                         std::span<const Eigen::Vector3d> points);

  /// True if `name` is this entry's name or one of its aliases ('-' and '_' alike).
  [[nodiscard]] bool is_called(std::string_view name) const;
  /// Every name this entry answers to: the canonical one first, then the aliases.
  [[nodiscard]] std::vector<std::string> names() const;
  /// The size called `name` (canonical or alias, '-' and '_' alike), if any.
  [[nodiscard]] std::optional<std::size_t> size_index(std::string_view name) const;
  /// The point called `name`, if any.
  [[nodiscard]] std::optional<std::size_t> point_index(std::string_view name) const;
};

/// Every primitive, in documentation order.
[[nodiscard]] const std::vector<PrimitiveEntry>& primitive_table();

/// The entry called `name` (canonical or alias).
/// @throws rigid::Error "unknown primitive 'x'; did you mean 'y'?" listing the known names.
[[nodiscard]] const PrimitiveEntry& find_primitive(std::string_view name);

/// Sizes and points given by name, as a front end collects them.
struct PrimitiveArguments {
  std::vector<std::pair<std::string, double>> sizes;            ///< (name or alias, m)
  std::vector<std::pair<std::string, Eigen::Vector3d>> points;  ///< (name, m)
};

/// Mass properties of primitive `name` with its sizes and points given by name.
/// @throws rigid::Error for an unknown primitive, an unknown size (with did-you-mean), a size
///   given twice or missing (naming the expected ones), or sizes the primitive refuses
///   (non-positive, inner ≥ outer, ...).
[[nodiscard]] MassProperties make_primitive(std::string_view name, Amount amount, double value,
                                            const PrimitiveArguments& arguments);

/// The older form: sizes only.
[[nodiscard]] MassProperties make_primitive(
    std::string_view name, Amount amount, double value,
    std::span<const std::pair<std::string, double>> sizes);

/// The closed forms of an entry instantiated for a body: every size name replaced by the
/// (parenthesised) expression text of `sizes` (in the entry's order), `rho` by `amount` when
/// it is a density, and `m` by `amount` or by the mass formula. Returns mass, COM (3) and
/// inertia (6) as expression text. @throws rigid::Error if the entry has no formulas.
[[nodiscard]] std::array<std::string, 10> primitive_expressions(const PrimitiveEntry& entry,
                                                                Amount amount,
                                                                const std::string& amount_text,
                                                                std::span<const std::string> sizes);

/// A point mass as expression text: its mass (kg) and position (m) in the body frame.
struct PointMassText {
  std::string mass;
  std::array<std::string, 3> position;
};

/// The closed forms of point_masses as expression text, laid out as primitive_expressions':
/// mass Σ mᵢ, COM c = Σ mᵢ pᵢ / Σ mᵢ (3), inertia about c (6: xx yy zz xy xz yz)
/// Σ mᵢ (|pᵢ − c|² 1 − (pᵢ − c)(pᵢ − c)ᵀ), every operand in parentheses and nothing
/// simplified (the symbolic engine does that: one point at the origin gives m and zeros).
/// @throws rigid::Error if `points` is empty.
[[nodiscard]] std::array<std::string, 10> point_mass_expressions(
    std::span<const PointMassText> points);

}  // namespace rigid::mass
