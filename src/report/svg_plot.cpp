// A plot as a standalone SVG document (see svg_plot.hpp for the mapping it writes down).
#include "rigid/report/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"

namespace rigid::report {
namespace {

// the picture, in SVG user units
constexpr double kWidth = 800;
constexpr double kHeight = 500;
constexpr double kLeft = 84;    // room for the y tick labels and the y label
constexpr double kTop = 44;     // room for the title
constexpr double kBottom = 56;  // the x tick labels and the x label
constexpr double kNoteLine = 16;
constexpr std::size_t kMaxNotes = 4;
constexpr std::size_t kMaxTicks = 8;  // intervals per axis at most
constexpr std::size_t kLegendChars = 40;
constexpr double kCharWidth = 7;  // a 12-unit sans-serif character, about
// a line leaves out a point closer than this to the last one it drew (user units)
constexpr double kMinStep = 0.5;

constexpr std::array<std::string_view, 10> kColours = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                                       "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                                       "#bcbd22", "#17becf"};

// text for an XML element or attribute: printable UTF-8 (rigid::escaped shows other bytes as
// \xNN, which keeps the document well-formed), then the five XML entities
std::string xml(std::string_view text) {
  const std::string safe = escaped(text);
  std::string out;
  out.reserve(safe.size());
  for (const char c : safe) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// the step of round_ticks as m · 10^e, m one of 1, 2, 2.5, 5
struct Step {
  double mantissa = 1;
  int exponent = 0;
  // k · step, divided rather than multiplied for e < 0, so that 3 · 0.1 prints as 0.3
  [[nodiscard]] double times(double k) const {
    return exponent >= 0 ? k * mantissa * std::pow(10.0, exponent)
                         : k * mantissa / std::pow(10.0, -exponent);
  }
};

// lo == hi (or equal to 12 digits, a conserved energy) widened so the axis has a span
std::pair<double, double> widened(double lo, double hi) {
  const double scale = std::max(std::abs(lo), std::abs(hi));
  if (hi - lo > 1e-12 * scale) return {lo, hi};
  const double mid = lo / 2 + hi / 2;
  const double d = mid == 0 ? 1.0 : 0.1 * std::abs(mid);
  return {mid - d, mid + d};
}

Step tick_step(double lo, double hi, std::size_t at_most) {
  const double n = static_cast<double>(at_most);
  // the span over n without overflow (hi − lo may exceed the largest double); a step below
  // 1e-300 is not tried (a span of subnormals gets ticks 1e-300 apart)
  const double raw = hi / n - lo / n;
  int e = raw > 1e-300 ? static_cast<int>(std::floor(std::log10(raw))) : -300;
  for (;; ++e) {
    for (const double m : {1.0, 2.0, 2.5, 5.0}) {
      const Step s{m, e};
      const double step = s.times(1);
      // the outer multiples floor(lo/step) … ceil(hi/step) span at most n intervals
      if (!std::isfinite(step) || std::ceil(hi / step) - std::floor(lo / step) <= n) return s;
    }
  }
}

// the multiples of the step from the largest <= lo to the smallest >= hi (at most a few: the
// count is from tick_step, so the loop runs on a whole number, not on k, which may be large)
std::vector<double> multiples(double lo, double hi, const Step& s) {
  const double step = s.times(1);
  const double k0 = std::floor(lo / step);
  const double count = std::ceil(hi / step) - k0;
  std::vector<double> ticks;
  if (!std::isfinite(k0) || !(count >= 1) || count > 1e3) return ticks;
  for (int i = 0; i <= static_cast<int>(count); ++i) {
    ticks.push_back(s.times(k0 + i) + 0.0);  // + 0.0: no -0
  }
  return ticks;
}

// a tick's label: as many decimals as the step needs; scientific for large or small values
std::string tick_label(double v, const Step& s, double largest) {
  if (v == 0) return "0";
  const int extra = s.mantissa == 2.5 ? 1 : 0;
  const int decimals = std::max(0, -s.exponent + extra);
  if (largest >= 1e6 || largest < 1e-3 || decimals > 9) {
    const int lead = static_cast<int>(std::floor(std::log10(largest)));
    return fmt::format("{:.{}e}", v, std::max(0, lead - s.exponent + extra));
  }
  return fmt::format("{:.{}f}", v, decimals);
}

struct Axis {
  std::vector<double> ticks;
  std::vector<std::string> labels;
  double lo = 0;  // the outer ticks: the axis' span
  double hi = 1;
};

Axis axis_of(double lo, double hi) {
  Axis a;
  const auto [l, h] = widened(lo, hi);
  const Step s = tick_step(l, h, kMaxTicks);
  a.ticks = multiples(l, h, s);
  if (a.ticks.size() < 2) a.ticks = {l, h};
  a.lo = a.ticks.front();
  a.hi = a.ticks.back();
  // far out (near the largest double) the outer multiples may not exist: the data's own ends
  if (!std::isfinite(a.lo) || !std::isfinite(a.hi) || a.ticks.size() < 2) {
    a.ticks = {l, h};
    a.lo = l;
    a.hi = h;
  }
  const double largest = std::max(std::abs(a.lo), std::abs(a.hi));
  for (const double t : a.ticks) a.labels.push_back(tick_label(t, s, largest));
  return a;
}

// (v − lo) / (hi − lo) without overflow
double fraction(double v, double lo, double hi) { return (v / 2 - lo / 2) / (hi / 2 - lo / 2); }

std::string legend_text(const std::string& label) {
  const std::string safe = escaped(label);
  if (safe.size() <= kLegendChars) return xml(safe);
  return xml(safe.substr(0, kLegendChars - 1)) + "…";
}

}  // namespace

std::vector<double> round_ticks(double lo, double hi, std::size_t at_most) {
  RIGID_REQUIRE(std::isfinite(lo) && std::isfinite(hi) && lo <= hi,
                "expected finite ends lo <= hi, got [{}, {}]", lo, hi);
  RIGID_REQUIRE(at_most >= 1, "at_most must be at least 1 interval, got {}", at_most);
  const auto [l, h] = widened(lo, hi);
  const Step s = tick_step(l, h, at_most);
  std::vector<double> ticks = multiples(l, h, s);
  if (ticks.size() < 2) ticks = {l, h};
  return ticks;
}

std::string svg_plot(const Plot& plot) {
  // the data's finite extent
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (const PlotSeries& s : plot.series) {
    RIGID_ASSERT(s.x.size() == s.y.size());
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x_lo = std::min(x_lo, s.x[i]);
      x_hi = std::max(x_hi, s.x[i]);
      y_lo = std::min(y_lo, s.y[i]);
      y_hi = std::max(y_hi, s.y[i]);
    }
  }
  RIGID_REQUIRE(x_lo <= x_hi, "'{}' has no point with a finite x and y to draw", plot.title);
  // points get 5% of room around them (a circle on the frame is half hidden); lines end at it
  if (plot.marks == PlotMarks::kPoints) {
    const double dx = 0.05 * (x_hi / 2 - x_lo / 2), dy = 0.05 * (y_hi / 2 - y_lo / 2);
    // (kept within the doubles: near the largest one, no room)
    const auto pad = [](double& v, double d) {
      if (std::isfinite(v + d)) v += d;
    };
    pad(x_lo, -2 * dx);
    pad(x_hi, 2 * dx);
    pad(y_lo, -2 * dy);
    pad(y_hi, 2 * dy);
  }
  const Axis ax = axis_of(x_lo, x_hi);
  const Axis ay = axis_of(y_lo, y_hi);

