#pragma once

/// The inverse-dynamics regressor of a robot model as one dependency-free source file:
/// `rigid eom MODEL --regressor --emit c++|python`.

#include <string>

#include "rigid/io/robot_model.hpp"
#include "rigid/robot/regressor.hpp"

namespace rigid::robot {

/// What the exported file is called and where it comes from (for its comments).
struct RegressorExportOptions {
  /// The C++ namespace: an identifier (letters, digits, '_', not starting with a digit; refused
  /// otherwise). `rigid eom` makes one from the output file's name by the code export's rule,
  /// lagrange::export_namespace ("main" gives "main_"). Unused by Python.
  std::string name = "model";
  /// The model file, named in the file's first comment; may be empty.
  std::string source{};
};

/// One C++ header (<cmath> only, plain arrays) with, in namespace `options.name`:
///   inline constexpr int nq, nv;        // coordinates (hinges and slides: nq = nv)
///   inline constexpr int np, nb;        // standard parameters π, base parameters β
///   coordinate_names[nq], parameter_names[np], parameter_units[np], base_parameter_names[nb]
///   inline constexpr double standard_parameters[np];   // π of the model
///   inline constexpr int base_columns[nb];              // the columns of Y that make Y_b
///   inline constexpr double base_parameter_values[nb];  // β = C π of the model
///   void regressor(const double* q, const double* q_dot, const double* q_ddot, double* Y);
///   void base_regressor(q, q_dot, q_ddot, double* Y_b);   // nv * np doubles of stack
///   void base_parameters(const double* pi, double* beta);   // β = C π for any π
/// with Y nv × np and Y_b nv × nb row-major, τ = Y π = Y_b β (robot::regressor,
/// robot::base_parameters: the same recursion with the model's joints and placements as
/// constants; the same numbers up to rounding). The file's first comment gives each base
/// parameter as a combination of the named standard parameters.
/// @throws rigid::Error for a joint other than a hinge or a slide (as robot::regressor), a
///   namespace that is not an identifier, or base parameters of another model.
[[nodiscard]] std::string emit_regressor_cpp(const io::RobotModel& model,
                                             const BaseParameters& base,
                                             const RegressorExportOptions& options = {});

/// One Python module (`math` only) with the same content: COORDINATES, PARAMETERS (name → π
/// value), PARAMETER_UNITS, BASE_COLUMNS, BASE_PARAMETERS (name → β value), and
///   regressor(q, q_dot, q_ddot) -> Y (nv lists of np floats)
///   base_regressor(q, q_dot, q_ddot) -> Y_b (nv lists of nb floats)
///   base_parameters(pi=None) -> β (the model's π when pi is None)
[[nodiscard]] std::string emit_regressor_python(const io::RobotModel& model,
                                                const BaseParameters& base,
                                                const RegressorExportOptions& options = {});

}  // namespace rigid::robot
