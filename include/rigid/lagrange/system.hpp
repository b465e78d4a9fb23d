#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "rigid/common/error.hpp"
#include "rigid/integrate/integrator.hpp"
#include "rigid/lie/so3.hpp"
#include "rigid/mass/mass_properties.hpp"

namespace rigid::lagrange {

/// An expression string with, optionally, where it came from. Expressions use the names of
/// the parameters, the coordinates `q`, their velocities `q_dot`, the time `t`, `pi`,
/// numbers, `+ - * / ^ ( )` and sin cos tan asin acos atan exp log sqrt abs sinh cosh tanh.
/// When `where` names a file, errors inside the expression are reported as
/// `file:line:col` with col = where.column + offset; otherwise as the column in the text.
struct Expression {
  std::string text;
  SourceLocation where;
  Expression() = default;
  Expression(std::string text_) : text(std::move(text_)) {}   // NOLINT: implicit on purpose
  Expression(const char* text_) : text(text_) {}             // NOLINT: implicit on purpose
  Expression(std::string text_, SourceLocation where_)
      : text(std::move(text_)), where(std::move(where_)) {}
};

/// Limits of one expression, checked while it is parsed (before GiNaC builds or evaluates
/// anything), so that no input crashes the parser or runs for minutes; each is refused with
/// its position.
/// Most characters of an expression's text.
inline constexpr std::size_t kMaxExpressionLength = 1'000'000;
/// Most nested levels: parentheses, function arguments, signs and exponents (`((1))` is 2).
inline constexpr std::size_t kMaxExpressionDepth = 200;
/// A power of two numbers may reach 10^±kMaxPowerDigits (a double ends at 10^308; the margin
/// lets exact intermediate values such as 10^400/10^399 through).
inline constexpr double kMaxPowerDigits = 10'000;
/// A power of two rationals is exact while its result has at most this many bits (about
/// 1.26 million decimal digits); beyond, it is computed in floating point (at least 17
/// significant digits).
inline constexpr double kMaxExactPowerBits = 4'194'304;
/// Most terms an expression may expand to: the equations are derived from the expanded
/// expression, and a positive integer power of a sum multiplies out ((a + b)^n has n + 1
/// terms, a sum of t terms to the n has C(n + t − 1, n)), so (a + pi)^262144 would run for
/// minutes, and 6,562 terms of (a + pi)^6561 take 10 s to derive (1,000 take 0.4 s).
/// Estimated from the parsed expression before anything is expanded.
inline constexpr double kMaxExpandedTerms = 1'000;
/// Most symbols, numbers and operations that multiplying out may create, written out as a
/// tree: (a + (a + pi)^((a + pi)^626)·pi)^626 has 627 terms, each holding a 627-term exponent
/// (about 10^6.2 in all), which took minutes to derive and print. Ten per term of
/// kMaxExpandedTerms' thousand; a long sum as written is not counted. Estimated with
/// kMaxExpandedTerms, before anything is expanded.
inline constexpr double kMaxExpandedNodes = 10'000;
/// Most symbols, numbers and operations an equation of motion or a mass-matrix entry may
/// multiply out to, estimated like kMaxExpandedNodes before it is expanded. An expression
/// within kMaxExpandedNodes can still have derivatives far beyond it: the chain rule through
/// 626^8^(a + pi)^(q + pi)^626 makes each of 626 terms hold a 627-factor product (about
/// 10^6.9; it took minutes and gigabytes to print). A 7-link spatial chain derived expanded
/// estimates about 10^5.1 (its equations print 1.3 MB).
inline constexpr double kMaxEquationNodes = 1'000'000;

/// Three expressions: a vector of the world or a body frame (gravity, a COM). Implicit from a
/// numeric vector (each entry becomes its shortest round-trip decimal).
struct Vector3Expression {
  std::array<Expression, 3> e{Expression("0"), Expression("0"), Expression("0")};
  Vector3Expression() = default;
  Vector3Expression(const Eigen::Vector3d& v);                 // NOLINT: implicit on purpose
  Vector3Expression(std::array<Expression, 3> expressions) : e(std::move(expressions)) {}  // NOLINT
  [[nodiscard]] const Expression& operator[](std::size_t i) const { return e[i]; }
  [[nodiscard]] Expression& operator[](std::size_t i) { return e[i]; }
};

/// Mass properties whose entries are expressions of the parameters, in the body frame B:
/// mass (kg), COM p_BC_B (m) and the inertia about the COM (kg·m²) as the tensor elements
/// xx, yy, zz, xy, xz, yz (off-diagonal elements are −∫ρ x y dV). The equations keep them as
/// written, so a mass `m1` prints as m1. The System checks the numbers (mass > 0, a physical
/// tensor: rigid::MassProperties::check) for the parameters' values.
struct BodyMass {
  /// The order of `inertia`: each element's name (as a scene's [inertia] table spells it)
  /// and its (row, column) in the symmetric tensor.
  struct InertiaElement {
    const char* name;
    int row, col;
  };
  static constexpr std::array<InertiaElement, 6> kInertiaElements{
      {{"ixx", 0, 0}, {"iyy", 1, 1}, {"izz", 2, 2}, {"ixy", 0, 1}, {"ixz", 0, 2}, {"iyz", 1, 2}}};

