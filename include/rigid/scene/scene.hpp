#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"

namespace rigid::scene {

using rigid::did_you_mean;

/// A number or an expression string exactly as the scene file gave it, with the
/// position of the value so that later errors (undefined symbol, parse error inside
/// the expression) can point into the file.
struct Expression {
  std::string text;             ///< as written, or the number in shortest round-trip form
  SourceLocation where;         ///< position of the value in the scene file
  std::optional<double> number; ///< set when the file gave a plain number
  bool quoted = false;          ///< true for a string value (its text starts one column later)

  /// Location of character `offset` of `text` in the file (for errors inside the expression).
  [[nodiscard]] SourceLocation at(std::size_t offset) const;
  /// The number `value` as an expression (its shortest round-trip decimal), from `where`.
  [[nodiscard]] static Expression of(double value, SourceLocation where);
};

/// A named parameter from `[parameters]`, usable in every expression.
struct Parameter {
  std::string name;
  Expression value;
};

/// A generalized coordinate from `[[coordinates]]`.
struct Coordinate {
  std::string name;
  Expression initial;   ///< q(0) (m or rad)
  Expression velocity;  ///< q̇(0)
  SourceLocation where;
  /// kBall: the orientation of a ball joint (rigid::lagrange::Coordinate::Kind::kBall), with
  /// `orientation` its unit quaternion (w, x, y, z) at the start and `angular_velocity` ω(0)
  /// in its body's frame (rad/s); `initial` and `velocity` are not used
  enum class Kind { kScalar, kBall };
  Kind kind = Kind::kScalar;
  std::array<Expression, 4> orientation{};
  std::array<Expression, 3> angular_velocity{};
};

/// One elementary rotation about a fixed unit axis by an angle expression (rad).
struct AxisRotation {
  std::array<double, 3> axis{};
  Expression angle;
};

/// One joint of a body posed by coordinates, from `[[bodies.joints]]`, in the frame left by
/// the body's position, rotations and the joints before it: a turn by `amount` (rad, right
/// hand) about `axis` through `anchor` (m), or a slide by `amount` (m) along `axis`
/// (rigid::lagrange::JointMotion). The parser normalises `axis`.
/// A ball (kBall, from a robot model's ball or free joint) turns about `anchor` by the
/// orientation of the ball coordinate `amount` names.
struct Joint {
  enum class Kind { kTurn, kSlide, kBall };
  Kind kind = Kind::kTurn;
  std::array<double, 3> axis{0, 0, 1};
  std::array<double, 3> anchor{};
  Expression amount;
  SourceLocation where;  ///< the joint's table
};

/// A point mass (kg) at a position (m) in the body frame.
struct PointMass {
  Expression mass;
  std::array<Expression, 3> position;
};

/// Where a body's mass properties come from.
struct MassSpec {
  enum class Kind { kPrimitive, kMesh, kExplicit, kPointMasses };
  Kind kind = Kind::kPrimitive;
  /// kPrimitive: the shape's canonical name in the catalogue (rigid::mass::primitive_table;
  /// the file may use any alias), its sizes in metres (canonical size names, in the file's
  /// order), and its vertices (the tetrahedron).
  std::string primitive;
  std::vector<std::pair<std::string, Expression>> dimensions;
  std::vector<std::pair<std::string, std::array<Expression, 3>>> vertices;
  /// kPrimitive, kMesh: exactly one of total mass (kg) and density (kg/m³).
  std::optional<Expression> mass;
  std::optional<Expression> density;
  /// kPrimitive (box, cylinder, sphere), instead of mass and density: ρ(x, y, z) in kg/m³, an
  /// expression of x, y, z (m, the shape's own frame) and the parameters (density_field.hpp).
  std::optional<Expression> density_field;
  /// kMesh: the file (resolved against the scene file's directory), its length unit, a thin
  /// shell instead of a solid (with an optional wall thickness, m), and hole filling.
  std::filesystem::path mesh_file;
  std::string units = "m";
  bool shell = false;
  std::optional<Expression> thickness;
  bool fill_holes = false;
  /// kExplicit: mass, COM in the body frame, inertia about the COM (xx yy zz xy xz yz,
  /// tensor elements, kg·m²).
  std::array<Expression, 3> com;
  std::array<Expression, 6> inertia;
  /// kPointMasses.
  std::vector<PointMass> points;
  SourceLocation where;
};

/// A rigid body: its mass properties and either a pose that is a function of the
/// coordinates and time, or a free body with an initial pose and twist.
struct Body {
  std::string name;
  SourceLocation where;
  MassSpec mass;
  bool free = false;
  /// Pose of the body frame B in its parent's frame P (the world W when `parent` is empty) as
  /// expressions: X_PB = Trans(position) R_1 R_2 ... R_k J_1 ... J_m (the listed rotations,
  /// then the joints, composed left to right); X_WB = X_WP X_PB.
  std::array<Expression, 3> position;
  std::vector<AxisRotation> rotations;
  /// A constant rotation matrix before `rotations` (row-major; rigid::lagrange::Body::
  /// orientation): set for a robot link's placement, not by the TOML format.
  std::optional<std::array<double, 9>> orientation;
  /// The body this one hangs from (empty: the world): a body posed by coordinates declared
  /// earlier in the file.
  std::string parent;
  SourceLocation parent_where;  ///< the `parent` value, for errors about it
  std::vector<Joint> joints;
  /// Free body: initial position (m), orientation as a unit quaternion (w, x, y, z),
  /// velocity of the COM in the world (m/s), angular velocity in the body frame (rad/s).
  std::array<double, 3> initial_position{};
  std::array<double, 4> initial_orientation{1, 0, 0, 0};
  std::array<double, 3> initial_velocity{};
  std::array<double, 3> angular_velocity{};
  /// Free body with a fixed pivot (heavy top): the pivot in the body frame (m).
  std::optional<std::array<double, 3>> pivot;
};

/// A named expression: a holonomic constraint g(q, t) = 0, a potential V(q, t) (J), or
/// a generalized force Q_i(q, q̇, t) on one coordinate.
struct NamedExpression {
  std::string name;  ///< constraint/potential name, or the coordinate a force acts on
  Expression expression;
};

/// A velocity (nonholonomic) constraint from `[[velocity_constraints]]`:
/// Σᵢ Aᵢ(q, t) q̇ᵢ + a(q, t) = 0, with one coefficient per coordinate it involves.
struct VelocityConstraint {
  std::string name;
  std::vector<NamedExpression> coefficients;  ///< (coordinate name, Aᵢ)
  std::optional<Expression> term;             ///< a(q, t) (may hold velocities linearly)
  SourceLocation where;
};

/// A linear spring between a point of one body and a point of another body or of the
/// world: V = ½ k (|p_a − p_b| − rest_length)².
struct Spring {
  std::string body_a, body_b;            ///< body_b empty: anchored in the world
  std::array<double, 3> point_a{}, point_b{};  ///< in the body frames (or world for b)
  Expression stiffness;                  ///< N/m
  Expression rest_length;                ///< m
  SourceLocation where;
};

/// How the run page draws a constraint (`rope = {...}` in a `[[constraints]]` entry): a straight
/// rope from a point of `body_a` to a point of `body_b` or of the world. Drawing only: the
/// constraint's expression is what the equations use.
struct Rope {
  std::string constraint;                      ///< the constraint's name
  std::string body_a, body_b;                  ///< body_b empty: ends in the world
  std::array<double, 3> point_a{}, point_b{};  ///< in the body frames (or world for b), m
  SourceLocation where;
};

/// `[simulation]`.
struct Simulation {
  Expression t_end;                   ///< s
  std::string integrator;             ///< empty: the default of the system kind
  std::optional<Expression> dt;       ///< fixed step (s)
  std::optional<Expression> tolerance;///< relative and absolute tolerance of adaptive methods
  std::optional<Expression> output_dt;///< spacing of output rows (s); default: every step
  SourceLocation where;
};

/// A scalar a run reports, from `[[output.metrics]]` (docs/scene-format.md, "Metrics").
struct MetricSpec {
  enum class Kind { kCrossing, kExtremum, kPeriod, kMax, kMin, kFinal, kDrift };
  enum class Direction { kUp, kDown, kAny };
  std::string name;
  Kind kind = Kind::kFinal;
  /// The trajectory column it reads (drift: "energy", "jacobi" or "<body>.L", the norm of a
  /// free body's angular momentum).
  std::string column;
  double level = 0;  ///< crossing, period: the zeros of column − level
  Direction direction = Direction::kAny;  ///< crossing (default any), period (default up)
  /// crossing, extremum: which event (1 = the first); period: which interval between successive
  /// crossings (unset: their mean).
  std::optional<std::size_t> k;
  bool maximum = true;         ///< extremum: of a maximum (true) or a minimum
  bool report_value = false;   ///< extremum: its value instead of its time
  std::string unit;            ///< as given by `unit` (empty: derived from the column)
  bool unit_given = false;
  SourceLocation where;         ///< the metric's table
  SourceLocation column_where;  ///< its `column` value
};

/// `[output]`.
struct Output {
  /// relative to the working directory; empty: "out/<scene file stem>"
  std::filesystem::path directory;
  std::vector<std::string> formats = {"csv", "json"};  ///< csv, npy, json
  /// Columns of the trajectory to keep (names or shell patterns such as "racket.w*");
  /// empty: all. `t` is always kept.
  std::vector<std::string> quantities;
  SourceLocation quantities_where;
  /// Most bytes the trajectory may take (rows × columns × 8), checked before a run; unset:
  /// the front end's value or rigid::io::kDefaultMaxMemory.
  std::optional<std::uint64_t> max_memory;
  SourceLocation max_memory_where;
  /// `[[output.metrics]]`, in file order.
  std::vector<MetricSpec> metrics;
};

/// How a robot model file (URDF, MJCF) is read where a scene takes one: a model file given as
/// the scene, or the file of a scene's `[model]` section. A field left unset keeps the
/// section's setting (else the default, io::RobotReadOptions's); a field set overrides it (the
/// command line's --pin-free-root, --inertia-from-geometry, --density; Python's keywords). A
/// TOML scene without `[model]` reads no model file, so a field set for it is refused.
struct ModelOptions {
  /// A free joint on a body of the world is welded where it stands instead of refused.
  std::optional<bool> pin_free_root{};
  /// Every link's inertial from its geometry (MJCF: MuJoCo's compiler's rules; URDF: the
  /// collision geometry at `density`; a link without collision keeps its stated inertial).
  std::optional<bool> inertia_from_geometry{};
  /// kg/m³, finite and > 0: the density of a URDF's collision geometry, used with
  /// inertia_from_geometry (default 1000).
  std::optional<double> density{};
  /// Each link's mass, COM (in its frame) and inertia about the COM (in its frame) as the scene
  /// parameters m_<link>, com_<link>_x … and I_<link>_xx, _yy, _zz, _xy, _xz, _yz (SI), whose
  /// values are the file's: the equations keep them as symbols, `--set` and sweeps change them.
  std::optional<bool> symbolic_inertia{};

