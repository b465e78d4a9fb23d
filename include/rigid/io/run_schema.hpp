#pragma once

/// The typed schema of a run: what each column of the trajectory is (quantity, the body or
/// other owner it belongs to, component, SI unit), the run's kind, and the units of its
/// parameters, diagnostics and metrics. A model publishes it once (rigid::scene::Model::schema);
/// summary.json carries it, and the report, sweeps and Python read it, so no reader infers a
/// unit or a role from a column's name.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::io {

/// What a run integrated: the Euler–Lagrange equations of generalized coordinates, or free
/// bodies (and heavy tops) stepped on SO(3).
enum class RunKind { kCoordinates, kFreeBodies };

/// "coordinates", "free_bodies" (summary.json's "kind").
[[nodiscard]] std::string_view to_string(RunKind kind);
/// Inverse of to_string. @throws rigid::Error naming the kinds.
[[nodiscard]] RunKind parse_run_kind(std::string_view name);

/// The physical quantity of a trajectory column.
enum class Quantity {
  kTime,                ///< t (s)
  kCoordinate,          ///< a generalized coordinate q (m or rad: the scene does not say)
  kCoordinateRate,      ///< its rate q̇
  kPosition,            ///< <body>.x .y .z: origin of B (coordinates) or COM (free bodies) in W (m)
  kOrientation,         ///< <body>.qw .qx .qy .qz: R_WB as a unit quaternion
  kVelocity,            ///< <body>.vx .vy .vz: COM velocity in W (m/s)
  kAngularVelocity,     ///< <body>.wx .wy .wz: ω in B (rad/s)
  kAngularMomentum,     ///< <body>.Lx .Ly .Lz: L in W about the COM or the pivot (kg·m²/s)
  kEnergy,              ///< total energy (J)
  kJacobi,              ///< Jacobi integral (J)
  kMultiplier,          ///< lambda_<constraint>: a generalized constraint force
  kConstraintResidual,  ///< largest |g(q)| of the holonomic constraints
  kVelocityMultiplier,  ///< mu_<constraint> of a velocity constraint
  kVelocityConstraintResidual,  ///< largest |A(q) q̇ + b| of the velocity constraints
  kConjugateMomentum,           ///< p_<q> = ∂L/∂q̇ of a cyclic coordinate
};

/// "time", "coordinate", "coordinate_rate", "position", "orientation", "velocity",
/// "angular_velocity", "angular_momentum", "energy", "jacobi", "multiplier",
/// "constraint_residual", "velocity_multiplier", "velocity_constraint_residual",
/// "conjugate_momentum".
[[nodiscard]] std::string_view to_string(Quantity quantity);
/// Inverse of to_string. @throws rigid::Error naming the quantities.
[[nodiscard]] Quantity parse_quantity(std::string_view name);
/// The SI unit of a quantity: "s", "m", "m/s", "rad/s", "kg·m²/s", "J"; "" for a quaternion and
/// for the quantities whose unit depends on what a coordinate measures (q, q̇, multipliers,
/// residuals, conjugate momenta), which a scene does not state.
[[nodiscard]] std::string_view unit_of(Quantity quantity);

/// One column of a trajectory.
struct Column {
  std::string name;
  Quantity quantity = Quantity::kTime;
  /// The body (pose, velocities, momentum), coordinate (q, q̇, p_q) or constraint (λ, μ) the
  /// column belongs to; "" for t, energy, jacobi and the residuals.
  std::string owner;
  /// "x" "y" "z" (position, and of v, ω, L), "w" "x" "y" "z" (quaternion); "" for a scalar.
  std::string component;
  std::string unit;  ///< unit_of(quantity)

  bool operator==(const Column&) const = default;
};

/// A scalar a run reports besides its columns (a parameter, a diagnostic, a metric), with its
/// SI unit ("" when dimensionless or not stated).
struct Scalar {
  std::string name;
  std::string unit;

  bool operator==(const Scalar&) const = default;
};

/// What a model's runs produce, known before any run.
struct RunSchema {
  RunKind kind = RunKind::kCoordinates;
  std::vector<Column> columns;      ///< the trajectory's, in order, `t` first
  std::vector<Scalar> parameters;   ///< in the order of the summary's parameters
  std::vector<Scalar> diagnostics;  ///< in the order of the summary's diagnostics
  std::vector<Scalar> metrics;      ///< the scene's [[output.metrics]], in file order

  bool operator==(const RunSchema&) const = default;

  /// The columns' names, in order.
  [[nodiscard]] std::vector<std::string> column_names() const;
  /// The column called `name`, or nullptr.
  [[nodiscard]] const Column* find(std::string_view name) const;
  /// The column of `quantity`, `owner` and `component`, or nullptr.
  [[nodiscard]] const Column* find(Quantity quantity, std::string_view owner,
                                   std::string_view component) const;
  /// This schema with only the columns `names`, in that order.
  /// @throws rigid::Error naming a column the schema does not have.
  [[nodiscard]] RunSchema select(std::span<const std::string> names) const;
};

/// A column of `quantity` for `owner`.`component` ("<owner>.<component>" for a body's vector,
/// with the quaternion's components w x y z named qw qx qy qz), unit from unit_of.
[[nodiscard]] Column body_column(Quantity quantity, const std::string& owner,
                                 std::string_view component);

/// The schema as a JSON object: {"kind", "columns": [{"name", "quantity", "owner",
/// "component", "unit"}], "parameters" / "diagnostics" / "metrics": {name: unit}}.
[[nodiscard]] std::string schema_json(const RunSchema& schema);
/// Inverse of schema_json (summary.json's "schema"). @throws rigid::Error naming `source` and
/// what is wrong.
[[nodiscard]] RunSchema parse_schema_json(std::string_view text, std::string_view source);

}  // namespace rigid::io
