#pragma once

// The metrics of a run ([[output.metrics]]), found while it marches: every accepted step is
// seen (rigid::integrate::MarchControl::on_step), and events between steps are located on the
// method's dense output or, for fixed-step methods, on the cubic through four neighbouring
// steps (docs/scene-format.md states the error of each).

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "rigid/io/run_output.hpp"
#include "rigid/scene/scene.hpp"

namespace rigid::scene {

/// The values of the metrics' columns at a time t inside the current step.
using MetricProbe = std::function<void(double t, std::vector<double>& values)>;

class MetricRecorder {
 public:
  /// `specs` (drift excluded: the caller computes it from the diagnostics), each reading
  /// values[column_of[i]] of the probe.
  MetricRecorder(std::vector<MetricSpec> specs, std::vector<std::size_t> column_of);

  /// The state at the start of the run (events at the start itself are not counted).
  void start(double t, const std::vector<double>& values);
  /// A step ending at t with the columns `values` there; `dense` evaluates them anywhere in
  /// the step (nullptr: a fixed-step method, whose steps are interpolated by cubics).
  void step(double t, const std::vector<double>& values, const MetricProbe* dense);
  /// The metrics' values (NaN with a note for an event that did not happen), in spec order;
  /// units are left to the caller.
  [[nodiscard]] std::vector<io::Metric> finish();

 private:
  struct Point {
    double t;
    std::vector<double> v;
  };
  struct State {
    std::size_t count = 0;             // events seen
    double time = 0, value = 0;        // the k-th event (or the running max/min)
    bool found = false;
    double last_slope = 0;             // extremum, max, min: slope at the end of the last interval
    std::vector<double> crossings;     // period: the crossing times
  };
  using Eval = std::function<double(double t, std::size_t column)>;
  void interval(double ta, double tb, const std::vector<double>& va, const std::vector<double>& vb,
                const Eval& g);
  void cubic_interval(std::size_t a, std::size_t b);

  std::vector<MetricSpec> specs_;
  std::vector<std::size_t> column_of_;
  std::vector<State> state_;
  std::vector<Point> history_;  // fixed-step mode: the last four points
  bool first_done_ = false, dense_mode_ = false;
  std::vector<double> last_;
  double t_last_ = 0, t_start_ = 0;
};

}  // namespace rigid::scene
