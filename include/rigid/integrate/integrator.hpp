#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rigid/integrate/march.hpp"

namespace rigid::integrate {

/// The integration methods on R^n.
enum class Method {
  kRk4,               ///< classical Runge–Kutta, order 4, fixed step (Boost.odeint)
  kDopri5,            ///< Dormand–Prince 5(4) [Dormand1980], adaptive step, dense output (Boost.odeint)
  kImplicitMidpoint,  ///< y1 = y0 + h f(t + h/2, (y0 + y1)/2): order 2, symplectic [Hairer2006, §VI.3]
  kStormerVerlet,     ///< velocity Verlet for y = (q, v), a = a(t, q): order 2, symplectic [Hairer2006, §I.1.4]
};

/// "rk4", "dopri5", "implicit_midpoint", "stormer_verlet".
[[nodiscard]] std::string_view to_string(Method method);
/// Inverse of to_string(). @throws rigid::Error naming the accepted names.
[[nodiscard]] Method parse_method(std::string_view name);

/// dy/dt = rhs(t, y). The right-hand side writes into `dydt` (already sized like y) and may
/// throw rigid::Error (e.g. a singular mass matrix), which ends the run.
using Rhs = std::function<void(double t, const Eigen::VectorXd& y, Eigen::VectorXd& dydt)>;

/// An initial-value problem y(t0) = y0, dy/dt = rhs(t, y) on [t0, t_end].
struct Problem {
  Rhs rhs;
  Eigen::VectorXd y0;
  double t0 = 0.0;   ///< s
  double t_end = 0;  ///< s, > t0
  /// Störmer–Verlet only: y = (q, v) with q the first n_position components, dq/dt = v
  /// and dv/dt = a(t, q) not depending on v. -1: half of y.
  int n_position = -1;
  /// Names of the components of y for error messages (empty: y[i]).
  std::vector<std::string> names;
  /// What y is the state of, for error messages (e.g. "system"); may be empty.
  std::string owner;
};

/// The smallest relative tolerance dopri5 accepts: 10 ε ≈ 2.2e-15. Below it the error
/// estimate is made of round-off, and no step size satisfies it (the step would shrink to
/// nothing).
inline constexpr double kMinRelativeTolerance = 10 * 2.220446049250313e-16;
/// The largest relative or absolute tolerance dopri5 accepts: 0.1. A step is accepted when its
/// error estimate is at most atol + rtol·|y|; at 0.1 that is an error of 10% of the state (or of
/// 0.1 in its units, SI in a scene) in every step, the loosest request that still asks for one
/// significant digit. Beyond it the error control controls nothing: every step the method's
/// stability allows is accepted, and the result is not a solution (rtol = 1e300 gave 5.8e20 for
/// a unit oscillator whose state stays at most 1).
inline constexpr double kMaxTolerance = 0.1;

/// The message that refuses a tolerance above kMaxTolerance, one wording for every entry point:
/// `what` names the argument as its caller knows it ("rtol", "[simulation] tolerance").
[[nodiscard]] std::string tolerance_above_bound(std::string_view what, double value);
/// A dopri5 step shorter than this many ulps of the time (kStepFloor · ε · max(|t|, t_end − t0))
/// ends the run with an error: the time no longer advances in double precision.
inline constexpr double kStepFloor = 16;

/// Integration settings. Units: seconds.
///
/// Fixed-step methods follow the one step rule of rigid::integrate::march: between two output
/// times they take the fewest equal steps no longer than `dt`. Output times are t0 + k·output_dt
/// and t_end (TimeGrid::uniform); output_dt = 0 samples every step of length dt.
struct Options {
  Method method = Method::kDopri5;
  double dt = 1e-3;          ///< largest fixed step; initial step of dopri5
  double rtol = 1e-10;       ///< dopri5 relative tolerance, kMinRelativeTolerance … kMaxTolerance
  double atol = 1e-10;       ///< dopri5 absolute tolerance, > 0 and ≤ kMaxTolerance
  double output_dt = 0.0;    ///< spacing of output samples; 0: every step (and t_end)
  int max_newton = 30;       ///< implicit midpoint: Newton iterations per try (≥ 1)
  /// implicit midpoint: converged when the Newton correction h |δk|∞ is at most
  /// newton_tol · max(1, |y0|∞), or stalled (not decreasing) within 1e3 times that; > 0
  double newton_tol = 1e-14;
  std::size_t max_steps = 500'000'000;
  /// Progress reports and cancellation (polled after every output and every
  /// MarchControl::kPollSteps steps; every step of dopri5).
  MarchControl control{};
};

/// Output samples y(t[k]) = y[k] and counters.
struct Solution {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> y;
  std::size_t steps = 0;
  std::size_t rhs_evaluations = 0;
};

/// Integrates `problem` with `options`. Every step is checked for a non-finite state.
/// @throws rigid::Error for bad options (non-positive dt, t_end ≤ t0, a dopri5 rtol below
///         kMinRelativeTolerance, a dopri5 rtol or atol above kMaxTolerance, max_newton < 1 or
///         newton_tol ≤ 0 for the implicit midpoint, an implicit midpoint whose dense n × n
///         Jacobian and LU would take more than 2 GiB: a state above 11,585; the other methods
///         need memory linear in the state's size, ...),
///         a dopri5 step that underflows (kStepFloor) or fails to be accepted, more than
///         control.max_outputs rows of dopri5 every-step output, a non-finite state (naming the
///         step, t and the component), an implicit-midpoint step whose Newton iteration does not
///         converge (naming h, the residual of the implicit equation and the tolerance), or
///         whatever the right-hand side throws (an error of a fixed step has "at step N from t = …
///         s: " in front, see rigid::integrate::march); rigid::Cancelled from options.control.
[[nodiscard]] Solution integrate(const Problem& problem, const Options& options);

}  // namespace rigid::integrate
