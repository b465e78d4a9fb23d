#include "rigid/integrate/march.hpp"

#include <cmath>

#include <fmt/format.h>

namespace rigid::integrate {

TimeGrid TimeGrid::uniform(double t0, double t_end, double output_dt) {
  RIGID_REQUIRE(std::isfinite(t0) && std::isfinite(t_end) && t_end > t0,
                "t_end = {} s must be finite and greater than the start t0 = {} s", t_end, t0);
  RIGID_REQUIRE(std::isfinite(output_dt) && output_dt > 0,
                "the output spacing must be positive and finite, got {} s", output_dt);
  // number of whole spacings in the span; compared as a double before any conversion
  const double whole = std::floor((t_end - t0) / output_dt * (1.0 + kRoundOff));
  RIGID_REQUIRE(whole + 2.0 <= static_cast<double>(kMaxOutputs),
                "{} s of output every {} s is {:.4g} samples, more than the {} a run may write; "
                "use a larger output spacing",
                t_end - t0, output_dt, whole + 1.0, kMaxOutputs);
  const auto n = static_cast<std::size_t>(whole);
  std::vector<double> times;
  times.reserve(n + 2);
  for (std::size_t k = 0; k <= n; ++k) {
    times.push_back(std::min(t_end, t0 + static_cast<double>(k) * output_dt));
  }
  // t_end itself closes the grid (replacing a last sample that round-off put just short of it)
  if (t_end - times.back() > kRoundOff * (t_end - t0)) {
    times.push_back(t_end);
  } else {
    times.back() = t_end;
  }
  return TimeGrid(t0, std::move(times));
}

TimeGrid TimeGrid::from_times(double t0, std::vector<double> outputs) {
  RIGID_REQUIRE(std::isfinite(t0), "the start time must be finite, got {} s", t0);
  RIGID_REQUIRE(outputs.size() <= kMaxOutputs, "{} output times are more than the {} a run may write",
                outputs.size(), kMaxOutputs);
  double previous = t0;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    RIGID_REQUIRE(std::isfinite(outputs[i]) && outputs[i] >= previous,
                  "output times must be finite, ≥ the start t0 = {} s and ascending; entry {} is {} s "
                  "after {} s",
                  t0, i, outputs[i], previous);
    previous = outputs[i];
  }
  return TimeGrid(t0, std::move(outputs));
}

std::size_t TimeGrid::steps_in(std::size_t k, double h_max, std::size_t max_steps,
                               std::size_t steps_before) const {
  RIGID_REQUIRE(std::isfinite(h_max) && h_max > 0, "the step h_max must be positive and finite, got {} s",
                h_max);
  const double span = outputs_[k] - before(k);
  if (span <= 0.0) return 0;
  // the kRoundOff keeps a span that is a multiple of h_max up to round-off from taking one
  // extra step
  const double n = std::max(1.0, std::ceil(span / h_max * (1.0 - kRoundOff)));
  const std::size_t left = max_steps - std::min(steps_before, max_steps);
  if (steps_before == 0) {
    RIGID_REQUIRE(n <= static_cast<double>(max_steps),
                  "{} s in steps of at most {} s is {:.4g} steps, more than the {} allowed; use a "
                  "larger step",
                  span, h_max, n, max_steps);
  } else {
    // the limit is the run's: the message counts the whole run, not what is left of it
    const double whole = std::ceil((end() - start_) / h_max * (1.0 - kRoundOff));
    RIGID_REQUIRE(n <= static_cast<double>(left),
                  "{} s in steps of at most {} s is about {:.4g} steps, more than the {} a run may "
                  "take ({} steps reach t = {} s, and the next output at {} s needs {:.4g} more); use "
                  "a larger step",
                  end() - start_, h_max, std::max(whole, static_cast<double>(steps_before) + n),
                  max_steps, steps_before, before(k), outputs_[k], n);
  }
  return static_cast<std::size_t>(n);
}

std::string nonfinite_message(const NonFinite& bad, std::size_t step, double t, double h) {
  const std::string who = bad.owner.empty() ? bad.component : bad.owner + " " + bad.component;
  return fmt::format("non-finite state at step {}, t = {} s: {} = {}; the motion diverged: "
                     "reduce the step (h = {} s) or check the model",
                     step, t, who, bad.value, h);
}

void throw_nonfinite(const NonFinite& bad, std::size_t step, double t, double h) {
  throw Error(nonfinite_message(bad, step, t, h));
}

void throw_in_step(const Error& e, std::size_t step, double t) {
  throw Error(fmt::format("at step {} from t = {} s: {}", step, t, e.what()));
}

void poll(const MarchControl& control, double t) {
  if (control.cancel != nullptr && control.cancel->load(std::memory_order_relaxed)) {
    throw Cancelled(fmt::format("cancelled at t = {} s; nothing was written", t));
  }
  if (control.progress) control.progress(t);
}

}  // namespace rigid::integrate