  /// True when no field is set.
  [[nodiscard]] bool empty() const {
    return !pin_free_root && !inertia_from_geometry && !density && !symbolic_inertia;
  }
};

/// `[model]`: the robot model file a scene is built on, and how it was read (the section's
/// settings with ModelOptions over them).
struct ModelSection {
  std::filesystem::path file;  ///< resolved against the scene file's directory
  bool pin_free_root = false;
  bool inertia_from_geometry = false;
  double density = 1000;  ///< kg/m³
  bool symbolic_inertia = false;
  SourceLocation where;   ///< the `file` value
};

/// A whole scene as written, checked for structure, types and names but not yet turned
/// into a model (that needs the expression parser; see rigid::scene::build).
struct Scene {
  std::filesystem::path file;
  /// Set when the scene is built on a robot model file (`[model]`): its bodies, coordinates,
  /// gravity, damping forces, spring potentials and armature come from that file, and the
  /// scene's own entries add to them (docs/scene-format.md, "[model]").
  std::optional<ModelSection> model;
  std::vector<Parameter> parameters;
  std::vector<Coordinate> coordinates;
  std::vector<Body> bodies;
  std::vector<NamedExpression> constraints;
  std::vector<NamedExpression> potentials;
  std::vector<NamedExpression> forces;
  std::vector<Spring> springs;
  std::vector<Rope> ropes;  ///< from the constraints' `rope` keys, for drawing
  std::vector<VelocityConstraint> velocity_constraints;
  std::array<Expression, 3> gravity;  ///< m/s², world frame; default (0, 0, 0)
  /// `lagrangian`: a Lagrangian L(q, q̇, t) (J) of the coordinates, added to the bodies'
  /// T − V (rigid::lagrange::SystemSpec::lagrangian). A multi-line string's `where` is the
  /// position of its first character, and errors inside it count lines from there.
  std::optional<Expression> lagrangian;
  Simulation simulation;
  Output output;

