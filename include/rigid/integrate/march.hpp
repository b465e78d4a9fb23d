#pragma once

/// The one time-marching loop of rigid. Every stepping client (free bodies, general rigid
/// bodies, heavy tops, spring networks, Lagrangian systems through rigid::integrate, scenes)
/// runs its steps through `march`, so that four things are written once:
///  - the output times of a run (`TimeGrid`),
///  - the one rule for the steps between two output times (`TimeGrid::steps_in`): the fewest
///    equal steps no longer than h_max,
///  - the finiteness check of every state component after every step (the error names the
///    body or system, the component, the step and t),
///  - where a step that fails is: an error thrown by a step (an implicit solve that does not
///    converge, a load that returns a non-finite wrench) is rethrown with the step and its
///    start time in front, so that no stepping code has to know them,
///  - progress reports and cancellation (`MarchControl`).
/// Adaptive methods (dopri5) choose their own steps but share the output times, the check
/// and the control.

#include <atomic>
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rigid/common/error.hpp"

namespace rigid::integrate {

/// The output times t_1 ≤ t_2 ≤ … of a run that starts at t_0 = start().
///
/// Class invariant: start and every output time finite; outputs ascending (equal neighbours
/// allowed), the first ≥ start; at most kMaxOutputs of them.
class TimeGrid {
 public:
  /// Most output times a grid may hold (each becomes a row of every output table).
  static constexpr std::size_t kMaxOutputs = 50'000'000;
  /// Relative round-off guard of the step and sample counts: a span within 1e-12 (relative)
  /// of a whole multiple of the step counts as that multiple.
  static constexpr double kRoundOff = 1e-12;

  /// Samples at t0 + k·output_dt (each computed from k, not accumulated) for k = 0, 1, … up to
  /// t_end, and t_end itself last: when t_end − t0 is not a whole multiple of output_dt the last
  /// interval is shorter. output_dt = 0 is refused (a caller that wants "every step" passes its
  /// step).
  /// @throws rigid::Error if t0, t_end or output_dt is not finite, t_end ≤ t0, output_dt ≤ 0, or
  /// the grid would hold more than kMaxOutputs samples (naming the count and the remedy).
  [[nodiscard]] static TimeGrid uniform(double t0, double t_end, double output_dt);

  /// Output times given one by one from the start t0 (the list need not contain t0).
  /// @throws rigid::Error if a time is not finite, comes before its predecessor (or t0), or
  /// there are more than kMaxOutputs of them.
  [[nodiscard]] static TimeGrid from_times(double t0, std::vector<double> outputs);

  [[nodiscard]] double start() const { return start_; }
  [[nodiscard]] double end() const { return outputs_.empty() ? start_ : outputs_.back(); }
  [[nodiscard]] std::size_t size() const { return outputs_.size(); }
  [[nodiscard]] double operator[](std::size_t k) const { return outputs_[k]; }
  [[nodiscard]] std::span<const double> times() const { return outputs_; }
  /// The time before output k: start() for k = 0, else output k − 1.
  [[nodiscard]] double before(std::size_t k) const { return k == 0 ? start_ : outputs_[k - 1]; }

  /// The one step rule: the fewest equal steps no longer than h_max between before(k) and
  /// output k, n = ⌈span/h_max · (1 − kRoundOff)⌉ (0 for an empty interval).
  /// `max_steps` is the limit of the whole run and `steps_before` the steps the intervals before
  /// k took, so that a refusal states the run's count and its limit.
  /// @throws rigid::Error if h_max is not positive and finite, or steps_before + n would exceed
  /// max_steps (the count is compared as a double first: never an out-of-range conversion).
  [[nodiscard]] std::size_t steps_in(std::size_t k, double h_max, std::size_t max_steps,
                                     std::size_t steps_before = 0) const;

