#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"
#include "rigid/mass/placement.hpp"
#include "rigid/mass/primitive_table.hpp"

/// First-order propagation of input uncertainty to mass properties. Every "±" is one standard
/// deviation (1σ) of an input assumed independent of the others; the output σ is
/// sqrt(Σ_i (∂y/∂x_i)² σ_i²), the linearisation at the nominal inputs, with the Jacobian by
/// central differences.
namespace rigid::mass {

/// One stated tolerance: `name=±value[unit]`, e.g. dims=±0.1mm, density=±2%, mass=±5g.
struct Tolerance {
  std::string name;       ///< dims, density, mass, vertices, or a size name (radius, ...)
  double sigma = 0.0;     ///< 1σ: absolute in SI units (m, kg, the density's unit) or a fraction
  bool relative = false;  ///< true: sigma is a fraction of the nominal value (from %)
  std::string unit;       ///< as written ("mm", "%", ...), "" for none (SI)
};

/// Parses "name=±value[unit],name=±value[unit],..." ('±', '+-' or no sign; units: % for
/// relative; m, cm, mm, um, in for lengths; kg, g for masses; kg/m3, kg/m³, kg/m2, kg/m², kg/m
/// for densities; none: SI).
/// @throws rigid::Error naming the item, what was expected and the position in `text`.
[[nodiscard]] std::vector<Tolerance> parse_tolerances(std::string_view text);

/// A value and its 1σ, element by element.
struct Propagated {
  Eigen::VectorXd value;
  Eigen::VectorXd sigma;
  Eigen::MatrixXd jacobian;  ///< ∂value/∂x (rows: outputs, columns: inputs)
};

/// y = f(x) and its first-order σ for independent inputs with standard deviations `sigma`:
/// σ_y,k = sqrt(Σ_i J_ki² σ_i²), J by central differences with the step
/// h_i = ε^(1/3) · max(|x_i|, σ_i) (truncation O(h²) and round-off O(ε/h) balanced).
/// Inputs whose σ is 0 are not differentiated.
/// @throws rigid::Error if x and sigma differ in size, a σ is negative or not finite, or f
///   throws at a stepped input (its message says which input).
[[nodiscard]] Propagated propagate(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                   const Eigen::VectorXd& x, const Eigen::VectorXd& sigma,
                                   std::span<const std::string> input_names = {});

/// The 10 numbers of a body as propagated: mass, COM (3), then the inertia about `about`
/// (the COM when nullopt) as xx, yy, zz, xy, xz, yz tensor elements.
[[nodiscard]] Eigen::Matrix<double, 10, 1> mass_properties_vector(
    const MassProperties& mp, const std::optional<Eigen::Vector3d>& about = std::nullopt);

/// Mass properties of a catalogue primitive with their 1σ.
struct UncertainMassProperties {
  MassProperties nominal;
  Eigen::Matrix<double, 10, 1> value;  ///< mass_properties_vector(nominal, about)
  Eigen::Matrix<double, 10, 1> sigma;  ///< 1σ of each
  std::vector<std::string> inputs;     ///< the uncertain inputs, e.g. "radius", "density"
};

/// make_primitive(name, amount, value, arguments) placed by `placement`, with the tolerances
/// propagated: `dims` applies to every size (a size's own name overrides it), `vertices` to
/// every coordinate of the points (tetrahedron), `density` and `mass` to the amount (only the
/// one given). Relative tolerances are fractions of each nominal value.
/// @throws rigid::Error for an unknown tolerance name (with did-you-mean), a tolerance of the
///   amount not given (density=… for a body given by mass), one named twice, or a primitive
///   the stepped inputs make invalid.
[[nodiscard]] UncertainMassProperties primitive_uncertainty(
    std::string_view name, Amount amount, double value, const PrimitiveArguments& arguments,
    const Placement& placement, std::span<const Tolerance> tolerances,
    const std::optional<Eigen::Vector3d>& about = std::nullopt);

}  // namespace rigid::mass