  Expression mass = "0";
  Vector3Expression com;
  std::array<Expression, 6> inertia{Expression("0"), Expression("0"), Expression("0"),
                                    Expression("0"), Expression("0"), Expression("0")};
  BodyMass() = default;
  /// The numbers of `mp` (each its shortest round-trip decimal).
  BodyMass(const MassProperties& mp);  // NOLINT: implicit on purpose
};

/// A named constant of the model (value in SI units).
struct Parameter {
  std::string name;
  double value = 0.0;
};

/// A generalized coordinate with its initial value q(0) (m or rad) and velocity q̇(0).
///
/// A ball coordinate (kind kBall) is an orientation: the unit quaternion (w, x, y, z) of a
/// ball joint (JointMotion::Kind::kBall), four entries of q named `<name>_qw … <name>_qz`,
/// and as its velocity the angular velocity ω of the body the joint turns, in that body's
/// frame, three entries named `<name>_wx <name>_wy <name>_wz` (MuJoCo's qpos and qvel). Its
/// rate is q̇ = ½ q ⊗ (0, ω) and its equations are Euler–Poincaré's (a quasi-velocity, not a
/// q̇). `initial` and `velocity` are not used; `orientation` and `angular_velocity` are.
struct Coordinate {
  std::string name;
  double initial = 0.0;
  double velocity = 0.0;
  enum class Kind { kScalar, kBall };
  Kind kind = Kind::kScalar;
  /// kBall: q(0), a unit quaternion (w, x, y, z), normalised on use (a norm off 1 by more
  /// than 1e-6 is refused)
  std::array<double, 4> orientation{1, 0, 0, 0};
  /// kBall: ω(0) in the body frame (rad/s)
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
};

/// One rotation exp(θ [a]ₓ) about the fixed unit axis a (normalised on use) by angle θ (rad).
struct AxisRotation {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Expression angle;
};

/// One joint of a body, in the frame left by the body's position, rotations and the joints
/// before it: a turn by `amount` (rad, right hand) about `axis` through `anchor`, or a slide by
/// `amount` (m) along `axis`. axis: non-zero, normalised on use; anchor in that frame (m).
/// As a pose: a turn is J = Trans(anchor) Rot(axis, amount) Trans(−anchor), a slide
/// J = Trans(axis · amount). Parsed like a rotation's angle (q, t and the parameters).
/// A ball (kBall) turns its body about `anchor` by the orientation of the ball coordinate
/// that `amount` names (Coordinate::Kind::kBall): J = Trans(anchor) R(q) Trans(−anchor);
/// `axis` is not used.
struct JointMotion {
  enum class Kind { kTurn, kSlide, kBall };
  Kind kind = Kind::kTurn;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  Expression amount;
};

/// A rigid body whose pose is a function of q and t, relative to its parent frame P (the world
/// W when `parent` is empty):
///   X_PB = Trans(position) · R₁ R₂ ⋯ R_k · J₁ ⋯ J_m,   X_WB = X_WP X_PB,
/// and ω_B = R_PBᵀ ω_P + ω_PB_B (the parent's angular velocity carried into B, plus B's own).
/// Kinetic energy T = ½ m |ċ|² + ½ ω_Bᵀ I_C_B ω_B with c = p_WB + R_WB p_BC and ω_B read off
/// R_WBᵀ Ṙ_WB; gravity adds V = −m g_W · c. Springs, poses and gravity use the world pose.
struct Body {
  std::string name;
  BodyMass mass;
  std::array<Expression, 3> position{Expression("0"), Expression("0"), Expression("0")};  ///< empty: 0
  std::vector<AxisRotation> rotations;
  /// A constant rotation before `rotations` (a robot link's placement: numbers, not angles, so
  /// that no cos of a constant stays in the equations): R = O R₁ ⋯ R_k. A proper rotation.
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
  /// The body this one hangs from: empty for the world, else the name of a body declared
  /// earlier in SystemSpec::bodies (refused otherwise, naming both).
  std::string parent{};
  /// Joints after the rotations, applied left to right (see JointMotion).
  std::vector<JointMotion> joints{};
};

/// A named expression: potential V(q, t) (J), constraint g(q, t) = 0, or, for a force, the
/// generalized force Q(q, q̇, t) on the coordinate called `name`.
struct NamedExpression {
  std::string name;
  Expression expression;
};

/// A linear spring between a point of a body and a point of another body (or of the world):
/// V = ½ k (|p_a − p_b| − rest_length)².
struct Spring {
  std::string body_a{};
  Eigen::Vector3d point_a_B = Eigen::Vector3d::Zero();  ///< in body a's frame (m)
  std::string body_b{};                                 ///< empty: the world
  Eigen::Vector3d point_b_B = Eigen::Vector3d::Zero();  ///< in body b's frame, or world (m)
  Expression stiffness;                                 ///< k (N/m)
  Expression rest_length = "0";                         ///< m
};

/// A velocity (nonholonomic) constraint, linear in the velocities:
///   Σᵢ Aᵢ(q, t) q̇ᵢ + a(q, t) = 0   (m/s or rad/s),
/// one coefficient Aᵢ per coordinate it involves (by the coordinate's name; the others are 0)
/// and an optional term a. The term may also hold velocities linearly (the whole left side
/// may be written there); a coefficient or a term that makes the row nonlinear in q̇ is
/// refused. Ideal constraint forces Aᵀ μ keep it: M q̈ = f + Gᵀ λ + Aᵀ μ.
struct VelocityConstraint {
  std::string name;
  std::vector<NamedExpression> coefficients;  ///< (coordinate name, Aᵢ(q, t))
  Expression term;                            ///< a(q, t); empty text: 0
  SourceLocation where;  ///< the declaration, for errors about the row as a whole
};

/// Everything that defines a system. L = lagrangian + Σ_bodies (T − V_gravity) − Σ potentials;
/// − Σ springs; the equations are M(q, t) q̈ = f(q, q̇, t) + Q + Gᵀ λ, G q̈ = γ.
struct SystemSpec {
  std::vector<Parameter> parameters;
  std::vector<Coordinate> coordinates;
  Expression lagrangian;  ///< optional (empty text: 0), J
  std::vector<Body> bodies;
  Vector3Expression gravity_W;  ///< m/s², acts on the bodies; expressions of the parameters
  std::vector<NamedExpression> potentials;
  std::vector<Spring> springs;
  std::vector<NamedExpression> forces;
  std::vector<NamedExpression> constraints;
  /// Rows A(q, t) q̇ + a(q, t) = 0 with multipliers μ: M q̈ = f + Q + Gᵀ λ + Aᵀ μ, kept at the
  /// acceleration level A q̈ = −(Ȧ q̇ + ȧ) (Baumgarte: the residual c = A q̇ + a obeys
  /// ċ + 2α c = 0, the holonomic rows' equation with g ≡ 0).
  std::vector<VelocityConstraint> velocity_constraints;
  /// How M and f of the bodies are found. kExpanded: Lagrange's equations of the expanded
  /// T − V (every entry a polynomial in q̇ and the sines and cosines of the angles). kRecursive:
  /// the tree's recursions (composite rigid bodies for M, Newton–Euler for the bias forces),
  /// with each link's rotation, axes, velocities, inertias and forces a named intermediate
  /// (Equations::intermediates): linear in the depth where the expanded form grows
  /// exponentially. It applies to bodies whose joints are the coordinates themselves (each
  /// coordinate one joint at most), with constant positions, no `rotations` and no springs;
  /// asked for elsewhere, it is refused saying why. kAuto: kRecursive where it applies and a
  /// chain holds more than kAutoRecursiveDepth joints, else kExpanded.
  enum class Derivation { kAuto, kExpanded, kRecursive };
  Derivation derivation = Derivation::kAuto;
  static constexpr int kAutoRecursiveDepth = 3;
};

/// One printed quantity: plain text (parsable by SymPy's sympify, `^` for powers) and LaTeX.
struct Printed {
  std::string text, latex;
};

/// A symbol of the equations: its name, its LaTeX, what it is and its unit.
struct EquationSymbol {
  std::string name, latex, role, unit;
};

/// The derived equations, printed canonically: the same bytes on every run, terms ordered by
/// coordinate index, then derivative order, then parameters in declaration order, then
/// numbers; simplified as a textbook does (collected per acceleration, common parameters
/// factored out, cos a cos b + sin a sin b = cos(a − b) and the like, sin² + cos² = 1).
struct Equations {
  std::string lagrangian_text, lagrangian_latex;   ///< L
  std::vector<std::string> text;    ///< "Σ_j M_ij q̈_j = f_i + Σ_k λ_k ∂g_k/∂q_i" per coordinate
  std::vector<std::string> latex;   ///< the same in LaTeX
  std::vector<std::string> constraints_text;  ///< g_k(q, t) = 0
  std::vector<std::string> constraints_latex;
  std::string energy_text;          ///< Jacobi integral h = q̇·∂L/∂q̇ − L
  std::vector<std::string> cyclic;  ///< names of cyclic coordinates