  // the layout: the legend to the right of the plot, the notes under the x label
  std::size_t legend_chars = 0;
  for (const PlotSeries& s : plot.series) {
    legend_chars = std::max(legend_chars, std::min(escaped(s.label).size(), kLegendChars));
  }
  const double right = 16 + 30 + kCharWidth * static_cast<double>(legend_chars) + 8;
  const std::size_t notes = std::min(plot.notes.size(), kMaxNotes);
  const double bottom = kBottom + kNoteLine * static_cast<double>(notes);
  const double left = kLeft, top = kTop;
  const double width = kWidth - left - right;
  const double height = kHeight - top - bottom;
  const auto px = [&](double x) { return left + fraction(x, ax.lo, ax.hi) * width; };
  const auto py = [&](double y) { return top + (1 - fraction(y, ay.lo, ay.hi)) * height; };

  std::string out;
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
  out += fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"12\" "
      "data-x-domain=\"{2} {3}\" data-y-domain=\"{4} {5}\" data-plot-box=\"{6} {7} {8} {9}\">\n",
      kWidth, kHeight, ax.lo, ax.hi, ay.lo, ay.hi, left, top, width, height);
  out += fmt::format("<title>{}</title>\n", xml(plot.title));
  out += fmt::format("<rect width=\"{}\" height=\"{}\" fill=\"white\"/>\n", kWidth, kHeight);
  out += fmt::format(
      "<text class=\"title\" x=\"{:.2f}\" y=\"26\" text-anchor=\"middle\" "
      "font-size=\"14\">{}</text>\n",
      left + width / 2, xml(plot.title));

