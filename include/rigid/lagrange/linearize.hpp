#pragma once

/// Linearisation of a Lagrangian system about an equilibrium or a steady motion, and its
/// normal modes.
///
/// At a point (q*, q̇*) where q̈ = 0 — an equilibrium (q̇* = 0) or a steady motion (cyclic
/// coordinates turning at constant rates, the others at rest) — a small motion
/// q = q*(t) + δq obeys
///   M δq̈ + C δq̇ + K δq = 0,   M = M(q*),  C = −∂f/∂q̇,  K = −∂f/∂q  at (q*, q̇*),
/// with f of rigid::lagrange::System (M q̈ = f). C and K are the symbolic derivatives of the
/// derived equations, evaluated in double: exact to rounding. Cyclic coordinates on which no
/// equation depends are ignorable: their momenta stay at their steady values (Routh), which
/// removes them from the eigenproblem [Goldstein2002, §5.6, §6.2]:
///   M̃ = M_rr − M_rc M_cc⁻¹ M_cr,
///   C̃ = C_rr − M_rc M_cc⁻¹ C_cr − C_rc M_cc⁻¹ M_cr,
///   K̃ = K_rr − C_rc M_cc⁻¹ C_cr     (r: the other coordinates, c: the ignorable ones).
/// With holonomic constraints g(q) = 0 the point also satisfies g = 0 and f + Gᵀλ = 0; the
/// constraint forces' change adds −Σ λ_k ∂²g_k/∂q² to K, and the motion stays on the
/// constraints' tangent space δq = N δy (G N = 0), so the matrices become Nᵀ M̃ N, Nᵀ C̃ N,
/// Nᵀ K̃ N. Without gyroscopic or damping terms (C = 0) and with a symmetric K, the modes solve
/// the symmetric problem K φ = ω² M φ; otherwise the state-space problem
///   λ x = A x,  A = [0 1; −M⁻¹K −M⁻¹C],  x = (δy, δẏ).

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/lagrange/system.hpp"

namespace rigid::lagrange {

/// A value given for the point: a coordinate's value (`theta1`, m or rad) or the rate of a
/// cyclic coordinate (`psi_dot`, m/s or rad/s).
struct PointValue {
  std::string name;
  double value = 0.0;
};

/// Where to linearise.
struct LinearizeOptions {
  /// Coordinates held at the given values and cyclic rates. Every other coordinate starts at
  /// the System's initial value and is found by Newton (steps of at most 0.5 per coordinate;
  /// where Newton stalls, pseudo-transient continuation follows the damped motion to rest);
  /// every other cyclic rate is the System's initial velocity; every other velocity is 0.
  std::vector<PointValue> at{};
  /// Values of parameters for this call only, by name.
  std::vector<Parameter> parameters{};
  /// Most iterations of each search.
  int max_iterations = 200;
};

/// Stability of the linearised motion.
///  - kStable: every eigenvalue λ has Re λ ≤ 0 and none is 0 (oscillating or decaying);
///  - kUnstable: some Re λ > 0 (a mode grows);
///  - kMarginal: none grows but some λ = 0 (a neutral direction: the linear terms do not
///    decide, and a system with no non-ignorable coordinate).
/// Zero is judged relative to the largest |λ|: 1e-9 of max ω² for the symmetric problem,
/// 1e-6 of max |λ| for the state-space one (whose double eigenvalues are only determined to
/// about √ε relative).
enum class Stability { kStable, kMarginal, kUnstable };
[[nodiscard]] const char* to_string(Stability stability);

/// One normal mode: δq(t) = Re(shape · e^{λ t}).
struct Mode {
  std::complex<double> eigenvalue;  ///< λ (1/s); Im λ ≥ 0
  double omega = 0.0;               ///< angular frequency |Im λ| (rad/s)
  double hz = 0.0;                  ///< omega / 2π (Hz)
  /// ω² of K̃ φ = ω² M̃ φ (1/s²; negative: unstable); NaN for the state-space problem.
  double omega_squared = 0.0;
  double growth_rate = 0.0;  ///< Re λ (1/s)
  Stability stability = Stability::kStable;  ///< of this mode alone
  /// Over all coordinates, in their order; M-normalised (φᴴ M̃ φ = 1 over the non-ignorable
  /// coordinates, which for an equilibrium is φᴴ M φ = 1 over all), and its largest component
  /// real and positive. Ignorable coordinates move as their fixed momenta require.
  Eigen::VectorXcd shape;
};

/// The linearisation and its modes.
struct NormalModes {
  std::vector<std::string> coordinate_names;
  std::vector<std::string> ignorable_names;  ///< cyclic coordinates removed by Routh reduction
  std::vector<std::string> reduced_names;    ///< the coordinates of M̃, C̃, K̃
  Eigen::VectorXd q, q_dot;                  ///< the point
  bool searched = false;  ///< true when some coordinate was found by the search
  int iterations = 0;     ///< iterations of the search
  double residual = 0.0;  ///< max |q̈ᵢ| at the point (the equilibrium's own error)
  std::vector<std::string> constraint_names;
  Eigen::VectorXd lambda;  ///< the multipliers at the point (constraint forces, N or N·m)
  /// n × n, all coordinates; K includes the change of the constraint forces, −Σ λ_k ∂²g_k/∂q²
  Eigen::MatrixXd M, C, K;
  Eigen::MatrixXd M_reduced, C_reduced, K_reduced;  ///< over reduced_names (before projection)
  /// N (n_r × (n_r − m), orthonormal): δq_r = N δy spans the constraints' tangent space
  /// (G N = 0); the eigenproblem is of Nᵀ M̃ N, Nᵀ C̃ N, Nᵀ K̃ N. The identity without
  /// constraints.
  Eigen::MatrixXd tangent_basis;
  bool gyroscopic = false;       ///< solved as the state-space problem
  Eigen::VectorXcd eigenvalues;  ///< all 2 n_r eigenvalues (1/s), by growth, then frequency
  std::vector<Mode> modes;       ///< by frequency, then growth rate
  Stability stability = Stability::kStable;
};

/// Finds (or takes) the point, linearises and solves for the modes. Derives C and K
/// symbolically on each call (GiNaC: call from one thread at a time).
/// @throws rigid::Error for an unknown name in `at` (with a suggestion), a rate given for a
///   coordinate that is not cyclic, a System with explicit time dependence, a point off the
///   constraints or where their gradients are dependent, a
///   search that does not converge (saying where it ended and how to give the point), a
///   given point that is not an equilibrium (naming the coordinate whose acceleration is not
///   0), and a mass matrix that is not positive definite there.
[[nodiscard]] NormalModes normal_modes(const System& system, const LinearizeOptions& options = {});

/// A multi-line, human-readable account: the point, the stability, each mode's ω (rad/s),
/// frequency (Hz) and shape.
[[nodiscard]] std::string to_text(const NormalModes& modes);

}  // namespace rigid::lagrange