  // the structured form (each quantity as text and LaTeX)
  std::vector<std::string> coordinates;      ///< q, in order
  /// With ball coordinates: the velocities (System::velocity_names), which the equations,
  /// M and f are per, and dq/dt of each entry of q (a ball's ½ q ⊗ (0, ω)); empty otherwise
  std::vector<std::string> velocities;
  std::vector<Printed> coordinate_rates;
  std::vector<Parameter> parameters;         ///< in declaration order, with their values
  std::vector<std::string> constraint_names; ///< in order
  Printed lagrangian, kinetic_energy, potential_energy;  ///< L = T − V (J)
  std::vector<std::vector<Printed>> mass_matrix;  ///< M(q, t) = ∂²L/∂q̇∂q̇, n × n
  /// f(q, q̇, t) = inertial + potential + generalized, per coordinate: inertial = ∂T/∂q −
  /// (∂²T/∂q̇∂q) q̇ − ∂²T/∂q̇∂t (Coriolis, centrifugal, driven), potential = −∂V/∂q (gravity,
  /// springs, potentials), generalized = Q (forces).
  std::vector<Printed> forcing, forcing_inertial, forcing_potential, forcing_generalized;
  std::vector<Printed> equations;             ///< the lines of `text` / `latex`
  std::vector<Printed> constraints;           ///< g_k(q, t) (= 0)
  std::vector<std::vector<Printed>> constraint_jacobian;  ///< G = ∂g/∂q, m × n
  std::vector<std::string> velocity_constraint_names;     ///< in order
  std::vector<Printed> velocity_constraints;               ///< A_k(q, t) q̇ + a_k(q, t) (= 0)
  std::vector<std::vector<Printed>> velocity_constraint_matrix;  ///< A, r × n
  Printed jacobi_integral;                    ///< h = q̇·∂L/∂q̇ − L (J)
  /// h is conserved: L and the constraints do not depend on t, there are no forces, and the
  /// velocity constraints have no term a (ideal constraint forces then do no work).
  bool jacobi_conserved = false;
  std::vector<Printed> cyclic_momenta;        ///< p_i = ∂L/∂q̇_i of the `cyclic` coordinates
  std::vector<EquationSymbol> symbols;        ///< every symbol that may appear, with units
  /// The named intermediates of a recursive derivation (SystemSpec::Derivation), in the order
  /// they are defined, each from the ones before it: M, f, L, T and V are printed in terms of
  /// them (name, definition). Empty for an expanded derivation.
  std::vector<std::pair<Printed, Printed>> intermediates;
  /// Free text appended by a front end (e.g. the values of constants named for a scene).
  std::string note;
};

/// How a document of the equations is written: plain text, LaTeX (align* environments) or
/// JSON (every quantity as text and LaTeX, M as a nested array, the symbol lists).
enum class EquationFormat { kText, kLatex, kJson };
/// "text", "latex" or "json". @throws rigid::Error naming the accepted values otherwise.
[[nodiscard]] EquationFormat parse_equation_format(std::string_view name);
/// The whole document. Its labels cannot collide with a user's symbols: text headings are
/// words ("Lagrangian:", "mass matrix:"), LaTeX labels are \mathcal{L}, \mathbf{M}, …, which
/// no name prints as.
[[nodiscard]] std::string format_equations(const Equations& eq, EquationFormat format);

/// How to run a simulation (seconds). Fixed-step methods follow the one step rule of
/// rigid::integrate::march: between two output times the fewest equal steps no longer than dt.
struct SimulationOptions {
  double t_end = 1.0;
  integrate::Method method = integrate::Method::kDopri5;
  double dt = 1e-3;          ///< largest fixed step, initial step of dopri5
  double tolerance = 1e-10;  ///< dopri5 relative and absolute tolerance
  double output_dt = 0.0;    ///< spacing of output rows; 0: every step
  /// Baumgarte stabilisation rate α (1/s) of the constraints: the solver enforces
  /// g̈ + 2α ġ + α² g = 0 instead of g̈ = 0 [Baumgarte1972]. 0 switches it off.
  double stabilization = 10.0;
  /// Initial conditions violating a constraint by more than this (m or rad, m/s or rad/s)
  /// are refused ...
  double consistency_tolerance = 1e-9;
  /// ... unless this is set: then q(0) is projected onto g = 0 (minimum-norm Newton) and
  /// q̇(0) onto ġ = 0.
  bool project_initial = false;
  /// Values of parameters for this run only, by name (the System's own stay as they are, so
  /// several runs with different values may share one System, also on several threads).
  std::vector<Parameter> parameters{};
  /// Progress reports and cancellation (rigid::integrate::MarchControl).
  integrate::MarchControl control{};
};

/// A simulated trajectory; row k of every matrix is the sample at time t[k].
struct Trajectory {
  std::vector<std::string> coordinate_names, constraint_names, cyclic_names;
  std::vector<std::string> velocity_names;  ///< q_dot's columns (System::velocity_names)
  Eigen::VectorXd t;          ///< s
  /// samples × nq and samples × nv (System::num_coordinates, num_velocities); a ball's
  /// quaternion is written normalised
  Eigen::MatrixXd q, q_dot;
  Eigen::MatrixXd lambda;     ///< samples × m: multipliers (constraint forces, N or N·m)
  Eigen::VectorXd energy;     ///< T + V (J)
  Eigen::VectorXd jacobi;     ///< h = q̇·∂L/∂q̇ − L (J)
  Eigen::MatrixXd cyclic_momenta;  ///< samples × #cyclic: p_i = ∂L/∂q̇_i
  Eigen::VectorXd residual;        ///< max_k |g_k(q, t)| per sample
  Eigen::VectorXd velocity_residual;  ///< max_k |ġ_k| per sample
  std::size_t steps = 0, rhs_evaluations = 0;
  // velocity (nonholonomic) constraints
  std::vector<std::string> velocity_constraint_names;
  Eigen::MatrixXd mu;                          ///< samples × r: their multipliers (N or N·m)
  Eigen::VectorXd velocity_constraint_residual;  ///< max_k |A_k q̇ + a_k| per sample
};

/// Pose of a body frame B in the world W: origin p_WB (m) and orientation R_WB.
struct BodyPose {
  Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();
  SO3d R_WB = SO3d::identity();
};

/// Scratch space for evaluating a System: inputs, outputs and factorizations of one run or one
/// thread. A System is immutable once built (but for set_parameter); every evaluation writes
/// only into a Workspace, so one System may be evaluated and simulated from several threads at
/// once, each with its own Workspace. The symbolic side (construction, destruction, equations())
/// uses GiNaC behind the library's one symbolic lock: it may be called from any thread, one
/// call at a time (rigid/lagrange/symbolic_core.hpp counts them).
class Workspace {
 public:
  Workspace(Workspace&&) noexcept;
  Workspace& operator=(Workspace&&) noexcept;
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;
  ~Workspace();
  /// Sets a parameter's value for evaluations through this workspace only.
  /// @throws rigid::Error for an unknown name or a non-finite value.
  void set_parameter(const std::string& name, double value);
  /// Sets several parameters at once; the bodies' masses are checked for the new values
  /// together. @throws rigid::Error for an unknown name, a non-finite value, invalid masses.
  void set_parameters(const std::vector<Parameter>& parameters);

