#pragma once

/// A line or scatter plot as one standalone SVG document, written by rigid itself (no browser,
/// no plotting library): `rigid plot` draws a run's trajectory columns or a sweep's results
/// with it (docs/report.md, "Plots without a browser").

#include <cstddef>
#include <string>
#include <vector>

namespace rigid::report {

/// One named series: the points (x[i], y[i]); a point with a non-finite coordinate is not
/// drawn (it breaks a line).
struct PlotSeries {
  std::string label;  ///< the legend's text
  std::vector<double> x;
  std::vector<double> y;
};

/// How the points of a series are drawn.
enum class PlotMarks {
  kLines,   ///< a polyline through the points in order (a trajectory)
  kPoints,  ///< a circle at each point (a sweep's runs)
};

struct Plot {
  std::string title;
  std::string x_label;  ///< with the unit, e.g. "t (s)"
  std::string y_label;
  std::vector<PlotSeries> series;
  PlotMarks marks = PlotMarks::kLines;
  std::vector<std::string> notes;  ///< lines of text under the axes (what was left out)
};

/// Round tick values covering [lo, hi]: the multiples k·step of a step of 1, 2, 2.5 or 5
/// times a power of ten, the smallest such step that needs at most `at_most` intervals, from
/// the largest multiple ≤ lo to the smallest ≥ hi. lo == hi is widened to lo ± 10% (±1 at 0).
/// @throws rigid::Error if lo or hi is not finite, lo > hi, or at_most < 1.
[[nodiscard]] std::vector<double> round_ticks(double lo, double hi, std::size_t at_most);

/// The plot as an SVG 1.1 document (XML declaration, width, height and viewBox of 800 × 500
/// user units). The axes span the outer ticks of round_ticks over the finite points (for kPoints,
/// widened by 5% on each side first). The
/// mapping from data to the picture is written on the <svg> element: data-x-domain="x0 x1",
/// data-y-domain="y0 y1" and data-plot-box="left top width height" (shortest round-trip
/// doubles), so that a point (x, y) is drawn at
///   px = left + (x − x0) / (x1 − x0) · width,   py = top + (y1 − y) / (y1 − y0) · height,
/// printed with 2 decimals. A line leaves out a point closer than half a unit to the last point
/// it drew (it moves less than half a unit). Each series is a <g class="series"> with
/// data-label and either <polyline> elements (one per run of finite points) or <circle>s.
/// Text is XML-escaped, and bytes that are not printable UTF-8 are shown as \xNN.
/// @throws rigid::Error if no series has a finite point.
[[nodiscard]] std::string svg_plot(const Plot& plot);

}  // namespace rigid::report
