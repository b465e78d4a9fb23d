#include "detail/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <fmt/format.h>

namespace rigid::scene {
namespace {

using Kind = MetricSpec::Kind;
using Direction = MetricSpec::Direction;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool wants_extrema(const MetricSpec& s) {
  return s.kind == Kind::kExtremum || s.kind == Kind::kMax || s.kind == Kind::kMin;
}
// +1 when the spec looks for maxima, −1 for minima
double sense(const MetricSpec& s) {
  if (s.kind == Kind::kExtremum) return s.maximum ? 1.0 : -1.0;
  return s.kind == Kind::kMax ? 1.0 : -1.0;
}

std::string direction_word(Direction d) {
  switch (d) {
    case Direction::kUp: return "upward ";
    case Direction::kDown: return "downward ";
    case Direction::kAny: return "";
  }
  return "";
}

std::string of_what(const MetricSpec& s) {
  return s.level == 0 ? s.column : fmt::format("{} − {}", s.column, s.level);
}

}  // namespace

MetricRecorder::MetricRecorder(std::vector<MetricSpec> specs, std::vector<std::size_t> column_of)
    : specs_(std::move(specs)), column_of_(std::move(column_of)), state_(specs_.size()) {}

void MetricRecorder::start(double t, const std::vector<double>& values) {
  t_start_ = t_last_ = t;
  last_ = values;
  history_.assign(1, Point{t, values});
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (specs_[i].kind == Kind::kMax || specs_[i].kind == Kind::kMin) {
      state_[i].value = values[column_of_[i]];
      state_[i].found = true;
    }
  }
}

void MetricRecorder::step(double t, const std::vector<double>& values, const MetricProbe* dense) {
  if (dense != nullptr) {
    // the method's continuous extension on this step
    dense_mode_ = true;
    std::vector<double> buffer(values.size());
    const Eval g = [&](double tt, std::size_t c) {
      (*dense)(tt, buffer);
      return buffer[c];
    };
    interval(t_last_, t, last_, values, g);
  } else {
    // fixed steps: interval j is interpolated by the cubic through points j−1 … j+2, so it is
    // processed when the point after its end has come (the first and last use the four nearest)
    if (history_.size() == 4) {
      // the oldest point's buffer takes the new one: no allocation per step
      std::rotate(history_.begin(), history_.begin() + 1, history_.end());
      history_.back().t = t;
      history_.back().v.assign(values.begin(), values.end());
    } else {
      history_.push_back(Point{t, values});
    }
    if (history_.size() == 4) {
      if (!first_done_) {
        cubic_interval(0, 1);
        first_done_ = true;
      }
      cubic_interval(1, 2);
    }
  }
  last_ = values;
  t_last_ = t;
}

void MetricRecorder::cubic_interval(std::size_t a, std::size_t b) {
  // Lagrange form of the polynomial through every point of the history (up to 4: a cubic)
  const std::vector<Point>& h = history_;
  const Eval g = [&h](double t, std::size_t c) {
    double sum = 0;
    for (std::size_t j = 0; j < h.size(); ++j) {
      double w = 1;
      for (std::size_t m = 0; m < h.size(); ++m) {
        if (m != j) w *= (t - h[m].t) / (h[j].t - h[m].t);
      }
      sum += w * h[j].v[c];
    }
    return sum;
  };
  interval(h[a].t, h[b].t, h[a].v, h[b].v, g);
}