  struct Impl;
  struct Access;  ///< the library's own access to the scratch (src/lagrange)

 private:
  friend class System;
  friend struct Access;
  explicit Workspace(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The value of an expression that uses only numbers, `pi`, functions and the given
/// parameters (no coordinates, velocities or t), e.g. a parameter defined from earlier ones.
/// @throws rigid::Error "<context>: ..." at the offending position for a parse error or an
///   undefined name, and for a value that is not finite (naming it).
[[nodiscard]] double evaluate_constant(const Expression& expression,
                                       const std::vector<Parameter>& parameters,
                                       std::string_view context);

/// A Lagrangian system: symbols, the Euler–Lagrange equations derived once (GiNaC) and
/// compiled into a flat, common-subexpression-eliminated instruction tape evaluated in
/// double; no symbolic work happens after construction.
///
/// Equations [Goldstein2002, §1.4]: with p = ∂L/∂q̇,
///   M = ∂²L/∂q̇∂q̇,  f = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t + Q,
///   M q̈ = f + Gᵀ λ,  G = ∂g/∂q,  G q̈ = γ = −(∂(G q̇ + g_t)/∂q q̇ + ∂(G q̇ + g_t)/∂t).
class System {
 public:
  /// Parses, assembles and derives.
  /// @throws rigid::Error for a parse error (with its column or file:line:col), an undefined
  ///   symbol, a duplicate or invalid name, a velocity inside a position/constraint/potential,
  ///   a force on an unknown coordinate, or a Lagrangian with a velocity it does not depend
  ///   on quadratically (∂²L/∂q̇ᵢ² ≡ 0: singular mass matrix); for a velocity constraint:
  ///   a coefficient of an unknown or repeated coordinate, a row not linear in q̇, a row with
  ///   no velocity in it, or rows that are dependent for every q (at a generic point).
  explicit System(const SystemSpec& spec);
  ~System();
  System(System&&) noexcept;
  System& operator=(System&&) noexcept;
  System(const System&) = delete;
  System& operator=(const System&) = delete;

  /// Entries of q (nq): one per coordinate, four per ball coordinate.
  [[nodiscard]] int num_coordinates() const;
  /// Entries of the velocity q̇ (nv) and of M (nv × nv), f and q̈: one per coordinate, three
  /// per ball coordinate (its ω). Equal to num_coordinates() without ball coordinates.
  [[nodiscard]] int num_velocities() const;
  [[nodiscard]] int num_constraints() const;
  /// The names of q's entries (a ball coordinate `b`: b_qw b_qx b_qy b_qz).
  [[nodiscard]] const std::vector<std::string>& coordinate_names() const;
  /// The names of the velocities' entries: `<coordinate>_dot`, a ball's b_wx b_wy b_wz.
  [[nodiscard]] const std::vector<std::string>& velocity_names() const;
  /// Whether a coordinate is a ball (num_coordinates() != num_velocities()).
  [[nodiscard]] bool has_ball_coordinates() const;
  /// dq/dt at (q, v): v's entries for the coordinates, ½ q ⊗ (0, ω) for a ball's quaternion.
  [[nodiscard]] Eigen::VectorXd coordinate_rates(const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& q_dot) const;
  [[nodiscard]] const std::vector<std::string>& constraint_names() const;
  /// Velocity (nonholonomic) constraints: their number r and names.
  [[nodiscard]] int num_velocity_constraints() const;
  [[nodiscard]] const std::vector<std::string>& velocity_constraint_names() const;
  /// A(q, t) q̇ + a(q, t), one entry per velocity constraint.
  [[nodiscard]] Eigen::VectorXd velocity_constraint_residual(double t, const Eigen::VectorXd& q,
                                                             const Eigen::VectorXd& q_dot) const;
  /// Names of coordinates with ∂L/∂qᵢ ≡ 0, no force and no constraint on them: their
  /// momenta pᵢ = ∂L/∂q̇ᵢ are conserved.
  [[nodiscard]] const std::vector<std::string>& cyclic_coordinates() const;
  [[nodiscard]] Eigen::VectorXd initial_q() const;
  [[nodiscard]] Eigen::VectorXd initial_q_dot() const;

  /// Changes a parameter's default value without re-deriving (workspaces made afterwards see
  /// it). Not to be called while another thread evaluates or simulates this System.
  /// @throws rigid::Error if unknown, not finite, or if it makes a body unphysical.
  void set_parameter(const std::string& name, double value);
  /// Names and default values of the parameters, in declaration order.
  [[nodiscard]] std::vector<Parameter> parameters() const;

  /// A workspace for evaluating this System (with its current parameter values).
  [[nodiscard]] Workspace make_workspace() const;

  /// The equations for printing, made by the first call and kept (parameters with their
  /// current values). Any thread may call it.
  [[nodiscard]] Equations equations() const;

  /// Evaluates M(q, t) (n × n) and f(q, q̇, t) + Q (n).
  void mass_matrix_and_forces(Workspace& w, double t, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& q_dot, Eigen::MatrixXd& M,
                              Eigen::VectorXd& f) const;
  /// q̈ and the multipliers at (t, q, q̇), with Baumgarte rate `stabilization` (1/s): λ of
  /// the holonomic constraints, then μ of the velocity constraints (m + r entries).
  /// @throws rigid::Error naming t and q for a singular mass matrix or dependent constraints.
  void accelerations(Workspace& w, double t, const Eigen::VectorXd& q,
                     const Eigen::VectorXd& q_dot, Eigen::VectorXd& q_ddot,
                     Eigen::VectorXd& lambda, double stabilization = 0.0) const;
  /// T + V and the Jacobi integral h at (t, q, q̇).
  [[nodiscard]] double energy(Workspace& w, double t, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& q_dot) const;
  [[nodiscard]] double jacobi_integral(Workspace& w, double t, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& q_dot) const;
  /// g(q, t).
  [[nodiscard]] Eigen::VectorXd constraint_residual(Workspace& w, double t,
                                                    const Eigen::VectorXd& q) const;
  /// Poses of the bodies at (t, q), in the order of body_names().
  [[nodiscard]] std::vector<BodyPose> body_poses(Workspace& w, double t,
                                                 const Eigen::VectorXd& q) const;

  /// The same evaluations with a workspace made for the call (convenient, not for loops).
  void mass_matrix_and_forces(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
                              Eigen::MatrixXd& M, Eigen::VectorXd& f) const;
  void accelerations(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
                     Eigen::VectorXd& q_ddot, Eigen::VectorXd& lambda,
                     double stabilization = 0.0) const;
  [[nodiscard]] double energy(double t, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& q_dot) const;
  [[nodiscard]] double jacobi_integral(double t, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& q_dot) const;
  [[nodiscard]] Eigen::VectorXd constraint_residual(double t, const Eigen::VectorXd& q) const;
  [[nodiscard]] std::vector<BodyPose> body_poses(double t, const Eigen::VectorXd& q) const;

  /// Names of the bodies of the spec, in order ("body<i>" for an unnamed body i, from 0).
  [[nodiscard]] const std::vector<std::string>& body_names() const;

  /// Number of instructions of the compiled dynamics tape (M, f, G, γ, g, ġ).
  [[nodiscard]] std::size_t tape_size() const;

  /// Simulates from the initial state of the spec (or the given q0, q̇0), with a workspace of
  /// its own: several threads may simulate one System at once.
  /// @throws rigid::Error for inconsistent initial conditions (with the residual) unless
  ///   project_initial, dependent constraints (redundant or inconsistent, named), a mass
  ///   matrix that is not positive definite, a singular mass matrix or non-finite state
  ///   during the run (naming t and the coordinate), an unknown parameter override, and bad
  ///   options; rigid::Cancelled from options.control.
  [[nodiscard]] Trajectory simulate(const SimulationOptions& options) const;
  [[nodiscard]] Trajectory simulate(const SimulationOptions& options, const Eigen::VectorXd& q0,
                                    const Eigen::VectorXd& q_dot0) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Euler's equations of one free body (or of a heavy top about its pivot) in the body frame B,
/// with the inertia as the expressions of `mass`, for printing: text or LaTeX lines
///   I ω̇ + ω × (I ω) = τ   (one line per axis, I about the COM or the pivot),
///   Ṙ_WB = R_WB [ω]×,  and the COM's m c̈ = m g (free) or the gravity torque (top).
/// Parameters keep their names; the inertia about a pivot is I_C + m (|d|² 1 − d dᵀ) with
/// d = COM − pivot, simplified.
/// @throws rigid::Error for a parse error or an undefined name in an expression.
struct FreeBodyEquationsSpec {
  std::string name;
  BodyMass mass;
  bool has_pivot = false;
  Vector3Expression pivot_B;     ///< m, in B (with has_pivot)
  Vector3Expression gravity_W;   ///< m/s²
};
[[nodiscard]] std::vector<std::string> free_body_equations(const std::vector<Parameter>& parameters,
                                                           const FreeBodyEquationsSpec& body,
                                                           bool latex);

}  // namespace rigid::lagrange
