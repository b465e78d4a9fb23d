#pragma once

// Code export: a System's equations of motion as one dependency-free source file.

#include <cstddef>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "rigid/lagrange/system.hpp"

namespace rigid::lagrange {

/// The languages of the code export.
enum class Language { kCpp, kPython };

/// "c++" (or "cpp", "cxx") and "python" (or "py").
/// @throws rigid::Error naming the unknown language, a close match and the languages.
[[nodiscard]] Language parse_language(std::string_view name);

/// What the exported file is called and where its equations come from (for its comments).
struct ExportOptions {
  /// The C++ namespace of the functions, made an identifier by the export's naming rule
  /// (other characters become '_'; `main`, `std`, keywords, macros and the names <cmath>
  /// declares take a trailing '_': "main" gives `namespace main_`).
  std::string name = "model";
  /// Where the system came from (a scene file), named in the file's first comment; may be empty.
  std::string source{};
  /// C++ only: the flat layout of robot code, at global scope (see emit_cpp).
  bool flat = false;
  /// The flat layout: the most stack (bytes) forward_dynamics_derivatives may take for M⁻¹
  /// and the product −M⁻¹ ∂τ/∂x as n × n locals, 16 n² + 8 n bytes; above, it solves column
  /// by column (3n solves along the tree, O(n) stack: for controllers on small stacks). The
  /// default is 64 degrees of freedom's worth.
  std::size_t max_stack_bytes = kDefaultMaxStackBytes;
  static constexpr std::size_t kDefaultMaxStackBytes = 16 * 64 * 64 + 8 * 64;
  /// The flat layout: the namespace its declarations go in, so that the exports of two models
  /// can share one program (each at global scope would declare the same inline names: one
  /// definition each, which the linker takes as one); empty: global scope. A C++ identifier
  /// as the export's naming rule leaves it, else refused.
  std::string flat_namespace{};
};

/// One C++ header (only <cmath>, plain arrays, no Eigen) with, in namespace `options.name`:
///   struct Parameters { double <name> = <value>; ... };   // the System's current values
///   void mass_matrix(const double q[n], double t, double M[n*n], const Parameters& p = {});
///   void forces(const double q[n], const double q_dot[n], double t, double f[n], p = {});
///   void mass_matrix_and_forces(q, q_dot, t, M, f, p = {});           // shares the work
///   void constraint_jacobian(const double q[n], double t, double G[m*n], p = {});
///   void constraint_gamma(const double q[n], const double q_dot[n], double t, double gamma[m], p);
/// with M row-major, f including the generalized forces, G = ∂g/∂q row-major (m × n) and γ
/// such that G q̈ = γ: M q̈ = f + Gᵀ λ. Each function is the straight-line code of the
/// common-subexpression-eliminated tape of its outputs, with the operations of the engine's
/// tape in the same order, so it computes the engine's numbers (bitwise, on the same platform
/// and libm). Parameters are named arguments: `forces(q, qd, t, f, {.m1 = 2.0})`.
/// For a system without constraints (m = 0) also, on mass_matrix_and_forces:
///   void inverse_dynamics(q, q_dot, const double q_ddot[n], t, double tau[n], p = {});
///       // τ = M q̈ − f: the generalized force that, added to f, gives the acceleration q̈
///   [[nodiscard]] bool forward_dynamics(q, q_dot, const double tau[n], t, double q_ddot[n], p);
///       // q̈ = M⁻¹ (f + τ) by an in-place Cholesky L Lᵀ = M (plain loops); false, q_ddot
///       // unchanged, where a pivot is ≤ 0 or NaN (M not positive definite)
/// A system with constraints gets a comment line in their place: its multipliers λ enter
/// M q̈ = f + τ + Gᵀλ.
/// Names: the export writes the user's names as identifiers under one rule for both languages
/// (docs/lagrange.md, "Names"): a name starting with '_' takes a 'p' in front, then a reserved
/// name (here: a C or C++ keyword, a macro of the compiler or <cmath>, `Parameters`) or one
/// another parameter has takes '_' at its end until it is neither. The file's first comment
/// lists the renames ("float → float_"); the struct names the model's name beside a renamed
/// member. So the file builds with -std=c++20 and -std=gnu++20 whatever the model's names.
///
/// With options.flat, the dynamics as robot code calls them, at global scope (no namespace,
/// no t), for a system without constraints whose equations do not depend on t:
///   inline constexpr int nq, nv;  (n = nq = nv)   coordinate_names[nq]
///   struct Parameters { ... };                      // the model's values as defaults
///   void mass_matrix(const double* q, double* M, const Parameters& p = {});
///   void inverse_dynamics(q, q_dot, q_ddot, double* tau, p = {});        // τ = M q̈ − f
///   void forward_dynamics(q, q_dot, tau, double* q_ddot, p = {});        // q̈ = M⁻¹ (f + τ)
///   void inverse_dynamics_derivatives(q, q_dot, q_ddot, dtau_dq, dtau_dq_dot, dtau_dq_ddot, p);
///   void forward_dynamics_derivatives(q, q_dot, tau, q_ddot, dq_ddot_dq, dq_ddot_dq_dot,
///                                     dq_ddot_dtau, p);
/// Matrices nv × nv row-major, [i*nv + j] = ∂(output i)/∂(input j). forward_dynamics factors M
/// as Lᵀ D L along the tree of the coordinates that M's pattern shows (Featherstone 2008,
/// §6.5; a dense M: the chain), unrolled; the derivatives are the forward-mode derivatives of
/// the same equations through their intermediates (exact up to rounding), ∂q̈/∂x = −M⁻¹ ∂τ/∂x
/// (M⁻¹ times ∂τ/∂x as n × n locals, or column by column beyond options.max_stack_bytes).
/// Where M is not positive definite at q (parameters no body can have) the forward outputs are
/// NaN. Helpers live in namespace `<name>_detail`.
/// @throws rigid::Error for a system with constraints or explicit time dependence.
[[nodiscard]] std::string emit_cpp(const System& system, const ExportOptions& options = {});

/// One Python module (only `math`) with the same functions, returning lists:
///   mass_matrix(q, t=0.0, *, <name>=<value>, ...) -> M (n lists of n floats)
///   forces(q, q_dot, t=0.0, *, ...) -> f;  mass_matrix_and_forces(...) -> (M, f)
///   constraint_jacobian(q, t=0.0, *, ...) -> G (m lists of n);  constraint_gamma(...) -> γ
///   inverse_dynamics(q, q_dot, q_ddot, t=0.0, *, ...) -> τ          (m = 0 only, as in C++)
///   forward_dynamics(q, q_dot, tau, t=0.0, *, ...) -> q̈; ValueError where M is not
///       positive definite (a Cholesky pivot ≤ 0 or NaN)
/// and COORDINATES, CONSTRAINTS, PARAMETERS (name → default). A parameter's keyword argument
/// follows emit_cpp's rule with Python's reserved names (keywords and soft keywords, the
/// arguments q, q_dot, q_ddot, tau, t, and math, float, len, range, ValueError); the renames
/// are listed in the first comment and PARAMETER_NAMES (name → argument). Where C++ gives inf or NaN
/// (a division by 0, sqrt of a negative number), Python's math raises ValueError or
/// ZeroDivisionError.
[[nodiscard]] std::string emit_python(const System& system, const ExportOptions& options = {});

/// The C++ namespace the export writes for `name`, by the export's naming rule (emit_cpp):
/// other characters than letters, digits and '_' become '_'; `main`, `std`, keywords, macros
/// and the names <cmath> declares take a trailing '_' ("main" gives "main_").
[[nodiscard]] std::string export_namespace(const std::string& name);

/// emit_cpp or emit_python.
[[nodiscard]] std::string emit(const System& system, Language language,
                               const ExportOptions& options = {});

/// The constraint terms the exported code computes, from the engine: G = ∂g/∂q (m × n) and
/// γ with G q̈ = γ, at (t, q, q̇), for the parameters of `w`.
void constraint_terms(const System& system, Workspace& w, double t, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& q_dot, Eigen::MatrixXd& G, Eigen::VectorXd& gamma);

}  // namespace rigid::lagrange