void MetricRecorder::interval(double ta, double tb, const std::vector<double>& va,
                              const std::vector<double>& vb, const Eval& g) {
  if (!(tb > ta)) return;
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    const MetricSpec& s = specs_[i];
    State& st = state_[i];
    const std::size_t c = column_of_[i];
    if (s.kind == Kind::kCrossing || s.kind == Kind::kPeriod) {
      const double fa = va[c] - s.level, fb = vb[c] - s.level;
      const bool up = fa < 0 && fb >= 0, down = fa > 0 && fb <= 0;
      const bool match = s.direction == Direction::kUp ? up : s.direction == Direction::kDown ? down : (up || down);
      if (!match) continue;
      double t = tb;
      if (fb != 0) {
        // the zero of the interpolant, bracketed by the step: TOMS 748 to a few ulps of t
        std::uintmax_t iterations = 200;
        const auto root = boost::math::tools::toms748_solve(
            [&](double tt) { return g(tt, c) - s.level; }, ta, tb, fa, fb,
            boost::math::tools::eps_tolerance<double>(std::numeric_limits<double>::digits - 2), iterations);
        t = 0.5 * (root.first + root.second);
      }
      ++st.count;
      if (s.kind == Kind::kPeriod) {
        st.crossings.push_back(t);
      } else if (st.count == *s.k && !st.found) {
        st.time = t;
        st.found = true;
      }
      continue;
    }
    if (!wants_extrema(s)) continue;
    // slopes at both ends (a difference over 1e-3 of the step): a maximum at the shared end
    // of two steps when the slope turns from + to −, inside the step when it does so within
    const double sg = sense(s);
    const double delta = 1e-3 * (tb - ta);
    const double sa = sg * (g(ta + delta, c) - va[c]);
    const double sb = sg * (vb[c] - g(tb - delta, c));
    auto event = [&](double t, double v) {
      if (s.kind == Kind::kExtremum) {
        ++st.count;
        if (st.count == *s.k && !st.found) {
          st.time = t;
          st.value = v;
          st.found = true;
        }
      } else {
        st.value = sg > 0 ? std::max(st.value, v) : std::min(st.value, v);
      }
    };
    if (ta > t_start_ && st.last_slope > 0 && sa <= 0) event(ta, va[c]);
    if (sa > 0 && sb < 0) {
      // Brent's minimisation of −sense·g: the extremum's value to round-off, its time to about
      // √ε of the step (an extremum is flat)
      const auto best = boost::math::tools::brent_find_minima([&](double tt) { return -sg * g(tt, c); }, ta, tb,
                                                              std::numeric_limits<double>::digits / 2);
      event(best.first, -sg * best.second);
    }
    if (s.kind != Kind::kExtremum) event(tb, vb[c]);  // the running max/min sees every step
    st.last_slope = sb;
  }
}

std::vector<io::Metric> MetricRecorder::finish() {
  if (!dense_mode_) {
    if (first_done_) {
      cubic_interval(2, 3);
    } else {
      // fewer than four points in the whole run: every interval on the polynomial through all
      for (std::size_t j = 0; j + 1 < history_.size(); ++j) cubic_interval(j, j + 1);
    }
  }
  std::vector<io::Metric> out;
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    const MetricSpec& s = specs_[i];
    const State& st = state_[i];
    io::Metric m{s.name, kNaN, "", ""};
    switch (s.kind) {
      case Kind::kCrossing:
        if (st.found) {
          m.value = st.time;
        } else {
          m.note = fmt::format("{} {}crossing(s) of {} before t_end = {} s; crossing {} did not happen", st.count,
                               direction_word(s.direction), of_what(s), t_last_, *s.k);
        }
        break;
      case Kind::kExtremum:
        if (st.found) {
          m.value = s.report_value ? st.value : st.time;
        } else {
          m.note = fmt::format("{} {} of {} after t = {} s and before t_end = {} s; {} {} did not happen", st.count,
                               s.maximum ? "maxima" : "minima", s.column, t_start_, t_last_,
                               s.maximum ? "maximum" : "minimum", *s.k);
        }
        break;
      case Kind::kPeriod: {
        // same-direction crossings: every one (up, down), every other one (any: they alternate)
        const std::size_t stride = s.direction == Direction::kAny ? 2 : 1;
        const std::vector<double>& c = st.crossings;
        const std::size_t n = c.size();
        const std::size_t intervals = n > stride ? n - stride : 0;
        if (!s.k) {
          if (intervals > 0) {
            // the mean of c[i + stride] − c[i]: the sum telescopes per residue class
            double sum = 0;
            for (std::size_t r = 0; r < stride && r + stride < n; ++r) {
              const std::size_t last = r + ((n - 1 - r) / stride) * stride;
              sum += c[last] - c[r];
            }
            m.value = sum / static_cast<double>(intervals);
          } else {
            m.note = fmt::format("{} {}crossing(s) of {} before t_end = {} s; a period needs {}", n,
                                 direction_word(s.direction), of_what(s), t_last_, stride + 1);
          }
        } else if (*s.k <= intervals) {
          m.value = c[*s.k - 1 + stride] - c[*s.k - 1];
        } else {
          m.note = fmt::format("{} {}crossing(s) of {} before t_end = {} s; interval {} needs {}", n,
                               direction_word(s.direction), of_what(s), t_last_, *s.k, *s.k + stride);
        }
        break;
      }
      case Kind::kMax:
      case Kind::kMin: m.value = st.value; break;
      case Kind::kFinal: m.value = last_[column_of_[i]]; break;
      case Kind::kDrift: break;
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace rigid::scene