  // grid lines and tick labels at the round numbers
  out += "<g class=\"x-ticks\" stroke=\"#dddddd\">\n";
  for (std::size_t i = 0; i < ax.ticks.size(); ++i) {
    const double x = px(ax.ticks[i]);
    out += fmt::format(
        "<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{0:.2f}\" y2=\"{2:.2f}\"/>"
        "<text x=\"{0:.2f}\" y=\"{3:.2f}\" text-anchor=\"middle\" stroke=\"none\" "
        "data-value=\"{4}\">{5}</text>\n",
        x, top, top + height, top + height + 16, ax.ticks[i], ax.labels[i]);
  }
  out += "</g>\n<g class=\"y-ticks\" stroke=\"#dddddd\">\n";
  for (std::size_t i = 0; i < ay.ticks.size(); ++i) {
    const double y = py(ay.ticks[i]);
    out += fmt::format(
        "<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{2:.2f}\" y2=\"{1:.2f}\"/>"
        "<text x=\"{3:.2f}\" y=\"{4:.2f}\" text-anchor=\"end\" stroke=\"none\" "
        "data-value=\"{5}\">{6}</text>\n",
        left, y, left + width, left - 6, y + 4, ay.ticks[i], ay.labels[i]);
  }
  out += "</g>\n";
  out += fmt::format(
      "<rect class=\"axes\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" "
      "fill=\"none\" stroke=\"black\"/>\n",
      left, top, width, height);
  out += fmt::format(
      "<text class=\"x-label\" x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"middle\">{}</text>\n",
      left + width / 2, top + height + 38, xml(plot.x_label));
  out += fmt::format(
      "<text class=\"y-label\" x=\"18\" y=\"{0:.2f}\" text-anchor=\"middle\" "
      "transform=\"rotate(-90 18 {0:.2f})\">{1}</text>\n",
      top + height / 2, xml(plot.y_label));

  // the series, each in its colour, and its legend entry
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const std::string_view colour = kColours[k % kColours.size()];
    out += fmt::format("<g class=\"series\" data-label=\"{}\" fill=\"none\" stroke=\"{}\">\n",
                       xml(s.label), colour);
    if (plot.marks == PlotMarks::kPoints) {
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
        out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3\" fill=\"{}\"/>\n",
                           px(s.x[i]), py(s.y[i]), colour);
      }
    } else {
      // one polyline per run of finite points; a point within kMinStep of the last one drawn
      // is left out, except the run's last
      std::string points;
      double last_x = 0, last_y = 0;
      std::size_t count = 0;
      const auto flush = [&] {
        if (count > 0)
          out += fmt::format("<polyline stroke-width=\"1.5\" points=\"{}\"/>\n", points);
        points.clear();
        count = 0;
      };
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
          flush();
          continue;
        }
        const double x = px(s.x[i]), y = py(s.y[i]);
        const bool last =
            i + 1 == s.x.size() || !std::isfinite(s.x[i + 1]) || !std::isfinite(s.y[i + 1]);
        if (count > 0 && !last && std::hypot(x - last_x, y - last_y) < kMinStep) continue;
        points += fmt::format("{}{:.2f},{:.2f}", count > 0 ? " " : "", x, y);
        last_x = x;
        last_y = y;
        ++count;
      }
      flush();
    }
    out += "</g>\n";
    const double lx = left + width + 16, ly = top + 10 + 18 * static_cast<double>(k);
    out += fmt::format("<g class=\"legend\" data-label=\"{}\">", xml(s.label));
    if (plot.marks == PlotMarks::kPoints) {
      out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3\" fill=\"{}\"/>", lx + 12, ly,
                         colour);
    } else {
      out += fmt::format(
          "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" "
          "stroke-width=\"2\"/>",
          lx, ly, lx + 24, ly, colour);
    }
    out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\">{}</text></g>\n", lx + 30, ly + 4,
                       legend_text(s.label));
  }

  // what was left out
  for (std::size_t i = 0; i < notes; ++i) {
    const std::string text = i + 1 == notes && plot.notes.size() > notes
                                 ? fmt::format("(and {} more notes)", plot.notes.size() - notes + 1)
                                 : plot.notes[i];
    out +=
        fmt::format("<text class=\"note\" x=\"{:.2f}\" y=\"{:.2f}\" fill=\"#555555\">{}</text>\n",
                    left, top + height + 56 + kNoteLine * static_cast<double>(i), xml(text));
  }
  out += "</svg>\n";
  return out;
}

}  // namespace rigid::report