 private:
  TimeGrid(double start, std::vector<double> outputs) : start_(start), outputs_(std::move(outputs)) {}
  double start_;
  std::vector<double> outputs_;
};

/// One accepted step as an observer of every step sees it: its span, and the state and the
/// method's continuous extension when the stepping code has them.
struct StepView {
  double t0 = 0;  ///< start of the step (s)
  double t1 = 0;  ///< end of the step (s)
  /// The state at t1 when it is one vector (rigid::integrate::integrate's y); empty when the
  /// caller keeps the state itself (free bodies read it from their own variables).
  std::span<const double> y{};
  /// The method's dense output on [t0, t1]: writes y(t) into `out` (the size of y). Empty when
  /// the method has none (fixed-step methods); dopri5 has its 4th-order continuous extension.
  std::function<void(double t, std::span<double> out)> dense{};
};

/// How a march reports progress and is stopped. Default: silent and unstoppable.
struct MarchControl {
  /// Called with the simulated time reached (s) after every output time and at least every
  /// kPollSteps steps in between. It may throw (rigid::Cancelled) to stop the run.
  std::function<void(double t)> progress{};
  /// When set, read after every step (one relaxed atomic load): true stops the run with
  /// rigid::Cancelled.
  const std::atomic<bool>* cancel = nullptr;
  /// Most steps a whole run may take (a guard against a step far too small for the span).
  std::size_t max_steps = 10'000'000'000;
  /// Most output rows a run may record when their number is not known before it runs (dopri5
  /// sampling every step): a memory guard, set by the front end from its memory limit.
  std::size_t max_outputs = TimeGrid::kMaxOutputs;
  /// When set, called after every accepted step whose state passed the finiteness check,
  /// before the step's output (if it ends an interval) is observed: events between output
  /// times (a scene's metrics) are found here, at the resolution of the steps. It may throw.
  std::function<void(const StepView& step)> on_step{};
  /// Steps between two polls inside a long output interval.
  static constexpr std::size_t kPollSteps = 1024;
};

/// A non-finite state component found after a step: who (a body name, a system, or empty),
/// which component (e.g. "w_B.x", "theta_dot") and its value.
struct NonFinite {
  std::string owner;
  std::string component;
  double value = 0;
};

/// Counters of a march.
struct MarchStats {
  std::size_t steps = 0;
};

/// The message of throw_nonfinite, for a caller that records it instead of throwing (a run
/// that leaves a batch of runs marched together).
[[nodiscard]] std::string nonfinite_message(const NonFinite& bad, std::size_t step, double t, double h);

/// Throws the one error of a diverged state: "non-finite state at step N, t = … s: <owner>
/// <component> = <value>; the motion diverged: reduce the step (h = … s) or check the model".
[[noreturn]] void throw_nonfinite(const NonFinite& bad, std::size_t step, double t, double h);

/// Rethrows the error `e` that step number `step` (counted from 1) starting at time t threw,
/// with the place in front: "at step N from t = … s: <e.what()>".
[[noreturn]] void throw_in_step(const Error& e, std::size_t step, double t);

/// Polls `control` at time t: calls progress, and throws rigid::Cancelled when the cancel
/// flag is set ("cancelled at t = … s").
void poll(const MarchControl& control, double t);

/// The index of the first non-finite value of `values`, if any.
[[nodiscard]] inline std::optional<std::size_t> first_nonfinite(std::span<const double> values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) [[unlikely]] return i;
  }
  return std::nullopt;
}

/// Marches from grid.start() through every output time of `grid`:
///  - `step(t, h)` advances the caller's state from t by h (the caller owns the state);
///  - `find_nonfinite()` returns the first non-finite component of the state
///    (std::optional<NonFinite>), checked after every step;
///  - `observe(k, t)` records output k at its time t (output times are exact grid values; the
///    last step of an interval lands on it).
/// After each step (and its check) control.on_step, when set, sees the step's span.
/// Steps between outputs follow TimeGrid::steps_in; the time inside an interval is
/// before(k) + j·h. Returns the number of steps.
/// @throws rigid::Error for a non-positive or non-finite h_max, a step count above
/// control.max_steps, a non-finite state (throw_nonfinite), whatever `observe` throws, a
/// rigid::Error that `step` throws with "at step N from t = … s: " in front (throw_in_step;
/// anything else `step` throws, rigid::Cancelled included, passes unchanged), and
/// rigid::Cancelled from `control`.
template <typename Step, typename FindNonFinite, typename Observe>
MarchStats march(const TimeGrid& grid, double h_max, Step&& step, FindNonFinite&& find_nonfinite,
                 Observe&& observe, const MarchControl& control = {}) {
  RIGID_REQUIRE(std::isfinite(h_max) && h_max > 0, "the step h_max must be positive and finite, got {} s",
                h_max);
  MarchStats stats;
  std::size_t since_poll = 0;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const double t0 = grid.before(k), t1 = grid[k];
    const std::size_t n = grid.steps_in(k, h_max, control.max_steps, stats.steps);
    const double h = n > 0 ? (t1 - t0) / static_cast<double>(n) : 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double t = t0 + static_cast<double>(j) * h;
      try {
        step(t, h);
      } catch (const Cancelled&) {
        throw;
      } catch (const Error& e) {
        throw_in_step(e, stats.steps + 1, t);  // the place, once for every stepping client
      }
      ++stats.steps;
      if (auto bad = find_nonfinite()) [[unlikely]] {
        throw_nonfinite(*bad, stats.steps, j + 1 == n ? t1 : t + h, h);
      }
      if (control.on_step) control.on_step(StepView{t, j + 1 == n ? t1 : t + h});
      if (++since_poll == MarchControl::kPollSteps) [[unlikely]] {
        since_poll = 0;
        poll(control, t + h);
      } else if (control.cancel != nullptr && control.cancel->load(std::memory_order_relaxed)) [[unlikely]] {
        poll(control, t + h);  // throws rigid::Cancelled
      }
    }
    observe(k, t1);
    poll(control, t1);
  }
  return stats;
}

}  // namespace rigid::integrate