  /// True when the scene is made of free bodies (simulated on SO(3)); false when it is
  /// a system of generalized coordinates (simulated by the Lagrangian engine).
  [[nodiscard]] bool is_free_body_scene() const;
};

/// Parses a scene from TOML text; `file` is used in messages and to resolve mesh paths and a
/// `[model]` file. `model` overrides the settings of a `[model]` section.
/// @throws rigid::Error starting with "file:line:col:" for TOML syntax errors, unknown
///         keys (with a "did you mean" suggestion), wrong types and missing fields; the
///         model file's errors start with its own file:line. A `model` option set for a scene
///         without `[model]` is refused.
[[nodiscard]] Scene parse_scene(std::string_view toml_text, const std::filesystem::path& file,
                                const ModelOptions& model = {});

/// Largest scene file that is read (16 MiB).
inline constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t{16} << 20;

/// Reads and parses a scene file: a regular file of at most kMaxSceneFileBytes, TOML or a robot
/// model file (URDF, MJCF; rigid/scene/robot_scene.hpp) read with `model`'s settings.
/// @throws rigid::Error if it is missing, a directory, not a regular file (a device such as
///   /dev/zero, a pipe), larger than the cap, cannot be read, or cannot be parsed, and for a
///   `model` option that does not apply (set for a TOML scene without `[model]`; a density
///   without inertia_from_geometry, or for a model other than URDF; a density ≤ 0).
[[nodiscard]] Scene load_scene(const std::filesystem::path& file, const ModelOptions& model = {});

/// The names an override may set, as the scene file nests them: each parameter by its plain
/// name, `simulation.<key>` (t_end, dt, tolerance, output_dt, integrator), `<coordinate>.initial`
/// and `<coordinate>.velocity`, and for each free body `<body>.<key>` with key one of
/// initial_position (alias position), initial_velocity (velocity), angular_velocity (omega),
/// initial_quaternion (quaternion).
[[nodiscard]] std::vector<std::string> override_names(const Scene& scene);

/// Applies `name=value` assignments (the command line's --set, Python's set=[...], a sweep's
/// grid): a parameter, a [simulation] setting or an initial condition, named as
/// override_names() lists them. A scalar value is a number or an expression of the parameters
/// (as the file would hold it); a vector value is `[a, b, c]` (numbers); integrator a name.
/// @throws rigid::Error naming the assignment for a malformed one, an unknown name (with "did
///   you mean" and, for a coordinate or body named alone, the names that set it), a value of
///   the wrong shape or a non-finite number.
void apply_overrides(Scene& scene, const std::vector<std::string>& assignments);

}  // namespace rigid::scene
